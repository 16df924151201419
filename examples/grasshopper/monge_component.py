# r: monge
"""monge for Grasshopper (Rhino 8, Python 3 script component).

Inputs (set their type hints on the component):
    guide_u  Curve   the first guide (rows run along it); starts at the common corner
    guide_v  Curve   the second guide; starts at the same corner, at 90° to guide_u
    theta    float   θ in degrees (§3.1, §3.2)
    samples  int     samples per guide (default 21)
    conical  bool    the conical mesh (§2.3) instead of the circular one
Outputs:
    mesh     the quad mesh (node axes as vertex normals for a circular mesh)
    gauss    its Gauss map: the node axes on the unit sphere, same faces
    metrics  mode, admissible θ, folds and every measured error, one line each
    error    the message when the design is invalid (then the other outputs are empty)

The `# r: monge` line makes Rhino 8 find the package, once the wheel is built and
installed into Rhino's Python as README.md says (the package index has no `monge`). Everything
but the component's inputs and outputs is in monge.grasshopper, tested outside Rhino.
"""

import Rhino.Geometry as rg

import monge
import monge.grasshopper as mgh


mesh = gauss = metrics = error = None
if guide_u is not None and guide_v is not None and theta is not None:
    try:
        r = mgh.solve(guide_u, guide_v, theta, samples or 21, "conical" if conical else "circular")
        mesh = mgh.rhino_mesh(rg.Mesh, r["vertices"], r["faces"], r["gauss"])
        if r["gauss"] is not None:
            gauss = mgh.rhino_mesh(rg.Mesh, r["gauss"], r["faces"], r["gauss"])
        metrics = r["metrics"]
    except monge.MongeError as e:
        error = str(e)
