"""Native Rhino files (.3dm) with rhino3dm (openNURBS; ``pip install rhino3dm``).

``write_3dm(path, mesh, smooth=...)`` writes, each on its own named layer:

* ``monge mesh``: the quad mesh, double-precision vertices, the node axes as
  vertex normals (circular meshes);
* ``monge guides``: guide_u (the first column, red) and guide_v (the first row,
  blue) through the guide samples, as degree-1 NURBS curves;
* ``monge panels``: every face as a closed planar polyline, named ``P<i>.<j>``
  after its face of the grid;
* with ``trimmed`` (a mesh trimmed to a target's outline, ``monge.approximate``'s
  ``trimmed``), the mesh and panels are the trimmed ones: the mesh's cut panels as
  triangles in their planes, the panels each a whole polygon;
* with ``smooth`` (the result of ``monge.smooth``): ``monge cyclidic net``, the
  smooth C¹ surface (§4.4) as one exact rational degree-2 NURBS surface, and
  ``monge beams``, every curvature line as its chain of circular arcs (named
  ``u<index>`` or ``v<index>`` after its family).

The model's unit system is set (``units``, a name of ``rhino3dm.UnitSystem``,
default meters). A mesh generated with ``base_point`` (coordinates relative to
that point, exact far from the origin) keeps its relative coordinates, and the
point is every object's attribute user text ``monge.base_point``, ``"x y z"``
(Rhino, too, models best near the origin: move the objects by it if needed).
The file is written to a hidden file beside ``path`` and renamed, so no
half-written file is left; its permissions are those of every file monge
writes (read and write for all, less the umask). This module only converts arrays
into openNURBS objects: the geometry is monge's.
"""

import math
import os
import secrets

import numpy as np

try:
    import rhino3dm
except ImportError as _missing:  # pragma: no cover - depends on the environment
    raise ImportError("monge.rhino needs rhino3dm: pip install rhino3dm") from _missing

from ._monge import FileError, Mesh, MeshError

LAYERS = {
    "mesh": ("monge mesh", (200, 200, 200)),
    "guides": ("monge guides", (0, 0, 0)),
    "panels": ("monge panels", (90, 140, 200)),
    "net": ("monge cyclidic net", (230, 200, 140)),
    "beams": ("monge beams", (120, 60, 20)),
}
GUIDE_COLOURS = {"guide_u": (220, 40, 40), "guide_v": (40, 80, 220)}
# The objects' attribute user text that records a mesh's base point (``Mesh.base_point``).
BASE_POINT_KEY = "monge.base_point"


def _point(p):
    return rhino3dm.Point3d(float(p[0]), float(p[1]), float(p[2]))


def _attributes(layer, name, colour=None):
    a = rhino3dm.ObjectAttributes()
    a.LayerIndex = layer
    a.Name = name
    if colour is not None:
        a.ColorSource = rhino3dm.ObjectColorSource.ColorFromObject
        a.ObjectColor = (*colour, 255)
    return a


def quad_mesh(vertices, faces, normals=None):
    """A ``rhino3dm.Mesh`` with double-precision ``vertices`` (rows, cols, 3),
    ``faces`` of four or three corners (indices into the flattened vertices) and
    optional vertex ``normals`` (rows, cols, 3)."""
    m = rhino3dm.Mesh()
    m.Vertices.UseDoublePrecisionVertices = True
    for p in np.asarray(vertices, dtype=float).reshape(-1, 3).tolist():
        m.Vertices.AddPoint3d(*p)
    for face in faces.tolist() if isinstance(faces, np.ndarray) else faces:
        m.Faces.AddFace(*face)
    if normals is not None:
        for n in np.asarray(normals, dtype=float).reshape(-1, 3).tolist():
            m.Normals.Add(*n)
    return m


def rhino_mesh(mesh):
    """A ``monge.Mesh`` as a ``rhino3dm.Mesh``: quads, and for a circular mesh the
    node axes as vertex normals."""
    return quad_mesh(mesh.vertices, mesh.faces, mesh.normals)


def gauss_mesh(mesh):
    """The Gauss map of a circular ``monge.Mesh`` (§2.2.1) as a ``rhino3dm.Mesh``
    on the unit sphere: its node axes as vertices, with the mesh's faces."""
    if mesh.normals is None:
        raise MeshError("a conical mesh has no node axes: its Gauss map is that of the circular mesh")
    return quad_mesh(mesh.normals, mesh.faces, mesh.normals)


def polyline_nurbs(points):
    """A degree-1 NURBS curve through ``points`` (n, 3)."""
    return rhino3dm.NurbsCurve.Create(False, 1, [_point(p) for p in points])


def nurbs_surface(nurbs):
    """``monge.smooth(...)["nurbs"]`` as a ``rhino3dm.NurbsSurface`` (openNURBS
    knot vectors omit the first and last knot of the clamped ones)."""
    cp, w = nurbs["control_points"], nurbs["weights"]
    order = nurbs["degree"] + 1
    s = rhino3dm.NurbsSurface.Create(3, True, order, order, cp.shape[0], cp.shape[1])
    for i in range(cp.shape[0]):
        for j in range(cp.shape[1]):
            x, y, z = (float(c) * float(w[i, j]) for c in cp[i, j])
            s.Points[i, j] = rhino3dm.Point4d(x, y, z, float(w[i, j]))
    for knots, target in ((nurbs["knots_u"], s.KnotsU), (nurbs["knots_v"], s.KnotsV)):
        for k, t in enumerate(knots[1:-1]):
            target[k] = float(t)
    return s


def arc_curve(arc):
    """One arc of ``monge.smooth(...)["lines"]`` as a ``rhino3dm.ArcCurve``: the
    circle about ``center`` in the plane spanned by ``start − center`` and
    ``normal × (start − center)``, from ``start`` through ``sweep_deg``."""
    start, centre, normal = (np.asarray(arc[k], dtype=float) for k in ("start", "center", "normal"))
    x = start - centre
    y = np.cross(normal, x)
    plane = rhino3dm.Plane(_point(centre), rhino3dm.Vector3d(*map(float, x)), rhino3dm.Vector3d(*map(float, y)))
    circle = rhino3dm.Circle(float(arc["radius"]))
    circle.Plane = plane
    return rhino3dm.ArcCurve.CreateFromArc(rhino3dm.Arc(circle, math.radians(arc["sweep_deg"])))


def _new_file_beside(path):
    """A new empty file beside ``path``, named ``.NAME.XXXXXX.tmp`` as the command's,
    and made as open(2) makes files, ``0o666`` less the umask (``tempfile.mkstemp``
    makes them ``0o600``, which the rename would keep); its path."""
    directory, name = os.path.split(os.path.abspath(os.fspath(path)))
    while True:
        tmp = os.path.join(directory, f".{name}.{secrets.token_hex(3)}.tmp")
        try:
            os.close(os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666))
            return tmp
        except FileExistsError:
            continue  # another writer's name: draw again


def write_3dm(path, mesh, smooth=None, panels=True, units="Meters", trimmed=None):
    """Writes ``mesh`` (a ``monge.Mesh``), and the cyclidic net and beams of
    ``smooth`` (``monge.smooth``'s result) if given, to the Rhino file ``path``
    (openNURBS version 8), each on a named layer; returns the layer names. With
    ``trimmed`` (``monge.approximate``'s ``trimmed``: ``mesh`` trimmed to a target's
    outline), the mesh and panels written are the trimmed ones (the cut panels as
    triangles in the mesh, whole in the panels), the guides ``mesh``'s."""
    if not isinstance(mesh, Mesh):
        raise MeshError(f"write_3dm needs a monge.Mesh, got {type(mesh).__name__}")
    try:
        unit = getattr(rhino3dm.UnitSystem, units)
    except AttributeError:
        raise MeshError(f"units = {units!r} is not a rhino3dm.UnitSystem name (e.g. Meters, Millimeters, Feet)") from None
    model = rhino3dm.File3dm()
    model.Settings.ModelUnitSystem = unit
    index = {}

    def layer(key):
        if key not in index:
            name, colour = LAYERS[key]
            lay = rhino3dm.Layer()
            lay.Name = name
            lay.Color = (*colour, 255)
            index[key] = model.Layers.Add(lay)
        return index[key]

    base = None if mesh.base_point is None else " ".join(repr(float(x)) for x in mesh.base_point)

    def attributes(key, name, colour=None):
        a = _attributes(layer(key), name, colour)
        if base is not None:
            a.SetUserString(BASE_POINT_KEY, base)
        return a

    v = mesh.vertices
    if trimmed is None:
        model.Objects.AddMesh(rhino_mesh(mesh), attributes("mesh", f"monge {mesh.kind} mesh"))
        flat = v.reshape(-1, 3)
        faces = [(divmod(k, mesh.cols - 1), face) for k, face in enumerate(mesh.faces.tolist())]
    else:
        flat = np.asarray(trimmed["vertices"], dtype=float)
        model.Objects.AddMesh(
            quad_mesh(flat, trimmed["mesh_faces"]), attributes("mesh", f"monge {mesh.kind} mesh, trimmed")
        )
        faces = list(zip(trimmed["from"], trimmed["faces"]))
    for name, points in (("guide_u", v[:, 0]), ("guide_v", v[0, :])):
        model.Objects.AddCurve(polyline_nurbs(points), attributes("guides", name, GUIDE_COLOURS[name]))
    if panels:
        for (i, j), face in faces:
            outline = rhino3dm.PolylineCurve([_point(flat[c]) for c in face + face[:1]])
            model.Objects.AddCurve(outline, attributes("panels", f"P{i}.{j}"))
    if smooth is not None:
        model.Objects.AddSurface(nurbs_surface(smooth["nurbs"]), attributes("net", "cyclidic net"))
        for line in smooth["lines"]:
            name = f"{line['family']}{line['index']}"
            for arc in line["arcs"]:
                model.Objects.AddCurve(arc_curve(arc), attributes("beams", name))
    directory = os.path.dirname(os.path.abspath(os.fspath(path)))
    if not os.path.isdir(directory):
        raise FileError(f"cannot write `{os.fspath(path)}`: the directory `{directory}` does not exist")
    tmp = _new_file_beside(path)
    try:
        if not model.Write(tmp, 8):
            raise FileError(f"cannot write `{os.fspath(path)}`: openNURBS refused to write the model")
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)
    return [LAYERS[k][0] for k in index]
