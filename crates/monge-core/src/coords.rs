//! A row of the mesh coordinate by coordinate (§2.2.3): vectors kept as three
//! arrays (a structure of arrays), so that the loops over a row's columns,
//! which are independent, run in SIMD lanes.
//!
//! A vector is read and written whole ([`Coords::get`], [`Coords::set`]) and
//! computed with plain `DVec3` operations, so each column's result is bit for
//! bit what the same formula gives on that column alone: the compiler may put
//! columns in lanes, but adds no fused multiply-add and reorders no sum.

use glam::DVec3;

/// Vectors as three arrays of coordinates.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Coords {
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    pub z: Vec<f64>,
}

impl Coords {
    /// `n` zero vectors.
    pub fn zeros(n: usize) -> Coords {
        Coords {
            x: vec![0.0; n],
            y: vec![0.0; n],
            z: vec![0.0; n],
        }
    }

    /// The vectors `points`.
    pub fn from_points(points: impl ExactSizeIterator<Item = DVec3>) -> Coords {
        let mut c = Coords::zeros(points.len());
        for (k, p) in points.enumerate() {
            c.set(k, p);
        }
        c
    }

    /// Vector `k`.
    #[inline(always)]
    pub fn get(&self, k: usize) -> DVec3 {
        DVec3::new(self.x[k], self.y[k], self.z[k])
    }

    /// Sets vector `k`.
    #[inline(always)]
    pub fn set(&mut self, k: usize, v: DVec3) {
        self.view_mut(self.x.len()).set(k, v);
    }

    /// The first `m` vectors, as slices of length `m` exactly: indexing them
    /// below `m` needs no bound check, so that loops over them run in SIMD.
    #[inline(always)]
    pub fn view(&self, m: usize) -> View<'_> {
        self.range(0..m)
    }

    /// The vectors `r`, as slices of its length exactly (see [`Coords::view`]).
    #[inline(always)]
    pub fn range(&self, r: std::ops::Range<usize>) -> View<'_> {
        View {
            x: &self.x[r.clone()],
            y: &self.y[r.clone()],
            z: &self.z[r],
        }
    }

    /// The first `m` vectors, to write (see [`Coords::view`]).
    #[inline(always)]
    pub fn view_mut(&mut self, m: usize) -> ViewMut<'_> {
        ViewMut {
            x: &mut self.x[..m],
            y: &mut self.y[..m],
            z: &mut self.z[..m],
        }
    }

    /// The vectors `range` (copied), for the loops of one block of columns.
    pub fn slice(&self, range: std::ops::Range<usize>) -> Coords {
        Coords {
            x: self.x[range.clone()].to_vec(),
            y: self.y[range.clone()].to_vec(),
            z: self.z[range].to_vec(),
        }
    }
}

/// Vectors read from a [`Coords`] (see [`Coords::view`]).
#[derive(Clone, Copy)]
pub(crate) struct View<'a> {
    x: &'a [f64],
    y: &'a [f64],
    z: &'a [f64],
}

impl View<'_> {
    /// Vector `k`.
    #[inline(always)]
    pub fn get(&self, k: usize) -> DVec3 {
        DVec3::new(self.x[k], self.y[k], self.z[k])
    }
}

/// Vectors written into a [`Coords`] (see [`Coords::view_mut`]).
pub(crate) struct ViewMut<'a> {
    x: &'a mut [f64],
    y: &'a mut [f64],
    z: &'a mut [f64],
}

impl ViewMut<'_> {
    /// Sets vector `k`.
    #[inline(always)]
    pub fn set(&mut self, k: usize, v: DVec3) {
        self.x[k] = v.x;
        self.y[k] = v.y;
        self.z[k] = v.z;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vectors_are_kept_whole() {
        let p = [DVec3::new(0.1, 0.2, 0.3), DVec3::new(-1.0, 1e-300, 7.0)];
        let mut c = Coords::from_points(p.into_iter());
        assert_eq!((c.x.len(), c.get(0), c.get(1)), (2, p[0], p[1]));
        c.set(0, DVec3::Z);
        assert_eq!(c.slice(0..1), Coords::from_points([DVec3::Z].into_iter()));
    }
}
