//! Darboux's envelope of radical planes (§2.1.1, Figure 2) as an independent
//! smooth reference for the generator (§3, §4.2).
//!
//! The envelope is checked against its closed form and, numerically, to have
//! planar curvature lines (least-squares planes, Joachimsthal's constant angle,
//! Rodrigues). Then the generator is fed with the envelope's two curvature lines
//! through a corner and must converge to the envelope.
//!
//! Sampling: equal parameter spacing in `s` and `t`. The generated vertex
//! `(i, j)` is fixed by the Gauss circles through the guide normals at guide_u's
//! sample `i` and guide_v's sample `j` (§2.2.1), so it approximates `X(s_i, t_j)`
//! whatever the spacing; arc-length sampling would only move the samples.
//!
//! `cargo test -p monge-core-tests --test integration darboux:: -- --nocapture` prints the θ scan,
//! the errors per refinement and the rates.

use glam::DVec3;
use monge_core::darboux::EnneperEnvelope;
use monge_core::measure::measure;
use monge_core::projective::Line;
use monge_core::{generate, Design, GenerateOptions, GuideSpec, QuadGrid};

use crate::common;
use common::plane_fit;

/// Equal radii: Enneper's minimal surface itself.
const ENNEPER: EnneperEnvelope = EnneperEnvelope {
    p: 1.0,
    r1: 0.5,
    r2: 0.5,
};

/// Unequal radii (ρ = r1² − r2² = 0.6): a translated parallel surface of Enneper's.
const PARALLEL: EnneperEnvelope = EnneperEnvelope {
    p: 1.3,
    r1: 0.8,
    r2: 0.2,
};

/// `n` equally spaced values from `a` to `b`, ends included.
fn linspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|k| a + (b - a) * k as f64 / (n - 1) as f64)
        .collect()
}

/// The closed form of the envelope (module documentation of `darboux`).
fn closed_form(e: &EnneperEnvelope, s: f64, t: f64) -> DVec3 {
    let enneper = 0.75
        * e.p
        * DVec3::new(
            s - s * s * s / 3.0 + s * t * t,
            t - t * t * t / 3.0 + s * s * t,
            s * s - t * t,
        );
    let w = 1.0 + s * s + t * t;
    let normal = DVec3::new(-2.0 * s, 2.0 * t, 2.0 - w) / w;
    let rho = e.r1 * e.r1 - e.r2 * e.r2;
    enneper + 0.25 * e.p * DVec3::Z + rho / (2.0 * e.p) * (normal + DVec3::Z)
}

/// The envelope's curvature line through parameters `params`: points and normals.
fn line(e: &EnneperEnvelope, params: &[(f64, f64)]) -> (Vec<DVec3>, Vec<DVec3>) {
    params
        .iter()
        .map(|&(s, t)| (e.point(s, t), e.normal(s, t)))
        .unzip()
}

/// Planarity (largest distance from the fitted plane) and Joachimsthal's angle
/// (spread of `N·m`, m the plane's unit normal) of one curvature line, and the
/// Gauss circle's plane `{Y : m·Y = c}` as `(m, c)`.
fn check_line(points: &[DVec3], normals: &[DVec3]) -> (f64, f64, (DVec3, f64)) {
    let (_, m, planarity) = plane_fit(points);
    let cosines: Vec<f64> = normals.iter().map(|n| n.dot(m)).collect();
    let (lo, hi) = cosines
        .iter()
        .fold((f64::MAX, f64::MIN), |(lo, hi), &c| (lo.min(c), hi.max(c)));
    (planarity, hi - lo, (m, 0.5 * (lo + hi)))
}

/// Common line of two planes `{Y : m·Y = c}` (Plücker coordinates, direction normalised).
fn meet(a: (DVec3, f64), b: (DVec3, f64)) -> Line {
    let dir = a.0.cross(b.0);
    let point = (a.1 * b.0.cross(dir) + b.1 * dir.cross(a.0)) / dir.length_squared();
    let dir = dir.normalize();
    Line {
        dir,
        moment: point.cross(dir),
    }
}

/// A point of a finite line, and its unit direction.
fn point_and_dir(l: &Line) -> (DVec3, DVec3) {
    let d = l.dir.length();
    (l.dir.cross(l.moment) / (d * d), l.dir / d)
}

/// Distance between two finite lines seen as sets: max over the two sample
/// points `q ± dir` of one line of their distance from the other line.
fn line_distance(a: &Line, b: &Line) -> f64 {
    let (pa, da) = point_and_dir(a);
    let (pb, db) = point_and_dir(b);
    [pa + da, pa - da]
        .iter()
        .map(|q| (*q - pb).cross(db).length())
        .fold(0.0, f64::max)
}

#[test]
fn envelope_matches_the_closed_form_and_touches_the_radical_planes() {
    for e in [ENNEPER, PARALLEL] {
        for s in linspace(-1.5, 1.5, 13) {
            for t in linspace(-1.5, 1.5, 13) {
                let x = e.point(s, t);
                assert!(x.distance(closed_form(&e, s, t)) < 1e-13, "{e:?} {s} {t}");
                // On the radical plane: equal power with respect to both spheres.
                let (p1, p2) = (e.sphere_1(s).power(x), e.sphere_2(t).power(x));
                assert!((p1 - p2).abs() < 1e-13 * (1.0 + p1.abs()));
                // Tangency: neighbouring radical planes pass at O(h²) from x.
                for h in [1e-3, 1e-4] {
                    let d = e.radical_plane(s + h, t - h).signed_distance(x).abs();
                    assert!(d < 10.0 * h * h, "{d} at h = {h}");
                }
                // The normal is the radical plane's and the envelope's (⊥ X_s, X_t).
                let n = e.normal(s, t);
                let (x_s, x_t) = e.derivatives(s, t);
                assert!(n.cross(e.radical_plane(s, t).normal).length() < 1e-14);
                assert!(n.dot(x_s).abs() < 1e-13 && n.dot(x_t).abs() < 1e-13);
            }
        }
    }
}

#[test]
fn parameter_lines_are_planar_curvature_lines() {
    let h = 1e-5;
    for e in [ENNEPER, PARALLEL] {
        for c in linspace(-1.2, 1.2, 7) {
            let range = linspace(-1.2, 1.2, 41);
            let s_line: Vec<(f64, f64)> = range.iter().map(|&t| (c, t)).collect();
            let t_line: Vec<(f64, f64)> = range.iter().map(|&s| (s, c)).collect();
            for (params, exact_plane) in [
                (&s_line, e.plane_of_s_line(c)),
                (&t_line, e.plane_of_t_line(c)),
            ] {
                let (points, normals) = line(&e, params);
                let (planarity, spread, (m, _)) = check_line(&points, &normals);
                assert!(
                    planarity < 1e-13,
                    "{e:?} line {c}: off its plane by {planarity}"
                );
                assert!(spread < 1e-13, "{e:?} line {c}: N·m varies by {spread}");
                assert!(m.cross(exact_plane.normal.normalize()).length() < 1e-12);
            }
            // Rodrigues: N_s ∥ X_s and N_t ∥ X_t (N differentiated numerically).
            for &t in &range {
                let (x_s, x_t) = e.derivatives(c, t);
                let n_s = (e.normal(c + h, t) - e.normal(c - h, t)) / (2.0 * h);
                let n_t = (e.normal(c, t + h) - e.normal(c, t - h)) / (2.0 * h);
                assert!(x_s.normalize().cross(n_s.normalize()).length() < 1e-8);
                assert!(x_t.normalize().cross(n_t.normalize()).length() < 1e-8);
            }
        }
    }
}

/// The pencil axes of the envelope's Gauss map, measured from its curvature
/// lines: the common line of the Gauss circles' planes `{Y : m·Y = c}` of the
/// lines `s = const` (first) and `t = const` (second).
fn envelope_axes(e: &EnneperEnvelope, s_range: (f64, f64), t_range: (f64, f64)) -> (Line, Line) {
    let circle = |params: Vec<(f64, f64)>| {
        let (points, normals) = line(e, &params);
        check_line(&points, &normals).2
    };
    let s_circles: Vec<_> = linspace(s_range.0, s_range.1, 5)
        .into_iter()
        .map(|s| {
            circle(
                linspace(t_range.0, t_range.1, 21)
                    .into_iter()
                    .map(|t| (s, t))
                    .collect(),
            )
        })
        .collect();
    let t_circles: Vec<_> = linspace(t_range.0, t_range.1, 5)
        .into_iter()
        .map(|t| {
            circle(
                linspace(s_range.0, s_range.1, 21)
                    .into_iter()
                    .map(|s| (s, t))
                    .collect(),
            )
        })
        .collect();
    let axis = |circles: &[(DVec3, f64)]| {
        let l = meet(circles[0], circles[4]);
        // Every circle of the family belongs to the same pencil.
        for c in circles {
            let (q, d) = point_and_dir(&l);
            assert!((c.0.dot(q) - c.1).abs() < 1e-11 && c.0.dot(d).abs() < 1e-11);
        }
        l
    };
    (axis(&s_circles), axis(&t_circles))
}

/// Corner `(s0, t0)` and parameter lengths of the cross-check: a generic corner,
/// so that the guide planes are not orthogonal (§3.2, arbitrary mode).
const S0: f64 = 0.3;
const T0: f64 = -0.2;
const LENGTH: f64 = 1.0;

/// The design whose guides are the envelope's curvature lines `t = t0` (guide_u,
/// index i, parameter s) and `s = s0` (guide_v, index j, parameter t) through the
/// corner, sampled at `n` equally spaced parameter values, with the exact start
/// tangents `X_s`, `X_t`.
fn design(
    e: &EnneperEnvelope,
    corner: (f64, f64),
    n: usize,
    theta_deg: f64,
) -> (Design, Vec<f64>, Vec<f64>) {
    let (s0, t0) = corner;
    let s = linspace(s0, s0 + LENGTH, n);
    let t = linspace(t0, t0 + LENGTH, n);
    let (x_s, x_t) = e.derivatives(s0, t0);
    let guide = |pts: Vec<DVec3>, tangent: DVec3| GuideSpec::Points {
        points: pts.iter().map(|p| p.to_array()).collect(),
        tangent: Some(tangent.to_array()),
    };
    let d = Design {
        theta_deg,
        guide_u: guide(s.iter().map(|&si| e.point(si, t0)).collect(), x_s),
        guide_v: guide(t.iter().map(|&tj| e.point(s0, tj)).collect(), x_t),
        tolerance: None,
        mesh: Default::default(),
    };
    (d, s, t)
}

/// Largest distance between generated vertices and the envelope at the same
/// parameters, and largest angle (radians) between the node axes and the
/// envelope's normals.
fn deviation(mesh: &QuadGrid, reference: &QuadGrid) -> (f64, f64) {
    let dist = mesh
        .vertices
        .iter()
        .zip(&reference.vertices)
        .map(|(a, b)| a.distance(*b))
        .fold(0.0, f64::max);
    let angle = mesh
        .normals
        .iter()
        .zip(&reference.normals)
        .map(|(a, b)| a.angle_between(*b))
        .fold(0.0, f64::max);
    (dist, angle)
}

#[test]
fn theta_is_minus_90_from_the_pencil_axes() {
    for (e, corner) in [
        (ENNEPER, (S0, T0)),
        (PARALLEL, (S0, T0)),
        (ENNEPER, (0.0, 0.0)),
    ] {
        let (a_s, a_t) = envelope_axes(
            &e,
            (corner.0, corner.0 + LENGTH),
            (corner.1, corner.1 + LENGTH),
        );
        // Both axes touch S² (|a| = |tan(θ/2)| = 1, so |θ| = 90°), at the pole
        // (0, 0, −1) where every Gauss circle passes (N(s, t) → (0, 0, −1) at infinity).
        let pole = -DVec3::Z;
        for axis in [&a_s, &a_t] {
            assert!((axis.distance_to_origin() - 1.0).abs() < 1e-11);
            let (q, d) = point_and_dir(axis);
            assert!((q - pole).cross(d).length() < 1e-11);
        }
        // The pole is not the corner normal N_p: in the generator's convention
        // (θ = +90° puts both axes tangent at N_p), this is θ = −90°. The
        // generator's axes at θ = −90° are the envelope's: L1 (v-lines, fixed i,
        // i.e. s = const) and L2 (u-lines, t = const).
        let n_p = e.normal(corner.0, corner.1);
        assert!(n_p.distance(pole) > 0.1);
        let generated =
            generate(&design(&e, corner, 9, -90.0).0, &GenerateOptions::default()).unwrap();
        assert!(generated.grid.normals[0].distance(n_p) < 1e-14);
        let (l1, l2) = (&generated.axes.l1, &generated.axes.l2);
        assert!(line_distance(l1, &a_s) < 1e-11, "{l1:?} vs {a_s:?}");
        assert!(line_distance(l2, &a_t) < 1e-11, "{l2:?} vs {a_t:?}");
    }
}

#[test]
fn theta_scan_finds_minus_90() {
    let n = 17;
    let mut best = (f64::MAX, f64::NAN);
    let mut errors = Vec::new();
    for k in -17..=18 {
        let theta = 10.0 * k as f64;
        let (d, s, t) = design(&PARALLEL, (S0, T0), n, theta);
        let Ok(generated) = generate(&d, &GenerateOptions::default()) else {
            errors.push((theta, f64::NAN));
            continue;
        };
        let error = deviation(&generated.grid, &PARALLEL.sample(&s, &t)).0;
        errors.push((theta, error));
        if error < best.0 {
            best = (error, theta);
        }
    }
    println!("θ scan at n = {n} (max vertex distance; NaN = refused):");
    for (theta, error) in &errors {
        println!("  θ = {theta:6.1}°  {error:.3e}");
    }
    assert_eq!(best.1, -90.0);
    // Every other θ is far off: the match is not a coincidence of the guides.
    let second = errors
        .iter()
        .filter(|(theta, e)| *theta != -90.0 && e.is_finite())
        .map(|(_, e)| *e)
        .fold(f64::MAX, f64::min);
    assert!(second > 10.0 * best.0, "best {best:?}, second {second}");
}

#[test]
fn generator_converges_to_the_envelope() {
    for (e, corner) in [
        (ENNEPER, (S0, T0)),
        (PARALLEL, (S0, T0)),
        (ENNEPER, (0.0, 0.0)),
    ] {
        println!("{e:?}, corner (s0, t0) = {corner:?}, θ = −90°:");
        let mut previous: Option<(usize, f64)> = None;
        let mut rates = Vec::new();
        for n in [8, 16, 32, 64, 128] {
            let (d, s, t) = design(&e, corner, n, -90.0);
            let generated =
                generate(&d, &GenerateOptions::default()).unwrap_or_else(|err| panic!("{err}"));
            let mesh = &generated.grid;
            let exactness = measure(mesh).max_error();
            assert!(
                exactness <= 1e-9,
                "n = {n}: not an exact circular mesh ({exactness:e})"
            );
            let reference = e.sample(&s, &t);
            let (dist, angle) = deviation(mesh, &reference);
            let relative = dist / reference.bbox_diagonal();
            let rate = previous.map(|(m, prev)| (prev / dist).ln() / (n as f64 / m as f64).ln());
            println!(
                "  n = {n:3}: max |X_gen − X_env| = {dist:.3e} (relative {relative:.3e}), normals {angle:.3e} rad, \
                 circular/planar {exactness:.1e}, rate {}",
                rate.map_or("-".into(), |r| format!("{r:.2}"))
            );
            rates.extend(rate);
            previous = Some((n, dist));
        }
        // At least h^1.5 over the last refinements.
        for r in &rates[rates.len() - 2..] {
            assert!(*r >= 1.5, "rates {rates:?}");
        }
    }
}
