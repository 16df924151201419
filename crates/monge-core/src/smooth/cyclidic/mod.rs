//! Cyclidic nets (§4.4): one Dupin cyclide patch on every face of a circular mesh.
//!
//! Neighbouring patches share their boundary arcs and their tangent planes (C¹),
//! every curvature line of the net is a chain of circular arcs, and on a circular
//! mesh with planar lines, with the frames of §4.4, those chains are planar (§4.4),
//! one circle or an n-arc when a guide is (§4.6, Proposition 4).
//!
//! Each patch is the quaternionic bilinear (QB) patch
//! `F(u,v) = N(u,v)·D(u,v)⁻¹`, `N = Σ p_ij W_ij B_i(u) B_j(v)`, `D = Σ W_ij B_i(u) B_j(v)`
//! (points are imaginary quaternions), and equally an exact rational biquadratic
//! Bézier patch. The whole net is one degree-(2,2) NURBS surface with double
//! interior knots (§5.3). Conventions: face `(i, j)` has corners
//! `A = (i, j)`, `B = (i+1, j)`, `C = (i+1, j+1)`, `D = (i, j+1)`; its parameter `u`
//! runs from `A` towards `B`, `v` from `A` towards `D`.

use std::fmt;

mod arcs;
mod frame;
mod net;
mod nurbs;
mod patch;
mod quat;

pub use arcs::{Arc, CurvatureLine};
pub use frame::Frame;
pub use net::CyclidicNet;
pub use nurbs::{NurbsSurface, NURBS_DEGREE};
pub use patch::{Patch, RationalBezier};

/// The two families of curvature lines of a net (§4.4).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Family {
    /// Lines along guide_u: `j` fixed, `i` running (the net's `u` direction).
    U,
    /// Lines along guide_v: `i` fixed, `j` running (the net's `v` direction).
    V,
}

impl fmt::Display for Family {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Family::U => "u-line (along guide_u, fixed j)",
            Family::V => "v-line (along guide_v, fixed i)",
        })
    }
}

/// Why a quad is folded (§4.4, §5.2). In a net, whether a face is folded is
/// decided as for every mesh, by
/// [`QuadGrid::folds`](crate::grid::QuadGrid::folds) (crossed or turned over); the
/// arc and weight reasons are those of a patch whose frame, not its face, turns it
/// over.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FoldReason {
    /// The corners do not all turn the same way
    /// ([`Turn::Crossed`](crate::grid::Turn::Crossed)): the quad is a bow-tie (two of
    /// its edges cross) or is not convex.
    Crossed,
    /// The face turns the other way than most faces of its mesh about their
    /// node axes: the mesh folds back over itself there
    /// ([`QuadGrid::folds`](crate::grid::QuadGrid::folds)).
    TurnedOver,
    /// The arc of an edge turns by 180° or more: the frame tangent at the
    /// edge's start points away from the edge (`tangent · edge = cos(half arc)` ≤ 0).
    ArcOver180 {
        /// The edge: `"AB"`, `"AD"`, `"BC"` or `"DC"`.
        edge: &'static str,
        /// The cosine of half the arc's angle.
        cos_half: f64,
    },
    /// The centre weight of the Bézier form is not positive.
    CentreWeight {
        /// The weight (relative to the corner weight at A).
        weight: f64,
    },
}

impl fmt::Display for FoldReason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FoldReason::Crossed => f.write_str(
                "its corners do not all turn the same way (two of its edges cross like a bow-tie, or it \
                 is not convex)",
            ),
            FoldReason::TurnedOver => f.write_str(
                "it turns the other way than most faces about their node axes (the mesh folds back \
                 over itself there)",
            ),
            FoldReason::ArcOver180 { edge, cos_half } => write!(
                f,
                "the arc of edge {edge} turns by {:.3}° (over 180°: cos of half the arc = {cos_half:.3e})",
                2.0 * cos_half.clamp(-1.0, 1.0).acos().to_degrees()
            ),
            FoldReason::CentreWeight { weight } => write!(
                f,
                "the centre weight of its Bézier form is {weight:.3e} (not positive)"
            ),
        }
    }
}

/// What stops a cyclidic net from being built (§4.4).
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum CyclidicError {
    /// The mesh has no face.
    #[error(
        "the mesh has {rows} × {cols} vertices and no face: a cyclidic net needs at least 2 × 2 vertices"
    )]
    TooSmall {
        /// Vertices along guide_u.
        rows: usize,
        /// Vertices along guide_v.
        cols: usize,
    },
    /// §4.4 frames need the node axes (the Gauss map) and the mesh has none.
    #[error(
        "the mesh carries no normals, so the frames of §4.4 cannot be computed from its Gauss map: \
         build the net from one given frame instead (`monge smooth --frame`, `CyclidicNet::from_frame`)"
    )]
    NoNormals,
    /// Both families have lines of only 2 vertices, so no Gauss circle is known.
    #[error(
        "the mesh has {rows} × {cols} vertices: with fewer than 3 vertices along both families the \
         planes of the Gauss circles are not determined. Use a mesh with 3 or more vertices along one \
         family, or give one frame (`monge smooth --frame`, `CyclidicNet::from_frame`)"
    )]
    GaussUndetermined {
        /// Vertices along guide_u.
        rows: usize,
        /// Vertices along guide_v.
        cols: usize,
    },
    /// The Gauss points of a line are (nearly) collinear, so its plane is unknown.
    #[error(
        "the Gauss map of {family} {index} does not span a plane: the normals of its first, middle and \
         last vertices are (nearly) collinear points, the sine of the angle at the first between the \
         other two being {sine:.1e} (below 1e-12; NaN if two coincide). The line is straight or its \
         normals do not turn. \
         Give one frame instead (`monge smooth --frame`, `CyclidicNet::from_frame`)"
    )]
    GaussLineDegenerate {
        /// The family of the line.
        family: Family,
        /// Its index (`j` for a u-line, `i` for a v-line).
        index: usize,
        /// Sine of the angle at the first Gauss point between the chords to the
        /// middle and the last (0 when the three are collinear; NaN if two coincide).
        sine: f64,
    },
    /// The two Gauss circles through a vertex are not orthogonal: the mesh is not
    /// a circular mesh with planar lines (or its normals are not its Gauss map).
    #[error(
        "at vertex ({}, {}) the tangents of the two Gauss circles make {angle_deg:.6}°, not 90° \
         (tolerance {tolerance_deg:.1e}°): the normals are not the Gauss map of a circular mesh with \
         planar lines (§2.2). Give one frame instead (`monge smooth --frame`, `CyclidicNet::from_frame`)",
        vertex.0, vertex.1
    )]
    GaussNotOrthogonal {
        /// The vertex `(i, j)`.
        vertex: (usize, usize),
        /// Angle between the tangents, degrees.
        angle_deg: f64,
        /// The tolerance, degrees.
        tolerance_deg: f64,
    },
    /// The given frame is not orthonormal.
    #[error(
        "the given frame is not orthonormal: |t1| − 1 = {t1_len:.1e}, |t2| − 1 = {t2_len:.1e}, \
         t1·t2 = {dot:.1e} (tolerance 1e-9). Normalise t1 and t2 and make them orthogonal"
    )]
    FrameNotOrthonormal {
        /// `|t1| − 1`.
        t1_len: f64,
        /// `|t2| − 1`.
        t2_len: f64,
        /// `t1 · t2`.
        dot: f64,
    },
    /// A face is not inscribed in a circle, so it carries no Dupin cyclide patch.
    #[error(
        "face ({}, {}) is not circular: its cross-ratio is off the real line by an angle of {deviation:.3e} rad \
         (tolerance {tolerance:.1e}). A cyclidic net needs a circular mesh (§2.2); raise \
         the tolerance if the mesh is only nearly circular (`monge smooth --circularity-tol`, \
         `CyclidicOptions::circularity_tolerance`)",
        face.0, face.1
    )]
    NotCircular {
        /// The face `(i, j)`.
        face: (usize, usize),
        /// `|Im q| / |q|` for the cross-ratio `q` of the corners.
        deviation: f64,
        /// The tolerance.
        tolerance: f64,
    },
    /// A face is folded.
    #[error(
        "face ({}, {}) is folded (§5.2, the fold `monge generate` and `monge check` count): {reason}. \
         A Dupin cyclide patch on it would cross itself or its neighbours; this happens for some θ with \
         tight curvature. Change θ or the guides, or build it anyway \
         (`monge smooth --allow-folded`, Python `allow_folded=True`, `CyclidicOptions::allow_folded`)",
        face.0, face.1
    )]
    Folded {
        /// The face `(i, j)`.
        face: (usize, usize),
        /// What is folded.
        reason: FoldReason,
    },
}

/// Options of [`CyclidicNet`] (§4.4).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CyclidicOptions {
    /// Build folded quads instead of refusing them. Default `false`.
    pub allow_folded: bool,
    /// Largest accepted `|Im q| / |q|` of the cross-ratio `q` of a face's corners. Default `1e-8`.
    pub circularity_tolerance: f64,
    /// Consecutive arcs of a curvature line are reported as one arc when their
    /// centres and radii agree to this fraction of the net's size and their
    /// normals to this angle (rad). Default `1e-9`.
    pub circle_tolerance: f64,
}

impl Default for CyclidicOptions {
    fn default() -> Self {
        CyclidicOptions {
            allow_folded: false,
            circularity_tolerance: 1e-8,
            circle_tolerance: 1e-9,
        }
    }
}
