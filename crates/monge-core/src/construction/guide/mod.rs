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
//!
//! One file per idea: each kind is sampled in its own (`points`, `bspline` with
//! its knot and parameter checks, `arc`, `parabola`), `plane` fits the plane,
//! `error` says why a guide is refused; the common checks are here.

mod arc;
mod bspline;
mod error;
mod parabola;
mod plane;
mod points;
#[cfg(test)]
mod tests;

use std::fmt;

use glam::DVec3;

use crate::design::{GuideSpec, Tolerances, Xyz};

pub(crate) use bspline::clamped_uniform_knots;
pub use bspline::MAX_DEGREE;
pub use error::{GuideError, TangentSource};

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
        let (samples, tangent) = match spec {
            GuideSpec::Points { points, tangent } => points::polyline(points, *tangent, name)?,
            GuideSpec::BSpline {
                bspline,
                parameters,
            } => bspline::sample_bspline(bspline, parameters.as_deref(), name)?,
            GuideSpec::Arc(a) => arc::sample_arc(a, name, tol)?,
            GuideSpec::Parabola(p) => parabola::sample_parabola(p, name)?,
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
    let plane::Fit {
        centroid,
        normal,
        axis,
    } = plane::fit(&points, size);
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
