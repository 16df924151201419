//! A rational B-spline surface read from IGES (entity 128), and its evaluation.

use glam::DVec3;
use monge_core::bspline::surface_point;

/// A rational B-spline surface (IGES entity 128) read by [`read_iges_surfaces`](crate::read_iges_surfaces).
///
/// Control point `(a, b)`, `a` along `u` (the IGES `S` direction), is
/// `control_points[a * count_v + b]`, as in
/// [`NurbsSurface`](monge_core::cyclidic::NurbsSurface); its weight is `weights[a * count_v + b]`.
#[derive(Clone, Debug, PartialEq)]
pub struct IgesSurface {
    /// Degree along `u` (IGES `M1`).
    pub degree_u: usize,
    /// Degree along `v` (IGES `M2`).
    pub degree_v: usize,
    /// Control points along `u` (IGES `K1 + 1`).
    pub count_u: usize,
    /// Control points along `v` (IGES `K2 + 1`).
    pub count_v: usize,
    /// Knots along `u`: `count_u + degree_u + 1`, non-decreasing.
    pub knots_u: Vec<f64>,
    /// Knots along `v`: `count_v + degree_v + 1`, non-decreasing.
    pub knots_v: Vec<f64>,
    /// Positive weights, `count_u · count_v`.
    pub weights: Vec<f64>,
    /// Control points, `count_u · count_v`, with the entity's transformation applied.
    pub control_points: Vec<DVec3>,
    /// The parameter range along `u` given in the file (`U0`, `U1`).
    pub range_u: [f64; 2],
    /// The parameter range along `v` given in the file (`V0`, `V1`).
    pub range_v: [f64; 2],
}

impl IgesSurface {
    /// The point at `(u, v)`: the rational tensor-product B-spline, evaluated by
    /// monge-core ([`surface_point`]).
    ///
    /// Parameters outside the knot domain `[knots[degree], knots[count]]` are
    /// clamped to it; NaN gives NaN.
    ///
    /// # Panics
    ///
    /// If the fields are inconsistent (lengths as documented), which never
    /// happens for a surface returned by [`read_iges_surfaces`](crate::read_iges_surfaces).
    pub fn point(&self, u: f64, v: f64) -> DVec3 {
        let clamp = |t: f64, knots: &[f64], degree: usize, count: usize| {
            t.clamp(knots[degree], knots[count])
        };
        surface_point(
            [self.degree_u, self.degree_v],
            [&self.knots_u, &self.knots_v],
            &self.control_points,
            &self.weights,
            clamp(u, &self.knots_u, self.degree_u, self.count_u),
            clamp(v, &self.knots_v, self.degree_v, self.count_v),
        )
    }
}
