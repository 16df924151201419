//! Why a guide is refused (§3), and where its start tangent comes from, for messages.

use std::fmt;

use super::GuideName;

/// Where a guide's start tangent comes from (§3), for messages.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TangentSource {
    /// The `tangent` given with `points`.
    Given,
    /// `P1 − P0` of a `bspline`'s control points.
    ControlPolygon,
    /// `normal × (start − center)` of an `arc`.
    Arc,
    /// The `tangent` of a `parabola`.
    Parabola,
    /// The tangent of the circle through the first three `points` (or the first chord).
    Circle,
}

impl fmt::Display for TangentSource {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            TangentSource::Given => "`tangent`",
            TangentSource::ControlPolygon => "P1 − P0 of `bspline.control_points`",
            TangentSource::Arc => "`arc.normal` × (`arc.start` − `arc.center`)",
            TangentSource::Parabola => "`parabola.tangent`",
            TangentSource::Circle => "(of the circle through the first three `points`)",
        })
    }
}

impl TangentSource {
    /// How to fix a zero tangent from this source.
    fn zero_fix(self) -> &'static str {
        match self {
            TangentSource::Given => "Give a non-zero `tangent`, or omit it",
            TangentSource::ControlPolygon => "Make the first two control points distinct",
            TangentSource::Arc => "Give a non-zero `arc.normal` and a positive radius",
            TangentSource::Parabola => "Give a non-zero `parabola.tangent`",
            TangentSource::Circle => "Remove repeated points",
        }
    }

    /// Whether a tangent from this source can leave the guide's plane: the
    /// others lie in it by construction (up to rounding) and are only projected.
    pub(super) fn may_leave_plane(self) -> bool {
        matches!(self, TangentSource::Given | TangentSource::ControlPolygon)
    }

    /// How to fix a tangent that leaves the guide's plane.
    fn plane_fix(self) -> &'static str {
        match self {
            TangentSource::Given => "Give a `tangent` in the plane of the points, or omit it",
            TangentSource::ControlPolygon => "Put all control points in one plane",
            TangentSource::Arc => "Make `arc.normal` orthogonal to `arc.start` − `arc.center`",
            TangentSource::Parabola => "Check `parabola.tangent` and `parabola.quadratic`",
            TangentSource::Circle => "Put all points in one plane",
        }
    }
}

/// Why a guide curve is refused (§3): what is wrong, where, by how much, and
/// how to fix it.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum GuideError {
    /// `parameters` does not have one value per sample.
    #[error(
        "{guide}: `parameters` has {count} values but `bspline.samples` is {samples}: give one parameter per sample."
    )]
    ParameterCount {
        /// The guide.
        guide: GuideName,
        /// Number of parameters given.
        count: usize,
        /// `bspline.samples`.
        samples: usize,
    },
    /// `parameters` is not strictly increasing.
    #[error(
        "{guide}: `parameters` must increase strictly, but entry {index} is {value} after {previous}."
    )]
    ParametersNotIncreasing {
        /// The guide.
        guide: GuideName,
        /// Index of the offending entry.
        index: usize,
        /// The entry before it.
        previous: f64,
        /// The entry.
        value: f64,
    },
    /// A parameter lies outside the knot range.
    #[error(
        "{guide}: `parameters` entry {index} is {value}, outside the curve's parameter range [{lo}, {hi}] (first and last knot)."
    )]
    ParameterOutOfRange {
        /// The guide.
        guide: GuideName,
        /// Index of the entry.
        index: usize,
        /// The entry.
        value: f64,
        /// First knot.
        lo: f64,
        /// Last knot.
        hi: f64,
    },
    /// Fewer than 2 points or samples.
    #[error(
        "{guide} has {count} sample(s) (from `{field}`); a guide needs at least 2, and at least 3 to be curved. Give more points or raise the number of samples."
    )]
    TooFewSamples {
        /// The guide.
        guide: GuideName,
        /// The key that sets the number of samples (`points`, `bspline.samples`, …).
        field: &'static str,
        /// The number of samples given.
        count: usize,
    },
    /// A number is NaN or infinite.
    #[error("{guide}: {} Replace it by a finite number.", non_finite_place(.field, .index))]
    NonFinite {
        /// The guide.
        guide: GuideName,
        /// The key holding the number (`points`, `arc.center`, …), or `samples`
        /// when a computed sample overflows.
        field: &'static str,
        /// The entry of a list (point, control point, knot, weight, sample).
        index: Option<usize>,
    },
    /// The bounding box of the samples is too large to measure.
    #[error(
        "{guide} is too large: its bounding-box diagonal overflows ({size}). Scale the design down."
    )]
    Overflow {
        /// The guide.
        guide: GuideName,
        /// The (infinite) bounding-box diagonal.
        size: f64,
    },
    /// Two consecutive samples coincide (a zero-length edge).
    #[error(
        "{guide}: samples {index} and {} coincide ({distance:.1e} apart, a zero-length edge). Remove the repeated point.",
        .index + 1
    )]
    RepeatedPoint {
        /// The guide.
        guide: GuideName,
        /// The first of the two samples.
        index: usize,
        /// Their distance.
        distance: f64,
    },
    /// All samples lie on one line.
    #[error(
        "{guide} is a straight line (all samples lie within {deviation:.1e} of its size from one line): it has no plane and no curvature. A guide must be curved: bend it in its plane."
    )]
    Straight {
        /// The guide.
        guide: GuideName,
        /// Largest distance of a sample from the best-fit line, relative to the guide's size.
        deviation: f64,
    },
    /// The samples do not lie in one plane within [`crate::design::Tolerances::planarity`].
    #[error(
        "{guide} is not planar: sample {index} is {deviation:.1e} from the best-fit plane ({relative:.1e} of the guide's size; tolerance {tolerance:e}). {}",
        crate::grid::tolerance_fix(*origin_ratio, *relative, "planarity", "Put all points of a guide in one plane")
    )]
    NotPlanar {
        /// The guide.
        guide: GuideName,
        /// The sample farthest from the plane.
        index: usize,
        /// Its distance from the plane.
        deviation: f64,
        /// That distance relative to the guide's size.
        relative: f64,
        /// [`crate::design::Tolerances::planarity`].
        tolerance: f64,
        /// How far the guide lies from the origin compared with its size
        /// ([`crate::grid::origin_ratio`] of its samples): far away, the
        /// rounding of the coordinates alone makes it non-planar.
        origin_ratio: f64,
    },
    /// The start tangent is zero.
    #[error("{guide}: the start tangent {from} is zero. {}.", .from.zero_fix())]
    ZeroTangent {
        /// The guide.
        guide: GuideName,
        /// Where the tangent comes from.
        from: TangentSource,
    },
    /// The start tangent leaves the guide's plane by more than [`crate::design::Tolerances::angle`].
    #[error(
        "{guide}: the start tangent {from} leaves the guide's plane by {angle:.1e} rad (tolerance {tolerance:e} rad). {}",
        crate::grid::tolerance_fix(*origin_ratio, *angle, "angle", .from.plane_fix())
    )]
    TangentNotInPlane {
        /// The guide.
        guide: GuideName,
        /// Where the tangent comes from.
        from: TangentSource,
        /// Angle between the tangent and the plane, in radians.
        angle: f64,
        /// [`crate::design::Tolerances::angle`].
        tolerance: f64,
        /// How far the guide lies from the origin compared with its size
        /// ([`crate::grid::origin_ratio`] of its samples).
        origin_ratio: f64,
    },
    /// `bspline.degree` is 0.
    #[error(
        "{guide}: `bspline.degree` is 0; a B-spline guide needs degree 1 or more (2 or 3 is usual)."
    )]
    ZeroDegree {
        /// The guide.
        guide: GuideName,
    },
    /// `bspline.degree` is above [`MAX_DEGREE`](super::MAX_DEGREE).
    #[error(
        "{guide}: `bspline.degree` is {degree}, above the largest accepted, {max}: a sample of a \
         B-spline costs about degree² operations (degree {degree}: {} per sample), and CAD \
         systems stop far below (Rhino at 11; guides are usually of degree 2 or 3). Lower the \
         degree: a curve of many control points is given as well at degree 3.",
        .degree.saturating_mul(*.degree)
    )]
    DegreeTooHigh {
        /// The guide.
        guide: GuideName,
        /// The degree given.
        degree: usize,
        /// [`MAX_DEGREE`](super::MAX_DEGREE).
        max: usize,
    },
    /// Fewer than `degree + 1` control points.
    #[error(
        "{guide}: a B-spline of degree {degree} needs more than {degree} control points; `bspline.control_points` has {count}. Add control points or lower the degree."
    )]
    TooFewControlPoints {
        /// The guide.
        guide: GuideName,
        /// The number of control points.
        count: usize,
        /// The degree.
        degree: usize,
    },
    /// The knot vector does not have `control points + degree + 1` entries.
    #[error(
        "{guide}: `bspline.knots` has {count} values, but {control_points} control points of degree {degree} need {expected} (control points + degree + 1). Fix the knots, or omit them for clamped uniform knots."
    )]
    KnotCount {
        /// The guide.
        guide: GuideName,
        /// The number of knots given.
        count: usize,
        /// The number of knots needed.
        expected: usize,
        /// The number of control points.
        control_points: usize,
        /// The degree.
        degree: usize,
    },
    /// A knot is smaller than the one before.
    #[error(
        "{guide}: `bspline.knots` decrease at index {index} ({previous} then {value}). Knots must be non-decreasing."
    )]
    KnotsDecreasing {
        /// The guide.
        guide: GuideName,
        /// The index of the smaller knot.
        index: usize,
        /// The knot before it.
        previous: f64,
        /// The knot.
        value: f64,
    },
    /// All knots are equal: the parameter range is empty.
    #[error(
        "{guide}: all `bspline.knots` are equal ({value}), so the curve's parameter range is empty. Give increasing knots, or omit them."
    )]
    EmptyKnotSpan {
        /// The guide.
        guide: GuideName,
        /// The common value.
        value: f64,
    },
    /// The first or last knot is not repeated exactly `degree + 1` times.
    #[error(
        "{guide}: `bspline.knots` are not clamped at the {end}: the {end} knot must be repeated exactly degree + 1 = {} times, it is repeated {multiplicity} times. Clamp the knots, or omit them.",
        .degree + 1
    )]
    KnotsNotClamped {
        /// The guide.
        guide: GuideName,
        /// `"start"` or `"end"`.
        end: &'static str,
        /// How often the end knot is repeated.
        multiplicity: usize,
        /// The degree.
        degree: usize,
    },
    /// An interior knot is repeated more than `degree` times (the curve breaks apart there).
    #[error(
        "{guide}: the interior knot {value} (index {index}) of `bspline.knots` is repeated {multiplicity} times, more than the degree {degree}: the curve would break apart there. Repeat it at most {degree} times."
    )]
    KnotMultiplicity {
        /// The guide.
        guide: GuideName,
        /// The index of its first occurrence.
        index: usize,
        /// The knot.
        value: f64,
        /// How often it is repeated.
        multiplicity: usize,
        /// The degree.
        degree: usize,
    },
    /// `bspline.weights` does not have one entry per control point.
    #[error(
        "{guide}: `bspline.weights` has {count} values; give one per control point ({expected}), or omit them."
    )]
    WeightCount {
        /// The guide.
        guide: GuideName,
        /// The number of weights given.
        count: usize,
        /// The number of control points.
        expected: usize,
    },
    /// A weight is zero or negative.
    #[error("{guide}: `bspline.weights` entry {index} is {value}; weights must be positive.")]
    WeightNotPositive {
        /// The guide.
        guide: GuideName,
        /// The index of the weight.
        index: usize,
        /// The weight.
        value: f64,
    },
    /// `arc.normal` is zero.
    #[error("{guide}: `arc.normal` is zero. Give the normal of the arc's plane.")]
    ArcZeroNormal {
        /// The guide.
        guide: GuideName,
    },
    /// `arc.start` equals `arc.center`.
    #[error(
        "{guide}: `arc.start` equals `arc.center`, a circle of radius 0. Give a start point away from the center."
    )]
    ArcZeroRadius {
        /// The guide.
        guide: GuideName,
    },
    /// `arc.normal` is not orthogonal to `arc.start − arc.center`.
    #[error(
        "{guide}: `arc.normal` is not orthogonal to `arc.start` − `arc.center`: the angle between them differs from 90° by {angle:.1e} rad (tolerance {tolerance:e} rad). Give the normal of the plane through the center and the start point, or raise `tolerance.angle`."
    )]
    ArcNotOrthogonal {
        /// The guide.
        guide: GuideName,
        /// Deviation from 90°, in radians.
        angle: f64,
        /// [`crate::design::Tolerances::angle`].
        tolerance: f64,
    },
    /// `arc.angle_deg` is zero, or not strictly between −360 and 360.
    #[error(
        "{guide}: `arc.angle_deg` is {angle_deg}; it must be non-zero and strictly between -360 and 360."
    )]
    ArcAngle {
        /// The guide.
        guide: GuideName,
        /// The angle given.
        angle_deg: f64,
    },
}

/// Where a non-finite number is, for [`GuideError::NonFinite`].
fn non_finite_place(field: &str, index: &Option<usize>) -> String {
    match (field, index) {
        ("samples", Some(i)) => {
            format!("sample {i} is not a finite number: the curve's coordinates overflow.")
        }
        (_, Some(i)) => format!("`{field}` entry {i} is not a finite number."),
        (_, None) => format!("`{field}` is not a finite number."),
    }
}
