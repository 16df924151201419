//! Guide curves (§3): sampled, validated, planar.
//!
//! A guide is given in a design as one of four kinds ([`GuideSpec`]): a
//! polyline (`points`), a clamped B-spline / NURBS (`bspline`), a circular arc
//! (`arc`) or a parabola arc (`parabola`). [`Guide::from_spec`] samples it,
//! checks everything the generator relies on (finite, no zero-length edges,
//! curved, planar within [`Tolerances::planarity`]), projects the samples onto
//! the best-fit plane and computes the unit start tangent.
//!
//! B-splines are evaluated by [`crate::bspline::Nurbs`], the rational de Boor
//! algorithm written as a chain of convex combinations of points, so that
//! clamped end points are reproduced exactly and the evaluation is accurate to a
//! few ulps.

use std::fmt;

use glam::DVec3;

use crate::bspline::Nurbs;
use crate::design::{ArcSpec, BSplineSpec, GuideSpec, ParabolaSpec, Tolerances, Xyz};

/// Relative size (to the guide's bounding-box diagonal) below which an edge is
/// of zero length and a guide is a straight line.
const DEGENERATE: f64 = 1e-12;

/// Which guide of a design (§3), for messages.
///
/// ```
/// use monge_core::guide::GuideName;
/// assert_eq!(GuideName::V.to_string(), "guide_v");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GuideName {
    /// `guide_u`.
    U,
    /// `guide_v`.
    V,
}

impl fmt::Display for GuideName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            GuideName::U => "guide_u",
            GuideName::V => "guide_v",
        })
    }
}

/// A validated, sampled planar guide curve (§3).
#[derive(Clone, Debug, PartialEq)]
pub struct Guide {
    /// The samples, projected onto the plane of [`Guide::plane_normal`] through
    /// their centroid. Samples already in it up to rounding (within
    /// `4 ε (size + max |centroid coordinate|)`) are kept bit for bit, so
    /// exactly planar input is unchanged.
    pub points: Vec<DVec3>,
    /// Unit start tangent, in the plane.
    pub tangent: DVec3,
    /// Unit normal of the guide's plane; its sign is chosen so that its
    /// largest-magnitude component (the first of equals) is positive.
    pub plane_normal: DVec3,
    /// Largest distance of an input sample from the fitted plane (absolute,
    /// before projection).
    pub planarity: f64,
    /// Bounding-box diagonal of the samples.
    pub size: f64,
}

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
    fn may_leave_plane(self) -> bool {
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
    /// None of `points`, `bspline`, `arc`, `parabola` is given.
    #[error("{guide} has no curve: give exactly one of `points`, `bspline`, `arc` or `parabola`.")]
    NoKind {
        /// The guide.
        guide: GuideName,
    },
    /// More than one of `points`, `bspline`, `arc`, `parabola` is given.
    #[error(
        "{guide} has several curves ({}): give exactly one of `points`, `bspline`, `arc` or `parabola`.",
        .found.join(", ")
    )]
    SeveralKinds {
        /// The guide.
        guide: GuideName,
        /// The keys found, in the order `points`, `bspline`, `arc`, `parabola`.
        found: Vec<&'static str>,
    },
    /// `tangent` is given with a kind other than `points`.
    #[error(
        "{guide}: `tangent` is only allowed with `points`; this guide is a `{kind}`, whose start tangent is given by the curve itself. Remove `tangent`."
    )]
    TangentWithoutPoints {
        /// The guide.
        guide: GuideName,
        /// The kind given (`bspline`, `arc` or `parabola`).
        kind: &'static str,
    },
    /// `parameters` is given with a kind other than `bspline`.
    #[error(
        "{guide}: `parameters` (sample parameters, §4.8) is only allowed with `bspline`; this guide is a `{kind}`. Remove `parameters`."
    )]
    ParametersWithoutBSpline {
        /// The guide.
        guide: GuideName,
        /// The kind given (`points`, `arc` or `parabola`).
        kind: &'static str,
    },
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
    /// The samples do not lie in one plane within [`Tolerances::planarity`].
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
        /// [`Tolerances::planarity`].
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
    /// The start tangent leaves the guide's plane by more than [`Tolerances::angle`].
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
        /// [`Tolerances::angle`].
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
    /// `bspline.degree` is above [`MAX_DEGREE`].
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
        /// [`MAX_DEGREE`].
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
        /// [`Tolerances::angle`].
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

impl Guide {
    /// Sample and validate a guide (§3).
    ///
    /// The samples are those of the spec (see [`GuideSpec`]); they must be
    /// finite, without zero-length edges, not all on one line, and in one plane
    /// within `tol.planarity` of the guide's size. They are then projected onto
    /// the least-squares plane, and the start tangent is projected into it.
    ///
    /// ```
    /// use monge_core::design::{GuideSpec, Tolerances};
    /// use monge_core::guide::{Guide, GuideName};
    /// let spec = GuideSpec::points(vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.2], [2.0, 0.0, 0.7]]);
    /// let g = Guide::from_spec(&spec, GuideName::U, &Tolerances::default()).unwrap();
    /// assert_eq!(g.points[1].z, 0.2);
    /// assert_eq!(g.plane_normal, glam::DVec3::Y);
    /// assert!(g.tangent.x > 0.99 && g.tangent.y == 0.0);
    /// ```
    pub fn from_spec(
        spec: &GuideSpec,
        name: GuideName,
        tol: &Tolerances,
    ) -> Result<Guide, GuideError> {
        let kinds = [
            ("points", spec.points.is_some()),
            ("bspline", spec.bspline.is_some()),
            ("arc", spec.arc.is_some()),
            ("parabola", spec.parabola.is_some()),
        ];
        let found: Vec<&'static str> = kinds.iter().filter(|k| k.1).map(|k| k.0).collect();
        match found.len() {
            0 => return Err(GuideError::NoKind { guide: name }),
            1 => {}
            _ => return Err(GuideError::SeveralKinds { guide: name, found }),
        }
        if spec.tangent.is_some() && found[0] != "points" {
            return Err(GuideError::TangentWithoutPoints {
                guide: name,
                kind: found[0],
            });
        }
        if spec.parameters.is_some() && found[0] != "bspline" {
            return Err(GuideError::ParametersWithoutBSpline {
                guide: name,
                kind: found[0],
            });
        }
        let (samples, tangent) = match (&spec.points, &spec.bspline, &spec.arc, &spec.parabola) {
            (Some(points), ..) => polyline(points, spec.tangent, name)?,
            (_, Some(b), ..) => sample_bspline(b, spec.parameters.as_deref(), name)?,
            (_, _, Some(a), _) => sample_arc(a, name, tol)?,
            (.., Some(p)) => sample_parabola(p, name)?,
            _ => unreachable!("exactly one kind was found above"),
        };
        finish(samples, tangent, name, tol)
    }
}

/// The samples of a spec and its start tangent, if the spec defines one
/// (`None` for a polyline without `tangent`).
type Sampled = (Vec<DVec3>, Option<(DVec3, TangentSource)>);

/// `x ≤ limit`, false if either is NaN (so a NaN tolerance refuses).
fn within(x: f64, limit: f64) -> bool {
    x <= limit
}

/// A point of a design file as a vector.
fn v(p: &Xyz) -> DVec3 {
    DVec3::from_array(*p)
}

/// `Err(NonFinite)` unless every coordinate of `p` is finite.
fn check_finite(
    p: &Xyz,
    field: &'static str,
    index: Option<usize>,
    name: GuideName,
) -> Result<(), GuideError> {
    if p.iter().all(|c| c.is_finite()) {
        Ok(())
    } else {
        Err(GuideError::NonFinite {
            guide: name,
            field,
            index,
        })
    }
}

/// `Err(TooFewSamples)` if `count < 2`.
fn check_count(count: usize, field: &'static str, name: GuideName) -> Result<(), GuideError> {
    if count < 2 {
        Err(GuideError::TooFewSamples {
            guide: name,
            field,
            count,
        })
    } else {
        Ok(())
    }
}

/// `v / |v|`, computed without overflow or underflow; `None` for the zero vector.
fn unit(v: DVec3) -> Option<DVec3> {
    let m = v.abs().max_element();
    if m == 0.0 {
        return None;
    }
    let w = v / m;
    Some(w / w.length())
}

/// The `points` kind: the points as given.
fn polyline(points: &[Xyz], tangent: Option<Xyz>, name: GuideName) -> Result<Sampled, GuideError> {
    check_count(points.len(), "points", name)?;
    for (i, p) in points.iter().enumerate() {
        check_finite(p, "points", Some(i), name)?;
    }
    let points: Vec<DVec3> = points.iter().map(v).collect();
    if let Some(t) = &tangent {
        check_finite(t, "tangent", None, name)?;
    }
    Ok((points, tangent.map(|t| (v(&t), TangentSource::Given))))
}

/// The `parabola` kind: `start + t·tangent + t²·quadratic` at `t = k / (samples − 1)`.
fn sample_parabola(p: &ParabolaSpec, name: GuideName) -> Result<Sampled, GuideError> {
    check_count(p.samples, "parabola.samples", name)?;
    check_finite(&p.start, "parabola.start", None, name)?;
    check_finite(&p.tangent, "parabola.tangent", None, name)?;
    check_finite(&p.quadratic, "parabola.quadratic", None, name)?;
    let (start, tangent, quadratic) = (v(&p.start), v(&p.tangent), v(&p.quadratic));
    if tangent == DVec3::ZERO {
        return Err(GuideError::ZeroTangent {
            guide: name,
            from: TangentSource::Parabola,
        });
    }
    let last = (p.samples - 1) as f64;
    let points = (0..p.samples)
        .map(|k| {
            let t = k as f64 / last;
            start + t * tangent + (t * t) * quadratic
        })
        .collect();
    Ok((points, Some((tangent, TangentSource::Parabola))))
}

/// The `arc` kind: `start` rotated about the axis through `center` along
/// `normal`, each sample computed directly from its angle.
fn sample_arc(a: &ArcSpec, name: GuideName, tol: &Tolerances) -> Result<Sampled, GuideError> {
    check_count(a.samples, "arc.samples", name)?;
    check_finite(&a.center, "arc.center", None, name)?;
    check_finite(&a.start, "arc.start", None, name)?;
    check_finite(&a.normal, "arc.normal", None, name)?;
    if !a.angle_deg.is_finite() {
        return Err(GuideError::NonFinite {
            guide: name,
            field: "arc.angle_deg",
            index: None,
        });
    }
    if a.angle_deg == 0.0 || a.angle_deg.abs() >= 360.0 {
        return Err(GuideError::ArcAngle {
            guide: name,
            angle_deg: a.angle_deg,
        });
    }
    let n = unit(v(&a.normal)).ok_or(GuideError::ArcZeroNormal { guide: name })?;
    let start = v(&a.start);
    let r = start - v(&a.center);
    let r_unit = unit(r).ok_or(GuideError::ArcZeroRadius { guide: name })?;
    // Deviation from 90° of the angle between the normal and the radius.
    let off = libm::asin(n.dot(r_unit).abs().min(1.0));
    if !within(off, tol.angle) {
        return Err(GuideError::ArcNotOrthogonal {
            guide: name,
            angle: off,
            tolerance: tol.angle,
        });
    }
    // Rodrigues' rotation, written as a displacement from `start` so that
    // sample 0 is `start` exactly: R(φ)r − r = sin φ (n × r) − 2 sin²(φ/2) r⊥.
    let side = n.cross(r);
    let r_perp = r - n * n.dot(r);
    let step = a.angle_deg.to_radians() / (a.samples - 1) as f64;
    let points = (0..a.samples)
        .map(|k| {
            let phi = step * k as f64;
            let half = libm::sin(0.5 * phi);
            start + libm::sin(phi) * side - (2.0 * half * half) * r_perp
        })
        .collect();
    let tangent = side * a.angle_deg.signum();
    Ok((points, Some((tangent, TangentSource::Arc))))
}

/// Checks a knot vector for `count` control points of `degree` (see [`BSplineSpec`]).
fn check_knots(
    knots: &[f64],
    count: usize,
    degree: usize,
    name: GuideName,
) -> Result<(), GuideError> {
    let expected = count + degree + 1;
    if knots.len() != expected {
        return Err(GuideError::KnotCount {
            guide: name,
            count: knots.len(),
            expected,
            control_points: count,
            degree,
        });
    }
    if let Some(i) = knots.iter().position(|k| !k.is_finite()) {
        return Err(GuideError::NonFinite {
            guide: name,
            field: "bspline.knots",
            index: Some(i),
        });
    }
    if let Some(i) = (1..knots.len()).find(|&i| knots[i] < knots[i - 1]) {
        return Err(GuideError::KnotsDecreasing {
            guide: name,
            index: i,
            previous: knots[i - 1],
            value: knots[i],
        });
    }
    let (first, last) = (knots[0], knots[knots.len() - 1]);
    if first == last {
        return Err(GuideError::EmptyKnotSpan {
            guide: name,
            value: first,
        });
    }
    let at_start = knots.iter().take_while(|&&k| k == first).count();
    let at_end = knots.iter().rev().take_while(|&&k| k == last).count();
    for (end, multiplicity) in [("start", at_start), ("end", at_end)] {
        if multiplicity != degree + 1 {
            return Err(GuideError::KnotsNotClamped {
                guide: name,
                end,
                multiplicity,
                degree,
            });
        }
    }
    let mut i = at_start;
    while i < knots.len() - at_end {
        let multiplicity = knots[i..].iter().take_while(|&&k| k == knots[i]).count();
        if multiplicity > degree {
            return Err(GuideError::KnotMultiplicity {
                guide: name,
                index: i,
                value: knots[i],
                multiplicity,
                degree,
            });
        }
        i += multiplicity;
    }
    Ok(())
}

/// The largest B-spline degree accepted, for guides and for the IGES surfaces
/// read as targets: a point costs about degree² operations (a guide of degree
/// 4000 and 500 samples took 20 s to validate), and no designer needs more
/// (Rhino stops at 11; guides are usually of degree 2 or 3).
pub const MAX_DEGREE: usize = 32;

/// Clamped uniform knots on `[0, 1]` for `count` control points of `degree`.
pub(crate) fn clamped_uniform_knots(count: usize, degree: usize) -> Vec<f64> {
    let spans = count - degree;
    let mut knots = vec![0.0; degree + 1];
    knots.extend((1..spans).map(|i| i as f64 / spans as f64));
    knots.extend(vec![1.0; degree + 1]);
    knots
}

/// The `bspline` kind: `samples` points at uniformly spaced parameters, or at
/// the given `parameters` (§4.8).
fn sample_bspline(
    b: &BSplineSpec,
    parameters: Option<&[f64]>,
    name: GuideName,
) -> Result<Sampled, GuideError> {
    check_count(b.samples, "bspline.samples", name)?;
    let degree = b.degree;
    if degree == 0 {
        return Err(GuideError::ZeroDegree { guide: name });
    }
    if degree > MAX_DEGREE {
        return Err(GuideError::DegreeTooHigh {
            guide: name,
            degree,
            max: MAX_DEGREE,
        });
    }
    let count = b.control_points.len();
    if count <= degree {
        return Err(GuideError::TooFewControlPoints {
            guide: name,
            count,
            degree,
        });
    }
    for (i, p) in b.control_points.iter().enumerate() {
        check_finite(p, "bspline.control_points", Some(i), name)?;
    }
    let knots = match &b.knots {
        Some(k) => {
            check_knots(k, count, degree, name)?;
            k.clone()
        }
        None => clamped_uniform_knots(count, degree),
    };
    let weights = match &b.weights {
        Some(w) => {
            if w.len() != count {
                return Err(GuideError::WeightCount {
                    guide: name,
                    count: w.len(),
                    expected: count,
                });
            }
            if let Some(i) = w.iter().position(|x| !x.is_finite()) {
                return Err(GuideError::NonFinite {
                    guide: name,
                    field: "bspline.weights",
                    index: Some(i),
                });
            }
            if let Some(i) = w.iter().position(|&x| x <= 0.0) {
                return Err(GuideError::WeightNotPositive {
                    guide: name,
                    index: i,
                    value: w[i],
                });
            }
            w.clone()
        }
        None => vec![1.0; count],
    };
    // Relative to P0, so that round-off stays relative to the curve's size far
    // from the origin (and coordinates shared by all control points stay exact).
    let origin = v(&b.control_points[0]);
    let points: Vec<DVec3> = b.control_points.iter().map(|p| v(p) - origin).collect();
    let tangent = points[1] - points[0];
    let end = v(&b.control_points[count - 1]);
    let curve = Nurbs::new(degree, &points, &weights, &knots);
    let (lo, hi) = (knots[0], knots[knots.len() - 1]);
    if let Some(t) = parameters {
        check_parameters(t, b.samples, (lo, hi), name)?;
    }
    let last = (b.samples - 1) as f64;
    let samples = (0..b.samples)
        .map(|k| {
            let s = k as f64 / last;
            // Exactly `lo` at s = 0 and exactly `hi` at s = 1.
            let u = parameters.map_or((1.0 - s) * lo + s * hi, |t| t[k]);
            if u >= hi {
                end // the clamped end, exactly (P_n − P0 + P0 may round)
            } else {
                curve.point(u) + origin
            }
        })
        .collect();
    Ok((samples, Some((tangent, TangentSource::ControlPolygon))))
}

/// Checks `parameters` of a `bspline` guide (§4.8): one per sample, finite,
/// strictly increasing, within `[lo, hi]`.
fn check_parameters(
    t: &[f64],
    samples: usize,
    (lo, hi): (f64, f64),
    name: GuideName,
) -> Result<(), GuideError> {
    if t.len() != samples {
        return Err(GuideError::ParameterCount {
            guide: name,
            count: t.len(),
            samples,
        });
    }
    if let Some(index) = t.iter().position(|x| !x.is_finite()) {
        return Err(GuideError::NonFinite {
            guide: name,
            field: "parameters",
            index: Some(index),
        });
    }
    if let Some(index) = t.iter().position(|&x| !(lo..=hi).contains(&x)) {
        return Err(GuideError::ParameterOutOfRange {
            guide: name,
            index,
            value: t[index],
            lo,
            hi,
        });
    }
    if let Some(k) = t.windows(2).position(|w| w[1] <= w[0]) {
        return Err(GuideError::ParametersNotIncreasing {
            guide: name,
            index: k + 1,
            previous: t[k],
            value: t[k + 1],
        });
    }
    Ok(())
}

/// A least-squares plane and line through a point set.
struct Fit {
    /// The centroid.
    centroid: DVec3,
    /// Unit normal of the best-fit plane (smallest singular direction).
    normal: DVec3,
    /// Unit direction of the best-fit line (largest singular direction).
    axis: DVec3,
}

/// Least-squares plane and line of `points` (finite, bounding-box diagonal
/// `size` finite and non-zero): the right singular vectors of the centred
/// points, by one-sided Jacobi on the `N × 3` matrix itself (no covariance
/// matrix, so no squaring of the condition number). Exactly planar input in an
/// axis-aligned plane gives that axis exactly.
fn fit(points: &[DVec3], size: f64) -> Fit {
    let (lo, hi) = points.iter().fold((points[0], points[0]), |(lo, hi), &p| {
        (lo.min(p), hi.max(p))
    });
    let mid = 0.5 * lo + 0.5 * hi;
    let mean = points.iter().map(|&p| p - mid).sum::<DVec3>() / points.len() as f64;
    let centroid = mid + mean;
    // A power of two, so scaling is exact and keeps the sums in range.
    let scale = libm::ldexp(1.0, -(libm::log2(size).floor() as i32));
    let mut a: Vec<[f64; 3]> = points
        .iter()
        .map(|&p| ((p - centroid) * scale).to_array())
        .collect();
    let mut vt = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]; // columns of V
    for _sweep in 0..64 {
        let mut rotated = false;
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            let (mut alpha, mut beta, mut gamma) = (0.0, 0.0, 0.0);
            for row in &a {
                alpha += row[p] * row[p];
                beta += row[q] * row[q];
                gamma += row[p] * row[q];
            }
            if gamma == 0.0 || gamma.abs() <= f64::EPSILON * (alpha * beta).sqrt() {
                continue;
            }
            rotated = true;
            let zeta = (beta - alpha) / (2.0 * gamma);
            let t = zeta.signum() / (zeta.abs() + libm::hypot(zeta, 1.0));
            let c = 1.0 / libm::hypot(t, 1.0);
            let s = c * t;
            for row in a.iter_mut().chain(vt.iter_mut()) {
                let (x, y) = (row[p], row[q]);
                row[p] = c * x - s * y;
                row[q] = s * x + c * y;
            }
        }
        if !rotated {
            break;
        }
    }
    let norms: [f64; 3] = std::array::from_fn(|j| a.iter().map(|row| row[j] * row[j]).sum::<f64>());
    let column = |j: usize| DVec3::new(vt[0][j], vt[1][j], vt[2][j]).normalize();
    let order = {
        let mut o = [0, 1, 2];
        o.sort_by(|&i, &j| norms[i].total_cmp(&norms[j]));
        o
    };
    let mut normal = column(order[0]);
    let largest = (0..3)
        .max_by(|&i, &j| normal[i].abs().total_cmp(&normal[j].abs()).then(j.cmp(&i)))
        .unwrap_or(0);
    if normal[largest] < 0.0 {
        normal = -normal;
    }
    Fit {
        centroid,
        normal,
        axis: column(order[2]),
    }
}

/// The common checks, the projection and the start tangent, for every kind
/// (`tangent` is `None` for a polyline without one).
fn finish(
    mut points: Vec<DVec3>,
    tangent: Option<(DVec3, TangentSource)>,
    name: GuideName,
    tol: &Tolerances,
) -> Result<Guide, GuideError> {
    if let Some(i) = points.iter().position(|p| !p.is_finite()) {
        return Err(GuideError::NonFinite {
            guide: name,
            field: "samples",
            index: Some(i),
        });
    }
    let (lo, hi) = points.iter().fold((points[0], points[0]), |(lo, hi), &p| {
        (lo.min(p), hi.max(p))
    });
    let size = (hi - lo).length();
    if !size.is_finite() {
        return Err(GuideError::Overflow { guide: name, size });
    }
    for (i, e) in points.windows(2).enumerate() {
        let distance = e[0].distance(e[1]);
        if distance <= DEGENERATE * size {
            return Err(GuideError::RepeatedPoint {
                guide: name,
                index: i,
                distance,
            });
        }
    }
    let Fit {
        centroid,
        normal,
        axis,
    } = fit(&points, size);
    let off_line = points
        .iter()
        .map(|&p| {
            let q = p - centroid;
            (q - q.dot(axis) * axis).length()
        })
        .fold(0.0, f64::max);
    if off_line <= DEGENERATE * size {
        return Err(GuideError::Straight {
            guide: name,
            deviation: off_line / size,
        });
    }
    let offsets: Vec<f64> = points.iter().map(|&p| (p - centroid).dot(normal)).collect();
    let (mut worst, mut planarity) = (0, 0.0);
    for (i, d) in offsets.iter().enumerate() {
        if d.abs() > planarity {
            (worst, planarity) = (i, d.abs());
        }
    }
    if !within(planarity, tol.planarity * size) {
        return Err(GuideError::NotPlanar {
            guide: name,
            index: worst,
            deviation: planarity,
            relative: planarity / size,
            tolerance: tol.planarity,
            origin_ratio: crate::grid::origin_ratio(&points),
        });
    }
    // Offsets at the level of rounding are noise of the fit, not of the input:
    // such samples are kept bit for bit (so the start point stays exact).
    let noise = 4.0 * f64::EPSILON * (size + centroid.abs().max_element());
    for (p, &d) in points.iter_mut().zip(&offsets) {
        if d.abs() > noise {
            *p -= d * normal;
        }
    }
    let (tangent, source) =
        tangent.unwrap_or_else(|| (circle_tangent(&points), TangentSource::Circle));
    let t = unit(tangent).ok_or(GuideError::ZeroTangent {
        guide: name,
        from: source,
    })?;
    let across = t.dot(normal);
    let along = t - across * normal;
    let angle = libm::atan2(across.abs(), along.length());
    let not_in_plane = GuideError::TangentNotInPlane {
        guide: name,
        from: source,
        angle,
        tolerance: tol.angle,
        origin_ratio: crate::grid::origin_ratio(&points),
    };
    if source.may_leave_plane() && !within(angle, tol.angle) {
        return Err(not_in_plane);
    }
    // `None` only for a tangent along the normal, with `tol.angle` ≥ 90°.
    let tangent = unit(along).ok_or(not_in_plane)?;
    Ok(Guide {
        points,
        tangent,
        plane_normal: normal,
        planarity,
        size,
    })
}

/// Tangent at `points[0]` of the circle through the first three points, towards
/// `points[1]`; the first chord if there are only two or they are collinear.
///
/// By inversion about `points[0]` the circle becomes the line through
/// `a / |a|²` and `b / |b|²` (`a`, `b` the first two chords from `points[0]`),
/// which is parallel to the tangent.
fn circle_tangent(points: &[DVec3]) -> DVec3 {
    let a = points[1] - points[0];
    let Some(&third) = points.get(2) else {
        return a;
    };
    let b = third - points[0];
    let (la, lb) = (a.length(), b.length());
    // Unit chords first, so that nothing is squared (no overflow or underflow).
    let (ua, ub) = (a / la, b / lb);
    if ua.cross(ub).length() <= DEGENERATE {
        return a;
    }
    ua / la - ub / lb
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bspline::tests::cox_de_boor;

    use std::f64::consts::{FRAC_1_SQRT_2, PI};

    const U: GuideName = GuideName::U;

    fn tol() -> Tolerances {
        Tolerances::default()
    }

    fn guide(spec: &GuideSpec) -> Result<Guide, GuideError> {
        Guide::from_spec(spec, U, &tol())
    }

    fn err(spec: &GuideSpec) -> GuideError {
        let e = guide(spec).expect_err("the spec should be refused");
        // Every message names the guide.
        assert!(e.to_string().contains("guide_u"), "{e}");
        e
    }

    /// A curved, exactly planar (y = 0) polyline.
    fn bent() -> Vec<Xyz> {
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.2],
            [2.0, 0.0, 0.7],
            [3.0, 0.0, 1.5],
        ]
    }

    fn bspline(control_points: Vec<Xyz>, degree: usize, samples: usize) -> BSplineSpec {
        BSplineSpec {
            degree,
            control_points,
            knots: None,
            weights: None,
            samples,
        }
    }

    fn bspline_spec(b: BSplineSpec) -> GuideSpec {
        GuideSpec {
            bspline: Some(b),
            ..Default::default()
        }
    }

    fn cubic() -> BSplineSpec {
        bspline(
            vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.5],
                [2.0, 0.0, 1.5],
                [3.0, 0.0, 1.0],
                [4.0, 0.0, 2.0],
            ],
            3,
            17,
        )
    }

    fn arc(angle_deg: f64, samples: usize) -> ArcSpec {
        ArcSpec {
            center: [1.0, 2.0, 3.0],
            start: [1.0, 2.0, 5.0],
            normal: [0.0, 3.0, 0.0],
            angle_deg,
            samples,
        }
    }

    fn arc_spec(a: ArcSpec) -> GuideSpec {
        GuideSpec {
            arc: Some(a),
            ..Default::default()
        }
    }

    fn parabola(tangent: Xyz, quadratic: Xyz, samples: usize) -> GuideSpec {
        GuideSpec {
            parabola: Some(ParabolaSpec {
                start: [0.5, -1.0, 2.0],
                tangent,
                quadratic,
                samples,
            }),
            ..Default::default()
        }
    }

    fn unit_of(x: Xyz) -> DVec3 {
        DVec3::from_array(x).normalize()
    }

    #[test]
    fn guide_names_display() {
        assert_eq!(GuideName::U.to_string(), "guide_u");
        assert_eq!(GuideName::V.to_string(), "guide_v");
        let e = Guide::from_spec(&GuideSpec::default(), GuideName::V, &tol()).unwrap_err();
        assert!(e.to_string().starts_with("guide_v"));
    }

    // ---- one test per error variant ----

    #[test]
    fn no_kind() {
        assert_eq!(err(&GuideSpec::default()), GuideError::NoKind { guide: U });
        let only_tangent = GuideSpec {
            tangent: Some([1.0, 0.0, 0.0]),
            ..Default::default()
        };
        assert_eq!(err(&only_tangent), GuideError::NoKind { guide: U });
    }

    #[test]
    fn several_kinds() {
        let spec = GuideSpec {
            points: Some(bent()),
            arc: Some(arc(90.0, 5)),
            parabola: Some(ParabolaSpec {
                start: [0.0; 3],
                tangent: [1.0, 0.0, 0.0],
                quadratic: [0.0, 0.0, 1.0],
                samples: 3,
            }),
            ..Default::default()
        };
        let e = err(&spec);
        assert_eq!(
            e,
            GuideError::SeveralKinds {
                guide: U,
                found: vec!["points", "arc", "parabola"]
            }
        );
        assert!(e.to_string().contains("(points, arc, parabola)"), "{e}");
    }

    #[test]
    fn tangent_without_points() {
        let mut spec = arc_spec(arc(90.0, 5));
        spec.tangent = Some([1.0, 0.0, 0.0]);
        let e = err(&spec);
        assert_eq!(
            e,
            GuideError::TangentWithoutPoints {
                guide: U,
                kind: "arc"
            }
        );
        assert!(e.to_string().contains("Remove `tangent`"), "{e}");
    }

    #[test]
    fn too_few_samples() {
        let cases = [
            (GuideSpec::points(vec![[0.0; 3]]), "points", 1),
            (GuideSpec::points(vec![]), "points", 0),
            (bspline_spec(bspline(bent(), 2, 1)), "bspline.samples", 1),
            (arc_spec(arc(90.0, 0)), "arc.samples", 0),
            (
                parabola([1.0, 0.0, 0.0], [0.0, 0.0, 1.0], 1),
                "parabola.samples",
                1,
            ),
        ];
        for (spec, field, count) in cases {
            assert_eq!(
                err(&spec),
                GuideError::TooFewSamples {
                    guide: U,
                    field,
                    count
                }
            );
        }
    }

    #[test]
    fn non_finite() {
        let mut points = bent();
        points[2][1] = f64::NAN;
        let e = err(&GuideSpec::points(points));
        assert_eq!(
            e,
            GuideError::NonFinite {
                guide: U,
                field: "points",
                index: Some(2)
            }
        );
        assert!(e.to_string().contains("`points` entry 2"), "{e}");

        let mut spec = GuideSpec::points(bent());
        spec.tangent = Some([f64::INFINITY, 0.0, 0.0]);
        assert_eq!(
            err(&spec),
            GuideError::NonFinite {
                guide: U,
                field: "tangent",
                index: None
            }
        );

        let mut b = cubic();
        b.knots = Some(vec![0.0, 0.0, 0.0, 0.0, f64::NAN, 1.0, 1.0, 1.0, 1.0]);
        assert_eq!(
            err(&bspline_spec(b)),
            GuideError::NonFinite {
                guide: U,
                field: "bspline.knots",
                index: Some(4)
            }
        );

        let mut b = cubic();
        b.weights = Some(vec![1.0, 1.0, f64::INFINITY, 1.0, 1.0]);
        assert_eq!(
            err(&bspline_spec(b)),
            GuideError::NonFinite {
                guide: U,
                field: "bspline.weights",
                index: Some(2)
            }
        );

        let mut b = cubic();
        b.control_points[3][0] = f64::NEG_INFINITY;
        assert_eq!(
            err(&bspline_spec(b)),
            GuideError::NonFinite {
                guide: U,
                field: "bspline.control_points",
                index: Some(3)
            }
        );

        let mut a = arc(90.0, 5);
        a.angle_deg = f64::NAN;
        assert_eq!(
            err(&arc_spec(a)),
            GuideError::NonFinite {
                guide: U,
                field: "arc.angle_deg",
                index: None
            }
        );

        // Finite input whose samples overflow.
        let e = err(&parabola([1e308, 0.0, 0.0], [1e308, 0.0, 1.0], 5));
        assert_eq!(
            e,
            GuideError::NonFinite {
                guide: U,
                field: "samples",
                index: Some(4)
            }
        );
        assert!(
            e.to_string().contains("sample 4 is not a finite number"),
            "{e}"
        );
    }

    #[test]
    fn overflow() {
        let spec = GuideSpec::points(vec![
            [-1e308, 0.0, 0.0],
            [0.0, 0.0, 1e308],
            [1e308, 0.0, 0.0],
        ]);
        assert!(matches!(err(&spec), GuideError::Overflow { size, .. } if size.is_infinite()));
    }

    #[test]
    fn repeated_point() {
        let mut points = bent();
        points.insert(2, points[1]);
        let e = err(&GuideSpec::points(points));
        assert_eq!(
            e,
            GuideError::RepeatedPoint {
                guide: U,
                index: 1,
                distance: 0.0
            }
        );
        assert!(e.to_string().contains("samples 1 and 2 coincide"), "{e}");
        // Nearly repeated, relative to the size.
        let mut points = bent();
        points[3] = [2.0, 0.0, 0.7 + 1e-13];
        assert!(matches!(
            err(&GuideSpec::points(points)),
            GuideError::RepeatedPoint { index: 2, distance, .. } if distance > 0.0
        ));
    }

    #[test]
    fn straight() {
        let line = GuideSpec::points(vec![[0.0, 0.0, 0.0], [1.0, 2.0, 3.0], [3.0, 6.0, 9.0]]);
        let e = err(&line);
        assert!(matches!(e, GuideError::Straight { deviation, .. } if deviation <= 1e-12));
        assert!(e.to_string().contains("must be curved"), "{e}");
        // Two points are always a straight line.
        assert!(matches!(
            err(&GuideSpec::points(vec![[0.0; 3], [1.0, 0.0, 0.0]])),
            GuideError::Straight { .. }
        ));
        // A parabola whose quadratic term is parallel to its tangent.
        assert!(matches!(
            err(&parabola([1.0, 1.0, 0.0], [0.5, 0.5, 0.0], 9)),
            GuideError::Straight { .. }
        ));
    }

    #[test]
    fn far_from_the_origin_a_refusal_blames_the_precision_of_the_coordinates() {
        // A planar parabola in a tilted plane (a, b orthonormal), of size 4.5,
        // `corner` from the origin: exact as a design, but its coordinates
        // round off its plane.
        let (a, b) = (DVec3::new(0.6, -0.48, 0.64), DVec3::new(0.8, 0.36, -0.48));
        let at = |corner: DVec3| -> Vec<Xyz> {
            (0..12)
                .map(|k| {
                    let t = k as f64 / 11.0;
                    (corner + 4.0 * t * a + 2.0 * t * t * b).to_array()
                })
                .collect()
        };
        let e = err(&GuideSpec::points(at(DVec3::new(1e8, -2e8, 3e7))));
        let GuideError::NotPlanar {
            relative,
            origin_ratio,
            ..
        } = e
        else {
            panic!("{e:?}")
        };
        // Measured here: the distance of each sample from the exact plane is
        // what rounding to f64 moved it, below ε |coordinate| per axis.
        assert!(origin_ratio > 4e7, "{origin_ratio:e}");
        assert!(
            relative > 1e-9 && relative < 1e3 * f64::EPSILON * origin_ratio,
            "{relative:e}"
        );
        let msg = e.to_string();
        for words in [
            "times their size from the origin",
            "that precision, not the design, is the cause",
            "Model the design near the origin",
            "raise `tolerance.planarity` to 1e-7",
            "`--base-point start`",
        ] {
            assert!(msg.contains(words), "{words}: {msg}");
        }
        // Accepted with that tolerance.
        let loose = Tolerances {
            planarity: 1e-7,
            ..tol()
        };
        Guide::from_spec(
            &GuideSpec::points(at(DVec3::new(1e8, -2e8, 3e7))),
            U,
            &loose,
        )
        .unwrap();
        // Near the origin, the same guide is planar.
        guide(&GuideSpec::points(at(DVec3::ZERO))).unwrap();
    }

    #[test]
    fn not_planar() {
        // A planar parabola with sample 6 lifted out of its plane.
        let lifted = |lift: f64| -> Vec<Xyz> {
            (0..12)
                .map(|k| {
                    let t = k as f64 / 11.0;
                    [4.0 * t, if k == 6 { lift } else { 0.0 }, 2.0 * t * t]
                })
                .collect()
        };
        let e = err(&GuideSpec::points(lifted(1e-3)));
        let GuideError::NotPlanar {
            index,
            deviation,
            relative,
            tolerance,
            ..
        } = e.clone()
        else {
            panic!("{e:?}")
        };
        assert_eq!(index, 6);
        assert!(deviation > 8e-4 && deviation < 1e-3, "{deviation}");
        assert!((relative - deviation / DVec3::new(4.0, 1e-3, 2.0).length()).abs() < 1e-15);
        assert_eq!(tolerance, 1e-9);
        let msg = e.to_string();
        assert!(
            msg.starts_with("guide_u is not planar: sample 6 is "),
            "{msg}"
        );
        assert!(msg.contains("tolerance 1e-9"), "{msg}");
        assert!(msg.contains("raise `tolerance.planarity`"), "{msg}");
        assert!(!msg.contains("precision"), "{msg}");
        // A larger tolerance accepts it, and the samples are projected.
        let loose = Tolerances {
            planarity: 1e-3,
            ..tol()
        };
        let g = Guide::from_spec(&GuideSpec::points(lifted(1e-3)), U, &loose).unwrap();
        assert!((g.planarity - deviation).abs() < 1e-15);
        let c = g.points.iter().sum::<DVec3>() / g.points.len() as f64;
        for p in &g.points {
            assert!((*p - c).dot(g.plane_normal).abs() < 1e-15);
        }
    }

    #[test]
    fn zero_tangent() {
        let mut spec = GuideSpec::points(bent());
        spec.tangent = Some([0.0; 3]);
        let e = err(&spec);
        assert_eq!(
            e,
            GuideError::ZeroTangent {
                guide: U,
                from: TangentSource::Given
            }
        );
        assert!(e.to_string().contains("non-zero `tangent`"), "{e}");
        assert_eq!(
            err(&parabola([0.0; 3], [0.0, 0.0, 1.0], 5)),
            GuideError::ZeroTangent {
                guide: U,
                from: TangentSource::Parabola
            }
        );
        let mut b = cubic();
        b.control_points[1] = b.control_points[0];
        let e = err(&bspline_spec(b));
        assert_eq!(
            e,
            GuideError::ZeroTangent {
                guide: U,
                from: TangentSource::ControlPolygon
            }
        );
        assert!(e.to_string().contains("first two control points"), "{e}");
    }

    #[test]
    fn tangent_not_in_plane() {
        let mut spec = GuideSpec::points(bent());
        spec.tangent = Some([1.0, 1e-6, 0.0]);
        let e = err(&spec);
        assert!(matches!(
            e,
            GuideError::TangentNotInPlane { from: TangentSource::Given, angle, tolerance, .. }
                if (angle - 1e-6).abs() < 1e-12 && tolerance == 1e-9
        ));
        assert!(e.to_string().contains("raise `tolerance.angle`"), "{e}");
        // Within the tolerance it is projected into the plane and normalised.
        spec.tangent = Some([2.0, 1e-10, 0.0]);
        assert_eq!(guide(&spec).unwrap().tangent, DVec3::X);
        // A B-spline whose curve is planar to the tolerance but whose P1 is not.
        let mut b = cubic();
        b.control_points[1][1] = 1e-7;
        b.samples = 3;
        let loose = Tolerances {
            planarity: 1e-6,
            ..tol()
        };
        assert!(matches!(
            Guide::from_spec(&bspline_spec(b), U, &loose),
            Err(GuideError::TangentNotInPlane {
                from: TangentSource::ControlPolygon,
                ..
            })
        ));
    }

    #[test]
    fn zero_degree() {
        assert_eq!(
            err(&bspline_spec(bspline(bent(), 0, 5))),
            GuideError::ZeroDegree { guide: U }
        );
    }

    #[test]
    fn too_few_control_points() {
        let e = err(&bspline_spec(bspline(bent(), 4, 5)));
        assert_eq!(
            e,
            GuideError::TooFewControlPoints {
                guide: U,
                count: 4,
                degree: 4
            }
        );
        assert!(
            e.to_string().contains("needs more than 4 control points"),
            "{e}"
        );
    }

    #[test]
    fn degree_above_the_limit_is_refused_before_sampling() {
        // A Bézier curve of degree MAX_DEGREE in the plane y = 0 is read: its
        // midpoint is the Bernstein sum Σ C(n, k) / 2ⁿ · P_k, here of
        // P_k = (k, 0, k²): (n/2, 0, n(n+1)/4).
        let n = MAX_DEGREE;
        let points: Vec<Xyz> = (0..=n).map(|k| [k as f64, 0.0, (k * k) as f64]).collect();
        let g = guide(&bspline_spec(bspline(points.clone(), n, 3))).unwrap();
        let expected = [n as f64 / 2.0, 0.0, (n * (n + 1)) as f64 / 4.0];
        assert!(
            (g.points[1] - DVec3::from(expected)).length() < 1e-9 * n as f64,
            "{:?}",
            g.points[1]
        );
        // One more is refused, whatever the control points: a huge degree too,
        // without overflow.
        for degree in [n + 1, 4000, usize::MAX] {
            let e = err(&bspline_spec(bspline(points.clone(), degree, 5)));
            assert_eq!(
                e,
                GuideError::DegreeTooHigh {
                    guide: U,
                    degree,
                    max: MAX_DEGREE
                }
            );
        }
        let e = err(&bspline_spec(bspline(points, 4000, 500)));
        assert!(
            e.to_string()
                .contains("`bspline.degree` is 4000, above the largest accepted, 32")
                && e.to_string().contains("Lower the degree"),
            "{e}"
        );
    }

    #[test]
    fn knot_count() {
        let mut b = cubic();
        b.knots = Some(vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0]);
        assert_eq!(
            err(&bspline_spec(b)),
            GuideError::KnotCount {
                guide: U,
                count: 8,
                expected: 9,
                control_points: 5,
                degree: 3
            }
        );
    }

    #[test]
    fn knots_decreasing() {
        let mut b = cubic();
        b.knots = Some(vec![0.0, 0.0, 0.0, 0.0, 0.6, 0.4, 1.0, 1.0, 1.0]);
        assert_eq!(
            err(&bspline_spec(b)),
            GuideError::KnotsDecreasing {
                guide: U,
                index: 5,
                previous: 0.6,
                value: 0.4
            }
        );
    }

    #[test]
    fn empty_knot_span() {
        let mut b = cubic();
        b.knots = Some(vec![2.0; 9]);
        assert_eq!(
            err(&bspline_spec(b)),
            GuideError::EmptyKnotSpan {
                guide: U,
                value: 2.0
            }
        );
    }

    #[test]
    fn knots_not_clamped() {
        let mut b = cubic();
        b.knots = Some(vec![0.0, 0.0, 0.0, 0.2, 0.5, 1.0, 1.0, 1.0, 1.0]);
        let e = err(&bspline_spec(b.clone()));
        assert_eq!(
            e,
            GuideError::KnotsNotClamped {
                guide: U,
                end: "start",
                multiplicity: 3,
                degree: 3
            }
        );
        assert!(
            e.to_string().contains("exactly degree + 1 = 4 times"),
            "{e}"
        );
        b.knots = Some(vec![0.0, 0.0, 0.0, 0.0, 0.5, 0.8, 0.9, 1.0, 1.0]);
        assert_eq!(
            err(&bspline_spec(b.clone())),
            GuideError::KnotsNotClamped {
                guide: U,
                end: "end",
                multiplicity: 2,
                degree: 3
            }
        );
        // Too many repetitions at an end are refused too.
        b.knots = Some(vec![0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0]);
        assert!(matches!(
            err(&bspline_spec(b)),
            GuideError::KnotsNotClamped {
                end: "start",
                multiplicity: 5,
                ..
            }
        ));
    }

    #[test]
    fn knot_multiplicity() {
        let mut b = cubic();
        b.control_points
            .extend([[5.0, 0.0, 2.5], [6.0, 0.0, 2.0], [7.0, 0.0, 3.0]]);
        // 8 control points, degree 3: 12 knots; 0.5 repeated 4 times.
        b.knots = Some(vec![
            0.0, 0.0, 0.0, 0.0, 0.5, 0.5, 0.5, 0.5, 1.0, 1.0, 1.0, 1.0,
        ]);
        assert_eq!(
            err(&bspline_spec(b.clone())),
            GuideError::KnotMultiplicity {
                guide: U,
                index: 4,
                value: 0.5,
                multiplicity: 4,
                degree: 3
            }
        );
        // Repeated `degree` times is fine (a C⁰ kink).
        b.knots = Some(vec![
            0.0, 0.0, 0.0, 0.0, 0.25, 0.5, 0.5, 0.5, 1.0, 1.0, 1.0, 1.0,
        ]);
        let g = guide(&bspline_spec(b.clone())).unwrap();
        assert_eq!(g.points.len(), 17);
    }

    #[test]
    fn weight_count() {
        let mut b = cubic();
        b.weights = Some(vec![1.0; 4]);
        assert_eq!(
            err(&bspline_spec(b)),
            GuideError::WeightCount {
                guide: U,
                count: 4,
                expected: 5
            }
        );
    }

    #[test]
    fn weight_not_positive() {
        let mut b = cubic();
        b.weights = Some(vec![1.0, 1.0, 1.0, -0.5, 1.0]);
        assert_eq!(
            err(&bspline_spec(b.clone())),
            GuideError::WeightNotPositive {
                guide: U,
                index: 3,
                value: -0.5
            }
        );
        b.weights = Some(vec![0.0, 1.0, 1.0, 1.0, 1.0]);
        assert!(matches!(
            err(&bspline_spec(b)),
            GuideError::WeightNotPositive { index: 0, .. }
        ));
    }

    #[test]
    fn arc_zero_normal() {
        let mut a = arc(90.0, 5);
        a.normal = [0.0; 3];
        assert_eq!(err(&arc_spec(a)), GuideError::ArcZeroNormal { guide: U });
    }

    #[test]
    fn arc_zero_radius() {
        let mut a = arc(90.0, 5);
        a.start = a.center;
        assert_eq!(err(&arc_spec(a)), GuideError::ArcZeroRadius { guide: U });
    }

    #[test]
    fn arc_not_orthogonal() {
        let mut a = arc(90.0, 5);
        a.normal = [0.0, 1.0, 1e-6];
        let e = err(&arc_spec(a));
        assert!(matches!(
            e,
            GuideError::ArcNotOrthogonal { angle, tolerance, .. }
                if (angle - 1e-6).abs() < 1e-12 && tolerance == 1e-9
        ));
        assert!(e.to_string().contains("raise `tolerance.angle`"), "{e}");
    }

    #[test]
    fn arc_angle() {
        for angle_deg in [0.0, 360.0, -360.0, 400.0] {
            assert_eq!(
                err(&arc_spec(arc(angle_deg, 5))),
                GuideError::ArcAngle {
                    guide: U,
                    angle_deg
                }
            );
        }
    }

    // ---- sampling and geometry ----

    #[test]
    fn polyline_is_used_as_given() {
        let g = guide(&GuideSpec::points(bent())).unwrap();
        let expected: Vec<DVec3> = bent().iter().map(|p| DVec3::from_array(*p)).collect();
        assert_eq!(g.points, expected);
        assert_eq!(g.plane_normal, DVec3::Y);
        assert_eq!(g.planarity, 0.0);
        assert_eq!(g.size, 3.0f64.hypot(1.5));
    }

    #[test]
    fn exactly_planar_input_is_bit_identical() {
        // y = 0 and y = 3.7, with awkward coordinates.
        for y in [0.0, 3.7] {
            let points: Vec<Xyz> = (0..25)
                .map(|k| {
                    let t = k as f64 * 0.137;
                    [t.sin() * 3.3 + 0.1, y, (t * 1.7).cos() * t + 1e-3]
                })
                .collect();
            let g = guide(&GuideSpec::points(points.clone())).unwrap();
            let expected: Vec<DVec3> = points.iter().map(|p| DVec3::from_array(*p)).collect();
            assert_eq!(g.points, expected);
            assert_eq!(g.plane_normal, DVec3::Y);
            assert_eq!(g.planarity, 0.0);
            assert_eq!(g.tangent.y, 0.0);
        }
    }

    #[test]
    fn plane_normal_sign_convention() {
        // Largest-magnitude component positive, whatever the orientation of the curve.
        let spec = GuideSpec::points(vec![[0.0, 0.0, -1.0], [1.0, 1.0, -1.0], [3.0, 1.5, -1.0]]);
        let g = guide(&spec).unwrap();
        assert_eq!(g.plane_normal, DVec3::Z);
        let reversed =
            GuideSpec::points(vec![[3.0, 1.5, -1.0], [1.0, 1.0, -1.0], [0.0, 0.0, -1.0]]);
        assert_eq!(guide(&reversed).unwrap().plane_normal, DVec3::Z);
        // Oblique: normal (-1, 2, 2) / 3 is reported as (-1, 2, 2) / 3 (first of the largest).
        let n = DVec3::new(-1.0, 2.0, 2.0) / 3.0;
        let (e1, e2) = n.any_orthonormal_pair();
        let spec = GuideSpec::points(
            (0..7)
                .map(|k| {
                    let t = k as f64 * 0.3;
                    (5.0 * n + t * e1 + t * t * e2).to_array()
                })
                .collect(),
        );
        let g = guide(&spec).unwrap();
        assert!(
            (g.plane_normal - n).length() < 1e-15,
            "{:?}",
            g.plane_normal
        );
    }

    /// Points on a circle of radius `r` about `c` in the plane of `e1`, `e2`, from angle 0.
    fn circle_points(c: DVec3, r: f64, e1: DVec3, e2: DVec3, step: f64, n: usize) -> Vec<Xyz> {
        (0..n)
            .map(|k| {
                let phi = step * k as f64;
                (c + r * (phi.cos() * e1 + phi.sin() * e2)).to_array()
            })
            .collect()
    }

    #[test]
    fn sampled_circular_arc_gets_its_exact_tangent() {
        let n = DVec3::new(0.3, -0.5, 0.8).normalize();
        let (e1, e2) = n.any_orthonormal_pair();
        let c = DVec3::new(10.0, -3.0, 2.5);
        for (step, count) in [(0.01, 50), (0.3, 3), (PI / 4.0, 6)] {
            let g = guide(&GuideSpec::points(circle_points(
                c, 7.0, e1, e2, step, count,
            )))
            .unwrap();
            assert!(
                (g.tangent - e2).length() <= 1e-12,
                "{step}: {:?}",
                g.tangent
            );
            assert!(g.plane_normal.cross(n).length() < 1e-13);
            assert!(g.planarity < 1e-13);
        }
    }

    #[test]
    fn polyline_tangent_falls_back_to_the_first_chord() {
        // The first three points are collinear.
        let spec = GuideSpec::points(vec![
            [0.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [2.0, 2.0, 0.0],
            [3.0, 2.0, 0.0],
        ]);
        let g = guide(&spec).unwrap();
        assert!((g.tangent - DVec3::new(1.0, 1.0, 0.0).normalize()).length() < 1e-15);
        assert_eq!(g.plane_normal, DVec3::Z);
    }

    #[test]
    fn bspline_end_points_and_start_tangent() {
        let b = cubic();
        let g = guide(&bspline_spec(b.clone())).unwrap();
        assert_eq!(g.points.len(), 17);
        assert_eq!(g.points[0], DVec3::from_array(b.control_points[0]));
        assert_eq!(g.points[16], DVec3::from_array(b.control_points[4]));
        assert_eq!(g.tangent, unit_of([1.0, 0.0, 0.5]));

        // Oblique plane, non-uniform knots on [2, 7], rational weights: ends exact,
        // tangent parallel to P1 − P0.
        let n = DVec3::new(1.0, 2.0, -0.7).normalize();
        let (e1, e2) = n.any_orthonormal_pair();
        let origin = DVec3::new(-3.0, 4.0, 1.25);
        let control: Vec<Xyz> = [(0.0, 0.0), (1.0, 0.7), (2.5, 1.0), (3.0, -0.5), (4.1, 0.3)]
            .iter()
            .map(|&(x, y)| (origin + x * e1 + y * e2).to_array())
            .collect();
        let b = BSplineSpec {
            degree: 2,
            control_points: control.clone(),
            knots: Some(vec![2.0, 2.0, 2.0, 3.1, 5.5, 7.0, 7.0, 7.0]),
            weights: Some(vec![1.0, 0.5, 2.0, 1.5, 0.8]),
            samples: 11,
        };
        let g = guide(&bspline_spec(b)).unwrap();
        assert_eq!(g.points[0], DVec3::from_array(control[0]));
        assert_eq!(g.points[10], DVec3::from_array(control[4]));
        let chord = (DVec3::from_array(control[1]) - DVec3::from_array(control[0])).normalize();
        assert!(g.tangent.cross(chord).length() < 1e-15 && g.tangent.dot(chord) > 0.0);
        assert!(g.plane_normal.cross(n).length() < 1e-14);
    }

    #[test]
    fn bspline_matches_an_independent_evaluation() {
        let control = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 2.0],
            [2.0, 0.0, 2.5],
            [3.5, 0.0, 1.0],
            [4.0, 0.0, -1.0],
            [6.0, 0.0, 0.5],
            [7.0, 0.0, 2.0],
        ];
        let weights = [1.0, 2.0, 0.5, 1.0, 3.0, 0.7, 1.0];
        let knots = vec![0.0, 0.0, 0.0, 0.0, 0.2, 0.2, 0.65, 1.0, 1.0, 1.0, 1.0];
        let b = BSplineSpec {
            degree: 3,
            control_points: control.to_vec(),
            knots: Some(knots.clone()),
            weights: Some(weights.to_vec()),
            samples: 41,
        };
        let g = guide(&bspline_spec(b)).unwrap();
        for (k, p) in g.points.iter().enumerate() {
            let u = k as f64 / 40.0;
            let (mut num, mut den) = (DVec3::ZERO, 0.0);
            for i in 0..control.len() {
                let nw = cox_de_boor(&knots, i, 3, u) * weights[i];
                num += nw * DVec3::from_array(control[i]);
                den += nw;
            }
            let expected = num / den;
            assert!(
                (*p - expected).length() <= 1e-15 * 7.0,
                "{k}: {p} vs {expected}"
            );
        }
    }

    #[test]
    fn nurbs_quarter_circle_lies_on_the_circle() {
        let b = BSplineSpec {
            degree: 2,
            control_points: vec![[1.0, 0.0, 0.0], [1.0, 0.0, 1.0], [0.0, 0.0, 1.0]],
            knots: None,
            weights: Some(vec![1.0, FRAC_1_SQRT_2, 1.0]),
            samples: 33,
        };
        let g = guide(&bspline_spec(b)).unwrap();
        for p in &g.points {
            assert!((p.length() - 1.0).abs() <= 1e-14, "{p}");
            assert_eq!(p.y, 0.0);
        }
        assert_eq!(g.points[0], DVec3::X);
        assert_eq!(g.points[32], DVec3::Z);
        // Symmetric about the diagonal: the middle sample is at 45°.
        assert!((g.points[16] - DVec3::new(FRAC_1_SQRT_2, 0.0, FRAC_1_SQRT_2)).length() < 1e-15);
        assert_eq!(g.tangent, DVec3::Z);
    }

    #[test]
    fn default_knots_are_clamped_uniform() {
        assert_eq!(
            clamped_uniform_knots(5, 2),
            vec![0.0, 0.0, 0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0, 1.0, 1.0]
        );
        assert_eq!(
            clamped_uniform_knots(3, 2),
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0]
        );
        let mut explicit = cubic();
        explicit.knots = Some(vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0]);
        assert_eq!(
            guide(&bspline_spec(cubic())).unwrap(),
            guide(&bspline_spec(explicit)).unwrap()
        );
    }

    #[test]
    fn degree_one_bspline_is_the_control_polygon() {
        let b = bspline(bent(), 1, 7);
        let g = guide(&bspline_spec(b)).unwrap();
        let expected = [
            [0.0, 0.0, 0.0],
            [0.5, 0.0, 0.1],
            [1.0, 0.0, 0.2],
            [1.5, 0.0, 0.45],
            [2.0, 0.0, 0.7],
            [2.5, 0.0, 1.1],
            [3.0, 0.0, 1.5],
        ];
        for (p, e) in g.points.iter().zip(expected) {
            assert!((*p - DVec3::from_array(e)).length() < 1e-15, "{p}");
        }
    }

    #[test]
    fn arc_samples_lie_on_the_circle() {
        for angle_deg in [90.0, -135.0, 359.0, 1e-3] {
            let a = arc(angle_deg, 13);
            let g = guide(&arc_spec(a.clone())).unwrap();
            let c = DVec3::from_array(a.center);
            assert_eq!(g.points[0], DVec3::from_array(a.start));
            for (k, p) in g.points.iter().enumerate() {
                let r = *p - c;
                assert!((r.length() - 2.0).abs() <= 1e-15 * 4.0, "{k}: {p}");
                assert_eq!(r.y, 0.0);
                // Right-hand rule about +y: from +z towards +x.
                let phi = (angle_deg * k as f64 / 12.0).to_radians();
                let expected = c + 2.0 * DVec3::new(phi.sin(), 0.0, phi.cos());
                assert!((*p - expected).length() <= 1e-14, "{k}: {p} vs {expected}");
            }
            assert_eq!(g.tangent, DVec3::X * angle_deg.signum());
            assert_eq!(g.plane_normal, DVec3::Y);
        }
        // An oblique arc.
        let n = DVec3::new(1.0, -2.0, 0.5);
        let (e1, _) = n.normalize().any_orthonormal_pair();
        let c = DVec3::new(0.1, 0.2, 0.3);
        let a = ArcSpec {
            center: c.to_array(),
            start: (c + 3.0 * e1).to_array(),
            normal: n.to_array(),
            angle_deg: 200.0,
            samples: 40,
        };
        let g = guide(&arc_spec(a.clone())).unwrap();
        assert_eq!(g.points[0], DVec3::from_array(a.start));
        for p in &g.points {
            assert!(((*p - c).length() - 3.0).abs() < 1e-14);
        }
        let t = n.normalize().cross(e1);
        assert!((g.tangent - t).length() < 1e-15);
    }

    #[test]
    fn parabola_samples() {
        let spec = parabola([1.0, 0.0, 0.5], [0.0, 0.0, 2.0], 5);
        let g = guide(&spec).unwrap();
        let start = DVec3::new(0.5, -1.0, 2.0);
        for (k, p) in g.points.iter().enumerate() {
            let t = k as f64 / 4.0;
            let expected =
                start + t * DVec3::new(1.0, 0.0, 0.5) + t * t * DVec3::new(0.0, 0.0, 2.0);
            assert_eq!(*p, expected);
        }
        assert_eq!(g.points[0], start);
        assert_eq!(g.tangent, unit_of([1.0, 0.0, 0.5]));
        assert_eq!(g.plane_normal, DVec3::Y);
    }

    #[test]
    fn plane_fit_agrees_with_nalgebra_svd() {
        // Noisy, nearly planar points: compare with an SVD that shares no code.
        let normal = DVec3::new(0.2, 0.9, -0.4).normalize();
        let (e1, e2) = normal.any_orthonormal_pair();
        let origin = DVec3::new(3.0, -1.0, 0.5);
        let points: Vec<Xyz> = (0..30)
            .map(|k| {
                let t = k as f64 * 0.21;
                let noise = 1e-11 * ((k * 7919) % 13) as f64;
                (origin + (2.0 * t) * e1 + t.sin() * e2 + noise * normal).to_array()
            })
            .collect();
        let g = guide(&GuideSpec::points(points.clone())).unwrap();
        let c = points.iter().map(|p| DVec3::from_array(*p)).sum::<DVec3>() / 30.0;
        let m = nalgebra::DMatrix::from_fn(30, 3, |i, j| points[i][j] - c[j]);
        let svd = m.svd(false, true);
        let v_t = svd.v_t.unwrap();
        let smallest = svd.singular_values.imin();
        let n = DVec3::new(v_t[(smallest, 0)], v_t[(smallest, 1)], v_t[(smallest, 2)]);
        assert!(
            g.plane_normal.cross(n).length() < 1e-12,
            "{} vs {n}",
            g.plane_normal
        );
        let worst = points
            .iter()
            .map(|p| (DVec3::from_array(*p) - c).dot(n).abs())
            .fold(0.0, f64::max);
        assert!((g.planarity - worst).abs() < 1e-14);
        assert!(g.planarity > 0.0 && g.planarity < 1e-9 * g.size);
    }
}
