//! The structure of a multi-patch design (§4.7): every patch spec's shape checked,
//! and the patches ordered along one chain of rows or columns.

use super::error::MultiPatchError;
use super::spec::MultiPatchDesign;

/// The order of the patches along the chain, known before anything is generated.
pub(super) struct Chain {
    /// Whether the patches follow each other along rows.
    pub(super) along_rows: bool,
    /// Per patch: the patch after it along the chain.
    pub(super) next: Vec<Option<usize>>,
    /// The first patch along the chain.
    pub(super) first: usize,
}

/// Check the shape of every patch spec and order the patches along the chain.
pub(super) fn check_structure(design: &MultiPatchDesign) -> Result<Chain, MultiPatchError> {
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
