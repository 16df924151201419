"""monge.grasshopper (the logic of the Grasshopper component and of the Hops
endpoint in examples/grasshopper/) with rhino3dm curves, and the Hops endpoint
itself through Flask's test client, as Grasshopper would call it."""

import importlib.util
import json
import pathlib

import numpy as np
import pytest

rhino3dm = pytest.importorskip("rhino3dm")

import monge
import monge.grasshopper as mgh
import monge.rhino
import measure_np as mnp
from conftest import torus_patch_brep

EXAMPLES = pathlib.Path(__file__).resolve().parents[3] / "examples" / "grasshopper"
SAMPLES = 25
# The guides of fig12-dupin-theta30.json, both sampled 25 times.
ARCS = {
    "guide_u": {"center": [0, 0, -10], "start": [0, 0, 0], "normal": [0, 1, 0], "angle_deg": 120},
    "guide_v": {"center": [0, 0, -3], "start": [0, 0, 0], "normal": [-1, 0, 0], "angle_deg": 80},
}


def curve(arc):
    """The arc as a rhino3dm ArcCurve (openNURBS evaluates it)."""
    radius = float(np.linalg.norm(np.subtract(arc["start"], arc["center"])))
    return monge.rhino.arc_curve({**arc, "radius": radius, "sweep_deg": arc["angle_deg"]})


def reference():
    guides = {k: {"arc": {**a, "samples": SAMPLES}} for k, a in ARCS.items()}
    return monge.generate(monge.Design.from_dict({"theta_deg": 30, **guides}))


def test_curves_give_the_mesh_of_the_same_arcs():
    r = mgh.solve(curve(ARCS["guide_u"]), curve(ARCS["guide_v"]), 30, SAMPLES)
    ref = reference()
    v = np.array(r["vertices"]).reshape(ref.vertices.shape)
    # openNURBS and monge evaluate the arcs with different round-off only
    assert np.abs(v - ref.vertices).max() <= 1e-12 * mnp.scale(ref.vertices)
    assert np.array_equal(np.array(r["faces"]), ref.faces)
    g = np.array(r["gauss"]).reshape(ref.vertices.shape)
    assert np.abs(np.linalg.norm(g, axis=2) - 1).max() <= 1e-12  # on the unit sphere
    assert mnp.circularity(v) <= 1e-9 and mnp.line_planarity(v) <= 1e-9
    text = "\n".join(r["metrics"])
    assert "mode: characteristic, θ = 30°" in text and "folded faces: 0" in text
    assert "circularity: " in text and "face_planarity: " in text


def test_conical_and_errors():
    u, v = curve(ARCS["guide_u"]), curve(ARCS["guide_v"])
    r = mgh.solve(u, v, 30, SAMPLES, kind="conical")
    assert r["gauss"] is None and r["mesh"].kind == "conical"
    with pytest.raises(monge.ThetaError, match="singular"):
        mgh.solve(u, v, 90, SAMPLES)
    with pytest.raises(monge.DesignError, match="samples = 2"):
        mgh.solve(u, v, 30, 2)
    # a curve that does not start at the corner
    moved = curve({**ARCS["guide_v"], "center": [0, 1, -3], "start": [0, 1, 0]})
    with pytest.raises(monge.DesignError, match="do not start at the same point"):
        mgh.solve(u, moved, 30, SAMPLES)


@pytest.fixture(scope="module")
def hops_client():
    pytest.importorskip("ghhops_server")
    pytest.importorskip("flask")
    spec = importlib.util.spec_from_file_location("hops_server", EXAMPLES / "hops_server.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.app.test_client()


def hops_request(theta):
    def item(name, type_, data):
        return {"ParamName": name, "InnerTree": {"{0}": [{"type": type_, "data": data}]}}

    return {
        "pointer": "/monge_generate",
        "values": [
            item("GuideU", "Rhino.Geometry.Curve", json.dumps(curve(ARCS["guide_u"]).Encode())),
            item("GuideV", "Rhino.Geometry.Curve", json.dumps(curve(ARCS["guide_v"]).Encode())),
            item("Theta", "System.Double", json.dumps(theta)),
            item("Samples", "System.Int32", json.dumps(SAMPLES)),
        ],
    }


def outputs(response):
    assert response.status_code == 200, response.data
    values = json.loads(response.data)["values"]
    return {v["ParamName"]: [x["data"] for x in v["InnerTree"]["0"]] for v in values}


def test_hops_describes_the_component(hops_client):
    desc = json.loads(hops_client.get("/monge_generate").data)
    assert [i["Name"] for i in desc["Inputs"]] == ["GuideU", "GuideV", "Theta", "Samples"]
    assert [o["Name"] for o in desc["Outputs"]] == ["Mesh", "Gauss", "Metrics"]


def test_hops_solves_like_monge_generate(hops_client):
    out = outputs(hops_client.post("/solve", data=json.dumps(hops_request(30))))
    mesh = rhino3dm.CommonObject.Decode(json.loads(out["Mesh"][0]))
    ref = reference()
    v = np.array([[p.X, p.Y, p.Z] for p in (mesh.Vertices.Point3dAt(k) for k in range(len(mesh.Vertices)))])
    assert np.abs(v - ref.vertices.reshape(-1, 3)).max() <= 1e-12 * mnp.scale(ref.vertices)
    assert mesh.Faces.QuadCount == (SAMPLES - 1) ** 2
    gauss = rhino3dm.CommonObject.Decode(json.loads(out["Gauss"][0]))
    g = np.array([[p.X, p.Y, p.Z] for p in (gauss.Vertices.Point3dAt(k) for k in range(len(gauss.Vertices)))])
    assert np.abs(g - ref.normals.reshape(-1, 3)).max() <= 1e-12
    assert any("circularity" in json.loads(m) for m in out["Metrics"])


def test_hops_reports_errors_as_metrics(hops_client):
    out = outputs(hops_client.post("/solve", data=json.dumps(hops_request(90))))
    assert any(json.loads(m).startswith("error: theta_deg = 90° is singular") for m in out["Metrics"])


def test_hops_approximates_a_surface(hops_client):
    # A curved surface (a torus patch, which one patch fits at once) sent as Hops
    # sends a Brep.
    brep = torus_patch_brep()

    def request(target, tolerance=None):
        def item(name, type_, data):
            return {"ParamName": name, "InnerTree": {"{0}": [{"type": type_, "data": data}]}}

        values = [
            item("Target", "Rhino.Geometry.Brep", json.dumps(target.Encode())),
            item("Faces", "System.Int32", json.dumps(8)),
            item("Starts", "System.Int32", json.dumps(1)),
        ]
        if tolerance is None:  # unconnected
            values.append({"ParamName": "Tolerance", "InnerTree": {}})
        else:
            values.append(item("Tolerance", "System.String", json.dumps(tolerance)))
        return {"pointer": "/monge_approximate", "values": values}

    desc = json.loads(hops_client.get("/monge_approximate").data)
    assert [i["Name"] for i in desc["Inputs"]] == ["Target", "Faces", "Starts", "Tolerance"]
    def vertices(out):
        mesh = rhino3dm.CommonObject.Decode(json.loads(out["Mesh"][0]))
        assert mesh.Faces.QuadCount == 64 and len(mesh.Vertices) == 81
        return np.array([[p.X, p.Y, p.Z] for p in mesh.Vertices.ToPoint3dArray()])

    # With a tolerance: the metrics of monge.grasshopper.approximate with it (whether
    # it is met, and why not), and the patches' merged mesh.
    out = outputs(hops_client.post("/solve", data=json.dumps(request(brep, "50m"))))
    metrics = [json.loads(m) for m in out["Metrics"]]
    expected = mgh.approximate(brep, grid=(8, 8), starts=1, tolerance="50m")
    assert metrics == expected["metrics"]
    r = expected["result"]
    assert any(m.startswith(f"{'' if r['met'] else 'NOT '}within the tolerance of {r['tolerance']:.3g}") for m in metrics)
    assert np.array_equal(vertices(out), r["vertices"].reshape(-1, 3))
    # Unconnected: the one-patch fit, which is what a tolerance that one patch
    # meets returns too (so the same mesh as monge.approximate's, one fit fewer).
    out = outputs(hops_client.post("/solve", data=json.dumps(request(brep))))
    assert np.array_equal(vertices(out), r["vertices"].reshape(-1, 3))
    metrics = [json.loads(m) for m in out["Metrics"]]
    assert metrics[0] == f"panels: 64, θ = {r['theta_deg']:g}°"
    assert metrics[1].startswith(f"largest deviation: {r['max_deviation']:.3g} model units")
