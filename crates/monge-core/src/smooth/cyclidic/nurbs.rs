//! The whole cyclidic net as one degree-(2,2) NURBS surface with double interior
//! knots (§4.4, §5.3).

use glam::DVec3;

use crate::bspline;

/// The whole net as one NURBS surface of degree (2, 2) with double interior knots (§4.4, §5.3).
///
/// Control point `(a, b)` is `control_points[a * cols + b]`; vertex `(i, j)` of
/// the mesh is control point `(2i, 2j)`. Parameter `u ∈ [0, rows_mesh − 1]`, and
/// `(u, v) = (i + s, j + t)` is the point `(s, t)` of patch `(i, j)`.
#[derive(Clone, Debug, PartialEq)]
pub struct NurbsSurface {
    /// Control points along `u`: `2·(mesh rows) − 1`.
    pub rows: usize,
    /// Control points along `v`: `2·(mesh cols) − 1`.
    pub cols: usize,
    /// Control points, row-major.
    pub control_points: Vec<DVec3>,
    /// Positive weights, row-major.
    pub weights: Vec<f64>,
    /// Knots along `u`: `[0, 0, 0, 1, 1, 2, 2, …, m, m, m]`.
    pub knots_u: Vec<f64>,
    /// Knots along `v`.
    pub knots_v: Vec<f64>,
}

/// Degree of both directions of [`NurbsSurface`].
pub const NURBS_DEGREE: usize = 2;

impl NurbsSurface {
    /// The point at `(u, v)` (§5.3), by [`bspline::surface_point`].
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::cyclidic::{CyclidicNet, CyclidicOptions, Frame};
    /// use monge_core::QuadGrid;
    /// let g = QuadGrid::new(2, 2, vec![DVec3::ZERO, DVec3::Y, DVec3::X, DVec3::X + DVec3::Y], vec![]);
    /// let net = CyclidicNet::from_frame(&g, Frame::new(DVec3::X, DVec3::Y), &CyclidicOptions::default()).unwrap();
    /// assert!((net.nurbs().point(0.5, 0.5) - DVec3::new(0.5, 0.5, 0.0)).length() < 1e-15);
    /// ```
    pub fn point(&self, u: f64, v: f64) -> DVec3 {
        bspline::surface_point(
            [NURBS_DEGREE; 2],
            [&self.knots_u, &self.knots_v],
            &self.control_points,
            &self.weights,
            u,
            v,
        )
    }
}

/// `[0, 0, 0, 1, 1, …, m − 1, m − 1, m, m, m]`.
pub(super) fn knots(m: usize) -> Vec<f64> {
    let mut k = vec![0.0; 3];
    for s in 1..m {
        k.extend([s as f64; 2]);
    }
    k.extend([m as f64; 3]);
    k
}
