//! Every way `developable` refuses a design (§3.3), one test per error
//! variant, with the words of its message; garbage in, never a panic.

use std::f64::consts::TAU;

use glam::DVec3;
use monge_core::developable::{developable, DevelopableError, DevelopableSpec, Field};
use monge_core::{GenerateError, GenerateOptions};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed, TestRunner};

use crate::common;
use common::developable::{check, curve, generate_checked, square, Xyz};
use common::TOL;

fn err(spec: &DevelopableSpec) -> (DevelopableError, String) {
    let e = developable(spec, &GenerateOptions::default()).expect_err("must be refused");
    let msg = e.to_string();
    (e, msg)
}

#[test]
fn error_curve_choice() {
    let mut s = DevelopableSpec::projection(square(), 30.0, vec![-1.0, -2.0]);
    s.helix = DevelopableSpec::helix(square(), vec![]).helix;
    let (e, msg) = err(&s);
    assert_eq!(e, DevelopableError::CurveChoice { given: 2 });
    assert!(msg.contains("exactly one of `helix`") && msg.contains("2 were given"));
    s.helix = None;
    s.projection = None;
    assert_eq!(err(&s).0, DevelopableError::CurveChoice { given: 0 });
}

#[test]
fn error_not_finite() {
    let mut pts = square();
    pts[2][1] = f64::NAN;
    let (e, msg) = err(&DevelopableSpec::projection(
        pts.clone(),
        30.0,
        vec![-1.0, -2.0],
    ));
    assert!(matches!(
        e,
        DevelopableError::NotFinite { field: Field::ProjectionPoint, index: 2, value } if value.is_nan()
    ));
    assert!(
        msg.contains("projection.points[2]") && msg.contains("NaN"),
        "{msg}"
    );
    let (e, _) = err(&DevelopableSpec::helix(pts, vec![-1.0, -2.0]));
    assert!(matches!(
        e,
        DevelopableError::NotFinite {
            field: Field::HelixPoint,
            index: 2,
            ..
        }
    ));
    let (e, msg) = err(&DevelopableSpec::projection(
        square(),
        f64::INFINITY,
        vec![-1.0, -2.0],
    ));
    assert_eq!(
        e,
        DevelopableError::NotFinite {
            field: Field::Alpha,
            index: 0,
            value: f64::INFINITY
        }
    );
    assert!(msg.contains("alpha_deg") && msg.contains("inf"), "{msg}");
    let (e, msg) = err(&DevelopableSpec::projection(
        square(),
        30.0,
        vec![-1.0, f64::NEG_INFINITY],
    ));
    assert!(matches!(
        e,
        DevelopableError::NotFinite {
            field: Field::Height,
            index: 1,
            ..
        }
    ));
    assert!(msg.contains("heights[1]"), "{msg}");
    let mut s = DevelopableSpec::projection(square(), 30.0, vec![-1.0, -2.0]);
    s.reference_normal = [0.0, f64::NAN, 1.0];
    let (e, msg) = err(&s);
    assert!(matches!(
        e,
        DevelopableError::NotFinite {
            field: Field::ReferenceNormal,
            ..
        }
    ));
    assert!(msg.contains("reference_normal"), "{msg}");
}

#[test]
fn error_zero_normal() {
    let mut s = DevelopableSpec::projection(square(), 30.0, vec![-1.0, -2.0]);
    s.reference_normal = [0.0; 3];
    let (e, msg) = err(&s);
    assert_eq!(e, DevelopableError::ZeroNormal);
    assert!(msg.contains("[0, 0, 1]"), "{msg}");
    // A tiny normal is only a direction.
    s.reference_normal = [0.0, 0.0, 1e-300];
    generate_checked(&s, 30.0);
}

#[test]
fn error_too_few_segments_and_heights() {
    let (e, msg) = err(&DevelopableSpec::projection(
        square()[..2].to_vec(),
        30.0,
        vec![-1.0, -2.0],
    ));
    assert_eq!(
        e,
        DevelopableError::TooFewSegments {
            points: 2,
            segments: 1
        }
    );
    assert!(msg.contains("at least 3 points"), "{msg}");
    let (e, msg) = err(&DevelopableSpec::projection(square(), 30.0, vec![-1.0]));
    assert_eq!(e, DevelopableError::TooFewHeights { heights: 1 });
    assert!(msg.contains("at least 2"), "{msg}");
}

#[test]
fn error_too_many_points_and_a_crossing_at_the_limit() {
    // An Archimedean spiral of the most points accepted: a mesh of 999 rulings.
    let spiral = |k: usize| {
        curve(k, 0.0, 3.0 * TAU, |t| {
            let r = 1.0 + 0.4 * t;
            [r * t.cos(), r * t.sin(), 2.0]
        })
    };
    let max = monge_core::developable::MAX_HELIX_POINTS;
    let spec = DevelopableSpec::projection(spiral(max), 20.0, vec![-1.0, -2.0]);
    let mesh = developable(&spec, &GenerateOptions::default()).unwrap();
    assert_eq!((mesh.grid.rows, mesh.grid.cols), (max - 1, 2));
    // An open polygon of as many points on a circle, its last segment turned
    // to run from its first point through the middle of segment 0 and on: the
    // crossing is still found, segment 0 with the last segment.
    let mut arc = curve(max, 0.0, 0.9 * TAU, |t| [t.cos(), t.sin(), 0.0]);
    let middle = (DVec3::from(arc[0]) + DVec3::from(arc[1])) / 2.0;
    arc[max - 1] = (2.0 * middle - DVec3::from(arc[max - 2])).to_array();
    let (e, _) = err(&DevelopableSpec::projection(arc, 20.0, vec![-1.0, -2.0]));
    assert!(
        matches!(e, DevelopableError::SelfCrossing { a: 0, b, distance, .. }
            if b == max - 2 && distance == 0.0),
        "{e:?}"
    );
    // One point more is refused, by its count.
    let (e, msg) = err(&DevelopableSpec::projection(
        spiral(max + 1),
        20.0,
        vec![-1.0, -2.0],
    ));
    assert_eq!(e, DevelopableError::TooManyPoints { points: max + 1 });
    assert!(
        msg.contains("1001 points") && msg.contains("limit of 1000"),
        "{msg}"
    );
}

#[test]
fn error_grid_too_large_names_the_limit_and_the_option() {
    // 3 rulings × 3 cutting planes = 9 vertices.
    let spec = DevelopableSpec::projection(square(), 30.0, vec![-1.0, -2.0, -3.0]);
    let limit = |max_vertices| GenerateOptions { max_vertices };
    assert_eq!(
        developable(&spec, &limit(9)).unwrap().grid.vertices.len(),
        9
    );
    let e = developable(&spec, &limit(8)).unwrap_err();
    assert_eq!(
        e,
        DevelopableError::GridTooLarge(GenerateError::GridTooLarge {
            rows: 3,
            cols: 3,
            vertices: 9,
            limit: 8
        })
    );
    let msg = e.to_string();
    for part in [
        "3 × 3 = 9 vertices",
        "limit of 8",
        "helix points",
        "`--max-vertices`",
    ] {
        assert!(msg.contains(part), "{part}: {msg}");
    }
    // A mesh of 999 × 200 000 ≈ 2e8 vertices (9.6 GB) is refused by the default
    // limit before it is built.
    let pts = curve(1000, 0.0, 0.9 * TAU, |t| [t.cos(), t.sin(), 0.0]);
    let heights: Vec<f64> = (1..=200_000).map(|k| -f64::from(k)).collect();
    let e = developable(
        &DevelopableSpec::projection(pts, 30.0, heights),
        &GenerateOptions::default(),
    )
    .unwrap_err();
    assert!(
        matches!(
            e,
            DevelopableError::GridTooLarge(GenerateError::GridTooLarge {
                rows: 999,
                cols: 200_000,
                vertices: 199_800_000,
                limit: 25_000_000
            })
        ),
        "{e:?}"
    );
}

#[test]
fn error_projection_not_planar() {
    let mut pts = square();
    pts[3][2] = 0.01;
    pts[1][2] = -0.001;
    let (e, msg) = err(&DevelopableSpec::projection(pts, 30.0, vec![-1.0, -2.0]));
    let DevelopableError::ProjectionNotPlanar {
        index,
        offset,
        relative,
    } = e
    else {
        panic!("{e:?}")
    };
    assert_eq!(index, 3);
    assert_eq!(offset, 0.01);
    assert!(relative > 1e-4 && relative < 1e-2);
    assert!(
        msg.contains("projection.points[3]") && msg.contains("1.000e-2"),
        "{msg}"
    );
}

#[test]
fn error_repeated_point() {
    let mut pts = square();
    pts.insert(2, pts[2]);
    let (e, msg) = err(&DevelopableSpec::projection(
        pts.clone(),
        30.0,
        vec![-1.0, -2.0],
    ));
    assert!(
        matches!(e, DevelopableError::RepeatedPoint { index: 2, distance, .. } if distance == 0.0)
    );
    assert!(msg.contains("helix points 2 and 3 coincide"), "{msg}");
    let helix: Vec<Xyz> = pts.iter().map(|p| [p[0], p[1], p[0] + p[1]]).collect();
    let (e, _) = err(&DevelopableSpec::helix(helix, vec![-1.0, -2.0]));
    assert!(matches!(
        e,
        DevelopableError::RepeatedPoint { index: 2, .. }
    ));
}

#[test]
fn error_flat_and_vertical_slopes() {
    let (e, msg) = err(&DevelopableSpec::projection(
        square(),
        0.0,
        vec![-1.0, -2.0],
    ));
    assert_eq!(e, DevelopableError::Flat { alpha_deg: 0.0 });
    assert!(msg.contains("α = 0°") && msg.contains("parallel"), "{msg}");
    let (e, msg) = err(&DevelopableSpec::projection(
        square(),
        -90.0,
        vec![-1.0, -2.0],
    ));
    assert_eq!(e, DevelopableError::Vertical { alpha_deg: -90.0 });
    assert!(
        msg.contains("α = -90°") && msg.contains("cylinder"),
        "{msg}"
    );
    let (e, msg) = err(&DevelopableSpec::projection(
        square(),
        120.0,
        vec![-1.0, -2.0],
    ));
    assert_eq!(e, DevelopableError::AlphaOutOfRange { alpha_deg: 120.0 });
    assert!(msg.contains("120°"), "{msg}");
    // Given directly: a flat polyline, and a vertical one.
    let (e, _) = err(&DevelopableSpec::helix(square(), vec![-1.0, -2.0]));
    assert_eq!(e, DevelopableError::Flat { alpha_deg: 0.0 });
    let vertical = vec![[0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 0.0, 2.0]];
    let (e, msg) = err(&DevelopableSpec::helix(vertical, vec![-1.0, -2.0]));
    assert_eq!(e, DevelopableError::Vertical { alpha_deg: 90.0 });
    assert!(msg.contains("α = 90°"), "{msg}");
}

#[test]
fn error_non_constant_slope_reports_the_worst_segment() {
    // Rises 1, 1, 1.1 over unit runs: segment 2 is the outlier.
    let helix = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 1.0],
        [1.0, 1.0, 2.0],
        [0.0, 1.0, 3.1],
    ];
    let (e, msg) = err(&DevelopableSpec::helix(helix.clone(), vec![-1.0, -2.0]));
    let DevelopableError::NonConstantSlope {
        segment,
        angle_deg,
        alpha_deg,
        deviation,
    } = e
    else {
        panic!("{e:?}")
    };
    assert_eq!(segment, 2);
    assert!((angle_deg - 1.1f64.atan().to_degrees()).abs() < 1e-12);
    assert!((alpha_deg - (3.1f64 / 3.0).atan().to_degrees()).abs() < 1e-12);
    assert!(deviation > 1e-2);
    assert!(msg.contains("segment 2 (points 2..3)"), "{msg}");
    // Within the tolerance the helix is accepted and re-lifted exactly.
    let mut close = helix;
    close[3][2] = 3.0 + 1e-11;
    let spec = DevelopableSpec::helix(close, vec![-1.0, -2.0]);
    generate_checked(&spec, (3.0f64 + 1e-11).atan2(3.0).to_degrees());
    // A zigzag at ±45° has a mean slope of 0° but is not a helix.
    let zigzag = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 1.0], [1.0, 1.0, 0.0]];
    let (e, _) = err(&DevelopableSpec::helix(zigzag, vec![-1.0, -2.0]));
    assert!(
        matches!(e, DevelopableError::NonConstantSlope { .. }),
        "{e:?}"
    );
}

#[test]
fn error_straight_vertex() {
    let pts = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [2.0, 1.0, 0.0],
    ];
    let (e, msg) = err(&DevelopableSpec::projection(pts, 30.0, vec![-1.0, -2.0]));
    assert!(
        matches!(e, DevelopableError::Straight { vertex: 1, .. }),
        "{e:?}"
    );
    assert!(msg.contains("segments 0 and 1 are collinear"), "{msg}");
}

#[test]
fn error_self_crossing() {
    // A bow tie: segments 0 and 2 cross at (1, 0.5).
    let pts = vec![
        [0.0, 0.0, 0.0],
        [2.0, 1.0, 0.0],
        [2.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
    ];
    let (e, msg) = err(&DevelopableSpec::projection(pts, 30.0, vec![-1.0, -2.0]));
    assert!(
        matches!(e, DevelopableError::SelfCrossing { a: 0, b: 2, distance, .. } if distance == 0.0),
        "{e:?}"
    );
    assert!(
        msg.contains("segments 0 (points 0..1) and 2 (points 2..3)"),
        "{msg}"
    );
    // Folding back onto the previous segment.
    let pts = vec![[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0, 0.0, 0.0]];
    let (e, _) = err(&DevelopableSpec::projection(pts, 30.0, vec![-1.0, -2.0]));
    assert!(
        matches!(e, DevelopableError::SelfCrossing { a: 0, b: 1, .. }),
        "{e:?}"
    );
    // More than one turn of a circular helix: its projection overlaps itself.
    let pts = curve(20, 0.0, 1.5 * TAU, |t| [t.cos(), t.sin(), 0.0]);
    let (e, _) = err(&DevelopableSpec::projection(pts, 30.0, vec![-1.0, -2.0]));
    assert!(matches!(e, DevelopableError::SelfCrossing { .. }), "{e:?}");
}

#[test]
fn error_heights_not_monotonic() {
    let (e, msg) = err(&DevelopableSpec::projection(
        square(),
        30.0,
        vec![-1.0, -2.0, -1.5],
    ));
    assert_eq!(
        e,
        DevelopableError::HeightsNotMonotonic {
            index: 2,
            previous: -2.0,
            height: -1.5
        }
    );
    assert!(
        msg.contains("heights[2] = -1.5") && msg.contains("heights[1] = -2"),
        "{msg}"
    );
    let (e, _) = err(&DevelopableSpec::projection(
        square(),
        30.0,
        vec![-1.0, -1.0],
    ));
    assert!(matches!(
        e,
        DevelopableError::HeightsNotMonotonic { index: 1, .. }
    ));
}

#[test]
fn error_height_at_a_helix_vertex() {
    // α = 45° over the unit square: helix vertices at heights 0, 1, 2, 3.
    let (e, msg) = err(&DevelopableSpec::projection(
        square(),
        45.0,
        vec![2.0 + 1e-12, 2.5],
    ));
    let DevelopableError::HeightAtHelixVertex {
        height_index,
        vertex,
        vertex_height,
        ..
    } = e
    else {
        panic!("{e:?}")
    };
    assert_eq!((height_index, vertex), (0, 2));
    assert!((vertex_height - 2.0).abs() < 1e-14);
    assert!(
        msg.contains("helix vertex 2") && msg.contains("rulings 1 and 2 meet"),
        "{msg}"
    );
}

#[test]
fn error_face_crosses_the_helix() {
    let (e, msg) = err(&DevelopableSpec::projection(square(), 45.0, vec![0.5, 1.5]));
    let DevelopableError::FaceCrossesHelix {
        vertex,
        j,
        below,
        above,
        ..
    } = e
    else {
        panic!("{e:?}")
    };
    assert_eq!((vertex, j, below, above), (1, 0, 0.5, 1.5));
    assert!(
        msg.contains("helix vertex 1") && msg.contains("rulings 0 and 1"),
        "{msg}"
    );
}

#[test]
fn error_scale_and_extreme_scales() {
    let scaled = |k: f64| {
        let pts = square().iter().map(|p| p.map(|x| x * k)).collect();
        DevelopableSpec::projection(pts, 30.0, vec![-k, -2.0 * k])
    };
    for k in [1e-90, 1e-40, 1e-5, 1e5, 1e40, 1e90] {
        generate_checked(&scaled(k), 30.0);
    }
    for k in [1e-120, 1e120, 1e300] {
        let (e, msg) = err(&scaled(k));
        assert_eq!(e, DevelopableError::Scale { extent: 2.0 * k });
        assert!(msg.contains("rescale"), "{msg}");
    }
}

#[test]
fn garbage_never_panics() {
    // Random, often invalid specs: refused with an error or measured exact.
    let num = prop_oneof![
        -3.0f64..3.0,
        Just(0.0),
        Just(1.0),
        Just(90.0),
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(1e200),
        Just(1e-200),
    ];
    let xyz = [num.clone(), num.clone(), num.clone()];
    let strategy = (
        prop::collection::vec(xyz.clone(), 0..7),
        num.clone(),
        prop::collection::vec(num.clone(), 0..5),
        xyz,
        any::<bool>(),
    );
    let mut runner = TestRunner::new(Config {
        rng_seed: RngSeed::Fixed(0x646576),
        failure_persistence: None,
        cases: 2000,
        ..Config::default()
    });
    runner
        .run(&strategy, |(points, alpha, heights, normal, direct)| {
            let mut spec = if direct {
                DevelopableSpec::helix(points, heights)
            } else {
                DevelopableSpec::projection(points, alpha, heights)
            };
            spec.reference_normal = normal;
            if let Ok(mesh) = developable(&spec, &GenerateOptions::default()) {
                let w = check(
                    &mesh,
                    &spec.heights,
                    DVec3::from_array(normal),
                    mesh.alpha_deg,
                );
                prop_assert!(w.max() <= TOL, "{:?} {:?}", spec, w);
            }
            Ok(())
        })
        .unwrap();
}
