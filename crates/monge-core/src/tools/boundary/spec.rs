//! The boundary planes a designer asks for (§4.5) and what aligning refuses.

use serde::{Deserialize, Serialize};

use crate::design::Xyz;

/// Largest angle (radians) by which the directions of P1 ∩ P2 and P3 ∩ P4 may miss
/// 90°, and by which façade planes may miss vertical / parallel / orthogonal.
pub const ANGLE_TOLERANCE: f64 = 1e-10;

/// Largest distance of a boundary line from its plane, relative to the mesh size,
/// that [`align`](super::align) accepts for a candidate.
pub const BOUNDARY_TOLERANCE: f64 = 1e-9;

/// A plane as written in an alignment file: a point of it and a normal (need not be unit).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlaneSpec {
    /// A point of the plane.
    pub point: Xyz,
    /// A normal of the plane (non-zero; its sign does not matter).
    pub normal: Xyz,
}

/// How much each façade guide rises between its two horizontal ends (§4.5, Figure 16).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Rise {
    /// Height gained along guide_u (from the corner to P2); may be negative, not zero.
    pub guide_u: f64,
    /// Height gained along guide_v (from the corner to P4); may be negative, not zero.
    pub guide_v: f64,
}

/// The input of [`align`](super::align): four boundary planes and optional choices (§4.5).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoundarySpec {
    /// P1: holds the first row (`i = 0`), i.e. guide_v.
    pub first_row: PlaneSpec,
    /// P2: holds the last row (`i = rows − 1`).
    pub last_row: PlaneSpec,
    /// P3: holds the first column (`j = 0`), i.e. guide_u.
    pub first_column: PlaneSpec,
    /// P4: holds the last column (`j = cols − 1`).
    pub last_column: PlaneSpec,
    /// θ of the design; without it, [`align`](super::align) chooses one (see the module docs).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub theta_deg: Option<f64>,
    /// The guides' common start point; projected onto the line P1 ∩ P3. Default:
    /// the point of that line nearest to the mean of the four planes' points.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub corner: Option<Xyz>,
    /// Samples per guide; [`AlignOptions::samples`](super::AlignOptions::samples) when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub samples: Option<usize>,
    /// Façade case only: the guides' rises. Default: a quarter of each guide's run.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rise: Option<Rise>,
    /// The façade case (four vertical planes, a rectangle in plan, Figure 16).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub facade: bool,
}

/// Why four planes cannot be aligned with (§4.5).
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum AlignError {
    /// A plane's point or normal is not finite, or its normal is zero.
    #[error("{plane}: the {what} is {value:?}; give finite numbers and a non-zero normal")]
    InvalidPlane {
        /// `first_row`, `last_row`, `first_column` or `last_column`.
        plane: &'static str,
        /// `point` or `normal`.
        what: &'static str,
        /// The value given.
        value: Xyz,
    },
    /// Two planes whose intersection line is needed are parallel.
    #[error(
        "{first} and {second} are parallel (their normals make {angle_deg:.3e}°): their intersection \
         line, the axis of the pencil of the {family}, does not exist. Tilt one of them{hint}"
    )]
    ParallelPlanes {
        /// The first plane.
        first: &'static str,
        /// The second plane.
        second: &'static str,
        /// Angle between the normals, in degrees (0 or near 180 folded to near 0).
        angle_deg: f64,
        /// `rows` or `columns`.
        family: &'static str,
        /// A hint (the façade option for vertical rectangles).
        hint: &'static str,
    },
    /// The directions of P1 ∩ P2 and P3 ∩ P4 are not orthogonal.
    #[error(
        "the intersection lines first_row ∩ last_row (direction {d12:?}) and first_column ∩ \
         last_column (direction {d34:?}) make {angle_deg:.9}°, off 90° by {off_deg:.3e}° (tolerance \
         {tolerance_deg:.1e}°): a mesh with planar curvature lines fits four planes only if these \
         directions are orthogonal (§4.5). Turn one plane about its line with the other pair's plane"
    )]
    NotOrthogonal {
        /// Unit direction of P1 ∩ P2.
        d12: Xyz,
        /// Unit direction of P3 ∩ P4.
        d34: Xyz,
        /// Angle between them, degrees.
        angle_deg: f64,
        /// `|angle − 90°|`.
        off_deg: f64,
        /// The tolerance, degrees.
        tolerance_deg: f64,
    },
    /// A corner of the mesh (a row plane meeting a column plane) does not exist.
    #[error(
        "the corner {row_plane} ∩ {column_plane} does not exist: the planes are parallel (normals \
         {angle_deg:.3e}° apart), so the {what} cannot end there. Make every row plane cross every \
         column plane"
    )]
    NoCorner {
        /// The row plane.
        row_plane: &'static str,
        /// The column plane.
        column_plane: &'static str,
        /// Angle between the normals, degrees.
        angle_deg: f64,
        /// Which boundary line needed it.
        what: &'static str,
    },
    /// No θ gives an aligned mesh (or the θ asked for does not).
    #[error("no admissible θ: {detail}")]
    NoAdmissibleTheta {
        /// θ asked for, if any.
        requested: Option<f64>,
        /// What was tried and why it failed.
        detail: String,
    },
    /// Façade: a plane is not vertical.
    #[error(
        "--facade needs vertical planes, but {plane} is tilted {tilt_deg:.3e}° from vertical \
         (normal {normal:?} has a z component). Give normals with z = 0, or leave out --facade"
    )]
    NotVertical {
        /// The plane.
        plane: &'static str,
        /// Tilt, degrees.
        tilt_deg: f64,
        /// Its normal as given.
        normal: Xyz,
    },
    /// Façade: the planes do not form a rectangle in plan.
    #[error(
        "--facade needs the planes to form a rectangle in plan (first_row ∥ last_row, first_column \
         ∥ last_column, first_row ⊥ first_column), but {what} is off by {off_deg:.3e}°. For planes \
         in general position leave out --facade"
    )]
    NotRectangle {
        /// Which condition fails.
        what: &'static str,
        /// By how much, degrees.
        off_deg: f64,
    },
    /// Façade: a guide has no run or no rise.
    #[error("--facade: {guide} {problem}")]
    Facade {
        /// The guide.
        guide: &'static str,
        /// What is wrong.
        problem: String,
    },
    /// Fewer than 3 samples per guide, or more than the vertex limit allows.
    #[error(
        "samples is {given}: give 3 to {max} samples per guide (the mesh has samples² vertices, \
         at most the {} a generated mesh may have)",
        max * max
    )]
    Samples {
        /// Samples given.
        given: usize,
        /// The most samples whose square is within the generator's vertex limit.
        max: usize,
    },
}

/// Names of P1 … P4 as in the file format.
pub const PLANE_NAMES: [&str; 4] = ["first_row", "last_row", "first_column", "last_column"];
