//! A tolerance in, a design out (monge's extension; the patches are §4.7's
//! piecewise planar curvature lines): [`approximate_to_tolerance`] fits one patch,
//! then more patches ([`refinements`]: 2 × 1, 2 × 2, 3 × 2, …), until the mesh is within the tolerance of the target both
//! ways (the largest distances, mesh → target and target → mesh), or says why it
//! stopped short ([`Stop`]): the patch budget, the time limit, patches that cannot be
//! fitted, or a scan's edge that its points cannot place. It never returns a design
//! farther from the target than the best one it saw, the initial guess included (on a
//! scan, as far as its points tell its edge). What a designer looks at in the result is
//! [`super::report`]'s.

use std::str::FromStr;
use std::time::Instant;

use glam::DVec3;

use crate::design::Design;
use crate::generate::GenerateError;
use crate::grid::QuadGrid;
use crate::multipatch::{MultiPatchDesign, MultiPatchError};

use super::patches::patches_of;
use super::trim::{resolved, TrimmedMesh};
use super::{
    approximate_target, check_faces, fair_mesh, ApproxError, ApproxOptions, Approximation,
    Deviation, PatchLayout, Progress, TargetCloud,
};

/// How close the result must come to the target, both ways.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Tolerance {
    /// A fraction of the target's size (its bounding-box diagonal), below 1.
    Relative(f64),
    /// A length in model units.
    Length(f64),
}

/// The units a length tolerance may be written in, and their lengths in model units:
/// the target's coordinates are taken as metres.
pub const LENGTH_UNITS: [(&str, f64); 3] = [("m", 1.0), ("cm", 0.01), ("mm", 0.001)];

impl Tolerance {
    /// The tolerance as a fraction of a target of `size`.
    pub fn relative_to(&self, size: f64) -> f64 {
        match *self {
            Tolerance::Relative(r) => r,
            Tolerance::Length(l) => l / size,
        }
    }
}

impl FromStr for Tolerance {
    type Err = ToleranceError;

    /// A number alone is relative to the target's size (`5e-3`); a number and a unit
    /// of [`LENGTH_UNITS`] is a length (`0.05m`, `5cm`, `50mm`).
    ///
    /// ```
    /// use monge_core::approximate::{Tolerance, ToleranceError};
    /// assert_eq!("5e-3".parse(), Ok(Tolerance::Relative(5e-3)));
    /// assert_eq!("5cm".parse::<Tolerance>().unwrap(), Tolerance::Length(0.05));
    /// assert!(matches!("-1".parse::<Tolerance>(), Err(ToleranceError::NotPositive { .. })));
    /// assert!(matches!("0.05parsecs".parse::<Tolerance>(), Err(ToleranceError::UnknownUnit { .. })));
    /// ```
    fn from_str(text: &str) -> Result<Self, ToleranceError> {
        let trimmed = text.trim();
        let number_end = trimmed
            .char_indices()
            .rev()
            .take_while(|(_, c)| c.is_alphabetic())
            .last()
            .map_or(trimmed.len(), |(k, _)| k);
        let (number, unit) = trimmed.split_at(number_end);
        let value: f64 = number
            .trim()
            .parse()
            .map_err(|_| ToleranceError::NotANumber {
                text: text.to_owned(),
            })?;
        if !(value > 0.0 && value.is_finite()) {
            return Err(ToleranceError::NotPositive {
                text: text.to_owned(),
            });
        }
        if unit.is_empty() {
            return if value < 1.0 {
                Ok(Tolerance::Relative(value))
            } else {
                Err(ToleranceError::RelativeTooLarge { value })
            };
        }
        LENGTH_UNITS
            .iter()
            .find(|(name, _)| *name == unit)
            .map(|(_, metres)| Tolerance::Length(value * metres))
            .ok_or_else(|| ToleranceError::UnknownUnit {
                text: text.to_owned(),
                unit: unit.to_owned(),
            })
    }
}

/// Why a tolerance fit cannot start, or its result cannot be measured.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum ToleranceError {
    /// The tolerance is not a number (with or without a unit).
    #[error(
        "`{text}` is not a tolerance: give a number relative to the target's size (e.g. 5e-3) \
         or a length with its unit (e.g. 0.05m, 5cm, 50mm)"
    )]
    NotANumber {
        /// The text given.
        text: String,
    },
    /// The tolerance's unit is not one of [`LENGTH_UNITS`].
    #[error(
        "`{text}`: unknown unit `{unit}`; give a length in m, cm or mm (the target's \
         coordinates taken as metres), or a number without a unit, relative to the target's \
         size (e.g. 5e-3)"
    )]
    UnknownUnit {
        /// The text given.
        text: String,
        /// Its unit.
        unit: String,
    },
    /// The tolerance is zero, negative, NaN or infinite.
    #[error("a tolerance of `{text}`: give a positive, finite number (e.g. 5e-3 or 0.05m)")]
    NotPositive {
        /// The text given.
        text: String,
    },
    /// A relative tolerance of 1 or more: any design is within it.
    #[error(
        "a relative tolerance of {value} is {value} times the target's size, which any design \
         meets: give a fraction of the size below 1 (e.g. 5e-3), or a length with its unit \
         (e.g. {value}m)"
    )]
    RelativeTooLarge {
        /// The number given.
        value: f64,
    },
    /// No patch at all: [`ToleranceOptions::max_patches`] is 0.
    #[error("at most 0 patches: allow at least 1")]
    NoPatches,
    /// The first patch cannot be fitted.
    #[error(transparent)]
    Approx(#[from] ApproxError),
    /// The design found cannot be generated again (for its report).
    #[error("the design found: {0}")]
    Generate(#[from] GenerateError),
    /// The multi-patch design found cannot be built again (for its report).
    #[error("the multi-patch design found: {0}")]
    MultiPatch(#[from] MultiPatchError),
}

/// Options of [`approximate_to_tolerance`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ToleranceOptions {
    /// The tolerance, both ways (default 5e-3 of the target's size).
    pub tolerance: Tolerance,
    /// The most patches tried (default 6); 1 fits one patch only.
    pub max_patches: usize,
    /// The options of each fit; its deadline ends the whole search (checked between
    /// the fits, and during the first).
    pub approx: ApproxOptions,
}

impl Default for ToleranceOptions {
    fn default() -> Self {
        ToleranceOptions {
            tolerance: Tolerance::Relative(5e-3),
            max_patches: 6,
            approx: ApproxOptions::default(),
        }
    }
}

/// What [`approximate_to_tolerance`] reports while it runs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ToleranceProgress {
    /// Patches of the fit under way.
    pub patches: usize,
    /// Meshes generated so far, over all the fits.
    pub evaluations: usize,
    /// The fit under way.
    pub search: Progress,
    /// Largest distance both ways of the best design so far, relative to the target's
    /// size (infinite before the first fit ends).
    pub best_max: f64,
}

/// Why [`approximate_to_tolerance`] stopped.
#[derive(Clone, Debug, PartialEq)]
pub enum Stop {
    /// The result is within the tolerance both ways.
    Met,
    /// Not within it with [`ToleranceOptions::max_patches`] patches.
    MaxPatches(usize),
    /// The deadline ([`ApproxOptions::deadline`]) came first.
    TimeLimit,
    /// The target is a scan, and the result within the tolerance as far as its points
    /// tell ([`TargetCloud::resolved`]): every point of it near the mesh, every vertex
    /// near it across its surface, but the mesh's edge read beyond the scan's outermost
    /// points by more than the tolerance, which such a reading may overstate by up to
    /// `overread` (relative to the target's size, [`TargetCloud::edge_overread`]). More
    /// patches would only move the edge the points cannot place.
    ScanEdge {
        /// How much the reading of the edge may overstate, relative to the size.
        overread: f64,
    },
    /// This many patches cannot be fitted, nor any more (a grid too coarse for them, a
    /// conical mesh).
    Refused {
        /// Patches asked for.
        patches: usize,
        /// Why.
        error: ApproxError,
    },
}

impl Stop {
    /// Why the result is not certified within the tolerance where the search stopped at
    /// a scan's edge ([`Stop::ScanEdge`]; `None` for the other stops, which each front
    /// end words with its own option names), for a target of size `size`.
    ///
    /// ```
    /// use monge_core::approximate::Stop;
    /// let why = Stop::ScanEdge { overread: 0.02 }.scan_edge_reason(10.0).unwrap();
    /// assert!(why.contains("0.200 model units"));
    /// assert_eq!(Stop::Met.scan_edge_reason(10.0), None);
    /// ```
    pub fn scan_edge_reason(&self, size: f64) -> Option<String> {
        let Stop::ScanEdge { overread } = self else {
            return None;
        };
        Some(format!(
            "the target is a scan: every point of it is within the tolerance of the mesh, \
             and every vertex across its surface; only the mesh's edge reads farther beyond \
             the scan's outermost points, a reading that overstates by up to {:.3} model units \
             at nine corners in ten ({:.1e} of the size: {} mean spacings of its points, as \
             a random sampling leaves the target's corners bare), so the edge is within only \
             if the reading overstates; more patches would only move an edge the points \
             cannot place. A denser scan reads its edge closer",
            overread * size,
            overread,
            super::SCAN_EDGE_OVERREAD,
        ))
    }
}

/// One fit of [`approximate_to_tolerance`]: its patches and its deviation, or why it
/// failed.
#[derive(Clone, Debug, PartialEq)]
pub struct Step {
    /// Patches of the fit.
    pub patches: usize,
    /// Whether its mesh covers the target and is trimmed to its outline.
    pub trimmed: bool,
    /// Its deviation, or why it could not be fitted.
    pub outcome: Result<Deviation, ApproxError>,
    /// Its largest distance both ways as far as the target's points tell its edge
    /// ([`TargetCloud::resolved`]), by which the fits are compared: its deviation's on a
    /// mesh's vertices; NaN where it could not be fitted.
    pub resolved: f64,
}

impl Step {
    /// The step of the fit `seen` of `patches` patches, trimmed or not.
    fn of(seen: &Seen, patches: usize, trimmed: bool) -> Self {
        Step {
            patches,
            trimmed,
            outcome: Ok(seen.deviation),
            resolved: seen.resolved.max(),
        }
    }

    /// The step of a fit of `patches` patches that failed with `error`.
    fn failed(patches: usize, trimmed: bool, error: ApproxError) -> Self {
        Step {
            patches,
            trimmed,
            outcome: Err(error),
            resolved: f64::NAN,
        }
    }
}

/// The design of a fit: one patch, or several (§4.7).
#[derive(Clone, Debug, PartialEq)]
pub enum FitDesign {
    /// One design (`monge generate` reads it).
    Single(Design),
    /// A multi-patch design (`monge patches` reads it).
    Patches(MultiPatchDesign),
    /// One design whose mesh covers the target, and that mesh trimmed to the target's
    /// outline ([`ApproxOptions::trim`]): the trimmed mesh is the result.
    Trimmed(Design, TrimmedMesh),
    /// A multi-patch design whose mesh covers the target, and that mesh trimmed to the
    /// target's outline: the trimmed mesh is the result.
    TrimmedPatches(MultiPatchDesign, TrimmedMesh),
}

impl FitDesign {
    /// Its patches.
    pub fn patches(&self) -> usize {
        match self {
            FitDesign::Single(_) | FitDesign::Trimmed(..) => 1,
            FitDesign::Patches(d) | FitDesign::TrimmedPatches(d, _) => d.patches.len(),
        }
    }

    /// Its mesh trimmed to the target's outline, the result, where it is trimmed.
    pub fn trimmed(&self) -> Option<&TrimmedMesh> {
        match self {
            FitDesign::Trimmed(_, mesh) | FitDesign::TrimmedPatches(_, mesh) => Some(mesh),
            FitDesign::Single(_) | FitDesign::Patches(_) => None,
        }
    }
}

/// Which design [`approximate_to_tolerance`] kept.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Chosen {
    /// The initial guess of the one-patch fit, nearer than every fit.
    InitialGuess,
    /// The one-patch fit.
    OnePatch,
    /// The one-patch fit that covers the target, trimmed to its outline.
    Trimmed,
    /// The fit of this many patches.
    Patches(usize),
    /// The fit of this many patches that cover the target, trimmed to its outline.
    TrimmedPatches(usize),
}

/// The result of [`approximate_to_tolerance`].
#[derive(Clone, Debug)]
pub struct ToleranceFit {
    /// The design kept: the nearest to the target of all seen (largest distance both
    /// ways), the fewest patches among equals.
    pub design: FitDesign,
    /// Its mesh (the patches merged).
    pub grid: QuadGrid,
    /// Its deviation.
    pub deviation: Deviation,
    /// Its deviation as far as the target's points tell its edge
    /// ([`TargetCloud::resolved`]), by which the designs were compared.
    pub resolved: Deviation,
    /// Which design it is.
    pub chosen: Chosen,
    /// The tolerance, relative to the target's size.
    pub limit: f64,
    /// Why the search stopped.
    pub stop: Stop,
    /// The one-patch fit (its initial guess, its result).
    pub single: Approximation,
    /// Every fit, one patch first.
    pub steps: Vec<Step>,
    /// Meshes generated in all.
    pub evaluations: usize,
}

impl ToleranceFit {
    /// Whether the design is within the tolerance both ways.
    pub fn met(&self) -> bool {
        self.deviation.max() <= self.limit
    }

    /// Whether the last layout of several patches fitted ([`ToleranceFit::last_layout`])
    /// came nearer to the target than the designs of fewer patches (one patch, trimmed or
    /// not, and the layouts before it) by more than [`PATCHES_GAIN`] of their largest
    /// distance both ways; `None` where no layout of several patches was fitted. Where it
    /// did not, more patches are unlikely to bring the fit within the tolerance: on a roof
    /// that one grid of curvature lines does not follow, two patches may come nearer than
    /// one, and four or six no nearer than two.
    pub fn patches_helped(&self) -> Option<bool> {
        let last = self.last_layout()?;
        let nearest = |wanted: &dyn Fn(usize) -> bool| {
            self.steps
                .iter()
                .filter(|s| wanted(s.patches) && s.outcome.is_ok())
                .map(|s| s.resolved)
                .fold(f64::INFINITY, f64::min)
        };
        let (fewer, most) = (nearest(&|p| p < last), nearest(&|p| p == last));
        Some(most < (1.0 - PATCHES_GAIN) * fewer)
    }

    /// The most patches of a layout fitted (the last tried), or `None` where no layout of
    /// several patches was fitted.
    pub fn last_layout(&self) -> Option<usize> {
        self.steps
            .iter()
            .filter(|s| s.patches > 1 && s.outcome.is_ok())
            .map(|s| s.patches)
            .max()
    }
}

/// The share of the largest distance of fewer patches by which the last layout must come
/// nearer for [`ToleranceFit::patches_helped`]. Measured on the free-form held-out roofs,
/// two to six patches came 0 to 5 % nearer than one on domes with flat edges and saddle
/// corners, whose shape one grid of curvature lines does not follow; 16 % on a Bézier
/// roof and about 55 % on a paraboloid and a hyperbolic paraboloid (all trimmed).
pub const PATCHES_GAIN: f64 = 0.1;

/// The layouts tried after one patch, each refining the last along the direction
/// with fewer patches: 2 × 1, 2 × 2, 3 × 2, 3 × 3, … while they have at most
/// `max_patches` patches.
///
/// ```
/// use monge_core::approximate::{refinements, PatchLayout};
/// let tried: Vec<String> = refinements(6).map(|l| l.to_string()).collect();
/// assert_eq!(tried, ["2x1", "2x2", "3x2"]);
/// ```
pub fn refinements(max_patches: usize) -> impl Iterator<Item = PatchLayout> {
    std::iter::successors(Some(PatchLayout { u: 1, v: 1 }), |l| {
        Some(if l.u <= l.v {
            PatchLayout { u: l.u + 1, v: l.v }
        } else {
            PatchLayout { u: l.u, v: l.v + 1 }
        })
    })
    .skip(1)
    .take_while(move |l| l.count() <= max_patches)
}

/// The fit of `layout` from the one-patch fit `single`: the one call of
/// [`approximate_patches`](super::approximate_patches).
fn fit_patches(
    target: &TargetCloud,
    single: &Approximation,
    layout: PatchLayout,
    options: &ApproxOptions,
    progress: &mut dyn FnMut(&Progress),
) -> Result<(FitDesign, QuadGrid, Deviation, usize), ApproxError> {
    let p = patches_of(target, single, layout, options, progress)?;
    let design = match p.trimmed {
        Some(mesh) => FitDesign::TrimmedPatches(p.design, mesh),
        None => FitDesign::Patches(p.design),
    };
    Ok((design, p.grid, p.after, p.evaluations))
}

/// A design seen, its mesh, its deviation and its deviation as far as the target's
/// points tell ([`TargetCloud::resolved`]), by which designs are compared.
struct Seen {
    design: FitDesign,
    grid: QuadGrid,
    deviation: Deviation,
    resolved: Deviation,
    chosen: Chosen,
}

impl Seen {
    /// `design`, of mesh `grid` and deviation `deviation` from `target`.
    fn new(
        target: &TargetCloud,
        design: FitDesign,
        grid: QuadGrid,
        deviation: Deviation,
        chosen: Chosen,
    ) -> Self {
        let resolved = resolved(target, &deviation, &grid, design.trimmed());
        Seen {
            design,
            grid,
            deviation,
            resolved,
            chosen,
        }
    }
}

/// The design nearest to a target within `options.tolerance` both ways: one patch
/// ([`super::approximate`]), then (where the target's outline can be traced) one patch
/// that covers it, trimmed to its outline ([`ApproxOptions::trim`]: a target whose
/// edges are not curvature lines), then the layouts of [`refinements`] of up to
/// [`ToleranceOptions::max_patches`] patches
/// ([`approximate_patches`](super::approximate_patches): the nearer of the one-patch
/// results cut into blocks from its middle, every free guide and θ free, §4.7; from the
/// trimmed one, they cover the target and are trimmed too), until one is within the
/// tolerance. The result is the nearest design seen (largest distance both ways; the
/// initial guess included; on a scan, as far as its points tell its edge,
/// [`TargetCloud::resolved`]), whether or not within the tolerance
/// ([`ToleranceFit::met`], [`ToleranceFit::stop`]). `progress` is called after every
/// mesh generated.
///
/// Errors: the tolerance and patch budget ([`ToleranceError`]), and whatever keeps
/// the first patch from being fitted ([`ApproxError`]: an umbilic, a flat target, …).
///
/// ```
/// use glam::DVec3;
/// use monge_core::approximate::{approximate_to_tolerance, ApproxOptions, Stop, Tolerance, ToleranceOptions};
/// // A paraboloid, which has no planar curvature lines.
/// let target: Vec<DVec3> = (0..121)
///     .map(|k| {
///         let (x, y) = ((k % 11) as f64, (k / 11) as f64);
///         DVec3::new(x, y, 0.04 * x * x + 0.1 * y * y)
///     })
///     .collect();
/// let approx = ApproxOptions { faces: (8, 8), starts: 1, max_evaluations: 40, ..Default::default() };
/// let options = ToleranceOptions { tolerance: Tolerance::Relative(1e-6), max_patches: 2, approx };
/// let fit = approximate_to_tolerance(&target, &options, &mut |_| {}).unwrap();
/// assert!(!fit.met());
/// assert_eq!(fit.stop, Stop::MaxPatches(2));
/// assert!(fit.deviation.max() <= fit.single.after.max());
/// ```
pub fn approximate_to_tolerance(
    points: &[DVec3],
    options: &ToleranceOptions,
    progress: &mut dyn FnMut(&ToleranceProgress),
) -> Result<ToleranceFit, ToleranceError> {
    if options.max_patches == 0 {
        return Err(ToleranceError::NoPatches);
    }
    check_faces(&options.approx)?;
    let target = TargetCloud::new(points)?;
    let never = || false;
    let mut done = 0;
    let mut best_max = f64::INFINITY;
    let single = approximate_target(&target, &options.approx, &never, &mut |p| {
        progress(&ToleranceProgress {
            patches: 1,
            evaluations: p.evaluations,
            search: *p,
            best_max,
        });
    })?;
    done += single.evaluations;
    let limit = options.tolerance.relative_to(single.after.size);
    let mut best = Seen::new(
        &target,
        FitDesign::Single(single.design.clone()),
        single.grid.clone(),
        single.after,
        Chosen::OnePatch,
    );
    let mut steps = vec![Step::of(&best, 1, false)];
    // The initial guess as it is (never trimmed).
    if let Some(grid) = fair_mesh(&single.initial, None) {
        let initial = Seen::new(
            &target,
            FitDesign::Single(single.initial.clone()),
            grid,
            single.before,
            Chosen::InitialGuess,
        );
        if initial.resolved.closer_than(&best.resolved) {
            best = initial;
        }
    }
    best_max = best.resolved.max();
    let past_deadline = || options.approx.deadline.is_some_and(|d| Instant::now() >= d);
    // One patch covering the target, trimmed to its outline, where one patch does not
    // meet the tolerance and the outline can be traced; the patches then refine the
    // nearer of the two (and are trimmed where it is).
    let mut nearer: Option<Approximation> = None;
    if best_max > limit && !single.timed_out && !options.approx.trim {
        let trim = ApproxOptions {
            trim: true,
            ..options.approx
        };
        let fit = approximate_target(&target, &trim, &never, &mut |p| {
            progress(&ToleranceProgress {
                patches: 1,
                evaluations: done + p.evaluations,
                search: *p,
                best_max,
            });
        });
        match fit {
            Ok(t) => {
                done += t.evaluations;
                let design = match &t.trimmed {
                    Some(mesh) => FitDesign::Trimmed(t.design.clone(), mesh.clone()),
                    None => FitDesign::Single(t.design.clone()),
                };
                let seen = Seen::new(&target, design, t.grid.clone(), t.after, Chosen::Trimmed);
                steps.push(Step::of(&seen, 1, true));
                if t.trimmed.is_some() && seen.resolved.closer_than(&best.resolved) {
                    best_max = seen.resolved.max();
                    best = seen;
                }
                if t.after.closer_than(&single.after) {
                    nearer = Some(t);
                }
            }
            Err(error) => steps.push(Step::failed(1, true, error)),
        }
    }
    let mut stop = Stop::MaxPatches(options.max_patches);
    if best_max <= limit {
        stop = within(&best, limit, &target);
    } else if single.timed_out || past_deadline() {
        stop = Stop::TimeLimit;
    } else {
        for layout in refinements(options.max_patches) {
            let patches = layout.count();
            if past_deadline() {
                stop = Stop::TimeLimit;
                break;
            }
            let from = nearer.as_ref().unwrap_or(&single);
            let fit = fit_patches(&target, from, layout, &options.approx, &mut |p| {
                progress(&ToleranceProgress {
                    patches,
                    evaluations: done + p.evaluations,
                    search: *p,
                    best_max,
                });
            });
            match fit {
                Ok((design, grid, deviation, evaluations)) => {
                    done += evaluations;
                    let trimmed = design.trimmed().is_some();
                    let chosen = if trimmed {
                        Chosen::TrimmedPatches(patches)
                    } else {
                        Chosen::Patches(patches)
                    };
                    let seen = Seen::new(&target, design, grid, deviation, chosen);
                    steps.push(Step::of(&seen, patches, trimmed));
                    if seen.resolved.closer_than(&best.resolved) {
                        best_max = seen.resolved.max();
                        best = seen;
                    }
                    if best_max <= limit {
                        stop = within(&best, limit, &target);
                        break;
                    }
                }
                // No more patches can help: a grid too coarse for them, a conical mesh.
                Err(
                    error @ (ApproxError::TooManyPatches { .. } | ApproxError::PatchesNotCircular),
                ) => {
                    stop = Stop::Refused { patches, error };
                    break;
                }
                Err(error) => steps.push(Step::failed(patches, nearer.is_some(), error)),
            }
        }
    }
    Ok(ToleranceFit {
        design: best.design,
        grid: best.grid,
        deviation: best.deviation,
        resolved: best.resolved,
        chosen: best.chosen,
        limit,
        stop,
        single,
        steps,
        evaluations: done,
    })
}

/// Why the search stops at `best`, within the tolerance `limit` as far as the target's
/// points tell: met, or only at a scan's edge ([`Stop::ScanEdge`]).
fn within(best: &Seen, limit: f64, target: &TargetCloud) -> Stop {
    if best.deviation.max() <= limit {
        Stop::Met
    } else {
        Stop::ScanEdge {
            overread: target.edge_overread(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn patches_help_when_the_last_layout_comes_a_tenth_nearer_than_fewer_patches() {
        let target: Vec<DVec3> = (0..121)
            .map(|k| {
                let (x, y) = ((k % 11) as f64, (k / 11) as f64);
                DVec3::new(x, y, 0.04 * x * x + 0.1 * y * y)
            })
            .collect();
        let approx = ApproxOptions {
            faces: (4, 4),
            starts: 1,
            max_evaluations: 40,
            ..Default::default()
        };
        let options = ToleranceOptions {
            tolerance: Tolerance::Relative(1.0),
            max_patches: 1,
            approx,
        };
        let mut fit = approximate_to_tolerance(&target, &options, &mut |_| {}).unwrap();
        let step = |patches: usize, trimmed: bool, max: f64| Step {
            patches,
            trimmed,
            outcome: Ok(Deviation {
                mesh_to_target_max: max,
                target_to_mesh_max: 0.5 * max,
                ..fit.deviation
            }),
            resolved: max,
        };
        fit.steps = vec![step(1, false, 0.02), step(1, true, 0.018)];
        assert_eq!(fit.patches_helped(), None);
        // Against the trimmed patch, the nearer of the two: 0.017 is 5.6 % nearer.
        fit.steps.push(step(2, false, 0.017));
        assert_eq!(fit.patches_helped(), Some(false));
        assert_eq!(fit.last_layout(), Some(2));
        // The last layout against the nearest with fewer patches (0.017): 0.016 is 5.9 %
        // nearer, 0.015 11.8 %.
        fit.steps.push(step(4, false, 0.016));
        assert_eq!(fit.patches_helped(), Some(false));
        fit.steps.pop();
        fit.steps.push(step(4, false, 0.015));
        assert_eq!(fit.patches_helped(), Some(true));
        // Six patches no nearer than four: more are unlikely to help, though four did.
        fit.steps.push(step(6, false, 0.0149));
        assert_eq!(fit.last_layout(), Some(6));
        assert_eq!(fit.patches_helped(), Some(false));
        // A layout that could not be fitted is not the last one.
        fit.steps
            .push(Step::failed(9, false, ApproxError::PatchesNotCircular));
        assert_eq!(fit.last_layout(), Some(6));
        fit.steps.truncate(2);
        fit.steps
            .push(Step::failed(2, false, ApproxError::PatchesNotCircular));
        assert_eq!(fit.patches_helped(), None);
    }
}
