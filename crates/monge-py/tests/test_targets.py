"""monge.approximate from what designers have (rhino3dm meshes, point clouds,
surfaces and Breps, COMPAS meshes, lists of points, files), its result written
to a .3dm and read back, and the Grasshopper component rationalising a surface
(monge.grasshopper.approximate, the docs' recipe, the example component), with
the real rhino3dm and compas packages."""

import math
import pathlib
import sys
import types

import numpy as np
import pytest

rhino3dm = pytest.importorskip("rhino3dm")

import monge
import monge.grasshopper as mgh
import monge.rhino
import measure_np as mnp
from conftest import ROOT, example

TARGET = example("targets/paraboloid.obj")
# Small and quick: the same search for every form of the same target.
SEARCH = {"grid": (5, 5), "starts": 1, "max_evaluations": 40}


def obj_points(path):
    """The `v` lines of an OBJ file, read here (not by monge)."""
    return np.array([[float(x) for x in line.split()[1:4]] for line in open(path) if line.startswith("v ")])


@pytest.fixture(scope="module")
def points():
    return obj_points(TARGET)


@pytest.fixture(scope="module")
def reference(points):
    """The result from the points as an (N, 3) array."""
    return monge.approximate(points, **SEARCH)


def rhino_points(points):
    return [rhino3dm.Point3d(*map(float, p)) for p in points]


def point3d_list(points):
    """A rhino3dm.Point3dList (a collection with `Count`, as .NET lists in Grasshopper)."""
    lst = rhino3dm.Point3dList()
    for p in points.tolist():
        lst.Add(*p)
    return lst


def test_rhino_and_compas_targets_are_their_points(points, reference):
    mesh = monge.rhino.quad_mesh(points, [])  # double-precision vertices, no faces needed
    cloud = rhino3dm.PointCloud()
    for p in rhino_points(points):
        cloud.Add(p)
    compas_mesh = pytest.importorskip("compas.datastructures").Mesh()
    for p in points.tolist():
        compas_mesh.add_vertex(x=p[0], y=p[1], z=p[2])
    for name, target in [
        ("rhino3dm.Mesh", mesh),
        ("rhino3dm.PointCloud", cloud),
        ("list of rhino3dm.Point3d", rhino_points(points)),
        ("rhino3dm.Point3dList", point3d_list(points)),
        ("list of tuples", [tuple(p) for p in points.tolist()]),
        ("compas Mesh", compas_mesh),
        ("compas Pointcloud", pytest.importorskip("compas.geometry").Pointcloud(points.tolist())),
        ("OBJ path", pathlib.Path(TARGET)),
        ("OBJ path as text", TARGET),
        ("(rows, cols, 3) array", points.reshape(41, 41, 3)),
    ]:
        taken = monge.target_points(target)
        assert taken.shape == points.shape and np.array_equal(taken, points), name
    # approximate takes them so: the same design as from the array.
    r = monge.approximate(mesh, **SEARCH)
    assert r["design"] == reference["design"] and r["after"] == reference["after"]


def bezier_roof():
    """A bicubic Bézier roof (rise 20 %) as control points (4, 4, 3), away from the origin."""
    i, j = np.meshgrid(np.arange(4.0), np.arange(4.0), indexing="ij")
    z = 2.0 * np.sin(np.pi * i / 3) * np.sin(np.pi * j / 3) + 0.3 * i
    return np.stack([10 * i / 3, 8 * j / 3, z], axis=-1) + [100.0, 50.0, 10.0]


def rhino_surface(control, domain_u):
    """The Bézier patch as a rhino3dm.NurbsSurface, u over `domain_u`, v over [0, 1]."""
    s = rhino3dm.NurbsSurface.Create(3, False, 4, 4, 4, 4)
    for a in range(4):
        for b in range(4):
            s.Points[a, b] = rhino3dm.Point4d(*map(float, control[a, b]), 1.0)
    for knots, (t0, t1) in ((s.KnotsU, domain_u), (s.KnotsV, (0.0, 1.0))):
        for k, t in enumerate([t0, t0, t0, t1, t1, t1]):
            knots[k] = t
    assert s.IsValid
    return s


def bernstein(t):
    return np.stack([(1 - t) ** 3, 3 * t * (1 - t) ** 2, 3 * t**2 * (1 - t), t**3], axis=-1)


def test_a_surface_is_sampled_on_a_grid_of_its_parameters(points):
    # As the command samples an IGES surface: side × side parameters, ends
    # included, u slowest, side = ⌈√4000⌉ = 64 for one surface; evaluated here
    # with Bernstein polynomials, not openNURBS.
    control = bezier_roof()
    surface = rhino_surface(control, (2.0, 5.0))
    side = math.ceil(math.sqrt(4000))
    t = np.linspace(0.0, 1.0, side)
    grid = np.einsum("ua,vb,abk->uvk", bernstein(t), bernstein(t), control).reshape(-1, 3)
    taken = monge.target_points(surface)
    assert taken.shape == grid.shape == (64 * 64, 3)
    assert np.abs(taken - grid).max() <= 1e-13 * mnp.scale(grid)
    # A Brep of that surface: its face, sampled alike.
    brep = rhino3dm.Brep.CreateFromSurface(surface)
    assert np.array_equal(monge.target_points(brep), taken)
    r = monge.approximate(brep, **SEARCH)
    assert r["design"] == monge.approximate(taken, **SEARCH)["design"]
    assert r["after"]["size"] == pytest.approx(np.linalg.norm(np.ptp(grid, axis=0)), rel=1e-12)


def test_what_is_not_a_target_is_named():
    curve = rhino3dm.NurbsCurve.Create(False, 1, rhino_points([[0, 0, 0], [1, 0, 0]]))
    for target, name in [(curve, "rhino3dm._rhino3dm.NurbsCurve"), (object(), "object"), (None, "NoneType")]:
        with pytest.raises(monge.OptimiseError) as e:
            monge.target_points(target)
        assert str(e.value) == (
            f"the target is a {name}: give the target as an array of shape (..., 3) or a list of points, a "
            "Rhino or rhino3dm Mesh, PointCloud, Surface or Brep, a COMPAS Mesh, or the path of a file "
            "`monge approximate` reads (OBJ, PLY, JSON, STL, points one a line: .xyz, .pts, .csv, .txt; IGES)"
        )
    with pytest.raises(monge.FileError, match="no-such-roof.obj"):
        monge.approximate("no-such-roof.obj")
    with pytest.raises(monge.OptimiseError, match="is a NoneType"):
        monge.approximate(None)


def test_the_result_is_a_mesh_to_write_and_its_figures_in_model_units(points, reference, tmp_path):
    r = reference
    mesh = r["mesh"]
    assert isinstance(mesh, monge.Mesh) and mesh.kind == "circular"
    assert np.array_equal(mesh.vertices, r["vertices"]) and np.array_equal(mesh.normals, r["normals"])
    assert r["panels"] == mesh.faces.shape[0] == 5 * 5
    # A .3dm read back by openNURBS: the same vertices.
    path = tmp_path / "roof.3dm"
    monge.rhino.write_3dm(path, mesh)
    model = rhino3dm.File3dm.Read(str(path))
    (m,) = [o.Geometry for o in model.Objects if isinstance(o.Geometry, rhino3dm.Mesh)]
    v = np.array([[p.X, p.Y, p.Z] for p in m.Vertices.ToPoint3dArray()])
    assert np.array_equal(v, r["vertices"].reshape(-1, 3))
    # The design saved and read back.
    r["design"].to_file(str(tmp_path / "roof.json"))
    assert monge.Design.from_file(str(tmp_path / "roof.json")) == r["design"]
    # Model units: the relative distances times the size, and bounded by
    # distances measured here: a target point's distance to the nearest mesh
    # vertex, a mesh vertex's to the nearest target point.
    after, d, size = r["after"], r["deviation"], r["after"]["size"]
    assert size == pytest.approx(np.linalg.norm(np.ptp(points, axis=0)))
    for key in after:
        assert d[key] == pytest.approx(after[key] * (1 if key == "size" else size), rel=1e-15)
    assert r["max_deviation"] == max(d["mesh_to_target_max"], d["target_to_mesh_max"])
    distances = np.linalg.norm(points[:, None, :] - r["vertices"].reshape(-1, 3)[None], axis=2)
    assert 0 < d["target_to_mesh_max"] <= distances.min(axis=1).max() + 1e-12 * size
    assert 0 < d["mesh_to_target_max"] <= distances.min(axis=0).max() + 1e-12 * size
    # Last (skipped without compas): a COMPAS mesh of it, measured exact by monge.check from COMPAS's arrays.
    mc = pytest.importorskip("monge.compas")
    c = mc.to_mesh(mesh)
    assert c.number_of_faces() == r["panels"]
    assert monge.check(*mc.from_mesh(c))["max_error"] <= 1e-9


def test_the_conical_result_is_a_conical_mesh(points):
    r = monge.approximate(points, kind="conical", **SEARCH)
    mesh = r["mesh"]
    assert mesh.kind == "conical" and mesh.normals is None and mesh.face_normals is not None
    assert np.array_equal(mesh.vertices, r["vertices"])
    assert r["panels"] == (mesh.rows - 1) * (mesh.cols - 1)
    assert mnp.conical(mesh.vertices) < 1e-9


def test_grasshopper_rationalises_the_geometry_connected(reference):
    control = bezier_roof()
    surface = rhino_surface(control, (0.0, 1.0))
    out = mgh.approximate(surface, **SEARCH)
    r = out["result"]
    assert out["mesh"] is r["mesh"] and out["design"] is r["design"]
    text = "\n".join(out["metrics"])
    assert f"panels: 25, θ = {r['theta_deg']:g}°" in text
    assert f"largest deviation: {r['max_deviation']:.3g} model units" in text
    assert "circularity: " in text and "folded faces: " in text
    m = mgh.rhino_mesh(rhino3dm.Mesh, out["vertices"], out["faces"], out["gauss"])
    assert len(m.Vertices) == 36 and m.Faces.QuadCount == 25 and len(m.Normals) == 36


def run_component(code, filename, monkeypatch, **inputs):
    """Runs a Grasshopper script component's code outside Rhino: `Rhino.Geometry`
    is rhino3dm (the members the code uses are the same), the inputs are globals;
    returns the globals after the run (its outputs)."""
    rhino = types.ModuleType("Rhino")
    rhino.Geometry = rhino3dm
    monkeypatch.setitem(sys.modules, "Rhino", rhino)
    monkeypatch.setitem(sys.modules, "Rhino.Geometry", rhino3dm)
    scope = dict(inputs)
    exec(compile(code, filename, "exec"), scope)
    return scope


def docs_block(needle):
    """The ```python block of docs/python.md that holds `needle`."""
    text = (ROOT / "docs" / "python.md").read_text()
    return next(b.split("```", 1)[0] for b in text.split("```python\n")[1:] if needle in b)


def test_the_docs_example_runs(monkeypatch, tmp_path, capsys):
    (tmp_path / "examples").symlink_to(ROOT / "examples")
    monkeypatch.chdir(tmp_path)
    exec(compile(docs_block("rationalised.3dm"), "docs/python.md", "exec"), {})
    assert "100 panels, largest deviation" in capsys.readouterr().out
    model = rhino3dm.File3dm.Read("rationalised.3dm")
    assert [l.Name for l in model.Layers] == ["monge mesh", "monge guides", "monge panels"]
    assert monge.Design.from_file("rationalised.json").theta_deg


def test_the_docs_grasshopper_recipe_runs(monkeypatch):
    code = docs_block("mgh.approximate")
    surface = rhino_surface(bezier_roof(), (0.0, 1.0))
    out = run_component(code, "docs/python.md", monkeypatch, geometry=surface, faces=8, starts=1, tolerance=None)
    assert out["error"] is None, out["error"]
    assert out["mesh"].Faces.QuadCount == 64 and any("largest deviation" in line for line in out["metrics"])
    # A tolerance of about four times the size (one patch meets it, quickly): the metrics say whether it is met.
    out = run_component(code, "docs/python.md", monkeypatch, geometry=surface, faces=8, starts=1, tolerance="50m")
    assert out["error"] is None, out["error"]
    assert any("within the tolerance of" in line for line in out["metrics"])
    out = run_component(code, "docs/python.md", monkeypatch, geometry=rhino3dm.Point3d(0, 0, 0), faces=5, starts=1,
                        tolerance=None)
    assert out["mesh"] is None and out["error"].startswith("the target is a rhino3dm._rhino3dm.Point3d")


def test_the_example_component_runs(monkeypatch):
    path = ROOT / "examples" / "grasshopper" / "monge_component.py"
    design = monge.Design.from_file(example("fig12-dupin-theta30.json"))
    arcs = {k: v["arc"] for k, v in design.to_dict().items() if k.startswith("guide_")}
    curves = {}
    for name, arc in arcs.items():
        radius = float(np.linalg.norm(np.subtract(arc["start"], arc["center"])))
        curves[name] = monge.rhino.arc_curve({**arc, "radius": radius, "sweep_deg": arc["angle_deg"]})
    out = run_component(path.read_text(), str(path), monkeypatch, theta=30.0, samples=9, conical=False, **curves)
    assert out["error"] is None, out["error"]
    assert out["mesh"].Faces.QuadCount == 64 and len(out["gauss"].Vertices) == 81


def test_a_scans_text_and_an_stl_are_targets_as_the_command_reads_them(points, tmp_path):
    # The scan's points as a CSV with a header and an intensity column: the points to the
    # bit. As a binary STL (written here with numpy's structured array): the distinct
    # corners of its triangles, in single precision.
    xyz = tmp_path / "scan.csv"
    xyz.write_text("x,y,z,intensity\n" + "".join(f"{float(x)!r},{float(y)!r},{float(z)!r},0.5\n" for x, y, z in points))
    assert np.array_equal(monge.target_points(xyz), np.asarray(points, dtype=float))
    triangles = np.asarray(points[:30], dtype=np.float32).reshape(10, 3, 3)
    record = np.dtype([("normal", "<f4", 3), ("corners", "<f4", (3, 3)), ("attribute", "<u2")])
    body = np.zeros(len(triangles), dtype=record)
    body["corners"] = triangles
    stl = tmp_path / "scan.stl"
    stl.write_bytes(b"solid by numpy".ljust(80) + np.uint32(len(triangles)).tobytes() + body.tobytes())
    read = monge.target_points(stl)
    _, first = np.unique(triangles.reshape(-1, 3), axis=0, return_index=True)
    assert np.array_equal(read, triangles.reshape(-1, 3)[np.sort(first)].astype(float))


def test_stray_points_are_set_aside_as_the_command_sets_them_aside(points, reference):
    # Two points far above the roof among its points: set aside, named by their index,
    # and the result is the one without them.
    assert reference["stray"] == []
    top = points[:, 2].max() - points[:, 2].min()
    with_stray = np.insert(points, [10, 500], [[5.0, 5.0, points[:, 2].max() + top], [2.0, 8.0, -top]], axis=0)
    result = monge.approximate(with_stray, **SEARCH)
    assert result["stray"] == [10, 501]
    assert np.array_equal(result["vertices"], reference["vertices"])
