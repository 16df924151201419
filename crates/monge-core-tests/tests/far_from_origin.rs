//! Exactness far from the origin: the same design, scaled to a size of 1e-3 … 5
//! and moved to 0 … 5e5 from the origin, in both modes (§3.1, §3.2).
//!
//! The generator computes relative to the guides' common start point, so its
//! error stays relative to the design's size; what remains is the rounding of
//! the output coordinates themselves, ulp(|corner|), which no f64 file can
//! avoid. Measured here independently of `monge_core::measure`: nalgebra SVD
//! plane fits and circles in each face's plane, every point taken relative to a
//! local origin (the face's, the row's or the column's first vertex).
//!
//! Run with `-- --nocapture` to see the table of errors.

use std::cell::RefCell;

use glam::DVec3;
use monge_core::design::BSplineSpec;
use monge_core::developable::{developable, DevelopableSpec};
use monge_core::grid::{bbox_diagonal, origin_ratio};
use monge_core::guide::GuideError;
use monge_core::measure::measure;
use monge_core::{
    generate, inspect, Design, GenerateError, GenerateOptions, GuideSpec, Mode, QuadGrid,
    Tolerances,
};
use nalgebra::{DMatrix, Vector2};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};

use crate::common;
use common::random_designs::{bbox, characteristic_case};
use common::{own_face_planarity, ulp, TOL};

/// Largest distance of `points` from their least-squares plane, relative to the first point.
fn plane_distance(points: &[DVec3]) -> f64 {
    let (p0, n) = fit_plane(points);
    points
        .iter()
        .map(|p| (*p - p0).dot(n).abs())
        .fold(0.0, f64::max)
}

/// `(a point of the plane, unit normal)` of the least-squares plane by SVD.
fn fit_plane(points: &[DVec3]) -> (DVec3, DVec3) {
    let o = points[0];
    let rel: Vec<DVec3> = points.iter().map(|p| *p - o).collect();
    let c = rel.iter().sum::<DVec3>() / rel.len() as f64;
    let m = DMatrix::from_fn(rel.len(), 3, |r, k| (rel[r] - c)[k]);
    let svd = m.svd(false, true);
    let v_t = svd.v_t.unwrap();
    let k = svd.singular_values.imin();
    (o + c, DVec3::new(v_t[(k, 0)], v_t[(k, 1)], v_t[(k, 2)]))
}

/// Distance of the fourth corner from the circle through the first three, in
/// the quad's best-fit plane (2D coordinates relative to the first corner).
fn circle_distance(q: &[DVec3; 4]) -> f64 {
    let (_, n) = fit_plane(q);
    let e1 = (q[1] - q[0]).normalize();
    let e2 = n.cross(e1);
    let p: Vec<Vector2<f64>> = q
        .iter()
        .map(|x| Vector2::new((*x - q[0]).dot(e1), (*x - q[0]).dot(e2)))
        .collect();
    // Circumcentre of p0 = 0, p1, p2 by solving 2 [p1; p2] c = [|p1|², |p2|²].
    let a = nalgebra::Matrix2::new(p[1].x, p[1].y, p[2].x, p[2].y) * 2.0;
    let c = a
        .lu()
        .solve(&Vector2::new(p[1].norm_squared(), p[2].norm_squared()))
        .unwrap();
    ((p[3] - c).norm() - c.norm()).abs()
}

/// Worst face planarity, circularity, row and column planarity, relative to `size`.
fn errors(g: &QuadGrid, size: f64) -> f64 {
    let mut worst = 0.0f64;
    for i in 0..g.rows - 1 {
        for j in 0..g.cols - 1 {
            let q = g.face(i, j);
            worst = worst.max(plane_distance(&q)).max(circle_distance(&q));
        }
    }
    for i in 0..g.rows {
        worst = worst.max(plane_distance(&g.row(i).collect::<Vec<_>>()));
    }
    for j in 0..g.cols {
        worst = worst.max(plane_distance(&g.column(j).collect::<Vec<_>>()));
    }
    worst / size
}

fn bspline(points: &[[f64; 3]], size: f64, corner: DVec3) -> GuideSpec {
    GuideSpec::BSpline {
        bspline: BSplineSpec {
            degree: 3,
            control_points: points
                .iter()
                .map(|p| (size / 9.0 * DVec3::from_array(*p) + corner).to_array())
                .collect(),
            knots: None,
            weights: None,
            samples: 81,
        },
        parameters: None,
    }
}

/// The design of Figure 10 (arbitrary, θ = 100°) or a characteristic one
/// (θ = 30°), of about `size`, its corner at `corner`.
fn design(arbitrary: bool, size: f64, corner: DVec3) -> Design {
    let u = [
        [0.0, 0.0, 0.0],
        [3.0, 0.0, 0.0],
        [6.0, 0.0, 1.5],
        [9.0, 0.0, 1.0],
    ];
    let (v, theta_deg) = if arbitrary {
        (
            [
                [0.0, 0.0, 0.0],
                [0.0, 3.0, 0.0],
                [0.6, 6.0, 0.8],
                [1.8, 9.0, 2.4],
            ],
            100.0,
        )
    } else {
        (
            [
                [0.0, 0.0, 0.0],
                [0.0, 3.0, 0.0],
                [0.0, 6.0, 1.2],
                [0.0, 9.0, 3.0],
            ],
            30.0,
        )
    };
    // Input rounding at |corner| tilts a guide's plane by up to ε |corner| / size:
    // relax the input checks by that much (the guides are then projected).
    let slack = (64.0 * f64::EPSILON * corner.length() / size).max(1e-9);
    Design {
        mesh: Default::default(),
        theta_deg,
        guide_u: bspline(&u, size, corner),
        guide_v: bspline(&v, size, corner),
        tolerance: Some(Tolerances {
            planarity: slack,
            angle: slack,
            start: slack,
        }),
    }
}

/// The corners of the table, along one direction that is no axis.
const CORNERS: [f64; 4] = [0.0, 1e4, 1e5, 5e5];
/// The sizes of the table (before the designs' own proportions).
const SIZES: [f64; 3] = [1e-3, 1e-1, 5.0];

fn direction() -> DVec3 {
    DVec3::new(0.6, -0.48, 0.64)
}

/// The bound of the table: 1e-9 where f64 holds the output coordinates to 1e-11
/// of the size; elsewhere a few ulps of the coordinates, relative to the size.
fn bound(corner: f64, size: f64) -> f64 {
    if corner * f64::EPSILON <= 1e-11 * size {
        TOL
    } else {
        4.0 * ulp(corner) / size
    }
}

/// Prints a row of the table; returns a failure message if `err` exceeds the bound.
fn row(what: &str, corner: f64, size: f64, err: f64) -> Option<String> {
    let b = bound(corner, size);
    let ulps = if corner == 0.0 {
        "-".to_owned()
    } else {
        format!("{:.2}", err * size / ulp(corner))
    };
    println!("{what:14} {corner:7.0e} {size:8.1e} {err:10.2e} {b:10.2e} {ulps:>8}");
    (err.is_nan() || err > b)
        .then(|| format!("{what} corner {corner:e} size {size:e}: {err:e} > {b:e}"))
}

#[test]
fn error_stays_relative_to_the_size_far_from_the_origin() {
    let mut failures = Vec::new();
    println!("mode          corner     size error/size      bound  ulp(corner)s");
    for arbitrary in [false, true] {
        for corner in CORNERS {
            for size in SIZES {
                let d = design(arbitrary, size, corner * direction());
                let g = generate(&d, &GenerateOptions::default()).unwrap().grid;
                let size = g.bbox_diagonal();
                let mode = if arbitrary {
                    "arbitrary"
                } else {
                    "characteristic"
                };
                failures.extend(row(mode, corner, size, errors(&g, size)));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn developable_meshes_stay_exact_far_from_the_origin() {
    // Figure 11's helix over a circle-like plan, α = 25°.
    let plan: Vec<[f64; 2]> = (0..24)
        .map(|k| {
            let t = 0.3 * k as f64;
            let r = 6.0 - 0.1 * k as f64;
            [r * t.cos(), r * t.sin()]
        })
        .collect();
    let mut failures = Vec::new();
    for corner in CORNERS {
        for size in SIZES {
            let c = corner * direction();
            let s = size / 12.0;
            let spec = DevelopableSpec::projection(
                plan.iter()
                    .map(|p| [s * p[0] + c.x, s * p[1] + c.y, c.z])
                    .collect(),
                25.0,
                (0..8).map(|k| c.z - s * (0.5 + k as f64)).collect(),
            );
            let g = developable(&spec, &GenerateOptions::default())
                .unwrap()
                .grid;
            let size = g.bbox_diagonal();
            failures.extend(row("developable", corner, size, errors(&g, size)));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn ratio_and_diagonal_over_many_blocks_match_one_plain_pass() {
    // 200 003 points: several blocks of the side-by-side pass, the last partial;
    // the extremes sit in different blocks.
    let points: Vec<DVec3> = (0..200_003u32)
        .map(|k| {
            let t = f64::from(k);
            DVec3::new(
                (t * 0.37).sin() * 3.0 + 1e4,
                (t * 0.011).cos() - 2.0,
                t * 1e-6,
            )
        })
        .collect();
    let (mut lo, mut hi, mut far) = ([f64::MAX; 3], [f64::MIN; 3], 0.0f64);
    for p in &points {
        for (k, x) in p.to_array().into_iter().enumerate() {
            lo[k] = lo[k].min(x);
            hi[k] = hi[k].max(x);
            far = far.max(x.abs());
        }
    }
    let diagonal = (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt();
    assert_eq!(bbox_diagonal(&points), diagonal);
    assert_eq!(origin_ratio(&points), far / diagonal);
    assert_eq!(bbox_diagonal(&[]), 0.0);
    assert_eq!(origin_ratio(&[]), 0.0);
}

/// A small deterministic generator (SplitMix64), so that sweeps repeat exactly.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in [lo, hi).
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }

    fn unit(&mut self) -> DVec3 {
        loop {
            let v = DVec3::new(
                self.uniform(-1.0, 1.0),
                self.uniform(-1.0, 1.0),
                self.uniform(-1.0, 1.0),
            );
            if (0.1..1.0).contains(&v.length()) {
                return v.normalize();
            }
        }
    }

    /// A unit vector orthogonal to the unit `t`.
    fn orthogonal(&mut self, t: DVec3) -> DVec3 {
        let v = self.unit();
        (v - v.dot(t) * t).normalize()
    }
}

/// Cubic B-spline control points of a planar guide from 0 along `t`, bending
/// in the plane of `t` and `b`, of size about 1.
fn random_guide(rng: &mut Rng, t: DVec3, b: DVec3) -> Vec<DVec3> {
    let mut x = 0.0;
    (0..5)
        .map(|k| {
            if k > 0 {
                x += rng.uniform(0.15, 0.3);
            }
            let y = if k < 2 { 0.0 } else { rng.uniform(-0.3, 0.3) };
            x * t + y * b
        })
        .collect()
}

/// A random design of size about `size` (both modes, θ admissible), its start
/// point `offset · size` from the origin in a random direction; its
/// tolerances admit the rounding of its input coordinates (the guides are then
/// projected onto their planes), as the table above.
fn random_design(rng: &mut Rng, size: f64, offset: f64) -> Design {
    let t_u = rng.unit();
    let t_v = rng.orthogonal(t_u);
    let (b_u, b_v) = (rng.orthogonal(t_u), rng.orthogonal(t_v));
    let corner = offset * size * rng.unit();
    let (u, v) = (random_guide(rng, t_u, b_u), random_guide(rng, t_v, b_v));
    let spec = |points: &[DVec3], samples: usize| {
        GuideSpec::bspline(
            3,
            points
                .iter()
                .map(|p| (size * *p + corner).to_array())
                .collect(),
            samples,
        )
    };
    let slack = (64.0 * f64::EPSILON * offset).max(1e-9);
    let mut d = Design {
        mesh: Default::default(),
        theta_deg: 0.0,
        guide_u: spec(&u, 6 + (rng.next() % 12) as usize),
        guide_v: spec(&v, 6 + (rng.next() % 12) as usize),
        tolerance: Some(Tolerances {
            planarity: slack,
            angle: slack,
            start: slack,
        }),
    };
    let theta = match inspect(&d, &GenerateOptions::default()) {
        Ok(info) if info.mode == Mode::Characteristic => rng.uniform(-175.0, 85.0),
        Ok(info) => {
            let r = info.theta_range;
            let sign = if rng.next().is_multiple_of(2) {
                1.0
            } else {
                -1.0
            };
            sign * rng.uniform(r.min_deg, r.max_deg)
        }
        Err(_) => 30.0,
    };
    d.theta_deg = theta;
    d
}

/// Worst face planarity (the distance between the lines of the two diagonals)
/// and circularity (the distance of the fourth corner from the circle through
/// the other three), relative to the mesh's bounding-box diagonal, with
/// closed forms in each face's own coordinates (relative to its first corner).
fn face_errors(g: &QuadGrid) -> (f64, f64) {
    let (mut planarity, mut circularity) = (0.0f64, 0.0f64);
    for i in 0..g.rows - 1 {
        for j in 0..g.cols - 1 {
            let q = g.face(i, j);
            let [a, b, c, d] = [DVec3::ZERO, q[1] - q[0], q[2] - q[0], q[3] - q[0]];
            let (d1, d2) = (c - a, d - b);
            let m = d1.cross(d2);
            planarity = planarity.max((b - a).dot(m).abs() / m.length());
            // Circumcentre of a, b, c: c + ((|x|² y − |y|² x) × (x × y)) / (2 |x × y|²).
            let (x, y) = (a - c, b - c);
            let n = x.cross(y);
            let o = c
                + (x.length_squared() * y - y.length_squared() * x).cross(n)
                    / (2.0 * n.length_squared());
            let r = (a - o).length();
            let w = d - o;
            let h = w.dot(n.normalize());
            let in_plane = (w - h * n.normalize()).length();
            circularity = circularity.max(h.hypot(in_plane - r));
        }
    }
    let size = g.bbox_diagonal();
    (planarity / size, circularity / size)
}

/// The mesh of `d` as generated, and relative to its start point (the design
/// moved by −start first, as `--base-point start` does).
fn with_and_without_base(d: &Design) -> Option<(QuadGrid, QuadGrid)> {
    let g = generate(d, &GenerateOptions::default()).ok()?;
    if g.report.folded_faces > 0 {
        return None;
    }
    let moved = d.translated(d.start_point()?);
    let r = generate(&moved, &GenerateOptions::default()).ok()?;
    Some((g.grid, r.grid))
}

#[test]
fn a_mesh_written_relative_to_its_start_is_exact_a_million_sizes_away() {
    let mut rng = Rng(7);
    let (mut measured, mut worst_before, mut worst_after) = (0, 0.0f64, 0.0f64);
    while measured < 12 {
        let d = random_design(&mut rng, 1.0, 1e6);
        let Some((far, near)) = with_and_without_base(&d) else {
            continue;
        };
        measured += 1;
        let (p, c) = face_errors(&far);
        worst_before = worst_before.max(p).max(c);
        let (p, c) = face_errors(&near);
        worst_after = worst_after.max(p).max(c);
        // The same mesh: moved back, it is the far one to the rounding of the far coordinates.
        let start = DVec3::from_array(d.start_point().unwrap());
        let moved = far
            .vertices
            .iter()
            .zip(&near.vertices)
            .map(|(a, b)| (*a - (*b + start)).abs().max_element())
            .fold(0.0, f64::max);
        assert!(moved <= 1e-6 * far.bbox_diagonal(), "{moved:e}");
    }
    println!("at 1e6 sizes: worst error {worst_before:.1e} as generated, {worst_after:.1e} relative to the start");
    assert!(worst_after <= TOL, "{worst_after:e}");
}

/// The sweep that sets [`monge_core::grid::FAR_FROM_ORIGIN`]: random designs at
/// several distances from the origin, the worst face error with and without
/// the base point, the largest error that the rounding of the coordinates adds
/// per rounding ((error − error relative to the start) / (ε · origin ratio)),
/// and the refusals with the default tolerances. Run with `cargo test -p monge-core-tests --release
/// --test integration far_from_origin:: -- --ignored --nocapture`.
#[test]
#[ignore = "a sweep of a few minutes: prints the table behind FAR_FROM_ORIGIN"]
fn sweep_errors_against_the_distance_from_the_origin() {
    let mut rng = Rng(2024);
    let mut gain = 0.0f64;
    let mut nearest_over = f64::INFINITY;
    println!(
        "offset/size  designs  >1e-9   worst(as is)  >1e-9(base) worst(base)  max excess/(ε·ratio)"
    );
    for offset in [1e2, 3e2, 1e3, 3e3, 1e4, 1e5, 1e6, 1e7] {
        let (mut n, mut over, mut over_base) = (0, 0, 0);
        let (mut worst, mut worst_base, mut g_max) = (0.0f64, 0.0f64, 0.0f64);
        let mut refused = std::collections::BTreeMap::<String, (usize, usize)>::new();
        while n < 1000 {
            let size = rng.uniform(1e-2, 1e2);
            let d = random_design(&mut rng, size, offset);
            // With the default tolerances: which refusals, and how many of them blame the precision.
            let strict = Design {
                tolerance: None,
                ..d.clone()
            };
            if let Err(e) = generate(&strict, &GenerateOptions::default()) {
                let text = e.to_string();
                let kind = format!("{e:?}");
                let kind = kind
                    .split(['(', ' ', '{'])
                    .take(3)
                    .collect::<Vec<_>>()
                    .join(" ");
                let entry = refused.entry(kind).or_default();
                entry.0 += 1;
                entry.1 += usize::from(text.contains("precision"));
            }
            let Some((far, near)) = with_and_without_base(&d) else {
                continue;
            };
            n += 1;
            let (p, c) = face_errors(&far);
            let e = p.max(c);
            let ratio = origin_ratio(&far.vertices);
            if e > TOL {
                over += 1;
                nearest_over = nearest_over.min(ratio);
            }
            worst = worst.max(e);
            let (p, c) = face_errors(&near);
            let e_near = p.max(c);
            worst_base = worst_base.max(e_near);
            over_base += usize::from(e_near > TOL);
            // What the coordinates' rounding adds to the design's own error, per rounding.
            g_max = g_max.max((e - e_near) / (f64::EPSILON * ratio));
        }
        gain = gain.max(g_max);
        println!(
            "{offset:9.0e} {n:8} {:6.2}% {worst:12.2e} {:10.2}% {worst_base:12.2e} {g_max:12.0}",
            100.0 * over as f64 / n as f64,
            100.0 * over_base as f64 / n as f64
        );
        for (kind, (count, blamed)) in refused {
            println!("    refused with default tolerances: {count} {kind} ({blamed} blaming the precision)");
        }
    }
    println!("smallest origin ratio with an error over 1e-9: {nearest_over:.3e}");
    println!(
        "largest error per rounding: {gain:.0}, so errors can pass 1e-9 from {:.3e}",
        TOL / (gain * f64::EPSILON)
    );
}

#[test]
fn refusals_far_from_the_origin_blame_the_precision_of_the_coordinates() {
    // 1e7 sizes from the origin, with the default tolerances of 1e-9: the
    // rounding of the input coordinates (2.2e-9 of the size) alone puts the
    // guides off their planes and the start tangents off 90°.
    let mut rng = Rng(11);
    let mut seen = std::collections::BTreeSet::new();
    for _ in 0..400 {
        let size = rng_size(&mut rng);
        let d = Design {
            tolerance: None,
            ..random_design(&mut rng, size, 1e7)
        };
        let Err(e) = generate(&d, &GenerateOptions::default()) else {
            continue;
        };
        let kind = match &e {
            GenerateError::Guide(GuideError::NotPlanar { .. }) => "planarity",
            GenerateError::Guide(GuideError::TangentNotInPlane { .. }) => "tangent",
            GenerateError::NotOrthogonal { .. } => "orthogonal",
            _ => continue,
        };
        let text = e.to_string();
        for words in [
            "times their size from the origin",
            "that precision, not the design, is the cause",
            "Model the design near the origin",
            "`--base-point start`",
        ] {
            assert!(text.contains(words), "{words}: {text}");
        }
        seen.insert(kind);
        if seen.len() == 3 {
            break;
        }
    }
    assert_eq!(seen.len(), 3, "{seen:?}");
}

/// A design size from 1e-2 to 1e2.
fn rng_size(rng: &mut Rng) -> f64 {
    10f64.powf(rng.uniform(-2.0, 2.0))
}

/// `spec` scaled by `s` about the origin, then moved by `shift`.
fn placed(spec: &GuideSpec, s: f64, shift: DVec3) -> GuideSpec {
    let point = |p: &[f64; 3]| (s * DVec3::from_array(*p) + shift).to_array();
    let vector = |v: &[f64; 3]| (s * DVec3::from_array(*v)).to_array();
    let mut g = spec.clone();
    match &mut g {
        GuideSpec::Points { points, tangent } => {
            points.iter_mut().for_each(|p| *p = point(p));
            *tangent = tangent.as_ref().map(vector);
        }
        GuideSpec::BSpline { bspline: b, .. } => {
            b.control_points.iter_mut().for_each(|p| *p = point(p));
        }
        GuideSpec::Arc(a) => (a.center, a.start) = (point(&a.center), point(&a.start)),
        GuideSpec::Parabola(p) => {
            (p.start, p.tangent, p.quadratic) =
                (point(&p.start), vector(&p.tangent), vector(&p.quadratic));
        }
    }
    g
}

/// Random characteristic designs in axis-aligned planes (every kind of guide,
/// any θ), scaled to 1e-3 … 5 and moved up to 5e5 from the origin in any
/// direction: every measure (relative to the size) stays within 1e-9 plus a few
/// ulps of the coordinates (the rounding of the output itself), relative to the
/// size. Axis-aligned planes keep the input itself exact when moved (a tilted
/// plane's points round by ε |corner|, which bends the guides and the angle
/// between them by ε |corner| / size: another design;
/// `error_stays_relative_to_the_size_far_from_the_origin` covers the arbitrary
/// mode with a tilted plane).
#[test]
fn designs_far_from_the_origin_stay_exact_relative_to_their_size() {
    let case = characteristic_case().prop_filter("axis-aligned planes", |c| {
        c.label.ends_with("rotated=false")
    });
    let place = (
        -3.0..0.7f64,
        prop::sample::select(vec![0.0, 1e4, 1e5, 5e5]),
        (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64),
    );
    let mut config = TestRunner::new_with_rng(
        Config {
            cases: 400,
            max_global_rejects: 20_000,
            failure_persistence: None,
            ..Config::default()
        },
        TestRng::from_seed(RngAlgorithm::ChaCha, &[31; 32]),
    );
    let worst = RefCell::new((0.0f64, String::new()));
    let result = config.run(&(case, place), |(case, (log_s, corner, (x, y, z)))| {
        let shift = corner * DVec3::new(x, y, z).normalize_or(DVec3::X);
        let s = 10f64.powf(log_s);
        let size = s * bbox(&case.u).max(bbox(&case.v));
        // Input rounding at |shift| bends planes by up to ε |shift| / size.
        let slack = (64.0 * f64::EPSILON * corner / size).max(1e-9);
        let design = Design {
            guide_u: placed(&case.design.guide_u, s, shift),
            guide_v: placed(&case.design.guide_v, s, shift),
            tolerance: Some(Tolerances {
                planarity: slack,
                angle: slack,
                start: slack,
            }),
            ..case.design.clone()
        };
        let Ok(g) = generate(&design, &GenerateOptions::default()) else {
            return Err(TestCaseError::reject("invalid or degenerate"));
        };
        if g.report.folded_faces > 0 || g.report.min_crossing.sine < 1e-2 {
            return Err(TestCaseError::reject("folded or nearly pinched"));
        }
        let grid = &g.grid;
        let m = measure(grid);
        let mut own: f64 = 0.0;
        for i in 0..grid.rows - 1 {
            for j in 0..grid.cols - 1 {
                let q = grid.face(i, j);
                let o = q[0];
                own = own.max(own_face_planarity(&q.map(|p| p - o)) / m.scale);
            }
        }
        let err = own
            .max(m.circularity.value)
            .max(m.row_planarity.value)
            .max(m.column_planarity.value);
        let ulps = (err - TOL).max(0.0) * m.scale / ulp(corner).max(f64::MIN_POSITIVE);
        let label = format!("{} s={s:.1e} corner={corner:e}: {err:.2e}", case.label);
        if ulps > worst.borrow().0 {
            *worst.borrow_mut() = (ulps, label.clone());
        }
        prop_assert!(err <= TOL + 4.0 * ulp(corner) / m.scale, "{label}");
        Ok(())
    });
    let (ulps, label) = worst.into_inner();
    eprintln!("far from the origin: worst excess over 1e-9 {ulps:.2} ulps of the corner [{label}]");
    if let Err(e) = result {
        panic!("{e}");
    }
}
