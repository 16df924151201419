//! Why a multi-patch design cannot be built (§4.7): its structure, a boundary
//! that cannot continue, or a patch that cannot be generated.

use crate::design::Xyz;
use crate::generate::GenerateError;
use crate::guide::GuideError;

use super::side::Attach;

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
    #[error("patch {patch} is attached to an earlier patch: it needs `attach` and `guide` (the continuation) \
             or `guide_from`, and no `guide_u` or `guide_v` ({problem})")]
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
    /// The patches leave a block of their layout empty: the mesh would not be one grid.
    #[error("incompatible boundaries: the {patches} patches lie in a layout of {} × {} blocks (rows × columns \
             of patches) but block {missing:?} has no patch, so they do not make one grid; add a patch there \
             (attached to one neighbour, with `guide_from` the other), or attach all patches along rows, or all \
             along columns", blocks.0, blocks.1)]
    Hole {
        /// Block rows and columns of the layout.
        blocks: (usize, usize),
        /// The first empty block (row, column).
        missing: (usize, usize),
        /// Patches in the design.
        patches: usize,
    },
    /// `guide_from` names a line that does not pass through the patch's corner.
    #[error("incompatible boundaries: patch {patch} is attached to the {attach_side} of patch {to}, but its \
             `guide_from`, the {side} of patch {from}, is not the other line through that corner (it must be a \
             {} side of the patch next to patch {patch} across it, starting at the same vertex)",
             if attach_side.ends_with("row") { "column" } else { "row" })]
    GuideFromElsewhere {
        /// The patch.
        patch: usize,
        /// The side named by `guide_from`.
        side: &'static str,
        /// The patch named by `guide_from`.
        from: usize,
        /// The side named by `attach`.
        attach_side: &'static str,
        /// The patch named by `attach`.
        to: usize,
    },
    /// A patch lies next to an earlier one without sharing its line.
    #[error("incompatible boundaries: patch {patch} lies next to patch {other} but takes neither guide from the \
             {kind} between them, so the two would meet along two different lines; give patch {patch} \
             `guide_from` that {kind} of patch {other} (or attach it there)")]
    Unjoined {
        /// The later patch.
        patch: usize,
        /// The earlier neighbour.
        other: usize,
        /// `row` or `column`.
        kind: &'static str,
    },
    /// The two lines of a `guide_from` patch do not start at the same vertex.
    #[error("incompatible boundaries: patch {patch}'s two guides, the {} of patch {} and the {} of patch {}, \
             start {distance:.3e} apart ({relative:.1e} of the size; tolerance {tolerance:.0e}), at {corner:?} \
             and {other:?}; they must start at the same vertex",
             attach.side.name(), attach.patch, from.side.name(), from.patch)]
    CornerMismatch {
        /// The patch.
        patch: usize,
        /// Its `attach`.
        attach: Attach,
        /// Its `guide_from`.
        from: Attach,
        /// First vertex of the attached line.
        corner: Xyz,
        /// First vertex of the `guide_from` line.
        other: Xyz,
        /// Their distance.
        distance: f64,
        /// The distance relative to the larger line's size.
        relative: f64,
        /// [`Tolerances::start`](crate::design::Tolerances::start).
        tolerance: f64,
    },
    /// The two lines of a `guide_from` patch have different node axes at their corner.
    #[error("incompatible boundaries: patch {patch}'s two guides, the {} of patch {} and the {} of patch {}, \
             have node axes {axis:?} and {other:?} at their common corner, {angle:.3e} rad apart (tolerance \
             {tolerance:.0e}): the normals could not continue across both seams",
             attach.side.name(), attach.patch, from.side.name(), from.patch)]
    AxisMismatch {
        /// The patch.
        patch: usize,
        /// Its `attach`.
        attach: Attach,
        /// Its `guide_from`.
        from: Attach,
        /// Node axis of the attached line at the corner, in the new patch's orientation.
        axis: Xyz,
        /// Node axis of the `guide_from` line there.
        other: Xyz,
        /// Angle between them.
        angle: f64,
        /// [`Tolerances::angle`](crate::design::Tolerances::angle).
        tolerance: f64,
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
        /// [`Tolerances::start`](crate::design::Tolerances::start).
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
