"""Build a monge mesh in Blender.

In Blender (with monge installed into Blender's Python, see README.md):
    blender --background --python examples/blender/monge_mesh.py -- DESIGN [OUT.blend] [--conical]
or in Blender's Scripting workspace, with DESIGN set below; or with the bpy
module from the package index (pip install bpy):
    python examples/blender/monge_mesh.py DESIGN OUT.blend

Adds the mesh (node axes as custom normals and as the `node_axis` attribute)
and its Gauss map to the scene, and saves OUT.blend if given.
"""

import sys

import bpy

import monge
import monge.blender

DESIGN = "examples/fig12-dupin-theta30.json"

args = sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else sys.argv[1:]
kind = "conical" if "--conical" in args else "circular"
paths = [a for a in args if a != "--conical"]
design = monge.Design.from_file(paths[0] if paths else DESIGN)
mesh = monge.generate(design, kind=kind)
monge.blender.add_mesh(mesh, name="monge")
if mesh.normals is not None:
    monge.blender.add_mesh(mesh, name="monge Gauss map", gauss=True)
print(f"monge: {mesh.rows} × {mesh.cols} {mesh.kind} mesh from {design.source}, θ = {mesh.theta_deg}°")
if len(paths) > 1:
    bpy.ops.wm.save_as_mainfile(filepath=paths[1])
