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
    /// The point at `(u, v)` by the rational Cox–de Boor recursion (§5.3).
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
        let (su, nu) = basis(&self.knots_u, u);
        let (sv, nv) = basis(&self.knots_v, v);
        let (mut h, mut w) = (DVec3::ZERO, 0.0);
        for (a, ba) in nu.iter().enumerate() {
            for (b, bb) in nv.iter().enumerate() {
                let idx = (su - NURBS_DEGREE + a) * self.cols + (sv - NURBS_DEGREE + b);
                let wt = self.weights[idx] * ba * bb;
                h += self.control_points[idx] * wt;
                w += wt;
            }
        }
        h / w
    }
}

/// The knot span `s` of `t` and the three quadratic B-spline basis functions
/// non-zero there ([`bspline::span`], [`bspline::basis`]).
fn basis(knots: &[f64], t: f64) -> (usize, [f64; 3]) {
    let span = bspline::span(knots, NURBS_DEGREE, t);
    let mut n = [0.0; NURBS_DEGREE + 1];
    bspline::basis(knots, span, t, &mut n);
    (span, n)
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
