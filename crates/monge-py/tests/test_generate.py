"""monge.generate: the meshes equal `monge generate`'s and are exact, measured
independently with numpy (SVD, least-squares circles) to 1e-9 of the model size."""

import json
import warnings

import numpy as np
import pytest

import monge
import measure_np as mnp
from conftest import example

CIRCULAR = [
    "fig12-dupin-theta30.json",
    "fig13-freeform.json",
    "fig10-arbitrary.json",
    "fig2-enneper.json",
    "fig14-family.toml",
]
TOL = 1e-9


@pytest.mark.parametrize("name", CIRCULAR)
def test_vertices_and_normals_equal_the_commands(name, cli_mesh):
    mesh = monge.generate(monge.Design.from_file(example(name)))
    ref = cli_mesh(example(name))
    size = mnp.scale(ref["vertices"])
    assert mesh.vertices.shape == ref["vertices"].shape == (ref["rows"], ref["cols"], 3)
    assert mesh.vertices.dtype == np.float64
    assert np.abs(mesh.vertices - ref["vertices"]).max() <= 1e-12 * size
    assert np.abs(mesh.normals - ref["normals"]).max() <= 1e-12
    assert mesh.theta_deg == ref["theta_deg"]
    assert mesh.mode == ref["mode"]
    assert mesh.report["folded_faces"] == ref["report"]["folded_faces"]
    assert mesh.report["min_crossing_sine"] == ref["report"]["min_crossing_sine"]


@pytest.mark.parametrize("name", CIRCULAR)
def test_circular_meshes_are_exact(name):
    mesh = monge.generate(monge.Design.from_file(example(name)))
    v, n = mesh.vertices, mesh.normals
    assert mnp.face_planarity(v) <= TOL
    assert mnp.circularity(v) <= TOL
    assert mnp.line_planarity(v) <= TOL
    assert mnp.torsion(v, n) <= TOL
    assert np.abs(np.linalg.norm(n, axis=2) - 1).max() <= TOL
    # the package's own measure agrees with numpy's within round-off
    assert mesh.report["max_error"] <= TOL


def test_conical_mesh_equals_the_command_and_is_conical(cli_mesh):
    design = monge.Design.from_file(example("fig13-conical.json"))
    assert design.mesh == "conical"
    mesh = monge.generate(design)
    ref = cli_mesh(example("fig13-conical.json"))
    assert mesh.kind == "conical" and mesh.normals is None
    assert np.abs(mesh.vertices - ref["vertices"]).max() <= 1e-12 * mnp.scale(ref["vertices"])
    fn = np.array(ref["face_normals"]).reshape(mesh.face_normals.shape)
    assert np.abs(mesh.face_normals - fn).max() <= 1e-12
    assert mnp.face_planarity(mesh.vertices) <= TOL
    assert mnp.line_planarity(mesh.vertices) <= TOL
    assert mnp.conical(mesh.vertices) <= TOL
    assert mesh.report["max_error"] == monge.check(mesh)["max_error"] <= TOL
    # the face normals are those of the faces' planes (measured by SVD)
    assert np.abs(mnp.face_normals(mesh.vertices) - mesh.face_normals).max() <= TOL


def test_kind_overrides_the_design():
    design = monge.Design.from_file(example("fig12-dupin-theta30.json"))
    circular = monge.generate(design)
    conical = monge.generate(design, kind="conical")
    assert (conical.rows, conical.cols) == (circular.rows - 1, circular.cols - 1)
    assert mnp.conical(conical.vertices) <= TOL
    with pytest.raises(monge.DesignError, match='kind = "helical"'):
        monge.generate(design, kind="helical")


@pytest.mark.parametrize("d", [0.25, -0.4])
def test_node_offsets_are_at_constant_distance(d, cli, tmp_path):
    design = monge.Design.from_file(example("fig12-dupin-theta30.json"))
    mesh = monge.generate(design)
    off = mesh.offset(d)
    assert off.offset_distance == d
    dist = np.linalg.norm(off.vertices - mesh.vertices, axis=2)
    assert np.abs(dist - abs(d)).max() <= TOL * mnp.scale(mesh.vertices)
    assert mnp.circularity(off.vertices) <= TOL
    assert mnp.face_planarity(off.vertices) <= TOL
    # the command's offset file holds the same vertices
    out = tmp_path / "m.obj"
    cli("generate", example("fig12-dupin-theta30.json"), "-o", out, "--offset", d)
    offset_file = tmp_path / f"m.offset{d:+}.obj"
    vs = [list(map(float, l.split()[1:])) for l in offset_file.read_text().splitlines() if l.startswith("v ")]
    assert np.abs(np.array(vs).reshape(off.vertices.shape) - off.vertices).max() <= 1e-12 * mnp.scale(mesh.vertices)


def test_face_offsets_of_conical_meshes_move_every_face_plane_by_d():
    mesh = monge.generate(monge.Design.from_file(example("fig13-conical.json")))
    d = 0.3
    off = mesh.offset(d)
    n = mnp.face_normals(mesh.vertices)
    q0 = mnp.faces(mesh.vertices).reshape(n.shape[0], n.shape[1], 4, 3)
    q1 = mnp.faces(off.vertices).reshape(q0.shape)
    h0 = np.einsum("ijkl,ijl->ijk", q0, n).mean(axis=2)
    h1 = np.einsum("ijkl,ijl->ijk", q1, n)
    assert np.abs(h1 - h0[..., None] - d).max() <= TOL * mnp.scale(mesh.vertices)
    assert mnp.conical(off.vertices) <= TOL


def test_faces_index_the_flattened_vertices_like_obj(cli, tmp_path):
    mesh = monge.generate(monge.Design.from_file(example("fig12-dupin-theta30.json")))
    faces = mesh.faces
    assert faces.shape == ((mesh.rows - 1) * (mesh.cols - 1), 4)
    flat = mesh.vertices.reshape(-1, 3)
    assert np.array_equal(flat[faces], mnp.faces(mesh.vertices))
    out = tmp_path / "m.obj"
    cli("generate", example("fig12-dupin-theta30.json"), "-o", out)
    obj = [[int(c.split("/")[0]) - 1 for c in l.split()[1:]] for l in out.read_text().splitlines() if l.startswith("f ")]
    assert np.array_equal(np.array(obj), faces)


def test_arrays_are_read_only_views_of_the_mesh():
    mesh = monge.generate(monge.Design.from_file(example("fig13-freeform.json")))
    v = mesh.vertices
    assert v.base is mesh and mesh.normals.base is mesh
    assert not v.flags.writeable and v.flags.c_contiguous
    # two views share the mesh's memory: no copy was made
    assert np.shares_memory(v, mesh.vertices)
    with pytest.raises(ValueError):
        v[0, 0, 0] = 1.0
    del mesh  # the view keeps the mesh alive
    assert np.isfinite(v).all()


@pytest.mark.parametrize(
    "name, d",
    [("fig12-dupin-theta30.json", -5), ("fig12-torus.json", -5), ("fig12-dupin-theta30.json", 0.25),
     ("fig13-conical.json", -20), ("fig13-conical.json", 0.3)],
)
def test_an_offsets_report_is_measured_on_the_offset(name, d, cli, tmp_path):
    # It was the generated mesh's: dupin's offset at -5 reported 0 folded faces
    # while check() and `monge check` find 288.
    mesh = monge.generate(monge.Design.from_file(example(name)))
    off = mesh.offset(d)
    checked = monge.check(off)
    assert off.report["folded_faces"] == checked["folded_faces"]["value"]
    assert off.report["first_fold"] == checked["folded_faces"]["at"]
    assert off.report["max_error"] == checked["max_error"]
    assert off.report["min_crossing_sine"] == mesh.report["min_crossing_sine"]
    out = tmp_path / "m.json"
    cli("generate", example(name), "-o", out, "--offset", d)
    kind = ["--kind", "conical"] if mesh.kind == "conical" else []
    p = cli("check", "--json", *kind, tmp_path / f"m.offset{d:+}.json", check=False)
    assert p.returncode in (0, 1), p.stderr  # 1: the mesh folds
    ref = json.loads(p.stdout)
    assert off.report["folded_faces"] == ref["metrics"]["folded_faces"]["value"]
    if name == "fig12-dupin-theta30.json" and d == -5:
        assert off.report["folded_faces"] == 288 and mesh.report["folded_faces"] == 0


def obj_faces(path):
    return np.array([[int(c.split("/")[0]) - 1 for c in l.split()[1:]]
                     for l in path.read_text().splitlines() if l.startswith("f ")])


@pytest.mark.parametrize("name", ["fig12-dupin-theta30.json", "fig12-torus.json", "fig13-conical.json"])
@pytest.mark.parametrize("d", [-20, -5, 5])
def test_faces_are_wound_as_the_commands_obj_files(name, d, cli, tmp_path):
    # An offset through the focal surface turns its faces over: the command winds
    # them the other way round (dupin and torus at -5: face 0 [0, 1, 34, 33]),
    # and so must Mesh.faces (it once kept [0, 33, 34, 1]).
    mesh = monge.generate(monge.Design.from_file(example(name)))
    out = tmp_path / "m.obj"
    cli("generate", example(name), "-o", out, "--offset", d)
    assert np.array_equal(mesh.faces, obj_faces(out))
    off = mesh.offset(d)
    assert off.faces.dtype == np.uint64 and off.faces.shape == ((off.rows - 1) * (off.cols - 1), 4)
    assert np.array_equal(off.faces, obj_faces(tmp_path / f"m.offset{d:+}.obj"))
    if name != "fig13-conical.json" and d == -5:
        assert list(off.faces[0]) == [0, 1, mesh.cols + 1, mesh.cols]


def far(by):
    """Figure 13's freeform design with both guides moved by `by` along x, y and z."""
    d = json.loads(open(example("fig13-freeform.json")).read())
    for g in ("guide_u", "guide_v"):
        spec = d[g]["bspline"]
        spec["control_points"] = [[c + by for c in p] for p in spec["control_points"]]
    return monge.Design.from_dict(d)


def worst(mesh):
    return max(mnp.face_planarity(mesh.vertices), mnp.circularity(mesh.vertices))


def test_base_point_keeps_a_far_mesh_exact():
    design = far(1e9)  # about 5e7 times the design's size from the origin
    with pytest.warns(monge.FarFromOriginWarning, match="base_point="):
        absolute = monge.generate(design)
    with warnings.catch_warnings():
        warnings.simplefilter("error", monge.FarFromOriginWarning)
        relative = monge.generate(design, base_point="start")
    assert absolute.base_point is None
    assert relative.base_point == (1e9, 1e9, 1e9)
    # measured with numpy: the relative mesh is exact, the absolute one is not
    before, after = worst(absolute), worst(relative)
    assert after <= 1e-9 < before, (before, after)
    # the same mesh, moved by the base point
    moved = relative.vertices + np.array(relative.base_point)
    assert np.abs(moved - absolute.vertices).max() < 1e-5
    # an offset keeps the base point; a given point works as well
    assert relative.offset(0.1).base_point == (1e9, 1e9, 1e9)
    given = monge.generate(design, base_point=(1e9, 1e9 + 1, 1e9))
    assert given.base_point == (1e9, 1e9 + 1, 1e9)
    assert np.abs(given.vertices + np.array([0, 1, 0]) - relative.vertices).max() < 1e-9


@pytest.mark.parametrize("bad", ["origin", (1.0, 2.0), (0.0, float("nan"), 0.0), "1,2,3"])
def test_a_base_point_is_start_or_a_point(bad):
    with pytest.raises(monge.DesignError, match="base_point = .*give \"start\""):
        monge.generate(far(0.0), base_point=bad)
