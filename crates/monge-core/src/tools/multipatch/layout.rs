//! The layout of a multi-patch design (§4.7): every patch spec's shape checked, and
//! each patch placed in a rectangle of blocks, known before anything is generated.

use super::error::MultiPatchError;
use super::side::{Attach, Side};
use super::spec::MultiPatchDesign;

/// Where a patch lies among the blocks, and which way its own grid runs there.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Placement {
    /// Block row and column.
    pub(super) block: (usize, usize),
    /// Whether the patch's own `i` (then `j`) runs against the layout's.
    pub(super) flip: (bool, bool),
}

impl Placement {
    /// `+1` or `−1`: the patch's normals relative to the first patch's orientation.
    pub(super) fn sign(&self) -> f64 {
        if self.flip.0 == self.flip.1 {
            1.0
        } else {
            -1.0
        }
    }
}

/// The patches placed in a rectangle of blocks.
pub(super) struct Layout {
    /// Block rows and block columns.
    pub(super) blocks: (usize, usize),
    /// Per patch, in design order.
    pub(super) placements: Vec<Placement>,
}

/// A placement before the blocks are counted from the rectangle's corner.
#[derive(Clone, Copy, PartialEq, Eq)]
struct Raw {
    block: (isize, isize),
    flip: (bool, bool),
}

/// Where a patch attached to `side` of a patch placed at `parent` lies.
fn beyond(parent: Raw, side: Side) -> Raw {
    let own = if side.is_last() { 1 } else { -1 };
    let (mut block, mut flip) = (parent.block, parent.flip);
    if side.is_row() {
        block.0 += if parent.flip.0 { -own } else { own };
        flip.0 ^= !side.is_last();
    } else {
        block.1 += if parent.flip.1 { -own } else { own };
        flip.1 ^= !side.is_last();
    }
    Raw { block, flip }
}

/// Check the shape of every patch spec and place the patches in blocks.
pub(super) fn check_layout(design: &MultiPatchDesign) -> Result<Layout, MultiPatchError> {
    let Some(first) = design.patches.first() else {
        return Err(MultiPatchError::NoPatches);
    };
    let problem = match (&first.guide_u, &first.guide_v, &first.attach, &first.guide) {
        (None, _, _, _) => Some("`guide_u` is missing"),
        (_, None, _, _) => Some("`guide_v` is missing"),
        (_, _, Some(_), _) => Some("it has `attach`"),
        (_, _, _, Some(_)) => Some("it has `guide`"),
        _ if first.guide_from.is_some() => Some("it has `guide_from`"),
        _ => None,
    };
    if let Some(problem) = problem {
        return Err(MultiPatchError::FirstPatch { problem });
    }
    let mut raw = vec![Raw {
        block: (0, 0),
        flip: (false, false),
    }];
    for (k, p) in design.patches.iter().enumerate().skip(1) {
        let problem = match (&p.attach, &p.guide, &p.guide_from, &p.guide_u, &p.guide_v) {
            (None, _, _, _, _) => Some("`attach` is missing"),
            (_, None, None, _, _) => Some("`guide` (or `guide_from`) is missing"),
            (_, Some(_), Some(_), _, _) => Some("it has both `guide` and `guide_from`"),
            (_, _, _, Some(_), _) => Some("it has `guide_u`"),
            (_, _, _, _, Some(_)) => Some("it has `guide_v`"),
            _ => None,
        };
        if let Some(problem) = problem {
            return Err(MultiPatchError::LaterPatch { patch: k, problem });
        }
        let a = p.attach.expect("checked");
        let earlier = |to: Attach| {
            if to.patch >= k {
                Err(MultiPatchError::AttachNotEarlier {
                    patch: k,
                    to: to.patch,
                })
            } else {
                Ok(beyond(raw[to.patch], to.side))
            }
        };
        let here = earlier(a)?;
        if let Some(from) = p.guide_from {
            let there = earlier(from)?;
            if from.side.is_row() == a.side.is_row() || there != here {
                return Err(MultiPatchError::GuideFromElsewhere {
                    patch: k,
                    side: from.side.name(),
                    from: from.patch,
                    attach_side: a.side.name(),
                    to: a.patch,
                });
            }
        }
        if let Some(taken_by) = raw.iter().position(|r| r.block == here.block) {
            return Err(MultiPatchError::SideTaken {
                patch: k,
                side: a.side.name(),
                to: a.patch,
                taken_by,
            });
        }
        // Every earlier neighbour must share its line with this patch.
        for (j, r) in raw.iter().enumerate() {
            let (di, dj) = (r.block.0 - here.block.0, r.block.1 - here.block.1);
            if di.abs() + dj.abs() != 1 {
                continue;
            }
            let joined = [Some(a), p.guide_from]
                .into_iter()
                .flatten()
                .any(|t| t.patch == j && beyond(*r, t.side).block == here.block);
            if !joined {
                return Err(MultiPatchError::Unjoined {
                    patch: k,
                    other: j,
                    kind: if di != 0 { "row" } else { "column" },
                });
            }
        }
        raw.push(here);
    }
    let low = raw.iter().fold((isize::MAX, isize::MAX), |(a, b), r| {
        (a.min(r.block.0), b.min(r.block.1))
    });
    let high = raw.iter().fold((isize::MIN, isize::MIN), |(a, b), r| {
        (a.max(r.block.0), b.max(r.block.1))
    });
    let blocks = ((high.0 - low.0 + 1) as usize, (high.1 - low.1 + 1) as usize);
    let placements: Vec<Placement> = raw
        .iter()
        .map(|r| Placement {
            block: ((r.block.0 - low.0) as usize, (r.block.1 - low.1) as usize),
            flip: r.flip,
        })
        .collect();
    if placements.len() < blocks.0 * blocks.1 {
        let missing = (0..blocks.0)
            .flat_map(|a| (0..blocks.1).map(move |b| (a, b)))
            .find(|b| placements.iter().all(|p| p.block != *b))
            .expect("a block is empty");
        return Err(MultiPatchError::Hole {
            blocks,
            missing,
            patches: placements.len(),
        });
    }
    Ok(Layout { blocks, placements })
}
