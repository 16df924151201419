"""Grasshopper and Hops: two guide curves and θ in, the mesh, its Gauss map
and its metrics out (``solve``); or a surface, mesh or points in, the nearest
exact mesh and its deviation out (``approximate``).

The logic of the Grasshopper script components and of the Hops endpoint in
``examples/grasshopper/`` and docs/python.md, kept here so that it runs (and is
tested) outside Rhino: the curves, surfaces and meshes may be RhinoCommon ones
(inside Rhino) or rhino3dm ones (Hops, tests), which share the members used
here (``Domain``, ``PointAt``, ``TangentAtStart``, ``Vertices``, ``Faces``). No
geometry is made here: the curves are sampled and the samples handed to
``monge.generate`` as ``points`` guides with the curves' exact start tangents;
a target goes to ``monge.approximate`` as it is.
"""


from ._monge import Design, DesignError, TrimmedDesign, check, generate, info
from ._monge import approximate as _approximate


def sample_curve(curve, samples):
    """``samples`` points of ``curve`` at uniformly spaced parameters, ends
    included, and its unit start tangent."""
    if samples < 3:
        raise DesignError(f"samples = {samples}: a guide needs at least 3 samples to be curved")
    t0, t1 = curve.Domain.T0, curve.Domain.T1
    points = []
    for k in range(samples):
        p = curve.PointAt(t0 + (t1 - t0) * k / (samples - 1))
        points.append([p.X, p.Y, p.Z])
    t = curve.TangentAtStart
    return points, [t.X, t.Y, t.Z]


def design_from_curves(guide_u, guide_v, theta_deg, samples=21, kind="circular"):
    """A ``monge.Design`` whose guides are the two curves, sampled (both start at
    the common corner and meet there at 90°)."""
    guides = {}
    for name, curve in (("guide_u", guide_u), ("guide_v", guide_v)):
        points, tangent = sample_curve(curve, samples)
        guides[name] = {"points": points, "tangent": tangent}
    return Design.from_dict({"theta_deg": float(theta_deg), "mesh": kind, **guides})


def metrics_text(mesh, design):
    """The metrics as lines of text: mode, admissible θ, folds, and each measured
    error (relative to the model size) with where it is worst."""
    i = info(design)
    lines = [
        f"mode: {i['mode']}, θ = {mesh.theta_deg:g}°, admissible |θ| in "
        f"[{i['theta_abs_min_deg']:g}°, {i['theta_abs_max_deg']:g}°]",
        f"grid: {mesh.rows} × {mesh.cols} vertices ({mesh.kind})",
        f"folded faces: {mesh.report['folded_faces']}, "
        f"smallest crossing sine: {mesh.report['min_crossing_sine']:.3g}",
    ]
    for key, value in check(mesh).items():
        if key == "folded_faces" or not isinstance(value, dict):
            continue  # the folds are the generator's report, above
        lines.append(f"{key}: {value['value']:.2e} at {tuple(value['at'])}")
    return lines


def rhino_mesh(mesh_type, vertices, faces, normals=None):
    """A mesh of ``mesh_type`` (``Rhino.Geometry.Mesh`` in Rhino,
    ``rhino3dm.Mesh`` elsewhere) with the ``vertices``, ``faces`` (of four or three
    corners) and optional vertex ``normals`` that ``solve`` and ``approximate``
    output."""
    m = mesh_type()
    for x, y, z in vertices:
        m.Vertices.Add(x, y, z)
    for face in faces:
        m.Faces.AddFace(*face)
    for x, y, z in normals or []:
        m.Normals.Add(x, y, z)
    return m


def solve(guide_u, guide_v, theta_deg, samples=21, kind="circular"):
    """Everything the components output: ``mesh`` (a ``monge.Mesh``),
    ``vertices`` and ``gauss`` (its node axes, the Gauss map, circular meshes
    only) as lists of (x, y, z), ``faces`` as lists of four indices, and
    ``metrics`` as lines of text."""
    design = design_from_curves(guide_u, guide_v, theta_deg, samples, kind)
    mesh = generate(design)
    return _outputs(mesh, metrics_text(mesh, design))


def _outputs(mesh, metrics):
    """The outputs of a component showing ``mesh`` (see ``solve``)."""
    return {
        "mesh": mesh,
        "vertices": mesh.vertices.reshape(-1, 3).tolist(),
        "faces": mesh.faces.tolist(),
        "gauss": None if mesh.normals is None else mesh.normals.reshape(-1, 3).tolist(),
        "metrics": metrics,
    }


def _untrimmed(design):
    """The design before trimming of a ``TrimmedDesign``; any other design as it is."""
    return design.design if isinstance(design, TrimmedDesign) else design


def approximation_text(result):
    """What a designer looks at in ``monge.approximate``'s ``result``, as lines of
    text: the panels and node types, the largest and RMS deviation both ways in
    model units, each patch of several, the tolerance (met, or why not) and the
    search."""
    d, size = result["deviation"], result["deviation"]["size"]
    timed_out = ", stopped at the time limit" if result["timed_out"] else ""
    if result["patches"] == 1:
        shape = f"θ = {result['theta_deg']:g}°"
    else:
        thetas = ", ".join(f"{t:g}°" for t in _untrimmed(result["design"]).theta_deg)
        shape = f"{result['patches']} patches (§4.7), θ = {thetas}"
    lines = [
        f"panels: {result['panels']}, {shape}",
        f"largest deviation: {result['max_deviation']:.3g} model units (the target's size is {size:.4g}): "
        f"mesh → target {d['mesh_to_target_max']:.3g}, target → mesh {d['target_to_mesh_max']:.3g}",
        f"RMS deviation: mesh → target {d['mesh_to_target_rms']:.3g}, "
        f"target → mesh {d['target_to_mesh_rms']:.3g} model units",
    ]
    if result.get("node_types") is not None:
        lines.append(f"node types: {result['node_types']} (beam angles within {result['node_angle_tol_deg']:g}°)")
    elif result.get("node_types_why_not"):
        lines.append(f"node types not counted: {result['node_types_why_not']}")
    if result["patches"] > 1:
        fit = result.get("patch_fit", result)
        for k, p in enumerate(fit["per_patch"]):
            lines.append(
                f"patch {k + 1}: θ = {p['theta_deg']:g}°, largest deviation target → mesh "
                f"{p['max'] * size:.3g} model units ({p['target_points']} points)"
            )
    trimmed = result.get("trimmed")
    if trimmed is not None:
        lines.append(
            f"trimmed to the target's outline: {len(trimmed['faces'])} planar panels, "
            f"{sum(trimmed['cut'])} of them cut"
        )
    if "met" in result:
        tolerance = f"{result['tolerance']:.3g} model units"
        lines.append(
            f"within the tolerance of {tolerance}"
            if result["met"]
            else f"NOT within the tolerance of {tolerance}: {result['why']}"
        )
    lines.append(f"search: {result['evaluations']} meshes generated, {result['starts']} starts{timed_out}")
    return lines


def approximate(geometry, **options):
    """Everything a component rationalising ``geometry`` outputs: ``geometry`` is
    what ``monge.approximate`` accepts (a Rhino mesh, point cloud, surface or
    Brep, points, ...), ``options`` its keywords (``grid``, ``kind``,
    ``tolerance``, ``trim``, ``time_limit``, ...). Returns, as ``solve`` does, ``mesh`` (a
    ``monge.Mesh``; None for several patches), ``vertices``, ``faces`` (of a result
    trimmed to the target's outline, its mesh's, ``gauss`` None), ``gauss``
    and ``metrics`` (the deviation, ``approximation_text``, then for one patch the
    mesh's metrics, ``metrics_text``), with the ``design`` found
    (``design.to_file(path)`` saves it) and ``result``, ``monge.approximate``'s
    whole answer (of a result trimmed to the target's outline, ``design`` is a
    ``monge.TrimmedDesign``, the file ``monge generate`` cuts as the fit did)."""
    result = _approximate(geometry, **options)
    mesh, design, trimmed = result["mesh"], result["design"], result.get("trimmed")
    metrics = approximation_text(result)
    if trimmed is not None:
        # The result is the mesh trimmed to the target's outline: its panels as
        # triangles and quads (each cut one split in its plane); `mesh` is the design's.
        # Of several patches, each is exact on its own grid.
        exactness = (
            metrics_text(mesh, _untrimmed(design))
            if mesh is not None
            else [f"exactness (each patch measured on its own grid): {result['max_error']:.2e}"]
        )
        outputs = {
            "mesh": mesh,
            "vertices": trimmed["vertices"].tolist(),
            "faces": trimmed["mesh_faces"],
            "gauss": None,
            "metrics": metrics + exactness,
        }
    elif mesh is not None:
        outputs = _outputs(mesh, metrics + metrics_text(mesh, design))
    else:
        # Several patches: their merged mesh (each patch is exact on its own grid,
        # the exactness the text gives), as lists like a Mesh's outputs.
        normals = result["normals"]
        outputs = {
            "mesh": None,
            "vertices": result["vertices"].reshape(-1, 3).tolist(),
            "faces": result["faces"].tolist(),
            "gauss": None if normals is None else normals.reshape(-1, 3).tolist(),
            "metrics": metrics + [f"exactness (each patch measured on its own grid): {result['max_error']:.2e}"],
        }
    return {**outputs, "design": design, "result": result}


__all__ = [
    "sample_curve",
    "design_from_curves",
    "metrics_text",
    "rhino_mesh",
    "solve",
    "approximation_text",
    "approximate",
]
