//! The frames of a cyclidic net (§4.4): an orthonormal frame at each mesh vertex,
//! carried along the arcs, from the Gauss map of the mesh.

use glam::DVec3;

use crate::grid::QuadGrid;

use super::{CyclidicError, Family};

/// An orthonormal frame at a mesh vertex (§4.4): `t1` along the u-arc, `t2`
/// along the v-arc, `n = t1 × t2`.
///
/// ```
/// use glam::DVec3;
/// use monge_core::cyclidic::{Family, Frame};
/// let f = Frame::new(DVec3::X, DVec3::Y);
/// assert_eq!(f.n, DVec3::Z);
/// // Carried over a u-edge from the origin to (2, 0, 0): t1 turns back to point along the arc.
/// let g = f.carried(DVec3::ZERO, DVec3::new(2.0, 0.0, 0.0), Family::U);
/// assert_eq!((g.t1, g.t2, g.n), (DVec3::X, DVec3::Y, DVec3::Z));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// Unit tangent of the arc towards vertex `(i+1, j)` (§4.4).
    pub t1: DVec3,
    /// Unit tangent of the arc towards vertex `(i, j+1)` (§4.4).
    pub t2: DVec3,
    /// `t1 × t2`, the normal of the net at the vertex (§4.4).
    pub n: DVec3,
}

impl Frame {
    /// The frame `(t1, t2, t1 × t2)` (§4.4); `t1`, `t2` should be orthonormal.
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::cyclidic::Frame;
    /// assert_eq!(Frame::new(DVec3::Y, DVec3::Z).n, DVec3::X);
    /// ```
    pub fn new(t1: DVec3, t2: DVec3) -> Frame {
        Frame {
            t1,
            t2,
            n: t1.cross(t2),
        }
    }

    /// The frame carried over the edge `from → to` of a family-`family` line (§4.4):
    /// reflected in the perpendicular-bisector plane of the edge, with the tangent
    /// along the edge turned back so that it again points forward along its line.
    /// Over a `U` edge (`(i, j) → (i+1, j)`) `t1` is turned, over a `V` edge `t2`.
    /// Carrying backwards (`to → from`) turns the tangent the same way.
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::cyclidic::{Family, Frame};
    /// let f = Frame::new(DVec3::new(1.0, 1.0, 0.0).normalize(), DVec3::Z.cross(DVec3::new(1.0, 1.0, 0.0)).normalize());
    /// let g = f.carried(DVec3::ZERO, DVec3::X, Family::U);
    /// // t1 at the end of a quarter circle: the tangent turned by 90°.
    /// assert!((g.t1 - DVec3::new(1.0, -1.0, 0.0).normalize()).length() < 1e-15);
    /// ```
    pub fn carried(&self, from: DVec3, to: DVec3, family: Family) -> Frame {
        let e = (to - from).normalize();
        let s = |x: DVec3| x - 2.0 * x.dot(e) * e;
        let (t1, t2) = match family {
            Family::U => (-s(self.t1), s(self.t2)),
            Family::V => (s(self.t1), -s(self.t2)),
        };
        Frame {
            t1,
            t2,
            n: s(self.n),
        }
    }
}

/// Largest angle, in degrees, accepted between the two Gauss-circle tangents
/// and 90° in [`CyclidicNet::from_normals`](super::CyclidicNet::from_normals).
const GAUSS_ORTHOGONALITY_DEG: f64 = 1e-6;

/// The frames of §4.4 from the Gauss map of a circular mesh with planar lines.
pub(super) fn gauss_frames(grid: &QuadGrid) -> Result<Vec<Frame>, CyclidicError> {
    let (rows, cols) = (grid.rows, grid.cols);
    if grid.normals.is_empty() {
        return Err(CyclidicError::NoNormals);
    }
    if rows < 3 && cols < 3 {
        return Err(CyclidicError::GaussUndetermined { rows, cols });
    }
    let n = |i: usize, j: usize| grid.normals[i * cols + j];
    // Plane normal of the Gauss circle through the first, middle and last Gauss points.
    let plane = |family: Family, index: usize, pts: [DVec3; 3]| {
        let c = (pts[1] - pts[0]).cross(pts[2] - pts[0]);
        let sine = c.length() / (pts[1] - pts[0]).length() / (pts[2] - pts[0]).length();
        if sine > 1e-12 {
            Ok(c.normalize())
        } else {
            Err(CyclidicError::GaussLineDegenerate {
                family,
                index,
                sine,
            })
        }
    };
    let m1: Vec<Option<DVec3>> = (0..cols)
        .map(|j| {
            (rows >= 3)
                .then(|| plane(Family::U, j, [n(0, j), n(rows / 2, j), n(rows - 1, j)]))
                .transpose()
        })
        .collect::<Result<_, _>>()?;
    let m2: Vec<Option<DVec3>> = (0..rows)
        .map(|i| {
            (cols >= 3)
                .then(|| plane(Family::V, i, [n(i, 0), n(i, cols / 2), n(i, cols - 1)]))
                .transpose()
        })
        .collect::<Result<_, _>>()?;
    // Orient a tangent along the mesh line: towards the next vertex (or from the previous one).
    let forward = |t: DVec3, x: &dyn Fn(usize) -> DVec3, at: usize, len: usize| {
        let d = if at + 1 < len {
            x(at + 1) - x(at)
        } else {
            x(at) - x(at - 1)
        };
        if t.dot(d) < 0.0 {
            -t
        } else {
            t
        }
    };
    let mut frames = Vec::with_capacity(rows * cols);
    for (i, m2) in m2.iter().enumerate() {
        for (j, m1) in m1.iter().enumerate() {
            let nv = n(i, j);
            let t1 = m1.map(|m| m.cross(nv).normalize());
            let t2 = m2.map(|m| m.cross(nv).normalize());
            let (t1, t2) = match (t1, t2) {
                (Some(a), Some(b)) => (a, b),
                (Some(a), None) => (a, nv.cross(a).normalize()),
                (None, Some(b)) => (b.cross(nv).normalize(), b),
                (None, None) => unreachable!("rows ≥ 3 or cols ≥ 3"),
            };
            let t1 = forward(t1, &|r| grid.vertex(r, j), i, rows);
            let t2 = forward(t2, &|c| grid.vertex(i, c), j, cols);
            let cos = t1.dot(t2);
            if cos.abs() > GAUSS_ORTHOGONALITY_DEG.to_radians().sin() || cos.is_nan() {
                return Err(CyclidicError::GaussNotOrthogonal {
                    vertex: (i, j),
                    angle_deg: cos.clamp(-1.0, 1.0).acos().to_degrees(),
                    tolerance_deg: GAUSS_ORTHOGONALITY_DEG,
                });
            }
            frames.push(Frame::new(t1, t2));
        }
    }
    Ok(frames)
}
