//! Every way `generate` / `inspect` refuses a design (§3, §5.2), through the
//! public API: the variant, and a message that says what is wrong, by how
//! much, and how to fix it. The degenerate Gauss maps are in degenerate.rs,
//! garbage designs in garbage_designs.rs.

use monge_core::guide::GuideError;
use monge_core::measure::measure;
use monge_core::{
    generate, inspect, Design, GenerateError, GenerateOptions, GuideSpec, Tolerances,
};

use crate::common;
use common::{arc, assert_mentions, bspline, design, opts, refused};

/// A characteristic design (§3.1): guide_u in y = 0 with start tangent +x,
/// guide_v in x = 0 with start tangent +y.
fn characteristic(theta_deg: f64) -> Design {
    design(
        theta_deg,
        bspline(
            vec![
                [0.0, 0.0, 0.0],
                [3.0, 0.0, 0.0],
                [6.0, 0.0, 1.5],
                [9.0, 0.0, 1.0],
            ],
            21,
        ),
        bspline(
            vec![
                [0.0, 0.0, 0.0],
                [0.0, 3.0, 0.0],
                [0.0, 6.0, -1.0],
                [0.0, 9.0, 1.0],
            ],
            17,
        ),
    )
}

#[test]
fn grid_too_large_is_refused_before_sampling() {
    // 10⁹ × 10⁹ samples: sampling would take hours and 48 EB (the test would not end,
    // or abort on the allocation); the refusal comes first.
    let huge = design(
        30.0,
        arc([0.0, 0.0, -10.0], [0.0, 1.0, 0.0], 120.0, 1_000_000_000),
        arc([0.0, 0.0, -3.0], [-1.0, 0.0, 0.0], 80.0, 1_000_000_000),
    );
    let small = GenerateOptions { max_vertices: 1000 };
    let e = refused(&huge, &small);
    assert_eq!(
        e,
        GenerateError::GridTooLarge {
            rows: 1_000_000_000,
            cols: 1_000_000_000,
            vertices: 1_000_000_000_000_000_000,
            limit: 1000,
        }
    );
    assert_eq!(inspect(&huge, &small).unwrap_err(), e);
    assert_mentions(
        &e.to_string(),
        &[
            "1000000000 × 1000000000",
            "1000000000000000000",
            "limit of 1000",
            "lower the `samples`",
            "max_vertices",
        ],
    );
    // Even the default limit refuses it, and the product saturates instead of overflowing.
    let mut worse = huge.clone();
    worse.guide_u = bspline(vec![[0.0; 3]; 4], usize::MAX);
    worse.guide_v = GuideSpec::points(vec![[0.0; 3]; 3]);
    match refused(&worse, &opts()) {
        GenerateError::GridTooLarge {
            rows,
            cols,
            vertices,
            limit,
        } => {
            assert_eq!((rows, cols, vertices), (usize::MAX, 3, usize::MAX));
            assert_eq!(limit, opts().max_vertices);
        }
        e => panic!("{e}"),
    }
    // A grid exactly at the limit is accepted.
    let at_limit = Design {
        mesh: Default::default(),
        guide_u: arc([0.0, 0.0, -10.0], [0.0, 1.0, 0.0], 120.0, 40),
        guide_v: arc([0.0, 0.0, -3.0], [-1.0, 0.0, 0.0], 80.0, 25),
        ..huge
    };
    assert!(generate(&at_limit, &small).is_ok());
}

#[test]
fn bad_tolerance() {
    // A negative tolerance once gave contradictory errors ("0.0e0 from the
    // best-fit plane … tolerance -1e0"); an angle above π rejected valid guides.
    use monge_core::design::Tolerances;
    for (tolerance, name) in [
        (
            Tolerances {
                planarity: -1.0,
                ..Default::default()
            },
            "planarity",
        ),
        (
            Tolerances {
                angle: 3.0,
                ..Default::default()
            },
            "angle",
        ),
        (
            Tolerances {
                start: f64::NAN,
                ..Default::default()
            },
            "start",
        ),
    ] {
        let mut d = characteristic(30.0);
        d.tolerance = Some(tolerance);
        let e = refused(&d, &opts());
        assert!(
            matches!(e, GenerateError::BadTolerance { name: n, .. } if n == name),
            "{e}"
        );
        assert!(
            e.to_string().contains(&format!("`tolerance.{name}`")),
            "{e}"
        );
    }
}

#[test]
fn theta_not_finite() {
    for theta in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let d = characteristic(theta);
        let e = refused(&d, &opts());
        match e {
            GenerateError::ThetaNotFinite(t) => {
                assert!(t.is_nan() == theta.is_nan() && (t.is_nan() || t == theta))
            }
            ref e => panic!("{e}"),
        }
        assert!(matches!(
            inspect(&d, &opts()),
            Err(GenerateError::ThetaNotFinite(_))
        ));
        let shown = if theta.is_nan() {
            "NaN"
        } else if theta > 0.0 {
            "theta_deg is inf"
        } else {
            "theta_deg is -inf"
        };
        assert_mentions(&e.to_string(), &[shown, "give a finite angle"]);
    }
}

#[test]
fn start_points_differ() {
    let mut d = characteristic(30.0);
    // guide_v moved up by 0.5 (its size is about 9.3).
    d.guide_v = bspline(
        vec![
            [0.0, 0.0, 0.5],
            [0.0, 3.0, 0.5],
            [0.0, 6.0, -0.5],
            [0.0, 9.0, 1.5],
        ],
        17,
    );
    let e = refused(&d, &opts());
    match &e {
        GenerateError::StartPointsDiffer {
            u,
            v,
            distance,
            relative,
            tolerance,
            ..
        } => {
            assert_eq!(*u, [0.0, 0.0, 0.0]);
            assert_eq!(*v, [0.0, 0.0, 0.5]);
            assert_eq!(*distance, 0.5);
            assert!(*relative > 0.01 && *relative < 0.1, "{relative}");
            assert_eq!(*tolerance, 1e-9);
        }
        e => panic!("{e}"),
    }
    assert_eq!(inspect(&d, &opts()).unwrap_err(), e);
    assert_mentions(
        &e.to_string(),
        &[
            "[0.0, 0.0, 0.0]",
            "[0.0, 0.0, 0.5]",
            "5.000e-1 apart",
            "tolerance 1e-9",
            "Make their first points equal",
        ],
    );
    // Within a loosened tolerance it is accepted.
    d.tolerance = Some(Tolerances {
        start: 0.1,
        ..Default::default()
    });
    assert!(inspect(&d, &opts()).is_ok());
}

#[test]
fn not_orthogonal() {
    let mut d = characteristic(30.0);
    // guide_v's start tangent at 80° from +x: (cos 80°, sin 80°, 0), in a vertical plane.
    let (s, c) = 80f64.to_radians().sin_cos();
    d.guide_v = bspline(
        vec![
            [0.0, 0.0, 0.0],
            [3.0 * c, 3.0 * s, 0.0],
            [6.0 * c, 6.0 * s, -1.0],
            [9.0 * c, 9.0 * s, 1.0],
        ],
        17,
    );
    let e = refused(&d, &opts());
    match &e {
        GenerateError::NotOrthogonal {
            angle_deg,
            off_deg,
            tolerance_deg,
            ..
        } => {
            assert!((angle_deg - 80.0).abs() < 1e-9, "{angle_deg}");
            assert!((off_deg - 10.0).abs() < 1e-9, "{off_deg}");
            assert!((tolerance_deg - 1e-9f64.to_degrees()).abs() < 1e-20);
        }
        e => panic!("{e}"),
    }
    assert_eq!(inspect(&d, &opts()).unwrap_err(), e);
    assert_mentions(
        &e.to_string(),
        &[
            "80.000000000°",
            "off by 1.000e1°",
            "Turn one guide's start tangent",
            "P1 − P0",
        ],
    );
}

/// guide_v in the plane through the y axis tilted by φ from x = 0 (§3.2).
fn arbitrary(theta_deg: f64, phi_deg: f64) -> Design {
    let (s, c) = phi_deg.to_radians().sin_cos();
    let p = |t: f64, f: f64| [f * s, t, f * c];
    Design {
        mesh: Default::default(),
        guide_v: bspline(
            vec![p(0.0, 0.0), p(3.0, 0.0), p(6.0, -1.0), p(9.0, 1.0)],
            17,
        ),
        ..characteristic(theta_deg)
    }
}

#[test]
fn theta_inadmissible_in_the_arbitrary_case() {
    // c_v = N_p · n_v = ± sin 45°: |θ| must be at least 2·atan(sin 45°) ≈ 70.53°.
    let min = 2.0 * 45f64.to_radians().sin().atan().to_degrees();
    let info = inspect(&arbitrary(30.0, 45.0), &opts()).unwrap();
    assert!((info.theta_range.min_deg - min).abs() < 1e-12);
    assert!((info.theta_range.max_deg - 180.0).abs() < 1e-12);
    for theta in [30.0, -30.0, 0.0, 70.0, 390.0] {
        let e = refused(&arbitrary(theta, 45.0), &opts());
        match &e {
            GenerateError::ThetaInadmissible {
                theta_deg,
                min_deg,
                max_deg,
            } => {
                assert_eq!(*theta_deg, if theta == 390.0 { 30.0 } else { theta });
                assert!((min_deg - min).abs() < 1e-12 && (max_deg - 180.0).abs() < 1e-12);
            }
            e => panic!("θ = {theta}: {e}"),
        }
        assert_mentions(
            &e.to_string(),
            &[&format!("{min:.6}°"), "180.000000°", "Pick θ in that range"],
        );
    }
    // Both ends of the range, both signs, are admissible.
    for theta in [min, -min, 120.0, -120.0, 180.0] {
        assert!(
            generate(&arbitrary(theta, 45.0), &opts()).is_ok(),
            "{theta}"
        );
    }
}

#[test]
fn theta_singular() {
    // θ = +90°: both pencil axes touch S² at N_p, every Gauss circle passes
    // through it and the corner Gauss quad is not circular (§2.2.1).
    for (theta, reduced) in [
        (90.0, 90.0),
        (450.0, 90.0),
        (-270.0, 90.0),
        (90.0005, 90.0005),
    ] {
        for d in [characteristic(theta), arbitrary(theta, 45.0)] {
            let e = refused(&d, &opts());
            match &e {
                GenerateError::ThetaSingular { theta_deg, window } => {
                    assert!((theta_deg - reduced).abs() < 1e-9, "{theta_deg}");
                    assert!(*window > 0.0 && *window <= 0.01, "{window}");
                }
                e => panic!("θ = {theta}: {e}"),
            }
            assert_mentions(
                &e.to_string(),
                &[
                    &format!("theta_deg = {reduced}°"),
                    "θ = +90°",
                    "Move θ away from 90°",
                ],
            );
        }
    }
    // −90° is regular (Enneper's structure), and so is 90° ± 0.01°.
    for theta in [-90.0, 89.99, 90.01] {
        let g = generate(&characteristic(theta), &opts()).unwrap();
        let worst = measure(&g.grid).max_error();
        eprintln!("θ = {theta}: worst measured error {worst:.2e}");
        assert!(worst <= 1e-9, "θ = {theta}: {worst:e}");
    }
}

#[test]
fn guide_errors_pass_through() {
    // A straight guide_u.
    let mut d = characteristic(30.0);
    d.guide_u = GuideSpec::points(vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.5, 0.0, 0.0]]);
    let e = refused(&d, &opts());
    assert!(
        matches!(e, GenerateError::Guide(GuideError::Straight { .. })),
        "{e:?}"
    );
    assert_eq!(inspect(&d, &opts()).unwrap_err(), e);
    assert_mentions(&e.to_string(), &["guide_u is a straight line", "bend it"]);

    // A single point in guide_v.
    let mut d = characteristic(30.0);
    d.guide_v = GuideSpec::points(vec![[0.0; 3]]);
    let e = refused(&d, &opts());
    assert!(
        matches!(e, GenerateError::Guide(GuideError::TooFewSamples { .. })),
        "{e:?}"
    );
    assert_mentions(&e.to_string(), &["guide_v has 1 sample(s)", "at least 2"]);

    // A non-planar guide_v: control point 3 is 0.01 off the plane x = 0.
    let mut d = characteristic(30.0);
    d.guide_v = bspline(
        vec![
            [0.0, 0.0, 0.0],
            [0.0, 3.0, 0.0],
            [0.0, 6.0, -1.0],
            [0.01, 9.0, 1.0],
        ],
        17,
    );
    let e = refused(&d, &opts());
    match &e {
        GenerateError::Guide(GuideError::NotPlanar {
            index,
            relative,
            tolerance,
            ..
        }) => {
            assert_eq!(*tolerance, 1e-9);
            assert!(*relative > 1e-5 && *relative < 1e-2, "{relative}");
            assert!(*index < 17);
        }
        e => panic!("{e:?}"),
    }
    assert_mentions(
        &e.to_string(),
        &[
            "guide_v is not planar",
            "tolerance 1e-9",
            "raise `tolerance.planarity`",
        ],
    );

    // Repeated points in guide_u.
    let mut d = characteristic(30.0);
    d.guide_u = GuideSpec::Points {
        points: vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.2],
            [1.0, 0.0, 0.2],
            [2.0, 0.0, 0.7],
        ],
        tangent: Some([1.0, 0.0, 0.0]),
    };
    let e = refused(&d, &opts());
    assert!(
        matches!(
            e,
            GenerateError::Guide(GuideError::RepeatedPoint { index: 1, .. })
        ),
        "{e:?}"
    );
    assert_mentions(
        &e.to_string(),
        &["samples 1 and 2 coincide", "Remove the repeated point"],
    );
}

/// The characteristic design scaled by `s`: refused, or exact. The mesh is
/// measured after scaling back by 1/s (`measure` itself overflows to NaN for
/// coordinates around 1e150).
fn scaled_is_refused_or_exact(s: f64) -> Result<String, String> {
    let mut d = characteristic(30.0);
    for g in [&mut d.guide_u, &mut d.guide_v] {
        let GuideSpec::BSpline { bspline: b, .. } = g else {
            panic!("a B-spline guide");
        };
        b.control_points
            .iter_mut()
            .for_each(|p| p.iter_mut().for_each(|c| *c *= s));
    }
    match generate(&d, &opts()) {
        Err(e) => Ok(format!("refused: {e}")),
        Ok(g) => {
            let mut h = g.grid.clone();
            h.vertices.iter_mut().for_each(|v| *v /= s);
            let worst = measure(&h).max_error();
            if worst <= 1e-9 {
                Ok(format!("exact to {worst:.1e}"))
            } else {
                Err(format!("accepted, worst measured error {worst:e}"))
            }
        }
    }
}

#[test]
fn extreme_scales_are_refused_or_exact() {
    for s in [1e-300, 1e-200, 1e-150, 1e-100, 1e100, 1e150, 1e200, 1e300] {
        let r = scaled_is_refused_or_exact(s);
        eprintln!("scale {s:e}: {r:?}");
        assert!(r.is_ok(), "scale {s:e}: {r:?}");
    }
}

#[test]
fn tiny_scale_1e_160_is_refused_or_exact() {
    let r = scaled_is_refused_or_exact(1e-160);
    assert!(r.is_ok(), "{r:?}");
}

#[test]
fn scale_out_of_range_is_refused_with_the_limits() {
    for s in [1e-120, 1e120] {
        let mut d = characteristic(30.0);
        for g in [&mut d.guide_u, &mut d.guide_v] {
            let GuideSpec::BSpline { bspline: b, .. } = g else {
                panic!("a B-spline guide");
            };
            b.control_points
                .iter_mut()
                .for_each(|p| p.iter_mut().for_each(|c| *c *= s));
        }
        match generate(&d, &opts()) {
            Err(e @ GenerateError::ScaleOutOfRange { size, min, max }) => {
                assert!(size < min || size > max);
                let msg = e.to_string();
                assert!(msg.contains("1e-100") && msg.contains("Rescale"), "{msg}");
            }
            other => panic!("scale {s:e}: {other:?}"),
        }
    }
}
