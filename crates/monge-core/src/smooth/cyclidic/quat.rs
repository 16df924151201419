//! Quaternions for the QB form of Dupin cyclide patches (§4.4): points and vectors
//! as imaginary quaternions, and the cross-ratio of four points.

use glam::DVec3;
use std::ops::{Add, Mul, Neg, Sub};

/// A quaternion `w + v` (a point or vector is the imaginary quaternion `0 + v`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Quat {
    pub(super) w: f64,
    pub(super) v: DVec3,
}

impl Quat {
    pub(super) const ONE: Quat = Quat {
        w: 1.0,
        v: DVec3::ZERO,
    };

    pub(super) fn pure(v: DVec3) -> Quat {
        Quat { w: 0.0, v }
    }

    pub(super) fn conj(self) -> Quat {
        Quat {
            w: self.w,
            v: -self.v,
        }
    }

    pub(super) fn norm2(self) -> f64 {
        self.w * self.w + self.v.length_squared()
    }

    pub(super) fn inv(self) -> Quat {
        self.conj() * (1.0 / self.norm2())
    }

    /// The Euclidean inner product in ℝ⁴.
    pub(super) fn dot(self, o: Quat) -> f64 {
        self.w * o.w + self.v.dot(o.v)
    }
}

impl Mul for Quat {
    type Output = Quat;
    fn mul(self, o: Quat) -> Quat {
        Quat {
            w: self.w * o.w - self.v.dot(o.v),
            v: self.w * o.v + o.w * self.v + self.v.cross(o.v),
        }
    }
}

impl Mul<f64> for Quat {
    type Output = Quat;
    fn mul(self, s: f64) -> Quat {
        Quat {
            w: self.w * s,
            v: self.v * s,
        }
    }
}

impl Add for Quat {
    type Output = Quat;
    fn add(self, o: Quat) -> Quat {
        Quat {
            w: self.w + o.w,
            v: self.v + o.v,
        }
    }
}

impl Sub for Quat {
    type Output = Quat;
    fn sub(self, o: Quat) -> Quat {
        Quat {
            w: self.w - o.w,
            v: self.v - o.v,
        }
    }
}

impl Neg for Quat {
    type Output = Quat;
    fn neg(self) -> Quat {
        self * -1.0
    }
}

/// The cross-ratio `(A−C)(C−B)⁻¹(B−D)(D−A)⁻¹` of a quad's corners (real for concyclic points).
pub(super) fn cross_ratio([a, b, c, d]: [DVec3; 4]) -> Quat {
    let p = |x: DVec3| Quat::pure(x);
    p(a - c) * p(c - b).inv() * p(b - d) * p(d - a).inv()
}

/// `(x − y) / |x − y|`.
pub(super) fn unit_from(x: DVec3, y: DVec3) -> DVec3 {
    (y - x).normalize()
}
