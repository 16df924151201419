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
//! patches before it, [`ContinuationStart`]): the plane's tilt about that tangent, the
//! second control point's distance along it and both in-plane coordinates of the
//! others are free, as in [`approximate`](super::approximate). With every patch's θ,
//! BOBYQA moves them all together from the single patch's own lines and θ, with the
//! objective of the single patch (a folded mesh counts as worse than the start by its
//! number of folded faces, never as a result). The result is the design seen closest
//! to the target by the largest distance both ways ([`Deviation::closer_than`]), the
//! single patch included (then a design of one patch).

use glam::DVec3;

use super::distance::MeshFaces;
use super::fit_guide::{guide_basis, CONTROL_POINTS};
use super::{
    ApproxError, ApproxOptions, Approximation, Deviation, PatchLayout, Progress, TargetCloud,
    OBJECTIVE_POINTS,
};
use crate::design::{GuideSpec, MeshKind, Tolerances};
use crate::generate::GenerateOptions;
use crate::grid::QuadGrid;
use crate::guide::{Guide, GuideName};
use crate::multipatch::{
    build, build_with, Attach, ContinuationStart, MultiPatch, MultiPatchDesign, PatchSpec, Side,
};

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

/// Free numbers of one guide: the plane's tilt, then the along and up coordinates of
/// the displacement's B-spline coefficients (all but the corner's).
const PER_GUIDE: usize = 1 + 2 * (CONTROL_POINTS - 1);

/// A piece of a guide in its plane: `(along, up)` of each sample from the corner, and
/// its chord-length parameter in `[0, 1]`.
#[derive(Clone, Debug)]
struct Section {
    points: Vec<(f64, f64)>,
    parameters: Vec<f64>,
}

impl Section {
    /// `piece` in the plane through its first point spanned by `tangent` and
    /// `normal × tangent`.
    fn of(piece: &[DVec3], tangent: DVec3, normal: DVec3) -> Self {
        let up = normal.cross(tangent);
        let points: Vec<(f64, f64)> = piece
            .iter()
            .map(|p| ((*p - piece[0]).dot(tangent), (*p - piece[0]).dot(up)))
            .collect();
        let mut chords = vec![0.0];
        for w in piece.windows(2) {
            chords.push(chords[chords.len() - 1] + w[0].distance(w[1]));
        }
        let total = chords[chords.len() - 1].max(f64::MIN_POSITIVE);
        Section {
            points,
            parameters: chords.iter().map(|c| c / total).collect(),
        }
    }

    /// The piece placed at `corner` in the plane containing `tangent` of normal
    /// `normal` turned about `tangent` by `p[0]`, each sample displaced in that plane
    /// by a cubic B-spline whose coefficients are `p[1..]` (the corner's is zero, so
    /// the guide starts at the corner): a `points` guide with the forced tangent.
    fn guide(&self, corner: DVec3, tangent: DVec3, normal: DVec3, p: &[f64]) -> GuideSpec {
        let m = p[0].cos() * normal + p[0].sin() * tangent.cross(normal);
        let up = m.cross(tangent);
        let points = self
            .points
            .iter()
            .zip(&self.parameters)
            .map(|((s, w), u)| {
                let b = guide_basis(*u);
                let (mut s, mut w) = (*s, *w);
                for k in 1..CONTROL_POINTS {
                    s += b[k] * p[2 * k - 1];
                    w += b[k] * p[2 * k];
                }
                (corner + s * tangent + w * up).to_array()
            })
            .collect();
        GuideSpec::Points {
            points,
            tangent: Some(tangent.to_array()),
        }
    }
}

/// A block of the layout in the single patch's grid: its rows and columns (inclusive)
/// and whether the patch's own `i` (then `j`) runs against the grid's, so that its own
/// corner `(0, 0)` is the one nearest to the layout's origin.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Block {
    rows: (usize, usize),
    cols: (usize, usize),
    flip: (bool, bool),
}

impl Block {
    /// Its own vertex `(i, j)` in the single patch's grid.
    fn at(&self, grid: &QuadGrid, i: usize, j: usize) -> usize {
        let r = if self.flip.0 {
            self.rows.1 - i
        } else {
            self.rows.0 + i
        };
        let c = if self.flip.1 {
            self.cols.1 - j
        } else {
            self.cols.0 + j
        };
        grid.index(r, c)
    }

    fn size(&self) -> (usize, usize) {
        (self.rows.1 - self.rows.0 + 1, self.cols.1 - self.cols.0 + 1)
    }

    /// Its own column 0 (its guide_u) and row 0 (its guide_v) in `grid`.
    fn lines(&self, grid: &QuadGrid) -> [Vec<DVec3>; 2] {
        let (rows, cols) = self.size();
        [
            (0..rows)
                .map(|i| grid.vertices[self.at(grid, i, 0)])
                .collect(),
            (0..cols)
                .map(|j| grid.vertices[self.at(grid, 0, j)])
                .collect(),
        ]
    }

    /// The start frame that makes a patch from [`Block::lines`] continue `grid`: the
    /// node axis at its corner (turned with the patch's orientation), and per line the
    /// start tangent in the line's plane orthogonal to that axis (oriented along the
    /// line) and the plane's normal. `None` where a line has no plane.
    fn frame(&self, grid: &QuadGrid, tol: &Tolerances) -> Option<([DVec3; 2], [DVec3; 2])> {
        let sign = if self.flip.0 == self.flip.1 {
            1.0
        } else {
            -1.0
        };
        let axis = sign * grid.normals[self.at(grid, 0, 0)];
        let lines = self.lines(grid);
        let mut tangents = [DVec3::ZERO; 2];
        let mut normals = [DVec3::ZERO; 2];
        for (k, (line, name)) in lines.iter().zip([GuideName::U, GuideName::V]).enumerate() {
            let raw = line.iter().map(|p| p.to_array()).collect();
            let m = Guide::from_spec(&GuideSpec::points(raw), name, tol)
                .ok()?
                .plane_normal;
            let t = m.cross(axis).normalize_or_zero();
            if t == DVec3::ZERO {
                return None;
            }
            tangents[k] = if t.dot(line[1] - line[0]) < 0.0 {
                -t
            } else {
                t
            };
            normals[k] = m;
        }
        Some((tangents, normals))
    }
}

/// What a patch of the layout takes its guides from.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Role {
    /// The first patch, in the origin's block: both guides free (slots 0 and 1).
    First,
    /// Attached to a side of an earlier patch, continuing a line of the cross through
    /// the origin with the free guide `slot`.
    Continue { attach: Attach, slot: usize },
    /// Attached to a side of an earlier patch, its other guide a line of another.
    Between { attach: Attach, from: Attach },
}

/// The patches of `layout` in design order: each one's block `(along guide_u, along
/// guide_v)` and its [`Role`]. The origin is the block `(u / 2, v / 2)`: the first
/// patch's corner is the middle of the layout (see the module documentation), and
/// every patch is built after its neighbours towards the origin.
fn plan(layout: PatchLayout) -> Vec<((usize, usize), Role)> {
    let origin = (layout.u / 2, layout.v / 2);
    let mut blocks: Vec<(usize, usize)> = (0..layout.u)
        .flat_map(|a| (0..layout.v).map(move |b| (a, b)))
        .collect();
    blocks.sort_by_key(|&(a, b)| (a.abs_diff(origin.0) + b.abs_diff(origin.1), a, b));
    let index = |block| blocks.iter().position(|b| *b == block).expect("a block");
    // The side of the patch in block `from` whose line the patch in the next block
    // `to` takes: a patch's own grid runs away from the origin.
    let side = |from: (usize, usize), to: (usize, usize)| {
        let (row, forward, flipped) = if from.0 == to.0 {
            (false, to.1 > from.1, from.1 < origin.1)
        } else {
            (true, to.0 > from.0, from.0 < origin.0)
        };
        let side = match (row, forward != flipped) {
            (true, true) => Side::LastRow,
            (true, false) => Side::FirstRow,
            (false, true) => Side::LastColumn,
            (false, false) => Side::FirstColumn,
        };
        Attach {
            patch: index(from),
            side,
        }
    };
    let inward = |k: usize, o: usize| if k > o { k - 1 } else { k + 1 };
    let mut slots = 2..;
    blocks
        .iter()
        .map(|&(a, b)| {
            let role = if (a, b) == origin {
                Role::First
            } else if b == origin.1 {
                Role::Continue {
                    attach: side((inward(a, origin.0), b), (a, b)),
                    slot: slots.next().expect("unbounded"),
                }
            } else if a == origin.0 {
                Role::Continue {
                    attach: side((a, inward(b, origin.1)), (a, b)),
                    slot: slots.next().expect("unbounded"),
                }
            } else {
                Role::Between {
                    attach: side((inward(a, origin.0), b), (a, b)),
                    from: side((a, inward(b, origin.1)), (a, b)),
                }
            };
            ((a, b), role)
        })
        .collect()
}

/// The layout's patches and pieces, and the design of given parameters: every θ (in
/// design order), then [`PER_GUIDE`] numbers per free guide (slot).
struct Pieces {
    /// Per patch in design order: its role.
    roles: Vec<Role>,
    /// The first patch's corner, start tangents and guide-plane normals.
    corner: DVec3,
    tangents: [DVec3; 2],
    normals: [DVec3; 2],
    /// Per slot, its piece of the single patch's lines through the origin.
    pieces: Vec<Vec<DVec3>>,
    /// Each piece in the plane of its guide: the single patch's for the first patch's
    /// two, the one its start forced at the first build for the continuations.
    sections: std::cell::RefCell<Vec<Section>>,
    tolerance: Option<Tolerances>,
}

impl Pieces {
    /// The pieces of `layout` cut from the single patch `single`, and the parameters
    /// that make the patches continue it (no displacement, its θ): every piece needs
    /// at least two faces.
    fn cut(single: &Approximation, layout: PatchLayout) -> Result<(Self, Vec<f64>), ApproxError> {
        if single.design.mesh != MeshKind::Circular {
            return Err(ApproxError::PatchesNotCircular);
        }
        let grid = &single.grid;
        for (patches, segments, along) in [
            (layout.u, grid.rows - 1, "guide_u"),
            (layout.v, grid.cols - 1, "guide_v"),
        ] {
            if patches == 0 || layout.count() < 2 || segments < 2 * patches {
                return Err(ApproxError::TooManyPatches {
                    patches,
                    segments,
                    along,
                });
            }
        }
        let tol = single.design.tolerance.unwrap_or_default();
        // The blocks: guide_u cut into `u` pieces and guide_v into `v`, of nearly equal
        // numbers of samples; each patch's own grid runs away from the origin.
        let roles = plan(layout);
        let origin = (layout.u / 2, layout.v / 2);
        let cuts = |segments: usize, n: usize, k: usize| (k * segments / n, (k + 1) * segments / n);
        let blocks: Vec<Block> = roles
            .iter()
            .map(|&((a, b), _)| Block {
                rows: cuts(grid.rows - 1, layout.u, a),
                cols: cuts(grid.cols - 1, layout.v, b),
                flip: (a < origin.0, b < origin.1),
            })
            .collect();
        let roles: Vec<Role> = roles.into_iter().map(|(_, role)| role).collect();
        let first = blocks[0];
        let (tangents, normals) = first
            .frame(grid, &tol)
            .ok_or(ApproxError::NoPatchStart { patch: 0 })?;
        // Per slot, its piece: the first patch's own lines, then each continuation's.
        let mut pieces = vec![Vec::new(); layout.u + layout.v];
        [pieces[0], pieces[1]] = first.lines(grid);
        for (role, block) in roles.iter().zip(&blocks) {
            if let Role::Continue { attach, slot } = role {
                let [line_u, line_v] = block.lines(grid);
                pieces[*slot] = if attach.side.is_row() { line_u } else { line_v };
            }
        }
        // The first patch's two pieces in its own guide planes; the continuations' once
        // their starts are known (first build).
        let sections = (0..pieces.len())
            .map(|slot| {
                let axis = slot.min(1);
                Section::of(&pieces[slot], tangents[axis], normals[axis])
            })
            .collect();
        let setup = Pieces {
            roles,
            corner: grid.vertices[first.at(grid, 0, 0)],
            tangents,
            normals,
            pieces,
            sections: std::cell::RefCell::new(sections),
            tolerance: single.design.tolerance,
        };
        let mut x0 = vec![0.0; layout.count() + (layout.u + layout.v) * PER_GUIDE];
        // The single patch's θ in every patch: each then continues it (θ is the same
        // in every block's own frame, whichever way it runs).
        x0[..layout.count()].fill(single.design.theta_deg);
        Ok((setup, x0))
    }

    /// Parameters of the free guide `slot` in `x`.
    fn slot<'x>(&self, x: &'x [f64], slot: usize) -> &'x [f64] {
        let at = self.roles.len() + slot * PER_GUIDE;
        &x[at..at + PER_GUIDE]
    }

    /// The design of `x`; the continuations are placeholders of the right number of
    /// samples, which [`Pieces::build`] replaces.
    fn design(&self, x: &[f64]) -> MultiPatchDesign {
        let sections = self.sections.borrow();
        let free = |slot: usize, axis: usize| {
            sections[slot].guide(
                self.corner,
                self.tangents[axis],
                self.normals[axis],
                self.slot(x, slot),
            )
        };
        let patches = self
            .roles
            .iter()
            .enumerate()
            .map(|(k, role)| {
                let mut spec = PatchSpec {
                    theta_deg: x[k],
                    guide_u: None,
                    guide_v: None,
                    attach: None,
                    guide: None,
                    guide_from: None,
                };
                match *role {
                    Role::First => {
                        spec.guide_u = Some(free(0, 0));
                        spec.guide_v = Some(free(1, 1));
                    }
                    Role::Continue { attach, slot } => {
                        spec.attach = Some(attach);
                        spec.guide = Some(free(slot, usize::from(!attach.side.is_row())));
                    }
                    Role::Between { attach, from } => {
                        spec.attach = Some(attach);
                        spec.guide_from = Some(from);
                    }
                }
                spec
            })
            .collect();
        MultiPatchDesign {
            patches,
            tolerance: self.tolerance,
            fit: None,
            symmetry: vec![],
        }
    }

    /// The design of `x` and its mesh, each continuation in the plane its start forces
    /// ([`ContinuationStart::plane_normal`] turned by its tilt). With `fit`, each
    /// continuation's piece is first placed in that plane (with no displacement it
    /// then continues the single patch's line).
    fn build(&self, x: &[f64], fit: bool) -> Option<(MultiPatchDesign, MultiPatch)> {
        let mut design = self.design(x);
        let mut guides: Vec<Option<GuideSpec>> = vec![None; self.roles.len()];
        let mp = build_with(
            &design,
            &GenerateOptions::default(),
            &mut |k, start: &ContinuationStart, placeholder| {
                let Role::Continue { slot, .. } = self.roles[k] else {
                    return placeholder.clone();
                };
                if fit {
                    self.sections.borrow_mut()[slot] =
                        Section::of(&self.pieces[slot], start.tangent, start.plane_normal);
                }
                let guide = self.sections.borrow()[slot].guide(
                    start.corner,
                    start.tangent,
                    start.plane_normal,
                    self.slot(x, slot),
                );
                guides[k] = Some(guide.clone());
                guide
            },
        )
        .ok()?;
        for (spec, guide) in design.patches.iter_mut().zip(guides) {
            if guide.is_some() {
                spec.guide = guide;
            }
        }
        Some((design, mp))
    }
}

/// Folded faces of a mesh (§5.2), all of them if a vertex is not finite.
fn folds(grid: &QuadGrid) -> usize {
    if grid.vertices.iter().all(|v| v.is_finite()) {
        grid.folds().count()
    } else {
        (grid.rows - 1) * (grid.cols - 1)
    }
}

/// Per patch: θ, and the distances to the mesh of the target points nearest to it.
pub(super) fn per_patch(target: &TargetCloud, mp: &MultiPatch) -> Vec<PatchFit> {
    let faces = MeshFaces::new(&mp.grid);
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
    let target = TargetCloud::new(points)?;
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
    let single_strided = target.deviation_strided(grid, stride);
    let mut evaluations = 0;
    let budget = count * 359 + options.max_evaluations.max(2 * n + 2);
    // The best point seen by the search's objective, and the closest to the target
    // (largest distance both ways, on the objective's points).
    let mut best: (f64, Option<Vec<f64>>) = (single_strided.objective(), None);
    let mut closest: (Deviation, Option<Vec<f64>>) = (single_strided, None);
    // The folded faces at `x` (all when it cannot be built) and the objective, NaN when
    // it folds or the time is up.
    let mut evaluate = |x: &[f64], fit: bool| -> (usize, f64) {
        if stop() {
            return (usize::MAX, f64::NAN);
        }
        evaluations += 1;
        let (folded, f) = match setup.build(x, fit) {
            Some((_, mp)) => match folds(&mp.grid) {
                0 => {
                    let d = target.deviation_strided(&mp.grid, stride);
                    if d.closer_than(&closest.0) {
                        closest = (d, Some(x.to_vec()));
                    }
                    (0, d.objective())
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
    // its points, if closer than the single patch.
    let mut kept: Option<(MultiPatchDesign, MultiPatch, Deviation)> = None;
    for x in [&best.1, &closest.1].into_iter().flatten() {
        let (design, mp) = setup.build(x, false).expect("the design was built");
        let after = target.deviation(&mp.grid);
        if after.closer_than(kept.as_ref().map_or(&single.after, |k| &k.2)) {
            kept = Some((design, mp, after));
        }
    }
    let (design, mp, after, out_layout) = match kept {
        Some((design, mp, after)) => (design, mp, after, layout),
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
            (design, mp, single.after, PatchLayout { u: 1, v: 1 })
        }
    };
    Ok(PatchApproximation {
        after,
        per_patch: per_patch(&target, &mp),
        before: single.after,
        design,
        layout: out_layout,
        grid: mp.grid,
        evaluations,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::approximate::approximate;

    /// A paraboloid on a 21 × 21 grid of 10 × 10, and its one-patch fit.
    fn single() -> Approximation {
        let target: Vec<DVec3> = (0..21 * 21)
            .map(|k| {
                let (x, y) = ((k % 21) as f64 * 0.5, (k / 21) as f64 * 0.5);
                DVec3::new(x, y, 0.04 * x * x + 0.1 * y * y)
            })
            .collect();
        let options = ApproxOptions {
            faces: (8, 8),
            starts: 1,
            max_evaluations: 60,
            ..Default::default()
        };
        approximate(&target, &options, &mut |_| {}).unwrap()
    }

    /// A layout's patches with the single patch's lines as guides and its θ rebuild it
    /// (every vertex, measured against the single patch's own grid), the first patch's
    /// corner in the middle; the design alone (as `monge patches` reads it) builds the
    /// same mesh.
    #[test]
    fn layouts_cut_from_one_patch_rebuild_it() {
        let single = single();
        let size = single.grid.bbox_diagonal();
        for (u, v) in [(2, 1), (1, 2), (2, 2), (3, 2), (3, 3), (4, 4)] {
            let layout = PatchLayout { u, v };
            let (pieces, x0) = Pieces::cut(&single, layout).unwrap();
            let (design, mp) = pieces.build(&x0, true).unwrap();
            assert_eq!(mp.layout, (u, v));
            assert_eq!(mp.patches[0].block, (u / 2, v / 2));
            assert_eq!(
                (mp.patches[0].rows.0, mp.patches[0].cols.0),
                ((u / 2) * 8 / u, (v / 2) * 8 / v),
            );
            let worst = mp
                .grid
                .vertices
                .iter()
                .zip(&single.grid.vertices)
                .map(|(a, b)| a.distance(*b))
                .fold(0.0, f64::max);
            assert!(worst < 1e-9 * size, "{layout}: {worst:e}");
            let again = build(&design, &GenerateOptions::default()).unwrap();
            assert_eq!(again.grid, mp.grid, "{layout}");
        }
    }
}
