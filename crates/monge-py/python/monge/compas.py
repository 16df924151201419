"""COMPAS meshes (with compas: ``pip install compas``): ``to_mesh`` and back.

``to_mesh(mesh)`` gives a ``compas.datastructures.Mesh`` with the quad faces
of a ``monge.Mesh`` (vertex keys ``i·cols + j``, faces in the order of
``mesh.faces``), each vertex with the attributes ``i``, ``j`` and, for a
circular mesh, ``normal`` and ``node_axis`` (the same unit node axis, §2.2);
for a conical mesh each face has ``normal`` (its unit face normal, §2.3). The
mesh attributes say ``rows``, ``cols``, ``kind``, ``theta_deg`` and
``offset_distance``. ``from_mesh`` reads such a mesh back as numpy arrays
(rows, cols, 3) that ``monge.check`` measures: ``monge.check(*from_mesh(c))``.
``to_mesh(mesh, trimmed=t)`` gives instead the mesh trimmed to a target's outline
(``monge.approximate``'s ``trimmed``): its planar panels as COMPAS faces of 3 to 8
corners, each with the attributes ``cut`` (whether the outline cut it) and ``i``,
``j`` (the grid face it was cut from). Only data is converted here.
"""

import numpy as np

try:
    from compas.datastructures import Mesh as CompasMesh
except ImportError as _missing:  # pragma: no cover - depends on the environment
    raise ImportError("monge.compas needs compas: pip install compas") from _missing

from ._monge import Mesh, MeshError


def to_mesh(mesh, trimmed=None):
    """A ``compas.datastructures.Mesh`` of a ``monge.Mesh`` (quad faces, node axes);
    with ``trimmed`` (``monge.approximate``'s ``trimmed``: ``mesh`` trimmed to a
    target's outline), of the trimmed panels (polygons, no node axes)."""
    if not isinstance(mesh, Mesh):
        raise MeshError(f"to_mesh needs a monge.Mesh, got {type(mesh).__name__}")
    if trimmed is not None:
        return _trimmed_mesh(mesh, trimmed)
    c = CompasMesh.from_vertices_and_faces(mesh.vertices.reshape(-1, 3).tolist(), mesh.faces.tolist())
    c.attributes.update(
        rows=mesh.rows,
        cols=mesh.cols,
        kind=mesh.kind,
        theta_deg=mesh.theta_deg,
        offset_distance=mesh.offset_distance,
    )
    normals = None if mesh.normals is None else mesh.normals.reshape(-1, 3).tolist()
    for key in c.vertices():
        i, j = divmod(key, mesh.cols)
        c.vertex_attributes(key, ["i", "j"], [i, j])
        if normals is not None:
            c.vertex_attributes(key, ["normal", "node_axis"], [normals[key], normals[key]])
    if mesh.face_normals is not None:
        for key, n in zip(c.faces(), mesh.face_normals.reshape(-1, 3).tolist()):
            c.face_attribute(key, "normal", n)
    return c


def _trimmed_mesh(mesh, trimmed):
    """The panels of ``trimmed`` as a COMPAS mesh (see ``to_mesh``)."""
    vertices = np.asarray(trimmed["vertices"], dtype=float).tolist()
    c = CompasMesh.from_vertices_and_faces(vertices, [list(f) for f in trimmed["faces"]])
    c.attributes.update(kind=mesh.kind, theta_deg=mesh.theta_deg, trimmed=True)
    for key, cut, (i, j) in zip(c.faces(), trimmed["cut"], trimmed["from"]):
        c.face_attributes(key, ["cut", "i", "j"], [bool(cut), i, j])
    return c


def from_mesh(cmesh):
    """``(vertices, normals)`` of a COMPAS mesh made by ``to_mesh`` (or any mesh
    whose vertices have the attributes ``i`` and ``j`` and whose attributes give
    ``rows`` and ``cols``): arrays (rows, cols, 3); normals None without the
    ``node_axis`` attribute."""
    try:
        rows, cols = int(cmesh.attributes["rows"]), int(cmesh.attributes["cols"])
    except KeyError as e:
        raise MeshError(f"the COMPAS mesh has no `{e.args[0]}` attribute: it must say its grid size") from None
    if cmesh.number_of_vertices() != rows * cols:
        raise MeshError(
            f"the COMPAS mesh has {cmesh.number_of_vertices()} vertices, "
            f"not rows × cols = {rows} × {cols} = {rows * cols}"
        )
    vertices = np.full((rows, cols, 3), np.nan)
    normals = np.full((rows, cols, 3), np.nan)
    with_normals = True
    for key in cmesh.vertices():
        i, j = cmesh.vertex_attributes(key, ["i", "j"])
        if i is None or j is None or not (0 <= i < rows and 0 <= j < cols):
            raise MeshError(f"vertex {key} of the COMPAS mesh has no grid position (i, j) in {rows} × {cols}")
        vertices[i, j] = cmesh.vertex_coordinates(key)
        axis = cmesh.vertex_attribute(key, "node_axis")
        if axis is None:
            with_normals = False
        else:
            normals[i, j] = axis
    if np.isnan(vertices).any():
        raise MeshError("the COMPAS mesh's (i, j) attributes do not cover the grid: a position is missing")
    return vertices, (normals if with_normals else None)
