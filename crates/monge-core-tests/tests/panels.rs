//! Panel-size optimisation (§4.8, Figure 22) and the `parameters` of B-spline guides.

use glam::DVec3;
use monge_core::design::{BSplineSpec, GuideSpec};
use monge_core::grid::quad_area;
use monge_core::guide::GuideError;
use monge_core::measure::measure;
use monge_core::panels::{optimise_panels, PanelError, PanelOptions, MAX_FREE_SAMPLES};
use monge_core::scan::panel_stats;
use monge_core::{generate, Design, GenerateError, QuadGrid};

use crate::common;
use common::figure22;

#[test]
fn optimised_sampling_evens_out_the_panels_and_stays_exact() {
    let d = figure22(9);
    let r = optimise_panels(&d, &Default::default(), &PanelOptions::default()).unwrap();
    println!(
        "variance {:e} -> {:e}, spread {} -> {}, evals {}",
        r.before.area_variance,
        r.after.area_variance,
        r.before.spread(),
        r.after.spread(),
        r.evaluations
    );
    assert!(r.after.area_variance < 0.5 * r.before.area_variance);
    assert!(r.after.spread() < r.before.spread());
    assert!(r.max_error <= 1e-9, "{}", r.max_error);
    assert_eq!(r.folded_faces, 0);
    // The optimised design carries the parameters; generating it gives the same panels.
    for g in [&r.design.guide_u, &r.design.guide_v] {
        let GuideSpec::BSpline {
            parameters: Some(t),
            ..
        } = g
        else {
            panic!("a B-spline guide with parameters");
        };
        assert_eq!(t.len(), 9);
        assert_eq!((t[0], t[8]), (0.0, 1.0));
        assert!(t.windows(2).all(|w| w[1] > w[0]));
    }
    let g = generate(&r.design, &Default::default()).unwrap();
    assert!(measure(&g.grid).max_error() <= 1e-9);
    assert_eq!(panel_stats(&g.grid), r.after);
    // Samples lie on the same curve: the end points do not move.
    let g0 = generate(&d, &Default::default()).unwrap();
    assert_eq!(g.grid.vertex(8, 0), g0.grid.vertex(8, 0));
}

#[test]
fn panel_errors() {
    let mut d = figure22(9);
    d.guide_u = GuideSpec::Points {
        points: vec![[0.0; 3], [1.0, 0.0, 0.1], [2.0, 0.0, 0.5]],
        tangent: Some([1.0, 0.0, 0.0]),
    };
    d.guide_v = GuideSpec::points(vec![[0.0; 3], [0.0, 1.0, 0.1], [0.0, 2.0, 0.5]]);
    let o = PanelOptions::default();
    assert_eq!(
        optimise_panels(&d, &Default::default(), &o).unwrap_err(),
        PanelError::NoBSplineGuide
    );
    let mut d = figure22(9);
    bspline_of(&mut d.guide_u).samples = 2;
    bspline_of(&mut d.guide_v).samples = 2;
    assert_eq!(
        optimise_panels(&d, &Default::default(), &o).unwrap_err(),
        PanelError::NothingToChoose
    );
    // 10 000 samples once took 3 GB of BOBYQA model before failing to allocate more.
    let mut d = figure22(9);
    bspline_of(&mut d.guide_u).samples = 10_000;
    assert_eq!(
        optimise_panels(&d, &Default::default(), &o).unwrap_err(),
        PanelError::TooManySamples {
            free: 9_998 + bspline_of(&mut d.guide_v.clone()).samples - 2,
            max: MAX_FREE_SAMPLES
        }
    );
    let mut d = figure22(9);
    d.theta_deg = 90.0;
    assert!(matches!(
        optimise_panels(&d, &Default::default(), &o).unwrap_err(),
        PanelError::Start(GenerateError::ThetaSingular { .. })
    ));
    let d = figure22(9);
    let few = PanelOptions {
        max_evaluations: Some(5),
        ..o
    };
    assert_eq!(
        optimise_panels(&d, &Default::default(), &few).unwrap_err(),
        PanelError::TooFewEvaluations {
            given: 5,
            needed: 30
        }
    );
    let bad = PanelOptions {
        max_gap_ratio: 1.0,
        ..o
    };
    assert_eq!(
        optimise_panels(&d, &Default::default(), &bad).unwrap_err(),
        PanelError::BadGapRatio(1.0)
    );
}

#[test]
fn guide_parameters_are_validated() {
    let check = |guide_u: GuideSpec| match generate(
        &Design {
            guide_u,
            ..figure22(9)
        },
        &Default::default(),
    ) {
        Err(GenerateError::Guide(e)) => e,
        other => panic!("{:?}", other.map(|g| g.grid.rows)),
    };
    let with = |t: Vec<f64>| GuideSpec::BSpline {
        bspline: bspline_of(&mut figure22(9).guide_u).clone(),
        parameters: Some(t),
    };
    let nine = |k: usize, v: f64| {
        let mut t: Vec<f64> = (0..9).map(|i| i as f64 / 8.0).collect();
        t[k] = v;
        t
    };
    assert!(matches!(
        check(with(vec![0.0, 1.0])),
        GuideError::ParameterCount {
            count: 2,
            samples: 9,
            ..
        }
    ));
    assert!(matches!(
        check(with(nine(3, 0.1))),
        GuideError::ParametersNotIncreasing { index: 3, .. }
    ));
    assert!(matches!(
        check(with(nine(8, 1.5))),
        GuideError::ParameterOutOfRange { index: 8, .. }
    ));
    assert!(matches!(
        check(with(nine(4, f64::NAN))),
        GuideError::NonFinite {
            field: "parameters",
            index: Some(4),
            ..
        }
    ));
    // Uniform parameters given explicitly sample exactly like no parameters.
    let uniform = generate(
        &Design {
            guide_u: with((0..9).map(|i| i as f64 / 8.0).collect()),
            ..figure22(9)
        },
        &Default::default(),
    )
    .unwrap();
    let plain = generate(&figure22(9), &Default::default()).unwrap();
    assert_eq!(uniform.grid.vertices, plain.grid.vertices);
}

/// A square of side `s` has area `s²` at every scale a design may have
/// (sizes 1e-100 to 1e100): the squares of its vector area's components
/// overflowed beyond sides of 1e77 (area inf, `scan`'s area spread NaN) and
/// underflowed below 1e-77 (area 0).
#[test]
fn panel_areas_hold_at_the_extremes_of_the_design_scale() {
    for s in [1e-99, 1e-90, 1e-78, 1.0, 1e78, 1e90, 1e99] {
        let sq = [
            DVec3::ZERO,
            DVec3::new(s, 0.0, 0.0),
            DVec3::new(s, s, 0.0),
            DVec3::new(0.0, s, 0.0),
        ];
        let expected = s * s;
        let area = quad_area(&sq);
        assert!(
            (area - expected).abs() <= 4.0 * f64::EPSILON * expected,
            "side {s:e}: area {area:e}, expected {expected:e}"
        );
        let grid = QuadGrid::new(2, 2, vec![sq[0], sq[3], sq[1], sq[2]], vec![DVec3::Z; 4]);
        let stats = panel_stats(&grid);
        assert!(
            stats.area_max.is_finite() && stats.area_min > 0.0,
            "side {s:e}: {stats:?}"
        );
        assert_eq!(stats.spread(), 1.0, "side {s:e}");
    }
}

/// A design of size about 1e99 (the largest accepted is 1e100) is optimised as
/// at size 1: its areas' squares overflowed, the objective was NaN everywhere
/// and the design came back unchanged with exit 0.
#[test]
fn a_huge_design_is_optimised_as_at_unit_scale() {
    let unit = figure22(9);
    let mut huge = figure22(9);
    for g in [&mut huge.guide_u, &mut huge.guide_v] {
        for p in bspline_of(g).control_points.iter_mut() {
            *p = p.map(|c| c * 1e99);
        }
    }
    let options = PanelOptions::default();
    let r1 = optimise_panels(&unit, &Default::default(), &options).unwrap();
    let r99 = optimise_panels(&huge, &Default::default(), &options).unwrap();
    assert!(
        r99.after.spread() < 0.5 * r99.before.spread(),
        "{:?}",
        r99.after
    );
    assert!((r99.after.spread() - r1.after.spread()).abs() < 1e-6 * r1.after.spread());
}

/// The curve of a B-spline guide.
fn bspline_of(g: &mut GuideSpec) -> &mut BSplineSpec {
    match g {
        GuideSpec::BSpline { bspline, .. } => bspline,
        other => panic!("a B-spline guide, not {other:?}"),
    }
}
