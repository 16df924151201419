//! The result of the generator: a quad grid of vertices with node axes (§2.2).

use glam::DVec3;

/// An `rows × cols` grid of vertices, each with a unit normal (its node axis).
///
/// Vertex `(i, j)` is entry `i * cols + j`: `i` runs along guide_u, `j` along
/// guide_v; vertex `(i, 0)` is guide_u's sample `i` and vertex `(0, j)` is
/// guide_v's sample `j`. Faces are the quads `(i, j), (i+1, j), (i+1, j+1), (i, j+1)`;
/// [`QuadGrid::oriented_faces`] winds them counter-clockwise about the node axes.
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

    /// Whether the node axes point against the face order
    /// `(i, j), (i+1, j), (i+1, j+1), (i, j+1)` (§2.2): the sum over all faces
    /// of the face's vector area dotted with the sum of its corners' normals is
    /// negative. `false` for a grid without normals.
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::QuadGrid;
    /// let v = vec![DVec3::ZERO, DVec3::Y, DVec3::X, DVec3::X + DVec3::Y];
    /// assert!(!QuadGrid::new(2, 2, v.clone(), vec![DVec3::Z; 4]).faces_reversed());
    /// assert!(QuadGrid::new(2, 2, v, vec![-DVec3::Z; 4]).faces_reversed());
    /// ```
    pub fn faces_reversed(&self) -> bool {
        if self.normals.is_empty() {
            return false;
        }
        let mut sum = 0.0;
        for [a, b, c, d] in self.face_indices() {
            let p = |k: usize| self.vertices[k];
            let area = (p(c) - p(a)).cross(p(d) - p(b));
            let n = self.normals[a] + self.normals[b] + self.normals[c] + self.normals[d];
            sum += area.dot(n);
        }
        sum < 0.0
    }

    /// The vertex indices of every face, row by row, wound counter-clockwise
    /// about the node axes (right-hand rule; §2.2): `(i, j), (i+1, j), (i+1, j+1),
    /// (i, j+1)`, or `(i, j), (i, j+1), (i+1, j+1), (i+1, j)` when
    /// [`QuadGrid::faces_reversed`]. Every mesh writer and the renderer use it.
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::QuadGrid;
    /// let v = vec![DVec3::ZERO, DVec3::Y, DVec3::X, DVec3::X + DVec3::Y];
    /// let up = QuadGrid::new(2, 2, v.clone(), vec![DVec3::Z; 4]);
    /// assert_eq!(up.oriented_faces().collect::<Vec<_>>(), [[0, 2, 3, 1]]);
    /// let down = QuadGrid::new(2, 2, v, vec![-DVec3::Z; 4]);
    /// assert_eq!(down.oriented_faces().collect::<Vec<_>>(), [[0, 1, 3, 2]]);
    /// ```
    pub fn oriented_faces(&self) -> impl Iterator<Item = [usize; 4]> + '_ {
        let reversed = self.faces_reversed();
        self.face_indices()
            .map(move |[a, b, c, d]| if reversed { [a, d, c, b] } else { [a, b, c, d] })
    }

    /// The vertex indices `(i, j), (i+1, j), (i+1, j+1), (i, j+1)` of every face, row by row.
    fn face_indices(&self) -> impl Iterator<Item = [usize; 4]> + '_ {
        let c = self.cols;
        (0..self.rows.saturating_sub(1)).flat_map(move |i| {
            (0..c.saturating_sub(1)).map(move |j| {
                let k = i * c + j;
                [k, k + c, k + c + 1, k + 1]
            })
        })
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

/// Diagonal of the axis-aligned bounding box of `points` (0 for none).
pub fn bbox_diagonal(points: &[DVec3]) -> f64 {
    let mut it = points.iter();
    let Some(first) = it.next() else { return 0.0 };
    let (lo, hi) = it.fold((*first, *first), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
    (hi - lo).length()
}

/// Distance from the origin, relative to the size, beyond which f64 coordinates
/// cannot hold a mesh to 1e-9 of its size (§5.2): `1e-9 / (4 ε)` ≈ 1.1e6, since
/// writing a coordinate rounds it by up to ε times its magnitude and the measured
/// error of a mesh reaches a few such roundings (up to 4.6 in the tests).
pub const FAR_FROM_ORIGIN: f64 = 1e-9 / (4.0 * f64::EPSILON);

/// How far `points` lie from the origin compared with their size (§5.2): the
/// largest |coordinate| divided by the bounding-box diagonal (0 for no points,
/// infinite for one point away from the origin). Above [`FAR_FROM_ORIGIN`] the
/// output coordinates themselves cannot hold 1e-9 of the size.
///
/// ```
/// use glam::DVec3;
/// use monge_core::grid::origin_ratio;
/// let p = [DVec3::new(1e5, 0.0, 0.0), DVec3::new(1e5, 1e-3, 0.0)];
/// assert_eq!(origin_ratio(&p), 1e8);
/// ```
pub fn origin_ratio(points: &[DVec3]) -> f64 {
    let far = points
        .iter()
        .map(|p| p.abs().max_element())
        .fold(0.0, f64::max);
    if far == 0.0 {
        0.0
    } else {
        far / bbox_diagonal(points)
    }
}
