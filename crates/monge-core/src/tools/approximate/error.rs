//! What an approximation refuses, and the limits it checks.

use crate::design::Xyz;

/// Fewest target points accepted: a quadric has 6 coefficients, and the corner's own
/// fit uses a fraction of the points.
pub const MIN_POINTS: usize = 30;

/// Below this ratio `|κ1 − κ2| / max(|κ1|, |κ2|)` the target counts as umbilic.
pub const UMBILIC_RATIO: f64 = 0.05;

/// Below this largest `|κ|·size` the target counts as flat.
pub const FLAT_CURVATURE: f64 = 1e-3;

/// Why a target cannot be approximated.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum ApproxError {
    /// Too few target points.
    #[error(
        "the target has {found} points, too few to fit its curvature: give at least {needed} \
         (a mesh's vertices or a point cloud sampling the whole surface)"
    )]
    TooFewPoints {
        /// Points given.
        found: usize,
        /// [`MIN_POINTS`].
        needed: usize,
    },
    /// A coordinate is NaN or infinite.
    #[error("target point {index} is {point:?}, not finite: remove it or fix the file")]
    NotFinite {
        /// Index of the point.
        index: usize,
        /// Its coordinates.
        point: Xyz,
    },
    /// The grid asked for has more vertices than a mesh may have.
    #[error(
        "a grid of {0} × {1} faces has more vertices than the limit of {2} a generated mesh may \
         have: give a coarser grid (e.g. --grid 40x40)"
    )]
    GridTooLarge(usize, usize, usize),
    /// The target is too small or too large for double precision.
    #[error(
        "the target's size (its bounding-box diagonal) is {size:e}, outside [{min:e}, {max:e}]: \
         at such scales squared lengths underflow or overflow in double precision. Rescale the \
         target (e.g. use other units)"
    )]
    ScaleOutOfRange {
        /// The bounding-box diagonal of the target points.
        size: f64,
        /// [`crate::grid::MIN_SIZE`].
        min: f64,
        /// [`crate::grid::MAX_SIZE`].
        max: f64,
    },
    /// The target's outline, seen along its normal, cannot be traced as a polygon
    /// around its centre ([`Outline::of`](super::Outline::of)).
    #[error(
        "the target's outline cannot be traced: {outside} of its {points} points lie outside \
         the polygon of its boundary points seen along its normal from its centre, and \
         {hidden} of its boundary points lie well inside it (an L-shaped, ring-shaped or \
         closed target): trim only a target whose outline is star-shaped around its centre, \
         or split it"
    )]
    NoOutline {
        /// Target points outside the outline traced.
        outside: usize,
        /// Boundary points well inside it.
        hidden: usize,
        /// Target points.
        points: usize,
    },
    /// The grid asked for is too small.
    #[error(
        "a grid of {0} × {1} faces is too small: give at least 4 × 4 faces (e.g. --grid 40x40)"
    )]
    GridTooSmall(usize, usize),
    /// The target has (almost) no curvature at the corner.
    #[error(
        "the target is flat at {where_} ({point:?}): its principal curvatures are {k1:.3e} and \
         {k2:.3e} per unit length, |κ|·size ≤ {limit:e}, so its curvature lines have no \
         direction there and a surface with planar curvature lines cannot be started from it; \
         a plane needs no approximation: use it as it is"
    )]
    Flat {
        /// `the corner` or `the centre`.
        where_: &'static str,
        /// The point of the fitted quadric.
        point: Xyz,
        /// Larger principal curvature.
        k1: f64,
        /// Smaller principal curvature.
        k2: f64,
        /// [`FLAT_CURVATURE`].
        limit: f64,
    },
    /// The target is umbilic at its corners (principal directions undefined) and no other
    /// start exists (boundary, curvature lines, whole quadric).
    #[error(
        "the target is umbilic at {where_} ({point:?}), like a sphere: its principal \
         curvatures {k1:.4e} and {k2:.4e} differ by {percent:.2} % (less than {limit_percent} %), \
         so its curvature lines have no direction there, and no other start exists: its \
         boundary could not be traced from any corner, nor its curvature lines followed, nor \
         (its centre not a dome's) its whole quadric. The method, one surface with planar \
         curvature lines started along them, cannot follow the target: sample its edges more \
         densely, or approximate a part of it away from its umbilics"
    )]
    Umbilic {
        /// `the corner` or `the centre`.
        where_: &'static str,
        /// The point of the fitted quadric.
        point: Xyz,
        /// Larger principal curvature.
        k1: f64,
        /// Smaller principal curvature.
        k2: f64,
        /// `100 · |κ1 − κ2| / max(|κ1|, |κ2|)`.
        percent: f64,
        /// `100 · UMBILIC_RATIO`.
        limit_percent: f64,
    },
    /// The time limit ended before any design was generated.
    #[error(
        "the time limit ended before a first design could be generated from the target: \
         give more time (--time-limit) or a coarser grid"
    )]
    TimeLimit,
    /// A time limit that is not a positive number of seconds.
    #[error("a time limit of {0} s: give a positive number of seconds")]
    BadTimeLimit(f64),
    /// `keep_boundary` was asked, but no boundary curves could be traced.
    #[error(
        "the target's boundary could not be traced from any of its corners (too few points \
         along it, or no corner where two boundary curves meet), so there is no boundary to \
         keep: sample the target's edges more densely, or approximate without --keep-boundary"
    )]
    NoBoundary,
    /// Patches were asked of a conical approximation.
    #[error(
        "patches (§4.7) continue circular meshes: approximate with --kind circular to fit \
         several patches"
    )]
    PatchesNotCircular,
    /// Too many patches for the faces along a guide (or fewer than two in all).
    #[error(
        "{patches} patches along {along} need at least 2 faces each, but the grid has \
         {segments} faces along {along}: ask for at most {} patches (and at least 2 in all), \
         or a finer --grid",
        segments / 2
    )]
    TooManyPatches {
        /// Patches asked for along that guide.
        patches: usize,
        /// Faces along that guide.
        segments: usize,
        /// `guide_u` or `guide_v`.
        along: &'static str,
    },
    /// No θ of a patch gives a mesh without folds with the patches before it.
    #[error(
        "no θ of patch {patch} (scanned every degree) gives a mesh without folds with the \
         patches before it: ask for fewer patches (--patches) or a coarser --grid"
    )]
    NoPatchStart {
        /// The patch (0 when the patches found together fold).
        patch: usize,
    },
    /// No design of the search gives a fair mesh on the requested grid.
    #[error(
        "no design found can be generated without folds on the requested grid (θ scanned from \
         −170° to 170° every 10° from guides fitted at each corner of the target; a guide fitted \
         to a straight edge, for one, cannot be generated: guides must be curved): the target is \
         too far from what one patch can make; try a coarser --grid, a smaller part of the \
         target, or (with --keep-boundary) guides free to move"
    )]
    NoStart,
}
