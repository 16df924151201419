"""info, check, smooth, fabricate, scan, optimise_panels, fit and the Design
round trips, compared with the `monge` command's output files and measured
independently with numpy."""

import csv
import json
import math

import numpy as np
import pytest

import monge
import measure_np as mnp
from conftest import example

DUPIN = example("fig12-dupin-theta30.json")


@pytest.mark.parametrize("name", ["fig12-dupin-theta30.json", "fig10-arbitrary.json", "fig14-family.toml"])
def test_info_equals_the_commands(name, cli):
    i = monge.info(monge.Design.from_file(example(name)))
    ref = json.loads(cli("info", "--json", example(name)).stdout)
    assert i["mode"] == ref["mode"]
    assert i["theta_deg"] == ref["theta_deg"]
    assert i["theta_admissible"] == ref["theta_admissible"]
    assert i["theta_abs_min_deg"] == ref["admissible_theta_deg"]["abs_min"]
    assert i["theta_abs_max_deg"] == ref["admissible_theta_deg"]["abs_max"]
    assert (i["rows"], i["cols"], i["faces"]) == (ref["rows"], ref["cols"], ref["faces"])
    for g in ("guide_u", "guide_v"):
        assert i[g]["samples"].shape == (ref[g]["samples"], 3)
        assert list(i[g]["start_tangent"]) == ref[g]["start_tangent"]
        assert list(i[g]["plane_normal"]) == ref[g]["plane_normal"]
        assert i[g]["size"] == ref[g]["size"]


def test_info_samples_are_the_meshs_first_row_and_column():
    design = monge.Design.from_file(example("fig13-freeform.json"))
    i, mesh = monge.info(design), monge.generate(design)
    assert np.array_equal(i["guide_u"]["samples"], mesh.vertices[:, 0])
    assert np.array_equal(i["guide_v"]["samples"], mesh.vertices[0, :])


def test_check_equals_the_command_and_numpy(cli, tmp_path):
    mesh = monge.generate(monge.Design.from_file(DUPIN))
    out = tmp_path / "m.json"
    cli("generate", DUPIN, "-o", out)
    ref = json.loads(cli("check", "--json", out).stdout)
    for m in (monge.check(mesh), monge.check(str(out)), monge.check(mesh.vertices, normals=mesh.normals)):
        assert m["scale"] == ref["scale"]
        for key, metric in ref["metrics"].items():
            assert m[key]["value"] == metric["value"], key
            if metric["at"] is None:
                assert m[key]["at"] is None, key
            else:
                assert tuple(m[key]["at"]) == tuple(metric["at"]), key
        assert m["max_error"] == ref["max_error"]
    # a bent face is found where it is, with numpy's value
    v = np.array(mesh.vertices)
    v[5, 7, 2] += 1e-3
    m = monge.check(v)
    assert m["face_planarity"]["at"] in [(4, 6), (4, 7), (5, 6), (5, 7)]
    assert math.isclose(m["face_planarity"]["value"], mnp.face_planarity(v), rel_tol=0.6)
    assert m["face_planarity"]["value"] > 1e-6
    assert m["torsion"] is None and m["normal_length"] is None


def test_check_finds_a_crossed_face():
    # Two unit squares side by side; the far edge of the second crossed into a bow-tie,
    # whose diagonals' cross product vanishes (§5.2).
    v = np.array([[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 0]], [[2, 0, 0], [2, 1, 0]]], float)
    assert monge.check(v)["folded_faces"] == {"value": 0, "at": None}
    v[2] = v[2][::-1].copy()
    assert monge.check(v)["folded_faces"] == {"value": 1, "at": (1, 0)}


def test_check_refuses_what_cannot_be_measured():
    # As `monge check`: once max_error 0 for an empty mesh, NaN at 1e150.
    with pytest.raises(monge.MeshError, match="no face to measure"):
        monge.check(np.zeros((0, 0, 3)))
    with pytest.raises(monge.MeshError, match="no face to measure"):
        monge.check(np.zeros((1, 5, 3)))
    v = monge.generate(monge.Design.from_file(example("fig13-freeform.json"))).vertices
    with pytest.raises(monge.MeshError, match=r"outside \[1e-100, 1e100\]"):
        monge.check(v * 1e150)
    bad = np.array(v)
    bad[3, 4, 1] = np.nan
    with pytest.raises(monge.MeshError, match=r"vertices\[3, 4\] = .* is not finite"):
        monge.check(bad)


def test_check_conical(cli, tmp_path):
    conical = monge.generate(monge.Design.from_file(example("fig13-conical.json")))
    m = monge.check(conical)
    assert "circularity" not in m and m["conical"]["value"] <= 1e-9
    out = tmp_path / "c.json"
    cli("generate", example("fig13-conical.json"), "-o", out)
    ref = json.loads(cli("check", "--json", "--kind", "conical", out).stdout)
    assert m["conical"]["value"] == ref["metrics"]["conical"]["value"]
    # a bent vertex is found, with numpy's measure of the cone of normals
    v = np.array(conical.vertices)
    v[3, 4, 2] += 0.05
    m = monge.check(v, kind="conical")
    assert m["conical"]["value"] > 1e-6 and mnp.conical(v) > 1e-6
    # A JSON mesh file names its kind, as for `monge check`: measured as it says.
    assert "conical" in monge.check(out) and "circularity" in monge.check(out, kind="circular")


def test_check_takes_normals_second_and_the_kind_by_name():
    # As README.md shows: `check(v, n)`, e.g. `check(*monge.compas.from_mesh(c))`.
    mesh = monge.generate(monge.Design.from_file(DUPIN))
    v, n = np.array(mesh.vertices), np.array(mesh.normals)
    m = monge.check(v, n)
    assert m["torsion"]["value"] <= 1e-9 and m["normal_length"]["value"] <= 1e-9
    assert m == monge.check(mesh)
    # The torsion is measured with the normals given: turned node axes are found.
    turned = n.copy()
    axis = n[4, 5] + np.array([0.0, 0.0, 0.3])
    turned[4, 5] = axis / np.linalg.norm(axis)
    assert monge.check(v, turned)["torsion"]["value"] > 1e-6 and mnp.torsion(v, turned) > 1e-6
    # The kind once came second: a string there says to give it by name.
    with pytest.raises(TypeError, match=r"give the kind by name, kind='conical'"):
        monge.check(v, "conical")


def test_smooth_equals_the_command_and_interpolates_the_mesh(cli, tmp_path):
    design = monge.Design.from_file(DUPIN)
    s = monge.smooth(design, samples=5)
    mesh = monge.generate(design)
    out = tmp_path / "net.json"
    cli("smooth", DUPIN, "-o", out, "--samples", 5)
    ref = json.loads(out.read_text())
    r, c = ref["rows"] - 1, ref["cols"] - 1
    assert s["patches"].shape == (r, c, 5, 5, 3)
    pts = np.array([p["points"] for p in ref["patches"]]).reshape(r, c, 5, 5, 3)
    assert np.abs(s["patches"] - pts).max() <= 1e-12 * mnp.scale(mesh.vertices)
    assert len(s["lines"]) == len(ref["lines"])
    for a, b in zip(s["lines"], ref["lines"]):
        assert a["family"] == b["family"] and a["index"] == b["index"]
        for x, y in zip(a["arcs"], b["arcs"]):
            assert x["radius"] == y["radius"] and list(x["center"]) == y["center"]
    # each patch passes through its four mesh vertices
    size = mnp.scale(mesh.vertices)
    v = mesh.vertices
    assert np.abs(s["patches"][:, :, 0, 0] - v[:-1, :-1]).max() <= 1e-9 * size
    assert np.abs(s["patches"][:, :, -1, -1] - v[1:, 1:]).max() <= 1e-9 * size
    # arcs: start and end at distance radius from the centre, in the plane ⟂ normal
    for line in s["lines"]:
        for arc in line["arcs"]:
            centre, n = np.array(arc["center"]), np.array(arc["normal"])
            for end in (arc["start"], arc["end"]):
                e = np.array(end) - centre
                assert abs(np.linalg.norm(e) - arc["radius"]) <= 1e-9 * size
                assert abs(e @ n) <= 1e-9 * size
    nurbs = s["nurbs"]
    assert nurbs["degree"] == 2
    assert nurbs["control_points"].shape == (2 * v.shape[0] - 1, 2 * v.shape[1] - 1, 3)
    assert nurbs["weights"].shape == nurbs["control_points"].shape[:2]
    # the NURBS interpolates the mesh vertices at its even control points (patch corners)
    assert np.abs(nurbs["control_points"][::2, ::2] - v).max() <= 1e-9 * size


def test_fabricate_equals_the_commands_schedule(cli, tmp_path):
    f = monge.fabricate(monge.Design.from_file(DUPIN), layers=[0.0, 0.1])
    cli("fabricate", DUPIN, "-o", tmp_path / "fab", "--layers", "0,0.1", "--full-json")
    ref = json.loads((tmp_path / "fab" / "schedule.json").read_text())
    for key in ("summary", "layers", "panels", "beams", "nodes"):
        assert f[key] == ref[key], key
    mesh = monge.generate(monge.Design.from_file(DUPIN))
    assert np.array_equal(f["layer_vertices"][0], mesh.vertices)
    assert np.abs(f["layer_vertices"][1] - mesh.offset(0.1).vertices).max() <= 1e-12
    # panel areas from the outlines (shoelace), independently
    for p in f["panels"][:50]:
        x, y = np.array(p["outline"]).T
        assert abs(0.5 * abs(x @ np.roll(y, -1) - y @ np.roll(x, -1)) - p["area"]) <= 1e-12


def test_scan_columns_equal_the_commands_csv(cli, tmp_path):
    design = monge.Design.from_file(DUPIN)
    s = monge.scan(design, np.arange(-180, 181, 45.0))
    cli("scan", DUPIN, "--theta", "-180:180:45", "-o", tmp_path / "s.csv")
    rows = list(csv.DictReader((tmp_path / "s.csv").open()))
    assert s["parameter"] == "theta_deg"
    assert list(s["status"]) == [r["status"] for r in rows]
    assert s["value"].tolist() == [float(r["value"]) for r in rows]
    assert s["folded_faces"].tolist() == [int(r["folded_faces"]) for r in rows]
    for key in ("min_crossing_sine", "area_min", "area_max", "area_mean", "area_variance", "max_edge", "max_error"):
        ref = np.array([float(r[key]) if r[key] else np.nan for r in rows])
        assert np.array_equal(s[key], ref, equal_nan=True), key
    assert [e or "" for e in s["error"]] == [r["error"] for r in rows]


def test_scan_over_a_design_parameter():
    design = monge.Design.from_file(example("fig22-panels.json"))
    s = monge.scan(design, [3.0, 3.5], param="guide_v.bspline.control_points[2][1]")
    assert s["parameter"] == "guide_v.bspline.control_points[2][1]"
    assert len(s["status"]) == 2


def test_optimise_panels_equals_the_command(cli, tmp_path):
    path = example("fig22-panels.json")
    r = monge.optimise_panels(monge.Design.from_file(path), max_evaluations=60)
    out = tmp_path / "opt.json"
    cli("optimise-panels", path, "-o", out, "--max-evaluations", 60)
    assert r["design"] == monge.Design.from_file(str(out))
    assert r["after"]["area_variance"] <= r["before"]["area_variance"]
    assert mnp.circularity(monge.generate(r["design"]).vertices) <= 1e-9


def face_areas(vertices):
    """Areas of planar quads: half the cross product of the diagonals."""
    q = mnp.faces(vertices)
    return 0.5 * np.linalg.norm(np.cross(q[:, 2] - q[:, 0], q[:, 3] - q[:, 1]), axis=1)


def test_panel_statistics_are_the_face_areas():
    design = monge.Design.from_file(DUPIN)
    s = monge.scan(design, [0.0])
    design.theta_deg = 0.0
    areas = face_areas(monge.generate(design).vertices)
    assert math.isclose(s["area_min"][0], areas.min(), rel_tol=1e-12)
    assert math.isclose(s["area_max"][0], areas.max(), rel_tol=1e-12)
    assert math.isclose(s["area_variance"][0], areas.var(), rel_tol=1e-9)


def test_fit_equals_the_command(cli, tmp_path):
    path = example("fig20-piecewise.patches.json")
    r = monge.fit(path)
    out = tmp_path / "fit.patches.json"
    cli("fit", path, "-o", out)
    assert r["design"] == json.loads(out.read_text())
    assert r["after"]["max"] <= r["before"]["max"]
    assert r["vertices"].shape[2] == 3 and r["normals"].shape == r["vertices"].shape
    assert r["status"] and r["evaluations"] > 0
    assert monge.fit(json.loads(open(path).read()))["design"] == r["design"]


def test_design_round_trips(tmp_path):
    design = monge.Design.from_file(example("fig14-family.toml"))
    d = design.to_dict()
    assert monge.Design.from_dict(d) == design
    # numpy arrays are accepted where the file has lists
    pts = d["guide_u"]["bspline"]["control_points"]
    d["guide_u"]["bspline"]["control_points"] = np.array(pts)
    assert monge.Design.from_dict(d) == design
    for ext in ("json", "toml"):
        path = str(tmp_path / f"d.{ext}")
        design.to_file(path)
        again = monge.Design.from_file(path)
        assert again == design and again.source == path
    design.theta_deg = 12.5
    assert design.to_dict()["theta_deg"] == 12.5 and monge.generate(design).theta_deg == 12.5
    assert "Design(theta_deg=12.5" in repr(design)


def test_approximate_equals_the_command_and_its_mesh_is_exact(cli, tmp_path):
    """monge.approximate finds the command's design from the same points (a
    numpy array), and the mesh it returns is exact, measured with numpy."""
    target = example("targets/paraboloid.obj")
    out = tmp_path / "fit.json"
    cli("approximate", target, "-o", out, "--grid", "6x6", "--starts", "1", "--max-evaluations", "60")
    points = np.array(
        [[float(x) for x in line.split()[1:4]] for line in open(target) if line.startswith("v ")]
    )
    r = monge.approximate(points, grid=(6, 6), starts=1, max_evaluations=60)
    assert r["design"] == monge.Design.from_file(out)
    assert r["theta_deg"] == r["design"].theta_deg
    assert r["vertices"].shape == (7, 7, 3)
    v = r["vertices"]
    assert mnp.face_planarity(v) < 1e-9
    assert mnp.circularity(v) < 1e-9
    assert mnp.line_planarity(v) < 1e-9
    # Its deviation from the target, both ways, never worse than the initial guess's
    # in the search's objective; measured here by numpy: every target point's
    # distance to the nearest mesh vertex bounds the distance to the mesh from above.
    after, before = r["after"], r["before"]
    assert after["size"] == pytest.approx(np.linalg.norm(points.max(0) - points.min(0)))
    objective = lambda d: d["mesh_to_target_rms"] ** 2 + d["beyond_mesh_rms"] ** 2
    assert objective(after) <= objective(before)
    nearest = np.linalg.norm(points[:, None, :] - v.reshape(-1, 3)[None], axis=2).min(axis=1)
    assert after["target_to_mesh_max"] * after["size"] <= nearest.max() + 1e-12
    # Bad input: a message, not a crash.
    with pytest.raises(monge.OptimiseError, match="too few"):
        monge.approximate(points[:5])
    with pytest.raises(monge.OptimiseError, match="positive number of seconds"):
        monge.approximate(points, time_limit=0.0)
    # Beyond what the clock holds: no limit (it once raised a PanicException).
    assert monge.approximate(points, grid=(8, 8), starts=1, max_evaluations=10, time_limit=1e20)


def test_approximate_conical_equals_the_command(cli, tmp_path):
    """kind="conical" returns the conical dual (§2.3): no node axes, the command's
    design, and a mesh that is conical, measured with numpy (it once always
    failed reshaping the missing normals)."""
    target = example("targets/paraboloid.obj")
    out = tmp_path / "fit.json"
    cli("approximate", target, "-o", out, "--kind", "conical", "--grid", "6x6", "--starts", "1",
        "--max-evaluations", "60")
    points = np.array(
        [[float(x) for x in line.split()[1:4]] for line in open(target) if line.startswith("v ")]
    )
    r = monge.approximate(points, grid=(6, 6), kind="conical", starts=1, max_evaluations=60)
    assert r["design"] == monge.Design.from_file(out)
    assert r["design"].mesh == "conical" and r["kind"] == "conical"
    assert r["normals"] is None
    v = r["vertices"]
    assert v.shape == (7, 7, 3)
    assert np.array_equal(v, monge.generate(r["design"]).vertices)
    assert mnp.face_planarity(v) < 1e-9 and mnp.conical(v) < 1e-9
    assert r["max_error"] == monge.check(v, kind="conical")["max_error"] <= 1e-9
    circular = monge.approximate(points, grid=(6, 6), starts=1, max_evaluations=60)
    assert circular["kind"] == "circular" and circular["normals"].shape == (7, 7, 3)
    assert circular["max_error"] == monge.check(circular["vertices"], normals=circular["normals"])["max_error"]


def test_approximate_requires_x_y_z_along_the_last_axis():
    # (600, 2) was once reshaped into 400 points and optimised.
    for shape, text in [((600, 2), "(600, 2)"), ((5,), "(5,)"), ((6,), "(6,)"), ((4, 3, 2), "(4, 3, 2)"),
                        ((), "()")]:
        with pytest.raises(monge.OptimiseError) as e:
            monge.approximate(np.zeros(shape))
        assert str(e.value) == (
            f"points must be an array of shape (..., 3), x, y, z along the last axis; got shape {text}: "
            "give the target's points as an (N, 3) array"
        )
    with pytest.raises(monge.OptimiseError, match=r"points must be numbers"):
        monge.approximate([["a", "b", "c"]])
    # (..., 3) of any rank is accepted: a mesh's (rows, cols, 3) vertices (too few here)
    with pytest.raises(monge.OptimiseError, match="too few"):
        monge.approximate(np.zeros((1, 2, 3)))
