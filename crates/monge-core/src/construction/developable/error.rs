//! Why a developable mesh is refused (§3.3), and which input holds a bad number.

use crate::generate::GenerateError;

use super::limits::{MAX_EXTENT, MAX_HELIX_POINTS, MIN_EXTENT, TOLERANCE};

/// Which input holds a bad number (§3.3).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Field {
    /// `helix.points[index]`.
    HelixPoint,
    /// `projection.points[index]`.
    ProjectionPoint,
    /// `projection.alpha_deg`.
    Alpha,
    /// `heights[index]`.
    Height,
    /// `reference_normal`.
    ReferenceNormal,
}

impl std::fmt::Display for Field {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Field::HelixPoint => "helix.points",
            Field::ProjectionPoint => "projection.points",
            Field::Alpha => "projection.alpha_deg",
            Field::Height => "heights",
            Field::ReferenceNormal => "reference_normal",
        })
    }
}

/// Everything that stops a developable mesh (§3.3). Lengths are compared with
/// [`TOLERANCE`] times the design size: the bounding-box diagonal of the helix
/// vertices together with the first helix vertex moved onto every cutting plane.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum DevelopableError {
    /// Neither or both of `helix` and `projection`.
    #[error(
        "the developable mesh needs exactly one of `helix` (the discrete helix's points) or \
         `projection` (a planar curve and `alpha_deg`), but {given} were given"
    )]
    CurveChoice {
        /// How many of the two were given (0 or 2).
        given: usize,
    },
    /// A NaN or infinite number.
    #[error("{field}[{index}] is not finite ({value}): give finite numbers")]
    NotFinite {
        /// The input holding it.
        field: Field,
        /// Index in that list (0 for a single value or vector).
        index: usize,
        /// The value.
        value: f64,
    },
    /// Coordinates too large or too small for the squared lengths of `f64`.
    #[error(
        "the design's largest coordinate or height is {extent:e}, outside [{MIN_EXTENT:e}, \
         {MAX_EXTENT:e}] where squared lengths overflow or underflow: rescale the design (change \
         its unit)"
    )]
    Scale {
        /// The largest absolute coordinate or height.
        extent: f64,
    },
    /// The reference normal is the zero vector.
    #[error(
        "reference_normal is [0, 0, 0]: give the normal of the reference plane, e.g. [0, 0, 1]"
    )]
    ZeroNormal,
    /// Fewer than 3 helix points.
    #[error(
        "the helix has {points} point(s), {segments} segment(s): give at least 3 points \
         (2 segments, so that two rulings meet)"
    )]
    TooFewSegments {
        /// Number of points.
        points: usize,
        /// Number of segments.
        segments: usize,
    },
    /// More than [`MAX_HELIX_POINTS`] helix points.
    #[error(
        "the helix has {points} points, more than the limit of {MAX_HELIX_POINTS} (every pair of \
         its segments is checked for crossings): give fewer points (each point is a ruling, \
         a row of panels; Figure 11 of the paper has 24)"
    )]
    TooManyPoints {
        /// Number of points.
        points: usize,
    },
    /// The mesh would have more vertices than
    /// [`GenerateOptions::max_vertices`](crate::generate::GenerateOptions::max_vertices)
    /// (always [`GenerateError::GridTooLarge`]: rows are the rulings, columns the
    /// cutting planes).
    #[error(transparent)]
    GridTooLarge(GenerateError),
    /// Fewer than 2 cutting planes.
    #[error("{heights} cutting plane height(s) given: give at least 2 in `heights`")]
    TooFewHeights {
        /// Number of heights.
        heights: usize,
    },
    /// The projection curve is not in a plane orthogonal to the reference normal.
    #[error(
        "projection.points[{index}] is {offset:.3e} off the plane of projection.points[0] along \
         the reference normal ({relative:.1e} of the design size; tolerance {TOLERANCE:.0e}): the \
         projection curve must lie in a plane parallel to the reference plane — give all points \
         the same height, or change reference_normal"
    )]
    ProjectionNotPlanar {
        /// Index of the farthest point.
        index: usize,
        /// Its signed offset along the reference normal.
        offset: f64,
        /// `|offset|` / design size.
        relative: f64,
    },
    /// Two consecutive helix points coincide.
    #[error(
        "helix points {index} and {next} coincide ({distance:.3e} apart, {relative:.1e} of the \
         design size; tolerance {TOLERANCE:.0e}): remove one of them",
        next = index + 1
    )]
    RepeatedPoint {
        /// Index of the first of the two points.
        index: usize,
        /// Their distance.
        distance: f64,
        /// Distance / design size.
        relative: f64,
    },
    /// The slope is 0°: rulings in the reference plane, parallel to the cutting planes.
    #[error(
        "the helix slope is α = {alpha_deg}°: its rulings lie parallel to the reference plane and \
         never cross the cutting planes; give a slope away from 0° (|α| > {TOLERANCE:.0e} rad)"
    )]
    Flat {
        /// The slope, in degrees.
        alpha_deg: f64,
    },
    /// The slope is 90°: rulings parallel to the reference normal (a cylinder).
    #[error(
        "the helix slope is α = {alpha_deg}°: its rulings are orthogonal to the reference plane \
         (a cylinder, whose rulings do not meet); give |α| < 90° (by more than {TOLERANCE:.0e} rad)"
    )]
    Vertical {
        /// The slope, in degrees.
        alpha_deg: f64,
    },
    /// |α| > 90°.
    #[error(
        "projection.alpha_deg = {alpha_deg}° is outside (−90°, 90°): give the angle of the helix \
         segments with the reference plane, negative for a descending helix"
    )]
    AlphaOutOfRange {
        /// The given slope, in degrees.
        alpha_deg: f64,
    },
    /// The segments do not all make the same angle with the reference plane.
    #[error(
        "the helix segments must all make the same angle with the reference plane, but segment \
         {segment} (points {segment}..{next}) makes {angle_deg:.9}° while the mean slope is \
         {alpha_deg:.9}° (sin α off by {deviation:.3e} relative; tolerance {TOLERANCE:.0e}). Move \
         the points, or give the projection curve and `alpha_deg` instead",
        next = segment + 1
    )]
    NonConstantSlope {
        /// The worst segment.
        segment: usize,
        /// Its angle with the reference plane, in degrees.
        angle_deg: f64,
        /// The mean slope `atan(Σ rise / Σ horizontal length)`, in degrees.
        alpha_deg: f64,
        /// `|sin angle − sin α|` / the length-weighted mean of `|sin angle|`.
        deviation: f64,
    },
    /// Two consecutive segments are collinear: their rulings coincide.
    #[error(
        "helix segments {before} and {vertex} are collinear (they turn by {turn_deg:.3e}° at \
         vertex {vertex}; tolerance {TOLERANCE:.0e} rad): their rulings coincide and the faces \
         between them are flat; remove vertex {vertex} or bend the curve there",
        before = vertex - 1
    )]
    Straight {
        /// The helix vertex between the two segments.
        vertex: usize,
        /// The turning angle of the projection there, in degrees.
        turn_deg: f64,
    },
    /// The projection of the helix onto the reference plane crosses (or touches) itself.
    #[error(
        "the projection curve crosses itself: segments {a} (points {a}..{a1}) and {b} (points \
         {b}..{b1}) come {distance:.3e} close ({relative:.1e} of the design size; tolerance \
         {TOLERANCE:.0e}); its projection must not cross itself — remove or move points",
        a1 = a + 1,
        b1 = b + 1
    )]
    SelfCrossing {
        /// The first segment.
        a: usize,
        /// The second segment.
        b: usize,
        /// Their distance in the reference plane.
        distance: f64,
        /// Distance / design size.
        relative: f64,
    },
    /// The heights are not strictly monotonic (or two consecutive are equal).
    #[error(
        "heights[{index}] = {height} does not continue the order of the heights (heights[{prev}] \
         = {previous}; gap tolerance {TOLERANCE:.0e} of the design size): give distinct heights \
         in increasing or decreasing order",
        prev = index - 1
    )]
    HeightsNotMonotonic {
        /// Index of the offending height.
        index: usize,
        /// `heights[index − 1]`.
        previous: f64,
        /// `heights[index]`.
        height: f64,
    },
    /// A cutting plane passes through a helix vertex where two rulings meet.
    #[error(
        "heights[{height_index}] = {height} is the height of helix vertex {vertex} ({vertex_height}; \
         {relative:.1e} of the design size apart, tolerance {TOLERANCE:.0e}), where rulings \
         {before} and {vertex} meet: the cut hits the helix and the faces between those rulings \
         degenerate to triangles. Move the plane off the helix",
        before = vertex - 1
    )]
    HeightAtHelixVertex {
        /// Index of the height.
        height_index: usize,
        /// The height.
        height: f64,
        /// The helix vertex (1 ..= segments − 1).
        vertex: usize,
        /// Its height.
        vertex_height: f64,
        /// `|height − vertex_height|` / design size.
        relative: f64,
    },
    /// Two consecutive cutting planes lie on both sides of a helix vertex.
    #[error(
        "helix vertex {vertex} (height {vertex_height}) lies between heights[{j}] = {below} and \
         heights[{j1}] = {above}: the face between rulings {before} and {vertex} would cross \
         itself at the helix (a folded quad). Keep every helix vertex where two rulings meet \
         (vertices 1 to segments − 1) outside the range of the heights",
        j1 = j + 1,
        before = vertex - 1
    )]
    FaceCrossesHelix {
        /// The helix vertex.
        vertex: usize,
        /// Its height.
        vertex_height: f64,
        /// Index of the first of the two heights.
        j: usize,
        /// `heights[j]`.
        below: f64,
        /// `heights[j + 1]`.
        above: f64,
    },
}
