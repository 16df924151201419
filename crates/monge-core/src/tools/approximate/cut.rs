//! How a layout of patches is cut from one patch (§4.7): the layout's origin in the
//! middle of the single patch's grid, each block's corner towards it, the single
//! patch's lines through the origin as the free guides' pieces ([`Pieces`]), and the
//! multi-patch design of given parameters (every θ, then each free guide's plane tilt
//! and control points).

use glam::DVec3;

use super::fit_guide::{guide_basis, CONTROL_POINTS};
use super::{ApproxError, Approximation, PatchLayout};
use crate::design::{GuideSpec, MeshKind, Tolerances};
use crate::generate::GenerateOptions;
use crate::grid::QuadGrid;
use crate::guide::{Guide, GuideName};
use crate::multipatch::{
    build_with, Attach, ContinuationStart, MultiPatch, MultiPatchDesign, PatchSpec, Side,
};

/// Free numbers of one guide: the plane's tilt, then the along and up coordinates of
/// the displacement's B-spline coefficients (all but the corner's).
pub(super) const PER_GUIDE: usize = 1 + 2 * (CONTROL_POINTS - 1);

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
pub(super) struct Pieces {
    /// Per patch in design order: its role.
    roles: Vec<Role>,
    /// The first patch's corner, start tangents and guide-plane normals.
    corner: DVec3,
    tangents: [DVec3; 2],
    normals: [DVec3; 2],
    /// Per slot, its piece of the single patch's lines through the origin.
    pub(super) pieces: Vec<Vec<DVec3>>,
    /// Each piece in the plane of its guide: the single patch's for the first patch's
    /// two, the one its start forced at the first build for the continuations.
    sections: std::cell::RefCell<Vec<Section>>,
    tolerance: Option<Tolerances>,
}

impl Pieces {
    /// The pieces of `layout` cut from the single patch `single`, and the parameters
    /// that make the patches continue it (no displacement, its θ): every piece needs
    /// at least two faces.
    pub(super) fn cut(
        single: &Approximation,
        layout: PatchLayout,
    ) -> Result<(Self, Vec<f64>), ApproxError> {
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
    pub(super) fn build(&self, x: &[f64], fit: bool) -> Option<(MultiPatchDesign, MultiPatch)> {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::approximate::{approximate, ApproxOptions};
    use crate::multipatch::build;

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
