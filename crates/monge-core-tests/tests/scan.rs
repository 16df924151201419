//! Design-space scans (§4.3, Figure 14; §5.2).

use monge_core::scan::{parse_range, scan, set_parameter, values, ScanError, Status, MAX_VALUES};
use monge_core::{generate, Design, GuideSpec};

use crate::common;
use common::design;

/// The two guides of Figure 14 (`examples/fig14-family.toml`, fewer samples):
/// their θ family folds over itself between about 80° and 110°.
fn figure14() -> Design {
    design(
        20.0,
        GuideSpec::bspline(2, vec![[0.0; 3], [5.0, 0.0, 0.0], [10.0, 0.0, 4.0]], 21),
        GuideSpec::bspline(2, vec![[0.0; 3], [0.0, 4.0, 0.0], [0.0, 8.0, 3.0]], 21),
    )
}

#[test]
fn the_theta_family_of_figure_14_folds_on_one_interval() {
    let v = parse_range("-180:180:2").unwrap();
    assert_eq!(v.len(), 181);
    let s = scan(&figure14(), "theta", &v, &Default::default(), &|| {}).unwrap();
    assert_eq!(s.parameter, "theta_deg");
    // Folded values, with the singular θ = 90° (inadmissible) inside.
    let bad: Vec<f64> = s
        .rows
        .iter()
        .filter(|r| r.folded_faces > 0 || r.status == Status::Inadmissible)
        .map(|r| r.value)
        .collect();
    let (a, b) = (bad[0], *bad.last().unwrap());
    // One interval: every value between a and b is folded (or the singular 90°).
    let inside = s.rows.iter().filter(|r| (a..=b).contains(&r.value)).count();
    assert_eq!(
        inside,
        bad.len(),
        "folded values {bad:?} are not one interval"
    );
    assert!(
        (76.0..=82.0).contains(&a) && (108.0..=114.0).contains(&b),
        "[{a}, {b}]"
    );
    assert_eq!(
        s.rows
            .iter()
            .filter(|r| r.status == Status::Inadmissible)
            .map(|r| r.value)
            .collect::<Vec<_>>(),
        vec![90.0]
    );
    // Outside it the meshes are fair and exact; inside they are still exact (folded, not broken).
    for r in &s.rows {
        if r.status != Status::Inadmissible {
            assert!(
                r.max_error <= 1e-9,
                "θ = {}: error {}",
                r.value,
                r.max_error
            );
            let p = r.panels.unwrap();
            assert!(p.area_min > 0.0 && p.area_max >= p.area_min && p.max_edge > 0.0);
        }
        assert_eq!(r.folded_faces > 0, r.status == Status::Folded);
    }
    // The folded runs lie on either side of the singular value.
    assert_eq!(s.intervals(Status::Folded), vec![(a, 88.0), (92.0, b)]);
}

#[test]
fn results_do_not_depend_on_the_number_of_threads() {
    let v = parse_range("60:120:3").unwrap();
    let run = |threads| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let count = std::sync::atomic::AtomicUsize::new(0);
        let s = pool.install(|| {
            scan(&figure14(), "theta", &v, &Default::default(), &|| {
                count.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            })
            .unwrap()
        });
        assert_eq!(
            count.into_inner(),
            v.len(),
            "progress is called once per value"
        );
        // Debug prints every f64 exactly (and NaN as NaN, equal to itself).
        format!("{s:?}")
    };
    assert_eq!(run(1), run(4));
}

#[test]
fn any_numeric_parameter_can_be_scanned() {
    // Raise the end of guide_v: the panels grow with it.
    let s = scan(
        &figure14(),
        "guide_v.bspline.control_points[2][2]",
        &values(1.0, 5.0, 1.0).unwrap(),
        &Default::default(),
        &|| {},
    )
    .unwrap();
    assert!(s.rows.iter().all(|r| r.status == Status::Fair));
    let areas: Vec<f64> = s.rows.iter().map(|r| r.panels.unwrap().area_mean).collect();
    assert!(areas.windows(2).all(|w| w[1] > w[0]), "{areas:?}");
    // Turning guide_v's start tangent makes the design invalid there, with the reason.
    let s = scan(
        &figure14(),
        "guide_v.bspline.control_points[1][0]",
        &[0.0, 1.0],
        &Default::default(),
        &|| {},
    )
    .unwrap();
    assert_eq!(s.rows[0].status, Status::Fair);
    assert_eq!(s.rows[1].status, Status::Invalid);
    assert!(
        s.rows[1].error.as_deref().unwrap().contains("90°"),
        "{:?}",
        s.rows[1].error
    );
}

#[test]
fn bad_ranges_and_paths_are_typed_errors() {
    assert!(matches!(
        parse_range("0:10"),
        Err(ScanError::BadRange { .. })
    ));
    assert!(matches!(
        parse_range("0:x:1"),
        Err(ScanError::BadRange { .. })
    ));
    assert!(matches!(
        parse_range("0:inf:1"),
        Err(ScanError::BadRange { .. })
    ));
    assert!(matches!(
        parse_range("0:10:-1"),
        Err(ScanError::BadStep { .. })
    ));
    assert!(matches!(
        parse_range("0:10:0"),
        Err(ScanError::BadStep { .. })
    ));
    assert_eq!(
        parse_range("0:360:1e-6"),
        Err(ScanError::TooManyValues {
            count: 360_000_001,
            limit: MAX_VALUES
        })
    );
    let d = figure14();
    for path in [
        "guide_w.points[0][0]",
        "guide_u.bspline.degree[0]",
        "guide_u.bspline",
        "guide_u.bspline.control_points[9][0]",
    ] {
        let e = set_parameter(&d, path, 1.0).unwrap_err();
        assert!(matches!(e, ScanError::BadPath { .. }), "{path}: {e}");
        assert!(scan(&d, path, &[1.0], &Default::default(), &|| {}).is_err());
    }
    // A non-finite value cannot be written.
    assert!(matches!(
        set_parameter(&d, "guide_u.bspline.control_points[1][0]", f64::NAN),
        Err(ScanError::BadPath { .. })
    ));
}

/// Area of a planar polygon without crossings, independently of the code under
/// test: half the length of its vector area `½ Σ p_k × p_{k+1}` (the shoelace
/// formula in 3D), coordinates relative to the first corner, written out by hand.
fn shoelace_area(q: &[glam::DVec3; 4]) -> f64 {
    let p: Vec<[f64; 3]> = q.iter().map(|v| (*v - q[0]).to_array()).collect();
    let mut s = [0.0; 3];
    for k in 0..4 {
        let (a, b) = (p[k], p[(k + 1) % 4]);
        s[0] += a[1] * b[2] - a[2] * b[1];
        s[1] += a[2] * b[0] - a[0] * b[2];
        s[2] += a[0] * b[1] - a[1] * b[0];
    }
    0.5 * (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt()
}

/// Issue 10, item 1: the scan's panel areas are the areas of the quads (they were
/// half the cross product of two opposite edges: at θ = 20° a spread of 137
/// instead of 1.58, at θ = ±180° an infinite one).
#[test]
fn scan_panel_areas_are_the_quads_areas() {
    let mut d = figure14();
    for g in [&mut d.guide_u, &mut d.guide_v] {
        let GuideSpec::BSpline { bspline, .. } = g else {
            panic!("a B-spline guide");
        };
        bspline.samples = 41;
    }
    let s = scan(
        &d,
        "theta",
        &[-180.0, 20.0, 180.0],
        &Default::default(),
        &|| {},
    )
    .unwrap();
    for r in &s.rows {
        let g = generate(
            &Design {
                theta_deg: r.value,
                ..d.clone()
            },
            &Default::default(),
        )
        .unwrap()
        .grid;
        let truth: Vec<f64> = (0..g.rows - 1)
            .flat_map(|i| (0..g.cols - 1).map(move |j| (i, j)))
            .map(|(i, j)| shoelace_area(&g.face(i, j)))
            .collect();
        for (a, t) in g.face_areas().iter().zip(&truth) {
            assert!((a - t).abs() <= 1e-12 * t, "θ = {}: {a} vs {t}", r.value);
        }
        let n = truth.len() as f64;
        let mean = truth.iter().sum::<f64>() / n;
        let variance = truth.iter().map(|t| (t - mean).powi(2)).sum::<f64>() / n;
        let min = truth.iter().copied().fold(f64::INFINITY, f64::min);
        let max = truth.iter().copied().fold(0.0, f64::max);
        let p = r.panels.unwrap();
        println!("θ = {}: areas {min} … {max}, spread {}", r.value, max / min);
        let close = |x: f64, y: f64| (x - y).abs() <= 1e-12 * y.abs();
        assert!(close(p.area_min, min) && close(p.area_max, max), "{p:?}");
        assert!(close(p.area_mean, mean) && close(p.area_variance, variance));
        assert!(p.spread().is_finite() && p.spread() < 10.0, "{p:?}");
    }
}
