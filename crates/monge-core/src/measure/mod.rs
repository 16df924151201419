//! Measuring any quad grid independently of how it was made (§2.2, §2.3), and the
//! planarity of any mesh of polygons (a grid trimmed to an outline).
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

use serde::{Deserialize, Serialize};

use crate::grid::{Folds, MAX_SIZE, MIN_SIZE};
use crate::QuadGrid;

mod conical;
mod faces;
mod lines;
mod polygons;
#[cfg(test)]
mod tests;

pub use conical::conical_error;
pub use faces::{circularity, face_planarity};
pub use lines::polyline_planarity;
pub use polygons::{measure_polygons, PolygonMeasurements};

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
        /// [`crate::grid::MIN_SIZE`].
        min: f64,
        /// [`crate::grid::MAX_SIZE`].
        max: f64,
    },
}

/// Whether [`measure`] can measure `grid` (§2.2, §2.3): at least one face, every
/// vertex and node axis finite, and a size (bounding-box diagonal) in the range
/// the generator accepts, [`MIN_SIZE`] to
/// [`MAX_SIZE`]. A single point (size 0) passes.
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
