//! The circular arcs of a cyclidic net and its curvature lines, chains of arcs
//! (§4.4, §4.6).

use glam::DVec3;

use super::Family;

/// A circular arc of a curvature line (§4.4, §4.6): from `start` to `end`,
/// turning positively (right-hand rule) about `normal` around `center`.
///
/// ```
/// use glam::DVec3;
/// use monge_core::cyclidic::Arc;
/// let a = Arc { center: DVec3::ZERO, radius: 1.0, normal: DVec3::Z, start: DVec3::X, end: DVec3::Y };
/// assert!((a.sweep() - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Arc {
    /// Centre of the circle (§4.4).
    pub center: DVec3,
    /// Radius (§4.4).
    pub radius: f64,
    /// Unit normal of the circle's plane, oriented so that the arc turns positively about it.
    pub normal: DVec3,
    /// First point (a mesh vertex).
    pub start: DVec3,
    /// Last point (a mesh vertex).
    pub end: DVec3,
}

impl Arc {
    /// The angle swept from `start` to `end`, in `[0, 2π)` radians (§4.6).
    pub fn sweep(&self) -> f64 {
        let (x, y) = (self.start - self.center, self.end - self.center);
        let s = libm::atan2(self.normal.dot(x.cross(y)), x.dot(y));
        if s < 0.0 {
            s + std::f64::consts::TAU
        } else {
            s
        }
    }

    /// The point a fraction `t ∈ [0, 1]` of the way along the arc (§4.6): `start`
    /// turned by `t · sweep` about `normal` around `center`, exactly on the circle.
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::cyclidic::Arc;
    /// let a = Arc { center: DVec3::ZERO, radius: 1.0, normal: DVec3::Z, start: DVec3::X, end: DVec3::Y };
    /// let half = a.point(0.5);
    /// assert!((half - DVec3::new(1.0, 1.0, 0.0) / 2f64.sqrt()).length() < 1e-15);
    /// assert!((a.point(1.0) - a.end).length() < 1e-15);
    /// ```
    pub fn point(&self, t: f64) -> DVec3 {
        let x = self.start - self.center;
        let y = self.normal.cross(x);
        let (s, c) = libm::sincos(t * self.sweep());
        self.center + c * x + s * y
    }

    /// The arc through `p0` and `p2` tangent to `p1 − p0` at `p0`.
    pub(super) fn from_control(p0: DVec3, p1: DVec3, p2: DVec3) -> Arc {
        let t = (p1 - p0).normalize();
        let d = p2 - p0;
        let normal = t.cross(d).normalize();
        let s = normal.cross(t);
        let radius = d.length_squared() / (2.0 * d.dot(s));
        Arc {
            center: p0 + radius * s,
            radius,
            normal,
            start: p0,
            end: p2,
        }
    }
}

/// The curvature line of a net along one mesh line, as a chain of circular arcs (§4.4, §4.6).
#[derive(Clone, Debug, PartialEq)]
pub struct CurvatureLine {
    /// Its family.
    pub family: Family,
    /// Its index: `j` for a u-line, `i` for a v-line.
    pub index: usize,
    /// The arcs, consecutive arcs on one circle merged: one arc for a line
    /// inscribed in a circle, two for a bi-arc (§4.6).
    pub arcs: Vec<Arc>,
}
