//! Four rows of the mesh at once (§2.2.3): numbers and vectors of [`LANES`]
//! lanes, one lane per row, so that the Gauss map and the Combescure transform
//! of four independent rows run in the same SIMD instructions.
//!
//! Every operation is the same IEEE operation on each lane (no fused
//! multiply-add, no horizontal sum), so a lane's result is bit for bit what the
//! same formula gives on that row alone, whichever other rows share the lanes.

use std::ops::{Add, Mul, Sub};

use glam::DVec3;

/// Number of lanes: rows computed together.
pub(crate) const LANES: usize = 4;

/// A number per lane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct F(pub [f64; LANES]);

/// A vector per lane, as three coordinates of [`LANES`] lanes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct V {
    pub x: F,
    pub y: F,
    pub z: F,
}

impl F {
    /// The same number in every lane.
    #[inline(always)]
    pub fn splat(a: f64) -> F {
        F([a; LANES])
    }

    /// `f` of each lane.
    #[inline(always)]
    pub fn map(self, f: impl Fn(f64) -> f64) -> F {
        F(self.0.map(f))
    }

    /// `f` of each pair of lanes.
    #[inline(always)]
    pub fn zip(self, o: F, f: impl Fn(f64, f64) -> f64) -> F {
        F(std::array::from_fn(|k| f(self.0[k], o.0[k])))
    }

    /// `1 / self`, lane by lane.
    #[inline(always)]
    pub fn recip(self) -> F {
        self.map(|a| 1.0 / a)
    }
}

impl Add for F {
    type Output = F;
    #[inline(always)]
    fn add(self, o: F) -> F {
        self.zip(o, |a, b| a + b)
    }
}

impl Sub for F {
    type Output = F;
    #[inline(always)]
    fn sub(self, o: F) -> F {
        self.zip(o, |a, b| a - b)
    }
}

impl Mul for F {
    type Output = F;
    #[inline(always)]
    fn mul(self, o: F) -> F {
        self.zip(o, |a, b| a * b)
    }
}

impl V {
    /// The same vector in every lane.
    #[inline(always)]
    pub fn splat(a: DVec3) -> V {
        V {
            x: F::splat(a.x),
            y: F::splat(a.y),
            z: F::splat(a.z),
        }
    }

    /// One vector per lane.
    #[inline(always)]
    pub fn from_lanes(a: [DVec3; LANES]) -> V {
        V {
            x: F(a.map(|p| p.x)),
            y: F(a.map(|p| p.y)),
            z: F(a.map(|p| p.z)),
        }
    }

    /// Lane `k`.
    #[inline(always)]
    pub fn lane(&self, k: usize) -> DVec3 {
        DVec3::new(self.x.0[k], self.y.0[k], self.z.0[k])
    }

    /// The cross product, lane by lane.
    #[inline(always)]
    pub fn cross(self, o: V) -> V {
        V {
            x: self.y * o.z - self.z * o.y,
            y: self.z * o.x - self.x * o.z,
            z: self.x * o.y - self.y * o.x,
        }
    }

    /// `(x·x' + y·y') + z·z'`, lane by lane.
    #[inline(always)]
    pub fn dot(self, o: V) -> F {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    /// Each lane scaled by its number.
    #[inline(always)]
    pub fn scale(self, s: F) -> V {
        V {
            x: self.x * s,
            y: self.y * s,
            z: self.z * s,
        }
    }

    /// Lane `k` from `a` where `pick[k]`, else from `self`.
    #[inline(always)]
    pub fn select(self, pick: [bool; LANES], a: V) -> V {
        let s = |p: F, q: F| {
            F(std::array::from_fn(
                |k| if pick[k] { q.0[k] } else { p.0[k] },
            ))
        };
        V {
            x: s(self.x, a.x),
            y: s(self.y, a.y),
            z: s(self.z, a.z),
        }
    }
}

impl Add for V {
    type Output = V;
    #[inline(always)]
    fn add(self, o: V) -> V {
        V {
            x: self.x + o.x,
            y: self.y + o.y,
            z: self.z + o.z,
        }
    }
}

impl Sub for V {
    type Output = V;
    #[inline(always)]
    fn sub(self, o: V) -> V {
        V {
            x: self.x - o.x,
            y: self.y - o.y,
            z: self.z - o.z,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lanes_compute_what_each_row_computes_alone() {
        let a = [
            DVec3::new(0.1, 0.2, 0.3),
            DVec3::new(-1.0, 1e-300, 7.0),
            DVec3::new(1e300, -2.0, 0.5),
            DVec3::new(3.0, -0.0, 1.0),
        ];
        let b = DVec3::new(0.7, -0.3, 1.0 / 3.0);
        let (va, vb) = (V::from_lanes(a), V::splat(b));
        let d = va.dot(vb);
        let s = (va - vb).scale(d.recip()) + va;
        for (k, a) in a.iter().enumerate() {
            let e = a.x * b.x + a.y * b.y + a.z * b.z;
            assert_eq!(d.0[k].to_bits(), e.to_bits());
            let t = (*a - b) * (1.0 / e) + *a;
            assert_eq!(
                s.lane(k).to_array().map(f64::to_bits),
                t.to_array().map(f64::to_bits)
            );
        }
        let picked = va.select([true, false, true, false], vb);
        assert_eq!([picked.lane(0), picked.lane(1)], [b, va.lane(1)]);
    }
}
