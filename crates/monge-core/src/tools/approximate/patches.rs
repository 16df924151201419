//! The second step of an approximation (§4.7): where one patch cannot follow the
//! target, several patches with piecewise planar curvature lines, in a layout of
//! `u × v` blocks ([`PatchLayout`]).
//!
//! The single patch's grid is cut into blocks: along guide_u into `u`, along guide_v
//! into `v`, of nearly equal numbers of samples. The layout's origin is in the middle:
//! the corner of block `(u / 2, v / 2)`, where the single patch's row and column
//! through it cross (for `u = 1` or `v = 1`, its first row or column). The first
//! patch is that block, its guides the two lines of the cross leaving the origin; every
//! other patch's own grid runs away from the origin (its corner, where its guides
//! start, is the one nearest to it), so that each target corner is one block from a
//! free guide both ways, not `u` or `v` blocks. The patches along the cross continue
//! its lines, each attached to its neighbour towards the origin (a first row or column
//! on the far side of the origin: the continuation runs backwards there, and the
//! normals are turned in the assembly), with its own guide; the others are attached to
//! their neighbour towards the origin along guide_u and take their second guide from
//! their neighbour towards it along guide_v (`guide_from`). Patches are built
//! outwards from the origin. The curvature lines are planar in each patch and change
//! plane at each seam, where the panels stay planar and circular and the beams C¹
//! (§4.7). With every guide its piece of the single patch's lines and the single
//! patch's θ in every patch (θ is the same in every block's own frame), the patches
//! rebuild the single patch to round-off: the search starts there.
//!
//! Every free guide — both of the first patch, each continuation — is a cubic
//! B-spline of 5 control points in a plane through its start tangent (forced by the
//! patches before it, [`ContinuationStart`](crate::multipatch::ContinuationStart)): the plane's tilt about that tangent, the
//! second control point's distance along it and both in-plane coordinates of the
//! others are free, as in [`approximate`](super::approximate). With every patch's θ,
//! BOBYQA moves them all together from the single patch's own lines and θ, with the
//! objective of the single patch (a folded mesh counts as worse than the start by its
//! number of folded faces, never as a result). The result is the design seen closest
//! to the target by the largest distance both ways ([`Deviation::closer_than`]), the
//! single patch included (then a design of one patch).
//!
//! From a single patch that covers the target to be trimmed ([`ApproxOptions::trim`]),
//! the patches cover it too: the search's objective is the covering least squares
//! ([`TargetCloud::cover_residuals`]), the distances those of the mesh trimmed to the
//! target's outline, and the result is trimmed ([`PatchApproximation::trimmed`]).

use glam::DVec3;

use super::cut::{Pieces, PER_GUIDE};
use super::outline::Outline;
use super::trim::{
    kept_folds, measured, resolved, trim, trimmed_deviation_below, ResultFaces, TrimmedMesh,
};
use super::{
    sum_of_squares, ApproxError, ApproxOptions, Approximation, Deviation, PatchLayout, Progress,
    TargetCloud, OBJECTIVE_POINTS,
};
use crate::generate::GenerateOptions;
use crate::grid::QuadGrid;
use crate::multipatch::{build, MultiPatch, MultiPatchDesign, PatchSpec};

/// One patch of a [`PatchApproximation`]: its θ and how far the target points nearest
/// to it lie from the mesh.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct PatchFit {
    /// Its block (along guide_u, along guide_v) in the layout.
    pub block: (usize, usize),
    /// Its θ in degrees, in its own frame.
    pub theta_deg: f64,
    /// Target points whose nearest mesh vertex lies in this patch.
    pub target_points: usize,
    /// Largest distance from those points to the mesh, relative to the target's size
    /// (0 without points).
    pub max: f64,
    /// Their root-mean-square distance to the mesh, relative to the target's size.
    pub rms: f64,
}

/// The result of [`approximate_patches`].
#[derive(Clone, Debug)]
pub struct PatchApproximation {
    /// The multi-patch design found (§4.7).
    pub design: MultiPatchDesign,
    /// Its layout: the one asked for, or `1 × 1` when no design of several patches
    /// came closer to the target than the single patch (then `design` is that patch).
    pub layout: PatchLayout,
    /// Its mesh, the patches merged (shared lines once).
    pub grid: QuadGrid,
    /// Per patch, in design order.
    pub per_patch: Vec<PatchFit>,
    /// Deviation of the single patch it started from.
    pub before: Deviation,
    /// Deviation of the multi-patch mesh.
    pub after: Deviation,
    /// Meshes generated in all.
    pub evaluations: usize,
    /// Where `single` covers the target to be trimmed ([`ApproxOptions::trim`]), the
    /// multi-patch mesh trimmed to the target's outline: then the result, and what
    /// `after` measures.
    pub trimmed: Option<TrimmedMesh>,
}

impl PatchApproximation {
    /// Whether these patches follow the target closer than `single`, the patch they
    /// started from (§4.7), by the largest distance both ways
    /// ([`Deviation::closer_than`]): the design to keep.
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::approximate::{approximate, approximate_patches, ApproxOptions, PatchLayout};
    /// let target: Vec<DVec3> = (0..121)
    ///     .map(|k| {
    ///         let (x, y) = ((k % 11) as f64, (k / 11) as f64);
    ///         DVec3::new(x, y, 0.04 * x * x + 0.1 * y * y)
    ///     })
    ///     .collect();
    /// let options = ApproxOptions { faces: (6, 4), starts: 1, max_evaluations: 40, ..Default::default() };
    /// let single = approximate(&target, &options, &mut |_| {}).unwrap();
    /// let two = PatchLayout { u: 2, v: 1 };
    /// let patches = approximate_patches(&target, &single, two, &options, &mut |_| {}).unwrap();
    /// // Kept only when closer: a layout of 1 × 1 is the single patch itself.
    /// assert_eq!(patches.closer_than(&single), patches.layout != PatchLayout { u: 1, v: 1 });
    /// ```
    pub fn closer_than(&self, single: &Approximation) -> bool {
        self.after.closer_than(&single.after)
    }
}

/// Folded faces of a mesh (§5.2), where a mesh trimmed to `outline` keeps them
/// ([`kept_folds`]); all of them if a vertex is not finite.
fn folds(grid: &QuadGrid, outline: Option<&Outline>) -> usize {
    if grid.vertices.iter().all(|v| v.is_finite()) {
        kept_folds(grid, outline)
    } else {
        (grid.rows - 1) * (grid.cols - 1)
    }
}

/// Per patch: θ, and the distances to the mesh (`trimmed` where given) of the target
/// points nearest to it.
pub(super) fn per_patch(
    target: &TargetCloud,
    mp: &MultiPatch,
    trimmed: Option<&TrimmedMesh>,
) -> Vec<PatchFit> {
    let faces = ResultFaces::new(&mp.grid, trimmed);
    let cols = mp.grid.cols;
    let mut sums = vec![(0usize, 0.0f64, 0.0f64); mp.patches.len()];
    let owner = |at: usize| {
        let (i, j) = (at / cols, at % cols);
        mp.patches
            .iter()
            .position(|p| (p.rows.0..=p.rows.1).contains(&i) && (p.cols.0..=p.cols.1).contains(&j))
            .expect("every vertex lies in a patch")
    };
    let tree = rstar::RTree::bulk_load(
        mp.grid
            .vertices
            .iter()
            .enumerate()
            .map(|(i, p)| super::distance::Indexed::new(p.to_array(), i))
            .collect(),
    );
    for p in &target.points {
        let nearest = tree
            .nearest_neighbor(p.to_array())
            .expect("a mesh has vertices");
        let k = owner(nearest.data);
        let d = faces.distance_from(*p).0;
        let s = &mut sums[k];
        *s = (s.0 + 1, s.1.max(d), s.2 + d * d);
    }
    mp.patches
        .iter()
        .zip(sums)
        .map(|(p, (n, max, sq))| PatchFit {
            block: p.block,
            theta_deg: p.design.theta_deg,
            target_points: n,
            max: max / target.size,
            rms: if n == 0 {
                0.0
            } else {
                (sq / n as f64).sqrt() / target.size
            },
        })
        .collect()
}

/// A multi-patch design kept, its mesh, its deviation, its trimmed mesh and its
/// deviation as far as the target's points tell its edge.
type Kept = (
    MultiPatchDesign,
    MultiPatch,
    Deviation,
    Option<TrimmedMesh>,
    Deviation,
);

/// Several patches following the target more closely than the single patch `single`
/// (§4.7; see the module documentation): its grid cut into `layout.u` blocks along
/// guide_u times `layout.v` along guide_v, the first patch in the middle, every free
/// guide and θ free. Circular meshes only; every block needs at least two faces each way.
///
/// ```
/// use glam::DVec3;
/// use monge_core::approximate::{approximate, approximate_patches, ApproxOptions, PatchLayout};
/// // A paraboloid, which has no planar curvature lines.
/// let target: Vec<DVec3> = (0..121)
///     .map(|k| {
///         let (x, y) = ((k % 11) as f64, (k / 11) as f64);
///         DVec3::new(x, y, 0.04 * x * x + 0.1 * y * y)
///     })
///     .collect();
/// let options = ApproxOptions { faces: (8, 8), starts: 1, max_evaluations: 60, ..Default::default() };
/// let single = approximate(&target, &options, &mut |_| {}).unwrap();
/// let two = approximate_patches(&target, &single, PatchLayout { u: 2, v: 1 }, &options, &mut |_| {})
///     .unwrap();
/// // Never farther from the target than the single patch (the largest distance both ways).
/// assert!(two.after.max() <= single.after.max());
/// assert_eq!(two.per_patch.len(), two.layout.u * two.layout.v);
/// ```
pub fn approximate_patches(
    points: &[DVec3],
    single: &Approximation,
    layout: PatchLayout,
    options: &ApproxOptions,
    progress: &mut dyn FnMut(&Progress),
) -> Result<PatchApproximation, ApproxError> {
    patches_of(
        &TargetCloud::new(points)?,
        single,
        layout,
        options,
        progress,
    )
}

/// [`approximate_patches`] of the target `target`, indexed once for several fits (a
/// tolerance's).
pub(super) fn patches_of(
    target: &TargetCloud,
    single: &Approximation,
    layout: PatchLayout,
    options: &ApproxOptions,
    progress: &mut dyn FnMut(&Progress),
) -> Result<PatchApproximation, ApproxError> {
    let points = &target.points;
    // Patches from a mesh that covers the target cover it too, and are trimmed.
    let outline = single
        .trimmed
        .is_some()
        .then(|| Outline::of(target))
        .transpose()?;
    let (setup, x0) = Pieces::cut(single, layout)?;
    let grid = &single.grid;
    let count = layout.count();
    let n = x0.len();
    let stride = points.len().div_ceil(OBJECTIVE_POINTS);
    let stop = || {
        options
            .deadline
            .is_some_and(|d| std::time::Instant::now() >= d)
    };
    // The deviation on the objective's points (`None` for a trimmed mesh that cannot come
    // closer than a deviation of largest distance `than`, [`trimmed_deviation_below`]) and
    // the search's objective.
    let measure = |grid: &QuadGrid, than: f64| match outline.as_ref() {
        Some(outline) => {
            let d = trimmed_deviation_below(target, &trim(grid, outline), stride, than);
            let matches = target.matches(grid, stride);
            (d, sum_of_squares(&target.cover_residuals(grid, &matches)))
        }
        None => {
            let d = target.deviation_strided(grid, stride);
            (Some(d), d.objective())
        }
    };
    let (single_strided, single_objective) = measure(grid, f64::INFINITY);
    let single_strided = single_strided.expect("measured without a bound");
    let mut evaluations = 0;
    let budget = count * 359 + options.max_evaluations.max(2 * n + 2);
    // The best point seen by the search's objective, and the closest to the target
    // (largest distance both ways, on the objective's points).
    let mut best: (f64, Option<Vec<f64>>) = (single_objective, None);
    let mut closest: (Deviation, Option<Vec<f64>>) = (single_strided, None);
    // The folded faces at `x` (all when it cannot be built) and the objective, NaN when
    // it folds or the time is up.
    let mut evaluate = |x: &[f64], fit: bool| -> (usize, f64) {
        if stop() {
            return (usize::MAX, f64::NAN);
        }
        evaluations += 1;
        let (folded, f) = match setup.build(x, fit) {
            Some((_, mp)) => match folds(&mp.grid, outline.as_ref()) {
                0 => {
                    let (d, f) = measure(&mp.grid, closest.0.max());
                    if let Some(d) = d.filter(|d| d.closer_than(&closest.0)) {
                        closest = (d, Some(x.to_vec()));
                    }
                    (0, f)
                }
                n => (n, f64::NAN),
            },
            None => (usize::MAX, f64::NAN),
        };
        if f < best.0 {
            best = (f, Some(x.to_vec()));
        }
        progress(&Progress {
            evaluations,
            budget,
            best_rms: best.0.sqrt(),
        });
        (folded, f)
    };
    // The continuations fitted to their pieces in the planes their starts force, the
    // single patch's θ in every patch (it continues the surface along a chain).
    let mut start = x0;
    let (mut folded, mut f0) = evaluate(&start, true);
    // Where that folds, each patch's θ in turn by a scan every degree, the others kept:
    // the fewest folded faces, then the nearest to the target.
    for k in 0..count {
        if folded == 0 || stop() {
            break;
        }
        for theta in (-179..=179).map(f64::from) {
            let mut trial = start.clone();
            trial[k] = theta;
            let (n, f) = evaluate(&trial, true);
            if n < folded || (n == folded && f < f0) {
                (folded, f0, start) = (n, f, trial);
            }
        }
    }
    if folded == 0 {
        // The pieces placed as the chosen start forces them.
        (folded, f0) = evaluate(&start, true);
    }
    if folded == 0 && f0.is_finite() {
        // All together: θ within 30° of their start, each guide's tilt within 0.3 rad,
        // its displacement's coefficients within a quarter of its piece's chord.
        let chord = |slot: usize| {
            let p = &setup.pieces[slot];
            p[0].distance(p[p.len() - 1])
        };
        let span = |i: usize| {
            if i < count {
                30.0
            } else {
                let (slot, at) = ((i - count) / PER_GUIDE, (i - count) % PER_GUIDE);
                if at == 0 {
                    0.3
                } else {
                    0.25 * chord(slot)
                }
            }
        };
        let lower: Vec<f64> = (0..n).map(|i| start[i] - span(i)).collect();
        let upper: Vec<f64> = (0..n).map(|i| start[i] + span(i)).collect();
        let to_real = |t: &[f64]| -> Vec<f64> {
            t.iter()
                .zip(lower.iter().zip(&upper))
                .map(|(t, (l, u))| l + t * (u - l))
                .collect()
        };
        let mut t = vec![0.5; n];
        let mut config = bobyqa::Config::new(n);
        config.rho_begin = 0.05;
        config.rho_end = 1e-7;
        config.max_fun = options.max_evaluations.max(2 * n + 2);
        let mut solver = bobyqa::Bobyqa::new(n, config).expect("a valid BOBYQA configuration");
        solver.minimize(
            |t: &[f64]| match evaluate(&to_real(t), false) {
                // In units of the start's objective; a folded design worse than the
                // start by its folds (a finite value keeps the model going), one that
                // cannot be built worse still.
                (0, f) => f / f0,
                (usize::MAX, _) => 1e3,
                (folded, _) => 2.0 + folded as f64,
            },
            &mut t,
            &vec![0.0; n],
            &vec![1.0; n],
        );
    }
    // The closer to the target of the two, by the largest distance both ways over all
    // its points as far as they tell its edge, if closer than the single patch.
    let single_resolved = resolved(target, &single.after, &single.grid, single.trimmed.as_ref());
    let mut kept = None;
    for x in [&best.1, &closest.1].into_iter().flatten() {
        let (design, mp) = setup.build(x, false).expect("the design was built");
        let (after, trimmed) = measured(target, &mp.grid, outline.as_ref(), 1);
        let r = resolved(target, &after, &mp.grid, trimmed.as_ref());
        if r.closer_than(kept.as_ref().map_or(&single_resolved, |k: &Kept| &k.4)) {
            kept = Some((design, mp, after, trimmed, r));
        }
    }
    let (design, mp, after, trimmed, out_layout) = match kept {
        Some((design, mp, after, trimmed, _)) => (design, mp, after, trimmed, layout),
        None => {
            // The single patch stays the best: a design of one patch.
            let design = MultiPatchDesign {
                patches: vec![PatchSpec {
                    theta_deg: single.design.theta_deg,
                    guide_u: Some(single.design.guide_u.clone()),
                    guide_v: Some(single.design.guide_v.clone()),
                    attach: None,
                    guide: None,
                    guide_from: None,
                }],
                tolerance: single.design.tolerance,
                fit: None,
                symmetry: vec![],
            };
            let mp = build(&design, &GenerateOptions::default())
                .map_err(|_| ApproxError::NoPatchStart { patch: 0 })?;
            (
                design,
                mp,
                single.after,
                single.trimmed.clone(),
                PatchLayout { u: 1, v: 1 },
            )
        }
    };
    Ok(PatchApproximation {
        after,
        per_patch: per_patch(target, &mp, trimmed.as_ref()),
        before: single.after,
        design,
        layout: out_layout,
        grid: mp.grid,
        evaluations,
        trimmed,
    })
}
