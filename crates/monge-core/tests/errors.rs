//! Every way `generate` / `inspect` refuses a design (§3, §5.2), through the
//! public API: the variant, and a message that says what is wrong, by how
//! much, and how to fix it. Plus a fuzz test: garbage in, `Ok` or `Err` out,
//! never a panic.

use std::panic::{catch_unwind, AssertUnwindSafe};

use glam::{DQuat, DVec3};
use monge_core::design::{ArcSpec, BSplineSpec, ParabolaSpec};
use monge_core::guide::{GuideError, GuideName};
use monge_core::measure::measure;
use monge_core::{
    generate, inspect, Design, GenerateError, GenerateOptions, GuideSpec, Tolerances,
    MIN_NORMAL_TURN,
};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};

fn opts() -> GenerateOptions {
    GenerateOptions::default()
}

/// An arc guide starting at the origin.
fn arc(center: [f64; 3], normal: [f64; 3], angle_deg: f64, samples: usize) -> GuideSpec {
    GuideSpec::arc(center, [0.0; 3], normal, angle_deg, samples)
}

/// A cubic B-spline guide.
fn bspline(control_points: Vec<[f64; 3]>, samples: usize) -> GuideSpec {
    GuideSpec::bspline(3, control_points, samples)
}

/// A characteristic design (§3.1): guide_u in y = 0 with start tangent +x,
/// guide_v in x = 0 with start tangent +y.
fn characteristic(theta_deg: f64) -> Design {
    Design {
        mesh: Default::default(),
        theta_deg,
        guide_u: bspline(
            vec![
                [0.0, 0.0, 0.0],
                [3.0, 0.0, 0.0],
                [6.0, 0.0, 1.5],
                [9.0, 0.0, 1.0],
            ],
            21,
        ),
        guide_v: bspline(
            vec![
                [0.0, 0.0, 0.0],
                [0.0, 3.0, 0.0],
                [0.0, 6.0, -1.0],
                [0.0, 9.0, 1.0],
            ],
            17,
        ),
        tolerance: None,
    }
}

/// Both `generate` and `inspect` (when `inspect` checks it) give this error.
fn refused(design: &Design, options: &GenerateOptions) -> GenerateError {
    match generate(design, options) {
        Ok(_) => panic!("design accepted: {design:?}"),
        Err(e) => e,
    }
}

fn assert_mentions(message: &str, parts: &[&str]) {
    for p in parts {
        assert!(message.contains(p), "message lacks {p:?}: {message}");
    }
    eprintln!("message: {message}");
}

#[test]
fn grid_too_large_is_refused_before_sampling() {
    // 10⁹ × 10⁹ samples: sampling would take hours and 48 EB (the test would not end,
    // or abort on the allocation); the refusal comes first.
    let huge = Design {
        mesh: Default::default(),
        theta_deg: 30.0,
        guide_u: arc([0.0, 0.0, -10.0], [0.0, 1.0, 0.0], 120.0, 1_000_000_000),
        guide_v: arc([0.0, 0.0, -3.0], [-1.0, 0.0, 0.0], 80.0, 1_000_000_000),
        tolerance: None,
    };
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
fn degenerate_on_the_top_circle_of_a_torus() {
    // Profile arc of 150° in 31 samples (5° steps): sample 18 is at 90°, on the
    // torus' top circle, where the normal is the axis and does not turn along
    // the rail: the Gauss edge (0, 18) → (1, 18) has zero length.
    let d = Design {
        mesh: Default::default(),
        theta_deg: 0.0,
        guide_u: arc([0.0, 0.0, -10.0], [0.0, 1.0, 0.0], 120.0, 41),
        guide_v: arc([0.0, 0.0, -3.0], [-1.0, 0.0, 0.0], 150.0, 31),
        tolerance: None,
    };
    let e = refused(&d, &opts());
    match &e {
        GenerateError::Degenerate { face, .. } => assert_eq!(*face, (0, 17)),
        e => panic!("{e}"),
    }
    assert_mentions(
        &e.to_string(),
        &[
            "face (0, 17)",
            "vertex (1, 18)",
            "has (nearly) zero length",
            "top circle",
            "no sample falls exactly",
        ],
    );
    // Once "the two edges that fix vertex (1, 18) are parallel, sine 4.7e-1": an
    // edge of zero length has no direction, and a sine of 0.47 is not parallel.
    assert!(!e.to_string().contains("parallel"), "{e}");
    assert!(!e.to_string().contains("sine"), "{e}");
    // 30 samples (150/29 ° steps) miss the top circle: accepted.
    let mut ok = d.clone();
    ok.guide_v = arc([0.0, 0.0, -3.0], [-1.0, 0.0, 0.0], 150.0, 30);
    assert!(generate(&ok, &opts()).is_ok());
}

#[test]
fn a_normal_that_barely_turns_along_a_guide_is_refused() {
    // guide_v's start tangent (0, 3e-6/10, 1) leaves guide_u's plane y = 0 by
    // `tilt`: that plane is within `tilt` of the tangent plane at the start, and
    // the normal turns along guide_u by about 1.7·tilt (a 120° arc). Measured
    // independently, the mesh's error grows as the tilt shrinks; below the
    // bound it is refused before anything is built.
    let design = |tilt: f64| Design {
        mesh: Default::default(),
        theta_deg: 66.0,
        guide_u: arc([0.0, 0.0, -10.0], [0.0, 1.0, 0.0], 120.0, 41),
        guide_v: arc([0.0, 10.0, -10.0 * tilt], [-1.0, 0.0, 0.0], 80.0, 33),
        tolerance: None,
    };
    let error = |tilt: f64| measure(&generate(&design(tilt), &opts()).unwrap().grid).max_error();
    let (steep, shallow) = (error(1e-2), error(1e-5));
    eprintln!("tilt 1e-2: error {steep:.1e}; tilt 1e-5: error {shallow:.1e}");
    assert!(steep <= 1e-12 && shallow <= 1e-9 && shallow > 10.0 * steep);
    let e = refused(&design(3e-7), &opts());
    // A property of the guides, whatever θ: `inspect` refuses it too.
    assert_eq!(inspect(&design(3e-7), &opts()).unwrap_err(), e);
    match &e {
        GenerateError::NormalStill {
            guide: GuideName::U,
            turn,
            plane_deg,
            min,
        } => {
            assert!((turn / 5.2e-7 - 1.0).abs() < 0.01, "{turn:e}");
            assert!(
                (plane_deg.to_radians() / 3e-7 - 1.0).abs() < 1e-3,
                "{plane_deg:e}"
            );
            assert_eq!(*min, MIN_NORMAL_TURN);
        }
        e => panic!("{e}"),
    }
    assert_mentions(
        &e.to_string(),
        &[
            "turns by only 5.2e-7 rad along guide_u",
            "1.72e-5° from the tangent plane",
            "Tilt guide_u's plane",
        ],
    );
    // The same along guide_v: the design with the guides' roles exchanged.
    let mut swapped = design(3e-7);
    std::mem::swap(&mut swapped.guide_u, &mut swapped.guide_v);
    swapped.theta_deg = 120.0;
    match refused(&swapped, &opts()) {
        GenerateError::NormalStill {
            guide: GuideName::V,
            ..
        } => {}
        e => panic!("{e}"),
    }
}

/// A guide with an exactly straight run (a quadratic B-spline with three
/// collinear control points), in general position: along the run the normal
/// does not turn, so the Gauss edges are zero up to rounding and the
/// Combescure transform cannot scale them to the guide's edges (§5.2).
fn straight_run(rotation: DQuat) -> Design {
    let r = |p: [f64; 3]| (rotation * DVec3::from_array(p)).to_array();
    let guide_u = GuideSpec::BSpline {
        bspline: BSplineSpec {
            degree: 2,
            control_points: [
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [2.0, 0.0, 0.0],
                [3.0, 0.0, 1.0],
                [4.0, 0.0, 3.0],
            ]
            .map(r)
            .to_vec(),
            knots: None,
            weights: None,
            samples: 17,
        },
        parameters: None,
    };
    let guide_v = GuideSpec::BSpline {
        bspline: BSplineSpec {
            degree: 3,
            control_points: [
                [0.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 2.0, 0.6],
                [0.0, 3.0, 0.4],
            ]
            .map(r)
            .to_vec(),
            knots: None,
            weights: None,
            samples: 13,
        },
        parameters: None,
    };
    Design {
        mesh: Default::default(),
        theta_deg: 30.0,
        guide_u,
        guide_v,
        tolerance: None,
    }
}

fn expect_straight_run_refused(d: &Design) {
    match generate(d, &opts()) {
        Err(e @ GenerateError::Degenerate { .. }) => {
            assert_mentions(
                &e.to_string(),
                &["straight piece of a guide", "zero length"],
            );
            assert!(!e.to_string().contains("parallel"), "{e}");
        }
        Err(e) => panic!("{e}"),
        Ok(g) => {
            let m = measure(&g.grid);
            panic!(
                "accepted a guide with a straight run: the mesh is not circular \
                 (face planarity {:e} at {:?}, circularity {:e}, torsion {:e})",
                m.face_planarity.value,
                m.face_planarity.at,
                m.circularity.value,
                m.torsion.map_or(0.0, |w| w.value)
            );
        }
    }
}

#[test]
fn degenerate_on_a_straight_run_of_a_guide_in_axis_aligned_position() {
    // Axis-aligned: the Gauss edges along the run are exactly zero.
    expect_straight_run_refused(&straight_run(DQuat::IDENTITY));
}

#[test]
fn degenerate_on_a_straight_run_of_a_guide_in_general_position() {
    // The same design rotated: the Gauss edges along the run are ~1e-16, not 0.
    let rotation = DQuat::from_axis_angle(DVec3::new(1.0, 2.0, 3.0).normalize(), 0.7);
    expect_straight_run_refused(&straight_run(rotation));
}

#[test]
fn degenerate_on_a_straight_run_found_by_the_property_tests() {
    // The counterexample found by `properties.rs` (shrunk): a quadratic B-spline
    // guide_u whose first three control points are collinear with its start
    // tangent, in general position. With the core of 7a8b0bb it was accepted,
    // with a face planarity of 1.7e-2 of the model size at face (14, 8) and a
    // circularity of 3.6e-2; 98c224d treats Gauss edges under 1e-8 as zero.
    let design = Design {
        mesh: Default::default(),
        theta_deg: 57.63789537857576,
        guide_u: GuideSpec::BSpline {
            bspline: BSplineSpec {
                degree: 2,
                control_points: vec![
                    [2.744654018319016, 2.566740551212795, 0.7370667486318613],
                    [2.361699943374654, 2.8481810320010545, 0.892429009999227],
                    [0.9838140284471382, 3.860816488158329, 1.451429385384924],
                    [2.744654018319016, 2.566740551212795, 0.7370667486318613],
                    [2.744654018319016, 2.566740551212795, 0.7370667486318613],
                    [1.7421106994312296, 2.2774954392251803, -1.2101420730622072],
                ],
                knots: None,
                weights: None,
                samples: 20,
            },
            parameters: None,
        },
        guide_v: GuideSpec::BSpline {
            bspline: BSplineSpec {
                degree: 4,
                control_points: vec![
                    [2.744654018319016, 2.566740551212795, 0.7370667486318613],
                    [1.9853364009517502, 1.2061648314709565, 1.330114945499128],
                    [0.19277346821688246, -0.739498302024824, 0.4361982972753015],
                    [0.6807515299197142, 0.3878029660798181, -0.4030983409713932],
                    [3.065686107302015, 1.952685051930246, 2.640750558391477],
                    [2.191211956406643, 1.6753883980707804, 0.9875760121714634],
                    [3.370537352846789, 2.348279203485917, 2.675558358398948],
                ],
                knots: None,
                weights: None,
                samples: 10,
            },
            parameters: None,
        },
        tolerance: None,
    };
    expect_straight_run_refused(&design);
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

// ---------------------------------------------------------------------------
// Garbage in: Ok or Err out, never a panic.
// ---------------------------------------------------------------------------

fn garbage_f64() -> impl Strategy<Value = f64> {
    prop_oneof![
        6 => -10.0..10.0f64,
        1 => Just(0.0),
        1 => Just(1.0),
        1 => Just(f64::NAN),
        1 => Just(f64::INFINITY),
        1 => Just(f64::NEG_INFINITY),
        1 => Just(f64::MAX),
        1 => Just(-f64::MAX),
        1 => Just(f64::MIN_POSITIVE),
        1 => Just(1e-300),
        1 => Just(1e300),
        1 => Just(5e-324),
        1 => any::<f64>(),
    ]
}

fn garbage_point() -> impl Strategy<Value = [f64; 3]> {
    prop_oneof![
        4 => [garbage_f64(), garbage_f64(), garbage_f64()],
        // In the plane y = 0 or x = 0, so that the guide validation passes more often.
        4 => (-10.0..10.0f64, -10.0..10.0f64, any::<bool>())
            .prop_map(|(a, b, xz)| if xz { [a, 0.0, b] } else { [0.0, a, b] }),
        1 => Just([0.0, 0.0, 0.0]),
    ]
}

/// Point lists with duplicates and collinear runs.
fn garbage_points() -> impl Strategy<Value = Vec<[f64; 3]>> {
    prop_oneof![
        3 => prop::collection::vec(garbage_point(), 0..12),
        1 => (garbage_point(), 0usize..6).prop_map(|(p, n)| vec![p; n]),
        1 => (0usize..8, garbage_f64()).prop_map(|(n, s)| (0..n).map(|k| [k as f64 * s, 0.0, 0.0]).collect()),
        1 => (prop::collection::vec(garbage_point(), 2..8), 0usize..8)
            .prop_map(|(mut v, k)| { let p = v[k % v.len()]; v.insert(k % v.len(), p); v }),
    ]
}

fn garbage_guide() -> impl Strategy<Value = GuideSpec> {
    let points = (garbage_points(), prop::option::of(garbage_point()))
        .prop_map(|(p, tangent)| GuideSpec::Points { points: p, tangent });
    let bspline = (
        0usize..6,
        garbage_points(),
        prop::option::of(prop::collection::vec(garbage_f64(), 0..14)),
        prop::option::of(prop::collection::vec(garbage_f64(), 0..10)),
        0usize..30,
    )
        .prop_map(
            |(degree, control_points, knots, weights, samples)| GuideSpec::BSpline {
                bspline: BSplineSpec {
                    degree,
                    control_points,
                    knots,
                    weights,
                    samples,
                },
                parameters: None,
            },
        );
    let arc = (
        garbage_point(),
        garbage_point(),
        garbage_point(),
        prop_oneof![garbage_f64(), -400.0..400.0f64],
        0usize..30,
    )
        .prop_map(|(center, start, normal, angle_deg, samples)| {
            GuideSpec::Arc(ArcSpec {
                center,
                start,
                normal,
                angle_deg,
                samples,
            })
        });
    let parabola = (
        garbage_point(),
        garbage_point(),
        garbage_point(),
        0usize..30,
    )
        .prop_map(|(start, tangent, quadratic, samples)| {
            GuideSpec::Parabola(ParabolaSpec {
                start,
                tangent,
                quadratic,
                samples,
            })
        });
    prop_oneof![
        3 => points,
        3 => bspline,
        3 => arc,
        2 => parabola,
    ]
}

fn garbage_design() -> impl Strategy<Value = Design> {
    let tolerance = prop::option::of((garbage_f64(), garbage_f64(), garbage_f64()).prop_map(
        |(planarity, angle, start)| Tolerances {
            planarity: planarity.abs(),
            angle: angle.abs(),
            start: start.abs(),
        },
    ));
    (
        prop_oneof![garbage_f64(), -1000.0..1000.0f64, Just(90.0), Just(-180.0)],
        garbage_guide(),
        garbage_guide(),
        tolerance,
    )
        .prop_map(|(theta_deg, guide_u, guide_v, tolerance)| Design {
            mesh: Default::default(),
            theta_deg,
            guide_u,
            guide_v,
            tolerance,
        })
}

/// Designs close to valid ones, so that the generator itself runs on odd input:
/// extreme scales, loosened tolerances (non-planar guides, tangents not at 90°,
/// start points apart), straight and doubled points, any θ.
fn near_valid_design() -> impl Strategy<Value = Design> {
    let plane_points = |xz: bool| {
        let off = prop_oneof![3 => Just(0.0), 1 => -1e-3..1e-3f64];
        prop::collection::vec((-3.0..3.0f64, -3.0..3.0f64, off), 2..12).prop_map(move |v| {
            let mut pts = vec![[0.0; 3]];
            pts.extend(v.into_iter().enumerate().map(|(k, (a, b, off))| {
                let s = k as f64 + 1.0 + a.abs() * 0.1;
                if xz {
                    [s, off, b]
                } else {
                    [off, s, b]
                }
            }));
            pts
        })
    };
    let edit = prop_oneof![
        8 => Just(None),
        1 => (0usize..12).prop_map(|k| Some(("duplicate", k))),
        1 => (0usize..12).prop_map(|k| Some(("flatten", k))),
        1 => (0usize..12).prop_map(|k| Some(("nan", k))),
    ];
    let tangent = |t: [f64; 3]| {
        prop_oneof![
            4 => Just(Some(t)),
            1 => Just(None),
            1 => garbage_point().prop_map(Some),
        ]
    };
    let loose = prop_oneof![
        Just(1e-9),
        Just(1e-3),
        Just(10.0),
        Just(1e300),
        Just(f64::INFINITY)
    ];
    (
        (plane_points(true), plane_points(false)),
        (tangent([1.0, 0.0, 0.0]), tangent([0.0, 1.0, 0.0])),
        (edit.clone(), edit),
        prop::sample::select(vec![1e-300, 1e-150, 1e-8, 1.0, 1.0, 1.0, 1e8, 1e150, 1e300]),
        prop_oneof![
            garbage_f64(),
            -720.0..720.0f64,
            Just(90.0),
            Just(89.9999),
            Just(-90.0)
        ],
        prop::option::of((loose.clone(), loose.clone(), loose)),
    )
        .prop_map(
            |((mut u, mut v), (tu, tv), (eu, ev), scale, theta_deg, tol)| {
                for (pts, e) in [(&mut u, eu), (&mut v, ev)] {
                    match e {
                        Some(("duplicate", k)) => {
                            let p = pts[k % pts.len()];
                            pts.insert(k % pts.len(), p);
                        }
                        Some(("flatten", _)) => pts.iter_mut().for_each(|p| p[2] = 0.0),
                        Some(("nan", k)) => {
                            let n = pts.len();
                            pts[k % n][2] = f64::NAN;
                        }
                        _ => {}
                    }
                    pts.iter_mut()
                        .for_each(|p| p.iter_mut().for_each(|c| *c *= scale));
                }
                Design {
                    mesh: Default::default(),
                    theta_deg,
                    guide_u: GuideSpec::Points {
                        points: u,
                        tangent: tu,
                    },
                    guide_v: GuideSpec::Points {
                        points: v,
                        tangent: tv,
                    },
                    tolerance: tol.map(|(planarity, angle, start)| Tolerances {
                        planarity,
                        angle,
                        start,
                    }),
                }
            },
        )
}

#[test]
fn garbage_never_panics() {
    let config = Config {
        cases: 3000,
        failure_persistence: None,
        max_shrink_iters: 500,
        rng_algorithm: RngAlgorithm::ChaCha,
        ..Config::default()
    };
    let mut runner =
        TestRunner::new_with_rng(config, TestRng::from_seed(RngAlgorithm::ChaCha, &[7; 32]));
    let outcomes = std::cell::RefCell::new(std::collections::BTreeMap::<String, usize>::new());
    let strategy = prop_oneof![1 => garbage_design(), 2 => near_valid_design()];
    let result = runner.run(&strategy, |design| {
        let outcome = catch_unwind(AssertUnwindSafe(|| {
            let info = inspect(&design, &opts()).map(|_| ());
            let generated = generate(&design, &opts());
            if let Ok(g) = &generated {
                // What comes out is a consistent grid.
                assert_eq!(g.grid.vertices.len(), g.grid.rows * g.grid.cols);
                assert_eq!(g.grid.normals.len(), g.grid.vertices.len());
                let _ = measure(&g.grid);
            }
            // `inspect` fails exactly when `generate` fails before θ and the mesh.
            // (Compared as text: ThetaNotFinite(NaN) is not equal to itself.)
            if let Err(e) = &info {
                let g = generated.as_ref().err().map(|g| g.to_string());
                assert_eq!(g, Some(e.to_string()));
            }
            generated
        }));
        match outcome {
            Ok(r) => {
                let key = match r {
                    Ok(_) => "Ok".to_string(),
                    Err(GenerateError::Guide(g)) => {
                        format!(
                            "Guide::{}",
                            format!("{g:?}").split([' ', '{']).next().unwrap()
                        )
                    }
                    Err(e) => format!("{e:?}")
                        .split([' ', '{', '('])
                        .next()
                        .unwrap()
                        .to_string(),
                };
                *outcomes.borrow_mut().entry(key).or_default() += 1;
                Ok(())
            }
            Err(_) => Err(TestCaseError::fail(format!("panicked on {design:?}"))),
        }
    });
    eprintln!("outcomes of {} garbage designs:", runner.config().cases);
    for (k, n) in outcomes.borrow().iter() {
        eprintln!("   {n:5} {k}");
    }
    if let Err(e) = result {
        panic!("{e}");
    }
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

#[test]
fn nearly_parallel_lines_are_worded_with_the_sine_of_their_angle() {
    // The words of the other degenerate Gauss quad: two lines that cross at
    // an angle whose sine is 3e-12 (near 0 for parallel lines).
    let e = GenerateError::Degenerate {
        face: (4, 7),
        sine: 3e-12,
        zero_edge: false,
        hint: "The mesh pinches to a point there (§5.2). Change θ or the guides",
    };
    assert_mentions(
        &e.to_string(),
        &[
            "face (4, 7)",
            "the two lines that fix vertex (5, 8) are (nearly) parallel",
            "the sine of the angle between its two Gauss edges",
            "is 3.0e-12, below 1e-9",
        ],
    );
}
