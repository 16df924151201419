//! The discrete Combescure transform (§2.2.3): a mesh whose edges are parallel
//! to those of the Gauss map, fitted to the two guide polylines.

use glam::DVec3;

use crate::gauss_map::GaussMap;
use crate::grid::{quad_turn, Folds};

/// A face where the two lines that define its last vertex are (nearly) parallel,
/// so that the vertex is undefined (§5.2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParallelLines {
    /// The face `(i, j)`; its vertex `(i+1, j+1)` is undefined.
    pub face: (usize, usize),
    /// Sine of the angle between the two lines.
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

/// Smallest sine of the angle between two lines that still defines a vertex.
/// Below it the lines are taken as parallel (the Gauss quad is degenerate).
pub const MIN_CROSSING_SINE: f64 = 1e-9;

/// The Combescure transform of `gauss` through the two guide polylines (§2.2.3).
///
/// `guide_u[i]` becomes vertex `(i, 0)` and `guide_v[j]` vertex `(0, j)`; every
/// further vertex `(i+1, j+1)` is the common point of the line through `(i+1, j)`
/// parallel to the Gauss edge `(i+1, j) → (i+1, j+1)` and the line through
/// `(i, j+1)` parallel to the Gauss edge `(i, j+1) → (i+1, j+1)`. The two lines are
/// coplanar because the Gauss quad is planar; the midpoint of their closest points
/// is taken to absorb round-off. The guides must have been made with normals that
/// are their Gauss images (see [`crate::gauss_map::guide_normals`]).
///
/// Returns the vertices, row-major, or the first face whose lines are parallel
/// (a degenerate Gauss quad).
///
/// ```
/// use glam::DVec3;
/// use monge_core::combescure::combescure;
/// use monge_core::gauss_map::GaussMap;
/// // A Gauss quad and a scaled copy of two of its edges give the scaled quad.
/// let n = vec![DVec3::Z, DVec3::new(0.0, 0.1, 1.0), DVec3::new(0.1, 0.0, 1.0), DVec3::new(0.1, 0.1, 1.0)];
/// let g = GaussMap { rows: 2, cols: 2, normals: n.clone() };
/// let (x, _) = combescure(&g, &[n[0] * 2.0, n[2] * 2.0], &[n[0] * 2.0, n[1] * 2.0]).unwrap();
/// assert!(x[3].abs_diff_eq(n[3] * 2.0, 1e-15));
/// ```
pub fn combescure(
    gauss: &GaussMap,
    guide_u: &[DVec3],
    guide_v: &[DVec3],
) -> Result<(Vec<DVec3>, CombescureReport), ParallelLines> {
    assert_eq!(guide_u.len(), gauss.rows, "guide_u has one point per row");
    assert_eq!(
        guide_v.len(),
        gauss.cols,
        "guide_v has one point per column"
    );
    let rows = gauss.normals.chunks_exact(gauss.cols);
    let mut rows = rows.map(<[DVec3]>::to_vec);
    let transform = combescure_rows(guide_u, guide_v, |_, out| {
        out.copy_from_slice(&rows.next().expect("one Gauss row per guide_u sample"));
    })?;
    Ok((transform.vertices, transform.report))
}

/// What [`combescure_rows`] builds.
#[derive(Clone, Debug)]
pub struct Transform {
    /// The vertices, row-major.
    pub vertices: Vec<DVec3>,
    /// The Gauss map (node axes), row-major.
    pub normals: Vec<DVec3>,
    /// Pinching and folding (§5.2).
    pub report: CombescureReport,
}

/// The Combescure transform (§2.2.3) of a Gauss map that `gauss_row(i, out)`
/// writes row by row (one normal per guide_v sample), consuming each Gauss row
/// while it is still in cache (see [`combescure`] for the construction).
pub fn combescure_rows(
    guide_u: &[DVec3],
    guide_v: &[DVec3],
    mut gauss_row: impl FnMut(usize, &mut [DVec3]),
) -> Result<Transform, ParallelLines> {
    let (rows, cols) = (guide_u.len(), guide_v.len());
    let mut normals = vec![DVec3::ZERO; rows * cols];
    let mut vertices = vec![DVec3::ZERO; rows * cols];
    gauss_row(0, &mut normals[..cols]);
    vertices[..cols].copy_from_slice(guide_v);
    let mut propagation = Propagation::new();
    for (i, &start) in guide_u.iter().enumerate().skip(1) {
        let (n_done, n_rest) = normals.split_at_mut(i * cols);
        let (x_done, x_rest) = vertices.split_at_mut(i * cols);
        let n_cur = &mut n_rest[..cols];
        gauss_row(i, n_cur);
        propagation.row(
            i - 1,
            (&n_done[(i - 1) * cols..], n_cur),
            (&x_done[(i - 1) * cols..], &mut x_rest[..cols]),
            start,
        )?;
    }
    Ok(Transform {
        vertices,
        normals,
        report: propagation.report,
    })
}

/// The Combescure transform face row by face row (§2.2.3).
#[derive(Clone, Debug)]
struct Propagation {
    /// What has been seen so far (the fold count is in `folds`).
    report: CombescureReport,
    /// How the faces turn about their node axes (§5.2).
    folds: Folds,
}

impl Propagation {
    /// A propagation that has seen nothing yet.
    fn new() -> Self {
        Propagation {
            report: CombescureReport {
                min_crossing: ParallelLines {
                    face: (0, 0),
                    sine: 1.0,
                    zero_edge: false,
                },
                folded_faces: 0,
                first_fold: None,
            },
            folds: Folds::default(),
        }
    }

    /// Face row `i` (§2.2.3): fills vertex row `i + 1`, whose first vertex is
    /// `start` (guide_u's sample `i + 1`), from vertex row `i` and the Gauss map's
    /// rows `i` and `i + 1`.
    fn row(
        &mut self,
        i: usize,
        (n_prev, n_cur): (&[DVec3], &[DVec3]),
        (x_prev, x_cur): (&[DVec3], &mut [DVec3]),
        start: DVec3,
    ) -> Result<(), ParallelLines> {
        x_cur[0] = start;
        let mut p1 = start;
        let mut min_sine2 = self.report.min_crossing.sine.powi(2);
        let faces = n_prev
            .windows(2)
            .zip(n_cur.windows(2))
            .zip(x_prev.windows(2))
            .zip(&mut x_cur[1..]);
        for (j, (((np, nc), xp), out)) in faces.enumerate() {
            let d1 = nc[1] - nc[0];
            let d2 = nc[1] - np[1];
            let (a11, a12, a22) = (d1.dot(d1), d1.dot(d2), d2.dot(d2));
            // g = a11·a22·sin² of the angle between the lines.
            let g = a11 * a22 - a12 * a12;
            let product = a11 * a22;
            // A Gauss edge shorter than ZERO_GAUSS_EDGE has a direction known only to
            // round-off / its length; NaN comes from Gauss vertices undefined because
            // a guide's Gauss edge is zero.
            let zero_edge =
                a11.is_nan() || a22.is_nan() || a11.min(a22) < ZERO_GAUSS_EDGE * ZERO_GAUSS_EDGE;
            if zero_edge || g.is_nan() || g <= MIN_CROSSING_SINE * MIN_CROSSING_SINE * product {
                return Err(ParallelLines {
                    face: (i, j),
                    sine: (g / product).max(0.0).sqrt(),
                    zero_edge,
                });
            }
            if g < min_sine2 * product {
                min_sine2 = g / product;
                self.report.min_crossing.face = (i, j);
            }
            // The vertex is p2 + t·d2 with t solving s·d1 − t·d2 = p2 − p1 (the
            // lines are coplanar, so either line gives it to round-off); c2 does not
            // depend on the vertices, so one dot product stays on the dependency
            // chain from one vertex to the next.
            let inv_g = 1.0 / g;
            let c2 = (a12 * inv_g) * d1 - (a11 * inv_g) * d2;
            let p2 = xp[1];
            let r = p2 - p1;
            let v = p2 + c2.dot(r) * d2;
            *out = v;
            p1 = v;
        }
        // How each face turns about its node axes (§5.2), in a pass of its own:
        // off the dependency chain of the vertices above.
        let corners = x_prev.windows(2).zip(x_cur.windows(2));
        let axes = n_prev.windows(2).zip(n_cur.windows(2));
        for (j, ((xp, xc), (np, nc))) in corners.zip(axes).enumerate() {
            let axis = np[0] + nc[0] + nc[1] + np[1];
            self.folds
                .add((i, j), quad_turn(&[xp[0], xc[0], xc[1], xp[1]], axis));
        }
        self.report.min_crossing.sine = min_sine2.sqrt();
        self.report.folded_faces = self.folds.count();
        self.report.first_fold = self.folds.first();
        Ok(())
    }
}
