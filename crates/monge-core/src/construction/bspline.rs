//! B-spline and NURBS evaluation, for the guide curves (§3), the fitted guides
//! of the approximation (§4.8) and the NURBS export of cyclidic nets (§4.4, §5.3):
//! the knot span holding a parameter, the basis functions that are non-zero
//! there (algorithms A2.1 and A2.2 of Piegl and Tiller, *The NURBS Book*), the
//! point of a rational curve by the de Boor algorithm, and the point of a
//! rational tensor-product surface (the cyclidic net's, and the IGES surfaces
//! read as targets, §4.8).
//!
//! A knot vector of `n + 1` control points of degree `p` has `n + p + 2`
//! non-decreasing knots; the curve's domain is `[knots[p], knots[n + 1]]`.
//!
//! ```
//! use glam::DVec3;
//! use monge_core::bspline::{basis, span, Nurbs};
//! // A quadratic with one interior knot: 4 control points.
//! let knots = [0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0];
//! let s = span(&knots, 2, 0.25);
//! assert_eq!(s, 2);
//! let mut n = [0.0; 3];
//! basis(&knots, s, 0.25, &mut n);
//! assert_eq!(n, [0.25, 0.625, 0.125]);
//! // The same point from the basis functions and from the de Boor algorithm.
//! let points = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
//! let weights = [1.0; 4];
//! let curve = Nurbs::new(2, &points, &weights, &knots);
//! let by_basis = n[0] * points[0] + n[1] * points[1] + n[2] * points[2];
//! assert!((curve.point(0.25) - by_basis).length() < 1e-15);
//! assert_eq!(curve.point(1.0), DVec3::Y);
//! ```

use glam::DVec3;

/// The knot span of `u` (algorithm A2.1): the largest `s` in `degree..=n`
/// (`n + 1` control points, so `knots.len() = n + degree + 2`) with
/// `knots[s] ≤ u`, so `knots[s] ≤ u < knots[s + 1]` inside the domain; at and
/// beyond the domain's end `knots[n + 1]`, the last non-empty span (the largest
/// `s` with `knots[s] < knots[n + 1]`, which is `n` unless the knot before the
/// end equals it, as an unclamped knot vector may have); `degree` below the
/// domain (and for NaN).
///
/// The basis functions non-zero at `u` are those of control points
/// `s − degree ..= s`.
pub fn span(knots: &[f64], degree: usize, u: f64) -> usize {
    let n = knots.len() - degree - 2;
    let end = knots[n + 1];
    let inner = &knots[degree + 1..=n];
    degree
        + if u >= end {
            inner.partition_point(|&k| k < end)
        } else {
            inner.partition_point(|&k| k <= u)
        }
}

/// The `n.len() = degree + 1` basis functions of degree `n.len() − 1` that can
/// be non-zero in knot span `span` (see [`span`]), at `u`, written to `n`:
/// `n[r]` is the function of control point `span − degree + r` (algorithm A2.2,
/// the triangular Cox–de Boor recursion without zero terms). They sum to 1.
pub fn basis(knots: &[f64], span: usize, u: f64, n: &mut [f64]) {
    let p = n.len() - 1;
    n[0] = 1.0;
    for j in 1..=p {
        let mut saved = 0.0;
        for r in 0..j {
            let right = knots[span + r + 1] - u;
            let left = u - knots[span + 1 + r - j];
            let tmp = n[r] / (right + left);
            n[r] = saved + right * tmp;
            saved = left * tmp;
        }
        n[j] = saved;
    }
}

/// A NURBS curve: control points, positive weights and a valid knot vector
/// (`points.len() + degree + 1` non-decreasing knots, `degree ≥ 1`).
#[derive(Clone, Copy, Debug)]
pub struct Nurbs<'a> {
    degree: usize,
    points: &'a [DVec3],
    weights: &'a [f64],
    knots: &'a [f64],
    /// Whether the weights differ (else the curve is a polynomial B-spline).
    rational: bool,
}

impl<'a> Nurbs<'a> {
    /// The curve of degree `degree` with these control points, weights (one
    /// per control point) and knots.
    pub fn new(
        degree: usize,
        points: &'a [DVec3],
        weights: &'a [f64],
        knots: &'a [f64],
    ) -> Nurbs<'a> {
        Nurbs {
            degree,
            points,
            weights,
            knots,
            rational: weights.iter().any(|&w| w != weights[0]),
        }
    }

    /// The point at parameter `u` (clamped to the domain), by the rational
    /// de Boor algorithm in affine form: each step is the convex combination
    /// `(1 − β) d_{j−1} + β d_j` with `β = α w_j / ((1 − α) w_{j−1} + α w_j)`,
    /// which is exact at clamped ends (where every `β` is 0, resp. 1).
    /// With equal weights `β = α`: the polynomial de Boor algorithm, without
    /// the weights' divisions.
    pub fn point(&self, u: f64) -> DVec3 {
        let p = self.degree;
        let n = self.points.len() - 1;
        let u = u.clamp(self.knots[p], self.knots[n + 1]);
        let k = span(self.knots, p, u);
        let mut d = self.points[k - p..=k].to_vec();
        let mut w = if self.rational {
            self.weights[k - p..=k].to_vec()
        } else {
            Vec::new()
        };
        for r in 1..=p {
            for j in (r..=p).rev() {
                let i = j + k - p;
                let alpha = (u - self.knots[i]) / (self.knots[i + 1 + p - r] - self.knots[i]);
                // Equal weights stay equal: β = α (the polynomial de Boor step).
                let beta = if self.rational {
                    let w_new = (1.0 - alpha) * w[j - 1] + alpha * w[j];
                    let beta = alpha * w[j] / w_new;
                    w[j] = w_new;
                    beta
                } else {
                    alpha
                };
                d[j] = (1.0 - beta) * d[j - 1] + beta * d[j];
            }
        }
        d[p]
    }
}

/// The point at `(u, v)` of a rational tensor-product B-spline surface: degrees
/// `degrees` and knots `knots` along `u` and along `v`, control points `points`
/// and positive weights `weights` (control point `(a, b)` at `a · count_v + b`,
/// `count_v = knots[1].len() − degrees[1] − 1`). It is `Σ w N_a(u) N_b(v) P /
/// Σ w N_a(u) N_b(v)` over the basis functions non-zero there ([`span`],
/// [`basis`]); terms whose basis function is zero are skipped. Parameters are
/// not clamped: outside the domain, the end spans' polynomials go on.
///
/// ```
/// use glam::DVec3;
/// use monge_core::bspline::surface_point;
/// // A bilinear patch over the unit square.
/// let knots = [0.0, 0.0, 1.0, 1.0];
/// let points = [DVec3::ZERO, DVec3::Y, DVec3::X, DVec3::new(1.0, 1.0, 1.0)];
/// let p = surface_point([1, 1], [&knots, &knots], &points, &[1.0; 4], 0.5, 0.5);
/// assert_eq!(p, DVec3::new(0.5, 0.5, 0.25));
/// ```
pub fn surface_point(
    degrees: [usize; 2],
    knots: [&[f64]; 2],
    points: &[DVec3],
    weights: &[f64],
    u: f64,
    v: f64,
) -> DVec3 {
    let basis_at = |direction: usize, t: f64| {
        let s = span(knots[direction], degrees[direction], t);
        let mut n = vec![0.0; degrees[direction] + 1];
        basis(knots[direction], s, t, &mut n);
        (s - degrees[direction], n)
    };
    let (first_u, nu) = basis_at(0, u);
    let (first_v, nv) = basis_at(1, v);
    let count_v = knots[1].len() - degrees[1] - 1;
    let (mut sum, mut weight) = (DVec3::ZERO, 0.0);
    for (a, &na) in nu.iter().enumerate().filter(|&(_, &n)| n != 0.0) {
        for (b, &nb) in nv.iter().enumerate().filter(|&(_, &n)| n != 0.0) {
            let k = (first_u + a) * count_v + first_v + b;
            let w = weights[k] * na * nb;
            sum += points[k] * w;
            weight += w;
        }
    }
    sum / weight
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// Cox–de Boor basis function `N_{i,p}(u)` by its defining recursion
    /// (independent of [`basis`] and of the de Boor point).
    pub(crate) fn cox_de_boor(knots: &[f64], i: usize, p: usize, u: f64) -> f64 {
        if p == 0 {
            let last = knots[knots.len() - 1];
            let inside = knots[i] <= u && u < knots[i + 1];
            let at_end = u == last && knots[i] < knots[i + 1] && knots[i + 1] == last;
            return if inside || at_end { 1.0 } else { 0.0 };
        }
        let mut value = 0.0;
        let d1 = knots[i + p] - knots[i];
        if d1 > 0.0 {
            value += (u - knots[i]) / d1 * cox_de_boor(knots, i, p - 1, u);
        }
        let d2 = knots[i + p + 1] - knots[i + 1];
        if d2 > 0.0 {
            value += (knots[i + p + 1] - u) / d2 * cox_de_boor(knots, i + 1, p - 1, u);
        }
        value
    }

    /// Clamped knots with a double interior knot, for 7 control points of degree 3.
    const KNOTS: [f64; 11] = [0.0, 0.0, 0.0, 0.0, 0.2, 0.2, 0.65, 1.0, 1.0, 1.0, 1.0];

    #[test]
    fn span_holds_the_parameter() {
        let at = |u| span(&KNOTS, 3, u);
        // [0, 0.2) is span 3, [0.2, 0.65) span 5 (4 is empty), [0.65, 1] span 6.
        assert_eq!(
            [0.0, 0.1, 0.2, 0.5, 0.65, 0.9, 1.0].map(at),
            [3, 3, 5, 5, 6, 6, 6]
        );
        // Outside the domain: the first or last span.
        assert_eq!([-1.0, 2.0, f64::NAN].map(at), [3, 6, 3]);
    }

    #[test]
    fn span_at_the_end_is_the_last_non_empty_one() {
        // Unclamped, quadratic, 4 control points: the domain [0, 1] ends at a
        // double knot, so span 3 ([1, 1)) is empty and span 2 holds the end.
        let knots = [0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0];
        assert_eq!([0.5, 1.0, 1.5].map(|u| span(&knots, 2, u)), [2, 2, 2]);
        let mut n = [0.0; 3];
        basis(&knots, 2, 1.0, &mut n);
        // The defining recursion at the end of the domain (continuous there).
        let expected: Vec<f64> = (0..3).map(|i| cox_de_boor(&knots, i, 2, 1.0)).collect();
        assert_eq!(n.to_vec(), expected);
        assert_eq!(n, [0.0, 0.0, 1.0]);
        // Degree 1 whose last knot inside the domain repeats the end.
        let knots = [2.0, 2.0, 3.0, 3.0, 3.0];
        assert_eq!(span(&knots, 1, 3.0), 1);
    }

    #[test]
    fn surface_point_matches_the_defining_sums() {
        // Degree 2 along u on clamped knots with a double interior knot, degree 3
        // along v on unclamped knots: the sums of the defining recursion.
        let knots_u = [0.0, 0.0, 0.0, 0.4, 0.4, 1.0, 1.0, 1.0];
        let knots_v = [-1.0, -0.5, 0.0, 0.3, 0.6, 1.2, 1.5, 2.0];
        let (count_u, count_v) = (5, 4);
        let points: Vec<DVec3> = (0..count_u * count_v)
            .map(|k| {
                let (a, b) = ((k / count_v) as f64, (k % count_v) as f64);
                DVec3::new(a, b, (a * 1.7 + b * 0.9).sin())
            })
            .collect();
        let weights: Vec<f64> = (0..count_u * count_v)
            .map(|k| 0.5 + (k as f64 * 0.37).fract())
            .collect();
        for i in 0..=20 {
            for j in 0..=20 {
                let u = i as f64 / 20.0;
                let v = knots_v[3] + (knots_v[4] - knots_v[3]) * j as f64 / 20.0;
                let (mut num, mut den) = (DVec3::ZERO, 0.0);
                for a in 0..count_u {
                    for b in 0..count_v {
                        let k = a * count_v + b;
                        let nw = cox_de_boor(&knots_u, a, 2, u)
                            * cox_de_boor(&knots_v, b, 3, v)
                            * weights[k];
                        num += nw * points[k];
                        den += nw;
                    }
                }
                let got = surface_point([2, 3], [&knots_u, &knots_v], &points, &weights, u, v);
                assert!(
                    (got - num / den).length() < 1e-14,
                    "({u}, {v}): {got} vs {}",
                    num / den
                );
            }
        }
    }

    #[test]
    fn basis_matches_the_defining_recursion() {
        for degree in 1..=4 {
            // Clamped, non-uniform, with a double interior knot.
            let mut knots = vec![0.0; degree + 1];
            knots.extend([0.1, 0.35, 0.35, 0.8]);
            knots.extend(vec![1.0; degree + 1]);
            let count = knots.len() - degree - 1;
            for k in 0..=40 {
                let u = k as f64 / 40.0;
                let s = span(&knots, degree, u);
                let mut n = vec![0.0; degree + 1];
                basis(&knots, s, u, &mut n);
                for i in 0..count {
                    let expected = cox_de_boor(&knots, i, degree, u);
                    let got = if (s - degree..=s).contains(&i) {
                        n[i + degree - s]
                    } else {
                        0.0
                    };
                    assert!((got - expected).abs() < 1e-15, "{degree} {u} {i}");
                }
            }
        }
    }

    #[test]
    fn rational_point_matches_the_basis_sum() {
        let points: Vec<DVec3> = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 2.0],
            [2.0, 0.0, 2.5],
            [3.5, 0.0, 1.0],
            [4.0, 0.0, -1.0],
            [6.0, 0.0, 0.5],
            [7.0, 0.0, 2.0],
        ]
        .map(DVec3::from_array)
        .to_vec();
        let weights = [1.0, 2.0, 0.5, 1.0, 3.0, 0.7, 1.0];
        let curve = Nurbs::new(3, &points, &weights, &KNOTS);
        for k in 0..=40 {
            let u = k as f64 / 40.0;
            let (mut num, mut den) = (DVec3::ZERO, 0.0);
            for i in 0..points.len() {
                let nw = cox_de_boor(&KNOTS, i, 3, u) * weights[i];
                num += nw * points[i];
                den += nw;
            }
            let expected = num / den;
            let got = curve.point(u);
            assert!(
                (got - expected).length() <= 1e-15 * 7.0,
                "{k}: {got} vs {expected}"
            );
        }
        // Clamped ends exactly; outside the domain, clamped.
        assert_eq!(curve.point(0.0), points[0]);
        assert_eq!(curve.point(1.0), points[6]);
        assert_eq!(curve.point(-3.0), points[0]);
        assert_eq!(curve.point(3.0), points[6]);
        // Equal weights, whatever their value, give the polynomial curve, and a
        // nearly equal weight a nearby point.
        let one = Nurbs::new(3, &points, &[1.0; 7], &KNOTS).point(0.3);
        assert_eq!(Nurbs::new(3, &points, &[2.0; 7], &KNOTS).point(0.3), one);
        let near_weights = [1.0, 1.0, 1.0, 1.000001, 1.0, 1.0, 1.0];
        let near = Nurbs::new(3, &points, &near_weights, &KNOTS).point(0.3);
        let gap = (one - near).length();
        assert!(gap > 0.0 && gap < 1e-5, "{gap}");
    }
}
