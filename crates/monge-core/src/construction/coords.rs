//! A row of the mesh coordinate by coordinate (§2.2.3): vectors kept as three
//! arrays (a structure of arrays), so that the loops over a row's columns,
//! which are independent, run in SIMD lanes.
//!
//! A vector is read and written whole ([`Coords::get`], [`Coords::set`]) and
//! computed with plain `DVec3` operations, so each column's result is bit for
//! bit what the same formula gives on that column alone: the compiler may put
//! columns in lanes, but adds no fused multiply-add and reorders no sum.

use std::mem::MaybeUninit;

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

impl View<'_> {
    /// Writes vector `k` plus `offset` (if any) into `out[k]`, for every `k`
    /// below `out.len()` (at most the view's length). With `stream`, on x86-64,
    /// the stores bypass the cache (non-temporal), so that an output larger
    /// than the cache costs one write of its bytes rather than a read and a
    /// write; [`fence`] must then be called before another thread reads `out`.
    /// The values are the same to the bit either way.
    #[inline(always)]
    pub fn write_to(&self, offset: Option<DVec3>, out: &mut [MaybeUninit<DVec3>], stream: bool) {
        let value = |k: usize| offset.map_or(self.get(k), |o| self.get(k) + o);
        // `out` from its vector `from` on, with plain stores.
        let plain = |out: &mut [MaybeUninit<DVec3>], from: usize| {
            for (k, o) in (from..).zip(out) {
                o.write(value(k));
            }
        };
        #[cfg(target_arch = "x86_64")]
        if stream {
            use std::arch::x86_64::*;
            let m = out.len();
            let (x, y, z) = (&self.x[..m], &self.y[..m], &self.z[..m]);
            // Vector 0 or 1 starts on 16 bytes (vectors are 24 bytes long and
            // 8-aligned); pairs of vectors from there are three 16-byte stores.
            let head = (out.as_ptr() as usize % 16 / 8).min(m);
            plain(&mut out[..head], 0);
            let pairs = (m - head) / 2;
            for p in 0..pairs {
                let k = head + 2 * p;
                // SAFETY: `k + 1 < m`, the length of `x`, `y`, `z` and `out`;
                // `out[k]` is 16-aligned (above); SSE2 is in the x86-64 baseline.
                unsafe {
                    let mut v = [
                        _mm_loadu_pd(x.as_ptr().add(k)),
                        _mm_loadu_pd(y.as_ptr().add(k)),
                        _mm_loadu_pd(z.as_ptr().add(k)),
                    ];
                    if let Some(o) = offset {
                        for (v, o) in v.iter_mut().zip(o.to_array()) {
                            *v = _mm_add_pd(*v, _mm_set1_pd(o));
                        }
                    }
                    let [x, y, z] = v;
                    let to = out.as_mut_ptr().add(k).cast::<f64>();
                    _mm_stream_pd(to, _mm_unpacklo_pd(x, y));
                    _mm_stream_pd(to.add(2), _mm_shuffle_pd::<0b10>(z, x));
                    _mm_stream_pd(to.add(4), _mm_unpackhi_pd(y, z));
                }
            }
            let tail = head + 2 * pairs;
            plain(&mut out[tail..], tail);
            return;
        }
        let _ = stream;
        plain(out, 0);
    }
}

/// Orders the non-temporal stores of [`View::write_to`] before the stores
/// that follow (such as the one that tells another thread the work is done).
#[inline]
pub(crate) fn fence() {
    // SAFETY: SSE is in the x86-64 baseline.
    #[cfg(target_arch = "x86_64")]
    unsafe {
        std::arch::x86_64::_mm_sfence();
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

    #[test]
    fn streamed_vectors_are_the_vectors() {
        // Every length and both alignments of the output (a vector is 24
        // bytes, so the first or the second one starts on 16 bytes).
        let p: Vec<DVec3> = (0..9)
            .map(|k| DVec3::new(k as f64 + 0.1, -0.0, 1e300 / (k as f64 + 1.0)))
            .collect();
        let c = Coords::from_points(p.iter().copied());
        let offset = DVec3::new(1e-17, 3.0, -2.5);
        for start in 0..2 {
            for m in 0..=p.len() - start {
                for add in [None, Some(offset)] {
                    let want = p[..m].iter().map(|&v| add.map_or(v, |o| v + o));
                    let want: Vec<_> = want.map(|v| v.to_array().map(f64::to_bits)).collect();
                    for stream in [false, true] {
                        let mut out = [MaybeUninit::new(DVec3::NAN); 10];
                        let out = &mut out[start..start + m];
                        c.view(m).write_to(add, out, stream);
                        // SAFETY: `MaybeUninit::new` above.
                        let got = out.iter().map(|v| unsafe { v.assume_init() });
                        let got: Vec<_> = got.map(|v| v.to_array().map(f64::to_bits)).collect();
                        assert_eq!(got, want, "{start} {m} {add:?} {stream}");
                    }
                    fence();
                }
            }
        }
    }
}
