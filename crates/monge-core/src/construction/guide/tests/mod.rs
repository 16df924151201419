//! Tests of the guides: one per error variant, and the samples' geometry.

mod errors;
mod sampling;

use std::f64::consts::{FRAC_1_SQRT_2, PI};

use super::*;
use crate::bspline::tests::cox_de_boor;
use crate::design::{ArcSpec, BSplineSpec, ParabolaSpec};

const U: GuideName = GuideName::U;

fn tol() -> Tolerances {
    Tolerances::default()
}

fn guide(spec: &GuideSpec) -> Result<Guide, GuideError> {
    Guide::from_spec(spec, U, &tol())
}

fn err(spec: &GuideSpec) -> GuideError {
    let e = guide(spec).expect_err("the spec should be refused");
    // Every message names the guide.
    assert!(e.to_string().contains("guide_u"), "{e}");
    e
}

/// A curved, exactly planar (y = 0) polyline.
fn bent() -> Vec<Xyz> {
    vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.2],
        [2.0, 0.0, 0.7],
        [3.0, 0.0, 1.5],
    ]
}

fn bspline(control_points: Vec<Xyz>, degree: usize, samples: usize) -> BSplineSpec {
    BSplineSpec {
        degree,
        control_points,
        knots: None,
        weights: None,
        samples,
    }
}

fn bspline_spec(b: BSplineSpec) -> GuideSpec {
    GuideSpec::BSpline {
        bspline: b,
        parameters: None,
    }
}

fn cubic() -> BSplineSpec {
    bspline(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.5],
            [2.0, 0.0, 1.5],
            [3.0, 0.0, 1.0],
            [4.0, 0.0, 2.0],
        ],
        3,
        17,
    )
}

fn arc(angle_deg: f64, samples: usize) -> ArcSpec {
    ArcSpec {
        center: [1.0, 2.0, 3.0],
        start: [1.0, 2.0, 5.0],
        normal: [0.0, 3.0, 0.0],
        angle_deg,
        samples,
    }
}

fn arc_spec(a: ArcSpec) -> GuideSpec {
    GuideSpec::Arc(a)
}

fn parabola(tangent: Xyz, quadratic: Xyz, samples: usize) -> GuideSpec {
    GuideSpec::Parabola(ParabolaSpec {
        start: [0.5, -1.0, 2.0],
        tangent,
        quadratic,
        samples,
    })
}

fn unit_of(x: Xyz) -> DVec3 {
    DVec3::from_array(x).normalize()
}

#[test]
fn guide_names_display() {
    assert_eq!(GuideName::U.to_string(), "guide_u");
    assert_eq!(GuideName::V.to_string(), "guide_v");
    let e = Guide::from_spec(&GuideSpec::points(vec![]), GuideName::V, &tol()).unwrap_err();
    assert!(e.to_string().starts_with("guide_v"));
}
