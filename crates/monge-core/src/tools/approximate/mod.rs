//! Approximating a target shape by one surface with planar curvature lines: monge's
//! extension of the method. The paper is bottom-up (two guides and θ give the mesh,
//! §3); fitting a design to a target is related to its fit of a patch boundary to a
//! target curve (§4.7, BOBYQA) and to its optimisation of the guides' sampling
//! (§4.8), but choosing the whole design to follow a given surface is not in it.
//!
//! Given the points of a target (a mesh's vertices or a point cloud), [`approximate`]
//! finds the design — a corner, two planar guides starting there at 90°, θ — whose
//! exactly generated mesh is nearest to the target both ways:
//!
//! 1. **initial guess**: a quadric fitted to the whole target gives its principal
//!    directions at its centre (where the centre is umbilic, a dome of revolution or a
//!    spherical cap, the sides of the smallest rectangle enclosing the target's plan
//!    instead; a flat centre is refused: [`ApproxError::Flat`]) and, along them, the
//!    corners of the target; a quadric fitted near a corner gives the principal
//!    directions there, and each guide is a cubic B-spline (5 control points) in the
//!    normal plane of one direction, fitted to the target's section by that plane (not
//!    at an umbilic corner, where they are undefined). A second start at each corner
//!    follows the target's own boundary: at its corner (the boundary point lowest along
//!    the centre's directions whose neighbours fill a sector of at most 135°: the
//!    lowest point of all may be halfway up a side that bulges out), the two boundary
//!    curves leaving it along that sector's edges are
//!    traced through the points (gift wrapping), a plane is fitted to each, a B-spline to
//!    each in its plane (Levenberg–Marquardt over the control points and the points'
//!    parameters), and their start tangents, made orthogonal, give the frame: a target
//!    cut along its curvature lines is started from its own guides; and again with
//!    each B-spline at its points' chord lengths and each tangent the slope of the cubic
//!    nearest to the whole curve, which a scan's zigzag boundary does not tie into
//!    loops. Where those fold at every θ (a random sampling's outermost point far out to
//!    one side turned the path off the boundary), the boundary is traced again, each
//!    step ahead along the chord of the last three. A third follows the
//!    target's curvature lines (each step on the quadric of the nearest target points):
//!    from the centre to the boundary and along it to the corner, then the two lines
//!    leaving the corner are the curves of the boundary start's construction, their
//!    planes tilted as the target's are (a moulding's level rail). Where the target's
//!    centre is elliptic, a fourth lies on the quadric fitted to the whole target, at
//!    its point nearest to the corner, its frame along the centre's directions and its
//!    guides the quadric's sections along them: a dome whose edges lie flat (its corners
//!    saddles, their principal directions along the diagonals) is started along its
//!    edges. Only a target with no start at all is refused ([`ApproxError::Umbilic`]).
//!    θ comes from a scan every 10° of the angle φ around the circle of the admissible
//!    θ ([`crate::gauss_map::admissible_theta_at`]): where a guide plane is tilted, θ =
//!    0° or 180° (the surfaces of revolution and the mouldings, §4.1) is an end of the
//!    admissible range, which φ = 0° or 180° reaches and the search crosses smoothly;
//! 2. **optimisation** by least squares (Levenberg–Marquardt with Marquardt's diagonal
//!    damping) of the corner, the frame's rotation, the tilt of each guide plane about
//!    its start tangent, φ and the control points' coordinates in their planes (the
//!    second control point only along the start tangent, ahead of the corner, so the
//!    guides stay planar and meet at 90° exactly), from the best θ of the scan at each
//!    corner (whichever of its starts gives it) and the next best ones in turn until one
//!    recovers the target (multi-start), first on a
//!    grid of half the resolution, then on the full grid. The Jacobian is taken by
//!    forward differences, its columns in parallel, against the spatial matches of the
//!    current mesh (which target point is nearest to each vertex, which face to each
//!    target point), so its columns cost one mesh generation each and no search. Where
//!    the least squares stall away from the target from every start, they run again
//!    from each of their results with θ moved to the best two of a scan every 10° (the
//!    other parameters kept): they settle in the basin of their θ, which the scan
//!    leaves (not for a mesh to be trimmed, whose least squares were not tried so).
//!    Designs that cannot be generated or whose mesh folds
//!    ([`QuadGrid::folds`], §5.2; a mesh to be trimmed, where the trimming keeps it)
//!    are infeasible. The least squares then run again with
//!    finer guides (knot insertion: 7, then 11 control points, the same curves), kept
//!    only when closer to the target by the largest distance both ways: five control
//!    points may not follow a profile with an inflection as closely as the rest of the
//!    design can. Where θ ends within 5° of 0° or 180°, the nearest surface of
//!    revolution or moulding surface (§4.1: θ at that end of its range) is kept if its
//!    objective is within 1.5 times the free design's: there θ moves by degrees for a
//!    small gain, with a scan's noise. The result is the best of the designs refined on
//!    the full grid and the initial guess, so it is never worse than where the search
//!    started;
//! 3. the objective (`TargetCloud::residuals`) is the mean squared distance of the
//!    mesh's vertices to the target (to the quadric fitted around the nearest target
//!    point, so that a random sampling's spacing does not bias it by `κd²/2`, moved
//!    through that point by the share of its height that is not noise; plus a
//!    guard against a vertex overhanging the target's boundary by several spacings, ten
//!    on a scan, whose true corners lie bare),
//!    plus that of the mesh's edges: each side of the mesh is fitted to the envelope of
//!    the target points along it as a whole (on a mesh its outermost point in each
//!    window: two a side, more where the target's points are dense along it; on a scan
//!    its outermost point along the whole side, each window only guarding against the
//!    side swinging out beyond its points there; every point near the target's edge
//!    counts, however many the target has), plus
//!    the gap that a sampling leaves between its outermost points and the true edge,
//!    estimated from the spacing of those outermost points (nil for a mesh's vertices,
//!    about `A / (n·L)` for `n` random points over an area `A` along a length `L`), so
//!    that a scan is recovered to its edges and a mesh exactly to its boundary; on a
//!    scan, plus how much farther than a few spacings each target point lies from the
//!    mesh (nil where the mesh reaches its edges; a corner cut off, or a part of the
//!    target the mesh does not reach). [`Deviation`] reports the whole distances both
//!    ways.
//!
//! With [`ApproxOptions::trim`], the mesh is fitted to cover the target rather than to
//! end on its edges (every vertex within the target's outline near it, every target
//! point near the mesh; the overhang, which the trimming cuts away, is free) and cut by
//! the target's outline
//! ([`trim()`]): a roof whose edges are not curvature lines.
//!
//! The result is generated by [`crate::generate()`], so it keeps every property of the
//! paper's meshes to floating-point precision; only its distance to the target is
//! approximate, and [`Deviation`] reports it.

use std::time::Instant;

use glam::DVec3;

use crate::conical::conical_dual;
use crate::design::{Design, GuideSpec, MeshKind, Xyz};
use crate::gauss_map::admissible_theta_at;
use crate::generate::{generate, GenerateOptions};
use crate::grid::QuadGrid;

mod clip;
mod cover;
mod cut;
mod deviation;
mod distance;
mod edge;
mod error;
mod fit_guide;
mod index;
mod layout;
mod outline;
mod patches;
mod quadric;
mod report;
mod solve;
mod start;
mod stray;
mod tolerance;
mod trim;

use start::{choose_starts, initial_guesses, Start};

pub use distance::{point_triangle, Deviation};
pub use error::{ApproxError, FLAT_CURVATURE, MIN_POINTS, UMBILIC_RATIO};
use fit_guide::{hooked, refine_guide, CONTROL_POINTS};
use index::Matches;
pub use index::{TargetCloud, SCAN_EDGE_OVERREAD};
pub use layout::PatchLayout;
pub use patches::{approximate_patches, PatchApproximation, PatchFit};

pub use outline::{Outline, OutlineError, OUTLINE_FRAME_TOL};
pub use report::{fit_report, target_distances, FitReport};
pub use tolerance::*;
pub use trim::{trim, TrimmedMesh};

/// Free numbers of a design: corner (3), rotation (3), plane tilts (2), θ, and per guide
/// the second control point's distance and two coordinates of each later one.
const PARAMETERS: usize = 9 + 2 * (1 + 2 * (CONTROL_POINTS - 2));

/// The fewest mesh generations a least-squares run of [`approximate`] takes: `2n + 2`
/// for its `n` parameters (two Jacobians and their steps); a smaller
/// [`ApproxOptions::max_evaluations`] is raised to it.
pub const MIN_EVALUATIONS: usize = 2 * PARAMETERS + 2;

/// Options of [`approximate`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ApproxOptions {
    /// Faces of the result along guide_u and guide_v (default 40 × 40).
    pub faces: (usize, usize),
    /// Circular (default) or conical mesh (§2.2, §2.3).
    pub kind: MeshKind,
    /// Number of starts: the best θ of the scan at each corner, then the next best ones,
    /// tried in turn until one recovers the target (default 4).
    pub starts: usize,
    /// Budget of mesh generations of each least-squares run (default 1500; at least
    /// [`MIN_EVALUATIONS`]).
    pub max_evaluations: usize,
    /// Stop improving at this instant and return the best design found (default none).
    pub deadline: Option<Instant>,
    /// Keep the target's boundary: the guides are two of the target's own boundary
    /// curves, traced and fitted from a corner, and stay as they are; only θ is searched
    /// (default false: the guides move too).
    pub keep_boundary: bool,
    /// Trim the result to the target's outline ([`trim`](trim())): the mesh is fitted to cover
    /// the target rather than to end on its edges, then cut by its outline, for a target
    /// whose edges are not curvature lines (default false: the mesh's boundary follows
    /// the target's edges).
    pub trim: bool,
}

impl Default for ApproxOptions {
    fn default() -> Self {
        ApproxOptions {
            faces: (40, 40),
            kind: MeshKind::Circular,
            starts: 4,
            max_evaluations: 1500,
            deadline: None,
            keep_boundary: false,
            trim: false,
        }
    }
}

/// The deadline [`ApproxOptions::deadline`] `seconds` from now (§4.7's search, time-limited).
///
/// A limit beyond what the clock can represent (about 10¹⁰ years and more) is no limit:
/// `None`. A limit that is not a positive number of seconds is an error.
///
/// ```
/// use monge_core::approximate::{deadline_after, ApproxError};
/// assert!(deadline_after(2.5).unwrap().is_some());
/// assert_eq!(deadline_after(1e300), Ok(None));
/// assert_eq!(deadline_after(0.0), Err(ApproxError::BadTimeLimit(0.0)));
/// ```
pub fn deadline_after(seconds: f64) -> Result<Option<Instant>, ApproxError> {
    if seconds.is_nan() || seconds <= 0.0 {
        return Err(ApproxError::BadTimeLimit(seconds));
    }
    Ok(std::time::Duration::try_from_secs_f64(seconds)
        .ok()
        .and_then(|d| Instant::now().checked_add(d)))
}

/// The result of [`approximate`].
#[derive(Clone, Debug)]
pub struct Approximation {
    /// The design found.
    pub design: Design,
    /// Its mesh (the conical dual for [`MeshKind::Conical`]).
    pub grid: QuadGrid,
    /// The initial guess: the best start of the θ scan, before any optimisation.
    pub initial: Design,
    /// Deviation of the initial guess on the full grid.
    pub before: Deviation,
    /// Deviation of the result.
    pub after: Deviation,
    /// θ of the initial guess, degrees.
    pub initial_theta_deg: f64,
    /// The objective of the initial guess and of the result on the full grid: the sum
    /// of the mean squared distances from the mesh's vertices to the target and of the
    /// target's points beyond the mesh (relative; see the module documentation). The
    /// result's is never the larger (infinite if the initial guess folds).
    pub objective: (f64, f64),
    /// Principal curvatures at the corner of the initial guess (larger first).
    pub corner_curvatures: (f64, f64),
    /// Meshes generated in all.
    pub evaluations: usize,
    /// Starts run to the end.
    pub starts: usize,
    /// Whether the deadline (or [`approximate_until`]'s stop) stopped the search early.
    pub timed_out: bool,
    /// With [`ApproxOptions::trim`], the result's mesh trimmed to the target's outline
    /// (what [`Approximation::after`] measures).
    pub trimmed: Option<TrimmedMesh>,
    /// The target's stray points, set aside ([`TargetCloud::stray`]): their indices in
    /// the points given.
    pub stray: Vec<usize>,
}

/// What [`approximate`] reports while it runs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Progress {
    /// Meshes generated so far.
    pub evaluations: usize,
    /// Largest number of meshes the search may generate.
    pub budget: usize,
    /// Best objective so far (relative RMS distance, both ways).
    pub best_rms: f64,
}

/// The design of parameters `x` (real units) from `start`, with `samples` per guide.
fn design_of(start: &Start, x: &[f64], samples: (usize, usize), kind: MeshKind) -> Design {
    let [t_u, t_v, n] = start.frame;
    let rotation = glam::DQuat::from_scaled_axis(DVec3::new(x[3], x[4], x[5]));
    let (t_u, t_v, n) = (rotation * t_u, rotation * t_v, rotation * n);
    let corner = start.corner + x[0] * t_u + x[1] * t_v + x[2] * n;
    // x[8] is the angle around the circle of admissible θ (φ): the surfaces of
    // revolution and the mouldings (θ = 0° or 180°, §4.1) lie at the ends of the
    // admissible range of a design whose guide planes are tilted (§3.2), which φ
    // crosses smoothly.
    let theta = admissible_theta_at(x[6].sin(), x[7].sin(), x[8]);
    let per_guide = per_guide(x);
    let guide = |t: DVec3, other: DVec3, tilt: f64, c: &[f64], samples: usize| {
        let up = tilt.cos() * n - tilt.sin() * other;
        let mut control: Vec<Xyz> = vec![corner.to_array(), (corner + c[0] * t).to_array()];
        for w in c[1..].chunks(2) {
            control.push((corner + w[0] * t + w[1] * up).to_array());
        }
        GuideSpec::bspline(3, control, samples)
    };
    Design {
        theta_deg: theta,
        guide_u: guide(t_u, t_v, x[6], &x[9..9 + per_guide], samples.0),
        guide_v: guide(t_v, t_u, x[7], &x[9 + per_guide..], samples.1),
        mesh: kind,
        tolerance: None,
    }
}

/// Free numbers of each guide among a design's parameters `x` (those of [`PARAMETERS`],
/// or more once refined by [`refine_guides`]).
fn per_guide(x: &[f64]) -> usize {
    (x.len() - 9) / 2
}

/// The same design with finer guides ([`refine_guide`]).
fn refine_guides(x: &[f64]) -> Vec<f64> {
    let per_guide = per_guide(x);
    let mut out = x[..9].to_vec();
    out.extend(refine_guide(&x[9..9 + per_guide]));
    out.extend(refine_guide(&x[9 + per_guide..]));
    out
}

/// The mesh of `design` if it can be generated without folds (§5.2): of a mesh to be
/// trimmed to `outline`, without folds where the trimming keeps it ([`trim::kept_folds`]).
fn fair_mesh(design: &Design, outline: Option<&Outline>) -> Option<QuadGrid> {
    let g = generate(design, &GenerateOptions::default()).ok()?;
    let grid = match design.mesh {
        MeshKind::Circular => g.grid,
        MeshKind::Conical => conical_dual(&g.grid).grid,
    };
    (grid.vertices.iter().all(|v| v.is_finite()) && trim::kept_folds(&grid, outline) == 0)
        .then_some(grid)
}

/// Samples per guide for `faces` faces of the mesh of `kind`.
fn samples_for(faces: (usize, usize), kind: MeshKind) -> (usize, usize) {
    let extra = match kind {
        MeshKind::Circular => 1,
        MeshKind::Conical => 2,
    };
    (faces.0 + extra, faces.1 + extra)
}

/// Largest target points used in the objective (every k-th beyond it); the final
/// deviation uses them all.
const OBJECTIVE_POINTS: usize = 1000;

/// Largest scan whose own points the initial guesses are built from; of a larger one,
/// this many of its points, spread over it ([`TargetCloud::thinned`]). The starts
/// (boundaries traced through the points, quadrics of their neighbours) were made on
/// scans of 2 000 points; a held-out scan of 8 000 points, read whole, started 5 times
/// farther from the target (a Dupin cyclide, 3.9e-2 against 7.4e-3 from 2 000 points of
/// the same surface) and ended off it. With the sides held in at most three windows
/// each (`EDGE_WINDOWS_MAX`), 1 of 40 such scans still fell off (2.5e-2) without this,
/// none with it.
const START_POINTS: usize = 2000;

/// Largest target points matched to the mesh at each step of the least squares (every
/// k-th beyond it), besides every point near the target's edge, which set the sides
/// ([`TargetCloud::matches`]): the edges' precision grows with the points measured.
const EDGE_POINTS: usize = 4000;

/// The search: objective, budget, best point.
struct Search<'a> {
    target: &'a TargetCloud,
    kind: MeshKind,
    stride: usize,
    evaluations: usize,
    /// Evaluations of one least-squares run.
    budget: usize,
    /// Evaluations of the whole search (for [`Progress::budget`]).
    total: usize,
    best: f64,
    /// Whether to stop now (the deadline, or the caller's own stop).
    stop: &'a (dyn Fn() -> bool + Sync),
    timed_out: bool,
    /// Faces of the mesh asked for, whose samples of the guides the search's coarser
    /// meshes must not step over ([`hooked`]).
    faces: (usize, usize),
    /// The target's outline where the mesh is to cover the target and be trimmed to it
    /// ([`ApproxOptions::trim`]).
    outline: Option<&'a Outline>,
}

impl Search<'_> {
    /// A search with the same target, settings and stop, and its own counts.
    fn fork(&self) -> Self {
        Search {
            target: self.target,
            kind: self.kind,
            stride: self.stride,
            faces: self.faces,
            outline: self.outline,
            evaluations: 0,
            budget: self.budget,
            total: self.total,
            best: f64::INFINITY,
            stop: self.stop,
            timed_out: false,
        }
    }

    /// Where the search stands, for the progress callback.
    fn progress(&self) -> Progress {
        Progress {
            evaluations: self.evaluations,
            budget: self.total,
            best_rms: self.best.sqrt(),
        }
    }

    /// The mesh at `x` (real units) from `start` on a grid of `faces`, or `None` when
    /// infeasible.
    fn mesh(&self, start: &Start, x: &[f64], faces: (usize, usize)) -> Option<QuadGrid> {
        // Each guide leaves the corner along its start tangent: its second control point
        // ahead of the corner (behind, the guide turns back in a cusp; a coarse grid may
        // not fold there, the full one does).
        if x[9] <= 0.0 || x[9 + per_guide(x)] <= 0.0 {
            return None;
        }
        // Nor may a guide turn back between the samples of the mesh asked for, which
        // a coarser one steps over.
        let full = samples_for(self.faces, self.kind);
        if faces != self.faces && hooked(&design_of(start, x, full, self.kind)) {
            return None;
        }
        fair_mesh(
            &design_of(start, x, samples_for(faces, self.kind), self.kind),
            self.outline,
        )
    }

    /// The residuals at `x` (real units) from `start` on a grid of `faces`
    /// ([`TargetCloud::residuals`]) and what they were measured against, or `None` when
    /// infeasible.
    fn residuals(
        &self,
        start: &Start,
        x: &[f64],
        faces: (usize, usize),
    ) -> Option<(Vec<f64>, Matches)> {
        let grid = self.mesh(start, x, faces)?;
        let matches = self.target.matches(&grid, self.stride);
        Some((self.residuals_against(&grid, &matches), matches))
    }

    /// The residuals of `grid` against `matches`: [`TargetCloud::residuals`], or
    /// [`TargetCloud::cover_residuals`] for a mesh to be trimmed.
    fn residuals_against(&self, grid: &QuadGrid, matches: &Matches) -> Vec<f64> {
        if self.outline.is_some() {
            self.target.cover_residuals(grid, matches)
        } else {
            self.target.residuals(grid, matches)
        }
    }

    /// The sum of squares of [`Search::residuals`] (not counted), or `None` when
    /// infeasible.
    fn sum_of_squares_at(&self, start: &Start, x: &[f64], faces: (usize, usize)) -> Option<f64> {
        self.residuals(start, x, faces)
            .map(|r| sum_of_squares(&r.0))
    }

    /// [`Search::residuals`], counted, or `None` once stopped.
    fn evaluate(
        &mut self,
        start: &Start,
        x: &[f64],
        faces: (usize, usize),
    ) -> Option<(Vec<f64>, Matches)> {
        if (self.stop)() {
            self.timed_out = true;
            return None;
        }
        self.evaluations += 1;
        let r = self.residuals(start, x, faces)?;
        self.best = self.best.min(sum_of_squares(&r.0));
        Some(r)
    }

    /// Objective at `x` (real units) from `start` on a grid of `faces`: the sum of
    /// squares of [`Search::residuals`], or NaN when infeasible (or once stopped).
    fn objective(&mut self, start: &Start, x: &[f64], faces: (usize, usize)) -> f64 {
        self.evaluate(start, x, faces)
            .map_or(f64::NAN, |r| sum_of_squares(&r.0))
    }
}

/// The least squares are deemed to have recovered the target when the root of their
/// sum of squares (relative RMS distances, both ways) is within this: a surface with
/// planar curvature lines sampled to 1e-4 of its size ends well under it, a target one
/// patch cannot follow well above.
const RECOVERED: f64 = 1e-3;

/// Where a coarse design folds on the full grid, the designs tried instead on the way
/// back to its start (the share of the way kept): a scan of the held-out onion dome fit
/// on the coarse grid (θ 1.3°) folded two faces on the full one, and its start settled
/// at θ 5.7°, 2.0e-2 of the size off; from 0.8 of the way, θ 0.0°, 1.1e-3 off.
const BACK_OFF: [f64; 3] = [0.8, 0.6, 0.4];

/// Sum of squares of residuals.
pub(super) fn sum_of_squares(r: &[f64]) -> f64 {
    r.iter().map(|r| r * r).sum()
}

impl<'a> Search<'a> {
    /// `stage` from each of `from` (a start's index in `guesses` and parameters), each its
    /// own search, in parallel: the results (objective, start, parameters) in `from`'s
    /// order whatever the threads, and how many ran to the end; their counts are added
    /// to this search's.
    #[allow(clippy::type_complexity)]
    fn each(
        &mut self,
        guesses: &[Start],
        from: &[(usize, Vec<f64>)],
        stage: &(dyn Fn(&mut Search<'a>, &Start, &[f64]) -> (f64, Vec<f64>) + Sync),
    ) -> (Vec<(f64, usize, Vec<f64>)>, usize) {
        let one = |(g, x): &(usize, Vec<f64>)| {
            let mut local = self.fork();
            let (f, x) = stage(&mut local, &guesses[*g], x);
            ((f, *g, x), local)
        };
        let runs = crate::tasks::map(from.len(), |k| one(&from[k]));
        let mut results = Vec::with_capacity(runs.len());
        let mut finished = 0;
        for (result, local) in runs {
            self.evaluations += local.evaluations;
            self.best = self.best.min(local.best);
            self.timed_out |= local.timed_out;
            finished += usize::from(!local.timed_out);
            results.push(result);
        }
        (results, finished)
    }
}

/// The start's own parameters: no move, φ given (see [`design_of`]), its guides'
/// control points.
fn start_parameters(start: &Start, phi: f64) -> Vec<f64> {
    let mut x = vec![0.0; PARAMETERS];
    x[6..8].copy_from_slice(&start.tilts);
    x[8] = phi;
    let per_guide = start.guides[0].len();
    for (k, c) in start.guides.iter().enumerate() {
        x[9 + k * per_guide..9 + (k + 1) * per_guide].copy_from_slice(c);
    }
    x
}

/// The surface with planar curvature lines nearest to a target (monge's extension of
/// the method; the paper's fitting of §4.7 and §4.8 are its relatives): see the
/// module documentation for the steps. `progress` is called after every mesh generated.
///
/// ```
/// use glam::DVec3;
/// use monge_core::approximate::{approximate, ApproxError};
/// // A plane: no curvature to follow.
/// let plane: Vec<DVec3> = (0..400)
///     .map(|k| DVec3::new((k % 20) as f64, (k / 20) as f64, 0.0))
///     .collect();
/// let e = approximate(&plane, &Default::default(), &mut |_| {}).unwrap_err();
/// assert!(matches!(e, ApproxError::Flat { .. }));
/// ```
pub fn approximate(
    points: &[DVec3],
    options: &ApproxOptions,
    progress: &mut dyn FnMut(&Progress),
) -> Result<Approximation, ApproxError> {
    approximate_until(points, options, &|| false, progress)
}

/// [`approximate`], stopped as by its deadline the first time `stop` returns true
/// (checked before every mesh generated, from the threads of the parallel starts too):
/// a caller's own limit (a cancel button, a budget). The result is the best design
/// found so far, with [`Approximation::timed_out`] set, or [`ApproxError::TimeLimit`]
/// when no design had been generated yet.
pub fn approximate_until(
    points: &[DVec3],
    options: &ApproxOptions,
    stop: &(dyn Fn() -> bool + Sync),
    progress: &mut dyn FnMut(&Progress),
) -> Result<Approximation, ApproxError> {
    check_faces(options)?;
    approximate_target(&TargetCloud::new(points)?, options, stop, progress)
}

/// Whether a grid of `options.faces` can be fitted: at least 4 × 4 faces, at most
/// [`GenerateOptions::max_vertices`] vertices.
fn check_faces(options: &ApproxOptions) -> Result<(), ApproxError> {
    let (fu, fv) = options.faces;
    if fu < 4 || fv < 4 {
        return Err(ApproxError::GridTooSmall(fu, fv));
    }
    let limit = GenerateOptions::default().max_vertices;
    if (fu + 1).saturating_mul(fv + 1) > limit {
        return Err(ApproxError::GridTooLarge(fu, fv, limit));
    }
    Ok(())
}

/// [`approximate_until`] of the target `target`, indexed once for several fits (a
/// tolerance's), `options.faces` checked ([`check_faces`]).
pub(super) fn approximate_target(
    target: &TargetCloud,
    options: &ApproxOptions,
    stop: &(dyn Fn() -> bool + Sync),
    progress: &mut dyn FnMut(&Progress),
) -> Result<Approximation, ApproxError> {
    let (fu, fv) = options.faces;
    let points = &target.points;
    let outline = options.trim.then(|| Outline::of(target)).transpose()?;
    let mut guesses = match target.thinned(START_POINTS) {
        Some(sparse) => initial_guesses(&sparse)?,
        None => initial_guesses(target)?,
    };
    if options.keep_boundary {
        guesses.retain(|g| g.on_boundary);
        if guesses.is_empty() {
            return Err(ApproxError::NoBoundary);
        }
    }
    let coarse = ((fu / 2).max(4), (fv / 2).max(4));
    let budget = options.max_evaluations.max(MIN_EVALUATIONS);
    let starts_wanted = options.starts.max(1);
    let mut search = Search {
        target,
        kind: options.kind,
        stride: points.len().div_ceil(EDGE_POINTS),
        faces: options.faces,
        outline: outline.as_ref(),
        evaluations: 0,
        budget,
        total: guesses.len() * 35 + (starts_wanted + 1) * budget,
        best: f64::INFINITY,
        stop: &|| options.deadline.is_some_and(|d| Instant::now() >= d) || stop(),
        timed_out: false,
    };
    // θ from a scan every 10° (§4.3) at each corner; the best few as starts.
    let scan = search.scan_starts(&guesses, coarse);
    let corners: Vec<usize> = guesses.iter().map(|g| g.at_corner).collect();
    let chosen = choose_starts(scan, &corners, starts_wanted);
    let (first, initial_phi) = *chosen.first().ok_or(if search.timed_out {
        ApproxError::TimeLimit
    } else {
        ApproxError::NoStart
    })?;
    // The starts on the coarse grid: the least squares from each in turn (their Jacobian
    // in parallel) until one recovers the target; where they stall away from it from
    // every start, again from each of their results with θ moved to the best of a scan
    // ([`Search::theta_restarts`]), in parallel (the first results stay candidates).
    let (mut results, mut starts) = (Vec::new(), 0);
    for (g, theta) in &chosen {
        let from = [(*g, start_parameters(&guesses[*g], *theta))];
        let (result, finished) = search.each(&guesses, &from, &|s, start, x| {
            if options.keep_boundary {
                s.run_theta(start, x, coarse, 10.0, &mut |_| {})
            } else {
                s.run(start, x, coarse, &mut |_| {})
            }
        });
        starts += finished;
        results.extend(result);
        if search.timed_out || results.iter().any(|r| r.0.sqrt() <= RECOVERED) {
            break;
        }
    }
    if !options.keep_boundary
        && !options.trim
        && !search.timed_out
        && !results.iter().any(|r| r.0.sqrt() <= RECOVERED)
    {
        let from = search.theta_restarts(&guesses, &results, coarse);
        let (restarted, _) = search.each(&guesses, &from, &|s, start, x| {
            s.run(start, x, coarse, &mut |_| {})
        });
        results.extend(restarted);
    }
    progress(&search.progress());
    results.sort_by(|a, b| a.0.total_cmp(&b.0));
    // A design fair on the coarse grid may fold on the full one: then designs on the way
    // back to its start (BACK_OFF), then the starts themselves.
    let mut results: Vec<(f64, usize, Vec<f64>)> = results
        .into_iter()
        .flat_map(|(f, g, x)| {
            let x0 = start_parameters(&guesses[g], x[8]);
            // None where the result is its start (θ alone, with --keep-boundary).
            let back: Vec<_> = if x0 == x {
                Vec::new()
            } else {
                BACK_OFF
                    .iter()
                    .map(|t| {
                        let x_t = x.iter().zip(&x0).map(|(a, b)| b + t * (a - b)).collect();
                        (f64::NAN, g, x_t)
                    })
                    .collect()
            };
            std::iter::once((f, g, x)).chain(back)
        })
        .collect();
    results.extend(
        chosen
            .iter()
            .map(|(g, theta)| (f64::NAN, *g, start_parameters(&guesses[*g], *theta))),
    );
    // Refine on the full grid, from the best result whose mesh is fair there; past the
    // deadline, that result as it is.
    let samples = samples_for(options.faces, options.kind);
    let (start, fine) = results
        .iter()
        .find_map(|(_, g, x)| {
            let (f, fine) = if options.keep_boundary {
                search.run_theta(&guesses[*g], x, (fu, fv), 1.0, progress)
            } else {
                search.run(&guesses[*g], x, (fu, fv), progress)
            };
            if f.is_finite() {
                return Some((&guesses[*g], fine));
            }
            let fair = || {
                fair_mesh(
                    &design_of(&guesses[*g], x, samples, options.kind),
                    outline.as_ref(),
                )
                .is_some()
            };
            (search.timed_out && fair()).then(|| (&guesses[*g], x.clone()))
        })
        .ok_or(if search.timed_out {
            ApproxError::TimeLimit
        } else {
            ApproxError::NoStart
        })?;
    let fine = if options.keep_boundary {
        fine
    } else {
        let fine = search.finer_guides(start, fine, (fu, fv), progress);
        search.moulding(start, fine, (fu, fv), progress)
    };
    // Never worse than the initial guess: the better of the two on the full grid.
    let initial_x = start_parameters(&guesses[first], initial_phi);
    let full = |s: &Start, x: &[f64]| {
        search
            .sum_of_squares_at(s, x, (fu, fv))
            .unwrap_or(f64::INFINITY)
    };
    let objective_before = full(&guesses[first], &initial_x);
    let mut objective_after = full(start, &fine);
    let (start, fine) = if objective_before < objective_after {
        objective_after = objective_before;
        (&guesses[first], initial_x.clone())
    } else {
        (start, fine)
    };
    let initial = design_of(&guesses[first], &initial_x, samples, options.kind);
    // Measured as trimmed, where trimmed.
    let measure = |grid: &QuadGrid| trim::measured(target, grid, outline.as_ref(), 1);
    let before = fair_mesh(&initial, outline.as_ref()).map(|g| measure(&g).0);
    let design = design_of(start, &fine, samples, options.kind);
    let grid = fair_mesh(&design, outline.as_ref()).expect("the refined design was generated fair");
    let (after, trimmed) = measure(&grid);
    let nan = Deviation {
        mesh_to_target_max: f64::NAN,
        mesh_to_target_rms: f64::NAN,
        target_to_mesh_max: f64::NAN,
        target_to_mesh_rms: f64::NAN,
        beyond_mesh_rms: f64::NAN,
        size: target.size,
    };
    Ok(Approximation {
        design,
        grid,
        initial_theta_deg: initial.theta_deg,
        initial,
        before: before.unwrap_or(nan),
        after,
        objective: (objective_before, objective_after),
        corner_curvatures: start.curvatures,
        evaluations: search.evaluations,
        starts,
        timed_out: search.timed_out,
        trimmed,
        stray: target.stray().to_vec(),
    })
}
