//! Homogeneous points, Plücker lines and planes of real projective 3-space, and
//! polarity with respect to the unit sphere S² (§2.1.2).
//!
//! Points at infinity (w = 0) and lines at infinity (direction 0) are ordinary
//! values here, so that the pencil axes of the Gauss map need no special case
//! when θ = 0, ±180° or a Gauss circle is a great circle.

use glam::DVec3;

/// A point `(xyz : w)` of projective 3-space; `w = 0` is a point at infinity
/// (a direction) (§2.1.2).
///
/// ```
/// use glam::DVec3;
/// use monge_core::projective::HPoint;
/// let p = HPoint::new(DVec3::new(2.0, 4.0, 6.0), 2.0);
/// assert_eq!(p.to_affine(), Some(DVec3::new(1.0, 2.0, 3.0)));
/// assert_eq!(HPoint::new(DVec3::X, 0.0).to_affine(), None);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HPoint {
    /// Spatial part.
    pub xyz: DVec3,
    /// Weight; 0 at infinity.
    pub w: f64,
}

impl HPoint {
    /// The point `(xyz : w)` (§2.1.2).
    pub const fn new(xyz: DVec3, w: f64) -> Self {
        HPoint { xyz, w }
    }

    /// The finite point `p`, i.e. `(p : 1)` (§2.1.2).
    pub const fn affine(p: DVec3) -> Self {
        HPoint { xyz: p, w: 1.0 }
    }

    /// The Euclidean point, or `None` at infinity (§2.1.2).
    pub fn to_affine(self) -> Option<DVec3> {
        (self.w != 0.0).then(|| self.xyz / self.w)
    }
}

/// A plane `{Y : normal · Y = offset}` (§2.1.2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    /// Normal (not necessarily unit).
    pub normal: DVec3,
    /// Offset, in units of `|normal|`.
    pub offset: f64,
}

impl Plane {
    /// The polar plane of a point with respect to S², `{Y : xyz · Y = w}` (§2.1.2).
    ///
    /// The polar plane of the apex of a cone tangent to S² is the plane of the
    /// circle of tangency.
    pub fn polar_of(p: HPoint) -> Plane {
        Plane {
            normal: p.xyz,
            offset: p.w,
        }
    }

    /// Signed distance of `y` from the plane (§2.1.2).
    pub fn signed_distance(&self, y: DVec3) -> f64 {
        (self.normal.dot(y) - self.offset) / self.normal.length()
    }
}

/// A line in Plücker coordinates: direction `dir` and moment `moment = p × dir`
/// for any point `p` on it; `dir = 0` is a line at infinity (§2.1.2).
/// Both are defined up to a common non-zero factor.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Line {
    /// Direction (zero for a line at infinity).
    pub dir: DVec3,
    /// Moment about the origin.
    pub moment: DVec3,
}

impl Line {
    /// The line through two distinct points, finite or not (§2.1.2).
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::projective::{HPoint, Line};
    /// // The line through (0, 0, 2) in the direction of y.
    /// let l = Line::join(HPoint::affine(2.0 * DVec3::Z), HPoint::new(DVec3::Y, 0.0));
    /// assert!((l.distance_to_origin() - 2.0).abs() < 1e-15);
    /// ```
    pub fn join(a: HPoint, b: HPoint) -> Line {
        Line {
            dir: a.w * b.xyz - b.w * a.xyz,
            moment: a.xyz.cross(b.xyz),
        }
    }

    /// The polar line with respect to S² (§2.1.2): the points `Y` with
    /// `X · Y = 1` for every point `X` of this line. A line at distance `a`
    /// from the centre has its polar at distance `1/a`, orthogonal to it.
    pub fn polar(&self) -> Line {
        Line {
            dir: self.moment,
            moment: -self.dir,
        }
    }

    /// The plane through this line and the finite point `x` (§2.2.1). Its normal
    /// is zero when `x` lies on the line.
    pub fn plane_through(&self, x: DVec3) -> Plane {
        Plane {
            normal: x.cross(self.dir) - self.moment,
            offset: -self.moment.dot(x),
        }
    }

    /// Distance of the line from the origin (`∞` for a line at infinity) (§2.1.2).
    pub fn distance_to_origin(&self) -> f64 {
        self.moment.length() / self.dir.length()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point_on(l: &Line, s: f64) -> DVec3 {
        // Closest point to the origin, then along the direction.
        let d2 = l.dir.length_squared();
        l.dir.cross(l.moment) / d2 + s * l.dir
    }

    #[test]
    fn polar_of_a_line_is_conjugate_to_every_point_of_it() {
        let l = Line::join(
            HPoint::affine(DVec3::new(0.3, -0.2, 0.5)),
            HPoint::affine(DVec3::new(1.0, 0.7, -0.4)),
        );
        let p = l.polar();
        for s in [-2.0, 0.0, 0.5, 3.0] {
            for t in [-1.0, 0.25, 2.0] {
                let x = point_on(&l, s);
                let y = point_on(&p, t);
                assert!((x.dot(y) - 1.0).abs() < 1e-12, "{}", x.dot(y));
            }
        }
        let a = l.distance_to_origin();
        assert!((p.distance_to_origin() * a - 1.0).abs() < 1e-12);
        assert!(l.dir.dot(p.dir).abs() < 1e-12);
    }

    #[test]
    fn polar_of_a_line_through_the_centre_is_at_infinity() {
        let l = Line::join(HPoint::affine(DVec3::ZERO), HPoint::affine(DVec3::Y));
        let p = l.polar();
        assert_eq!(p.dir, DVec3::ZERO);
        // Planes through it are the planes orthogonal to y.
        let pl = p.plane_through(DVec3::new(0.2, 0.6, 0.1));
        assert!(
            pl.normal.normalize().abs_diff_eq(DVec3::Y, 1e-15)
                || pl.normal.normalize().abs_diff_eq(-DVec3::Y, 1e-15)
        );
        assert!(pl.signed_distance(DVec3::new(5.0, 0.6, -3.0)).abs() < 1e-15);
    }

    #[test]
    fn plane_through_line_and_point_contains_both() {
        let l = Line::join(
            HPoint::affine(DVec3::new(0.0, 0.0, 0.4)),
            HPoint::new(DVec3::Y, 0.0),
        );
        let x = DVec3::new(0.6, 0.0, 0.8);
        let pl = l.plane_through(x);
        assert!(pl.signed_distance(x).abs() < 1e-15);
        for s in [-3.0, 0.0, 7.0] {
            assert!(pl.signed_distance(point_on(&l, s)).abs() < 1e-14);
        }
        assert_eq!(Plane::polar_of(HPoint::new(DVec3::Z, 0.5)).offset, 0.5);
        assert_eq!(HPoint::affine(DVec3::X).to_affine(), Some(DVec3::X));
    }
}
