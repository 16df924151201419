//! `approximate`, as `monge approximate`: the design whose exact mesh is nearest a
//! target (one patch, several patches, or as many as a tolerance needs), with the
//! command's report.

use monge_core::approximate::{
    approximate as core_approximate, approximate_patches, approximate_to_tolerance, deadline_after,
    fit_report, ApproxOptions, Approximation, Chosen, Deviation, FitDesign, FitReport, Outline,
    PatchApproximation, PatchLayout, Stop, TargetCloud, Tolerance, ToleranceFit, ToleranceOptions,
    PATCHES_GAIN,
};
use monge_core::fabrication::DESIGN_ANGLE_TOL_DEG;
use monge_core::multipatch::{build, MultiPatchDesign};
use monge_core::{GenerateOptions, MeshKind, QuadGrid};
use monge_io::Trimmable;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use pythonize::pythonize;

use crate::args;
use crate::design::{kind_name, parse_kind, Design, PatchesDesign};
use crate::errors::{py_float, OptimiseError};
use crate::mesh::{faces_array, measurements, Mesh};
use crate::target::{points_array, points_of};
use crate::trimmed::{trimmed_dict, TrimmedDesign};

/// The design whose exact mesh is nearest to a target, as `monge approximate`
/// (monge's extension of the method). `target` is what a designer has: any
/// array of shape (..., 3) or list of points (a mesh's vertices or a point
/// cloud); a Rhino mesh, point cloud, surface or Brep (RhinoCommon inside Rhino
/// 8, or rhino3dm), a surface or Brep sampled at about 4000 points on a grid of
/// its parameters as the command samples IGES surfaces; a COMPAS mesh (its
/// vertices); or the path of a file the command reads (OBJ, PLY, JSON, STL, points one a
/// line, IGES):
/// `target_points(target)` gives the points taken.
///
/// `patches` (`"2x3"`, `3` or `(2, 3)`, as `--patches`) then fits that many
/// patches with piecewise planar curvature lines (§4.7), kept if they follow the
/// target closer than one; `tolerance` (as `--tolerance`: a number relative to the
/// target's size, `5e-3`, or a length, `"0.05m"`, `"5cm"`, `"50mm"`) fits one
/// patch, then 2 × 1, 2 × 2, 3 × 2, … patches up to `max_patches` (default 6) until
/// the mesh is within it both ways. `trim=True` (as `--trim`) fits a mesh that
/// covers the target and trims it to the target's outline (with `patches`, the
/// patches cover it too and are trimmed where they are kept): `trimmed` is
/// then a dict of its `vertices` (n, 3), `faces` (lists of vertex indices, planar
/// polygons) and `cut` (per face, whether the outline cut it), and `after` measures
/// it; otherwise None.
///
/// Returns the `design` found (a `Design`, or a `PatchesDesign` of several patches,
/// or of a trimmed result a `TrimmedDesign`, the design before trimming and the
/// target's outline: `design.to_file(path)` writes it as the command does), the
/// `initial` guess (a
/// `Design`), its `mesh` (a `Mesh`, for `monge.rhino.write_3dm`,
/// `monge.compas.to_mesh`, `monge.blender.add_mesh`; None for several patches), its
/// `kind`, `vertices` (rows, cols, 3), `normals` (its node axes, (rows, cols, 3);
/// None for `kind="conical"`, whose mesh is the conical dual, §2.3) and `faces`
/// (as `Mesh.faces`), `panels` (its number of faces; of a trimmed mesh, its polygons),
/// its `max_error` as `check`
/// measures it (each patch on its own grid: the exactness the command prints), the
/// deviation `before` and `after` (dicts of distances relative to the target's
/// `size`), `deviation` (`after` in model units) and `max_deviation` (the larger of
/// its two largest distances, model units), `patches` (how many), `theta_deg` (None
/// for several patches), `target_points`, `stray` (the indices of the target's stray
/// points, set aside as the command sets them aside), `evaluations`, `starts` and
/// `timed_out`.
///
/// With `patches`: `patch_fit`, the fit of the patches (`design`, `after`,
/// `per_patch`, `max_error`, `evaluations`, and `closer`, whether it is the
/// `design` returned). With `tolerance`, the command's report: `tolerance` (model
/// units) and `tolerance_relative`, `met`, `stop` (`"met"`, `"max_patches"`,
/// `"time_limit"`, `"refused"` or `"scan_edge"`: a scan within the tolerance as far as
/// its points tell, its edge not) and `why` (None when met), `chosen`
/// (`"initial_guess"`, `"one_patch"`, `"trimmed"`: one patch covering the target, trimmed
/// to its outline, tried after one patch, its mesh in `trimmed`; `"patches"`; or
/// `"trimmed_patches"`: several patches refining that one, trimmed too), `steps`, each fit tried
/// (`patches`, `trimmed`, its `deviation` or the `error` that kept it from being
/// fitted, and `resolved_max`, its largest distance both ways as far as a scan's points
/// tell its edge, by which the fits are compared: on a mesh, the deviation's; NaN where
/// not fitted);
/// `node_types`, nodes whose beam angles and angles to the node axis agree within
/// `node_angle_tol_deg` (`angle_tol_deg`, default 0.5°, a designer's fabrication
/// tolerance) being one type, as `fabricate(angle_tol_deg=...)` groups them; and
/// `per_patch`, each patch's `block`, `theta_deg`, `target_points` (the target
/// points nearest to it) and their `max` and `rms` distance to the mesh (relative).
#[pyfunction]
#[pyo3(
    signature = (target, grid = (40, 40), kind = "circular", starts = 4, max_evaluations = 1500, time_limit = None, keep_boundary = false, trim = false, patches = None, tolerance = None, max_patches = None, angle_tol_deg = None),
    text_signature = "(target, grid=(40, 40), kind='circular', starts=4, max_evaluations=1500, time_limit=None, keep_boundary=False, trim=False, patches=None, tolerance=None, max_patches=None, angle_tol_deg=None)"
)]
#[allow(clippy::too_many_arguments)]
pub fn approximate<'py>(
    py: Python<'py>,
    target: &Bound<'py, PyAny>,
    #[pyo3(from_py_with = args::grid)] grid: (usize, usize),
    kind: &str,
    #[pyo3(from_py_with = args::starts)] starts: usize,
    #[pyo3(from_py_with = args::approximate_evaluations)] max_evaluations: usize,
    time_limit: Option<f64>,
    keep_boundary: bool,
    trim: bool,
    #[pyo3(from_py_with = args::patches)] patches: Option<PatchLayout>,
    #[pyo3(from_py_with = args::tolerance)] tolerance: Option<Tolerance>,
    #[pyo3(from_py_with = args::max_patches)] max_patches: Option<usize>,
    angle_tol_deg: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    if patches.is_some() && tolerance.is_some() {
        return Err(OptimiseError::new_err(
            "patches and tolerance: give one (tolerance chooses the patches itself), as the \
             command's --patches and --tolerance",
        ));
    }
    if trim && (tolerance.is_some() || keep_boundary) {
        return Err(OptimiseError::new_err(
            "trim fits a mesh that covers the target: give it without tolerance (which tries \
             one itself) and keep_boundary, as the command's --trim",
        ));
    }
    if max_patches.is_some() && tolerance.is_none() {
        return Err(OptimiseError::new_err(
            "max_patches bounds the patches a tolerance fit tries: give tolerance too",
        ));
    }
    match angle_tol_deg {
        Some(a) if !(a.is_finite() && a >= 0.0) => {
            return Err(OptimiseError::new_err(format!(
                "angle_tol_deg = {}: give a finite, non-negative number of degrees (default \
                 {DESIGN_ANGLE_TOL_DEG})",
                py_float(a)
            )));
        }
        Some(_) if tolerance.is_none() => {
            return Err(OptimiseError::new_err(
                "angle_tol_deg groups the node types of a tolerance fit's report: give \
                 tolerance too",
            ));
        }
        _ => {}
    }
    let points = points_of(target)?;
    let deadline = match time_limit {
        Some(t) => {
            deadline_after(t).map_err(|e| OptimiseError::new_err(format!("time_limit: {e}")))?
        }
        None => None,
    };
    let kind = parse_kind(Some(kind), MeshKind::Circular)?;
    let options = ApproxOptions {
        faces: grid,
        kind,
        starts,
        max_evaluations,
        deadline,
        keep_boundary,
        trim,
    };
    let error = |e: &dyn std::fmt::Display| OptimiseError::new_err(e.to_string());
    let fit = py.detach(|| -> PyResult<Fit> {
        if let Some(tolerance) = tolerance {
            let options = ToleranceOptions {
                tolerance,
                max_patches: max_patches.unwrap_or(ToleranceOptions::default().max_patches),
                approx: options,
            };
            let fit =
                approximate_to_tolerance(&points, &options, &mut |_| {}).map_err(|e| error(&e))?;
            return Ok(Fit::Tolerance(Box::new(fit)));
        }
        let single = core_approximate(&points, &options, &mut |_| {}).map_err(|e| error(&e))?;
        Ok(match patches {
            Some(layout) => {
                let p = approximate_patches(&points, &single, layout, &options, &mut |_| {})
                    .map_err(|e| error(&e))?;
                Fit::Patches(Box::new((single, p)))
            }
            None => Fit::Single(Box::new(single)),
        })
    })?;
    let (single, design, mesh_grid, after) = fit.kept();
    let (report, max_error) = py.detach(|| -> PyResult<(Option<FitReport>, f64)> {
        // The report of a tolerance fit, as the command prints it.
        let report = match &fit {
            Fit::Tolerance(_) => {
                let cloud = TargetCloud::new(&points).map_err(|e| error(&e))?;
                let angle_tol = angle_tol_deg.unwrap_or(DESIGN_ANGLE_TOL_DEG).to_radians();
                Some(fit_report(&cloud, &design, angle_tol).map_err(|e| error(&e))?)
            }
            _ => None,
        };
        let max_error = match &design {
            FitDesign::Single(_) | FitDesign::Trimmed(..) => measurements(mesh_grid, kind, None).1,
            FitDesign::Patches(d) | FitDesign::TrimmedPatches(d, _) => patches_max_error(d)?,
        };
        Ok((report, max_error))
    })?;
    let d = PyDict::new(py);
    let g = mesh_grid;
    d.set_item(
        "vertices",
        points_array(py, &g.vertices, &[g.rows, g.cols])?,
    )?;
    // A conical mesh has face normals, not node axes (§2.3).
    let normals = match kind {
        MeshKind::Circular => Some(points_array(py, &g.normals, &[g.rows, g.cols])?),
        MeshKind::Conical => None,
    };
    d.set_item("normals", normals)?;
    d.set_item("faces", faces_array(py, g)?)?;
    d.set_item("kind", kind_name(kind))?;

    d.set_item("max_error", max_error)?;
    d.set_item("before", pythonize(py, &single.before)?)?;
    d.set_item("after", pythonize(py, &after)?)?;
    d.set_item("deviation", model_units(py, &after)?)?;
    d.set_item("max_deviation", after.max() * after.size)?;
    d.set_item("patches", design.patches())?;
    d.set_item("target_points", points.len())?;
    // The target's stray points, set aside as the command sets them aside.
    d.set_item("stray", single.stray.clone())?;
    d.set_item("starts", single.starts)?;
    d.set_item("initial", Bound::new(py, plain(single.initial.clone()))?)?;
    let trimmed = design.trimmed();
    // A trimmed result's panels are its polygons, as the command counts them.
    d.set_item("panels", trimmed.map_or(g.face_count(), |m| m.faces.len()))?;
    let trimmed = trimmed.map(|m| trimmed_dict(py, m)).transpose()?;
    d.set_item("trimmed", trimmed)?;
    match &design {
        FitDesign::Single(inner) | FitDesign::Trimmed(inner, _) => {
            let found = plain(inner.clone());
            // The mesh as `generate` makes it: the same vertices as the grid, with its report.
            let mesh =
                py.detach(|| Mesh::generate(&found, kind, &GenerateOptions::default(), None))?;
            d.set_item("theta_deg", found.inner.theta_deg)?;
            d.set_item("design", Bound::new(py, found)?)?;
            d.set_item("mesh", Bound::new(py, mesh)?)?;
        }
        FitDesign::Patches(inner) | FitDesign::TrimmedPatches(inner, _) => {
            d.set_item("theta_deg", py.None())?;
            d.set_item(
                "design",
                Bound::new(
                    py,
                    PatchesDesign {
                        inner: inner.clone(),
                    },
                )?,
            )?;
            d.set_item("mesh", py.None())?;
        }
    }
    // A trimmed result's design is the command's trimmed design: the design before
    // trimming and the target's outline, which the fit cut it by.
    if design.trimmed().is_some() {
        let cloud = TargetCloud::new(&points).map_err(|e| error(&e))?;
        let trim = Outline::of(&cloud).map_err(|e| error(&e))?;
        let inner = monge_io::TrimmedDesign {
            design: Trimmable::of_fit(&design),
            trim,
        };
        d.set_item("design", Bound::new(py, TrimmedDesign { inner })?)?;
    }
    match &fit {
        Fit::Single(r) => {
            d.set_item("evaluations", r.evaluations)?;
            d.set_item("timed_out", r.timed_out)?;
        }
        Fit::Patches(b) => {
            let (r, p) = &**b;
            d.set_item("evaluations", r.evaluations)?;
            d.set_item("timed_out", r.timed_out)?;
            let pf = PyDict::new(py);
            pf.set_item(
                "design",
                Bound::new(
                    py,
                    PatchesDesign {
                        inner: p.design.clone(),
                    },
                )?,
            )?;
            pf.set_item("after", pythonize(py, &p.after)?)?;
            pf.set_item("per_patch", pythonize(py, &p.per_patch)?)?;
            pf.set_item("max_error", py.detach(|| patches_max_error(&p.design))?)?;
            pf.set_item("evaluations", p.evaluations)?;
            pf.set_item("closer", p.closer_than(r))?;
            d.set_item("patch_fit", pf)?;
        }
        Fit::Tolerance(f) => {
            d.set_item("evaluations", f.evaluations)?;
            d.set_item("timed_out", f.stop == Stop::TimeLimit)?;
            tolerance_items(py, &d, f)?;
            if let Some(report) = &report {
                // None, and why, when fabrication refuses the mesh found.
                d.set_item("node_types", report.node_types.as_ref().ok())?;
                d.set_item(
                    "node_types_why_not",
                    report.node_types.as_ref().err().map(|e| e.to_string()),
                )?;
                d.set_item("node_angle_tol_deg", report.node_angle_tol.to_degrees())?;
                d.set_item("per_patch", pythonize(py, &report.per_patch)?)?;
            }
        }
    }
    Ok(d)
}

/// What `approximate` found: one patch; one patch and the fit of patches
/// (`patches=`); or a tolerance fit (`tolerance=`).
enum Fit {
    Single(Box<Approximation>),
    Patches(Box<(Approximation, PatchApproximation)>),
    Tolerance(Box<ToleranceFit>),
}

impl Fit {
    /// The one-patch fit, and the design kept, its mesh and deviation: the fit of
    /// patches when it follows the target closer, as the command keeps it.
    fn kept(&self) -> (&Approximation, FitDesign, &QuadGrid, Deviation) {
        match self {
            Fit::Single(r) => (r, one_patch(r), &r.grid, r.after),
            Fit::Patches(b) => {
                let (r, p) = &**b;
                if p.closer_than(r) {
                    let design = match &p.trimmed {
                        Some(mesh) => FitDesign::TrimmedPatches(p.design.clone(), mesh.clone()),
                        None => FitDesign::Patches(p.design.clone()),
                    };
                    (r, design, &p.grid, p.after)
                } else {
                    (r, one_patch(r), &r.grid, r.after)
                }
            }
            Fit::Tolerance(f) => (&f.single, f.design.clone(), &f.grid, f.deviation),
        }
    }
}

/// The design of a one-patch fit, trimmed where it is.
fn one_patch(r: &Approximation) -> FitDesign {
    match &r.trimmed {
        Some(mesh) => FitDesign::Trimmed(r.design.clone(), mesh.clone()),
        None => FitDesign::Single(r.design.clone()),
    }
}

/// The exactness of a multi-patch design: each patch measured on its own grid.
fn patches_max_error(design: &MultiPatchDesign) -> PyResult<f64> {
    let mp = build(design, &GenerateOptions::default())
        .map_err(|e| OptimiseError::new_err(format!("the multi-patch design found: {e}")))?;
    Ok(mp.max_error())
}

/// A design made in Python (no file).
fn plain(inner: monge_core::Design) -> Design {
    Design {
        inner,
        source: None,
    }
}

/// The items of a tolerance fit's report: the tolerance, whether it is met and why
/// not, which design was kept, and every fit tried.
fn tolerance_items(py: Python<'_>, d: &Bound<'_, PyDict>, fit: &ToleranceFit) -> PyResult<()> {
    let size = fit.deviation.size;
    d.set_item("tolerance", fit.limit * size)?;
    d.set_item("tolerance_relative", fit.limit)?;
    d.set_item("met", fit.met())?;
    let (stop, why) = match &fit.stop {
        Stop::Met => ("met", None),
        Stop::MaxPatches(n) => (
            "max_patches",
            Some(if fit.patches_helped() == Some(false) {
                format!(
                    "up to {n} patches tried (max_patches={n}), the last layout ({} patches) \
                     not {}% nearer than fewer patches (steps): more patches are unlikely to \
                     reach it; split the target into parts and approximate each, or give a \
                     larger tolerance",
                    fit.last_layout().unwrap_or(*n),
                    100.0 * PATCHES_GAIN
                )
            } else {
                format!(
                    "{n} patch{} tried (max_patches={n}); allow more patches, give a finer grid \
                     or a larger tolerance",
                    if *n == 1 { "" } else { "es" }
                )
            }),
        ),
        Stop::TimeLimit => (
            "time_limit",
            Some("the time limit ended the search (time_limit); give more time".to_owned()),
        ),
        Stop::Refused { patches, error } => (
            "refused",
            Some(format!("{patches} patches cannot be fitted: {error}")),
        ),
        Stop::ScanEdge { .. } => ("scan_edge", fit.stop.scan_edge_reason(size)),
    };
    d.set_item("stop", stop)?;
    d.set_item("why", if fit.met() { None } else { why })?;
    d.set_item(
        "chosen",
        match fit.chosen {
            Chosen::InitialGuess => "initial_guess",
            Chosen::OnePatch => "one_patch",
            Chosen::Trimmed => "trimmed",
            Chosen::Patches(_) => "patches",
            Chosen::TrimmedPatches(_) => "trimmed_patches",
        },
    )?;
    let steps = PyList::empty(py);
    for step in &fit.steps {
        let s = PyDict::new(py);
        s.set_item("patches", step.patches)?;
        s.set_item("trimmed", step.trimmed)?;
        s.set_item("resolved_max", step.resolved)?;
        match &step.outcome {
            Ok(deviation) => {
                s.set_item("deviation", pythonize(py, deviation)?)?;
                s.set_item("error", py.None())?;
            }
            Err(e) => {
                s.set_item("deviation", py.None())?;
                s.set_item("error", e.to_string())?;
            }
        }
        steps.append(s)?;
    }
    d.set_item("steps", steps)?;
    Ok(())
}

/// The distances of `deviation` in model units: each relative distance times the
/// target's size (`size` itself as it is).
fn model_units<'py>(py: Python<'py>, deviation: &Deviation) -> PyResult<Bound<'py, PyDict>> {
    let d = pythonize(py, deviation)?.cast_into::<PyDict>()?;
    let items: Vec<_> = d.iter().collect();
    for (key, value) in items {
        if key.extract::<String>()? != "size" {
            d.set_item(&key, value.extract::<f64>()? * deviation.size)?;
        }
    }
    Ok(d)
}
