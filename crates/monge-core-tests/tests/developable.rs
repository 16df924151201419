//! Developable circular meshes with planar curvature lines (§3.3, Figure 11),
//! measured independently of their construction: isosceles trapezoid faces
//! around the meeting point of two rows (computed here from the rows alone),
//! `measure` (planar, circular faces, planar rows and columns, torsion-free unit
//! node axes), columns in their cutting planes, helix segments at slope α; a
//! property test over random projection curves. Every refusal is in
//! developable_errors.rs.

use std::f64::consts::TAU;

use glam::DVec3;
use monge_core::developable::{developable, DevelopableSpec};
use monge_core::measure::measure;
use monge_core::offset::vertex_offset;
use monge_core::{GenerateOptions, QuadGrid};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed, TestRunner};

use crate::common;
use common::developable::{check, curve, generate_checked, square, Xyz};
use common::TOL;

#[test]
fn circular_helix_over_a_regular_polygon() {
    // One full turn: the projection is a closed regular 12-gon.
    let poly = curve(13, 0.0, TAU, |t| [2.0 * t.cos(), 2.0 * t.sin(), 0.5]);
    for alpha in [5.0f64, 30.0, 60.0, 85.0, -40.0] {
        // Heights beyond helix vertex 1 on the side of vertex 0.
        let z1 = 0.5 + alpha.to_radians().tan() * 2.0 * 2.0 * (TAU / 24.0).sin();
        let dir = alpha.signum();
        let heights: Vec<f64> = (0..7).map(|k| z1 - dir * (0.3 + 0.4 * k as f64)).collect();
        let spec = DevelopableSpec::projection(poly.clone(), alpha, heights);
        let (mesh, w) = generate_checked(&spec, alpha);
        assert_eq!((mesh.grid.rows, mesh.grid.cols), (12, 7));
        eprintln!("12-gon α = {alpha}: {w:?}");
    }
}

#[test]
fn circular_helix_given_directly_about_a_tilted_axis() {
    // x = (r cos t, r sin t, c t) in a frame whose third axis is `n`.
    let n = DVec3::new(1.0, -2.0, 2.0).normalize();
    let (e1, e2) = n.any_orthonormal_pair();
    let origin = DVec3::new(0.3, 0.1, -0.7);
    let (r, c) = (1.5, 0.4);
    let helix: Vec<Xyz> = curve(10, 0.0, 1.6 * std::f64::consts::PI, |t| {
        (origin + r * t.cos() * e1 + r * t.sin() * e2 + c * t * n).to_array()
    });
    // Every chord of the circular helix has slope atan(c·Δt / (2 r sin(Δt/2))).
    let dt = 1.6 * std::f64::consts::PI / 9.0;
    let alpha = (c * dt / (2.0 * r * (dt / 2.0).sin())).atan().to_degrees();
    let top = (origin + c * 1.6 * std::f64::consts::PI * n).dot(n);
    let heights: Vec<f64> = (1..=6).map(|k| top + 0.25 * k as f64).collect();
    let mut spec = DevelopableSpec::helix(helix.clone(), heights);
    spec.reference_normal = (3.0 * n).to_array();
    let (mesh, w) = generate_checked(&spec, alpha);
    eprintln!("tilted circular helix: {w:?}");
    // The helix given exactly is kept (to round-off).
    for (h, p) in mesh.helix.iter().zip(&helix) {
        assert!((*h - DVec3::from_array(*p)).length() <= 1e-14 * 10.0);
    }
    assert!((mesh.alpha_deg - alpha).abs() < 1e-12);
}

#[test]
fn random_convex_projection_curve() {
    // A deterministic pseudo-random convex polygon arc on an ellipse.
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    let mut rnd = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    for _ in 0..20 {
        let k = 4 + (rnd() * 20.0) as usize;
        let mut ts: Vec<f64> = (0..k).map(|_| rnd() * 5.5).collect();
        ts.sort_by(f64::total_cmp);
        ts.dedup_by(|a, b| (*a - *b).abs() < 1e-3);
        if ts.len() < 3 {
            continue;
        }
        let (a, b) = (1.0 + 3.0 * rnd(), 1.0 + 3.0 * rnd());
        let pts: Vec<Xyz> = ts
            .iter()
            .map(|t| [a * t.cos(), b * t.sin(), -1.0])
            .collect();
        let alpha = 10.0 + 70.0 * rnd();
        // Above the last helix vertex.
        let run: f64 = pts
            .windows(2)
            .map(|w| DVec3::from_array(w[1]).distance(DVec3::from_array(w[0])))
            .sum();
        let top = -1.0 + alpha.to_radians().tan() * run;
        let heights: Vec<f64> = (0..8).map(|j| top + 0.1 + 0.5 * j as f64).collect();
        let spec = DevelopableSpec::projection(pts, alpha, heights);
        generate_checked(&spec, alpha);
    }
}

#[test]
fn spiral_projection_winding_three_times() {
    // An Archimedean spiral never crosses itself, however often it winds.
    let pts = curve(60, 0.0, 3.0 * TAU, |t| {
        let r = 1.0 + 0.4 * t;
        [r * t.cos(), r * t.sin(), 2.0]
    });
    let heights = vec![1.9, 1.0, 0.0, -1.0, -2.0, -4.0];
    let spec = DevelopableSpec::projection(pts, 20.0, heights);
    let (mesh, w) = generate_checked(&spec, 20.0);
    eprintln!("spiral: {w:?}");
    assert_eq!((mesh.grid.rows, mesh.grid.cols), (59, 6));
}

#[test]
fn node_axes_offset_is_the_mesh_of_the_raised_helix() {
    // The vertex offset along the node axes at distance d is the same
    // construction on the helix raised by d / cos α (module docs).
    let pts = curve(9, 0.0, 4.0, |t| [t, 0.3 * t * t, 0.0]);
    let alpha: f64 = 35.0;
    let heights = vec![-0.5, -1.0, -2.0, -3.5];
    let spec = DevelopableSpec::projection(pts.clone(), alpha, heights.clone());
    let mesh = developable(&spec, &GenerateOptions::default()).unwrap();
    let d = 0.7;
    let off = vertex_offset(&mesh.grid, d);
    let m = measure(&off);
    assert!(m.max_error() <= TOL, "{m:?}");
    let raise = d / alpha.to_radians().cos();
    let raised: Vec<Xyz> = pts.iter().map(|p| [p[0], p[1], p[2] + raise]).collect();
    let shifted: Vec<f64> = heights
        .iter()
        .map(|h| h + d * alpha.to_radians().cos())
        .collect();
    // Offset vertices of column j lie at height h_j + d cos α.
    for (j, h) in shifted.iter().enumerate() {
        for x in off.column(j) {
            assert!((x.z - h).abs() < 1e-12);
        }
    }
    let again = developable(
        &DevelopableSpec::projection(raised, alpha, shifted),
        &GenerateOptions::default(),
    )
    .unwrap();
    let diff = off
        .vertices
        .iter()
        .zip(&again.grid.vertices)
        .map(|(a, b)| a.distance(*b))
        .fold(0.0, f64::max);
    assert!(diff <= 1e-12 * off.bbox_diagonal(), "{diff}");
}

#[test]
fn cutting_at_the_end_vertices_is_fine() {
    // Heights of helix vertices 0 and n are allowed: no two rulings meet there.
    let pts = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]];
    let spec = DevelopableSpec::projection(pts.clone(), 45.0, vec![0.0, -1.0]);
    let (mesh, _) = generate_checked(&spec, 45.0);
    assert!(mesh.grid.vertex(0, 0).length() < 1e-15);
    let spec = DevelopableSpec::projection(pts, 45.0, vec![2.0, 3.0]);
    generate_checked(&spec, 45.0);
}

/// A random star-shaped projection curve (angles increasing by less than a
/// turn in all, radii varying), α of either sign, heights beyond helix vertex 1
/// (on the side of vertex 0) or beyond vertex n − 1.
fn random_spec() -> impl Strategy<Value = (DevelopableSpec, f64)> {
    (
        prop::collection::vec((0.05f64..0.6, 0.7f64..1.3), 2..25),
        0.3f64..5.0,
        prop_oneof![-85.0f64..-3.0, 3.0f64..85.0],
        prop::collection::vec(0.02f64..1.0, 2..10),
        any::<bool>(),
        -3.0f64..3.0,
    )
        .prop_filter_map(
            "projection of at most one turn",
            |(steps, scale, alpha, gaps, after, z0)| {
                let total: f64 = steps.iter().map(|s| s.0).sum();
                if total > 0.95 * TAU {
                    return None;
                }
                let mut t = 0.0;
                let mut pts = vec![[scale, 0.0, z0]];
                for (dt, r) in &steps {
                    t += dt;
                    pts.push([scale * r * t.cos(), scale * r * t.sin(), z0]);
                }
                let len =
                    |k: usize| DVec3::from_array(pts[k + 1]).distance(DVec3::from_array(pts[k]));
                let tan = alpha.to_radians().tan();
                let n = pts.len() - 1;
                let run_to = |k: usize| (0..k).map(len).sum::<f64>();
                let (start, dir) = if after {
                    (z0 + tan * run_to(n - 1), tan.signum())
                } else {
                    (z0 + tan * run_to(1), -tan.signum())
                };
                let mut h = start;
                let heights = gaps
                    .iter()
                    .map(|g| {
                        h += dir * g * scale;
                        h
                    })
                    .collect();
                Some((DevelopableSpec::projection(pts, alpha, heights), alpha))
            },
        )
}

#[test]
fn property_random_projection_curves() {
    let mut runner = TestRunner::new(Config {
        rng_seed: RngSeed::Fixed(0x646576),
        failure_persistence: None,
        cases: 300,
        ..Config::default()
    });
    let worst = std::cell::Cell::new(0.0f64);
    runner
        .run(&random_spec(), |(spec, alpha)| {
            let mesh = developable(&spec, &GenerateOptions::default())
                .map_err(|e| TestCaseError::fail(e.to_string()))?;
            let w = check(&mesh, &spec.heights, DVec3::Z, alpha);
            worst.set(worst.get().max(w.max()));
            prop_assert!(w.max() <= TOL, "{:?}", w);
            Ok(())
        })
        .unwrap();
    eprintln!("property test: worst measured value {:.3e}", worst.get());
}

#[test]
fn grid_shape_follows_the_rulings() {
    // Rows are rulings (straight), each row i passes through helix vertices i and i + 1.
    let spec = DevelopableSpec::projection(square(), 45.0, vec![-1.0, -2.0, -3.0]);
    let mesh = developable(&spec, &GenerateOptions::default()).unwrap();
    let g: &QuadGrid = &mesh.grid;
    for i in 0..g.rows {
        let (a, b) = (mesh.helix[i], mesh.helix[i + 1]);
        for x in g.row(i) {
            assert!((x - a).cross(b - a).length() < 1e-14);
        }
    }
}
