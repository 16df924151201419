//! Multi-patch meshes with piecewise planar curvature lines (§4.7, Figures 20 and 21).
//!
//! A first patch is generated from two guides and its own θ; every further patch
//! takes a boundary line of an earlier patch as one guide, continues the other
//! guide from the boundary's first vertex (or takes it from a third patch, below),
//! and has its own θ. The patches fill a rectangle of blocks — `K × 1` when they
//! follow each other along rows, `1 × K` along columns, `U × V` in general — so the
//! result is one [`QuadGrid`](crate::QuadGrid) whose shared lines are stored once:
//! they are identical, bit for bit, in both patches (the earlier patch's copy).
//!
//! # Which guides each patch uses
//!
//! Patch `k ≥ 1` is attached to a side of an earlier patch `p` ([`Attach`]); `p`'s
//! line on that side, taken in its own grid (vertex `(i, j)` at `i·cols + j`), is
//! the *boundary*: row `rows − 1` ([`Side::LastRow`]), row 0 ([`Side::FirstRow`]),
//! column `cols − 1` ([`Side::LastColumn`]) or column 0 ([`Side::FirstColumn`]).
//! Its first vertex is the *corner* `c`, with `p`'s node axis `n_c` there.
//!
//! - For a row side, patch `k`'s `guide_v` is the boundary row (a `points` guide, `j`
//!   running as in `p`), and its `guide_u` is the patch's own `guide`, the
//!   *continuation*, which must start at `c` (its first sample is replaced by `c`).
//! - For a column side, `guide_u` is the boundary column and `guide_v` the continuation.
//! - Start tangents are not taken from the curves but forced, so that patch `k`'s
//!   corner normal is `±n_c` and its torsion-free normals along the boundary are
//!   `p`'s node axes there (a circular mesh with planar lines has, along each line,
//!   normals that are reflections of each other in the planes orthogonal to the
//!   edges — exactly the propagation of §3.2): the boundary's tangent is
//!   `t_b = m × n_c` (`m` the normal of the boundary's plane, oriented along the
//!   boundary), the continuation's is `t_b × s·n_c` (row side) or `s·n_c × t_b`
//!   (column side), `s = +1` for a last side, `−1` for a first side (the
//!   continuation then runs backwards, and the patch's normals are negated in the
//!   assembled mesh so that every node axis points to the same side).
//!
//! The forced continuation tangent always lies in the plane of `p`'s guide on the
//! same side (the Gauss row plane passes through the apex `A1` of §3.2), so a
//! continuation drawn in that plane — one planar bottom guide cut into pieces —
//! is always accepted; its own start tangent is replaced, and the angle between the
//! two is reported as [`PatchInfo::kink_deg`] (zero for a discretely C¹ bottom guide).
//! With the normals continuous along the bottom guide, its node axes are those of a
//! single torsion-free curvature line: the beams are C¹ across every seam (§4.7).
//!
//! # Layouts of several rows and columns of patches
//!
//! A patch with `guide_from` instead of `guide` takes both its guides from earlier
//! patches: its `attach` line as above, and the line on the `guide_from` side of
//! another patch, of the other kind (a column when `attach` is a row). E.g. 2 × 2:
//! patch 0 first; patch 1 attached to its last row and patch 2 to its last column,
//! each with its continuation; patch 3 attached to patch 1's last column with
//! `guide_from` patch 2's last row. Both lines start at patch 0's far corner, where
//! their node axes are both patch 0's: the lines must start at the same vertex
//! ([`MultiPatchError::CornerMismatch`]) with the same axis
//! ([`MultiPatchError::AxisMismatch`]), and then the normals continue across both
//! seams. The two lines meet at 90° only in the limit (curvature lines of a smooth
//! surface are orthogonal; on a mesh they leave the corner a little off), so each
//! start tangent is turned about the axis by half the difference
//! ([`PatchInfo::kink_deg`] reports it). Every block next to a patch must share its
//! line with it ([`MultiPatchError::Unjoined`]) and no block may stay empty
//! ([`MultiPatchError::Hole`]).
//!
//! Every patch's θ follows the README's convention in the patch's own frame (its own
//! `guide_u`, `guide_v` and start tangents as above).
//!
//! One file per idea: [`Side`] and [`Attach`] name where a patch is attached,
//! `spec` is the design file and `fit_spec` its fit, `layout` checks the design's
//! structure and places the patches in blocks, `attach` generates an attached patch,
//! `assemble` joins the patches into one grid, `build` runs them in turn, `mesh`
//! is the result and `planes` the planes of its curvature lines; `error` says why
//! a design is refused.

mod assemble;
mod attach;
mod build;
mod error;
mod fit_spec;
mod layout;
mod mesh;
mod planes;
mod side;
mod spec;

pub use attach::{Continuation, ContinuationStart};
pub use build::{build, build_with};
pub use error::MultiPatchError;
pub use fit_spec::{BoundaryRef, FitSpec, FreeParameter, GuideKey, Target};
pub use mesh::{MultiPatch, PatchInfo};
pub use planes::{LinePlane, LinePlanes};
pub use side::{Attach, Side};
pub use spec::{MultiPatchDesign, PatchSpec};
