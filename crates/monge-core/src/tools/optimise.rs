//! Fitting a multi-patch design to a target (§4.7, the HippoHaus of Figure 21):
//! choose free parameters — θ of chosen patches, optionally guide coordinates — so
//! that a patch boundary comes as close as possible to a target polyline (or plane),
//! with the paper's optimiser,
//! BOBYQA (M. J. D. Powell, *The BOBYQA algorithm for bound constrained
//! optimization without using derivatives*, DAMTP 2009/NA06, Cambridge, 2009;
//! the paper cites it as Powell 2007), the `bobyqa` crate (a port of PRIMA).
//!
//! Bounds: each free θ stays in the admissible range of its patch at the start
//! values (§3.2: `|θ| ∈ [min, max]`, on the side of 0 of the start value when the
//! range excludes 0) and at least [`SINGULAR_MARGIN_DEG`] away from the singular
//! +90°, intersected with the bounds given; coordinates stay in their given bounds.
//! BOBYQA works on the parameters scaled to `[0, 1]`. Points where a patch cannot be
//! generated (θ of a later patch inadmissible once earlier θ moved, a pinch) count
//! as infinitely far.
//!
//! The objective is the mean squared distance from the boundary's vertices to the
//! target (to the polyline's nearest point, or to the plane), divided by the squared
//! model size; the reported distances are the largest and the root-mean-square one.

use glam::DVec3;
use serde::Serialize;

use crate::design::{GuideSpec, Xyz};
use crate::generate::{GenerateOptions, SINGULAR_WINDOW_DEG};
use crate::grid::point_segment;
use crate::multipatch::{build, MultiPatch, MultiPatchDesign, MultiPatchError};

pub use crate::multipatch::{BoundaryRef, FitSpec, FreeParameter, GuideKey, Target};

/// How far (degrees) a fitted θ stays from the singular +90° (§2.2.1): closer, the
/// Gauss map contracts onto the corner normal and meshes collapse.
pub const SINGULAR_MARGIN_DEG: f64 = 1.0;

/// Why a fit cannot be run or did not reach its target (§4.7).
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum FitError {
    /// The design has no `fit` key.
    #[error("the design has no `fit`: add `\"fit\": {{\"free\": [{{\"theta\": {{\"patch\": 1}}}}], \"boundary\": \
             {{\"patch\": 1, \"side\": \"last_row\"}}, \"target\": {{\"polyline\": [[x, y, z], …]}}}}`")]
    NoFit,
    /// `free` is empty.
    #[error(
        "`fit.free` is empty: name at least one parameter, e.g. {{\"theta\": {{\"patch\": 1}}}}"
    )]
    NoFreeParameters,
    /// A free parameter names something that does not exist or is malformed.
    #[error("`fit.free[{index}]` ({name}): {problem}")]
    BadParameter {
        /// Index in `fit.free`.
        index: usize,
        /// The parameter's name.
        name: String,
        /// What is wrong.
        problem: String,
    },
    /// The bounds of a parameter leave no room.
    #[error("`fit.free[{index}]` ({name}) has empty bounds: the admissible interval {admissible:?}° (§3.2, \
             kept {margin}° away from the singular +90°) and the requested bounds {requested:?} do not overlap \
             in an interval; widen the bounds or start θ on the other side of 0 or of 90°")]
    EmptyBounds {
        /// Index in `fit.free`.
        index: usize,
        /// The parameter's name.
        name: String,
        /// The admissible interval at the start values.
        admissible: [f64; 2],
        /// The requested bounds.
        requested: [f64; 2],
        /// [`SINGULAR_MARGIN_DEG`].
        margin: f64,
    },
    /// The target is unusable.
    #[error("`fit.target`: {problem}")]
    BadTarget {
        /// What is wrong.
        problem: String,
    },
    /// The boundary names a patch that does not exist.
    #[error("`fit.boundary` names patch {patch}, but the design has {count} patches (0..{count})")]
    BadBoundary {
        /// The patch named.
        patch: usize,
        /// Number of patches.
        count: usize,
    },
    /// The design cannot be built at its start values.
    #[error(
        "the design cannot be built at its start values, so there is nothing to fit from: {0}"
    )]
    Start(#[from] MultiPatchError),
    /// The fit ended farther from the target than `max_distance`.
    #[error("unreachable target: the best fit leaves the boundary {distance:.3e} from the target at its farthest \
             vertex ({relative:.1e} of the model size), more than max_distance = {max_distance:.3e} \
             (fitted values {values:?}). Free more parameters, widen their bounds, or move the target")]
    Unreachable {
        /// The largest distance after the fit.
        distance: f64,
        /// The largest distance relative to the model size.
        relative: f64,
        /// `fit.max_distance`.
        max_distance: f64,
        /// The best values found.
        values: Vec<f64>,
    },
    /// `max_evaluations` leaves BOBYQA no room beyond its initial model.
    #[error("`fit.max_evaluations` = {given} is too small: BOBYQA needs more than its {needed_model} \
             initial model points, i.e. at least {needed}", needed_model = .needed - 1)]
    TooFewEvaluations {
        /// The budget given.
        given: usize,
        /// The smallest budget accepted.
        needed: usize,
    },
}

/// Distance from a boundary to a target (§4.7).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Distance {
    /// Largest distance of a boundary vertex from the target (model units).
    pub max: f64,
    /// Root-mean-square distance.
    pub rms: f64,
    /// `max` divided by the model size (the assembled grid's bounding-box diagonal).
    pub relative: f64,
}

/// The result of [`fit`] (§4.7).
#[derive(Clone, Debug)]
pub struct FitResult {
    /// The design with the fitted values written in.
    pub design: MultiPatchDesign,
    /// The multi-patch mesh of the fitted design.
    pub mesh: MultiPatch,
    /// Per free parameter: name, start value, fitted value, bounds used.
    pub values: Vec<(String, f64, f64, [f64; 2])>,
    /// Distance at the start values.
    pub before: Distance,
    /// Distance at the fitted values.
    pub after: Distance,
    /// Number of meshes generated by the optimiser.
    pub evaluations: usize,
    /// Why BOBYQA stopped.
    pub status: String,
}

/// Fit the free parameters of `design.fit` with BOBYQA (§4.7). Values where a
/// patch cannot be built or folds (§5.2) are infeasible.
///
/// ```
/// use monge_core::multipatch::MultiPatchDesign;
/// use monge_core::optimise::{fit, FitError};
/// let empty = MultiPatchDesign { patches: vec![], tolerance: None, fit: None, symmetry: vec![] };
/// assert_eq!(fit(&empty, &Default::default()).unwrap_err(), FitError::NoFit);
/// ```
pub fn fit(design: &MultiPatchDesign, options: &GenerateOptions) -> Result<FitResult, FitError> {
    let spec = design.fit.as_ref().ok_or(FitError::NoFit)?;
    if spec.free.is_empty() {
        return Err(FitError::NoFreeParameters);
    }
    let target = check_target(&spec.target)?;
    if spec.boundary.patch >= design.patches.len() {
        return Err(FitError::BadBoundary {
            patch: spec.boundary.patch,
            count: design.patches.len(),
        });
    }
    if let Some(m) = spec.max_distance
        && !(m.is_finite() && m >= 0.0)
    {
        return Err(FitError::BadTarget {
            problem: format!("`max_distance` is {m}: give a finite distance ≥ 0"),
        });
    }
    let start_mesh = build(design, options)?;
    let scale = start_mesh.grid.bbox_diagonal().max(f64::MIN_POSITIVE);
    let mut start = Vec::with_capacity(spec.free.len());
    let mut bounds = Vec::with_capacity(spec.free.len());
    for (index, p) in spec.free.iter().enumerate() {
        let value = read_value(design, index, p)?;
        let b = parameter_bounds(&start_mesh, index, p, value)?;
        start.push(value.clamp(b[0], b[1]));
        bounds.push(b);
    }
    let before = distance(&start_mesh, spec, &target, scale);
    let n = spec.free.len();
    let evaluate = |x: &[f64]| -> f64 {
        let values: Vec<f64> = x
            .iter()
            .zip(&bounds)
            .map(|(t, b)| b[0] + t * (b[1] - b[0]))
            .collect();
        let trial = with_values(design, &spec.free, &values);
        match build(&trial, options) {
            // A folded patch (§5.2) is infeasible, like one that cannot be built.
            Ok(mesh) if mesh.patches.iter().all(|p| p.folded_faces == 0) => {
                let d = distance(&mesh, spec, &target, scale);
                (d.rms / scale).powi(2)
            }
            _ => f64::NAN,
        }
    };
    let max_fun = spec.max_evaluations.unwrap_or(1000 * n + 200);
    let mut solver = solver(n, 1e-12, max_fun).map_err(|needed| FitError::TooFewEvaluations {
        given: max_fun,
        needed,
    })?;
    let mut x: Vec<f64> = start
        .iter()
        .zip(&bounds)
        .map(|(v, b)| (v - b[0]) / (b[1] - b[0]))
        .collect();
    let (lower, upper) = (vec![0.0; n], vec![1.0; n]);
    let x0 = x.clone();
    // The unit box is 10 × 2·rho_begin wide: BOBYQA accepts it.
    let outcome = solver.minimize(evaluate, &mut x, &lower, &upper);
    // BOBYQA returns the best point it evaluated; keep the start if nothing was better.
    if !outcome.found_finite() {
        x = x0;
    }
    let fitted: Vec<f64> = x
        .iter()
        .zip(&bounds)
        .map(|(t, b)| b[0] + t * (b[1] - b[0]))
        .collect();
    let fitted_design = with_values(design, &spec.free, &fitted);
    let mesh = build(&fitted_design, options)?;
    let after = distance(&mesh, spec, &target, scale);
    if let Some(max_distance) = spec.max_distance
        && (after.max > max_distance || after.max.is_nan())
    {
        return Err(FitError::Unreachable {
            distance: after.max,
            relative: after.relative,
            max_distance,
            values: fitted,
        });
    }
    let values = spec
        .free
        .iter()
        .zip(start.iter().zip(&fitted).zip(&bounds))
        .map(|(p, ((s, f), b))| (p.name(), *s, *f, *b))
        .collect();
    Ok(FitResult {
        design: fitted_design,
        mesh,
        values,
        before,
        after,
        evaluations: outcome.n_eval,
        status: outcome.status.to_string(),
    })
}

/// The target checked and converted.
enum CheckedTarget {
    Polyline(Vec<DVec3>),
    Plane { point: DVec3, normal: DVec3 },
}

fn check_target(t: &Target) -> Result<CheckedTarget, FitError> {
    let bad = |problem: String| FitError::BadTarget { problem };
    match t {
        Target::Polyline(points) => {
            if points.len() < 2 {
                return Err(bad(format!(
                    "the polyline has {} point(s); give at least 2",
                    points.len()
                )));
            }
            if let Some(k) = points.iter().position(|p| !p.iter().all(|x| x.is_finite())) {
                return Err(bad(format!("polyline point {k} is not finite")));
            }
            let pts: Vec<DVec3> = points.iter().map(|p| DVec3::from_array(*p)).collect();
            if crate::grid::bbox_diagonal(&pts) == 0.0 {
                return Err(bad("all polyline points coincide".to_owned()));
            }
            Ok(CheckedTarget::Polyline(pts))
        }
        Target::Plane { point, normal } => {
            let (p, n) = (DVec3::from_array(*point), DVec3::from_array(*normal));
            if !p.is_finite() || !n.is_finite() || n.length_squared() == 0.0 {
                return Err(bad(format!(
                    "the plane needs a finite point and a non-zero finite normal, got point {point:?}, normal {normal:?}"
                )));
            }
            Ok(CheckedTarget::Plane {
                point: p,
                normal: n.normalize(),
            })
        }
    }
}

/// Distance from the boundary of `mesh` named by `spec` to the target.
fn distance(mesh: &MultiPatch, spec: &FitSpec, target: &CheckedTarget, scale: f64) -> Distance {
    let line = mesh.boundary(spec.boundary.patch, spec.boundary.side);
    let d: Vec<f64> = line
        .iter()
        .map(|&p| match target {
            CheckedTarget::Polyline(t) => t
                .windows(2)
                .map(|w| point_segment(p, w[0], w[1]))
                .fold(f64::INFINITY, f64::min),
            CheckedTarget::Plane { point, normal } => (p - *point).dot(*normal).abs(),
        })
        .collect();
    let max = d.iter().copied().fold(0.0, f64::max);
    let rms = (d.iter().map(|x| x * x).sum::<f64>() / d.len() as f64).sqrt();
    let size = mesh.grid.bbox_diagonal();
    Distance {
        max,
        rms,
        relative: max / if size > 0.0 { size } else { scale },
    }
}

/// The guide spec a control-point parameter refers to, if the patch has it.
fn guide_of(design: &MultiPatchDesign, patch: usize, key: GuideKey) -> Option<&GuideSpec> {
    let p = design.patches.get(patch)?;
    match key {
        GuideKey::GuideU => p.guide_u.as_ref(),
        GuideKey::GuideV => p.guide_v.as_ref(),
        GuideKey::Guide => p.guide.as_ref(),
    }
}

/// The editable point list of a guide: `points` or `bspline.control_points`.
fn point_list(g: &GuideSpec) -> Option<&Vec<Xyz>> {
    match g {
        GuideSpec::Points { points, .. } => Some(points),
        GuideSpec::BSpline { bspline, .. } => Some(&bspline.control_points),
        GuideSpec::Arc(_) | GuideSpec::Parabola(_) => None,
    }
}

/// [`point_list`], to edit.
fn point_list_mut(g: &mut GuideSpec) -> Option<&mut Vec<Xyz>> {
    match g {
        GuideSpec::Points { points, .. } => Some(points),
        GuideSpec::BSpline { bspline, .. } => Some(&mut bspline.control_points),
        GuideSpec::Arc(_) | GuideSpec::Parabola(_) => None,
    }
}

/// The start value of a parameter, checking that it exists.
fn read_value(design: &MultiPatchDesign, index: usize, p: &FreeParameter) -> Result<f64, FitError> {
    let bad = |problem: String| FitError::BadParameter {
        index,
        name: p.name(),
        problem,
    };
    let count = design.patches.len();
    match p {
        FreeParameter::Theta { patch, .. } => design
            .patches
            .get(*patch)
            .map(|s| s.theta_deg)
            .ok_or_else(|| {
                bad(format!(
                    "there is no patch {patch} (the design has {count})"
                ))
            }),
        FreeParameter::ControlPoint {
            patch,
            guide,
            index: point,
            coordinate,
            ..
        } => {
            if *patch >= count {
                return Err(bad(format!(
                    "there is no patch {patch} (the design has {count})"
                )));
            }
            let g = guide_of(design, *patch, *guide)
                .ok_or_else(|| bad(format!("patch {patch} has no such guide")))?;
            let list = point_list(g).ok_or_else(|| {
                bad("only `points` and `bspline` guides have points to move".to_owned())
            })?;
            if *coordinate > 2 {
                return Err(bad(format!(
                    "coordinate {coordinate}: give 0, 1 or 2 (x, y, z)"
                )));
            }
            list.get(*point).map(|q| q[*coordinate]).ok_or_else(|| {
                bad(format!(
                    "point {point} does not exist (the guide has {})",
                    list.len()
                ))
            })
        }
    }
}

/// The box of a parameter (see the module docs).
fn parameter_bounds(
    mesh: &MultiPatch,
    index: usize,
    p: &FreeParameter,
    value: f64,
) -> Result<[f64; 2], FitError> {
    let name = p.name();
    let check = |b: [f64; 2]| -> Result<[f64; 2], FitError> {
        if b.iter().all(|x| x.is_finite()) && b[0] <= b[1] {
            Ok(b)
        } else {
            Err(FitError::BadParameter {
                index,
                name: name.clone(),
                problem: format!("bounds {b:?} must be finite and ordered [low, high]"),
            })
        }
    };
    let (admissible, requested) = match p {
        FreeParameter::Theta { patch, bounds } => {
            let range = mesh.patches[*patch].theta_range;
            let theta = crate::gauss_map::normalize_theta_deg(value);
            let (mut lo, mut hi) = if range.min_deg <= 1e-9 {
                (-range.max_deg, range.max_deg)
            } else if theta >= 0.0 {
                (range.min_deg, range.max_deg)
            } else {
                (-range.max_deg, -range.min_deg)
            };
            let margin = SINGULAR_MARGIN_DEG.max(SINGULAR_WINDOW_DEG);
            if lo < 90.0 + margin && hi > 90.0 - margin {
                if theta < 90.0 {
                    hi = hi.min(90.0 - margin);
                } else {
                    lo = lo.max(90.0 + margin);
                }
            }
            let requested = check(bounds.unwrap_or([lo, hi]))?;
            ([lo, hi], requested)
        }
        FreeParameter::ControlPoint { bounds, .. } => {
            let b = check(*bounds)?;
            (b, b)
        }
    };
    let lo = admissible[0].max(requested[0]);
    let hi = admissible[1].min(requested[1]);
    // BOBYQA needs room for its first steps; an interval narrower than this is a pinned value.
    if hi - lo <= 1e-9 * (1.0 + lo.abs().max(hi.abs())) {
        return Err(FitError::EmptyBounds {
            index,
            name,
            admissible,
            requested,
            margin: SINGULAR_MARGIN_DEG,
        });
    }
    Ok([lo, hi])
}

/// A copy of `design` with the free parameters set to `values`.
fn with_values(
    design: &MultiPatchDesign,
    free: &[FreeParameter],
    values: &[f64],
) -> MultiPatchDesign {
    let mut d = design.clone();
    for (p, &v) in free.iter().zip(values) {
        match p {
            FreeParameter::Theta { patch, .. } => d.patches[*patch].theta_deg = v,
            FreeParameter::ControlPoint {
                patch,
                guide,
                index,
                coordinate,
                ..
            } => {
                let spec = &mut d.patches[*patch];
                let g = match guide {
                    GuideKey::GuideU => spec.guide_u.as_mut(),
                    GuideKey::GuideV => spec.guide_v.as_mut(),
                    GuideKey::Guide => spec.guide.as_mut(),
                };
                if let Some(g) = g {
                    let list = point_list_mut(g);
                    if let Some(q) = list.and_then(|l| l.get_mut(*index)) {
                        q[*coordinate] = v;
                    }
                }
            }
        }
    }
    d
}

/// A BOBYQA solver over `n ≥ 1` variables scaled to [0, 1] (trust region from
/// 0.1 down to `rho_end`), allowed `max_fun` evaluations; `Err(needed)` when
/// `max_fun` is below the `2n + 2` BOBYQA needs to start.
pub(crate) fn solver(n: usize, rho_end: f64, max_fun: usize) -> Result<bobyqa::Bobyqa, usize> {
    let mut config = bobyqa::Config::new(n);
    config.rho_begin = 0.1;
    config.rho_end = rho_end;
    config.max_fun = max_fun;
    if config.max_fun <= config.npt {
        return Err(config.npt + 1);
    }
    // Valid by construction: n ≥ 1, npt = 2n + 1, 0 < rho_end ≤ rho_begin, max_fun > npt.
    Ok(bobyqa::Bobyqa::new(n, config).expect("a valid BOBYQA configuration"))
}
