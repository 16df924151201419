//! The result of the generator: a quad grid of vertices with node axes (§2.2).

use glam::DVec3;

/// An `rows × cols` grid of vertices, each with a unit normal (its node axis).
///
/// Vertex `(i, j)` is entry `i * cols + j`: `i` runs along guide_u, `j` along
/// guide_v; vertex `(i, 0)` is guide_u's sample `i` and vertex `(0, j)` is
/// guide_v's sample `j`. Faces are the quads `(i, j), (i+1, j), (i+1, j+1), (i, j+1)`.
///
/// ```
/// use glam::DVec3;
/// use monge_core::QuadGrid;
/// let g = QuadGrid::new(2, 2, vec![DVec3::ZERO, DVec3::Y, DVec3::X, DVec3::X + DVec3::Y], vec![DVec3::Z; 4]);
/// assert_eq!(g.vertex(1, 0), DVec3::X);
/// assert_eq!(g.face(0, 0), [DVec3::ZERO, DVec3::X, DVec3::X + DVec3::Y, DVec3::Y]);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct QuadGrid {
    /// Number of vertices along guide_u (index `i`).
    pub rows: usize,
    /// Number of vertices along guide_v (index `j`).
    pub cols: usize,
    /// Vertex positions, row-major.
    pub vertices: Vec<DVec3>,
    /// Unit node axes, row-major; empty when the grid carries no normals.
    pub normals: Vec<DVec3>,
}

impl QuadGrid {
    /// A grid from row-major vertices and normals (`normals` may be empty).
    ///
    /// # Panics
    /// If `vertices.len() != rows * cols`, or `normals` is neither empty nor of that length.
    pub fn new(rows: usize, cols: usize, vertices: Vec<DVec3>, normals: Vec<DVec3>) -> Self {
        assert_eq!(
            vertices.len(),
            rows * cols,
            "vertex count must be rows * cols"
        );
        assert!(
            normals.is_empty() || normals.len() == vertices.len(),
            "normals must be empty or one per vertex"
        );
        QuadGrid {
            rows,
            cols,
            vertices,
            normals,
        }
    }

    /// Index of vertex `(i, j)` in [`QuadGrid::vertices`].
    #[inline]
    pub fn index(&self, i: usize, j: usize) -> usize {
        i * self.cols + j
    }

    /// Vertex `(i, j)`.
    #[inline]
    pub fn vertex(&self, i: usize, j: usize) -> DVec3 {
        self.vertices[self.index(i, j)]
    }

    /// The four corners of face `(i, j)`, in the order
    /// `(i, j), (i+1, j), (i+1, j+1), (i, j+1)`.
    pub fn face(&self, i: usize, j: usize) -> [DVec3; 4] {
        [
            self.vertex(i, j),
            self.vertex(i + 1, j),
            self.vertex(i + 1, j + 1),
            self.vertex(i, j + 1),
        ]
    }

    /// Area of face `(i, j)` (§4.8): [`quad_area`] of [`QuadGrid::face`].
    pub fn face_area(&self, i: usize, j: usize) -> f64 {
        quad_area(&self.face(i, j))
    }

    /// Areas of all faces (§4.8), row-major (face `(i, j)` is entry `i·(cols − 1) + j`).
    pub fn face_areas(&self) -> Vec<f64> {
        let cols = self.cols.saturating_sub(1);
        (0..self.rows.saturating_sub(1))
            .flat_map(|i| (0..cols).map(move |j| self.face_area(i, j)))
            .collect()
    }

    /// Number of faces, `(rows − 1) · (cols − 1)`.
    pub fn face_count(&self) -> usize {
        self.rows.saturating_sub(1) * self.cols.saturating_sub(1)
    }

    /// The polyline of vertices `(i, 0), (i, 1), …` (a curvature line along guide_v).
    pub fn row(&self, i: usize) -> impl Iterator<Item = DVec3> + '_ {
        (0..self.cols).map(move |j| self.vertex(i, j))
    }

    /// The polyline of vertices `(0, j), (1, j), …` (a curvature line along guide_u).
    pub fn column(&self, j: usize) -> impl Iterator<Item = DVec3> + '_ {
        (0..self.rows).map(move |i| self.vertex(i, j))
    }

    /// Length of the diagonal of the axis-aligned bounding box (the model size
    /// that every relative error is measured against).
    pub fn bbox_diagonal(&self) -> f64 {
        bbox_diagonal(&self.vertices)
    }

    /// The transposed grid (`i` and `j` exchanged).
    pub fn transposed(&self) -> QuadGrid {
        let t = |v: &[DVec3]| -> Vec<DVec3> {
            if v.is_empty() {
                return Vec::new();
            }
            (0..self.cols)
                .flat_map(|j| (0..self.rows).map(move |i| v[i * self.cols + j]))
                .collect()
        };
        QuadGrid::new(self.cols, self.rows, t(&self.vertices), t(&self.normals))
    }
}

/// Area of a quad `[A, B, C, D]` given in cyclic order (§4.8, panel areas):
/// `½ |(C − A) × (D − B)|`, half the length of the cross product of its diagonals.
///
/// For a planar quad that is not crossed (convex or not) this is its area: the
/// sum of the areas of triangles `ABC` and `ACD`. For a skew quad it is the
/// area of its projection on the plane of the two diagonals (the length of its
/// vector area). The corners must be in cyclic order, as [`QuadGrid::face`]
/// gives them: with two corners exchanged the diagonals are two opposite edges
/// and the value means nothing.
///
/// ```
/// use glam::DVec3;
/// use monge_core::grid::quad_area;
/// // A trapezoid with parallel sides 4 and 2, height 3: (4 + 2) / 2 · 3 = 9.
/// let q = [DVec3::ZERO, DVec3::new(4.0, 0.0, 0.0), DVec3::new(3.0, 3.0, 0.0), DVec3::new(1.0, 3.0, 0.0)];
/// assert_eq!(quad_area(&q), 9.0);
/// // A non-convex quad (a dart, reflex at C): triangles ABC and ACD, 2 each.
/// let dart = [DVec3::ZERO, DVec3::new(4.0, 0.0, 0.0), DVec3::new(1.0, 1.0, 0.0), DVec3::new(0.0, 4.0, 0.0)];
/// assert_eq!(quad_area(&dart), 4.0);
/// ```
pub fn quad_area(q: &[DVec3; 4]) -> f64 {
    0.5 * (q[2] - q[0]).cross(q[3] - q[1]).length()
}

/// Diagonal of the axis-aligned bounding box of `points` (0 for none).
pub fn bbox_diagonal(points: &[DVec3]) -> f64 {
    let mut it = points.iter();
    let Some(first) = it.next() else { return 0.0 };
    let (lo, hi) = it.fold((*first, *first), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
    (hi - lo).length()
}
