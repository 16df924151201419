//! Multi-patch meshes with piecewise planar curvature lines (§4.7, Figures 20 and 21).
//!
//! A first patch is generated from two guides and its own θ; every further patch
//! takes a boundary line of an earlier patch as one guide, continues the other
//! guide from the boundary's first vertex, and has its own θ. The patches follow
//! each other along one grid direction, so the result is one [`QuadGrid`] whose
//! shared lines are stored once: they are identical, bit for bit, in both patches.
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
//! Every patch's θ follows the README's convention in the patch's own frame (its own
//! `guide_u`, `guide_v` and start tangents as above).

use glam::DVec3;
use nalgebra::Matrix3;
use serde::{Deserialize, Serialize};

use crate::design::{Design, GuideSpec, MeshKind, Tolerances, Xyz};
use crate::gauss_map::ThetaRange;
use crate::generate::{check_grid_size, generate, GenerateError, GenerateOptions, Generated, Mode};
use crate::guide::{Guide, GuideError, GuideName};
use crate::symmetry::SymmetrySpec;
use crate::QuadGrid;

mod fit_spec;

pub use fit_spec::{BoundaryRef, FitSpec, FreeParameter, GuideKey, Target};

/// A side of a patch's grid whose line another patch takes as a guide (§4.7).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Side {
    /// Row 0, the patch's `guide_v`; the new patch continues `guide_u` backwards.
    FirstRow,
    /// Row `rows − 1`; the new patch continues `guide_u` forwards.
    LastRow,
    /// Column 0, the patch's `guide_u`; the new patch continues `guide_v` backwards.
    FirstColumn,
    /// Column `cols − 1`; the new patch continues `guide_v` forwards.
    LastColumn,
}

impl Side {
    /// Whether the side is a row (the patches then follow each other along `i`) (§4.7).
    pub fn is_row(self) -> bool {
        matches!(self, Side::FirstRow | Side::LastRow)
    }

    /// Whether the side is a last row or column (§4.7).
    pub fn is_last(self) -> bool {
        matches!(self, Side::LastRow | Side::LastColumn)
    }

    /// The name used in design files (§4.7).
    pub fn name(self) -> &'static str {
        match self {
            Side::FirstRow => "first_row",
            Side::LastRow => "last_row",
            Side::FirstColumn => "first_column",
            Side::LastColumn => "last_column",
        }
    }
}

/// Where a patch is attached: a side of an earlier patch (§4.7).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Attach {
    /// Index of the earlier patch in [`MultiPatchDesign::patches`].
    pub patch: usize,
    /// Which of its sides.
    pub side: Side,
}

/// One patch of a multi-patch design (§4.7).
///
/// The first patch gives `guide_u` and `guide_v` (a [`Design`]'s guides); every
/// other patch gives `attach` and `guide`, the continuation (see the module docs).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PatchSpec {
    /// The patch's θ in degrees, in its own frame (README convention).
    pub theta_deg: f64,
    /// First patch only: its `guide_u`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub guide_u: Option<GuideSpec>,
    /// First patch only: its `guide_v`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub guide_v: Option<GuideSpec>,
    /// Later patches: the side of an earlier patch whose line is one guide.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub attach: Option<Attach>,
    /// Later patches: the continuation guide, starting at the boundary's first vertex.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub guide: Option<GuideSpec>,
}

/// A multi-patch design file (§4.7): patches, and optionally a fit (§4.7,
/// [`crate::optimise`]) and symmetries (§4.5, [`crate::symmetry`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MultiPatchDesign {
    /// The patches, first one first; each later one attaches to an earlier one.
    pub patches: Vec<PatchSpec>,
    /// Input tolerances of every patch (`None`: [`Tolerances::default`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tolerance: Option<Tolerances>,
    /// The fit run by `monge fit` ([`crate::optimise::fit`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fit: Option<FitSpec>,
    /// Mirrors and rotations applied, in order, to assemble the whole structure
    /// ([`crate::symmetry::assemble`]); empty: the multi-patch mesh alone.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub symmetry: Vec<SymmetrySpec>,
}

/// Why a multi-patch design cannot be built (§4.7).
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum MultiPatchError {
    /// `patches` is empty.
    #[error("the design has no patches: give at least one patch with `theta_deg`, `guide_u` and `guide_v`")]
    NoPatches,
    /// The first patch lacks a guide, or has `attach`/`guide`.
    #[error("patch 0 is the first patch: it needs `guide_u` and `guide_v`, and no `attach` or `guide` ({problem})")]
    FirstPatch {
        /// What is wrong.
        problem: &'static str,
    },
    /// A later patch lacks `attach` or `guide`, or has `guide_u`/`guide_v`.
    #[error("patch {patch} is attached to an earlier patch: it needs `attach` and `guide` (the continuation), \
             and no `guide_u` or `guide_v` ({problem})")]
    LaterPatch {
        /// The patch.
        patch: usize,
        /// What is wrong.
        problem: &'static str,
    },
    /// `attach.patch` is not an earlier patch.
    #[error("patch {patch} attaches to patch {to}, which is not an earlier patch: attach to one of patches 0..{patch}")]
    AttachNotEarlier {
        /// The patch.
        patch: usize,
        /// The patch it names.
        to: usize,
    },
    /// Rows and columns are mixed: the patches would not form one grid.
    #[error("incompatible boundaries: patch {patch} attaches to the {side} of patch {to}, but patch {first} \
             attaches to a {first_kind}; all patches must follow each other along rows, or all along columns, \
             to make one grid")]
    MixedSides {
        /// The patch.
        patch: usize,
        /// Its side's name.
        side: &'static str,
        /// The patch it attaches to.
        to: usize,
        /// The first attached patch.
        first: usize,
        /// `row` or `column`.
        first_kind: &'static str,
    },
    /// The side is already shared with another patch.
    #[error("incompatible boundaries: the {side} of patch {to} is already shared with patch {taken_by}, so patch \
             {patch} cannot attach there; attach it to a free side (the far side of the last patch)")]
    SideTaken {
        /// The patch.
        patch: usize,
        /// The side's name.
        side: &'static str,
        /// The patch it attaches to.
        to: usize,
        /// The patch already there.
        taken_by: usize,
    },
    /// The boundary line cannot serve as a guide.
    #[error("incompatible boundary: the {side} of patch {to} cannot be the guide of patch {patch}: {source}")]
    Boundary {
        /// The patch.
        patch: usize,
        /// The side's name.
        side: &'static str,
        /// The patch it attaches to.
        to: usize,
        /// Why.
        source: GuideError,
    },
    /// The continuation guide is invalid.
    #[error("patch {patch}: {source}")]
    Guide {
        /// The patch.
        patch: usize,
        /// Why.
        source: GuideError,
    },
    /// The continuation does not start at the corner.
    #[error("incompatible boundary: patch {patch}'s `guide` starts at {start:?}, but the {side} of patch {to} starts \
             at {corner:?}, {distance:.3e} away ({relative:.1e} of the size; tolerance {tolerance:.0e}); \
             start the continuation at that corner")]
    StartMismatch {
        /// The patch.
        patch: usize,
        /// The side's name.
        side: &'static str,
        /// The patch it attaches to.
        to: usize,
        /// First sample of the continuation.
        start: Xyz,
        /// The corner.
        corner: Xyz,
        /// Their distance.
        distance: f64,
        /// The distance relative to the larger size.
        relative: f64,
        /// [`Tolerances::start`].
        tolerance: f64,
    },
    /// The continuation's plane does not contain the forced start tangent.
    #[error("incompatible boundary: patch {patch}'s `guide` must start along {tangent:?} (orthogonal to the node axis \
             {axis:?} and to the boundary) for the normals to continue across the seam, but its plane (normal \
             {plane_normal:?}) makes {angle_deg:.3e}° with that direction; draw it in a plane containing that \
             direction, e.g. the plane of patch {to}'s guide on that side")]
    TangentOffPlane {
        /// The patch.
        patch: usize,
        /// The patch it attaches to.
        to: usize,
        /// The forced tangent.
        tangent: Xyz,
        /// The node axis at the corner.
        axis: Xyz,
        /// Normal of the continuation's plane.
        plane_normal: Xyz,
        /// Angle between the tangent and the plane.
        angle_deg: f64,
    },
    /// The continuation starts against the forced tangent.
    #[error("incompatible boundary: patch {patch}'s `guide` leaves the corner against the direction {tangent:?} \
             in which it must continue patch {to}'s guide (it folds back over patch {to}); continue the guide \
             beyond the boundary instead")]
    TurnsBack {
        /// The patch.
        patch: usize,
        /// The patch it attaches to.
        to: usize,
        /// The forced tangent.
        tangent: Xyz,
    },
    /// Generating a patch failed.
    #[error("patch {patch}: {source}")]
    Generate {
        /// The patch.
        patch: usize,
        /// Why.
        source: GenerateError,
    },
}

/// A patch of a built [`MultiPatch`] (§4.7).
#[derive(Clone, Debug)]
pub struct PatchInfo {
    /// The exact design the patch was generated from (for attached patches: the
    /// boundary and the continuation as `points` guides with their forced tangents).
    pub design: Design,
    /// First and last index, along the chain direction ([`MultiPatch::along_rows`]:
    /// rows, else columns), of the patch in the assembled grid (inclusive).
    pub range: (usize, usize),
    /// Whether the patch runs backwards in the assembled grid (its own `i`, or `j`
    /// for column chains, decreasing); its normals are then negated there.
    pub reversed: bool,
    /// The patch's own grid size `(rows, cols)`.
    pub size: (usize, usize),
    /// The generation mode of the patch (§3.1 or §3.2).
    pub mode: Mode,
    /// The admissible θ of the patch, given the patches it is attached to (§3.2).
    pub theta_range: ThetaRange,
    /// Folded faces found by the Combescure transform (§5.2).
    pub folded_faces: usize,
    /// Largest distance, relative to the assembled grid's size, between the shared
    /// line as this patch generated it and the earlier patch's line kept in the
    /// grid (round-off of the plane projection of the guide; 0 for the first patch).
    pub seam_gap: f64,
    /// Largest difference between this patch's node axes along the shared line and
    /// the earlier patch's (continuity of the normals, §4.7; 0 for the first patch).
    pub axis_gap: f64,
    /// Angle in degrees between the continuation's own start tangent and the forced
    /// one (0 for the first patch): the kink the continuation would have had.
    pub kink_deg: f64,
}

/// A multi-patch mesh (§4.7): one grid and where each patch lies in it.
#[derive(Clone, Debug)]
pub struct MultiPatch {
    /// The assembled grid; shared lines are stored once.
    pub grid: QuadGrid,
    /// Whether the patches follow each other along rows (index `i`), else columns.
    pub along_rows: bool,
    /// The patches, in design order.
    pub patches: Vec<PatchInfo>,
}

/// A least-squares plane of one piece of a curvature line (§4.7).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct LinePlane {
    /// The patch the piece belongs to.
    pub patch: usize,
    /// First and last vertex of the piece along the line (inclusive).
    pub vertices: (usize, usize),
    /// Unit normal of the plane.
    pub normal: Xyz,
    /// A point of the plane (the centroid of the piece).
    pub point: Xyz,
    /// Largest distance of a vertex of the piece from the plane, relative to the grid's size.
    pub deviation: f64,
}

/// The planes a curvature line lies in, one per patch it crosses (§4.7).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LinePlanes {
    /// `true` for row `index` (vertices `(index, 0..cols)`), `false` for column `index`.
    pub row: bool,
    /// The row or column index in the assembled grid.
    pub index: usize,
    /// One plane per patch the line runs through (a shared line has one per patch it bounds).
    pub planes: Vec<LinePlane>,
}

impl MultiPatch {
    /// Assembled-grid index of vertex `(i, j)` of patch `k`'s own grid (§4.7).
    pub fn own_to_grid(&self, k: usize, i: usize, j: usize) -> (usize, usize) {
        let p = &self.patches[k];
        let (along, across) = if self.along_rows { (i, j) } else { (j, i) };
        let n = if self.along_rows { p.size.0 } else { p.size.1 };
        let along = p.range.0 + if p.reversed { n - 1 - along } else { along };
        if self.along_rows {
            (along, across)
        } else {
            (across, along)
        }
    }

    /// Patch `k` as its own grid, cut out of the assembled one (shared lines with
    /// the bits of the assembled grid), with the normals of the assembled grid
    /// negated back if the patch is reversed, so that it can be measured (§4.7).
    pub fn patch_grid(&self, k: usize) -> QuadGrid {
        let (rows, cols) = self.patches[k].size;
        let sign = if self.patches[k].reversed { -1.0 } else { 1.0 };
        let mut vertices = Vec::with_capacity(rows * cols);
        let mut normals = Vec::with_capacity(rows * cols);
        for i in 0..rows {
            for j in 0..cols {
                let (a, b) = self.own_to_grid(k, i, j);
                let g = self.grid.index(a, b);
                vertices.push(self.grid.vertices[g]);
                normals.push(sign * self.grid.normals[g]);
            }
        }
        QuadGrid::new(rows, cols, vertices, normals)
    }

    /// The line on `side` of patch `k`, in the patch's own order (§4.7).
    pub fn boundary(&self, k: usize, side: Side) -> Vec<DVec3> {
        let (rows, cols) = self.patches[k].size;
        let at = |i: usize, j: usize| {
            let (a, b) = self.own_to_grid(k, i, j);
            self.grid.vertex(a, b)
        };
        match side {
            Side::FirstRow => (0..cols).map(|j| at(0, j)).collect(),
            Side::LastRow => (0..cols).map(|j| at(rows - 1, j)).collect(),
            Side::FirstColumn => (0..rows).map(|i| at(i, 0)).collect(),
            Side::LastColumn => (0..rows).map(|i| at(i, cols - 1)).collect(),
        }
    }

    /// For every row and column of the assembled grid, the planes it lies in: one
    /// per patch it runs through (§4.7). Lines across the seams lie in one plane per
    /// patch; lines of a single patch in one plane (two entries for a shared line).
    /// A piece of two vertices lies in many planes: the one reported contains it.
    pub fn line_planes(&self) -> Vec<LinePlanes> {
        let scale = self.grid.bbox_diagonal().max(f64::MIN_POSITIVE);
        let mut out = Vec::with_capacity(self.grid.rows + self.grid.cols);
        for row in [true, false] {
            let count = if row { self.grid.rows } else { self.grid.cols };
            for index in 0..count {
                let mut planes = Vec::new();
                for (k, p) in self.patches.iter().enumerate() {
                    let (lo, hi) = p.range;
                    // A line along the chain crosses every patch; a line across it lies in those whose range holds it.
                    let crosses = row != self.along_rows;
                    let (from, to) = if crosses {
                        (lo, hi)
                    } else if (lo..=hi).contains(&index) {
                        let n = if row { self.grid.cols } else { self.grid.rows };
                        (0, n - 1)
                    } else {
                        continue;
                    };
                    let points: Vec<DVec3> = (from..=to)
                        .map(|t| {
                            if row {
                                self.grid.vertex(index, t)
                            } else {
                                self.grid.vertex(t, index)
                            }
                        })
                        .collect();
                    let (point, normal, dev) = fit_plane(&points);
                    planes.push(LinePlane {
                        patch: k,
                        vertices: (from, to),
                        normal: normal.to_array(),
                        point: point.to_array(),
                        deviation: dev / scale,
                    });
                }
                planes.sort_by_key(|p| p.vertices.0);
                out.push(LinePlanes { row, index, planes });
            }
        }
        out
    }
}

/// Least-squares plane of `points`: (centroid, unit normal, largest distance).
fn fit_plane(points: &[DVec3]) -> (DVec3, DVec3, f64) {
    let origin = points[0];
    let centroid = points.iter().map(|p| *p - origin).sum::<DVec3>() / points.len() as f64 + origin;
    let mut cov = Matrix3::<f64>::zeros();
    for p in points {
        let d = *p - centroid;
        let d = nalgebra::Vector3::new(d.x, d.y, d.z);
        cov += d * d.transpose();
    }
    let eig = cov.symmetric_eigen();
    let k = eig.eigenvalues.imin();
    let v = eig.eigenvectors.column(k);
    let mut normal = DVec3::new(v[0], v[1], v[2]).normalize_or_zero();
    if normal == DVec3::ZERO {
        normal = DVec3::Z;
    }
    let dev = points
        .iter()
        .map(|p| (*p - centroid).dot(normal).abs())
        .fold(0.0, f64::max);
    (centroid, normal, dev)
}

/// One generated patch before assembly.
struct Built {
    generated: Generated,
    design: Design,
    /// `+1` or `−1`: the patch's normals relative to the first patch's orientation.
    sign: f64,
    parent: Option<usize>,
    seam_gap_abs: f64,
    axis_gap: f64,
    kink_deg: f64,
}

/// Build a multi-patch mesh (§4.7): every patch in design order, then one grid.
///
/// ```
/// use monge_core::multipatch::{build, Attach, MultiPatchDesign, PatchSpec, Side};
/// use monge_core::{GenerateOptions, GuideSpec};
/// let arc = |c: [f64; 3], s: [f64; 3], n: [f64; 3], a: f64| GuideSpec::arc(c, s, n, a, 7);
/// let design = MultiPatchDesign {
///     patches: vec![
///         PatchSpec { theta_deg: 30.0, guide_u: Some(arc([0.0, 0.0, -4.0], [0.0; 3], [0.0, -1.0, 0.0], 20.0)),
///                     guide_v: Some(arc([0.0, 0.0, -3.0], [0.0; 3], [1.0, 0.0, 0.0], 25.0)), attach: None, guide: None },
///         PatchSpec { theta_deg: -20.0, guide_u: None, guide_v: None,
///                     attach: Some(Attach { patch: 0, side: Side::LastRow }),
///                     guide: Some(arc([0.0, 0.0, -4.0], [-4.0 * 20f64.to_radians().sin(), 0.0, 4.0 * 20f64.to_radians().cos() - 4.0],
///                                     [0.0, -1.0, 0.0], 20.0)) },
///     ],
///     tolerance: None, fit: None, symmetry: vec![],
/// };
/// let mp = build(&design, &GenerateOptions::default()).unwrap();
/// assert_eq!((mp.grid.rows, mp.grid.cols), (13, 7));
/// assert_eq!(mp.boundary(0, Side::LastRow), mp.boundary(1, Side::FirstRow));
/// ```
pub fn build(
    design: &MultiPatchDesign,
    options: &GenerateOptions,
) -> Result<MultiPatch, MultiPatchError> {
    let tol = design.tolerance.unwrap_or_default();
    let chain = check_structure(design)?;
    let mut built: Vec<Built> = Vec::with_capacity(design.patches.len());
    for (k, spec) in design.patches.iter().enumerate() {
        let Some(attach) = spec.attach else {
            let d = Design {
                theta_deg: spec.theta_deg,
                guide_u: spec.guide_u.clone().expect("checked"),
                guide_v: spec.guide_v.clone().expect("checked"),
                mesh: MeshKind::Circular,
                tolerance: design.tolerance,
            };
            let generated = generate(&d, options)
                .map_err(|source| MultiPatchError::Generate { patch: k, source })?;
            built.push(Built {
                generated,
                design: d,
                sign: 1.0,
                parent: None,
                seam_gap_abs: 0.0,
                axis_gap: 0.0,
                kink_deg: 0.0,
            });
            continue;
        };
        let parent = &built[attach.patch];
        built.push(attach_patch(
            k,
            spec,
            attach,
            parent,
            &tol,
            design.tolerance,
            options,
        )?);
    }
    Ok(assemble(built, &chain))
}

/// The order of the patches along the chain, known before anything is generated.
struct Chain {
    /// Whether the patches follow each other along rows.
    along_rows: bool,
    /// Per patch: the patch after it along the chain.
    next: Vec<Option<usize>>,
    /// The first patch along the chain.
    first: usize,
}

/// Check the shape of every patch spec and order the patches along the chain.
fn check_structure(design: &MultiPatchDesign) -> Result<Chain, MultiPatchError> {
    let Some(first) = design.patches.first() else {
        return Err(MultiPatchError::NoPatches);
    };
    let problem = match (&first.guide_u, &first.guide_v, &first.attach, &first.guide) {
        (None, _, _, _) => Some("`guide_u` is missing"),
        (_, None, _, _) => Some("`guide_v` is missing"),
        (_, _, Some(_), _) => Some("it has `attach`"),
        (_, _, _, Some(_)) => Some("it has `guide`"),
        _ => None,
    };
    if let Some(problem) = problem {
        return Err(MultiPatchError::FirstPatch { problem });
    }
    let n = design.patches.len();
    let mut sign = vec![1.0; n];
    let mut prev: Vec<Option<usize>> = vec![None; n];
    let mut next: Vec<Option<usize>> = vec![None; n];
    let mut axis: Option<(usize, bool)> = None;
    for (k, p) in design.patches.iter().enumerate().skip(1) {
        let problem = match (&p.attach, &p.guide, &p.guide_u, &p.guide_v) {
            (None, _, _, _) => Some("`attach` is missing"),
            (_, None, _, _) => Some("`guide` is missing"),
            (_, _, Some(_), _) => Some("it has `guide_u`"),
            (_, _, _, Some(_)) => Some("it has `guide_v`"),
            _ => None,
        };
        if let Some(problem) = problem {
            return Err(MultiPatchError::LaterPatch { patch: k, problem });
        }
        let a = p.attach.expect("checked");
        let to = a.patch;
        if to >= k {
            return Err(MultiPatchError::AttachNotEarlier { patch: k, to });
        }
        match axis {
            None => axis = Some((k, a.side.is_row())),
            Some((first, rows)) if rows != a.side.is_row() => {
                return Err(MultiPatchError::MixedSides {
                    patch: k,
                    side: a.side.name(),
                    to,
                    first,
                    first_kind: if rows { "row" } else { "column" },
                })
            }
            Some(_) => {}
        }
        sign[k] = sign[to] * if a.side.is_last() { 1.0 } else { -1.0 };
        // The patch comes after the one it is attached to iff it runs forwards.
        let slot = if sign[k] > 0.0 {
            &mut next[to]
        } else {
            &mut prev[to]
        };
        if let Some(taken_by) = *slot {
            return Err(MultiPatchError::SideTaken {
                patch: k,
                side: a.side.name(),
                to,
                taken_by,
            });
        }
        *slot = Some(k);
        if sign[k] > 0.0 {
            prev[k] = Some(to);
        } else {
            next[k] = Some(to);
        }
    }
    Ok(Chain {
        along_rows: axis.is_none_or(|(_, rows)| rows),
        next,
        first: (0..n)
            .find(|&k| prev[k].is_none())
            .expect("a chain has a first patch"),
    })
}

/// The line on `side` of a patch's own grid, with its node axes.
fn own_line(grid: &QuadGrid, side: Side) -> (Vec<DVec3>, Vec<DVec3>) {
    let idx: Vec<usize> = match side {
        Side::FirstRow => (0..grid.cols).map(|j| grid.index(0, j)).collect(),
        Side::LastRow => (0..grid.cols)
            .map(|j| grid.index(grid.rows - 1, j))
            .collect(),
        Side::FirstColumn => (0..grid.rows).map(|i| grid.index(i, 0)).collect(),
        Side::LastColumn => (0..grid.rows)
            .map(|i| grid.index(i, grid.cols - 1))
            .collect(),
    };
    (
        idx.iter().map(|&k| grid.vertices[k]).collect(),
        idx.iter().map(|&k| grid.normals[k]).collect(),
    )
}

/// Generate patch `k` attached to `attach` of `parent` (see the module docs).
fn attach_patch(
    k: usize,
    spec: &PatchSpec,
    attach: Attach,
    parent: &Built,
    tol: &Tolerances,
    tolerance: Option<Tolerances>,
    options: &GenerateOptions,
) -> Result<Built, MultiPatchError> {
    let to = attach.patch;
    let side = attach.side;
    let (line, axes) = own_line(&parent.generated.grid, side);
    let boundary_name = if side.is_row() {
        GuideName::V
    } else {
        GuideName::U
    };
    let boundary_points: Vec<Xyz> = line.iter().map(|p| p.to_array()).collect();
    let boundary_spec = GuideSpec::points(boundary_points.clone());
    let boundary = Guide::from_spec(&boundary_spec, boundary_name, tol).map_err(|source| {
        MultiPatchError::Boundary {
            patch: k,
            side: side.name(),
            to,
            source,
        }
    })?;
    let (corner, n_c) = (line[0], axes[0]);
    let mut t_b = boundary.plane_normal.cross(n_c).normalize();
    if t_b.dot(line[1] - line[0]) < 0.0 {
        t_b = -t_b;
    }
    let n_target = if side.is_last() { n_c } else { -n_c };
    let t_cont = if side.is_row() {
        t_b.cross(n_target)
    } else {
        n_target.cross(t_b)
    }
    .normalize();
    let cont_name = if side.is_row() {
        GuideName::U
    } else {
        GuideName::V
    };
    let cont_spec = spec.guide.as_ref().expect("checked");
    // The patch's grid, refused before its guide is sampled if too large.
    let (rows, cols) = if side.is_row() {
        (cont_spec.sample_count(), line.len())
    } else {
        (line.len(), cont_spec.sample_count())
    };
    check_grid_size(rows, cols, options)
        .map_err(|source| MultiPatchError::Generate { patch: k, source })?;
    let cont = Guide::from_spec(cont_spec, cont_name, tol)
        .map_err(|source| MultiPatchError::Guide { patch: k, source })?;
    let size = cont.size.max(boundary.size);
    let distance = cont.points[0].distance(corner);
    let relative = distance / size;
    if relative.is_nan() || relative > tol.start {
        return Err(MultiPatchError::StartMismatch {
            patch: k,
            side: side.name(),
            to,
            start: cont.points[0].to_array(),
            corner: corner.to_array(),
            distance,
            relative,
            tolerance: tol.start,
        });
    }
    let off = t_cont.dot(cont.plane_normal).abs();
    if off > tol.angle.sin() {
        return Err(MultiPatchError::TangentOffPlane {
            patch: k,
            to,
            tangent: t_cont.to_array(),
            axis: n_c.to_array(),
            plane_normal: cont.plane_normal.to_array(),
            angle_deg: off.clamp(0.0, 1.0).asin().to_degrees(),
        });
    }
    if t_cont.dot(cont.points[1] - corner) <= 0.0 {
        return Err(MultiPatchError::TurnsBack {
            patch: k,
            to,
            tangent: t_cont.to_array(),
        });
    }
    let kink_deg = cont
        .tangent
        .dot(t_cont)
        .clamp(-1.0, 1.0)
        .acos()
        .to_degrees();
    let mut cont_points: Vec<Xyz> = cont.points.iter().map(|p| p.to_array()).collect();
    cont_points[0] = corner.to_array();
    let cont_guide = GuideSpec::Points {
        points: cont_points,
        tangent: Some(t_cont.to_array()),
    };
    let boundary_guide = GuideSpec::Points {
        points: boundary_points,
        tangent: Some(t_b.to_array()),
    };
    let (guide_u, guide_v) = if side.is_row() {
        (cont_guide, boundary_guide)
    } else {
        (boundary_guide, cont_guide)
    };
    let design = Design {
        theta_deg: spec.theta_deg,
        guide_u,
        guide_v,
        mesh: MeshKind::Circular,
        tolerance,
    };
    let generated = generate(&design, options)
        .map_err(|source| MultiPatchError::Generate { patch: k, source })?;
    // The shared line as the child generated it: its guide on the boundary side.
    let child_side = if side.is_row() {
        Side::FirstRow
    } else {
        Side::FirstColumn
    };
    let (own, own_axes) = own_line(&generated.grid, child_side);
    let seam_gap_abs = own
        .iter()
        .zip(&line)
        .map(|(a, b)| a.distance(*b))
        .fold(0.0, f64::max);
    let s = if side.is_last() { 1.0 } else { -1.0 };
    let axis_gap = own_axes
        .iter()
        .zip(&axes)
        .map(|(a, b)| (s * *a).distance(*b))
        .fold(0.0, f64::max);
    Ok(Built {
        generated,
        design,
        sign: s * parent.sign,
        parent: Some(to),
        seam_gap_abs,
        axis_gap,
        kink_deg,
    })
}

/// Assemble the patches into one grid along the chain.
fn assemble(built: Vec<Built>, chain: &Chain) -> MultiPatch {
    let along_rows = chain.along_rows;
    // Every patch as a grid whose rows run along the chain, forwards, with normals
    // in the first patch's orientation.
    let canonical: Vec<QuadGrid> = built
        .iter()
        .map(|b| {
            let g = &b.generated.grid;
            let g = if along_rows {
                g.clone()
            } else {
                g.transposed()
            };
            let (rows, cols) = (g.rows, g.cols);
            let order: Vec<usize> = if b.sign > 0.0 {
                (0..rows).collect()
            } else {
                (0..rows).rev().collect()
            };
            let pick = |v: &[DVec3], scale: f64| -> Vec<DVec3> {
                order
                    .iter()
                    .flat_map(|&i| v[i * cols..(i + 1) * cols].iter().map(move |x| scale * *x))
                    .collect()
            };
            QuadGrid::new(rows, cols, pick(&g.vertices, 1.0), pick(&g.normals, b.sign))
        })
        .collect();
    let mut order = Vec::with_capacity(built.len());
    let mut k = chain.first;
    order.push(k);
    while let Some(n) = chain.next[k] {
        order.push(n);
        k = n;
    }
    let cols = canonical[0].cols;
    let mut vertices: Vec<DVec3> = Vec::new();
    let mut normals: Vec<DVec3> = Vec::new();
    let mut ranges = vec![(0, 0); built.len()];
    for (pos, &k) in order.iter().enumerate() {
        let g = &canonical[k];
        let mut first = 0;
        if pos > 0 && built[k].parent == Some(order[pos - 1]) {
            first = 1; // keep the parent's (earlier) copy of the shared line
        } else if pos > 0 {
            // The patch before was attached to this one: keep this one's copy.
            vertices.truncate(vertices.len() - cols);
            normals.truncate(normals.len() - cols);
        }
        let start = vertices.len() / cols - first;
        vertices.extend_from_slice(&g.vertices[first * cols..]);
        normals.extend_from_slice(&g.normals[first * cols..]);
        ranges[k] = (start, vertices.len() / cols - 1);
    }
    let rows = vertices.len() / cols;
    let mut grid = QuadGrid::new(rows, cols, vertices, normals);
    if !along_rows {
        grid = grid.transposed();
    }
    let scale = grid.bbox_diagonal().max(f64::MIN_POSITIVE);
    let patches = built
        .into_iter()
        .zip(ranges)
        .map(|(b, range)| PatchInfo {
            size: (b.generated.grid.rows, b.generated.grid.cols),
            mode: b.generated.info.mode,
            theta_range: b.generated.info.theta_range,
            folded_faces: b.generated.report.folded_faces,
            design: b.design,
            range,
            reversed: b.sign < 0.0,
            seam_gap: b.seam_gap_abs / scale,
            axis_gap: b.axis_gap,
            kink_deg: b.kink_deg,
        })
        .collect();
    MultiPatch {
        grid,
        along_rows,
        patches,
    }
}
