//! Sampling and geometry of each kind of guide.

use super::*;

#[test]
fn polyline_is_used_as_given() {
    let g = guide(&GuideSpec::points(bent())).unwrap();
    let expected: Vec<DVec3> = bent().iter().map(|p| DVec3::from_array(*p)).collect();
    assert_eq!(g.points, expected);
    assert_eq!(g.plane_normal, DVec3::Y);
    assert_eq!(g.planarity, 0.0);
    assert_eq!(g.size, 3.0f64.hypot(1.5));
}

#[test]
fn exactly_planar_input_is_bit_identical() {
    // y = 0 and y = 3.7, with awkward coordinates.
    for y in [0.0, 3.7] {
        let points: Vec<Xyz> = (0..25)
            .map(|k| {
                let t = k as f64 * 0.137;
                [t.sin() * 3.3 + 0.1, y, (t * 1.7).cos() * t + 1e-3]
            })
            .collect();
        let g = guide(&GuideSpec::points(points.clone())).unwrap();
        let expected: Vec<DVec3> = points.iter().map(|p| DVec3::from_array(*p)).collect();
        assert_eq!(g.points, expected);
        assert_eq!(g.plane_normal, DVec3::Y);
        assert_eq!(g.planarity, 0.0);
        assert_eq!(g.tangent.y, 0.0);
    }
}

#[test]
fn plane_normal_sign_convention() {
    // Largest-magnitude component positive, whatever the orientation of the curve.
    let spec = GuideSpec::points(vec![[0.0, 0.0, -1.0], [1.0, 1.0, -1.0], [3.0, 1.5, -1.0]]);
    let g = guide(&spec).unwrap();
    assert_eq!(g.plane_normal, DVec3::Z);
    let reversed = GuideSpec::points(vec![[3.0, 1.5, -1.0], [1.0, 1.0, -1.0], [0.0, 0.0, -1.0]]);
    assert_eq!(guide(&reversed).unwrap().plane_normal, DVec3::Z);
    // Oblique: normal (-1, 2, 2) / 3 is reported as (-1, 2, 2) / 3 (first of the largest).
    let n = DVec3::new(-1.0, 2.0, 2.0) / 3.0;
    let (e1, e2) = n.any_orthonormal_pair();
    let spec = GuideSpec::points(
        (0..7)
            .map(|k| {
                let t = k as f64 * 0.3;
                (5.0 * n + t * e1 + t * t * e2).to_array()
            })
            .collect(),
    );
    let g = guide(&spec).unwrap();
    assert!(
        (g.plane_normal - n).length() < 1e-15,
        "{:?}",
        g.plane_normal
    );
}

/// Points on a circle of radius `r` about `c` in the plane of `e1`, `e2`, from angle 0.
fn circle_points(c: DVec3, r: f64, e1: DVec3, e2: DVec3, step: f64, n: usize) -> Vec<Xyz> {
    (0..n)
        .map(|k| {
            let phi = step * k as f64;
            (c + r * (phi.cos() * e1 + phi.sin() * e2)).to_array()
        })
        .collect()
}

#[test]
fn sampled_circular_arc_gets_its_exact_tangent() {
    let n = DVec3::new(0.3, -0.5, 0.8).normalize();
    let (e1, e2) = n.any_orthonormal_pair();
    let c = DVec3::new(10.0, -3.0, 2.5);
    for (step, count) in [(0.01, 50), (0.3, 3), (PI / 4.0, 6)] {
        let g = guide(&GuideSpec::points(circle_points(
            c, 7.0, e1, e2, step, count,
        )))
        .unwrap();
        assert!(
            (g.tangent - e2).length() <= 1e-12,
            "{step}: {:?}",
            g.tangent
        );
        assert!(g.plane_normal.cross(n).length() < 1e-13);
        assert!(g.planarity < 1e-13);
    }
}

#[test]
fn polyline_tangent_falls_back_to_the_first_chord() {
    // The first three points are collinear.
    let spec = GuideSpec::points(vec![
        [0.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [2.0, 2.0, 0.0],
        [3.0, 2.0, 0.0],
    ]);
    let g = guide(&spec).unwrap();
    assert!((g.tangent - DVec3::new(1.0, 1.0, 0.0).normalize()).length() < 1e-15);
    assert_eq!(g.plane_normal, DVec3::Z);
}

#[test]
fn bspline_end_points_and_start_tangent() {
    let b = cubic();
    let g = guide(&bspline_spec(b.clone())).unwrap();
    assert_eq!(g.points.len(), 17);
    assert_eq!(g.points[0], DVec3::from_array(b.control_points[0]));
    assert_eq!(g.points[16], DVec3::from_array(b.control_points[4]));
    assert_eq!(g.tangent, unit_of([1.0, 0.0, 0.5]));

    // Oblique plane, non-uniform knots on [2, 7], rational weights: ends exact,
    // tangent parallel to P1 − P0.
    let n = DVec3::new(1.0, 2.0, -0.7).normalize();
    let (e1, e2) = n.any_orthonormal_pair();
    let origin = DVec3::new(-3.0, 4.0, 1.25);
    let control: Vec<Xyz> = [(0.0, 0.0), (1.0, 0.7), (2.5, 1.0), (3.0, -0.5), (4.1, 0.3)]
        .iter()
        .map(|&(x, y)| (origin + x * e1 + y * e2).to_array())
        .collect();
    let b = BSplineSpec {
        degree: 2,
        control_points: control.clone(),
        knots: Some(vec![2.0, 2.0, 2.0, 3.1, 5.5, 7.0, 7.0, 7.0]),
        weights: Some(vec![1.0, 0.5, 2.0, 1.5, 0.8]),
        samples: 11,
    };
    let g = guide(&bspline_spec(b)).unwrap();
    assert_eq!(g.points[0], DVec3::from_array(control[0]));
    assert_eq!(g.points[10], DVec3::from_array(control[4]));
    let chord = (DVec3::from_array(control[1]) - DVec3::from_array(control[0])).normalize();
    assert!(g.tangent.cross(chord).length() < 1e-15 && g.tangent.dot(chord) > 0.0);
    assert!(g.plane_normal.cross(n).length() < 1e-14);
}

#[test]
fn bspline_matches_an_independent_evaluation() {
    let control = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 2.0],
        [2.0, 0.0, 2.5],
        [3.5, 0.0, 1.0],
        [4.0, 0.0, -1.0],
        [6.0, 0.0, 0.5],
        [7.0, 0.0, 2.0],
    ];
    let weights = [1.0, 2.0, 0.5, 1.0, 3.0, 0.7, 1.0];
    let knots = vec![0.0, 0.0, 0.0, 0.0, 0.2, 0.2, 0.65, 1.0, 1.0, 1.0, 1.0];
    let b = BSplineSpec {
        degree: 3,
        control_points: control.to_vec(),
        knots: Some(knots.clone()),
        weights: Some(weights.to_vec()),
        samples: 41,
    };
    let g = guide(&bspline_spec(b)).unwrap();
    for (k, p) in g.points.iter().enumerate() {
        let u = k as f64 / 40.0;
        let (mut num, mut den) = (DVec3::ZERO, 0.0);
        for i in 0..control.len() {
            let nw = cox_de_boor(&knots, i, 3, u) * weights[i];
            num += nw * DVec3::from_array(control[i]);
            den += nw;
        }
        let expected = num / den;
        assert!(
            (*p - expected).length() <= 1e-15 * 7.0,
            "{k}: {p} vs {expected}"
        );
    }
}

#[test]
fn nurbs_quarter_circle_lies_on_the_circle() {
    let b = BSplineSpec {
        degree: 2,
        control_points: vec![[1.0, 0.0, 0.0], [1.0, 0.0, 1.0], [0.0, 0.0, 1.0]],
        knots: None,
        weights: Some(vec![1.0, FRAC_1_SQRT_2, 1.0]),
        samples: 33,
    };
    let g = guide(&bspline_spec(b)).unwrap();
    for p in &g.points {
        assert!((p.length() - 1.0).abs() <= 1e-14, "{p}");
        assert_eq!(p.y, 0.0);
    }
    assert_eq!(g.points[0], DVec3::X);
    assert_eq!(g.points[32], DVec3::Z);
    // Symmetric about the diagonal: the middle sample is at 45°.
    assert!((g.points[16] - DVec3::new(FRAC_1_SQRT_2, 0.0, FRAC_1_SQRT_2)).length() < 1e-15);
    assert_eq!(g.tangent, DVec3::Z);
}

#[test]
fn default_knots_are_clamped_uniform() {
    assert_eq!(
        clamped_uniform_knots(5, 2),
        vec![0.0, 0.0, 0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0, 1.0, 1.0]
    );
    assert_eq!(
        clamped_uniform_knots(3, 2),
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0]
    );
    let mut explicit = cubic();
    explicit.knots = Some(vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0]);
    assert_eq!(
        guide(&bspline_spec(cubic())).unwrap(),
        guide(&bspline_spec(explicit)).unwrap()
    );
}

#[test]
fn degree_one_bspline_is_the_control_polygon() {
    let b = bspline(bent(), 1, 7);
    let g = guide(&bspline_spec(b)).unwrap();
    let expected = [
        [0.0, 0.0, 0.0],
        [0.5, 0.0, 0.1],
        [1.0, 0.0, 0.2],
        [1.5, 0.0, 0.45],
        [2.0, 0.0, 0.7],
        [2.5, 0.0, 1.1],
        [3.0, 0.0, 1.5],
    ];
    for (p, e) in g.points.iter().zip(expected) {
        assert!((*p - DVec3::from_array(e)).length() < 1e-15, "{p}");
    }
}

#[test]
fn arc_samples_lie_on_the_circle() {
    for angle_deg in [90.0, -135.0, 359.0, 1e-3] {
        let a = arc(angle_deg, 13);
        let g = guide(&arc_spec(a.clone())).unwrap();
        let c = DVec3::from_array(a.center);
        assert_eq!(g.points[0], DVec3::from_array(a.start));
        for (k, p) in g.points.iter().enumerate() {
            let r = *p - c;
            assert!((r.length() - 2.0).abs() <= 1e-15 * 4.0, "{k}: {p}");
            assert_eq!(r.y, 0.0);
            // Right-hand rule about +y: from +z towards +x.
            let phi = (angle_deg * k as f64 / 12.0).to_radians();
            let expected = c + 2.0 * DVec3::new(phi.sin(), 0.0, phi.cos());
            assert!((*p - expected).length() <= 1e-14, "{k}: {p} vs {expected}");
        }
        assert_eq!(g.tangent, DVec3::X * angle_deg.signum());
        assert_eq!(g.plane_normal, DVec3::Y);
    }
    // An oblique arc.
    let n = DVec3::new(1.0, -2.0, 0.5);
    let (e1, _) = n.normalize().any_orthonormal_pair();
    let c = DVec3::new(0.1, 0.2, 0.3);
    let a = ArcSpec {
        center: c.to_array(),
        start: (c + 3.0 * e1).to_array(),
        normal: n.to_array(),
        angle_deg: 200.0,
        samples: 40,
    };
    let g = guide(&arc_spec(a.clone())).unwrap();
    assert_eq!(g.points[0], DVec3::from_array(a.start));
    for p in &g.points {
        assert!(((*p - c).length() - 3.0).abs() < 1e-14);
    }
    let t = n.normalize().cross(e1);
    assert!((g.tangent - t).length() < 1e-15);
}

#[test]
fn parabola_samples() {
    let spec = parabola([1.0, 0.0, 0.5], [0.0, 0.0, 2.0], 5);
    let g = guide(&spec).unwrap();
    let start = DVec3::new(0.5, -1.0, 2.0);
    for (k, p) in g.points.iter().enumerate() {
        let t = k as f64 / 4.0;
        let expected = start + t * DVec3::new(1.0, 0.0, 0.5) + t * t * DVec3::new(0.0, 0.0, 2.0);
        assert_eq!(*p, expected);
    }
    assert_eq!(g.points[0], start);
    assert_eq!(g.tangent, unit_of([1.0, 0.0, 0.5]));
    assert_eq!(g.plane_normal, DVec3::Y);
}

#[test]
fn plane_fit_agrees_with_nalgebra_svd() {
    // Noisy, nearly planar points: compare with an SVD that shares no code.
    let normal = DVec3::new(0.2, 0.9, -0.4).normalize();
    let (e1, e2) = normal.any_orthonormal_pair();
    let origin = DVec3::new(3.0, -1.0, 0.5);
    let points: Vec<Xyz> = (0..30)
        .map(|k| {
            let t = k as f64 * 0.21;
            let noise = 1e-11 * ((k * 7919) % 13) as f64;
            (origin + (2.0 * t) * e1 + t.sin() * e2 + noise * normal).to_array()
        })
        .collect();
    let g = guide(&GuideSpec::points(points.clone())).unwrap();
    let c = points.iter().map(|p| DVec3::from_array(*p)).sum::<DVec3>() / 30.0;
    let m = nalgebra::DMatrix::from_fn(30, 3, |i, j| points[i][j] - c[j]);
    let svd = m.svd(false, true);
    let v_t = svd.v_t.unwrap();
    let smallest = svd.singular_values.imin();
    let n = DVec3::new(v_t[(smallest, 0)], v_t[(smallest, 1)], v_t[(smallest, 2)]);
    assert!(
        g.plane_normal.cross(n).length() < 1e-12,
        "{} vs {n}",
        g.plane_normal
    );
    let worst = points
        .iter()
        .map(|p| (DVec3::from_array(*p) - c).dot(n).abs())
        .fold(0.0, f64::max);
    assert!((g.planarity - worst).abs() < 1e-14);
    assert!(g.planarity > 0.0 && g.planarity < 1e-9 * g.size);
}
