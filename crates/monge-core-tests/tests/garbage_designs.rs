//! Garbage in, `Ok` or `Err` out, never a panic: `generate` and `inspect` on
//! random designs, garbage and nearly valid (§3, §5.2).

use std::panic::{catch_unwind, AssertUnwindSafe};

use monge_core::design::{ArcSpec, BSplineSpec, ParabolaSpec};
use monge_core::measure::measure;
use monge_core::{generate, inspect, Design, GenerateError, GuideSpec, Tolerances};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};

use crate::common;
use common::opts;

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
