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
        self.face_ids(i, j).map(|k| self.vertices[k])
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

    /// Folded faces (§5.2): each face's [`quad_turn`] about the sum of its four
    /// node axes, or without normals [`quad_turn_alone`] (which finds crossed
    /// and non-convex faces, not faces turned over whole), counted by [`Folds`].
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::QuadGrid;
    /// // Two unit squares side by side; then the far edge of the second twisted into a bow-tie.
    /// let v = |x: f64, y: f64| DVec3::new(x, y, 0.0);
    /// let mut g = QuadGrid::new(3, 2, vec![v(0.0, 0.0), v(0.0, 1.0), v(1.0, 0.0), v(1.0, 1.0), v(2.0, 0.0), v(2.0, 1.0)], vec![DVec3::Z; 6]);
    /// assert_eq!(g.folds().count(), 0);
    /// g.vertices.swap(4, 5);
    /// assert_eq!((g.folds().count(), g.folds().first()), (1, Some((1, 0))));
    /// ```
    pub fn folds(&self) -> Folds {
        let mut folds = Folds::default();
        for i in 0..self.rows.saturating_sub(1) {
            for j in 0..self.cols.saturating_sub(1) {
                folds.add((i, j), self.face_turn(i, j));
            }
        }
        folds
    }

    /// How face `(i, j)` turns (§5.2): [`quad_turn`] about the sum of its four
    /// node axes, or without normals [`quad_turn_alone`].
    pub fn face_turn(&self, i: usize, j: usize) -> Turn {
        let q = self.face(i, j);
        if self.normals.is_empty() {
            quad_turn_alone(&q)
        } else {
            let n = |i, j| self.normals[self.index(i, j)];
            quad_turn(&q, n(i, j) + n(i + 1, j) + n(i + 1, j + 1) + n(i, j + 1))
        }
    }

    /// Which faces are folded (§5.2), row-major as [`QuadGrid::face_areas`]:
    /// the faces that [`QuadGrid::folds`] counts.
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::QuadGrid;
    /// let v = |x: f64, y: f64| DVec3::new(x, y, 0.0);
    /// let mut g = QuadGrid::new(3, 2, vec![v(0.0, 0.0), v(0.0, 1.0), v(1.0, 0.0), v(1.0, 1.0), v(2.0, 0.0), v(2.0, 1.0)], vec![DVec3::Z; 6]);
    /// g.vertices.swap(4, 5);
    /// assert_eq!(g.folded_faces(), [false, true]);
    /// ```
    pub fn folded_faces(&self) -> Vec<bool> {
        let folds = self.folds();
        let cols = self.cols.saturating_sub(1);
        (0..self.rows.saturating_sub(1))
            .flat_map(|i| (0..cols).map(move |j| (i, j)))
            .map(|(i, j)| folds.is_folded(self.face_turn(i, j)))
            .collect()
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
        // Row by row side by side, the rows' sums added in order: the same
        // whatever the number of threads.
        let (p, n) = (&self.vertices, &self.normals);
        let rows = crate::tasks::map(self.rows.saturating_sub(1), |i| {
            let mut sum = 0.0;
            for j in 0..self.cols.saturating_sub(1) {
                let [a, b, c, d] = self.face_ids(i, j);
                let area = (p[c] - p[a]).cross(p[d] - p[b]);
                sum += area.dot(n[a] + n[b] + n[c] + n[d]);
            }
            sum
        });
        rows.iter().sum::<f64>() < 0.0
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
    ///
    /// The orientation is decided once, when this is called: the iterator can
    /// be cloned to go through the faces again at no cost.
    pub fn oriented_faces(&self) -> impl Iterator<Item = [usize; 4]> + Clone + '_ {
        self.faces_wound(self.faces_reversed(), 0..self.face_count())
    }

    /// The faces numbered `range` (row by row, as [`QuadGrid::oriented_faces`]
    /// numbers them), wound as [`QuadGrid::oriented_faces`] if `reversed` is
    /// [`QuadGrid::faces_reversed`]: for going through the faces in parts, side
    /// by side. A range past the last face stops there.
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::QuadGrid;
    /// let v = (0..9).map(|k| DVec3::new((k / 3) as f64, (k % 3) as f64, 0.0)).collect();
    /// let grid = QuadGrid::new(3, 3, v, vec![DVec3::Z; 9]);
    /// let all: Vec<_> = grid.oriented_faces().collect();
    /// let reversed = grid.faces_reversed();
    /// let parts: Vec<_> = grid.faces_wound(reversed, 0..1).chain(grid.faces_wound(reversed, 1..4)).collect();
    /// assert_eq!(parts, all);
    /// assert_eq!(grid.faces_wound(reversed, 3..9).collect::<Vec<_>>(), [all[3]]);
    /// ```
    pub fn faces_wound(
        &self,
        reversed: bool,
        range: std::ops::Range<usize>,
    ) -> impl Iterator<Item = [usize; 4]> + Clone + '_ {
        let w = self.cols.saturating_sub(1);
        // Row and column of the first face, then step (no division per face).
        let (i0, j0) = (
            range.start.checked_div(w).unwrap_or(0),
            range.start % w.max(1),
        );
        (i0..self.rows.saturating_sub(1))
            .flat_map(move |i| (if i == i0 { j0 } else { 0 }..w).map(move |j| (i, j)))
            .take(range.len())
            .map(move |(i, j)| {
                let [a, b, c, d] = self.face_ids(i, j);
                if reversed {
                    [a, d, c, b]
                } else {
                    [a, b, c, d]
                }
            })
    }

    /// The vertex indices of face `(i, j)` ([`face_corners`]).
    fn face_ids(&self, i: usize, j: usize) -> [usize; 4] {
        face_corners(self.cols, i, j)
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

/// Distance from `p` to the segment `ab`.
pub(crate) fn point_segment(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let e = b - a;
    let l2 = e.length_squared();
    let t = if l2 > 0.0 {
        ((p - a).dot(e) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + t * e)
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
    0.5 * scaled_length((q[2] - q[0]).cross(q[3] - q[1]))
}

/// `|v|` without overflow or underflow of the squares: the vector area of a
/// face whose edges are about 1e80 (or 1e-80) long has components whose
/// squares leave the range of a double, while the length itself does not.
pub fn scaled_length(v: DVec3) -> f64 {
    let m = v.abs().max_element();
    if m == 0.0 || !m.is_finite() {
        return m;
    }
    m * (v / m).length()
}

/// How the corners of a quad turn about an axis (§5.2): see [`quad_turn`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Turn {
    /// Every corner turns counter-clockwise about the axis.
    Positive,
    /// Every corner turns clockwise about the axis.
    Negative,
    /// The corners do not all turn the same way: the quad is crossed (a bow-tie,
    /// two corners each way), non-convex (one corner), or has a corner with no
    /// turn (a zero edge or three corners on a line, NaN included).
    Crossed,
}

/// How the quad `[A, B, C, D]` (cyclic order) turns about `axis` (§5.2): the
/// sign of `(e_in × e_out) · axis` at each corner, `e_in` the edge arriving at
/// the corner and `e_out` the edge leaving it.
///
/// A planar convex quad turns the same way at its four corners; a crossed one
/// (a bow-tie) turns one way at two corners and the other way at the two
/// others, even when it is symmetric and its diagonals' cross product (its
/// vector area) vanishes. The axis only decides which way is positive: the
/// node axes of the face, or, without them, the quad's largest corner turn
/// (see [`quad_turn_alone`]).
///
/// ```
/// use glam::DVec3;
/// use monge_core::grid::{quad_turn, Turn};
/// let square = [DVec3::ZERO, DVec3::X, DVec3::X + DVec3::Y, DVec3::Y];
/// assert_eq!(quad_turn(&square, DVec3::Z), Turn::Positive);
/// assert_eq!(quad_turn(&square, -DVec3::Z), Turn::Negative);
/// // C and D exchanged: edges AB and CD cross at (½, ½); (C − A) × (D − B) = 0.
/// let bow_tie = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::X + DVec3::Y];
/// assert_eq!((bow_tie[2] - bow_tie[0]).cross(bow_tie[3] - bow_tie[1]), DVec3::ZERO);
/// assert_eq!(quad_turn(&bow_tie, DVec3::Z), Turn::Crossed);
/// // A dart (non-convex at C) turns the other way at C only.
/// let dart = [DVec3::ZERO, DVec3::new(4.0, 0.0, 0.0), DVec3::new(1.0, 1.0, 0.0), DVec3::new(0.0, 4.0, 0.0)];
/// assert_eq!(quad_turn(&dart, DVec3::Z), Turn::Crossed);
/// ```
pub fn quad_turn(q: &[DVec3; 4], axis: DVec3) -> Turn {
    let sides = quad_sides(q, axis, |a, b| a.cross(b), |a, b| a.dot(b), |a| -a);
    Turn::of_sides(sides)
}

/// The four signed sides of [`quad_turn`], for any vector type (one vector, or
/// one per SIMD lane) given its cross and dot products and negation.
#[inline(always)]
pub(crate) fn quad_sides<V: Copy + std::ops::Sub<Output = V>, S>(
    q: &[V; 4],
    axis: V,
    cross: impl Fn(V, V) -> V,
    dot: impl Fn(V, V) -> S,
    neg: impl Fn(S) -> S,
) -> [S; 4] {
    // The sign of corner k's turn is that of the 2D cross product of its edges
    // in the quad's projection along the axis. There, the quad is convex and
    // turns positively iff each diagonal's line has the other two corners
    // strictly on its proper sides: 2 cross and 4 dot products instead of 4 and 4.
    let [a, b, c, d] = *q;
    let across_ac = cross(c - a, axis);
    let across_bd = cross(d - b, axis);
    [
        dot(across_ac, b - a),
        neg(dot(across_ac, d - a)),
        dot(across_bd, c - b),
        neg(dot(across_bd, a - b)),
    ]
}

impl Turn {
    /// The turn of a quad from its four signed sides (see [`quad_turn`]).
    #[inline(always)]
    pub(crate) fn of_sides(sides: [f64; 4]) -> Turn {
        // Counted without branches; NaN counts neither way, so it is crossed.
        let positive: u32 = sides.iter().map(|s| u32::from(*s > 0.0)).sum();
        let negative: u32 = sides.iter().map(|s| u32::from(*s < 0.0)).sum();
        match (positive, negative) {
            (4, _) => Turn::Positive,
            (_, 4) => Turn::Negative,
            _ => Turn::Crossed,
        }
    }
}

/// [`quad_turn`] about the quad's own largest corner turn (§5.2), for a quad
/// without node axes: [`Turn::Positive`] or [`Turn::Crossed`].
pub fn quad_turn_alone(q: &[DVec3; 4]) -> Turn {
    let corner = |k: usize| (q[k] - q[(k + 3) % 4]).cross(q[(k + 1) % 4] - q[k]);
    let axis = (1..4).map(corner).fold(corner(0), |a, b| {
        if b.length_squared() > a.length_squared() {
            b
        } else {
            a
        }
    });
    quad_turn(q, axis)
}

/// Folded faces of a quad grid (§5.2), counted face by face with [`Folds::add`].
///
/// A face is folded when it is [`Turn::Crossed`], or when it turns the other
/// way than most faces do (the mesh folds back over itself there); on a tie,
/// the way of the first face that is not crossed counts as the right one.
///
/// ```
/// use monge_core::grid::{Folds, Turn};
/// let mut f = Folds::default();
/// for (face, turn) in [((0, 0), Turn::Negative), ((0, 1), Turn::Positive), ((0, 2), Turn::Positive), ((1, 0), Turn::Crossed)] {
///     f.add(face, turn);
/// }
/// assert_eq!((f.count(), f.first()), (2, Some((0, 0))));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Folds {
    /// Faces turning each way (indexed by `Turn as usize`).
    count: [usize; 3],
    /// The first face turning each way (row-major).
    first: [Option<(usize, usize)>; 3],
}

impl Folds {
    /// Counts face `(i, j)`, which turns as `turn`; faces come in row-major order.
    #[inline]
    pub fn add(&mut self, face: (usize, usize), turn: Turn) {
        let k = turn as usize;
        self.count[k] += 1;
        self.first[k].get_or_insert(face);
    }

    /// Whether a face turning as `turn` was counted already: then counting
    /// more such faces ([`Folds::add_more`]) needs no face.
    #[inline(always)]
    pub(crate) fn has(&self, turn: Turn) -> bool {
        self.first[turn as usize].is_some()
    }

    /// Counts `n` more faces turning as `turn`, after a first one (row-major
    /// before them) was counted by [`Folds::add`].
    #[inline]
    pub(crate) fn add_more(&mut self, turn: Turn, n: usize) {
        debug_assert!(self.has(turn) || n == 0);
        self.count[turn as usize] += n;
    }

    /// The way that counts as wrong: the fewer of the two ways (on a tie, the
    /// way of the later first face).
    fn wrong_way(&self) -> usize {
        let (p, n) = (Turn::Positive as usize, Turn::Negative as usize);
        let positive_is_right = self.count[p] > self.count[n]
            || (self.count[p] == self.count[n] && self.first[p] < self.first[n]);
        if positive_is_right {
            n
        } else {
            p
        }
    }

    /// The faces counted by `self` and by `other` together: counting the faces
    /// of a grid in parts (e.g. in parallel) and merging the parts gives what
    /// counting them all in one [`Folds`] gives, in any order of merging.
    ///
    /// ```
    /// use monge_core::grid::{Folds, Turn};
    /// let (mut a, mut b) = (Folds::default(), Folds::default());
    /// a.add((1, 0), Turn::Positive);
    /// a.add((1, 1), Turn::Negative);
    /// b.add((0, 0), Turn::Positive);
    /// b.add((0, 1), Turn::Positive);
    /// assert_eq!((a.merge(b).count(), a.merge(b).first()), (1, Some((1, 1))));
    /// assert_eq!(a.merge(b), b.merge(a));
    /// ```
    pub fn merge(self, other: Folds) -> Folds {
        Folds {
            count: std::array::from_fn(|k| self.count[k] + other.count[k]),
            first: std::array::from_fn(|k| self.first[k].into_iter().chain(other.first[k]).min()),
        }
    }

    /// Number of folded faces.
    pub fn count(&self) -> usize {
        self.count[Turn::Crossed as usize] + self.count[self.wrong_way()]
    }

    /// Whether a face that turns as `turn` is folded: it is crossed, or turns
    /// the wrong way (§5.2).
    pub fn is_folded(&self, turn: Turn) -> bool {
        turn == Turn::Crossed || turn as usize == self.wrong_way()
    }

    /// The first folded face (row-major), if any.
    pub fn first(&self) -> Option<(usize, usize)> {
        [
            self.first[Turn::Crossed as usize],
            self.first[self.wrong_way()],
        ]
        .into_iter()
        .flatten()
        .min()
    }
}

/// Smallest accepted model size (a bounding-box diagonal: the larger guide's for a
/// design, the grid's for a measured mesh). Below it squared lengths approach the
/// subnormal range (measured: 1e-160 loses exactness).
pub const MIN_SIZE: f64 = 1e-100;
/// Largest accepted model size (a bounding-box diagonal, as for [`MIN_SIZE`]).
pub const MAX_SIZE: f64 = 1e100;

/// Diagonal of the axis-aligned bounding box of `points` (0 for none).
pub fn bbox_diagonal(points: &[DVec3]) -> f64 {
    bounds(points).map_or(0.0, |b| (b.hi - b.lo).length())
}

/// The vertex indices `(i, j), (i+1, j), (i+1, j+1), (i, j+1)` of face
/// `(i, j)` of a row-major grid of `cols` vertices a row: corners A, B, C, D
/// (§2.2), for the quad grid and the cyclidic net alike.
pub(crate) fn face_corners(cols: usize, i: usize, j: usize) -> [usize; 4] {
    let k = i * cols + j;
    [k, k + cols, k + cols + 1, k + 1]
}

/// The corners of the bounding box of some points, and their largest |coordinate|.
struct Bounds {
    lo: DVec3,
    hi: DVec3,
    far: f64,
}

/// The [`Bounds`] of `points` (`None` for none), blocks of them side by side.
fn bounds(points: &[DVec3]) -> Option<Bounds> {
    let blocks = crate::tasks::ranges(points.len(), crate::tasks::BLOCK, |r| {
        let (mut lo, mut hi, mut far) = (points[r.start], points[r.start], 0.0f64);
        for p in &points[r] {
            (lo, hi, far) = (lo.min(*p), hi.max(*p), far.max(p.abs().max_element()));
        }
        Bounds { lo, hi, far }
    });
    blocks.into_iter().reduce(|a, b| Bounds {
        lo: a.lo.min(b.lo),
        hi: a.hi.max(b.hi),
        far: a.far.max(b.far),
    })
}

/// How many times the rounding of its coordinates, ε · [`origin_ratio`] of its
/// size, the error of a mesh (or the deviation of a guide) can reach (§5.2): a
/// coordinate is rounded by up to ε times its magnitude, and faces with nearly
/// collinear corners or nearly parallel diagonals amplify it. Measured by the
/// sweep of `tests/far_from_origin.rs` (8000 random designs 1e2 to 1e7 sizes
/// from the origin, faces measured independently, the error the rounding adds
/// to the same design's error relative to its start): up to 3454 where errors
/// reach 1e-9 (1e4 sizes and beyond; one design at 3e2 sizes, 16 319, stays
/// below 1e-9 there). Rounded up to a power of two.
pub const ROUNDING_GAIN: f64 = 4096.0;

/// Distance from the origin, relative to the size, beyond which f64 coordinates
/// can put a mesh's error above 1e-9 of its size (§5.2): `1e-9 / (ROUNDING_GAIN ε)`
/// ≈ 1.1e3. Errors over 1e-9 were measured from 5.0e3 (the sweep of
/// `tests/far_from_origin.rs`) and from about 1.5e3 (an independent sweep of
/// 100 000 designs). Beyond it, write coordinates relative to a base point
/// near the design (`--base-point start`).
pub const FAR_FROM_ORIGIN: f64 = 1e-9 / (ROUNDING_GAIN * f64::EPSILON);

/// What a refusal of an input `ratio` times its size from the origin says when
/// the rounding of its coordinates, ε · ratio of its size, can explain a
/// deviation of `relative` (to the size, or radians for an angle): when it is
/// at most [`ROUNDING_GAIN`] such roundings (§5.2). `None` otherwise. The
/// sentence blames the precision of the coordinates, not the design, and says
/// what to do; each refusal adds which tolerance would accept it.
///
/// ```
/// use monge_core::grid::precision_cause;
/// let words = precision_cause(1e5, 3.7e-9).unwrap();
/// assert!(words.contains("that precision, not the design, is the cause"));
/// assert!(precision_cause(10.0, 3.7e-9).is_none());
/// ```
pub fn precision_cause(ratio: f64, relative: f64) -> Option<String> {
    let rounding = f64::EPSILON * ratio;
    rounding_explains(ratio, relative).then(|| {
        format!(
            "The guides lie {ratio:.1e} times their size from the origin, where their \
             coordinates, as f64 numbers, are rounded by up to {rounding:.1e} of their size: that \
             precision, not the design, is the cause. Model the design near the origin (e.g. \
             with the guides' start point at 0) and move the result into place afterwards"
        )
    })
}

/// Whether the rounding of coordinates `ratio` times the size from the origin
/// ([`origin_ratio`]), ε · ratio of the size, amplified by at most
/// [`ROUNDING_GAIN`], can explain a deviation or error of `relative` (to the
/// size, or radians) (§5.2). The one test behind [`precision_cause`] and the
/// causes of a measured error that front ends name.
///
/// ```
/// use monge_core::grid::rounding_explains;
/// assert!(rounding_explains(1e6, 1e-9));
/// assert!(!rounding_explains(10.0, 1e-9));
/// ```
pub fn rounding_explains(ratio: f64, relative: f64) -> bool {
    relative <= ROUNDING_GAIN * f64::EPSILON * ratio
}

/// What to do about an input refused for a deviation `relative` (to its size,
/// or radians) over `tolerance.NAME`, `ratio` times its size from the origin:
/// [`precision_cause`] and a tolerance that accepts it (the next power of ten
/// at or above twice the deviation) when the coordinates' rounding explains
/// it, `otherwise` followed by raising the tolerance when it does not.
pub(crate) fn tolerance_fix(ratio: f64, relative: f64, name: &str, otherwise: &str) -> String {
    match precision_cause(ratio, relative) {
        Some(cause) => format!(
            "{cause}, or raise `tolerance.{name}` to {:.0e} (then write the mesh with \
             `--base-point start` to keep it exact).",
            10f64.powf((2.0 * relative).log10().ceil())
        ),
        None => format!("{otherwise}, or raise `tolerance.{name}`."),
    }
}

/// How far `points` lie from the origin compared with their size (§5.2): the
/// largest |coordinate| divided by the bounding-box diagonal (0 for no points,
/// infinite for one point away from the origin). Above [`FAR_FROM_ORIGIN`] the
/// rounding of the coordinates themselves can exceed 1e-9 of the size.
///
/// ```
/// use glam::DVec3;
/// use monge_core::grid::origin_ratio;
/// let p = [DVec3::new(1e5, 0.0, 0.0), DVec3::new(1e5, 1e-3, 0.0)];
/// assert_eq!(origin_ratio(&p), 1e8);
/// ```
pub fn origin_ratio(points: &[DVec3]) -> f64 {
    match bounds(points) {
        Some(b) if b.far != 0.0 => b.far / (b.hi - b.lo).length(),
        _ => 0.0,
    }
}
