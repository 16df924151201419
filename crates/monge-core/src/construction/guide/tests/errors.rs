//! One test per [`GuideError`] variant.

use super::*;

#[test]
fn too_few_samples() {
    let cases = [
        (GuideSpec::points(vec![[0.0; 3]]), "points", 1),
        (GuideSpec::points(vec![]), "points", 0),
        (bspline_spec(bspline(bent(), 2, 1)), "bspline.samples", 1),
        (arc_spec(arc(90.0, 0)), "arc.samples", 0),
        (
            parabola([1.0, 0.0, 0.0], [0.0, 0.0, 1.0], 1),
            "parabola.samples",
            1,
        ),
    ];
    for (spec, field, count) in cases {
        assert_eq!(
            err(&spec),
            GuideError::TooFewSamples {
                guide: U,
                field,
                count
            }
        );
    }
}

#[test]
fn non_finite() {
    let mut points = bent();
    points[2][1] = f64::NAN;
    let e = err(&GuideSpec::points(points));
    assert_eq!(
        e,
        GuideError::NonFinite {
            guide: U,
            field: "points",
            index: Some(2)
        }
    );
    assert!(e.to_string().contains("`points` entry 2"), "{e}");

    let spec = GuideSpec::Points {
        points: bent(),
        tangent: Some([f64::INFINITY, 0.0, 0.0]),
    };
    assert_eq!(
        err(&spec),
        GuideError::NonFinite {
            guide: U,
            field: "tangent",
            index: None
        }
    );

    let mut b = cubic();
    b.knots = Some(vec![0.0, 0.0, 0.0, 0.0, f64::NAN, 1.0, 1.0, 1.0, 1.0]);
    assert_eq!(
        err(&bspline_spec(b)),
        GuideError::NonFinite {
            guide: U,
            field: "bspline.knots",
            index: Some(4)
        }
    );

    let mut b = cubic();
    b.weights = Some(vec![1.0, 1.0, f64::INFINITY, 1.0, 1.0]);
    assert_eq!(
        err(&bspline_spec(b)),
        GuideError::NonFinite {
            guide: U,
            field: "bspline.weights",
            index: Some(2)
        }
    );

    let mut b = cubic();
    b.control_points[3][0] = f64::NEG_INFINITY;
    assert_eq!(
        err(&bspline_spec(b)),
        GuideError::NonFinite {
            guide: U,
            field: "bspline.control_points",
            index: Some(3)
        }
    );

    let mut a = arc(90.0, 5);
    a.angle_deg = f64::NAN;
    assert_eq!(
        err(&arc_spec(a)),
        GuideError::NonFinite {
            guide: U,
            field: "arc.angle_deg",
            index: None
        }
    );

    // Finite input whose samples overflow.
    let e = err(&parabola([1e308, 0.0, 0.0], [1e308, 0.0, 1.0], 5));
    assert_eq!(
        e,
        GuideError::NonFinite {
            guide: U,
            field: "samples",
            index: Some(4)
        }
    );
    assert!(
        e.to_string().contains("sample 4 is not a finite number"),
        "{e}"
    );
}

#[test]
fn overflow() {
    let spec = GuideSpec::points(vec![
        [-1e308, 0.0, 0.0],
        [0.0, 0.0, 1e308],
        [1e308, 0.0, 0.0],
    ]);
    assert!(matches!(err(&spec), GuideError::Overflow { size, .. } if size.is_infinite()));
}

#[test]
fn repeated_point() {
    let mut points = bent();
    points.insert(2, points[1]);
    let e = err(&GuideSpec::points(points));
    assert_eq!(
        e,
        GuideError::RepeatedPoint {
            guide: U,
            index: 1,
            distance: 0.0
        }
    );
    assert!(e.to_string().contains("samples 1 and 2 coincide"), "{e}");
    // Nearly repeated, relative to the size.
    let mut points = bent();
    points[3] = [2.0, 0.0, 0.7 + 1e-13];
    assert!(matches!(
        err(&GuideSpec::points(points)),
        GuideError::RepeatedPoint { index: 2, distance, .. } if distance > 0.0
    ));
}

#[test]
fn straight() {
    let line = GuideSpec::points(vec![[0.0, 0.0, 0.0], [1.0, 2.0, 3.0], [3.0, 6.0, 9.0]]);
    let e = err(&line);
    assert!(matches!(e, GuideError::Straight { deviation, .. } if deviation <= 1e-12));
    assert!(e.to_string().contains("must be curved"), "{e}");
    // Two points are always a straight line.
    assert!(matches!(
        err(&GuideSpec::points(vec![[0.0; 3], [1.0, 0.0, 0.0]])),
        GuideError::Straight { .. }
    ));
    // A parabola whose quadratic term is parallel to its tangent.
    assert!(matches!(
        err(&parabola([1.0, 1.0, 0.0], [0.5, 0.5, 0.0], 9)),
        GuideError::Straight { .. }
    ));
}

#[test]
fn far_from_the_origin_a_refusal_blames_the_precision_of_the_coordinates() {
    // A planar parabola in a tilted plane (a, b orthonormal), of size 4.5,
    // `corner` from the origin: exact as a design, but its coordinates
    // round off its plane.
    let (a, b) = (DVec3::new(0.6, -0.48, 0.64), DVec3::new(0.8, 0.36, -0.48));
    let at = |corner: DVec3| -> Vec<Xyz> {
        (0..12)
            .map(|k| {
                let t = k as f64 / 11.0;
                (corner + 4.0 * t * a + 2.0 * t * t * b).to_array()
            })
            .collect()
    };
    let e = err(&GuideSpec::points(at(DVec3::new(1e8, -2e8, 3e7))));
    let GuideError::NotPlanar {
        relative,
        origin_ratio,
        ..
    } = e
    else {
        panic!("{e:?}")
    };
    // Measured here: the distance of each sample from the exact plane is
    // what rounding to f64 moved it, below ε |coordinate| per axis.
    assert!(origin_ratio > 4e7, "{origin_ratio:e}");
    assert!(
        relative > 1e-9 && relative < 1e3 * f64::EPSILON * origin_ratio,
        "{relative:e}"
    );
    let msg = e.to_string();
    for words in [
        "times their size from the origin",
        "that precision, not the design, is the cause",
        "Model the design near the origin",
        "raise `tolerance.planarity` to 1e-7",
        "`--base-point start`",
    ] {
        assert!(msg.contains(words), "{words}: {msg}");
    }
    // Accepted with that tolerance.
    let loose = Tolerances {
        planarity: 1e-7,
        ..tol()
    };
    Guide::from_spec(
        &GuideSpec::points(at(DVec3::new(1e8, -2e8, 3e7))),
        U,
        &loose,
    )
    .unwrap();
    // Near the origin, the same guide is planar.
    guide(&GuideSpec::points(at(DVec3::ZERO))).unwrap();
}

#[test]
fn not_planar() {
    // A planar parabola with sample 6 lifted out of its plane.
    let lifted = |lift: f64| -> Vec<Xyz> {
        (0..12)
            .map(|k| {
                let t = k as f64 / 11.0;
                [4.0 * t, if k == 6 { lift } else { 0.0 }, 2.0 * t * t]
            })
            .collect()
    };
    let e = err(&GuideSpec::points(lifted(1e-3)));
    let GuideError::NotPlanar {
        index,
        deviation,
        relative,
        tolerance,
        ..
    } = e.clone()
    else {
        panic!("{e:?}")
    };
    assert_eq!(index, 6);
    assert!(deviation > 8e-4 && deviation < 1e-3, "{deviation}");
    assert!((relative - deviation / DVec3::new(4.0, 1e-3, 2.0).length()).abs() < 1e-15);
    assert_eq!(tolerance, 1e-9);
    let msg = e.to_string();
    assert!(
        msg.starts_with("guide_u is not planar: sample 6 is "),
        "{msg}"
    );
    assert!(msg.contains("tolerance 1e-9"), "{msg}");
    assert!(msg.contains("raise `tolerance.planarity`"), "{msg}");
    assert!(!msg.contains("precision"), "{msg}");
    // A larger tolerance accepts it, and the samples are projected.
    let loose = Tolerances {
        planarity: 1e-3,
        ..tol()
    };
    let g = Guide::from_spec(&GuideSpec::points(lifted(1e-3)), U, &loose).unwrap();
    assert!((g.planarity - deviation).abs() < 1e-15);
    let c = g.points.iter().sum::<DVec3>() / g.points.len() as f64;
    for p in &g.points {
        assert!((*p - c).dot(g.plane_normal).abs() < 1e-15);
    }
}

#[test]
fn zero_tangent() {
    let spec = GuideSpec::Points {
        points: bent(),
        tangent: Some([0.0; 3]),
    };
    let e = err(&spec);
    assert_eq!(
        e,
        GuideError::ZeroTangent {
            guide: U,
            from: TangentSource::Given
        }
    );
    assert!(e.to_string().contains("non-zero `tangent`"), "{e}");
    assert_eq!(
        err(&parabola([0.0; 3], [0.0, 0.0, 1.0], 5)),
        GuideError::ZeroTangent {
            guide: U,
            from: TangentSource::Parabola
        }
    );
    let mut b = cubic();
    b.control_points[1] = b.control_points[0];
    let e = err(&bspline_spec(b));
    assert_eq!(
        e,
        GuideError::ZeroTangent {
            guide: U,
            from: TangentSource::ControlPolygon
        }
    );
    assert!(e.to_string().contains("first two control points"), "{e}");
}

#[test]
fn tangent_not_in_plane() {
    let spec = GuideSpec::Points {
        points: bent(),
        tangent: Some([1.0, 1e-6, 0.0]),
    };
    let e = err(&spec);
    assert!(matches!(
        e,
        GuideError::TangentNotInPlane { from: TangentSource::Given, angle, tolerance, .. }
            if (angle - 1e-6).abs() < 1e-12 && tolerance == 1e-9
    ));
    assert!(e.to_string().contains("raise `tolerance.angle`"), "{e}");
    // Within the tolerance it is projected into the plane and normalised.
    let spec = GuideSpec::Points {
        points: bent(),
        tangent: Some([2.0, 1e-10, 0.0]),
    };
    assert_eq!(guide(&spec).unwrap().tangent, DVec3::X);
    // A B-spline whose curve is planar to the tolerance but whose P1 is not.
    let mut b = cubic();
    b.control_points[1][1] = 1e-7;
    b.samples = 3;
    let loose = Tolerances {
        planarity: 1e-6,
        ..tol()
    };
    assert!(matches!(
        Guide::from_spec(&bspline_spec(b), U, &loose),
        Err(GuideError::TangentNotInPlane {
            from: TangentSource::ControlPolygon,
            ..
        })
    ));
}

#[test]
fn zero_degree() {
    assert_eq!(
        err(&bspline_spec(bspline(bent(), 0, 5))),
        GuideError::ZeroDegree { guide: U }
    );
}

#[test]
fn too_few_control_points() {
    let e = err(&bspline_spec(bspline(bent(), 4, 5)));
    assert_eq!(
        e,
        GuideError::TooFewControlPoints {
            guide: U,
            count: 4,
            degree: 4
        }
    );
    assert!(
        e.to_string().contains("needs more than 4 control points"),
        "{e}"
    );
}

#[test]
fn degree_above_the_limit_is_refused_before_sampling() {
    // A Bézier curve of degree MAX_DEGREE in the plane y = 0 is read: its
    // midpoint is the Bernstein sum Σ C(n, k) / 2ⁿ · P_k, here of
    // P_k = (k, 0, k²): (n/2, 0, n(n+1)/4).
    let n = MAX_DEGREE;
    let points: Vec<Xyz> = (0..=n).map(|k| [k as f64, 0.0, (k * k) as f64]).collect();
    let g = guide(&bspline_spec(bspline(points.clone(), n, 3))).unwrap();
    let expected = [n as f64 / 2.0, 0.0, (n * (n + 1)) as f64 / 4.0];
    assert!(
        (g.points[1] - DVec3::from(expected)).length() < 1e-9 * n as f64,
        "{:?}",
        g.points[1]
    );
    // One more is refused, whatever the control points: a huge degree too,
    // without overflow.
    for degree in [n + 1, 4000, usize::MAX] {
        let e = err(&bspline_spec(bspline(points.clone(), degree, 5)));
        assert_eq!(
            e,
            GuideError::DegreeTooHigh {
                guide: U,
                degree,
                max: MAX_DEGREE
            }
        );
    }
    let e = err(&bspline_spec(bspline(points, 4000, 500)));
    assert!(
        e.to_string()
            .contains("`bspline.degree` is 4000, above the largest accepted, 32")
            && e.to_string().contains("Lower the degree"),
        "{e}"
    );
}

#[test]
fn knot_count() {
    let mut b = cubic();
    b.knots = Some(vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0]);
    assert_eq!(
        err(&bspline_spec(b)),
        GuideError::KnotCount {
            guide: U,
            count: 8,
            expected: 9,
            control_points: 5,
            degree: 3
        }
    );
}

#[test]
fn knots_decreasing() {
    let mut b = cubic();
    b.knots = Some(vec![0.0, 0.0, 0.0, 0.0, 0.6, 0.4, 1.0, 1.0, 1.0]);
    assert_eq!(
        err(&bspline_spec(b)),
        GuideError::KnotsDecreasing {
            guide: U,
            index: 5,
            previous: 0.6,
            value: 0.4
        }
    );
}

#[test]
fn empty_knot_span() {
    let mut b = cubic();
    b.knots = Some(vec![2.0; 9]);
    assert_eq!(
        err(&bspline_spec(b)),
        GuideError::EmptyKnotSpan {
            guide: U,
            value: 2.0
        }
    );
}

#[test]
fn knots_not_clamped() {
    let mut b = cubic();
    b.knots = Some(vec![0.0, 0.0, 0.0, 0.2, 0.5, 1.0, 1.0, 1.0, 1.0]);
    let e = err(&bspline_spec(b.clone()));
    assert_eq!(
        e,
        GuideError::KnotsNotClamped {
            guide: U,
            end: "start",
            multiplicity: 3,
            degree: 3
        }
    );
    assert!(
        e.to_string().contains("exactly degree + 1 = 4 times"),
        "{e}"
    );
    b.knots = Some(vec![0.0, 0.0, 0.0, 0.0, 0.5, 0.8, 0.9, 1.0, 1.0]);
    assert_eq!(
        err(&bspline_spec(b.clone())),
        GuideError::KnotsNotClamped {
            guide: U,
            end: "end",
            multiplicity: 2,
            degree: 3
        }
    );
    // Too many repetitions at an end are refused too.
    b.knots = Some(vec![0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0]);
    assert!(matches!(
        err(&bspline_spec(b)),
        GuideError::KnotsNotClamped {
            end: "start",
            multiplicity: 5,
            ..
        }
    ));
}

#[test]
fn knot_multiplicity() {
    let mut b = cubic();
    b.control_points
        .extend([[5.0, 0.0, 2.5], [6.0, 0.0, 2.0], [7.0, 0.0, 3.0]]);
    // 8 control points, degree 3: 12 knots; 0.5 repeated 4 times.
    b.knots = Some(vec![
        0.0, 0.0, 0.0, 0.0, 0.5, 0.5, 0.5, 0.5, 1.0, 1.0, 1.0, 1.0,
    ]);
    assert_eq!(
        err(&bspline_spec(b.clone())),
        GuideError::KnotMultiplicity {
            guide: U,
            index: 4,
            value: 0.5,
            multiplicity: 4,
            degree: 3
        }
    );
    // Repeated `degree` times is fine (a C⁰ kink).
    b.knots = Some(vec![
        0.0, 0.0, 0.0, 0.0, 0.25, 0.5, 0.5, 0.5, 1.0, 1.0, 1.0, 1.0,
    ]);
    let g = guide(&bspline_spec(b.clone())).unwrap();
    assert_eq!(g.points.len(), 17);
}

#[test]
fn weight_count() {
    let mut b = cubic();
    b.weights = Some(vec![1.0; 4]);
    assert_eq!(
        err(&bspline_spec(b)),
        GuideError::WeightCount {
            guide: U,
            count: 4,
            expected: 5
        }
    );
}

#[test]
fn weight_not_positive() {
    let mut b = cubic();
    b.weights = Some(vec![1.0, 1.0, 1.0, -0.5, 1.0]);
    assert_eq!(
        err(&bspline_spec(b.clone())),
        GuideError::WeightNotPositive {
            guide: U,
            index: 3,
            value: -0.5
        }
    );
    b.weights = Some(vec![0.0, 1.0, 1.0, 1.0, 1.0]);
    assert!(matches!(
        err(&bspline_spec(b)),
        GuideError::WeightNotPositive { index: 0, .. }
    ));
}

#[test]
fn arc_zero_normal() {
    let mut a = arc(90.0, 5);
    a.normal = [0.0; 3];
    assert_eq!(err(&arc_spec(a)), GuideError::ArcZeroNormal { guide: U });
}

#[test]
fn arc_zero_radius() {
    let mut a = arc(90.0, 5);
    a.start = a.center;
    assert_eq!(err(&arc_spec(a)), GuideError::ArcZeroRadius { guide: U });
}

#[test]
fn arc_not_orthogonal() {
    let mut a = arc(90.0, 5);
    a.normal = [0.0, 1.0, 1e-6];
    let e = err(&arc_spec(a));
    assert!(matches!(
        e,
        GuideError::ArcNotOrthogonal { angle, tolerance, .. }
            if (angle - 1e-6).abs() < 1e-12 && tolerance == 1e-9
    ));
    assert!(e.to_string().contains("raise `tolerance.angle`"), "{e}");
}

#[test]
fn arc_angle() {
    for angle_deg in [0.0, 360.0, -360.0, 400.0] {
        assert_eq!(
            err(&arc_spec(arc(angle_deg, 5))),
            GuideError::ArcAngle {
                guide: U,
                angle_deg
            }
        );
    }
}
