//! Measuring any quad grid independently of how it was made (§2.2, §2.3).
//!
//! This module shares no code with the generator: it takes a finished
//! [`QuadGrid`] and measures, with elementary and numerically careful formulas,
//! how far it is from the guarantees of the paper — planar faces, circular
//! faces, planar curvature lines (§2.2), torsion-free unit node axes (§2.2) and,
//! for conical meshes, vertices whose face normals are concyclic (§2.3). Only
//! what a folded face is (§5.2) is one definition for both, [`QuadGrid::folds`].
//!
//! Lengths are divided by [`Measurements::scale`], the bounding-box diagonal of
//! the grid, so every value is relative to the model size (torsion too: see
//! [`Measurements::torsion`]); normal length and conical error are dimensionless
//! already.
//!
//! NaN coordinates are never hidden: a NaN measurement wins every maximum.

use glam::DVec3;
use nalgebra::DMatrix;
use serde::{Deserialize, Serialize};

use crate::grid::Folds;
use crate::QuadGrid;

/// Where a measurement is worst, and its value (§2.2).
///
/// The meaning of `at` depends on the metric and is documented on each field
/// of [`Measurements`] and on [`conical_error`]. A metric with nothing to
/// measure (e.g. no faces) is `Worst { value: 0.0, at: (0, 0) }`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Worst {
    /// The worst value, relative to the scale for lengths, dimensionless otherwise (§2.2).
    pub value: f64,
    /// Grid indices of the worst element (§2.2).
    pub at: (usize, usize),
}

impl Worst {
    /// Nothing measured yet (§2.2).
    const NONE: Worst = Worst {
        value: 0.0,
        at: (0, 0),
    };

    /// Keep the larger of `self` and `(value, at)`; the first NaN wins and stays.
    fn update(&mut self, value: f64, at: (usize, usize)) {
        if !self.value.is_nan() && (value.is_nan() || value > self.value) {
            *self = Worst { value, at };
        }
    }

    /// The same worst element with its value divided by `scale`.
    fn relative(self, scale: f64) -> Worst {
        Worst {
            value: self.value / scale,
            at: self.at,
        }
    }
}

/// All measurements of a circular quad grid (§2.2).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Measurements {
    /// Model size (§2.2): the bounding-box diagonal ([`QuadGrid::bbox_diagonal`])
    /// every length is divided by; 1 when the diagonal is 0 (all vertices coincide).
    pub scale: f64,
    /// Planar faces (§2.2): max over faces of the distance between the lines of
    /// the two diagonals (see [`face_planarity`]) / scale; `at` = face `(i, j)`.
    pub face_planarity: Worst,
    /// Circular faces (§2.2): max over faces of the distance of one corner from
    /// the circle through the other three (see [`circularity`]) / scale; `at` = face `(i, j)`.
    pub circularity: Worst,
    /// Planar rows (§2.2): max over rows `i` (polylines `(i, 0..cols)`) of the
    /// largest distance of a vertex from the row's least-squares plane (see
    /// [`polyline_planarity`]) / scale; `at` = `(i, j)` of the farthest vertex.
    pub row_planarity: Worst,
    /// Planar columns (§2.2): max over columns `j` (polylines `(0..rows, j)`) of the
    /// largest distance of a vertex from the column's least-squares plane / scale;
    /// `at` = `(i, j)` of the farthest vertex.
    pub column_planarity: Worst,
    /// Torsion-free nodes (§2.2), with normals: max over edges `pq` of
    /// `|det(e, n̂_p, n̂_q)| / scale` (e the edge, n̂ the normalised node axes) — 0
    /// iff the node axes at the two ends of the edge are coplanar (torsion-free
    /// node). It is the volume spanned by the edge and the two unit axes: how far
    /// the edge leaves the plane of the axes, times the sine of their angle,
    /// relative to the model size. (The same with the unit edge would be
    /// ill-conditioned on edges shrunk to round-off, e.g. offsets near a focal point.)
    /// `at` = `(i, j)`, the edge's end with the smaller indices (the edge goes to
    /// `(i, j+1)` or `(i+1, j)`; the one to `(i, j+1)` is scanned first).
    /// Zero-length edges and zero normals count as 0 here (a zero normal is
    /// reported by `normal_length`).
    pub torsion: Option<Worst>,
    /// Unit node axes (§2.2), with normals: max over vertices of `| |n| − 1 |`;
    /// `at` = vertex `(i, j)`.
    pub normal_length: Option<Worst>,
    /// Folded faces (§5.2, [`QuadGrid::folds`]): crossed (bow-tie) or
    /// non-convex faces, and with normals faces turned over against most
    /// others. A count, not an error: not part of [`Measurements::max_error`].
    pub folded_faces: usize,
    /// The first folded face `(i, j)` (row-major), if any.
    pub first_fold: Option<(usize, usize)>,
}

impl Measurements {
    /// The largest of the errors a circular mesh must meet (§2.2): all of them,
    /// circularity and the node axes included; NaN if any of them is NaN.
    pub fn max_error(&self) -> f64 {
        largest(
            [
                Some(self.face_planarity),
                Some(self.circularity),
                Some(self.row_planarity),
                Some(self.column_planarity),
                self.torsion,
                self.normal_length,
            ]
            .into_iter()
            .flatten()
            .map(|w| w.value),
        )
    }

    /// The largest of the errors a conical mesh must meet (§2.3): face
    /// planarity, `conical` (its [`conical_error`], `None` without an interior
    /// vertex), row and column planarity; not circularity nor the node axes,
    /// which a conical mesh has no reason to meet. NaN if any of them is NaN.
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::measure::{conical_error, measure};
    /// use monge_core::QuadGrid;
    /// // A planar 3 × 3 grid of kites: conical (all face normals equal), not circular.
    /// let v = |x: f64, y: f64| DVec3::new(x, y, 0.0);
    /// let g = QuadGrid::new(3, 3, vec![v(0.0, 0.0), v(0.0, 1.0), v(0.0, 2.0), v(1.0, 0.0), v(1.4, 1.4),
    ///     v(1.0, 2.0), v(2.0, 0.0), v(2.0, 1.0), v(2.0, 2.0)], vec![]);
    /// let m = measure(&g);
    /// assert!(m.circularity.value > 0.01);
    /// assert_eq!(m.max_error(), m.circularity.value);
    /// assert_eq!(m.max_error_conical(conical_error(&g)), 0.0);
    /// ```
    pub fn max_error_conical(&self, conical: Option<Worst>) -> f64 {
        largest(
            [
                Some(self.face_planarity),
                conical,
                Some(self.row_planarity),
                Some(self.column_planarity),
            ]
            .into_iter()
            .flatten()
            .map(|w| w.value),
        )
    }
}

/// The largest of `values` (errors ≥ 0, §2.2), 0 for none; NaN if any is NaN.
///
/// ```
/// use monge_core::measure::largest;
/// assert_eq!(largest([1e-16, 3e-15, 0.0]), 3e-15);
/// assert!(largest([1.0, f64::NAN, 2.0]).is_nan());
/// assert_eq!(largest([]), 0.0);
/// ```
pub fn largest(values: impl IntoIterator<Item = f64>) -> f64 {
    values.into_iter().fold(0.0, |m: f64, v| {
        if m.is_nan() || v.is_nan() {
            f64::NAN
        } else {
            m.max(v)
        }
    })
}

/// Why a quad grid cannot be measured (§2.2, §2.3): what [`measurable`] finds.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum MeasureError {
    /// Fewer than 2 × 2 vertices: no face.
    #[error(
        "the mesh has {rows} × {cols} vertices, so no face to measure: a quad mesh has at least \
         2 × 2 vertices"
    )]
    NoFaces {
        /// Rows of vertices.
        rows: usize,
        /// Columns of vertices.
        cols: usize,
    },
    /// A vertex or node axis is NaN or infinite.
    #[error("{what} ({}, {}) is {point:?}, not finite: fix or remove it", at.0, at.1)]
    NotFinite {
        /// `vertex` or `node axis`.
        what: &'static str,
        /// Its row and column.
        at: (usize, usize),
        /// Its coordinates.
        point: [f64; 3],
    },
    /// The mesh is too small or too large for its measurements to be computed.
    #[error(
        "the mesh's size (its bounding-box diagonal) is {size:e}, outside [{min:e}, {max:e}]: \
         at such scales squared lengths underflow or overflow in double precision and the \
         measurements would be meaningless. Rescale the mesh (e.g. use other units)"
    )]
    ScaleOutOfRange {
        /// The bounding-box diagonal (infinite if it overflows).
        size: f64,
        /// [`crate::generate::MIN_SIZE`].
        min: f64,
        /// [`crate::generate::MAX_SIZE`].
        max: f64,
    },
}

/// Whether [`measure`] can measure `grid` (§2.2, §2.3): at least one face, every
/// vertex and node axis finite, and a size (bounding-box diagonal) in the range
/// the generator accepts, [`MIN_SIZE`](crate::generate::MIN_SIZE) to
/// [`MAX_SIZE`](crate::generate::MAX_SIZE). A single point (size 0) passes.
///
/// ```
/// use glam::DVec3;
/// use monge_core::measure::{measurable, MeasureError};
/// use monge_core::QuadGrid;
/// let square = |s: f64| QuadGrid::new(2, 2, vec![DVec3::ZERO, DVec3::Y * s, DVec3::X * s, DVec3::ONE * s], vec![]);
/// assert!(measurable(&square(1.0)).is_ok());
/// assert!(matches!(measurable(&square(1e200)), Err(MeasureError::ScaleOutOfRange { .. })));
/// let line = QuadGrid::new(1, 2, vec![DVec3::ZERO, DVec3::X], vec![]);
/// assert_eq!(measurable(&line), Err(MeasureError::NoFaces { rows: 1, cols: 2 }));
/// ```
pub fn measurable(grid: &QuadGrid) -> Result<(), MeasureError> {
    use crate::generate::{MAX_SIZE, MIN_SIZE};
    if grid.rows < 2 || grid.cols < 2 {
        return Err(MeasureError::NoFaces {
            rows: grid.rows,
            cols: grid.cols,
        });
    }
    for (what, points) in [("vertex", &grid.vertices), ("node axis", &grid.normals)] {
        if let Some(k) = points.iter().position(|p| !p.is_finite()) {
            return Err(MeasureError::NotFinite {
                what,
                at: (k / grid.cols, k % grid.cols),
                point: points[k].to_array(),
            });
        }
    }
    let size = grid.bbox_diagonal();
    if size != 0.0 && !(MIN_SIZE..=MAX_SIZE).contains(&size) {
        return Err(MeasureError::ScaleOutOfRange {
            size,
            min: MIN_SIZE,
            max: MAX_SIZE,
        });
    }
    Ok(())
}

/// Measure planarity and circularity of faces, planarity of rows and columns,
/// and (with normals) torsion and unit length of the node axes (§2.2).
///
/// ```
/// use glam::DVec3;
/// use monge_core::measure::measure;
/// use monge_core::QuadGrid;
/// // A planar 2 × 1 rectangle, one face: planar and circular.
/// let g = QuadGrid::new(2, 2, vec![DVec3::ZERO, DVec3::Y, 2.0 * DVec3::X, 2.0 * DVec3::X + DVec3::Y], vec![]);
/// let m = measure(&g);
/// assert_eq!(m.scale, 5f64.sqrt());
/// assert!(m.face_planarity.value <= 1e-15 && m.circularity.value <= 1e-15);
/// assert!(m.torsion.is_none());
/// // Lift corners (0, 1) and (1, 0) by 0.1: the diagonals' lines are now 0.1 apart.
/// let mut twisted = g.clone();
/// twisted.vertices[1].z = 0.1;
/// twisted.vertices[2].z = 0.1;
/// let m = measure(&twisted);
/// assert!((m.face_planarity.value * m.scale - 0.1).abs() < 1e-15);
/// assert_eq!(m.face_planarity.at, (0, 0));
/// assert!(m.max_error() >= m.face_planarity.value);
/// ```
pub fn measure(grid: &QuadGrid) -> Measurements {
    let diagonal = grid.bbox_diagonal();
    let scale = if diagonal > 0.0 { diagonal } else { 1.0 };
    // Row by row and column by column, side by side, merged in order: the same
    // worst elements (the first of equal ones) as one pass, whatever the threads.
    let mut all = RowMeasures::default();
    for row in crate::tasks::map(grid.rows, |i| RowMeasures::of(grid, i, scale)) {
        all.merge(row);
    }
    let mut columns = Worst::NONE;
    let column = |j: usize| polyline_planarity(&grid.column(j).collect::<Vec<_>>());
    for (j, (d, i)) in crate::tasks::map(grid.cols, column).into_iter().enumerate() {
        columns.update(d, (i, j));
    }
    let (torsion, normal_length) = if grid.normals.is_empty() {
        (None, None)
    } else {
        (Some(all.torsion), Some(all.length))
    };
    Measurements {
        scale,
        folded_faces: all.folds.count(),
        first_fold: all.folds.first(),
        face_planarity: all.planar.relative(scale),
        circularity: all.circular.relative(scale),
        row_planarity: all.row.relative(scale),
        column_planarity: columns.relative(scale),
        torsion,
        normal_length,
    }
}

/// What [`measure`] finds in one row: its faces (below it), its polyline and
/// its node axes.
struct RowMeasures {
    planar: Worst,
    circular: Worst,
    row: Worst,
    torsion: Worst,
    length: Worst,
    folds: Folds,
}

impl Default for RowMeasures {
    fn default() -> Self {
        RowMeasures {
            planar: Worst::NONE,
            circular: Worst::NONE,
            row: Worst::NONE,
            torsion: Worst::NONE,
            length: Worst::NONE,
            folds: Folds::default(),
        }
    }
}

impl RowMeasures {
    /// Row `i` of `grid`, lengths divided by `scale` where [`node_axes`] does.
    fn of(grid: &QuadGrid, i: usize, scale: f64) -> RowMeasures {
        let mut m = RowMeasures::default();
        if i + 1 < grid.rows {
            for j in 0..grid.cols.saturating_sub(1) {
                let q = grid.face(i, j);
                m.planar.update(face_planarity(&q), (i, j));
                m.circular.update(circularity(&q), (i, j));
                m.folds.add((i, j), grid.face_turn(i, j));
            }
        }
        let (d, j) = polyline_planarity(&grid.row(i).collect::<Vec<_>>());
        m.row.update(d, (i, j));
        if !grid.normals.is_empty() {
            node_axes(grid, i, scale, (&mut m.torsion, &mut m.length));
        }
        m
    }

    /// `self` then `next` (a later row).
    fn merge(&mut self, next: RowMeasures) {
        for (worst, later) in [
            (&mut self.planar, next.planar),
            (&mut self.circular, next.circular),
            (&mut self.row, next.row),
            (&mut self.torsion, next.torsion),
            (&mut self.length, next.length),
        ] {
            worst.update(later.value, later.at);
        }
        self.folds = self.folds.merge(next.folds);
    }
}

/// Torsion and unit length of the node axes of row `i` (§2.2), into `(torsion, length)`.
fn node_axes(grid: &QuadGrid, i: usize, scale: f64, (torsion, length): (&mut Worst, &mut Worst)) {
    for j in 0..grid.cols {
        let k = grid.index(i, j);
        let (p, n) = (grid.vertices[k], grid.normals[k]);
        length.update((n.length() - 1.0).abs(), (i, j));
        let mut edge = |q: usize| {
            let e = grid.vertices[q] - p;
            let det = e.dot(
                n.normalize_or_zero()
                    .cross(grid.normals[q].normalize_or_zero()),
            );
            torsion.update(det.abs() / scale, (i, j));
        };
        if j + 1 < grid.cols {
            edge(k + 1);
        }
        if i + 1 < grid.rows {
            edge(k + grid.cols);
        }
    }
}

/// Face planarity of a quad `[A, B, C, D]` (§2.2): the distance between the
/// lines `AC` and `BD` of its diagonals, in absolute length units.
///
/// The four corners are coplanar iff the two diagonal lines meet (or are
/// parallel), so this is 0 exactly for planar quads; for a nearly planar convex
/// quad it is the width of the thinnest slab containing the corners. For a
/// non-convex or crossed face the lines meet outside the face and their
/// distance magnifies the deviation from a plane; when the diagonals are
/// (nearly) parallel — the angle between them below 1e-6 rad, only possible
/// for such a degenerate face — the magnification is unbounded, so the distance
/// of the remaining corner from the plane of the best-shaped corner triple (see
/// [`circularity`]) is used instead; 0 if all four corners are collinear.
///
/// ```
/// use glam::DVec3;
/// use monge_core::measure::face_planarity;
/// // A twisted unit square: C lifted by h. Diagonal AC rises h over its length.
/// let h = 0.25;
/// let q = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, h), DVec3::Y];
/// // Line AC at its crossing with BD (x = y = 1/2) is at height h/2; BD is at 0.
/// let expect = h / 2.0 / (1.0 + h * h / 2.0).sqrt();
/// assert!((face_planarity(&q) - expect).abs() < 1e-16);
/// ```
pub fn face_planarity(quad: &[DVec3; 4]) -> f64 {
    let [a, b, c, d] = *quad;
    let (ac, bd) = (c - a, d - b);
    let n = ac.cross(bd);
    let nn = n.length();
    if nn > 1e-6 * ac.length() * bd.length() {
        (b - a).dot(n).abs() / nn
    } else {
        let k = best_triple(quad);
        let [p, q, r] = triple(quad, k);
        let normal = (q - p).cross(r - p).normalize_or_zero();
        (quad[k] - p).dot(normal).abs()
    }
}

/// Circularity of a quad `[A, B, C, D]` (§2.2): the distance of one corner from
/// the circle through the other three, in absolute length units.
///
/// The omitted corner is the one whose complementary triple is best shaped
/// (largest `2·area / longest edge²`, i.e. farthest from collinear): the
/// circumcircle of that triple is the best-conditioned one, so noise on a thin
/// or nearly straight corner cannot blow the value up. For a cyclic quad all
/// four triples share one circle, so the choice only matters for conditioning;
/// taking the maximum over all four triples instead would let a near-collinear
/// triple (huge, unstable circumcircle) report a spurious large error.
///
/// The distance from a point `P` to a circle (centre `c`, radius `r`, unit
/// normal `ν`) is `√(h² + (|P' − c| − r)²)` with `h = (P − c)·ν` the
/// out-of-plane offset and `P' = P − hν` the in-plane projection. It is 0 iff
/// the quad is planar and its corners are concyclic. All corners on one line
/// (a circle of infinite radius) measure 0.
///
/// ```
/// use glam::DVec3;
/// use monge_core::measure::circularity;
/// // Kite A(−1,0) B(0,−1) C(2,0) D(0,1): the best triple BCD has the circle
/// // centred at (3/4, 0) with radius 5/4; A is at distance 7/4 from the centre.
/// let q = [DVec3::new(-1.0, 0.0, 0.0), DVec3::new(0.0, -1.0, 0.0), DVec3::new(2.0, 0.0, 0.0), DVec3::new(0.0, 1.0, 0.0)];
/// assert!((circularity(&q) - 0.5).abs() < 1e-15);
/// ```
pub fn circularity(quad: &[DVec3; 4]) -> f64 {
    let k = best_triple(quad);
    let [a, b, c] = triple(quad, k);
    // Relative to corner c, so that no coordinate far from the origin rounds, and
    // in units of a power of two near the triple's size (exact), so that the
    // fifth powers of lengths below neither overflow nor underflow.
    let unit = power_of_two_below((a - c).abs().max((b - c).abs()).max_element());
    if unit == 0.0 {
        return 0.0; // the triple is one point: the four corners are collinear
    }
    let (u, v) = ((a - c) / unit, (b - c) / unit);
    let w = u.cross(v);
    let w2 = w.length_squared();
    if w2 == 0.0 {
        return 0.0; // all four corners collinear (the best triple is)
    }
    let centre = (u.length_squared() * v - v.length_squared() * u).cross(w) / (2.0 * w2);
    let radius = ((u - centre).length() + (v - centre).length() + centre.length()) / 3.0;
    let normal = w / w2.sqrt();
    let p = (quad[k] - c) / unit - centre;
    let h = p.dot(normal);
    h.hypot((p - h * normal).length() - radius) * unit
}

/// The largest power of two `≤ x` for a positive normal `x` (its exponent
/// bits alone); 0 for 0, and `x` itself when it is subnormal or not finite.
fn power_of_two_below(x: f64) -> f64 {
    if x.is_normal() {
        f64::from_bits(x.to_bits() & 0x7ff0_0000_0000_0000)
    } else {
        x
    }
}

/// The three corners of `quad` other than corner `k`, in cyclic order.
fn triple(quad: &[DVec3; 4], k: usize) -> [DVec3; 3] {
    [quad[(k + 1) % 4], quad[(k + 2) % 4], quad[(k + 3) % 4]]
}

/// The corner whose complementary triple is best shaped: largest
/// `2·area / longest edge²` (0 for collinear, √3/2 for equilateral); the first on ties.
fn best_triple(quad: &[DVec3; 4]) -> usize {
    let shape = |[a, b, c]: [DVec3; 3]| {
        let longest = (b - a)
            .length_squared()
            .max((c - b).length_squared())
            .max((a - c).length_squared());
        let area2 = (b - a).cross(c - a).length();
        if longest > 0.0 {
            area2 / longest
        } else {
            0.0
        }
    };
    let mut best = (0, shape(triple(quad, 0)));
    for k in 1..4 {
        let s = shape(triple(quad, k));
        if s > best.1 {
            best = (k, s);
        }
    }
    best.0
}

/// Planarity of a polyline (§2.2): the largest distance of a point from the
/// least-squares plane of all points, and the index of that point (absolute
/// length units).
///
/// The plane passes through the centroid; its normal is the right singular
/// vector of the smallest singular value of the centred `n × 3` point matrix.
/// The SVD of the points themselves (not an eigen-decomposition of their
/// covariance, which squares the condition number) keeps the error of every
/// distance at the rounding level of the coordinates even for nearly straight
/// polylines, where the plane is barely determined; a straight polyline measures
/// 0 up to rounding, a polyline of at most 3 points exactly 0. A non-finite point
/// yields NaN (at that point).
///
/// ```
/// use glam::DVec3;
/// use monge_core::measure::polyline_planarity;
/// let mut p: Vec<DVec3> = (0..7).map(|k| DVec3::new(k as f64, (k * k) as f64, 0.0)).collect();
/// assert!(polyline_planarity(&p).0 < 1e-14);
/// p[3].z = 1.0; // the least-squares plane tilts; point 3 stays the farthest
/// let (d, k) = polyline_planarity(&p);
/// assert_eq!(k, 3);
/// assert!(d > 0.5 && d < 1.0);
/// ```
pub fn polyline_planarity(points: &[DVec3]) -> (f64, usize) {
    if let Some(bad) = points.iter().position(|p| !p.is_finite()) {
        return (f64::NAN, bad); // the SVD would not converge; report, never hide
    }
    if points.len() < 4 {
        // Three points always lie in a plane, however close to a line they are.
        return (0.0, 0);
    }
    // Relative to the first point, then to the centroid (never added back), to
    // keep the rounding error relative to the polyline's size rather than its
    // distance to the origin.
    let origin = points[0];
    let centroid = points.iter().map(|p| *p - origin).sum::<DVec3>() / points.len() as f64;
    let local = |p: &DVec3| (*p - origin) - centroid;
    let m = DMatrix::from_fn(points.len(), 3, |r, c| local(&points[r])[c]);
    if let Some(bad) = (0..points.len()).find(|&r| !local(&points[r]).is_finite()) {
        // Finite points whose differences overflow (beyond ±9e307): the SVD
        // would panic ("Singular value was NaN"); report, never hide.
        return (f64::NAN, bad);
    }
    // Golub–Kahan converges in a few sweeps per singular value; the cap only
    // guards against pathological input, which is then reported as NaN.
    let Some(svd) = m.try_svd(false, true, f64::EPSILON, 10_000) else {
        return (f64::NAN, 0);
    };
    let v_t = svd.v_t.expect("v_t was requested");
    let k = svd.singular_values.imin();
    let normal = DVec3::new(v_t[(k, 0)], v_t[(k, 1)], v_t[(k, 2)]);
    let mut worst = Worst::NONE;
    for (idx, p) in points.iter().enumerate() {
        worst.update(local(p).dot(normal).abs(), (idx, 0));
    }
    (worst.value, worst.at.0)
}

/// Conical error of a quad grid (§2.3): at every interior vertex, how far the
/// unit normals of its four faces are from lying on one circle of the unit sphere.
///
/// A conical mesh has, at each vertex, four face planes tangent to one cone of
/// revolution, i.e. the four unit face normals lie on a circle of S², i.e. they
/// are coplanar as points. The face normal is the normalised cross product of
/// the face's diagonals `(C − A) × (D − B)`. The four normals, taken in cyclic
/// order around the vertex (faces `(i−1, j−1), (i, j−1), (i, j), (i−1, j)`),
/// form a quad on S² whose [`face_planarity`] (distance between its diagonal
/// lines — symmetric in the four normals) is the error at the vertex. It is
/// dimensionless (a distance on the unit sphere's scale) and not divided by
/// the grid's scale. `at` = the vertex `(i, j)`.
///
/// Vertices next to a degenerate face (zero diagonal cross product, no normal)
/// are skipped. `None` when the grid has no interior vertex (fewer than 3 rows
/// or columns).
pub fn conical_error(grid: &QuadGrid) -> Option<Worst> {
    if grid.rows < 3 || grid.cols < 3 {
        return None;
    }
    let normal = |i: usize, j: usize| {
        let [a, b, c, d] = grid.face(i, j);
        (c - a).cross(d - b).try_normalize()
    };
    let mut worst = Worst::NONE;
    for i in 1..grid.rows - 1 {
        for j in 1..grid.cols - 1 {
            let around = [
                normal(i - 1, j - 1),
                normal(i, j - 1),
                normal(i, j),
                normal(i - 1, j),
            ];
            if let [Some(a), Some(b), Some(c), Some(d)] = around {
                worst.update(face_planarity(&[a, b, c, d]), (i, j));
            }
        }
    }
    Some(worst)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f64, y: f64, z: f64) -> DVec3 {
        DVec3::new(x, y, z)
    }

    /// A one-face grid with corners `A, B, C, D` = `(0,0), (1,0), (1,1), (0,1)`.
    fn one_face([a, b, c, d]: [DVec3; 4]) -> QuadGrid {
        QuadGrid::new(2, 2, vec![a, d, b, c], vec![])
    }

    #[test]
    fn finite_points_whose_differences_overflow_are_nan_not_a_panic() {
        // Once "Singular value was NaN" (a Python offset of 1.5e308).
        let p = [
            v(-1.5e308, 0.0, 0.0),
            v(1.5e308, 0.0, 0.0),
            v(0.0, 1.0, 0.0),
            v(0.0, 0.0, 1.0),
        ];
        assert!(polyline_planarity(&p).0.is_nan());
        let g = QuadGrid::new(2, 2, p.to_vec(), vec![]);
        let _ = measure(&g); // no panic; `measurable` says why it means nothing:
        assert!(matches!(
            measurable(&g),
            Err(MeasureError::ScaleOutOfRange { .. })
        ));
        let mut g = g;
        g.vertices[3].y = f64::INFINITY;
        assert!(matches!(
            measurable(&g),
            Err(MeasureError::NotFinite {
                what: "vertex",
                at: (1, 1),
                ..
            })
        ));
        g.vertices[3].y = 0.0;
        g.normals = vec![DVec3::Z, DVec3::Z, DVec3::NAN, DVec3::Z];
        assert!(matches!(
            measurable(&g),
            Err(MeasureError::NotFinite {
                what: "node axis",
                at: (1, 0),
                ..
            })
        ));
    }

    #[test]
    fn the_first_of_equal_worst_elements_is_reported_and_a_nan_wins() {
        // A flat 6 × 3 grid; faces (1, 1) and (3, 1) twisted alike (corner
        // (i + 1, 2) lifted): rows are measured side by side and merged in order.
        let flat = |i: usize, j: usize| v(i as f64, j as f64, 0.0);
        let mut g = QuadGrid::new(6, 3, (0..18).map(|k| flat(k / 3, k % 3)).collect(), vec![]);
        for i in [1, 3] {
            g.vertices[(i + 1) * 3 + 2].z = 0.25;
        }
        let m = measure(&g);
        assert!(m.face_planarity.value > 0.0);
        assert_eq!(m.face_planarity.at, (1, 1));
        // A NaN in row 5 (the last) beats every number, wherever it is.
        g.vertices[5 * 3].x = f64::NAN;
        let m = measure(&g);
        assert!(m.face_planarity.value.is_nan());
        assert_eq!(m.face_planarity.at, (4, 0));
        assert!(m.row_planarity.value.is_nan() && m.row_planarity.at == (5, 0));
    }

    const TORUS_R: f64 = 3.0;
    const TORUS_TUBE: f64 = 1.0;

    fn torus_u(i: usize) -> f64 {
        0.3 + 0.07 * i as f64
    }
    fn torus_v(j: usize) -> f64 {
        -1.2 + 0.09 * j as f64
    }

    /// A torus patch: `i ↦ u` (around the axis), `j ↦ v` (around the tube),
    /// normals radial from the tube's centre circle.
    fn torus(rows: usize, cols: usize) -> QuadGrid {
        let mut vertices = Vec::new();
        let mut normals = Vec::new();
        for i in 0..rows {
            for j in 0..cols {
                let (u, w) = (torus_u(i), torus_v(j));
                let n = v(w.cos() * u.cos(), w.cos() * u.sin(), w.sin());
                vertices.push(TORUS_R * v(u.cos(), u.sin(), 0.0) + TORUS_TUBE * n);
                normals.push(n);
            }
        }
        QuadGrid::new(rows, cols, vertices, normals)
    }

    #[test]
    fn measure_rectangle_and_isosceles_trapezoid_are_circular() {
        let rect = one_face([
            v(0.0, 0.0, 0.0),
            v(3.0, 0.0, 0.0),
            v(3.0, 1.0, 0.0),
            v(0.0, 1.0, 0.0),
        ]);
        let trap = one_face([
            v(-2.0, 0.0, 1.0),
            v(2.0, 0.0, 1.0),
            v(0.7, 1.3, 1.0),
            v(-0.7, 1.3, 1.0),
        ]);
        for g in [rect, trap] {
            let m = measure(&g);
            assert!(m.face_planarity.value <= 1e-15, "{m:?}");
            assert!(m.circularity.value <= 1e-15, "{m:?}");
            assert!(m.max_error() <= 1e-15, "{m:?}");
        }
    }

    #[test]
    fn measure_kite_has_hand_computed_circularity() {
        // Best triple BCD (shape 4/5 vs 1/2 for ABD, 1/3 for ABC and CDA):
        // circle centre (3/4, 0), radius 5/4; A = (−1, 0) is 7/4 from the centre.
        let g = one_face([
            v(-1.0, 0.0, 0.0),
            v(0.0, -1.0, 0.0),
            v(2.0, 0.0, 0.0),
            v(0.0, 1.0, 0.0),
        ]);
        let m = measure(&g);
        assert_eq!(m.scale, 13f64.sqrt());
        assert!((m.circularity.value - 0.5 / 13f64.sqrt()).abs() < 1e-16);
        assert!(m.face_planarity.value <= 1e-16);
    }

    #[test]
    fn circularity_scales_with_the_quad_at_every_accepted_size() {
        // The kite (circularity 1/2) at the extremes of the accepted design sizes
        // and beyond: lengths to the fifth power would overflow or underflow.
        let kite = [
            v(-1.0, 0.0, 0.0),
            v(0.0, -1.0, 0.0),
            v(2.0, 0.0, 0.0),
            v(0.0, 1.0, 0.0),
        ];
        for s in [1e-150, 1e-100, 1e-60, 1.0, 1e60, 1e100, 1e150] {
            let c = circularity(&kite.map(|p| p * s));
            assert!((c / s - 0.5).abs() < 1e-15, "size {s:e}: {c:e}");
        }
        // At a power of two the value is the same to the last bit.
        let c = circularity(&kite.map(|p| p * 2f64.powi(200)));
        assert_eq!(c, 0.5 * 2f64.powi(200));
    }

    #[test]
    fn measure_twisted_quad_has_expected_diagonal_distance() {
        // Square of side 2 with B and D lifted by h, A and C lowered by h: the
        // diagonals are horizontal lines at heights −h and +h, crossing in plan.
        let h = 0.3;
        let g = one_face([
            v(0.0, 0.0, -h),
            v(2.0, 0.0, h),
            v(2.0, 2.0, -h),
            v(0.0, 2.0, h),
        ]);
        let m = measure(&g);
        assert!((m.face_planarity.value * m.scale - 2.0 * h).abs() < 1e-15);
        // Not planar, hence not circular either.
        assert!(m.circularity.value > 0.0);
    }

    #[test]
    fn measure_parallel_diagonals_fall_back_to_plane_distance() {
        // Diagonals AC and BD both along x: a degenerate (crossed) face.
        let strip = [
            v(0.0, 0.0, 0.0),
            v(0.0, 1.0, 0.5),
            v(2.0, 0.0, 0.0),
            v(2.0, 1.0, 0.5),
        ];
        assert!(face_planarity(&strip) < 1e-16); // two parallel lines span a plane
                                                 // Lift D by 0.5 off that plane (normal (0, −1, 2)/√5): the diagonals are
                                                 // no longer parallel, so the line distance applies again and is positive.
        let mut lifted = strip;
        lifted[3] += 0.5 * v(0.0, -1.0, 2.0) / 5f64.sqrt();
        assert!(face_planarity(&lifted) > 0.0);
        // A crossed face, diagonals at an angle 1e-9 (below the 1e-6
        // threshold): their lines are 1 apart, yet the corners are only 2e-9
        // off a plane. The fallback (all four triples tie; A off plane BCD) says so.
        let nearly = [
            v(0.0, 0.0, 0.0),
            v(0.0, 1.0, 0.0),
            v(2.0, 0.0, 0.0),
            v(2.0, 1.0, 2e-9),
        ];
        assert!(
            (face_planarity(&nearly) - 2e-9).abs() < 1e-15,
            "{}",
            face_planarity(&nearly)
        );
        // Collinear corners: planar and (generalised) circular.
        let line = [
            v(0.0, 0.0, 0.0),
            v(1.0, 1.0, 1.0),
            v(3.0, 3.0, 3.0),
            v(2.0, 2.0, 2.0),
        ];
        assert_eq!(face_planarity(&line), 0.0);
        assert_eq!(circularity(&line), 0.0);
    }

    #[test]
    fn measure_long_thin_face_has_no_spurious_circularity() {
        let l = 1e4;
        let eps = 1e-9;
        let rect = [
            v(0.0, 0.0, 0.0),
            v(l, 0.0, 0.0),
            v(l, 1.0, 0.0),
            v(0.0, 1.0, 0.0),
        ];
        assert!(circularity(&rect) <= 1e-15 * l);
        // D moved along the circle's normal direction (≈ x): error ≈ eps.
        let mut q = rect;
        q[3].x += eps;
        let c = circularity(&q);
        assert!((c - eps).abs() < 1e-3 * eps, "{c}");
        // Any corner moved by eps in any direction: error at most ≈ eps.
        for k in 0..4 {
            for d in [DVec3::X, DVec3::Y, DVec3::Z, -DVec3::X, -DVec3::Y] {
                let mut q = rect;
                q[k] += eps * d;
                let c = circularity(&q);
                assert!(c <= 1.01 * eps, "corner {k} dir {d}: {c}");
            }
        }
    }

    #[test]
    fn measure_exact_torus_patch_is_clean() {
        let g = torus(12, 9);
        let m = measure(&g);
        assert!(m.max_error() <= 1e-14, "{m:?}");
        assert!(m.torsion.unwrap().value <= 1e-14);
        assert!(m.normal_length.unwrap().value <= 1e-14);
        let t = measure(&g.transposed());
        assert!(t.max_error() <= 1e-14, "{t:?}");
    }

    #[test]
    fn measure_vertex_moved_off_its_face_plane_is_located() {
        let mut g = torus(12, 9);
        // Vertex (0, 0) is corner A of face (0, 0) only; move it along the face normal.
        let [a, b, c, d] = g.face(0, 0);
        let nu = (c - a).cross(d - b).normalize();
        let delta = 1e-7;
        g.vertices[0] += delta * nu;
        let m = measure(&g);
        // The diagonals of the isosceles trapezoid cross at A + s (C − A),
        // s = |AB| / (|AB| + |DC|); the lifted line AC moves there by (1 − s) δ.
        let s = (b - a).length() / ((b - a).length() + (c - d).length());
        let expect = (1.0 - s) * delta / m.scale;
        assert_eq!(m.face_planarity.at, (0, 0));
        assert!(
            (m.face_planarity.value - expect).abs() < 1e-5 * expect,
            "{m:?}"
        );
        // One corner δ out of the plane of the other three.
        assert_eq!(m.circularity.at, (0, 0));
        let rel = m.circularity.value * m.scale / delta;
        assert!((0.9..1.1).contains(&rel), "{rel}");
    }

    #[test]
    fn measure_bent_row_is_caught_with_its_index() {
        let mut g = torus(12, 9);
        let (i0, j0) = (7, 4);
        let u = torus_u(i0);
        // Perpendicular to row i0's meridian plane (tangent to column j0's circle).
        let delta = 1e-6;
        let k = g.index(i0, j0);
        g.vertices[k] += delta * v(-u.sin(), u.cos(), 0.0);
        let m = measure(&g);
        assert_eq!(m.row_planarity.at, (i0, j0));
        let rel = m.row_planarity.value * m.scale / delta;
        assert!((0.5..=1.0).contains(&rel), "{rel}");
        assert!(m.column_planarity.value <= 1e-14, "{m:?}");
        let t = measure(&g.transposed());
        assert_eq!(t.column_planarity.at, (j0, i0));
        assert_eq!(t.column_planarity.value, m.row_planarity.value);
        assert!(t.row_planarity.value <= 1e-14);
    }

    #[test]
    fn measure_long_normal_is_reported() {
        let mut g = torus(6, 5);
        let k = g.index(2, 3);
        g.normals[k] *= 1.1;
        let m = measure(&g);
        let l = m.normal_length.unwrap();
        assert_eq!(l.at, (2, 3));
        assert!((l.value - 0.1).abs() < 1e-15);
        assert!(m.torsion.unwrap().value <= 1e-14);
        assert_eq!(m.max_error(), l.value);
    }

    #[test]
    fn measure_normal_rotated_about_its_edge_gives_torsion() {
        let mut g = torus(6, 5);
        let (i0, j0) = (2, 2);
        let (p, q) = (g.index(i0, j0), g.index(i0, j0 + 1));
        let e = (g.vertices[q] - g.vertices[p]).normalize();
        let phi: f64 = 0.01;
        let n = g.normals[p];
        let rotated = n * phi.cos() + e.cross(n) * phi.sin() + e * e.dot(n) * (1.0 - phi.cos());
        g.normals[p] = rotated;
        let m = measure(&g);
        let t = m.torsion.unwrap();
        let edge = (g.vertices[q] - g.vertices[p]).length() / m.scale;
        let expect = e.dot(rotated.cross(g.normals[q])).abs() * edge;
        assert!(expect > 0.9 * phi.sin() * edge);
        // The worst edge is the one rotated about, or the other row edge at the vertex.
        assert!([(i0, j0), (i0, j0 - 1)].contains(&t.at), "{t:?}");
        assert!(
            t.value >= expect * (1.0 - 1e-12) && t.value <= phi.sin() * edge * (1.0 + 1e-12),
            "{t:?}"
        );
        assert!(m.normal_length.unwrap().value <= 1e-15);
    }

    #[test]
    fn measure_straight_and_planar_polylines_measure_zero() {
        let o = v(1e3, -2e3, 5e2);
        let d = v(1.0, 2.0, -0.5).normalize();
        let e = d.cross(v(0.3, -1.0, 0.2)).normalize();
        let ts: Vec<f64> = (0..50).map(|k| (k as f64 * 0.37).powf(1.3)).collect();
        let size = ts[49];
        let straight: Vec<DVec3> = ts.iter().map(|t| o + *t * d).collect();
        assert!(polyline_planarity(&straight).0 <= 1e-14 * size);
        // Nearly straight (1e-9 off the line) but exactly in a plane: the plane
        // is barely determined, yet the distances must stay at rounding level.
        for bend in [1e-3, 1e-6, 1e-9, 1e-12] {
            let nearly: Vec<DVec3> = ts
                .iter()
                .map(|t| o + *t * d + bend * (t * 0.4).sin() * e)
                .collect();
            let (dist, _) = polyline_planarity(&nearly);
            assert!(dist <= 1e-14 * size, "bend {bend}: {dist}");
        }
        let circle: Vec<DVec3> = (0..100)
            .map(|k| o + 7.0 * ((k as f64 * 0.05).cos() * d + (k as f64 * 0.05).sin() * e))
            .collect();
        assert!(polyline_planarity(&circle).0 <= 1e-14 * 14.0);
        assert_eq!(polyline_planarity(&circle[..2]), (0.0, 0));
    }

    #[test]
    fn measure_degenerate_grids() {
        let empty = QuadGrid::new(0, 0, vec![], vec![]);
        let m = measure(&empty);
        assert_eq!(m.scale, 1.0);
        assert_eq!(m.max_error(), 0.0);
        let row = QuadGrid::new(
            1,
            3,
            vec![DVec3::ZERO, DVec3::X, DVec3::Y],
            vec![DVec3::Z; 3],
        );
        let m = measure(&row);
        assert_eq!(
            m.face_planarity,
            Worst {
                value: 0.0,
                at: (0, 0)
            }
        );
        assert_eq!(m.torsion.unwrap().value, 0.0);
        assert!(conical_error(&row).is_none());
        let mut nan = row.clone();
        nan.vertices[2].z = f64::NAN;
        assert!(measure(&nan).max_error().is_nan());
    }

    /// A surface of revolution on its meridian/parallel grid is conical too: the
    /// four face normals at a vertex are two mirror pairs across the meridian
    /// plane, i.e. an isosceles trapezoid — coplanar, hence on one circle of S².
    #[test]
    fn measure_conical_error_on_torus_and_perturbed() {
        let g = torus(8, 7);
        let c = conical_error(&g).unwrap();
        assert!(c.value <= 1e-14, "{c:?}");
        let mut bent = g.clone();
        let k = bent.index(3, 3);
        bent.vertices[k] += 1e-4 * bent.normals[k];
        let c = conical_error(&bent).unwrap();
        assert!(c.value > 1e-9, "{c:?}");
        assert!(
            (2..=4).contains(&c.at.0) && (2..=4).contains(&c.at.1),
            "{c:?}"
        );
    }
}
