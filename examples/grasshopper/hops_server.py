"""A Hops endpoint serving monge.generate (for Rhino 7 and 8 Grasshopper).

    pip install target/wheels/monge-*.whl rhino3dm ghhops-server flask
    python examples/grasshopper/hops_server.py          # http://127.0.0.1:5000/

from the repository root, with the wheel built as README.md says (the package
index has no `monge`).

In Grasshopper, place a Hops component and set its path to
http://127.0.0.1:5000/monge_generate: it takes two curves, θ and the number of
samples, and returns the mesh, its Gauss map and the metrics (or the error).
With the path http://127.0.0.1:5000/monge_approximate it takes a surface or
polysurface (a Brep), the faces along each side, the number of starts and
optionally a tolerance (as `monge approximate --tolerance`: 5cm, 0.05m, 50mm, or
5e-3 of the surface's size; then as many patches as it takes, up to 6), and
returns the exact mesh nearest to it and the metrics: the panels, node types,
the deviation in model units, each patch, whether the tolerance is met (or the
error).
"""

import sys

import ghhops_server as hs
from flask import Flask

import monge
import monge.grasshopper as mgh
import monge.rhino

app = Flask(__name__)
hops = hs.Hops(app)


@hops.component(
    "/monge_generate",
    name="monge generate",
    nickname="monge",
    description="Exact circular quad mesh with planar curvature lines from two planar guides and θ",
    inputs=[
        hs.HopsCurve("GuideU", "U", "First guide; starts at the common corner"),
        hs.HopsCurve("GuideV", "V", "Second guide; starts at the same corner, at 90°"),
        hs.HopsNumber("Theta", "θ", "θ in degrees (§3.1, §3.2)"),
        hs.HopsInteger("Samples", "N", "Samples per guide"),
    ],
    outputs=[
        hs.HopsMesh("Mesh", "M", "The quad mesh, node axes as vertex normals"),
        hs.HopsMesh("Gauss", "G", "The Gauss map: node axes on the unit sphere"),
        hs.HopsString("Metrics", "I", "Mode, admissible θ, folds, measured errors"),
    ],
)
def monge_generate(guide_u, guide_v, theta, samples=21):
    try:
        r = mgh.solve(guide_u, guide_v, theta, samples)
    except monge.MongeError as e:
        return None, None, [f"error: {e}"]
    mesh = r["mesh"]
    return monge.rhino.rhino_mesh(mesh), monge.rhino.gauss_mesh(mesh), r["metrics"]


@hops.component(
    "/monge_approximate",
    name="monge approximate",
    nickname="monge≈",
    description="The exact circular quad mesh with planar curvature lines nearest to a surface",
    inputs=[
        hs.HopsBrep("Target", "T", "The surface or polysurface to rationalise"),
        hs.HopsInteger("Faces", "F", "Faces along each side"),
        hs.HopsInteger("Starts", "S", "Starts of the search (more: slower, safer)"),
        # A tree: an unconnected input arrives as an empty one (an item would be refused).
        hs.HopsString(
            "Tolerance",
            "Tol",
            "Within this of the surface both ways, with as many patches as it takes: a length "
            "with its unit (5cm, 0.05m, 50mm) or a fraction of its size (5e-3); unconnected: one patch",
            access=hs.HopsParamAccess.TREE,
        ),
    ],
    outputs=[
        hs.HopsMesh("Mesh", "M", "The quad mesh (the patches merged), node axes as vertex normals"),
        hs.HopsString("Metrics", "I", "Panels, node types, deviation in model units, tolerance, measured errors"),
    ],
)
def monge_approximate(target, faces, starts, tolerance):
    tolerance = next((t for branch in tolerance.values() for t in branch if t), None)
    try:
        r = mgh.approximate(target, grid=(faces, faces), starts=starts, tolerance=tolerance)
    except monge.MongeError as e:
        return None, [f"error: {e}"]
    result = r["result"]
    return monge.rhino.quad_mesh(result["vertices"], result["faces"], result["normals"]), r["metrics"]


if __name__ == "__main__":
    port = int(sys.argv[1]) if len(sys.argv) > 1 else 5000
    app.run(host="127.0.0.1", port=port)
