//! Conical meshes with planar lines (§2.3, Proposition 3).
//!
//! The conical mesh of a design is the conical dual of its circular mesh
//! (Pottmann & Wallner's construction, §2.3): its faces are the planes through
//! the circular mesh's vertices orthogonal to their node axes. Around each face of
//! the circular mesh these four planes meet in one point (they are tangent to
//! the sphere through the face's corners whose centre lies on all four node
//! axes); that point is a vertex of the conical mesh. So the conical mesh is
//! fitted to the guides predictably: the planes of its boundary faces pass
//! through the guide samples, orthogonal to the normals along the guides. Its
//! face normals are the Gauss vertices, and it is a Combescure transform of the
//! conical Gauss image (the tangent planes to S² at the Gauss vertices), so its
//! rows and columns are planar (Proposition 3).

use glam::DVec3;

use crate::grid::{quad_turn, Folds, QuadGrid, Turn};

/// A conical mesh and what its face offsets need (§2.3).
#[derive(Clone, Debug, PartialEq)]
pub struct ConicalMesh {
    /// Vertices: `(rows − 1) × (cols − 1)`, one per face of the circular mesh;
    /// vertex `(i, j)` comes from circular face `(i, j)`. No vertex normals.
    pub grid: QuadGrid,
    /// Unit normal of each face, row-major over `(rows − 2) × (cols − 2)` faces:
    /// face `(i, j)` lies in the plane through circular vertex `(i + 1, j + 1)`
    /// orthogonal to its node axis, which is this normal.
    pub face_normals: Vec<DVec3>,
    /// Per vertex, the vector `K` with `n · K = 1` for the normals `n` of the four
    /// faces around it: the face offset at distance `d` moves the vertex by `d·K`.
    /// `K` is the apex of the cone tangent to S² along the circumcircle of the
    /// corresponding Gauss face (a vertex of the conical Gauss image).
    pub offset_directions: Vec<DVec3>,
}

/// The conical dual of a circular mesh with node axes (§2.3).
///
/// # Panics
/// If `circular` has no normals or fewer than 3 rows or columns.
///
/// ```
/// use monge_core::{conical::conical_dual, generate, Design, GenerateOptions, GuideSpec};
/// use monge_core::design::ArcSpec;
/// let arc = |center: [f64; 3], normal: [f64; 3], angle_deg: f64| {
///     GuideSpec::Arc(ArcSpec { center, start: [0.0; 3], normal, angle_deg, samples: 9 })
/// };
/// let design = Design {
///     mesh: Default::default(),
///     theta_deg: 30.0,
///     guide_u: arc([0.0, 0.0, -10.0], [0.0, 1.0, 0.0], 60.0),
///     guide_v: arc([0.0, 0.0, -3.0], [-1.0, 0.0, 0.0], 60.0),
///     tolerance: None,
/// };
/// let circular = generate(&design, &GenerateOptions::default()).unwrap().grid;
/// let conical = conical_dual(&circular);
/// assert_eq!((conical.grid.rows, conical.grid.cols), (8, 8));
/// // Face (0, 0) lies in the plane through circular vertex (1, 1) orthogonal to its axis.
/// let n = conical.face_normals[0];
/// let h = n.dot(circular.vertex(1, 1));
/// for v in conical.grid.face(0, 0) {
///     assert!((n.dot(v) - h).abs() < 1e-12);
/// }
/// ```
pub fn conical_dual(circular: &QuadGrid) -> ConicalMesh {
    let (rows, cols) = (circular.rows, circular.cols);
    assert!(
        rows >= 3 && cols >= 3,
        "a conical dual needs 3 × 3 vertices"
    );
    assert_eq!(
        circular.normals.len(),
        circular.vertices.len(),
        "node axes are needed"
    );
    let n = |i: usize, j: usize| circular.normals[circular.index(i, j)];
    let x = |i: usize, j: usize| circular.vertex(i, j);
    let mut vertices = Vec::with_capacity((rows - 1) * (cols - 1));
    let mut offset_directions = Vec::with_capacity((rows - 1) * (cols - 1));
    for i in 0..rows - 1 {
        for j in 0..cols - 1 {
            let (n0, nu, nv) = (n(i, j), n(i + 1, j), n(i, j + 1));
            let (u, v) = (nu - n0, nv - n0);
            let (eu, ev) = (x(i + 1, j) - x(i, j), x(i, j + 1) - x(i, j));
            vertices.push(x(i, j) + tangent_apex(n0, u, v, eu, ev));
            offset_directions.push(n0 + tangent_apex(n0, u, v, u, v));
        }
    }
    let face_normals = (1..rows - 1)
        .flat_map(|i| (1..cols - 1).map(move |j| (i, j)))
        .map(|(i, j)| n(i, j))
        .collect();
    ConicalMesh {
        grid: QuadGrid::new(rows - 1, cols - 1, vertices, Vec::new()),
        face_normals,
        offset_directions,
    }
}

/// The common point `X + Z` of the planes through `X`, `X + eu`, `X + ev`
/// orthogonal to the unit normals `n`, `n + u`, `n + v`, where the edges `eu`,
/// `ev` are parallel to `u`, `v` (§2.3). Returns `Z`.
///
/// Subtracting the first plane from the others leaves `n·Z = 0`,
/// `u·Z = eu·u / 2`, `v·Z = ev·v / 2` (as `(n + u)·u = |u|²/2` for unit normals);
/// with `u`, `v` normalised the system is well conditioned.
fn tangent_apex(n: DVec3, u: DVec3, v: DVec3, eu: DVec3, ev: DVec3) -> DVec3 {
    let (lu, lv) = (u.length(), v.length());
    let (uh, vh) = (u / lu, v / lv);
    let (bu, bv) = (0.5 * eu.dot(uh), 0.5 * ev.dot(vh));
    // Z = (0·(uh × vh) + bu·(vh × n) + bv·(n × uh)) / det(n, uh, vh)
    (bu * vh.cross(n) + bv * n.cross(uh)) / n.dot(uh.cross(vh))
}

/// Folded faces of a conical mesh (§2.3, §5.2), counted by [`Folds`]: each
/// face's [`quad_turn`] about its normal. A face is folded when it is crossed
/// or not convex, or turns the other way than most faces: its normal is
/// reversed against its neighbours', on the wrong side of the vertex cones at
/// its corners.
///
/// With `face_normals` (one per face, row-major, as [`ConicalMesh::face_normals`]:
/// the node axes of the circular mesh, oriented alike everywhere) each face
/// turns about its own normal. Without them (a mesh read from a file), about
/// the axes of the vertex cones at its four corners: a conical mesh's faces
/// around a vertex are tangent to one cone of revolution, their normals on one
/// side of its axis, which is taken as the sum of the unit normals
/// `(C − A) × (D − B)` of the faces around the vertex. (Neighbouring normals
/// may differ by more than 90° on a coarse mesh without any fold: the axes,
/// summed over the faces around the corners, keep the face's own side.) As
/// [`QuadGrid::folds`] without node axes, this finds fewer faces turned over.
///
/// ```
/// use glam::DVec3;
/// use monge_core::conical::conical_folds;
/// use monge_core::QuadGrid;
/// // A strip of three unit squares along x, flat; then the middle one folded
/// // back (x = 0, 2, 1, 3: it turns the other way and overlaps the others).
/// let strip = |x: [f64; 4]| {
///     let v = (0..8).map(|k| DVec3::new(x[k / 2], (k % 2) as f64, 0.0)).collect();
///     QuadGrid::new(4, 2, v, vec![])
/// };
/// assert_eq!(conical_folds(&strip([0.0, 1.0, 2.0, 3.0]), None).count(), 0);
/// let folded = strip([0.0, 2.0, 1.0, 3.0]);
/// for normals in [None, Some(&[DVec3::Z; 3][..])] {
///     let f = conical_folds(&folded, normals);
///     assert_eq!((f.count(), f.first()), (1, Some((1, 0))));
/// }
/// ```
///
/// # Panics
/// If `face_normals` is given with another length than the number of faces.
pub fn conical_folds(grid: &QuadGrid, face_normals: Option<&[DVec3]>) -> Folds {
    let (cols, turns) = (
        grid.cols.saturating_sub(1),
        conical_turns(grid, face_normals),
    );
    let mut folds = Folds::default();
    for (k, turn) in turns.into_iter().enumerate() {
        folds.add((k / cols, k % cols), turn);
    }
    folds
}

/// Which faces of a conical mesh are folded (§2.3, §5.2), row-major: the faces
/// [`conical_folds`] counts.
///
/// # Panics
/// As [`conical_folds`].
pub fn conical_folded_faces(grid: &QuadGrid, face_normals: Option<&[DVec3]>) -> Vec<bool> {
    let folds = conical_folds(grid, face_normals);
    let turns = conical_turns(grid, face_normals);
    turns.into_iter().map(|t| folds.is_folded(t)).collect()
}

/// How each face of a conical mesh turns (§5.2), row-major: see [`conical_folds`].
fn conical_turns(grid: &QuadGrid, face_normals: Option<&[DVec3]>) -> Vec<Turn> {
    let (fr, fc) = (grid.rows.saturating_sub(1), grid.cols.saturating_sub(1));
    let own: Vec<DVec3>;
    let axes = match face_normals {
        Some(n) => {
            assert_eq!(n.len(), fr * fc, "one normal per face");
            n
        }
        None => {
            let normal = |k: usize| {
                let [a, b, c, d] = grid.face(k / fc, k % fc);
                (c - a).cross(d - b).normalize_or_zero()
            };
            let normals: Vec<DVec3> = (0..fr * fc).map(normal).collect();
            let normals = &normals;
            // The cone axis at vertex (i, j): the faces (i − 1 or i, j − 1 or j) that exist.
            let cone = |i: usize, j: usize| -> DVec3 {
                let (r0, c0) = (i.saturating_sub(1), j.saturating_sub(1));
                let (r1, c1) = (i.min(fr - 1), j.min(fc - 1));
                (r0..=r1)
                    .flat_map(|a| (c0..=c1).map(move |b| normals[a * fc + b]))
                    .sum()
            };
            own = (0..fr * fc)
                .map(|k| {
                    let (i, j) = (k / fc, k % fc);
                    cone(i, j) + cone(i + 1, j) + cone(i + 1, j + 1) + cone(i, j + 1)
                })
                .collect();
            &own
        }
    };
    axes.iter()
        .enumerate()
        .map(|(k, axis)| quad_turn(&grid.face(k / fc, k % fc), *axis))
        .collect()
}
