"""monge.rhino.write_3dm: read back with rhino3dm (openNURBS) and compared with
`monge generate`'s output and with numpy's measurements."""

import math
import os

import numpy as np
import pytest

rhino3dm = pytest.importorskip("rhino3dm")  # an optional dependency (the wheel's extra `rhino`)

import monge
import monge.rhino
import measure_np as mnp
from conftest import example

DUPIN = example("fig12-dupin-theta30.json")


def objects(model, layer_name):
    index = next(l.Index for l in model.Layers if l.Name == layer_name)
    return [o for o in model.Objects if o.Attributes.LayerIndex == index]


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    design = monge.Design.from_file(DUPIN)
    mesh = monge.generate(design)
    smooth = monge.smooth(design, samples=3)
    path = tmp_path_factory.mktemp("rhino") / "dupin.3dm"
    layers = monge.rhino.write_3dm(path, mesh, smooth=smooth, units="Millimeters")
    return mesh, smooth, layers, rhino3dm.File3dm.Read(str(path))


def test_layers_and_units(written):
    _, _, layers, model = written
    assert layers == ["monge mesh", "monge guides", "monge panels", "monge cyclidic net", "monge beams"]
    assert [l.Name for l in model.Layers] == layers
    assert model.Settings.ModelUnitSystem == rhino3dm.UnitSystem.Millimeters


def test_mesh_vertices_equal_the_commands(written, cli_mesh):
    mesh, _, _, model = written
    (obj,) = objects(model, "monge mesh")
    m = obj.Geometry
    ref = cli_mesh(DUPIN)
    v = np.array([[p.X, p.Y, p.Z] for p in (m.Vertices.Point3dAt(k) for k in range(len(m.Vertices)))])
    assert v.shape == (mesh.rows * mesh.cols, 3)
    assert np.abs(v - ref["vertices"].reshape(-1, 3)).max() <= 1e-12 * mnp.scale(ref["vertices"])
    assert m.Faces.QuadCount == m.Faces.Count == (mesh.rows - 1) * (mesh.cols - 1)
    faces = np.array([list(m.Faces[k]) for k in range(m.Faces.Count)])
    assert np.array_equal(faces, mesh.faces)
    n = np.array([[q.X, q.Y, q.Z] for q in m.Normals])
    assert np.abs(n - ref["normals"].reshape(-1, 3)).max() <= 1e-6  # openNURBS keeps normals as float


def test_guides_and_panels(written):
    mesh, _, _, model = written
    guides = {o.Attributes.Name: o.Geometry for o in objects(model, "monge guides")}
    for name, points in (("guide_u", mesh.vertices[:, 0]), ("guide_v", mesh.vertices[0, :])):
        c = guides[name]
        assert c.Degree == 1 and len(c.Points) == len(points)
        cps = np.array([[c.Points[k].X, c.Points[k].Y, c.Points[k].Z] for k in range(len(c.Points))])
        assert np.array_equal(cps, points)
    panels = objects(model, "monge panels")
    assert len(panels) == (mesh.rows - 1) * (mesh.cols - 1)
    size = mnp.scale(mesh.vertices)
    for o in panels[::97]:
        c = o.Geometry
        pts = np.array([[c.Point(k).X, c.Point(k).Y, c.Point(k).Z] for k in range(c.PointCount)])
        assert c.IsClosed and len(pts) == 5
        assert mnp.plane_distances(pts[:4]) <= 1e-9 * size


def test_the_cyclidic_net_passes_through_the_mesh_vertices(written):
    mesh, smooth, _, model = written
    (obj,) = objects(model, "monge cyclidic net")
    s = obj.Geometry
    assert s.IsRational and s.OrderU == s.OrderV == 3
    v, size = mesh.vertices, mnp.scale(mesh.vertices)
    us = sorted(set(s.KnotsU.ToList()))
    vs = sorted(set(s.KnotsV.ToList()))
    assert (len(us), len(vs)) == (mesh.rows, mesh.cols)
    worst = 0.0
    for i in range(0, mesh.rows, 4):
        for j in range(0, mesh.cols, 4):
            p = s.PointAt(us[i], vs[j])  # evaluated by openNURBS
            worst = max(worst, np.linalg.norm(np.array([p.X, p.Y, p.Z]) - v[i, j]))
    assert worst <= 1e-9 * size
    # and through the patches' sample points inside the spans
    p = s.PointAt((us[3] + us[4]) / 2, (vs[5] + vs[6]) / 2)
    assert np.linalg.norm(np.array([p.X, p.Y, p.Z]) - smooth["patches"][3, 5, 1, 1]) <= 1e-9 * size


def test_beams_are_the_curvature_lines_arcs(written):
    _, smooth, _, model = written
    arcs = [a for line in smooth["lines"] for a in line["arcs"]]
    beams = objects(model, "monge beams")
    assert len(beams) == len(arcs)
    size = mnp.scale(written[0].vertices)
    for o, a in zip(beams, arcs):
        c = o.Geometry
        arc = c.Arc
        centre = np.array([arc.Center.X, arc.Center.Y, arc.Center.Z])
        assert abs(arc.Radius - a["radius"]) <= 1e-9 * size
        assert np.linalg.norm(centre - a["center"]) <= 1e-9 * size
        for end, p in ((a["start"], c.PointAtStart), (a["end"], c.PointAtEnd)):
            assert np.linalg.norm(np.array([p.X, p.Y, p.Z]) - end) <= 1e-9 * size
        assert math.isclose(arc.Length, a["radius"] * math.radians(a["sweep_deg"]), rel_tol=1e-9)


def test_conical_meshes_have_no_vertex_normals(tmp_path):
    mesh = monge.generate(monge.Design.from_file(example("fig13-conical.json")))
    path = tmp_path / "conical.3dm"
    assert monge.rhino.write_3dm(path, mesh, panels=False) == ["monge mesh", "monge guides"]
    model = rhino3dm.File3dm.Read(str(path))
    (obj,) = objects(model, "monge mesh")
    assert len(obj.Geometry.Vertices) == mesh.rows * mesh.cols and len(obj.Geometry.Normals) == 0
    assert model.Settings.ModelUnitSystem == rhino3dm.UnitSystem.Meters


def test_errors_leave_no_file(tmp_path):
    mesh = monge.generate(monge.Design.from_file(DUPIN))
    path = tmp_path / "x.3dm"
    with pytest.raises(monge.MeshError, match="needs a monge.Mesh"):
        monge.rhino.write_3dm(path, mesh.vertices)
    with pytest.raises(monge.MeshError, match="units = 'Cubits'"):
        monge.rhino.write_3dm(path, mesh, units="Cubits")
    with pytest.raises(monge.FileError, match="does not exist"):
        monge.rhino.write_3dm(tmp_path / "no" / "x.3dm", mesh)
    assert os.listdir(tmp_path) == []


def test_a_base_point_is_every_objects_user_text(tmp_path):
    design = monge.Design.from_file(DUPIN)
    path = tmp_path / "based.3dm"
    monge.rhino.write_3dm(path, monge.generate(design, base_point=(0.5, -1.0, 0.25)))
    model = rhino3dm.File3dm.Read(str(path))
    assert len(model.Objects) > 0
    for o in model.Objects:
        assert o.Attributes.GetUserString("monge.base_point") == "0.5 -1.0 0.25"
    monge.rhino.write_3dm(path, monge.generate(design))
    for o in rhino3dm.File3dm.Read(str(path)).Objects:
        assert o.Attributes.UserStringCount == 0


@pytest.mark.parametrize("umask", [0o022, 0o027])
def test_the_file_has_the_permissions_of_the_commands_files(tmp_path, cli, umask):
    # Once 0o600 whatever the umask (a temporary file's), where `monge generate` writes
    # 0o666 less the umask.
    mesh = monge.generate(monge.Design.from_file(DUPIN))
    previous = os.umask(umask)
    try:
        monge.rhino.write_3dm(tmp_path / "m.3dm", mesh, panels=False)
        cli("generate", DUPIN, "-o", tmp_path / "m.obj")
    finally:
        os.umask(previous)
    mode = os.stat(tmp_path / "m.3dm").st_mode & 0o777
    assert mode == os.stat(tmp_path / "m.obj").st_mode & 0o777 == 0o666 & ~umask
    assert sorted(os.listdir(tmp_path)) == ["m.3dm", "m.obj"]  # no temporary file left


def polygon_area(points):
    """Area of a planar polygon (n, 3), by the shoelace formula in the plane of its
    corners (numpy's SVD)."""
    p = np.asarray(points, dtype=float)
    c = p - p.mean(0)
    axes = np.linalg.svd(c)[2][:2]
    x, y = c @ axes[0], c @ axes[1]
    return 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def test_a_trimmed_result_is_written_and_given_to_grasshopper_as_its_panels(tmp_path):
    """A mesh trimmed to a target's outline (approximate's trim=True): the .3dm's mesh
    and Grasshopper's are the trimmed panels (each cut one as triangles covering it),
    its panel curves the polygons themselves."""
    import monge.grasshopper as mgh

    points = np.array(
        [[float(x) for x in line.split()[1:4]] for line in open(example("targets/paraboloid.obj")) if line.startswith("v ")]
    )
    out = mgh.approximate(points, grid=(8, 8), starts=1, max_evaluations=60, trim=True)
    r, t = out["result"], out["result"]["trimmed"]
    v = np.asarray(t["vertices"])
    assert 0 < sum(t["cut"]) < len(t["faces"]) == r["panels"]
    assert f"trimmed to the target's outline: {len(t['faces'])} planar panels, {sum(t['cut'])} of them cut" in out["metrics"]
    assert np.array_equal(out["vertices"], v) and out["faces"] == t["mesh_faces"] and out["gauss"] is None
    # The mesh's faces cover the polygons once: the same area, measured with numpy.
    polygons = sum(polygon_area(v[f]) for f in t["faces"])
    pieces = sum(polygon_area(v[f]) for f in t["mesh_faces"])
    assert pieces == pytest.approx(polygons, rel=1e-9)
    m = mgh.rhino_mesh(rhino3dm.Mesh, out["vertices"], out["faces"])
    assert m.Faces.TriangleCount + m.Faces.QuadCount == len(t["mesh_faces"]) > len(t["faces"])

    path = tmp_path / "trimmed.3dm"
    layers = monge.rhino.write_3dm(path, r["mesh"], trimmed=t)
    assert layers == ["monge mesh", "monge guides", "monge panels"]
    model = rhino3dm.File3dm.Read(str(path))
    (mesh,) = [o.Geometry for o in objects(model, "monge mesh")]
    assert len(mesh.Vertices) == len(v) and mesh.Faces.TriangleCount + mesh.Faces.QuadCount == len(t["mesh_faces"])
    panels = objects(model, "monge panels")
    assert [o.Attributes.Name for o in panels] == [f"P{i}.{j}" for i, j in t["from"]]
    for o, f in zip(panels, t["faces"]):
        curve = o.Geometry
        corners = np.array([[curve.Point(k).X, curve.Point(k).Y, curve.Point(k).Z] for k in range(curve.PointCount)])
        assert np.allclose(corners[:-1], v[f], rtol=0, atol=1e-12) and np.array_equal(corners[0], corners[-1])
