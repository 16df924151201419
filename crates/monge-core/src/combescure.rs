//! The discrete Combescure transform (§2.2.3): a mesh whose edges are parallel
//! to those of the Gauss map, fitted to the two guide polylines.

use std::mem::MaybeUninit;

use glam::DVec3;

use crate::gauss_map::{GaussRows, RowLanes};
use crate::grid::{quad_sides, Folds, Turn};
use crate::lanes::{F, LANES, V};

/// A face whose last vertex is undefined (§5.2): the Gauss edge along which it
/// is reached is (nearly) parallel to the other Gauss edge at that vertex, or to
/// the plane of its column that cuts it, or has (nearly) zero length.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParallelLines {
    /// The face `(i, j)`; its vertex `(i+1, j+1)` is undefined.
    pub face: (usize, usize),
    /// Sine of the angle between the two Gauss edges at the vertex or, where
    /// smaller, between the Gauss edge `(i+1, j) → (i+1, j+1)` and the plane of
    /// column `j + 1` (the first is the same for any construction of the mesh,
    /// the second is at most the first: their ratio is the sine of the angle
    /// between the Gauss face's plane and the column's).
    pub sine: f64,
    /// Whether one of the two Gauss edges has (nearly) zero length: the surface
    /// has zero curvature along a curvature line there (a parabolic line such as
    /// the top circle of a torus, or a straight piece of a guide).
    pub zero_edge: bool,
}

/// Length below which an edge of the Gauss map (on the unit sphere) counts as
/// zero: its direction, known to round-off (1e-16) divided by its length, would
/// carry more than 1e-8 of error into the mesh edge parallel to it.
pub const ZERO_GAUSS_EDGE: f64 = 1e-8;

/// What the propagation saw on its way (§5.2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CombescureReport {
    /// The smallest sine of the angle between the two lines that defined a
    /// vertex, and the face where it occurred.
    pub min_crossing: ParallelLines,
    /// Number of folded faces (see [`Folds`]): faces whose corners do not all
    /// turn the same way about the face's node axes (crossed, as a bow-tie, or
    /// pinched to a zero edge), or that turn the other way than most faces:
    /// where the mesh pinches or folds over itself (self-intersection, §5.2).
    pub folded_faces: usize,
    /// The first folded face (row-major), if any.
    pub first_fold: Option<(usize, usize)>,
}

/// Smallest sine of the angle between two lines, or between a line and the
/// plane that cuts it, that still defines a vertex. Below it they are taken as
/// parallel (the Gauss quad is degenerate).
pub const MIN_CROSSING_SINE: f64 = 1e-9;

/// What [`combescure`] builds.
#[derive(Clone, Debug)]
pub struct Transform {
    /// The vertices, row-major.
    pub vertices: Vec<DVec3>,
    /// The Gauss map (node axes), row-major.
    pub normals: Vec<DVec3>,
    /// Pinching and folding (§5.2).
    pub report: CombescureReport,
}

/// The Combescure transform (§2.2.3) of the Gauss map of `gauss` through the two
/// guide polylines, with the Gauss map itself.
///
/// `guide_u[i]` becomes vertex `(i, 0)` and `guide_v[j]` vertex `(0, j)`. Every
/// mesh edge is parallel to the corresponding Gauss edge, so each mesh line lies
/// in a plane parallel to its Gauss line's pencil plane (Joachimsthal; cf. the
/// proof of Proposition 4): column `j` in the plane through `guide_v[j]` with
/// the normal [`GaussRows::column_normal`]`(j)`. So vertex `(i, j+1)` is where
/// the line through `(i, j)` parallel to the Gauss edge `(i, j) → (i, j+1)`
/// meets the plane of column `j + 1`: the rows are independent chains, computed
/// four rows at a time in SIMD lanes and, with the `parallel`
/// feature, in parallel (rayon), each written once, in place. Every row is
/// computed by the same operations whatever rows share its lanes and whatever
/// the number of threads, so the result is the same to the bit.
///
/// The computation is relative to the start point `guide_u[0]` (added back on
/// output; the guide samples are copied bit for bit), so that round-off stays
/// relative to the design's size far from the origin. The guides must have been
/// made with normals that are their Gauss images (see
/// [`crate::gauss_map::guide_normals`]).
///
/// Returns the vertices and normals, row-major, or the first face (row-major)
/// whose last vertex is undefined.
///
/// ```
/// use glam::DVec3;
/// use monge_core::combescure::combescure;
/// use monge_core::gauss_map::{guide_normals, pencil_axes, GaussRows, StartFrame};
/// // Guides on the unit sphere are their own Gauss images, and so is the mesh.
/// let arc = |t: &dyn Fn(f64) -> DVec3| (0..6).map(|k| t(0.1 * k as f64)).collect::<Vec<_>>();
/// let u = arc(&|a| DVec3::new(a.sin(), 0.0, a.cos()));
/// let v = arc(&|b| DVec3::new(0.0, b.sin(), b.cos()));
/// let frame = StartFrame::new(DVec3::X, DVec3::Y, DVec3::Y, DVec3::X);
/// let (nu, nv) = (guide_normals(&u, DVec3::Z), guide_normals(&v, DVec3::Z));
/// let gauss = GaussRows::new(&pencil_axes(&frame, -40.0).unwrap(), &nu, &nv);
/// let t = combescure(&gauss, &u, &v).unwrap();
/// for (x, n) in t.vertices.iter().zip(&t.normals) {
///     assert!(x.abs_diff_eq(*n, 1e-14));
/// }
/// ```
pub fn combescure(
    gauss: &GaussRows,
    guide_u: &[DVec3],
    guide_v: &[DVec3],
) -> Result<Transform, ParallelLines> {
    combescure_in_chunks(gauss, guide_u, guide_v, chunk_rows(guide_u.len()))
}

/// [`combescure`] in tasks of `chunk` rows (a multiple of [`LANES`]).
fn combescure_in_chunks(
    gauss: &GaussRows,
    guide_u: &[DVec3],
    guide_v: &[DVec3],
    chunk: usize,
) -> Result<Transform, ParallelLines> {
    let (rows, cols) = (guide_u.len(), guide_v.len());
    let origin = guide_u[0];
    let rows_of = Rows {
        gauss,
        guide_u,
        guide_v,
        local_u: guide_u.iter().map(|p| *p - origin).collect(),
        columns: guide_v
            .iter()
            .enumerate()
            .map(|(j, p)| {
                let n2 = gauss.column_normal(j);
                (n2, n2.dot(*p - origin), *p - origin)
            })
            .collect(),
        origin,
        cols,
    };
    let len = rows * cols;
    let mut vertices = Vec::with_capacity(len);
    let mut normals = Vec::with_capacity(len);
    let chunk = chunk * cols.max(1);
    let xs = &mut vertices.spare_capacity_mut()[..len];
    let ns = &mut normals.spare_capacity_mut()[..len];
    let run = |(c, (x, n))| rows_of.chunk(c * chunk / cols.max(1), x, n);
    #[cfg(feature = "parallel")]
    let seen = {
        use rayon::prelude::*;
        xs.par_chunks_mut(chunk)
            .zip(ns.par_chunks_mut(chunk))
            .enumerate()
            .map(run)
            .reduce(Seen::default, Seen::merge)
    };
    #[cfg(not(feature = "parallel"))]
    let seen = xs
        .chunks_mut(chunk)
        .zip(ns.chunks_mut(chunk))
        .enumerate()
        .map(run)
        .fold(Seen::default(), Seen::merge);
    if let Some(e) = seen.error {
        return Err(e);
    }
    // SAFETY: the chunks cover `xs` and `ns`, and `Rows::chunk` writes every
    // element of its chunks (every row of its lanes, every column), so the first
    // `len` elements of both vectors are initialised.
    unsafe {
        vertices.set_len(len);
        normals.set_len(len);
    }
    let (sine2, face) = seen.min_crossing;
    Ok(Transform {
        vertices,
        normals,
        report: CombescureReport {
            min_crossing: ParallelLines {
                face,
                sine: sine2.sqrt(),
                zero_edge: false,
            },
            folded_faces: seen.folds.count(),
            first_fold: seen.folds.first(),
        },
    })
}

/// Rows per task: a multiple of [`LANES`], at least 8 rows per lane, and about
/// four tasks per thread (the result does not depend on it).
fn chunk_rows(rows: usize) -> usize {
    #[cfg(feature = "parallel")]
    let tasks = 4 * rayon::current_num_threads();
    #[cfg(not(feature = "parallel"))]
    let tasks = 1;
    let chunks = rows.div_ceil(8 * LANES).clamp(1, tasks);
    rows.div_ceil(chunks).div_ceil(LANES) * LANES
}

/// What the rows of a task saw (§5.2); merged over tasks in any order.
#[derive(Clone, Copy, Debug)]
struct Seen {
    /// How the faces turn.
    folds: Folds,
    /// The smallest squared sine between two Gauss edges at a vertex, and its
    /// face (the first one, row-major, on a tie).
    min_crossing: (f64, (usize, usize)),
    /// The first face (row-major) whose last vertex is undefined.
    error: Option<ParallelLines>,
}

impl Default for Seen {
    fn default() -> Self {
        Seen {
            folds: Folds::default(),
            min_crossing: (1.0, (0, 0)),
            error: None,
        }
    }
}

impl Seen {
    /// What `self` and `other` saw together.
    fn merge(self, other: Seen) -> Seen {
        Seen {
            folds: self.folds.merge(other.folds),
            min_crossing: if other.min_crossing.0 < self.min_crossing.0
                || (other.min_crossing.0 == self.min_crossing.0
                    && other.min_crossing.1 < self.min_crossing.1)
            {
                other.min_crossing
            } else {
                self.min_crossing
            },
            error: [self.error, other.error]
                .into_iter()
                .flatten()
                .min_by_key(|e| e.face),
        }
    }
}

/// Everything the rows of the mesh need (§2.2.3).
struct Rows<'a> {
    gauss: &'a GaussRows<'a>,
    guide_u: &'a [DVec3],
    guide_v: &'a [DVec3],
    /// guide_u relative to its start point.
    local_u: Vec<DVec3>,
    /// Per column `j`: the normal `n` and offset `h` of its plane `n · Y = h`, and
    /// guide_v's sample `j`, relative to the start point.
    columns: Vec<(DVec3, f64, DVec3)>,
    /// The start point.
    origin: DVec3,
    cols: usize,
}

impl Rows<'_> {
    /// Vertex and Gauss rows `r0..` into `xs` and `ns` (whole rows), and the
    /// faces between them and the row before (§2.2.3, §5.2).
    ///
    /// Lane `k` takes the `k`-th quarter of the rows, one row per step,
    /// starting one row early (computed, not written) so that it also sees the
    /// face row between its first row and the one before.
    fn chunk(
        &self,
        r0: usize,
        xs: &mut [MaybeUninit<DVec3>],
        ns: &mut [MaybeUninit<DVec3>],
    ) -> Seen {
        let cols = self.cols;
        let rows = self.local_u.len();
        let count = xs.len() / cols;
        let per_lane = count.div_ceil(LANES);
        let starts: [usize; LANES] = std::array::from_fn(|k| r0 + (k * per_lane).min(count));
        let ends: [usize; LANES] = std::array::from_fn(|k| r0 + ((k + 1) * per_lane).min(count));
        let mut seen = [Seen::default(); LANES];
        // The previous row of each lane: Gauss vertices and vertices.
        let mut prev = vec![(V::splat(DVec3::ZERO), V::splat(DVec3::ZERO)); cols];
        for step in 0..=per_lane {
            // Lane k's row at this step is starts[k] + step − 1.
            let row = |k: usize| (starts[k] + step).checked_sub(1);
            let write: [bool; LANES] =
                std::array::from_fn(|k| row(k).is_some_and(|r| r >= starts[k] && r < ends[k]));
            let check: [bool; LANES] =
                std::array::from_fn(|k| write[k] && step > 0 && row(k) > Some(0));
            let lanes = self
                .gauss
                .rows(std::array::from_fn(|k| row(k).unwrap_or(0).min(rows - 1)));
            let mut n = self.gauss.vertex(&lanes, 0);
            let mut x = V::from_lanes(lanes.rows.map(|i| self.local_u[i]));
            let (mut np, mut xp) = prev[0];
            prev[0] = (n, x);
            self.write((r0, &lanes, write), 0, (xs, ns), (x, n));
            let columns = prev.iter_mut().zip(&self.columns).enumerate();
            for (j, (prev, &(normal, h, on_guide_v))) in columns.skip(1) {
                let (n_left, x_left, np_left, xp_left) = (n, x, np, xp);
                (np, xp) = *prev;
                n = self.gauss.vertex(&lanes, j);
                let normal = V::splat(normal);
                // Vertex (i, j) = x_left + t·d1 on the plane normal·Y = h of column j.
                let d1 = n - n_left;
                let across = normal.dot(d1);
                let t = (F::splat(h) - normal.dot(x_left)) * across.recip();
                x = (x_left + d1.scale(t)).select(lanes.row0, V::splat(on_guide_v));
                *prev = (n, x);
                self.write((r0, &lanes, write), j, (xs, ns), (x, n));
                if check == [false; LANES] {
                    continue;
                }
                // Face (i − 1, j − 1): its Gauss edges at vertex (i, j), and its turn.
                let d2 = n - np;
                let (a11, a12, a22) = (d1.dot(d1), d1.dot(d2), d2.dot(d2));
                let product = a11 * a22;
                let g = product - a12 * a12;
                let sine2 = g.zip(product, |g, p| g / p);
                let plane2 = (across * across).zip(a11, |c, a| c / a);
                let axis = np_left + n_left + n + np;
                let sides = quad_sides(&[xp_left, x_left, x, xp], axis, V::cross, V::dot, |s| {
                    F::splat(0.0) - s
                });
                for k in (0..LANES).filter(|&k| check[k]) {
                    let face = (lanes.rows[k] - 1, j - 1);
                    let seen = &mut seen[k];
                    let (a11, a22) = (a11.0[k], a22.0[k]);
                    let zero_edge = a11.is_nan()
                        || a22.is_nan()
                        || a11.min(a22) < ZERO_GAUSS_EDGE * ZERO_GAUSS_EDGE;
                    let worst2 = sine2.0[k].min(plane2.0[k]);
                    let parallel = g.0[k].is_nan()
                        || plane2.0[k].is_nan()
                        || worst2 <= MIN_CROSSING_SINE * MIN_CROSSING_SINE;
                    if (zero_edge || parallel) && seen.error.is_none() {
                        seen.error = Some(ParallelLines {
                            face,
                            sine: worst2.max(0.0).sqrt(),
                            zero_edge,
                        });
                    }
                    if sine2.0[k] < seen.min_crossing.0 {
                        seen.min_crossing = (sine2.0[k], face);
                    }
                    let turn = Turn::of_sides(sides.map(|s| s.0[k]));
                    seen.folds.add(face, turn);
                }
            }
        }
        seen.into_iter().fold(Seen::default(), Seen::merge)
    }

    /// Column `j` of the rows of `lanes` that are written, into their places
    /// in `xs` and `ns` (whose first row is `r0`): the guide samples bit for
    /// bit, the other vertices moved back from the start point.
    #[inline(always)]
    fn write(
        &self,
        (r0, lanes, write): (usize, &RowLanes, [bool; LANES]),
        j: usize,
        (xs, ns): (&mut [MaybeUninit<DVec3>], &mut [MaybeUninit<DVec3>]),
        (x, n): (V, V),
    ) {
        for k in (0..LANES).filter(|&k| write[k]) {
            let i = lanes.rows[k];
            let at = (i - r0) * self.cols + j;
            xs[at].write(if j == 0 {
                self.guide_u[i]
            } else if i == 0 {
                self.guide_v[j]
            } else {
                x.lane(k) + self.origin
            });
            ns[at].write(n.lane(k));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gauss_map::{guide_normals, pencil_axes, StartFrame};

    fn bits(p: &[DVec3]) -> Vec<[u64; 3]> {
        p.iter().map(|p| p.to_array().map(f64::to_bits)).collect()
    }

    #[test]
    fn the_result_does_not_depend_on_the_tasks() {
        // A folded design (θ = 60° on these guides) with 37 rows: tasks of 4 to
        // 40 rows, the whole grid in one task as without the `parallel` feature.
        let u: Vec<DVec3> = (0..37)
            .map(|k| {
                let t = k as f64 * 0.1;
                DVec3::new(t, 0.0, 0.4 * t * t - 0.1 * t * t * t)
            })
            .collect();
        let v: Vec<DVec3> = (0..23)
            .map(|k| {
                let t = k as f64 * 0.15;
                DVec3::new(0.0, t, -0.3 * t * t + 0.2 * (2.0 * t).sin() * t)
            })
            .collect();
        let tangent_v = DVec3::new(0.0, 1.0, 0.4);
        let frame = StartFrame::new(DVec3::X, tangent_v.normalize(), DVec3::Y, DVec3::X);
        let n_p = frame.n_p;
        let (nu, nv) = (guide_normals(&u, n_p), guide_normals(&v, n_p));
        let gauss = GaussRows::new(&pencil_axes(&frame, 60.0).unwrap(), &nu, &nv);
        let whole = combescure_in_chunks(&gauss, &u, &v, 40).unwrap();
        assert!(whole.report.folded_faces > 0, "{:?}", whole.report);
        for chunk in [4, 8, 12, 36] {
            let t = combescure_in_chunks(&gauss, &u, &v, chunk).unwrap();
            assert_eq!(bits(&t.vertices), bits(&whole.vertices), "{chunk}");
            assert_eq!(bits(&t.normals), bits(&whole.normals), "{chunk}");
            assert_eq!(t.report, whole.report, "{chunk}");
        }
    }
}
