//! The discrete Combescure transform (§2.2.3): a mesh whose edges are parallel
//! to those of the Gauss map, fitted to the two guide polylines.

use std::mem::MaybeUninit;
use std::ops::Range;

use glam::DVec3;

use crate::coords::{self, Coords, View};
use crate::gauss_map::GaussRows;
use crate::grid::{quad_sides, Folds, Turn};

/// A face whose last vertex is undefined (§5.2): the Gauss edge along which it
/// is reached is (nearly) parallel to the other Gauss edge at that vertex, or to
/// the plane of its row that cuts it, or has (nearly) zero length.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParallelLines {
    /// The face `(i, j)`; its vertex `(i+1, j+1)` is undefined.
    pub face: (usize, usize),
    /// Sine of the angle between the two Gauss edges at the vertex or, where
    /// smaller, between the Gauss edge `(i, j+1) → (i+1, j+1)` and the plane of
    /// row `i + 1` (the first is the same for any construction of the mesh,
    /// the second is at most the first: their ratio is the sine of the angle
    /// between the Gauss face's plane and the row's).
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
/// proof of Proposition 4): row `i` in the plane through `guide_u[i]` with
/// the normal [`GaussRows::row_normal`]`(i)`. So vertex `(i+1, j)` is where
/// the line through `(i, j)` parallel to the Gauss edge `(i, j) → (i+1, j)`
/// meets the plane of row `i + 1`: the columns are independent chains. Row
/// after row, the columns of a row are computed in SIMD lanes and, with the
/// `parallel` feature, blocks of columns in parallel (rayon), each vertex
/// written once, in place. Every column is computed by the same operations
/// whatever columns share its lanes and whatever the number of threads, so the
/// result is the same to the bit.
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
    let (rows, cols) = (guide_u.len(), guide_v.len());
    let width = block_columns(rows, cols);
    let stream = 2 * rows * cols * std::mem::size_of::<DVec3>() > STREAM_BYTES;
    combescure_in_blocks(gauss, guide_u, guide_v, width, (Kernel::best(), stream))
}

/// [`combescure`] in tasks of `width` columns each (the last one narrower),
/// computed by `kernel`, its outputs written past the cache if `stream`.
fn combescure_in_blocks(
    gauss: &GaussRows,
    guide_u: &[DVec3],
    guide_v: &[DVec3],
    width: usize,
    (kernel, stream): (Kernel, bool),
) -> Result<Transform, ParallelLines> {
    let (rows, cols) = (guide_u.len(), guide_v.len());
    let origin = guide_u[0];
    let columns = Columns {
        gauss,
        guide_u,
        guide_v,
        local_v: Coords::from_points(guide_v.iter().map(|p| *p - origin)),
        rows: guide_u
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let n1 = gauss.row_normal(i);
                (n1, n1.dot(*p - origin), *p - origin)
            })
            .collect(),
        origin,
        stream,
    };
    let len = rows * cols;
    let mut vertices = Vec::with_capacity(len);
    let mut normals = Vec::with_capacity(len);
    let blocks: Vec<Range<usize>> = (0..cols)
        .step_by(width.max(1))
        .map(|c| c..(c + width).min(cols))
        .collect();
    // Each block's part of every row: disjoint pieces of the two outputs.
    let mut parts: Vec<Vec<Piece>> = blocks.iter().map(|_| Vec::with_capacity(rows)).collect();
    let xs = vertices.spare_capacity_mut()[..len].chunks_mut(cols.max(1));
    let ns = normals.spare_capacity_mut()[..len].chunks_mut(cols.max(1));
    for (mut x, mut n) in xs.zip(ns) {
        for (b, part) in blocks.iter().zip(&mut parts) {
            let (x_here, x_rest) = std::mem::take(&mut x).split_at_mut(b.len());
            let (n_here, n_rest) = std::mem::take(&mut n).split_at_mut(b.len());
            part.push((x_here, n_here));
            (x, n) = (x_rest, n_rest);
        }
    }
    let run = |(b, part): (&Range<usize>, Vec<Piece>)| columns.block(kernel, b.clone(), part);
    // One block runs on this thread (no task handed to the pool and waited for).
    let seen = match blocks.len() {
        #[cfg(feature = "parallel")]
        2.. => {
            use rayon::prelude::*;
            let tasks = blocks.par_iter().zip(parts);
            tasks.map(run).reduce(Seen::default, Seen::merge)
        }
        _ => blocks
            .iter()
            .zip(parts)
            .map(run)
            .fold(Seen::default(), Seen::merge),
    };
    if let Some(e) = seen.error {
        return Err(e);
    }
    // SAFETY: the blocks' pieces cover every row of `vertices` and `normals`,
    // and `Columns::block` writes every element of its pieces, so the first `len`
    // elements of both vectors are initialised.
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

/// How the loops over a row's columns are compiled: every kernel runs the same
/// IEEE operations on each column (none adds a fused multiply-add), so the
/// result is the same to the bit; they differ in how many columns one
/// instruction takes.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Kernel {
    /// The target's baseline (SSE2 on x86-64: two columns at a time).
    Baseline,
    /// AVX2 (four columns at a time).
    #[cfg(target_arch = "x86_64")]
    Avx2,
}

impl Kernel {
    /// The fastest kernel this processor runs.
    fn best() -> Kernel {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            return Kernel::Avx2;
        }
        Kernel::Baseline
    }
}

/// One block's part of one row of the outputs: vertices and normals.
type Piece<'a> = (&'a mut [MaybeUninit<DVec3>], &'a mut [MaybeUninit<DVec3>]);

/// Columns per task for a grid of `rows` × `cols` vertices: at most
/// [`WIDEST_TASK`], about two tasks per thread, and at least 64 columns and
/// [`TASK_VERTICES`] vertices (the result does not depend on it).
fn block_columns(rows: usize, cols: usize) -> usize {
    #[cfg(feature = "parallel")]
    let tasks = 2 * rayon::current_num_threads();
    #[cfg(not(feature = "parallel"))]
    let tasks = 1;
    let most = cols.div_ceil(64).min((rows * cols).div_ceil(TASK_VERTICES));
    let tasks = tasks.max(cols.div_ceil(WIDEST_TASK)).min(most);
    cols.div_ceil(tasks.max(1))
}

/// Most columns per task: a task's two rows (vertices and Gauss vertices) and
/// its face codes, 104 bytes per column, then stay in a 32 KiB L1 cache
/// (measured at 1000 × 1000 faces: 250 columns per task 5.6–6.0 ms, 125
/// columns 6.2–7.2 ms, 1001 columns on one thread 14 ms against 11).
const WIDEST_TASK: usize = 256;

/// Fewest vertices worth a task of their own: below, handing work to another
/// thread costs more than it saves.
const TASK_VERTICES: usize = 1 << 15;

/// Output size (vertices and normals) above which they are written past the
/// cache ([`View::write_to`]): larger than a usual last-level cache, so that
/// it would only be evicted again, and the stores save reading its lines in
/// first. Below, the output stays in the cache for whatever reads it next.
const STREAM_BYTES: usize = 32 << 20;

/// What the columns of a task saw (§5.2); merged over tasks in any order.
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

/// [`MIN_CROSSING_SINE`] squared.
const MIN_CROSSING2: f64 = MIN_CROSSING_SINE * MIN_CROSSING_SINE;

/// `1 + 1e-12`: a relative margin, far above round-off, by which a product
/// must clear a bound for a comparison of quotients to be settled without
/// dividing (see [`Columns::faces`]).
const MARGIN: f64 = 1.0 + 1e-12;

/// Everything the columns of the mesh need (§2.2.3).
struct Columns<'a> {
    gauss: &'a GaussRows<'a>,
    guide_u: &'a [DVec3],
    guide_v: &'a [DVec3],
    /// guide_v relative to the start point.
    local_v: Coords,
    /// Per row `i`: the normal `n` and offset `h` of its plane `n · Y = h`, and
    /// guide_u's sample `i`, relative to the start point.
    rows: Vec<(DVec3, f64, DVec3)>,
    /// The start point.
    origin: DVec3,
    /// Whether the outputs are written past the cache (see [`STREAM_BYTES`]).
    stream: bool,
}

/// The vertices and Gauss vertices of one row of a block of columns.
struct Row {
    x: Coords,
    n: Coords,
}

/// A [`Row`]'s first `m` columns, to read without bound checks.
#[derive(Clone, Copy)]
struct RowView<'a> {
    x: View<'a>,
    n: View<'a>,
}

impl Row {
    #[inline(always)]
    fn view(&self, m: usize) -> RowView<'_> {
        RowView {
            x: self.x.view(m),
            n: self.n.view(m),
        }
    }
}

/// What a face of the mesh and of its Gauss map give (§5.2), from the face's
/// four vertices `(i − 1, j − 1)`, `(i, j − 1)`, `(i, j)`, `(i − 1, j)`.
struct Face {
    /// Squared lengths and dot product of the Gauss edges at vertex `(i, j)`:
    /// `d1` along the row, `d2` along the column.
    a11: f64,
    a12: f64,
    a22: f64,
    /// Component of `d2` along the normal of row `i`'s plane.
    across: f64,
    /// The signed sides of the face's turn (see [`quad_sides`]).
    sides: [f64; 4],
}

impl Face {
    /// The face at column `k` of `prev` and `cur` (its right side), in a row
    /// whose plane has the normal `normal`.
    #[inline(always)]
    fn at(prev: RowView, cur: RowView, k: usize, normal: DVec3) -> Face {
        let (np_left, xp_left) = (prev.n.get(k - 1), prev.x.get(k - 1));
        let (np, xp) = (prev.n.get(k), prev.x.get(k));
        let (n_left, x_left) = (cur.n.get(k - 1), cur.x.get(k - 1));
        let (n, x) = (cur.n.get(k), cur.x.get(k));
        let (d1, d2) = (n - n_left, n - np);
        let axis = np_left + n_left + n + np;
        Face {
            a11: d1.dot(d1),
            a12: d1.dot(d2),
            a22: d2.dot(d2),
            across: normal.dot(d2),
            sides: quad_sides(
                &[xp_left, x_left, x, xp],
                axis,
                DVec3::cross,
                DVec3::dot,
                |s| -s,
            ),
        }
    }

    /// `|d1|²·|d2|²` and its part `|d1 × d2|²`: their ratio is the squared sine
    /// between the Gauss edges.
    #[inline(always)]
    fn product_and_gram(&self) -> (f64, f64) {
        let product = self.a11 * self.a22;
        (product, product - self.a12 * self.a12)
    }

    /// 0 or 1 for a usual face turning positively or negatively, 2 otherwise.
    /// A usual face's Gauss edges are long and cross well (sine above the
    /// larger of [`MIN_CROSSING_SINE`] and `sqrt(bound)`): the tests need no
    /// division and are conservative (NaN is not usual), so that a usual face
    /// only needs counting.
    #[inline(always)]
    fn code(&self, bound: f64) -> u64 {
        let s = self.sides;
        let pos = (s[0] > 0.0) & (s[1] > 0.0) & (s[2] > 0.0) & (s[3] > 0.0);
        let neg = (s[0] < 0.0) & (s[1] < 0.0) & (s[2] < 0.0) & (s[3] < 0.0);
        let (product, g) = self.product_and_gram();
        let zero2 = ZERO_GAUSS_EDGE * ZERO_GAUSS_EDGE;
        let well = (self.a11 >= zero2)
            & (self.a22 >= zero2)
            & (g > bound * (product * MARGIN))
            & (self.across * self.across > MIN_CROSSING2 * self.a22 * MARGIN);
        2 - 2 * u64::from(well & pos) - u64::from(well & neg)
    }
}

impl Columns<'_> {
    /// [`Columns::block_with`], by `kernel`.
    fn block(&self, kernel: Kernel, cols: Range<usize>, pieces: Vec<Piece>) -> Seen {
        match kernel {
            // SAFETY: `Kernel::Avx2` is only made where the processor has AVX2.
            #[cfg(target_arch = "x86_64")]
            Kernel::Avx2 => unsafe { self.block_avx2(cols, pieces) },
            Kernel::Baseline => self.block_with(cols, pieces),
        }
    }

    /// [`Columns::block_with`] with AVX2 instructions.
    ///
    /// # Safety
    /// The processor must have AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn block_avx2(&self, cols: Range<usize>, pieces: Vec<Piece>) -> Seen {
        self.block_with(cols, pieces)
    }

    /// The columns `cols` of every row into `pieces` (one per row), and the
    /// faces on their left (§2.2.3, §5.2). Column `cols.start − 1` is computed
    /// too (not written) for the faces between it and the block.
    #[inline(always)]
    fn block_with(&self, cols: Range<usize>, pieces: Vec<Piece>) -> Seen {
        let first = cols.start.saturating_sub(1);
        let span = first..cols.end;
        let (m, skip) = (span.len(), cols.start - first);
        let local_v = self.local_v.slice(span.clone());
        let new_row = || Row {
            x: Coords::zeros(m),
            n: Coords::zeros(m),
        };
        let (mut prev, mut cur) = (new_row(), new_row());
        let mut seen = Seen::default();
        // Usual faces per turn (positive, negative), counted apart (see `faces`).
        let mut more = [0usize; 2];
        let mut codes = vec![2u64; m];
        for (i, (xs, ns)) in pieces.into_iter().enumerate() {
            self.gauss.row_into(i, span.clone(), &mut cur.n);
            let (normal, h, on_guide_u) = self.rows[i];
            if i == 0 {
                cur.x.clone_from(&local_v);
            } else {
                // Vertex (i, j) = xp + t·d on the plane normal·Y = h of row i.
                let (p, n) = (prev.view(m), cur.n.view(m));
                let mut x = cur.x.view_mut(m);
                for k in 0..m {
                    let (xp, d) = (p.x.get(k), n.get(k) - p.n.get(k));
                    let t = (h - normal.dot(xp)) * (1.0 / normal.dot(d));
                    x.set(k, xp + d * t);
                }
                if first == 0 {
                    cur.x.set(0, on_guide_u);
                }
                self.faces(i, (first, &prev, &cur), &mut codes, (&mut seen, &mut more));
            }
            // The guide samples bit for bit, the other vertices moved back from
            // the start point.
            let (xs, ns) = (&mut xs[..m - skip], &mut ns[..m - skip]);
            cur.n.range(skip..m).write_to(None, ns, self.stream);
            if i == 0 {
                for (x, p) in xs.iter_mut().zip(&self.guide_v[cols.clone()]) {
                    x.write(*p);
                }
            } else {
                let lead = usize::from(cols.start == 0);
                let x = cur.x.range(skip + lead..m);
                x.write_to(Some(self.origin), &mut xs[lead..], self.stream);
            }
            if cols.start == 0 {
                xs[0].write(self.guide_u[i]);
            }
            std::mem::swap(&mut prev, &mut cur);
        }
        coords::fence();
        seen.folds.add_more(Turn::Positive, more[0]);
        seen.folds.add_more(Turn::Negative, more[1]);
        seen
    }

    /// The faces `(i − 1, j − 1)` between `prev` and `cur`, rows `i − 1` and
    /// `i` of the columns from `first` (§5.2): where a vertex is defined badly,
    /// the smallest crossing, and how the faces turn. Usual faces (see
    /// [`Face::code`]) are classified in SIMD lanes and only counted into
    /// `more`; the others take the exact path.
    #[inline(always)]
    fn faces(
        &self,
        i: usize,
        (first, prev, cur): (usize, &Row, &Row),
        codes: &mut [u64],
        (seen, more): (&mut Seen, &mut [usize; 2]),
    ) {
        let normal = self.rows[i].0;
        let bound = seen.min_crossing.0.max(MIN_CROSSING2);
        let m = codes.len();
        let (prev, cur) = (prev.view(m), cur.view(m));
        for (k, code) in (1..m).zip(&mut codes[1..]) {
            *code = Face::at(prev, cur, k, normal).code(bound);
        }
        // Usually every face is usual and turns a way seen before: then counting
        // (in SIMD lanes) is all.
        let (mut count, mut other) = ([0usize; 2], 0usize);
        for &code in &codes[1..] {
            count[0] += usize::from(code == 0);
            count[1] += usize::from(code == 1);
            other += usize::from(code == 2);
        }
        let seen_before = |k: usize, t: Turn| count[k] == 0 || seen.folds.has(t);
        if other == 0 && seen_before(0, Turn::Positive) && seen_before(1, Turn::Negative) {
            more[0] += count[0];
            more[1] += count[1];
            return;
        }
        for (k, &code) in codes.iter().enumerate().skip(1) {
            let turn = [Turn::Positive, Turn::Negative].get(code as usize);
            if let Some(&t) = turn.filter(|&&t| seen.folds.has(t)) {
                more[t as usize] += 1;
                continue;
            }
            let f = Face::at(prev, cur, k, normal);
            let face = (i - 1, first + k - 1);
            let (product, g) = f.product_and_gram();
            let sine2 = g / product;
            let plane2 = f.across * f.across / f.a22;
            let zero_edge = f.a11.is_nan()
                || f.a22.is_nan()
                || f.a11.min(f.a22) < ZERO_GAUSS_EDGE * ZERO_GAUSS_EDGE;
            // NaN if either is (`f64::min` would drop it and print the other).
            let worst2 = if sine2.is_nan() || plane2.is_nan() {
                f64::NAN
            } else {
                sine2.min(plane2)
            };
            let parallel = worst2.is_nan() || worst2 <= MIN_CROSSING2;
            if (zero_edge || parallel) && seen.error.is_none() {
                seen.error = Some(ParallelLines {
                    face,
                    sine: if worst2.is_nan() {
                        worst2
                    } else {
                        worst2.max(0.0).sqrt()
                    },
                    zero_edge,
                });
            }
            if sine2 < seen.min_crossing.0 {
                seen.min_crossing = (sine2, face);
            }
            seen.folds.add(face, Turn::of_sides(f.sides));
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
    fn the_result_depends_neither_on_the_tasks_nor_on_the_kernel() {
        // A folded design (θ = 60° on these guides) with 23 columns: tasks of 1
        // to 40 columns (the whole grid in one task, as without the `parallel`
        // feature), computed by the baseline and the best kernel in turn (AVX2
        // where the processor has it), written through the cache or past it.
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
        let whole = combescure_in_blocks(&gauss, &u, &v, 40, (Kernel::Baseline, false)).unwrap();
        assert!(whole.report.folded_faces > 0, "{:?}", whole.report);
        let ways = [Kernel::Baseline, Kernel::best()].map(|k| [(k, false), (k, true)]);
        for (chunk, way) in [1, 2, 3, 5, 8, 12, 22, 40]
            .into_iter()
            .zip(ways.as_flattened().iter().cycle())
        {
            let t = combescure_in_blocks(&gauss, &u, &v, chunk, *way).unwrap();
            assert_eq!(bits(&t.vertices), bits(&whole.vertices), "{chunk}");
            assert_eq!(bits(&t.normals), bits(&whole.normals), "{chunk}");
            assert_eq!(t.report, whole.report, "{chunk}");
        }
    }
}
