"""Blender (bpy): a ``monge.Mesh`` as a Blender mesh object.

``add_mesh(mesh)`` links a new object to the current scene: the quad faces,
the node axes (circular meshes) as custom split normals and as the point
attribute ``node_axis`` (for geometry nodes: node offsets are
``position + d · node_axis``), and for a conical mesh its face normals as the
face attribute ``face_normal``. Blender stores coordinates in single
precision: about 1e-7 of the model size, not monge's 1e-14 (export OBJ, PLY or
JSON with ``monge generate`` where double precision matters). ``add_mesh(mesh,
trimmed=t)`` adds instead the mesh trimmed to a target's outline
(``monge.approximate``'s ``trimmed``): its planar panels as polygons of 3 to 8
corners, with the face attribute ``cut`` (whether the outline cut the panel). Runs
inside Blender, or with the ``bpy`` module from the package index.
"""

try:
    import bpy
except ImportError as _missing:  # pragma: no cover - depends on the environment
    raise ImportError("monge.blender runs inside Blender, or needs the bpy module: pip install bpy") from _missing

from ._monge import Mesh, MeshError


def add_mesh(mesh, name="monge", collection=None, gauss=False, trimmed=None):
    """Links a new object named ``name`` with the mesh to ``collection`` (the
    scene's by default) and returns it; with ``gauss``, the mesh's Gauss map
    instead (§2.2.1): the node axes on the unit sphere, with the same faces; with
    ``trimmed``, the mesh trimmed to a target's outline (its panels, no node axes)."""
    if not isinstance(mesh, Mesh):
        raise MeshError(f"add_mesh needs a monge.Mesh, got {type(mesh).__name__}")
    if gauss and mesh.normals is None:
        raise MeshError("a conical mesh has no node axes: its Gauss map is that of the circular mesh")
    if gauss and trimmed is not None:
        raise MeshError("a trimmed mesh has no Gauss map of its own: draw the mesh's (without trimmed)")
    data = bpy.data.meshes.new(name)
    if trimmed is not None:
        vertices = [[float(x) for x in p] for p in trimmed["vertices"]]
        data.from_pydata(vertices, [], [list(f) for f in trimmed["faces"]])
        cut = [bool(c) for c in trimmed["cut"]]
        data.attributes.new("cut", "BOOLEAN", "FACE").data.foreach_set("value", cut)
        return _link(data, name, collection)
    points = mesh.normals if gauss else mesh.vertices
    data.from_pydata(points.reshape(-1, 3).tolist(), [], mesh.faces.tolist())
    if mesh.normals is not None:
        axes = mesh.normals.reshape(-1, 3)
        data.normals_split_custom_set_from_vertices(axes.tolist())
        data.attributes.new("node_axis", "FLOAT_VECTOR", "POINT").data.foreach_set("vector", axes.ravel())
    if mesh.face_normals is not None:
        normals = mesh.face_normals.reshape(-1, 3)
        data.attributes.new("face_normal", "FLOAT_VECTOR", "FACE").data.foreach_set("vector", normals.ravel())
    return _link(data, name, collection)


def _link(data, name, collection):
    """``data`` validated, as a new object named ``name`` linked to ``collection``."""
    data.validate()
    obj = bpy.data.objects.new(name, data)
    (collection or bpy.context.scene.collection).objects.link(obj)
    return obj
