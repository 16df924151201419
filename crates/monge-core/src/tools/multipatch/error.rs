//! Why a multi-patch design cannot be built (§4.7): its structure, a boundary
//! that cannot continue, or a patch that cannot be generated.

use crate::design::Xyz;
use crate::generate::GenerateError;
use crate::guide::GuideError;

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
