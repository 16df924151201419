//! The discrete Combescure transform (§2.2.3): a mesh whose edges are parallel
//! to those of the Gauss map, fitted to the two guide polylines.

use glam::DVec3;

use crate::gauss_map::GaussMap;

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

/// Length below which an edge of the Gauss map (on the unit sphere) is zero.
const ZERO_GAUSS_EDGE: f64 = 1e-12;

/// What the propagation saw on its way (§5.2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CombescureReport {
    /// The smallest sine of the angle between the two lines that defined a
    /// vertex, and the face where it occurred.
    pub min_crossing: ParallelLines,
    /// Number of faces whose orientation is opposite to that of face (0, 0) with
    /// respect to the node axes, or zero: where the mesh pinches or folds over
    /// itself (self-intersection, §5.2).
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
    let (rows, cols) = (gauss.rows, gauss.cols);
    assert_eq!(guide_u.len(), rows, "guide_u has one point per row");
    assert_eq!(guide_v.len(), cols, "guide_v has one point per column");
    let n = &gauss.normals;
    let mut x = Vec::with_capacity(rows * cols);
    x.extend_from_slice(guide_v);
    let mut min_crossing = ParallelLines {
        face: (0, 0),
        sine: 1.0,
        zero_edge: false,
    };
    let mut reference = 0.0;
    let mut folded_faces = 0;
    let mut first_fold = None;
    for i in 0..rows - 1 {
        x.push(guide_u[i + 1]);
        let (up, down) = ((i + 1) * cols, i * cols);
        for j in 0..cols - 1 {
            let corner = n[up + j + 1];
            let d1 = corner - n[up + j];
            let d2 = corner - n[down + j + 1];
            let (a11, a12, a22) = (d1.dot(d1), d1.dot(d2), d2.dot(d2));
            let g = a11 * a22 - a12 * a12;
            let sine2 = g / (a11 * a22);
            // NaN comes from zero-length Gauss edges.
            if sine2.is_nan() || sine2 <= MIN_CROSSING_SINE * MIN_CROSSING_SINE {
                return Err(ParallelLines {
                    face: (i, j),
                    sine: sine2.max(0.0).sqrt(),
                    zero_edge: a11.min(a22) < ZERO_GAUSS_EDGE * ZERO_GAUSS_EDGE,
                });
            }
            if sine2 < min_crossing.sine * min_crossing.sine {
                min_crossing = ParallelLines {
                    face: (i, j),
                    sine: sine2.sqrt(),
                    zero_edge: false,
                };
            }
            let p1 = x[up + j];
            let p2 = x[down + j + 1];
            let r = p2 - p1;
            let (b1, b2) = (d1.dot(r), d2.dot(r));
            let s = (a22 * b1 - a12 * b2) / g;
            let t = (a12 * b1 - a11 * b2) / g;
            let v = 0.5 * ((p1 + s * d1) + (p2 + t * d2));
            x.push(v);
            // Orientation of the face with respect to its node axis.
            let o = (v - x[down + j]).cross(p2 - p1).dot(n[down + j]);
            if i == 0 && j == 0 {
                reference = o;
            } else if o.is_nan() || o * reference <= 0.0 {
                folded_faces += 1;
                first_fold.get_or_insert((i, j));
            }
        }
    }
    Ok((
        x,
        CombescureReport {
            min_crossing,
            folded_faces,
            first_fold,
        },
    ))
}
