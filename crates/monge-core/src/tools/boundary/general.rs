//! Boundary alignment in the general case (§4.5): four planes with
//! orthogonal intersection-line directions, guides made of circular arcs.

use glam::DVec3;

use crate::design::{Design, GuideSpec};
use crate::gauss_map::pencil_axes;
use crate::generate::GenerateOptions;
use crate::projective::Line;

use super::candidate::{line_point, solve_gram, Candidate};
use super::spec::BoundarySpec;

/// The general case: four planes with orthogonal intersection-line directions.
pub(super) struct General {
    p: [DVec3; 4],
    d: [f64; 4],
    /// `M = γ δᵀ`.
    gamma: [f64; 2],
    delta: [f64; 2],
    /// Distance of `{n·p1 = γ1} ∩ {n·p2 = γ2}` from the centre.
    d0: f64,
    corner: DVec3,
    samples: usize,
}

impl General {
    pub(super) fn new(spec: &BoundarySpec, p: [DVec3; 4], d: [f64; 4], samples: usize) -> Self {
        let m = [
            [p[0].dot(p[2]), p[0].dot(p[3])],
            [p[1].dot(p[2]), p[1].dot(p[3])],
        ];
        let (mut a, mut b) = (0, 0);
        for i in 0..2 {
            for j in 0..2 {
                if m[i][j].abs() > m[a][b].abs() {
                    (a, b) = (i, j);
                }
            }
        }
        let gamma = [m[0][b], m[1][b]];
        let delta = [m[a][0] / m[a][b], m[a][1] / m[a][b]];
        let (al, be) = solve_gram(p[0].dot(p[1]), gamma[0], gamma[1]);
        let d0 = (al * p[0] + be * p[1]).length();
        let mean = [
            spec.first_row,
            spec.last_row,
            spec.first_column,
            spec.last_column,
        ]
        .iter()
        .map(|q| DVec3::from(q.point))
        .sum::<DVec3>()
            / 4.0;
        let near = spec.corner.map(DVec3::from).unwrap_or(mean);
        let corner = line_point(p[0], d[0], p[2], d[2], near);
        General {
            p,
            d,
            gamma,
            delta,
            d0,
            corner,
            samples,
        }
    }

    pub(super) fn candidates(&self, theta: f64) -> Result<Vec<Candidate>, String> {
        let a = (theta.to_radians() / 2.0).tan().abs();
        if !a.is_finite() || a == 0.0 {
            return Err(
                "θ = 0° and ±180° put an axis at infinity or through the centre, where \
                        P1 ∩ P2 and P3 ∩ P4 (both finite) cannot be"
                    .into(),
            );
        }
        let tabs = a / self.d0;
        let mut out = Vec::new();
        let mut why = "the Gauss circles of the planes would not exist (|c| ≥ 1)".to_string();
        for t in [tabs, -tabs] {
            let c = [
                t * self.gamma[0],
                t * self.gamma[1],
                self.delta[0] / t,
                self.delta[1] / t,
            ];
            if c.iter().any(|x| x.abs() >= 1.0) {
                continue;
            }
            why = "the Gauss circles of first_row and first_column do not meet".into();
            let p = &self.p;
            // Corner normals: circle 1 ∩ circle 3.
            let (al, be) = solve_gram(p[0].dot(p[2]), c[0], c[2]);
            let base = al * p[0] + be * p[2];
            let h2 = 1.0 - base.length_squared();
            if h2 <= 0.0 {
                continue;
            }
            let e = p[0].cross(p[2]).normalize();
            why = "no arc from the corner reaches the far planes with the right end normal".into();
            for branch in [1.0, -1.0] {
                let n_p = base + branch * h2.sqrt() * e;
                for eps in [1.0, -1.0] {
                    let t_v = eps * p[0].cross(n_p).normalize();
                    let t_u = t_v.cross(n_p);
                    let arcs_v = arcs(self.corner, t_v, n_p, p[0], c[0], p[3], c[3], self.d[3]);
                    let arcs_u = arcs(self.corner, t_u, n_p, p[2], c[2], p[1], c[1], self.d[1]);
                    for av in &arcs_v {
                        for au in &arcs_u {
                            let mut design = Design {
                                theta_deg: theta.abs(),
                                guide_u: au.spec(self.samples),
                                guide_v: av.spec(self.samples),
                                mesh: Default::default(),
                                tolerance: None,
                            };
                            // L1 = {n·p1 = c1} ∩ {n·p2 = c2}; which sign of θ makes it?
                            let (x, y) = solve_gram(p[0].dot(p[1]), c[0], c[1]);
                            let x0 = x * p[0] + y * p[1];
                            let dir = p[0].cross(p[1]);
                            let l1 = Line {
                                dir,
                                moment: x0.cross(dir),
                            };
                            let Some(sign) = theta_sign(&design, &l1, theta.abs()) else {
                                continue;
                            };
                            if theta != 0.0 && sign != theta.signum() {
                                continue;
                            }
                            design.theta_deg = sign * theta.abs();
                            out.push(Candidate {
                                design,
                                c,
                                turning: av.turning.abs() + au.turning.abs(),
                            });
                        }
                    }
                }
            }
        }
        if out.is_empty() {
            Err(why)
        } else {
            Ok(out)
        }
    }
}

/// The sign of θ (±1) for which the design's pencil axis L1 is `l1`, if either.
fn theta_sign(design: &Design, l1: &Line, theta_abs: f64) -> Option<f64> {
    let info = crate::generate::inspect(design, &GenerateOptions::default()).ok()?;
    let norm = |l: &Line| {
        let s = (l.dir.length_squared() + l.moment.length_squared()).sqrt();
        (l.dir / s, l.moment / s)
    };
    let (d, m) = norm(l1);
    [1.0, -1.0].into_iter().find(|&sign| {
        pencil_axes(&info.frame, sign * theta_abs).is_ok_and(|axes| {
            let (d2, m2) = norm(&axes.l1);
            let same = (d - d2).length() + (m - m2).length();
            let opposite = (d + d2).length() + (m + m2).length();
            same.min(opposite) < 1e-7
        })
    })
}

/// A circular arc guide: start, unit start tangent, signed turning angle about `axis`.
struct ArcGuide {
    start: DVec3,
    tangent: DVec3,
    axis: DVec3,
    turning: f64,
    chord: f64,
}

impl ArcGuide {
    fn spec(&self, samples: usize) -> GuideSpec {
        let half = self.turning.abs() / 2.0;
        let r = self.chord / (2.0 * half.sin());
        let w = self.axis.cross(self.tangent) * self.turning.signum();
        let center = self.start + r * w;
        let normal = self.axis * self.turning.signum();
        GuideSpec::arc(
            center.to_array(),
            self.start.to_array(),
            normal.to_array(),
            self.turning.abs().to_degrees(),
            samples,
        )
    }
}

/// The arcs in plane `(p, on circle c)` from `start` with tangent `t0` and normal
/// `n0`, whose end normal lies on `{n · q = cq}` and whose end point lies in
/// `{q · x = dq}` (zero, one or two).
#[allow(clippy::too_many_arguments)]
fn arcs(
    start: DVec3,
    t0: DVec3,
    n0: DVec3,
    p: DVec3,
    c: f64,
    q: DVec3,
    cq: f64,
    dq: f64,
) -> Vec<ArcGuide> {
    // N(φ) = c p + cos φ m0 + sin φ (p × m0) as the tangent turns by φ about p.
    let m0 = n0 - c * p;
    let (a, b) = (m0.dot(q), p.cross(m0).dot(q));
    let rhs = cq - c * p.dot(q);
    let r = a.hypot(b);
    if r == 0.0 || rhs.abs() > r {
        return Vec::new();
    }
    let base = b.atan2(a);
    let spread = (rhs / r).clamp(-1.0, 1.0).acos();
    let mut out = Vec::new();
    for phi in [base + spread, base - spread] {
        // Principal value in (−π, π].
        let phi = (phi + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI)
            - std::f64::consts::PI;
        if phi.abs() < 1e-6 {
            continue;
        }
        let (s, co) = (phi / 2.0).sin_cos();
        let mid = co * t0 + s * p.cross(t0);
        let denom = q.dot(mid);
        if denom.abs() < 1e-12 {
            continue;
        }
        let lambda = (dq - q.dot(start)) / denom;
        if lambda == 0.0 || !lambda.is_finite() {
            continue;
        }
        let turning = if lambda > 0.0 {
            phi
        } else {
            phi - 2.0 * std::f64::consts::PI * phi.signum()
        };
        out.push(ArcGuide {
            start,
            tangent: t0,
            axis: p,
            turning,
            chord: lambda.abs(),
        });
    }
    out
}
