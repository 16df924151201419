//! Fitting θ with BOBYQA (§4.7, HippoHaus): exact recovery of known values, one test per error.

use glam::DVec3;
use monge_core::measure::measure;
use monge_core::multipatch::{build, Attach, MultiPatchDesign, MultiPatchError, PatchSpec, Side};
use monge_core::optimise::{fit, BoundaryRef, FitError, FitSpec, FreeParameter, GuideKey, Target};
use monge_core::GuideSpec;

use crate::common;
use common::{arc_u, opts};

/// HippoHaus-like: a first dome patch (θ1 fixed), a transition patch (θ2) and a
/// second dome patch (θ3), along one bottom guide (a circle); G3 is the last row.
fn hippo(thetas: [f64; 3]) -> MultiPatchDesign {
    let later = |theta, patch, guide| PatchSpec {
        theta_deg: theta,
        guide_u: None,
        guide_v: None,
        attach: Some(Attach {
            patch,
            side: Side::LastRow,
        }),
        guide: Some(guide),
        guide_from: None,
    };
    MultiPatchDesign {
        patches: vec![
            PatchSpec {
                theta_deg: thetas[0],
                guide_u: Some(arc_u(0.0, 20.0, 9)),
                guide_v: Some(GuideSpec::arc(
                    [0.0, 0.0, -3.0],
                    [0.0; 3],
                    [-1.0, 0.0, 0.0],
                    35.0,
                    9,
                )),
                attach: None,
                guide: None,
                guide_from: None,
            },
            later(thetas[1], 0, arc_u(20.0, 10.0, 5)),
            later(thetas[2], 1, arc_u(30.0, 20.0, 9)),
        ],
        tolerance: None,
        fit: None,
        symmetry: vec![],
    }
}

fn theta(patch: usize) -> FreeParameter {
    FreeParameter::Theta {
        patch,
        bounds: None,
    }
}

fn with_fit(mut d: MultiPatchDesign, free: Vec<FreeParameter>, target: Target) -> MultiPatchDesign {
    d.fit = Some(FitSpec {
        free,
        boundary: BoundaryRef {
            patch: 2,
            side: Side::LastRow,
        },
        target,
        max_distance: None,
        max_evaluations: None,
    });
    d
}

/// G3: the last row of the design with the true values.
fn g3(truth: &MultiPatchDesign) -> Vec<[f64; 3]> {
    let mp = build(truth, &opts()).unwrap();
    mp.boundary(2, Side::LastRow)
        .iter()
        .map(|p| p.to_array())
        .collect()
}

#[test]
fn recovers_two_thetas_exactly() {
    let truth = [30.0, -25.0, 40.0];
    let target = g3(&hippo(truth));
    let d = with_fit(
        hippo([30.0, -40.0, 25.0]),
        vec![theta(1), theta(2)],
        Target::Polyline(target),
    );
    let r = fit(&d, &opts()).unwrap();
    println!(
        "before {:?}\nafter {:?}\nvalues {:?}\nevaluations {} ({})",
        r.before, r.after, r.values, r.evaluations, r.status
    );
    assert!(r.before.relative > 1e-3);
    assert!(r.after.relative <= 1e-6, "{:?}", r.after);
    assert!((r.design.patches[1].theta_deg - truth[1]).abs() < 1e-4);
    assert!((r.design.patches[2].theta_deg - truth[2]).abs() < 1e-4);
    assert!(r.evaluations < 2200);
    // The fitted mesh is as exact as any other.
    for k in 0..3 {
        assert!(measure(&r.mesh.patch_grid(k)).max_error() <= 1e-9);
    }
}

#[test]
fn ends_a_patch_in_a_plane() {
    // Figure 20: the second patch must end in the plane of symmetry; one θ, a plane target.
    let truth = hippo([30.0, -25.0, 40.0]);
    let mp = build(&truth, &opts()).unwrap();
    let row = mp.boundary(2, Side::LastRow);
    let normal = (row[1] - row[0])
        .cross(row[row.len() - 1] - row[0])
        .normalize();
    let d = with_fit(
        hippo([30.0, -25.0, 25.0]),
        vec![theta(2)],
        Target::Plane {
            point: row[0].to_array(),
            normal: normal.to_array(),
        },
    );
    let r = fit(&d, &opts()).unwrap();
    assert!(r.after.relative <= 1e-6, "{:?}", r.after);
    assert!(
        (r.design.patches[2].theta_deg - 40.0).abs() < 1e-4,
        "{:?}",
        r.values
    );
}

#[test]
fn fits_a_guide_coordinate() {
    // A points continuation whose fourth point's z is free (it stays in the plane y = 0).
    let corner = build(&hippo([30.0, -25.0, 40.0]), &opts())
        .unwrap()
        .boundary(0, Side::LastRow)[0];
    let points = |dz: f64| -> GuideSpec {
        let pts = (0..5)
            .map(|k| {
                let s = k as f64 * 0.3;
                let bump = if k == 3 { dz } else { 0.0 };
                (corner + DVec3::new(s, 0.0, -0.25 * s * s - 0.3 * s + bump)).to_array()
            })
            .collect();
        GuideSpec::points(pts)
    };
    // Two patches: the boundary is the last row of patch 1, whose guide is the points.
    let mut truth = hippo([30.0, -25.0, 40.0]);
    truth.patches.truncate(2);
    truth.patches[1].guide = Some(points(0.0));
    let z_true = truth.patches[1].guide.as_ref().map(points_of).unwrap()[3][2];
    let target = build(&truth, &opts())
        .unwrap()
        .boundary(1, Side::LastRow)
        .iter()
        .map(|p| p.to_array())
        .collect();
    let mut start = truth.clone();
    start.patches[1].guide = Some(points(0.05));
    let mut d = with_fit(
        start,
        vec![FreeParameter::ControlPoint {
            patch: 1,
            guide: GuideKey::Guide,
            index: 3,
            coordinate: 2,
            bounds: [z_true - 0.2, z_true + 0.2],
        }],
        Target::Polyline(target),
    );
    d.fit.as_mut().unwrap().boundary.patch = 1;
    let r = fit(&d, &opts()).unwrap();
    assert!(r.after.relative <= 1e-6, "{:?}", r.after);
    let z = r.design.patches[1].guide.as_ref().map(points_of).unwrap()[3][2];
    assert!((z - z_true).abs() < 1e-5, "{z} vs {z_true}");
}

fn fit_err(d: &MultiPatchDesign) -> FitError {
    fit(d, &opts()).unwrap_err()
}

fn simple(free: Vec<FreeParameter>) -> MultiPatchDesign {
    with_fit(
        hippo([30.0, -40.0, 25.0]),
        free,
        Target::Polyline(vec![[0.0; 3], [1.0, 0.0, 0.0]]),
    )
}

#[test]
fn error_no_fit() {
    assert_eq!(fit_err(&hippo([30.0, -40.0, 25.0])), FitError::NoFit);
}

#[test]
fn error_no_free_parameters() {
    assert_eq!(fit_err(&simple(vec![])), FitError::NoFreeParameters);
}

#[test]
fn error_bad_parameter() {
    let e = fit_err(&simple(vec![theta(7)]));
    assert!(matches!(e, FitError::BadParameter { index: 0, .. }), "{e}");
    assert!(e.to_string().contains("there is no patch 7"), "{e}");
    let e = fit_err(&simple(vec![FreeParameter::ControlPoint {
        patch: 0,
        guide: GuideKey::GuideU,
        index: 0,
        coordinate: 2,
        bounds: [0.0, 1.0],
    }]));
    assert!(e.to_string().contains("only `points` and `bspline`"), "{e}");
}

#[test]
fn error_empty_bounds() {
    // Patch 1 is in the arbitrary case (its frame is tilted): |θ| has a lower bound > 0.
    let e = fit_err(&simple(vec![FreeParameter::Theta {
        patch: 0,
        bounds: Some([95.0, 96.0]),
    }]));
    // Patch 0 is characteristic and starts at 30°: the +90° window cuts [−180, 180] at 89°.
    assert!(matches!(e, FitError::EmptyBounds { index: 0, .. }), "{e}");
    assert!(e.to_string().contains("empty bounds"), "{e}");
}

#[test]
fn error_bad_target() {
    let mut d = simple(vec![theta(1)]);
    d.fit.as_mut().unwrap().target = Target::Polyline(vec![[0.0; 3]]);
    let e = fit_err(&d);
    assert!(matches!(e, FitError::BadTarget { .. }), "{e}");
    d.fit.as_mut().unwrap().target = Target::Plane {
        point: [0.0; 3],
        normal: [0.0; 3],
    };
    assert!(fit_err(&d).to_string().contains("non-zero finite normal"));
}

#[test]
fn error_bad_boundary() {
    let mut d = simple(vec![theta(1)]);
    d.fit.as_mut().unwrap().boundary.patch = 3;
    assert_eq!(fit_err(&d), FitError::BadBoundary { patch: 3, count: 3 });
}

#[test]
fn error_start() {
    let mut d = simple(vec![theta(1)]);
    d.patches[1].theta_deg = 90.0;
    assert!(matches!(
        fit_err(&d),
        FitError::Start(MultiPatchError::Generate { patch: 1, .. })
    ));
}

#[test]
fn error_unreachable() {
    // A target far away from anything the boundary can reach.
    let mut d = simple(vec![theta(1), theta(2)]);
    let f = d.fit.as_mut().unwrap();
    f.target = Target::Polyline(vec![[50.0, 50.0, 50.0], [51.0, 50.0, 50.0]]);
    f.max_distance = Some(1e-3);
    f.max_evaluations = Some(60);
    let e = fit_err(&d);
    assert!(matches!(e, FitError::Unreachable { .. }), "{e}");
    assert!(e.to_string().starts_with("unreachable target"), "{e}");
}

#[test]
fn error_too_few_evaluations() {
    let mut d = simple(vec![theta(1)]);
    d.fit.as_mut().unwrap().max_evaluations = Some(2);
    let e = fit_err(&d);
    assert_eq!(
        e,
        FitError::TooFewEvaluations {
            given: 2,
            needed: 4
        }
    );
}

/// Issue 10, item 2: a folded mesh is infeasible. The guides of Figure 14 fold
/// for θ between about 78° and 110°; the target is the last row of their mesh
/// at θ = 84° (folded), so the unconstrained fit would go there (distance 0).
#[test]
fn fit_never_returns_a_folded_mesh() {
    let patch = |theta_deg| PatchSpec {
        theta_deg,
        guide_u: Some(GuideSpec::bspline(
            2,
            vec![[0.0; 3], [5.0, 0.0, 0.0], [10.0, 0.0, 4.0]],
            21,
        )),
        guide_v: Some(GuideSpec::bspline(
            2,
            vec![[0.0; 3], [0.0, 4.0, 0.0], [0.0, 8.0, 3.0]],
            21,
        )),
        attach: None,
        guide: None,
        guide_from: None,
    };
    let design = |theta_deg| MultiPatchDesign {
        patches: vec![patch(theta_deg)],
        tolerance: None,
        fit: None,
        symmetry: vec![],
    };
    let folded = build(&design(84.0), &opts()).unwrap();
    assert!(folded.patches[0].folded_faces > 0);
    let target: Vec<[f64; 3]> = folded
        .boundary(0, Side::LastRow)
        .iter()
        .map(|p| p.to_array())
        .collect();
    let mut d = design(60.0);
    d.fit = Some(FitSpec {
        free: vec![FreeParameter::Theta {
            patch: 0,
            bounds: Some([50.0, 88.0]),
        }],
        boundary: BoundaryRef {
            patch: 0,
            side: Side::LastRow,
        },
        target: Target::Polyline(target),
        max_distance: None,
        max_evaluations: None,
    });
    let r = fit(&d, &opts()).unwrap();
    let theta = r.values[0].2;
    println!("fitted θ = {theta}, distance {:?}", r.after);
    assert_eq!(r.mesh.patches[0].folded_faces, 0, "θ = {theta}");
    assert_eq!(measure(&r.mesh.grid).folded_faces, 0, "θ = {theta}");
    assert!(r.after.max > 1e-3, "{:?}", r.after);
}

/// The points of a `points` guide.
fn points_of(g: &GuideSpec) -> &[[f64; 3]] {
    match g {
        GuideSpec::Points { points, .. } => points,
        other => panic!("a points guide, not {other:?}"),
    }
}
