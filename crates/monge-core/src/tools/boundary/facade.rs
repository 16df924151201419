//! Boundary alignment in the façade case (§4.5, Figure 16): four vertical planes, a
//! rectangle in plan.

use glam::DVec3;

use crate::design::{Design, GuideSpec};

use super::candidate::{line_point, Candidate};
use super::spec::{AlignError, BoundarySpec, Rise, ANGLE_TOLERANCE, PLANE_NAMES};

/// The façade case: four vertical planes, a rectangle in plan (Figure 16).
pub(super) struct Facade {
    guide_u: Vec<DVec3>,
    guide_v: Vec<DVec3>,
    t_u: DVec3,
    t_v: DVec3,
    turning: f64,
}

impl Facade {
    pub(super) fn new(
        spec: &BoundarySpec,
        p: [DVec3; 4],
        d: [f64; 4],
        samples: usize,
    ) -> Result<Self, AlignError> {
        let given = [
            spec.first_row,
            spec.last_row,
            spec.first_column,
            spec.last_column,
        ];
        for k in 0..4 {
            let tilt = p[k].z.abs().min(1.0).asin();
            if tilt > ANGLE_TOLERANCE {
                return Err(AlignError::NotVertical {
                    plane: PLANE_NAMES[k],
                    tilt_deg: tilt.to_degrees(),
                    normal: given[k].normal,
                });
            }
        }
        for (a, b, what) in [
            (0, 1, "first_row ∥ last_row"),
            (2, 3, "first_column ∥ last_column"),
        ] {
            let off = p[a].cross(p[b]).length().min(1.0).asin();
            if off > ANGLE_TOLERANCE {
                return Err(AlignError::NotRectangle {
                    what,
                    off_deg: off.to_degrees(),
                });
            }
        }
        let off = p[0].dot(p[2]).abs().min(1.0).asin();
        if off > ANGLE_TOLERANCE {
            return Err(AlignError::NotRectangle {
                what: "first_row ⊥ first_column",
                off_deg: off.to_degrees(),
            });
        }
        let mean = given.iter().map(|q| DVec3::from(q.point)).sum::<DVec3>() / 4.0;
        let near = spec.corner.map(DVec3::from).unwrap_or(mean);
        let corner = line_point(p[0], d[0], p[2], d[2], near);
        // Horizontal start tangents, towards the far planes.
        let toward = |plane: DVec3, far: usize| {
            let t = plane.cross(DVec3::Z).normalize();
            let run = (d[far] - p[far].dot(corner)) / p[far].dot(t);
            if run < 0.0 {
                (-t, -run)
            } else {
                (t, run)
            }
        };
        let (t_v, run_v) = toward(p[0], 3);
        let (t_u, run_u) = toward(p[2], 1);
        let size = run_u.max(run_v);
        for (guide, run, far) in [
            ("guide_u", run_u, "last_row"),
            ("guide_v", run_v, "last_column"),
        ] {
            if run.is_nan() || run <= 1e-9 * size || !run.is_finite() {
                return Err(AlignError::Facade {
                    guide,
                    problem: format!(
                        "would have length {run:e}: the corner lies in {far}. Move {far} away"
                    ),
                });
            }
        }
        let rise = spec.rise.unwrap_or(Rise {
            guide_u: 0.25 * run_u,
            guide_v: 0.25 * run_v,
        });
        for (guide, h) in [("guide_u", rise.guide_u), ("guide_v", rise.guide_v)] {
            if !h.is_finite() || h == 0.0 {
                return Err(AlignError::Facade {
                    guide,
                    problem: format!(
                        "has rise {h}: a guide with horizontal ends that does not rise is straight, \
                         and the normal would not turn along it. Give a non-zero `rise`"
                    ),
                });
            }
        }
        let (guide_u, phi_u) = s_curve(corner, t_u, run_u, rise.guide_u, samples);
        let (guide_v, phi_v) = s_curve(corner, t_v, run_v, rise.guide_v, samples);
        Ok(Facade {
            guide_u,
            guide_v,
            t_u,
            t_v,
            turning: phi_u + phi_v,
        })
    }

    pub(super) fn candidates(&self, theta: f64) -> Result<Vec<Candidate>, String> {
        let pts = |v: &[DVec3]| v.iter().map(|x| x.to_array()).collect::<Vec<_>>();
        Ok(vec![Candidate {
            design: Design {
                theta_deg: theta,
                guide_u: GuideSpec::Points {
                    points: pts(&self.guide_u),
                    tangent: Some(self.t_u.to_array()),
                },
                guide_v: GuideSpec::Points {
                    points: pts(&self.guide_v),
                    tangent: Some(self.t_v.to_array()),
                },
                mesh: Default::default(),
                tolerance: None,
            },
            c: [0.0; 4],
            turning: self.turning,
        }])
    }
}

/// An S-shaped bi-arc from `start` along horizontal `t`, covering `run`
/// horizontally and `rise` vertically, horizontal at both ends, sampled at
/// `samples` points (the junction is a sample, so the torsion-free normals are
/// exact at every sample). Returns the points and the turning angle of each arc.
fn s_curve(start: DVec3, t: DVec3, run: f64, rise: f64, samples: usize) -> (Vec<DVec3>, f64) {
    let phi = 2.0 * (rise.abs() / run).atan();
    let r = run / (2.0 * phi.sin());
    let w = DVec3::Z * rise.signum();
    let first = (samples - 1) / 2;
    let second = samples - 1 - first;
    let on_first = |psi: f64| {
        let half = (psi / 2.0).sin();
        start + r * (psi.sin() * t + 2.0 * half * half * w)
    };
    let junction = on_first(phi);
    let end = start + run * t + rise * DVec3::Z;
    let mut points: Vec<DVec3> = (0..=first)
        .map(|k| on_first(phi * k as f64 / first as f64))
        .collect();
    // The second arc is the first one turned by 180° about the junction.
    for k in 1..=second {
        let psi = phi * (1.0 - k as f64 / second as f64);
        points.push(if k == second {
            end
        } else {
            2.0 * junction - on_first(psi)
        });
    }
    (points, phi)
}
