"""Grasshopper and Hops: two guide curves and θ in, the mesh, its Gauss map
and its metrics out.

The logic of the Grasshopper script component and of the Hops endpoint in
``examples/grasshopper/``, kept here so that it runs (and is tested) outside
Rhino: the curves may be RhinoCommon curves (inside Rhino) or rhino3dm curves
(Hops, tests), which share the members used here (``Domain.T0``/``T1``,
``PointAt``, ``TangentAtStart``). No geometry is made here: the curves are
sampled and the samples handed to ``monge.generate`` as ``points`` guides
with the curves' exact start tangents.
"""


from ._monge import Design, DesignError, check, generate, info


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


def solve(guide_u, guide_v, theta_deg, samples=21, kind="circular"):
    """Everything the components output: ``mesh`` (a ``monge.Mesh``),
    ``vertices`` and ``gauss`` (its node axes, the Gauss map, circular meshes
    only) as lists of (x, y, z), ``faces`` as lists of four indices, and
    ``metrics`` as lines of text."""
    design = design_from_curves(guide_u, guide_v, theta_deg, samples, kind)
    mesh = generate(design)
    return {
        "mesh": mesh,
        "vertices": mesh.vertices.reshape(-1, 3).tolist(),
        "faces": mesh.faces.tolist(),
        "gauss": None if mesh.normals is None else mesh.normals.reshape(-1, 3).tolist(),
        "metrics": metrics_text(mesh, design),
    }


__all__ = ["sample_curve", "design_from_curves", "metrics_text", "solve"]
