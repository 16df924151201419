//! Random designs for the property tests (§3.1, §3.2): every kind of guide
//! drawn as a planar curve in local coordinates, placed in space by a random
//! rigid motion, with its samples computed here, independently of the
//! generator's samplers (Cox–de Boor basis functions for B-splines, closed-form
//! arcs and parabolas).
//!
//! Two modes:
//! - characteristic (§3.1): guide_u in a plane through the start tangent `t_u`,
//!   guide_v in the orthogonal plane through `t_v`; any θ with |θ − 90| ≥ 5;
//! - arbitrary (§3.2): guide_v's plane tilted by φ ∈ [15°, 75°] about `t_v`,
//!   sometimes guide_u's too (ψ ∈ [15°, 60°] about `t_u`); θ inside the
//!   admissible range `2·atan(sin φ) ≤ |θ| ≤ 180 − 2·atan(sin ψ)`.

use std::fmt;

use glam::{DQuat, DVec3};
use monge_core::design::{ArcSpec, BSplineSpec, ParabolaSpec};
use monge_core::{Design, GuideSpec};
use proptest::prelude::*;

// ---------------------------------------------------------------------------
// Planar curves in local coordinates (s, z): start at (0, 0), start tangent +s.
// ---------------------------------------------------------------------------

/// A guide curve in its own plane, with coordinates `(s, z)`: it starts at the
/// origin with start tangent `+s`.
#[derive(Clone, Debug)]
pub enum Curve2 {
    /// Clamped uniform B-spline; control points `[0,0], [h,0], …`.
    BSpline {
        degree: usize,
        ctrl: Vec<[f64; 2]>,
        samples: usize,
    },
    /// A polyline whose start tangent is given (+s), first chord at any angle.
    Points {
        pts: Vec<[f64; 2]>,
        tangent_len: f64,
    },
    /// Circle through the origin with centre `(0, c)`, swept by `angle_deg`.
    Arc {
        c: f64,
        angle_deg: f64,
        samples: usize,
    },
    /// `(a t + q_s t², q_z t²)`, `t ∈ [0, 1]`.
    Parabola { a: f64, q: [f64; 2], samples: usize },
}

impl Curve2 {
    pub fn kind(&self) -> &'static str {
        match self {
            Curve2::BSpline { .. } => "bspline",
            Curve2::Points { .. } => "points",
            Curve2::Arc { .. } => "arc",
            Curve2::Parabola { .. } => "parabola",
        }
    }

    /// The samples, computed here (independently of the generator).
    pub fn samples(&self) -> Vec<[f64; 2]> {
        match self {
            Curve2::BSpline {
                degree,
                ctrl,
                samples,
            } => (0..*samples)
                .map(|k| bspline_point(*degree, ctrl, k as f64 / (*samples - 1) as f64))
                .collect(),
            Curve2::Points { pts, .. } => pts.clone(),
            Curve2::Arc {
                c,
                angle_deg,
                samples,
            } => {
                let rho = c.abs();
                (0..*samples)
                    .map(|k| {
                        let psi = angle_deg.abs().to_radians() * k as f64 / (*samples - 1) as f64;
                        [rho * psi.sin(), c * (1.0 - psi.cos())]
                    })
                    .collect()
            }
            Curve2::Parabola { a, q, samples } => (0..*samples)
                .map(|k| {
                    let t = k as f64 / (*samples - 1) as f64;
                    [a * t + q[0] * t * t, q[1] * t * t]
                })
                .collect(),
        }
    }
}

/// Clamped uniform knots on [0, 1].
pub fn clamped_knots(count: usize, degree: usize) -> Vec<f64> {
    let spans = count - degree;
    let mut k = vec![0.0; degree + 1];
    k.extend((1..spans).map(|i| i as f64 / spans as f64));
    k.extend(vec![1.0; degree + 1]);
    k
}

/// B-spline point by the Cox–de Boor recursion on the basis functions
/// (a different algorithm from the generator's de Boor point recursion).
pub fn bspline_point(degree: usize, ctrl: &[[f64; 2]], u: f64) -> [f64; 2] {
    let knots = clamped_knots(ctrl.len(), degree);
    let n = ctrl.len();
    // Degree-0 basis: the half-open span containing u; u = 1 belongs to the last one.
    let mut basis: Vec<f64> = (0..knots.len() - 1)
        .map(|i| {
            let inside = knots[i] <= u && u < knots[i + 1];
            let last = u >= 1.0 && knots[i] < knots[i + 1] && knots[i + 1] == 1.0;
            if inside || last {
                1.0
            } else {
                0.0
            }
        })
        .collect();
    for p in 1..=degree {
        let next: Vec<f64> = (0..knots.len() - 1 - p)
            .map(|i| {
                let left = {
                    let d = knots[i + p] - knots[i];
                    if d > 0.0 {
                        (u - knots[i]) / d * basis[i]
                    } else {
                        0.0
                    }
                };
                let right = {
                    let d = knots[i + p + 1] - knots[i + 1];
                    if d > 0.0 {
                        (knots[i + p + 1] - u) / d * basis[i + 1]
                    } else {
                        0.0
                    }
                };
                left + right
            })
            .collect();
        basis = next;
    }
    let mut p = [0.0; 2];
    for i in 0..n {
        p[0] += basis[i] * ctrl[i][0];
        p[1] += basis[i] * ctrl[i][1];
    }
    p
}

// ---------------------------------------------------------------------------
// Embedding in space.
// ---------------------------------------------------------------------------

/// A rigid motion `x ↦ rot·x + shift`.
#[derive(Clone, Copy, Debug)]
pub struct Motion {
    pub rot: DQuat,
    pub shift: DVec3,
}

impl Motion {
    pub fn point(&self, p: DVec3) -> DVec3 {
        self.rot * p + self.shift
    }
    pub fn vector(&self, v: DVec3) -> DVec3 {
        self.rot * v
    }
}

/// The plane of a guide: `(s, z) ↦ s·t + z·d` (t ⟂ d, unit), then a rigid motion.
#[derive(Clone, Copy, Debug)]
pub struct Frame {
    pub t: DVec3,
    pub d: DVec3,
    pub motion: Motion,
}

impl Frame {
    pub fn point(&self, p: [f64; 2]) -> DVec3 {
        self.motion.point(p[0] * self.t + p[1] * self.d)
    }
    pub fn vector(&self, p: [f64; 2]) -> DVec3 {
        self.motion.vector(p[0] * self.t + p[1] * self.d)
    }
}

pub fn arr(v: DVec3) -> [f64; 3] {
    v.to_array()
}

/// The design-file spec of `curve` placed in `frame`.
pub fn spec(curve: &Curve2, f: &Frame) -> GuideSpec {
    match curve {
        Curve2::BSpline {
            degree,
            ctrl,
            samples,
        } => GuideSpec::BSpline {
            bspline: BSplineSpec {
                degree: *degree,
                control_points: ctrl.iter().map(|&p| arr(f.point(p))).collect(),
                knots: None,
                weights: None,
                samples: *samples,
            },
            parameters: None,
        },
        Curve2::Points { pts, tangent_len } => GuideSpec::Points {
            points: pts.iter().map(|&p| arr(f.point(p))).collect(),
            tangent: Some(arr(f.vector([*tangent_len, 0.0]))),
        },
        Curve2::Arc {
            c,
            angle_deg,
            samples,
        } => {
            // Tangent = normal × (start − centre)·sign(angle) must be +t:
            // with normal = ν (t × d), that is ν·c·sign(angle)·t.
            let nu = c.signum() * angle_deg.signum();
            GuideSpec::Arc(ArcSpec {
                center: arr(f.point([0.0, *c])),
                start: arr(f.point([0.0, 0.0])),
                normal: arr(f.motion.vector(nu * f.t.cross(f.d))),
                angle_deg: *angle_deg,
                samples: *samples,
            })
        }
        Curve2::Parabola { a, q, samples } => GuideSpec::Parabola(ParabolaSpec {
            start: arr(f.point([0.0, 0.0])),
            tangent: arr(f.vector([*a, 0.0])),
            quadratic: arr(f.vector(*q)),
            samples: *samples,
        }),
    }
}

// ---------------------------------------------------------------------------
// Strategies.
// ---------------------------------------------------------------------------

pub fn samples() -> impl Strategy<Value = usize> {
    5usize..=25
}

pub fn signed(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (lo..hi, any::<bool>()).prop_map(|(x, neg)| if neg { -x } else { x })
}

pub fn bspline2() -> impl Strategy<Value = Curve2> {
    (2usize..=4)
        .prop_flat_map(|degree| {
            (
                Just(degree),
                0.5..3.0f64,
                prop::collection::vec((-1.0..4.0f64, -2.5..2.5f64), degree - 1..=degree + 3),
                samples(),
            )
        })
        .prop_map(|(degree, h, rest, samples)| {
            let mut ctrl = vec![[0.0, 0.0], [h, 0.0]];
            ctrl.extend(rest.into_iter().map(|(s, z)| [s, z]));
            Curve2::BSpline {
                degree,
                ctrl,
                samples,
            }
        })
}

pub fn points2() -> impl Strategy<Value = Curve2> {
    (
        -1.0..1.0f64,
        prop::collection::vec((0.3..1.5f64, -0.7..0.7f64), 4..=24),
        0.1..10.0f64,
    )
        .prop_map(|(first_angle, steps, tangent_len)| {
            let mut pts = vec![[0.0, 0.0]];
            let mut angle = first_angle;
            for (k, (len, turn)) in steps.into_iter().enumerate() {
                if k > 0 {
                    angle += turn;
                }
                let last = pts[pts.len() - 1];
                pts.push([last[0] + len * angle.cos(), last[1] + len * angle.sin()]);
            }
            Curve2::Points { pts, tangent_len }
        })
}

pub fn arc2() -> impl Strategy<Value = Curve2> {
    (signed(0.5, 5.0), signed(10.0, 300.0), samples()).prop_map(|(c, angle_deg, samples)| {
        Curve2::Arc {
            c,
            angle_deg,
            samples,
        }
    })
}

pub fn parabola2() -> impl Strategy<Value = Curve2> {
    (0.5..2.0f64, -1.0..1.0f64, signed(0.2, 2.0), samples()).prop_map(|(a, qs, qz, samples)| {
        Curve2::Parabola {
            a,
            q: [qs, qz],
            samples,
        }
    })
}

pub fn curve2() -> impl Strategy<Value = Curve2> {
    prop_oneof![
        3 => bspline2(),
        2 => points2(),
        2 => arc2(),
        1 => parabola2(),
    ]
}

/// A random rigid motion; the identity a third of the time (axis-aligned
/// planes, where the guide samples must be reproduced bit for bit).
pub fn motion() -> impl Strategy<Value = Motion> {
    prop_oneof![
        1 => Just(Motion { rot: DQuat::IDENTITY, shift: DVec3::ZERO }),
        2 => (
            (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64),
            0.0..std::f64::consts::PI,
            (-3.0..3.0f64, -3.0..3.0f64, -3.0..3.0f64),
        )
            .prop_filter("axis", |((x, y, z), _, _)| x * x + y * y + z * z > 0.01)
            .prop_map(|((x, y, z), angle, (a, b, c))| Motion {
                rot: DQuat::from_axis_angle(DVec3::new(x, y, z).normalize(), angle),
                shift: DVec3::new(a, b, c),
            }),
    ]
}

/// θ away from the singular +90°.
pub fn regular(theta: f64) -> bool {
    (theta - 90.0).abs() >= 5.0
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    Characteristic,
    Arbitrary,
}

impl fmt::Display for Mode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Mode::Characteristic => "characteristic",
            Mode::Arbitrary => "arbitrary",
        })
    }
}

/// A random design with the guide samples computed here.
#[derive(Clone, Debug)]
pub struct Case {
    pub design: Design,
    /// guide_u's samples, computed independently.
    pub u: Vec<DVec3>,
    /// guide_v's samples, computed independently.
    pub v: Vec<DVec3>,
    /// Expected start normal `t_u × t_v`.
    pub n_p: DVec3,
    /// Expected admissible range `(min, max)` of |θ|.
    pub range: (f64, f64),
    pub label: String,
}

pub fn build(
    mode: Mode,
    cu: Curve2,
    cv: Curve2,
    psi_deg: f64,
    phi_deg: f64,
    m: Motion,
    theta: f64,
) -> Case {
    let (psi, phi) = (psi_deg.to_radians(), phi_deg.to_radians());
    // guide_u: plane spanned by x and (0, sin ψ, cos ψ); guide_v: by y and (sin φ, 0, cos φ).
    let fu = Frame {
        t: DVec3::X,
        d: DVec3::new(0.0, psi.sin(), psi.cos()),
        motion: m,
    };
    let fv = Frame {
        t: DVec3::Y,
        d: DVec3::new(phi.sin(), 0.0, phi.cos()),
        motion: m,
    };
    let design = Design {
        mesh: Default::default(),
        theta_deg: theta,
        guide_u: spec(&cu, &fu),
        guide_v: spec(&cv, &fv),
        tolerance: None,
    };
    let range = (
        2.0 * phi.sin().abs().atan().to_degrees(),
        180.0 - 2.0 * psi.sin().abs().atan().to_degrees(),
    );
    Case {
        label: format!(
            "{mode} θ={theta} u={} ({} samples) v={} ({} samples) ψ={psi_deg:.2} φ={phi_deg:.2} rotated={}",
            cu.kind(),
            cu.samples().len(),
            cv.kind(),
            cv.samples().len(),
            m.rot != DQuat::IDENTITY
        ),
        u: cu.samples().into_iter().map(|p| fu.point(p)).collect(),
        v: cv.samples().into_iter().map(|p| fv.point(p)).collect(),
        n_p: m.vector(DVec3::Z),
        range,
        design,
    }
}

pub fn characteristic_case() -> impl Strategy<Value = Case> {
    let theta = prop_oneof![
        10 => (-180.0..180.0f64).prop_filter("θ near +90°", |&t| regular(t)),
        1 => prop::sample::select(vec![0.0, 180.0, -180.0, -90.0, 45.0, -45.0, 135.0, 1e-7, 179.9999]),
    ];
    (curve2(), curve2(), motion(), theta)
        .prop_map(|(cu, cv, m, theta)| build(Mode::Characteristic, cu, cv, 0.0, 0.0, m, theta))
}

pub fn arbitrary_case() -> impl Strategy<Value = Case> {
    let psi = prop_oneof![1 => Just(0.0), 1 => 15.0..60.0f64];
    (
        curve2(),
        curve2(),
        motion(),
        psi,
        15.0..=75.0f64,
        0.0..=1.0f64,
        any::<bool>(),
    )
        .prop_map(|(cu, cv, m, psi, phi, f, negative)| {
            let lo = 2.0 * phi.to_radians().sin().atan().to_degrees();
            let hi = 180.0 - 2.0 * psi.to_radians().sin().atan().to_degrees();
            let mut theta = lo + f * (hi - lo);
            if negative {
                theta = -theta;
            }
            build(Mode::Arbitrary, cu, cv, psi, phi, m, theta)
        })
        .prop_filter("θ near +90°", |c| regular(c.design.theta_deg))
}

pub fn bbox(points: &[DVec3]) -> f64 {
    let lo = points.iter().fold(points[0], |a, p| a.min(*p));
    let hi = points.iter().fold(points[0], |a, p| a.max(*p));
    (hi - lo).length()
}
