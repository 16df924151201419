//! A rational B-spline surface read from IGES (entity 128), and its evaluation.

use glam::DVec3;

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
    /// The point at `(u, v)`: the rational tensor-product B-spline, its basis
    /// functions by the Cox–de Boor recursion.
    ///
    /// Parameters outside the knot domain `[knots[degree], knots[count]]` are
    /// clamped to it; NaN gives NaN.
    ///
    /// # Panics
    ///
    /// If the fields are inconsistent (lengths as documented), which never
    /// happens for a surface returned by [`read_iges_surfaces`](crate::read_iges_surfaces).
    pub fn point(&self, u: f64, v: f64) -> DVec3 {
        let (first_u, nu) = basis(&self.knots_u, self.degree_u, self.count_u, u);
        let (first_v, nv) = basis(&self.knots_v, self.degree_v, self.count_v, v);
        let (mut sum, mut weight) = (DVec3::ZERO, 0.0);
        for (a, &na) in nu.iter().enumerate().filter(|(_, &n)| n != 0.0) {
            for (b, &nb) in nv.iter().enumerate().filter(|(_, &n)| n != 0.0) {
                let k = (first_u + a) * self.count_v + first_v + b;
                let w = self.weights[k] * na * nb;
                sum += self.control_points[k] * w;
                weight += w;
            }
        }
        sum / weight
    }
}

/// The `degree + 1` B-spline basis functions of `degree` on `knots` (for
/// `count` control points) that can be non-zero at `t` (clamped to the
/// domain), and the index of the first: from the degree-0 indicator of the
/// span holding `t` (the last non-empty span at the end of the domain) raised
/// one degree at a time, in `degree²` operations whatever the number of knots.
fn basis(knots: &[f64], degree: usize, count: usize, t: f64) -> (usize, Vec<f64>) {
    let t = t.clamp(knots[degree], knots[count]);
    let span = if t.is_nan() {
        degree
    } else if t < knots[count] {
        knots.partition_point(|&k| k <= t) - 1
    } else {
        knots.partition_point(|&k| k < t) - 1
    };
    let first = span - degree;
    let ratio = |num: f64, den: f64| if den == 0.0 { 0.0 } else { num / den };
    // n[i - first] is basis function i; one more, always 0, past the span.
    let mut n = vec![0.0; degree + 2];
    n[degree] = if t.is_nan() { f64::NAN } else { 1.0 };
    for p in 1..=degree {
        for i in first..=span {
            let j = i - first;
            n[j] = ratio(t - knots[i], knots[i + p] - knots[i]) * n[j]
                + ratio(knots[i + p + 1] - t, knots[i + p + 1] - knots[i + 1]) * n[j + 1];
        }
    }
    n.truncate(degree + 1);
    (first, n)
}
