//! A planar guide fitted to points (§4.7, monge's extension): the cubic B-spline of
//! five control points nearest to a section or a boundary curve of the target, by
//! least squares over its control points and the points' parameters.

use glam::DVec3;

use crate::bspline;
use crate::design::Design;
use crate::guide::{Guide, GuideName};

/// Number of control points of each fitted guide (a cubic B-spline).
pub(super) const CONTROL_POINTS: usize = 5;

/// Knots of the fitted guides: cubic, clamped uniform, [`CONTROL_POINTS`] control
/// points (those [`GuideSpec::bspline`](crate::design::GuideSpec::bspline) gives them).
const GUIDE_KNOTS: [f64; CONTROL_POINTS + 4] = [0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0];

/// The cubic B-spline basis functions of [`GUIDE_KNOTS`] at `u` ([`bspline::span`],
/// [`bspline::basis`]).
pub(super) fn guide_basis(u: f64) -> [f64; CONTROL_POINTS] {
    let u = u.clamp(0.0, 1.0);
    let span = bspline::span(&GUIDE_KNOTS, 3, u);
    let mut out = [0.0; CONTROL_POINTS];
    bspline::basis(&GUIDE_KNOTS, span, u, &mut out[span - 3..=span]);
    out
}

/// Weight of the parameters' distance from chord lengths in [`fit_guide`].
const EVEN_SAMPLING: f64 = 0.001;

/// A guide's control polygon in its plane, `(along, up)`, from the corner `(0, 0)`.
pub(super) type Polygon = [(f64, f64); CONTROL_POINTS];

/// Where [`fit_guide`] places a curve's points along the guide.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Parameters {
    /// Each point's parameter fitted with the control points: a mesh's curves, whose
    /// points lie on them.
    Fitted,
    /// At the points' chord lengths: a scan's boundary, traced through its outermost
    /// points, which zigzag by about a spacing. Fitted parameters tied such a guide into
    /// loops (a second control point behind the first, or one beyond the end and back)
    /// that every θ folded.
    ChordLength,
}

/// The cubic B-spline guide nearest to the points `(s, w)` of a curve in its plane,
/// from `(0, 0)` to the last point, its start tangent along `s` unless `free_tangent`:
/// the free control points by linear least squares at chord-length parameters, then
/// with [`Parameters::Fitted`] with each point's parameter by Levenberg–Marquardt,
/// which also holds the parameters near chord lengths (weight [`EVEN_SAMPLING`]), so
/// the guide is sampled evenly as a designer draws it. `None` for fewer points than
/// unknowns.
pub(super) fn fit_guide(
    section: &[(f64, f64)],
    free_tangent: bool,
    parameters: Parameters,
) -> Option<Polygon> {
    let m = section.len();
    if m < CONTROL_POINTS + 1 {
        return None;
    }
    let chords: Vec<f64> = std::iter::once(0.0)
        .chain(section.windows(2).scan(0.0, |length, w| {
            *length += (w[1].0 - w[0].0).hypot(w[1].1 - w[0].1);
            Some(*length)
        }))
        .collect();
    let total = chords[m - 1];
    if total.is_nan() || total <= 0.0 {
        return None;
    }
    let last = section[m - 1];
    let inner = CONTROL_POINTS - 3;
    // Unknowns: P₁ (along, and up if free), P₂ … P₃ (both), then the parameters of
    // points 1 … m − 2 (the corner is at 0, the last point at 1: the curve ends there).
    let free = 2 * inner + 1 + usize::from(free_tangent);
    let polygon = |x: &[f64]| -> Polygon {
        let mut p = [(0.0, 0.0); CONTROL_POINTS];
        p[1] = (x[0], if free_tangent { x[1] } else { 0.0 });
        let first = free - 2 * inner;
        for k in 0..inner {
            p[2 + k] = (x[first + 2 * k], x[first + 2 * k + 1]);
        }
        p[CONTROL_POINTS - 1] = last;
        p
    };
    // The control points by linear least squares at chord-length parameters.
    let u: Vec<f64> = chords.iter().map(|c| c / total).collect();
    let basis: Vec<[f64; CONTROL_POINTS]> = u.iter().map(|x| guide_basis(*x)).collect();
    let end = CONTROL_POINTS - 1;
    let solve = |first: usize, coordinate: fn(&(f64, f64)) -> f64| {
        let matrix = nalgebra::DMatrix::from_fn(m, end - first, |r, c| basis[r][first + c]);
        let rhs = nalgebra::DVector::from_fn(m, |r, _| {
            coordinate(&section[r]) - basis[r][end] * coordinate(&last)
        });
        matrix.svd(true, true).solve(&rhs, 1e-12).ok()
    };
    let along = solve(1, |p| p.0)?;
    let up = solve(if free_tangent { 1 } else { 2 }, |p| p.1)?;
    let mut x = vec![along[0]];
    if free_tangent {
        x.push(up[0]);
    }
    let up_first = usize::from(free_tangent);
    for k in 0..inner {
        x.extend([along[1 + k], up[up_first + k]]);
    }
    x.extend(&u[1..m - 1]);
    let finite = |p: Polygon| {
        p.iter()
            .all(|(a, b)| a.is_finite() && b.is_finite())
            .then_some(p)
    };
    if parameters == Parameters::ChordLength {
        return finite(polygon(&x));
    }
    let residuals = |x: &[f64]| -> nalgebra::DVector<f64> {
        let p = polygon(x);
        nalgebra::DVector::from_fn(3 * (m - 2), |r, _| {
            let (k, coordinate) = (r / 3, r % 3);
            let at = guide_point(&p, x[free + k]);
            let q = section[k + 1];
            match coordinate {
                0 => at.0 - q.0,
                1 => at.1 - q.1,
                _ => EVEN_SAMPLING * (x[free + k] * total - chords[k + 1]),
            }
        })
    };
    let mut lambda = 1e-3;
    let mut r = residuals(&x);
    let mut cost = r.norm_squared();
    for _ in 0..200 {
        // The Jacobian by central differences.
        let n = x.len();
        let mut jacobian = nalgebra::DMatrix::zeros(r.len(), n);
        for j in 0..n {
            let h = 1e-6 * x[j].abs().max(1.0);
            let (mut plus, mut minus) = (x.clone(), x.clone());
            plus[j] += h;
            minus[j] -= h;
            jacobian.set_column(j, &((residuals(&plus) - residuals(&minus)) / (2.0 * h)));
        }
        let jtj = jacobian.transpose() * &jacobian;
        let jtr = jacobian.transpose() * &r;
        let mut improved = false;
        while lambda < 1e12 {
            let mut damped = jtj.clone();
            for j in 0..n {
                damped[(j, j)] += lambda * jtj[(j, j)].max(1e-12);
            }
            let Some(step) = damped.cholesky().map(|c| c.solve(&(-&jtr))) else {
                lambda *= 10.0;
                continue;
            };
            let trial: Vec<f64> = x.iter().zip(step.iter()).map(|(a, b)| a + b).collect();
            // The points stay in their order along the curve, which leaves the corner
            // forwards: no loops through stray points.
            let ordered = trial[0] > 0.0
                && trial[free..].windows(2).all(|w| w[0] < w[1])
                && trial[free] > 0.0
                && trial[trial.len() - 1] < 1.0;
            let r_trial = residuals(&trial);
            let c_trial = r_trial.norm_squared();
            if ordered && c_trial < cost {
                (x, r, lambda) = (trial, r_trial, (lambda / 3.0).max(1e-12));
                improved = cost - c_trial > 1e-15 * cost.max(f64::MIN_POSITIVE);
                cost = c_trial;
                break;
            }
            lambda *= 4.0;
        }
        if !improved {
            break;
        }
    }
    finite(polygon(&x))
}

/// The point at `u` of the guide of control polygon `p` in its plane.
pub(super) fn guide_point(p: &Polygon, u: f64) -> (f64, f64) {
    let n = guide_basis(u);
    p.iter()
        .zip(n)
        .fold((0.0, 0.0), |(a, b), (q, n)| (a + n * q.0, b + n * q.1))
}

/// A cubic guide in the plane through `corner` spanned by `t` and `n` (normal
/// `other`), fitted to the target points near that plane: `w = c₂s² + c₃s³` by least
/// squares, over `s` from 0 to the target's extent along `t`; as the control points of
/// [`Start::guides`](super::start::Start::guides).
pub(super) fn section_guide(
    points: &[DVec3],
    corner: DVec3,
    t: DVec3,
    other: DVec3,
    n: DVec3,
    size: f64,
) -> Vec<f64> {
    let length = points
        .iter()
        .map(|p| (*p - corner).dot(t))
        .fold(0.0, f64::max)
        .max(1e-3 * size);
    let mut slab = 0.01 * size;
    let mut section: Vec<(f64, f64)> = Vec::new();
    while slab < size {
        section = points
            .iter()
            .filter(|p| (**p - corner).dot(other).abs() <= slab)
            .map(|p| ((*p - corner).dot(t), (*p - corner).dot(n)))
            .filter(|(s, _)| *s > 0.0)
            .collect();
        if section.len() >= 12 {
            break;
        }
        slab *= 2.0;
    }
    // Normal equations of w = c2 s² + c3 s³, in s / length.
    let (mut a, mut b) = (
        nalgebra::Matrix2::<f64>::zeros(),
        nalgebra::Vector2::zeros(),
    );
    for (s, w) in &section {
        let x = s / length;
        let row = nalgebra::Vector2::new(x * x, x * x * x);
        a += row * row.transpose();
        b += row * *w;
    }
    let c = a
        .try_inverse()
        .map_or(nalgebra::Vector2::zeros(), |inv| inv * b);
    // The cubic Bézier of (length·x, c2 x² + c3 x³), then the knot 1/2 inserted.
    let bezier = [
        (0.0, 0.0),
        (length / 3.0, 0.0),
        (2.0 * length / 3.0, c[0] / 3.0),
        (length, c[0] + c[1]),
    ];
    let mid = |p: (f64, f64), q: (f64, f64)| (0.5 * (p.0 + q.0), 0.5 * (p.1 + q.1));
    let control = [
        mid(bezier[0], bezier[1]),
        mid(bezier[1], bezier[2]),
        mid(bezier[2], bezier[3]),
        bezier[3],
    ];
    let mut out = vec![control[0].0];
    for (s, w) in &control[1..] {
        out.extend([*s, *w]);
    }
    out
}

/// A guide's free numbers (the second control point's distance along the start
/// tangent, then `(along, up)` of each later control point, as
/// [`approximate`](super::approximate) moves them) for the same cubic B-spline with
/// every span of its clamped uniform knots halved (knot insertion, Boehm 1980): the
/// same curve, sampled at the same parameters, with `2n − 3` control points for `n`,
/// so that the least squares can follow a target's curve more closely from where
/// they stopped. The second control point stays on the start tangent.
pub(super) fn refine_guide(free: &[f64]) -> Vec<f64> {
    let mut points = vec![(0.0, 0.0), (free[0], 0.0)];
    points.extend(free[1..].chunks(2).map(|c| (c[0], c[1])));
    let mut knots = crate::guide::clamped_uniform_knots(points.len(), 3);
    let mids: Vec<f64> = knots
        .windows(2)
        .filter(|w| w[1] > w[0])
        .map(|w| 0.5 * (w[0] + w[1]))
        .collect();
    for u in mids {
        let k = bspline::span(&knots, 3, u);
        let mut next = Vec::with_capacity(points.len() + 1);
        next.extend_from_slice(&points[..=k - 3]);
        for i in k - 2..=k {
            let a = (u - knots[i]) / (knots[i + 3] - knots[i]);
            let (p, q) = (points[i - 1], points[i]);
            next.push(((1.0 - a) * p.0 + a * q.0, (1.0 - a) * p.1 + a * q.1));
        }
        next.extend_from_slice(&points[k..]);
        points = next;
        knots.insert(k + 1, u);
    }
    let mut out = vec![points[1].0];
    out.extend(points[2..].iter().flat_map(|(s, w)| [*s, *w]));
    out
}

/// Whether a guide of `design` turns back between two of its samples (by more than
/// 90°): a cusp or a hook that a coarser sampling of the same guide steps over, and
/// which folds the whole row or column of faces along it (or a guide that cannot be
/// sampled).
pub(super) fn hooked(design: &Design) -> bool {
    [
        (&design.guide_u, GuideName::U),
        (&design.guide_v, GuideName::V),
    ]
    .into_iter()
    .any(
        |(spec, name)| match Guide::from_spec(spec, name, &Default::default()) {
            Ok(guide) => guide
                .points
                .windows(3)
                .any(|w| (w[1] - w[0]).dot(w[2] - w[1]) <= 0.0),
            Err(_) => true,
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::design::GuideSpec;
    use crate::guide::{Guide, GuideName};

    /// Points of a planar cubic B-spline sampled by the guide module's de Boor (not
    /// [`guide_basis`]), in the plane's `(along, up)` coordinates.
    fn sampled(polygon: &Polygon, samples: usize) -> Vec<(f64, f64)> {
        let control = polygon.iter().map(|(s, w)| [*s, 0.0, *w]).collect();
        let spec = GuideSpec::bspline(3, control, samples);
        let guide = Guide::from_spec(&spec, GuideName::U, &Default::default()).unwrap();
        guide.points.iter().map(|p| (p.x, p.z)).collect()
    }

    #[test]
    fn a_guide_is_recovered_from_its_points() {
        let truth = [
            (0.0, 0.0),
            (2.5, 0.0),
            (5.0, -0.949),
            (7.5, -1.686),
            (10.0, -2.108),
        ];
        for samples in [26, 11] {
            let points = sampled(&truth, samples);
            let fitted = fit_guide(&points, false, Parameters::Fitted).unwrap();
            // The curve, to 2e-4 of its length (~10.6): every point near the fitted curve.
            let curve = sampled(&fitted, 4001);
            let residual = points
                .iter()
                .map(|p| {
                    curve
                        .iter()
                        .map(|q| (p.0 - q.0).hypot(p.1 - q.1))
                        .fold(f64::INFINITY, f64::min)
                })
                .fold(0.0, f64::max);
            assert!(residual < 2e-3, "{residual:e}");
            // Its control polygon to 0.5 % of its length (the fit holds the parameters near chord
            // lengths, which differ slightly from the truth's).
            for (a, b) in fitted.iter().zip(&truth) {
                assert!((a.0 - b.0).hypot(a.1 - b.1) < 0.05, "{fitted:?}");
            }
        }
        // With the start tangent free, it is found too (turned by 0.1 rad here).
        let (c, s) = (0.1f64.cos(), 0.1f64.sin());
        let turned = truth.map(|(x, y)| (c * x - s * y, s * x + c * y));
        let fitted = fit_guide(&sampled(&turned, 21), true, Parameters::Fitted).unwrap();
        assert!(
            (fitted[1].1.atan2(fitted[1].0) - 0.1).abs() < 1e-3,
            "{fitted:?}"
        );
        // Too few points for the unknowns.
        assert_eq!(
            fit_guide(&sampled(&truth, 5), false, Parameters::Fitted),
            None
        );
    }

    #[test]
    fn a_noisy_boundary_is_fitted_at_chord_lengths_without_loops() {
        // A scan's boundary traced through its outermost points (the held-out moulding's,
        // seed 4): fitted with its points' parameters, the guide's second control point
        // came behind the first (0.055 against 0.159 along), a loop every θ folded.
        let section = [
            (0.0, 0.0),
            (0.060, -0.003),
            (0.107, -0.003),
            (0.138, -0.018),
            (0.192, -0.038),
            (0.249, -0.062),
            (0.283, -0.088),
            (0.330, -0.117),
            (0.350, -0.153),
            (0.422, -0.251),
            (0.432, -0.282),
        ];
        let p = fit_guide(&section, false, Parameters::ChordLength).unwrap();
        // Each leg of the polygon ahead of the last (no cusp, no loop).
        for k in 0..CONTROL_POINTS - 2 {
            let (a, b) = (
                (p[k + 1].0 - p[k].0, p[k + 1].1 - p[k].1),
                (p[k + 2].0 - p[k + 1].0, p[k + 2].1 - p[k + 1].1),
            );
            assert!(a.0 * b.0 + a.1 * b.1 > 0.0, "{p:?}");
        }
        // The points near the curve: within the zigzag of the scan's outermost points.
        let curve = sampled(&p, 2001);
        for q in section {
            let d = curve
                .iter()
                .map(|c| (q.0 - c.0).hypot(q.1 - c.1))
                .fold(f64::INFINITY, f64::min);
            assert!(d < 0.02, "{q:?} {d}");
        }
    }

    #[test]
    fn a_refined_guide_is_the_same_curve() {
        // 5 control points (the fitted guides'), then 7, then 11.
        let five = [2.5, 5.0, -0.949, 7.5, -1.686, 10.0, -2.108];
        let seven = refine_guide(&five);
        let eleven = refine_guide(&seven);
        assert_eq!((seven.len(), eleven.len()), (11, 19));
        // Sampled by the guide module's de Boor at the same parameters.
        let curve = |free: &[f64]| {
            let mut polygon = vec![[0.0; 3], [free[0], 0.0, 0.0]];
            polygon.extend(free[1..].chunks(2).map(|c| [c[0], 0.0, c[1]]));
            let spec = GuideSpec::bspline(3, polygon, 101);
            let guide = Guide::from_spec(&spec, GuideName::U, &Default::default()).unwrap();
            guide.points
        };
        let truth = curve(&five);
        for finer in [&seven, &eleven] {
            let gap = truth
                .iter()
                .zip(curve(finer))
                .map(|(a, b)| a.distance(b))
                .fold(0.0, f64::max);
            assert!(gap < 1e-12, "{gap}");
        }
        // The second control point on the start tangent, nearer the corner.
        assert!(seven[0] > 0.0 && seven[0] < five[0]);
    }
}
