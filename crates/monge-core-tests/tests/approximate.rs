//! `approximate` (monge's extension of the method, related to §4.7/§4.8): recovery of a
//! surface with planar curvature lines, the deviation from a non-PCL target (an
//! elliptic paraboloid), a sphere cap (umbilic everywhere), refusal of flat targets, and every
//! error; every deviation measured independently by brute force (every triangle of the
//! mesh, another point-triangle formula, not the library's spatial index).

use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use glam::DVec3;
use monge_core::approximate::{
    approximate, approximate_until, ApproxError, ApproxOptions, Approximation, TargetCloud,
};
use monge_core::measure::measure;
use monge_core::{generate, Design, GenerateOptions, GuideSpec, QuadGrid};

use crate::common;
use crate::heldout::Rng;
use common::{design, triangle_distance};

/// A deterministic noise in [−1, 1): the first draw of the held-out targets' stream
/// seeded with `k`.
fn noise(k: u64) -> f64 {
    2.0 * Rng::new(k).uniform() - 1.0
}

/// The 10 m roof of `examples/targets/roof.design.json` (arbitrary mode, §3.2).
fn roof(samples: usize) -> Design {
    design(
        50.0,
        GuideSpec::bspline(
            3,
            vec![
                [0.0; 3],
                [2.5, 0.0, 0.0],
                [5.0, 0.0, 1.2],
                [7.5, 0.0, 3.0],
                [10.0, 0.0, 4.5],
            ],
            samples,
        ),
        GuideSpec::bspline(
            3,
            vec![
                [0.0; 3],
                [0.0, 2.5, 0.0],
                [0.3, 5.0, 0.9],
                [1.6 / 3.0, 7.5, 1.6],
                [2.0 / 3.0, 10.0, 2.0],
            ],
            samples,
        ),
    )
}

/// Distance from `p` to the nearest triangle of `grid` (every face, two triangles each).
fn brute_to_mesh(p: DVec3, grid: &QuadGrid) -> f64 {
    let mut best = f64::INFINITY;
    for i in 0..grid.rows - 1 {
        for j in 0..grid.cols - 1 {
            let [a, b, c, d] = grid.face(i, j);
            for (x, y, z) in [(a, b, c), (a, c, d)] {
                best = best.min(triangle_distance(p, [x, y, z]));
            }
        }
    }
    best
}

/// Largest and RMS distance from `points` to `grid` ([`brute_to_mesh`]), relative to
/// `size`.
fn to_mesh(points: &[DVec3], grid: &QuadGrid, size: f64) -> (f64, f64) {
    max_rms(points.iter().map(|p| brute_to_mesh(*p, grid) / size))
}

/// Largest and RMS of `values`.
fn max_rms(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let v: Vec<f64> = values.collect();
    let max = v.iter().copied().fold(0.0, f64::max);
    (
        max,
        (v.iter().map(|x| x * x).sum::<f64>() / v.len() as f64).sqrt(),
    )
}

/// The roof at `samples` × `samples` vertices, its size, and its vertices noised by 1e-4
/// of it.
fn noised_roof(samples: usize) -> (QuadGrid, f64, Vec<DVec3>) {
    let fine = generate(&roof(samples), &GenerateOptions::default())
        .unwrap()
        .grid;
    let size = fine.bbox_diagonal();
    let target = fine
        .vertices
        .iter()
        .enumerate()
        .map(|(k, v)| {
            let k = 3 * k as u64;
            *v + 1e-4 * size * DVec3::new(noise(k), noise(k + 1), noise(k + 2))
        })
        .collect();
    (fine, size, target)
}

/// The mesh of `design` with its B-spline guides sampled at `samples` points: the
/// surface found, regenerated finer, so that comparisons are of surfaces, not of the
/// faces' sag.
fn finer(design: &Design, samples: usize) -> QuadGrid {
    let mut design = design.clone();
    for guide in [&mut design.guide_u, &mut design.guide_v] {
        let GuideSpec::BSpline { bspline, .. } = guide else {
            panic!("a B-spline guide");
        };
        bspline.samples = samples;
    }
    generate(&design, &GenerateOptions::default()).unwrap().grid
}

/// Small, quick options for the test suite (debug builds).
fn quick(faces: usize) -> ApproxOptions {
    ApproxOptions {
        faces: (faces, faces),
        starts: 2,
        max_evaluations: 300,
        ..Default::default()
    }
}

#[test]
fn a_noised_surface_with_planar_curvature_lines_is_recovered() {
    let (_, size, target) = noised_roof(31);
    let r = approximate(&target, &quick(10), &mut |_| {}).unwrap();
    // Independent: both ways against the exact surface the target was sampled from, as
    // meshes of 40 × 40 faces (the result's design regenerated finer, so that the
    // comparison is of the surfaces, not of the 10 × 10 faces' sag), by brute force.
    let truth = generate(&roof(41), &GenerateOptions::default())
        .unwrap()
        .grid;
    let result = finer(&r.design, 41);
    let (to_max, to_rms) = to_mesh(&result.vertices, &truth, size);
    let (from_max, from_rms) = to_mesh(&truth.vertices, &result, size);
    // And the 10 × 10 mesh's own vertices.
    let (coarse_max, _) = to_mesh(&r.grid.vertices, &truth, size);
    eprintln!(
        "recovery: surface found → surface max {to_max:.2e} RMS {to_rms:.2e}, surface → surface \
         found max {from_max:.2e} RMS {from_rms:.2e}; 10 × 10 vertices → surface max \
         {coarse_max:.2e} (initial guess: {:?}, result {:?})",
        r.before, r.after
    );
    // The bound: recovered to 1e-3 of the size, both ways (measured 2026-11-25
    // with these quick settings: 8.7e-4 and 1.5e-4, RMS 1.4e-4 and 5e-5).
    assert!(
        to_max <= 1e-3 && from_max <= 1e-3 && coarse_max <= 1e-3,
        "max {to_max:e} {from_max:e} {coarse_max:e}"
    );
    assert!(
        to_rms <= 3e-4 && from_rms <= 3e-4,
        "RMS {to_rms:e} {from_rms:e}"
    );
    // The search never ends worse than it started (its objective, on the full grid).
    assert!(r.objective.1 <= r.objective.0, "{:?}", r.objective);
    // Exact: it is generated, and the measure module says so independently.
    assert!(measure(&r.grid).max_error() <= 1e-9);
}

/// `count` random points of the roof (sampled on 61 × 61 vertices, each point at random
/// parameters inside a random face, by bilinear interpolation: the faces are planar), each
/// coordinate noised by up to 1e-4 of the size: a scan, whose outermost points stop short
/// of the roof's edges by the gaps of a random sampling. The exact roof, its size and the scan.
fn scanned_roof(count: usize) -> (QuadGrid, f64, Vec<DVec3>) {
    let truth = generate(&roof(61), &GenerateOptions::default())
        .unwrap()
        .grid;
    let size = truth.bbox_diagonal();
    let scan = (0..count as u64)
        .map(|k| {
            let (s, t) = (30.0 * (noise(5 * k) + 1.0), 30.0 * (noise(5 * k + 1) + 1.0));
            let (i, j) = ((s as usize).min(59), (t as usize).min(59));
            let (a, b) = (s - i as f64, t - j as f64);
            let p = (1.0 - a) * ((1.0 - b) * truth.vertex(i, j) + b * truth.vertex(i, j + 1))
                + a * ((1.0 - b) * truth.vertex(i + 1, j) + b * truth.vertex(i + 1, j + 1));
            let n = DVec3::new(noise(5 * k + 2), noise(5 * k + 3), noise(5 * k + 4));
            p + 1e-4 * size * n
        })
        .collect();
    (truth, size, scan)
}

#[test]
fn a_random_scan_is_recovered_to_its_edges() {
    // 1 500 random points: their outermost points lie inside the roof's edges by about a
    // spacing (1/√1500 of the side) here and there, which the search used to copy.
    let (truth, size, scan) = scanned_roof(1500);
    let r = approximate(&scan, &quick(10), &mut |_| {}).unwrap();
    let result = finer(&r.design, 41);
    // Both ways against the exact roof, by brute force, every third vertex of it.
    let (to_max, _) = to_mesh(&result.vertices, &truth, size);
    let (from_max, _) = max_rms(
        truth
            .vertices
            .iter()
            .step_by(3)
            .map(|v| brute_to_mesh(*v, &result) / size),
    );
    eprintln!("scan: found → roof max {to_max:.2e}, roof → found max {from_max:.2e}");
    // The mesh reaches the roof's edges (measured with these quick settings, 10 × 10
    // faces: 5.6e-4), and overhangs them little (2.8e-3, at a corner).
    assert!(from_max <= 1e-3, "roof → found {from_max:e}");
    assert!(to_max <= 4e-3, "found → roof {to_max:e}");
    assert!(r.objective.1 <= r.objective.0, "{:?}", r.objective);
}

#[test]
fn the_same_target_gives_the_same_design_twice() {
    // The starts and the Jacobian's columns run in parallel; the result must not depend
    // on the threads: the same bytes every time.
    let (_, _, target) = noised_roof(16);
    let run = || {
        let r = approximate(&target, &quick(8), &mut |_| {}).unwrap();
        let bits: Vec<u64> = r
            .grid
            .vertices
            .iter()
            .flat_map(|v| v.to_array().map(f64::to_bits))
            .collect();
        (
            serde_json::to_string(&r.design).unwrap(),
            bits,
            r.evaluations,
        )
    };
    let first = run();
    for _ in 0..2 {
        assert_eq!(run(), first);
    }
}

/// Approximates the height field `f` over [0, 10]², sampled on 21 × 21 points, with the
/// quick settings; the largest distance from the result's vertices to the surface over
/// that plan and the largest and RMS distances from the target points to the result's
/// faces (brute force), all relative to the target's size.
fn height_field_fit(name: &str, f: &dyn Fn(f64, f64) -> f64) -> (f64, f64, f64) {
    height_field_fit_over(name, f, 10.0)
}

/// [`height_field_fit`] over a 10 × `depth` plan.
fn height_field_fit_over(name: &str, f: &dyn Fn(f64, f64) -> f64, depth: f64) -> (f64, f64, f64) {
    height_field_fit_on(name, f, [0.0, 0.0], [10.0, depth])
}

/// [`height_field_fit`] over the plan from `low` to `high` (21 × 21 points).
fn height_field_fit_on(
    name: &str,
    f: &dyn Fn(f64, f64) -> f64,
    low: [f64; 2],
    high: [f64; 2],
) -> (f64, f64, f64) {
    let target: Vec<DVec3> = (0..21 * 21)
        .map(|k| {
            let (x, y) = (
                low[0] + (k % 21) as f64 * (high[0] - low[0]) / 20.0,
                low[1] + (k / 21) as f64 * (high[1] - low[1]) / 20.0,
            );
            DVec3::new(x, y, f(x, y))
        })
        .collect();
    let size = monge_core::grid::bbox_diagonal(&target);
    let r = approximate(&target, &quick(10), &mut |_| {}).unwrap();
    // Both ways by brute force: the mesh's vertices to the surface over its plan (a fine
    // triangulation of it, so that a vertex beyond the plan's edge counts by how far it
    // overhangs it), the target's points to the mesh.
    let m = 81;
    let fine: Vec<DVec3> = (0..m * m)
        .map(|k| {
            let (x, y) = (
                low[0] + (k % m) as f64 * (high[0] - low[0]) / (m - 1) as f64,
                low[1] + (k / m) as f64 * (high[1] - low[1]) / (m - 1) as f64,
            );
            DVec3::new(x, y, f(x, y))
        })
        .collect();
    let surface = QuadGrid::new(m, m, fine, vec![DVec3::Z; m * m]);
    let (to_max, _) = to_mesh(&r.grid.vertices, &surface, size);
    let (from_max, from_rms) = to_mesh(&target, &r.grid, size);
    eprintln!(
        "{name}: mesh → surface max {to_max:.2e}; target → mesh max {from_max:.2e} RMS {from_rms:.2e}"
    );
    assert!(measure(&r.grid).max_error() <= 1e-9);
    // Never worse than the initial guess, even where one patch cannot follow the target.
    assert!(r.objective.1 <= r.objective.0, "{name}: {:?}", r.objective);
    (to_max, from_max, from_rms)
}

#[test]
fn an_elliptic_paraboloid_gets_a_measured_bounded_deviation() {
    let (to_max, from_max, from_rms) =
        height_field_fit("paraboloid", &|x, y| 0.04 * x * x + 0.1 * y * y);
    // Measured with the quick settings: max 1.0e-1 / 5.3e-2, RMS 1.4e-2 (the mesh's
    // sides overhang the plan's edges; measured to the height field extended beyond
    // them, the mesh → surface largest distance read 2.4e-2).
    assert!(
        to_max <= 0.12 && from_max <= 0.1 && from_rms <= 2e-2,
        "{to_max:e} {from_max:e} {from_rms:e}"
    );
}

#[test]
fn a_hyperbolic_paraboloid_gets_a_measured_bounded_deviation() {
    // Negative curvature everywhere, no planar curvature lines.
    let (to_max, from_max, from_rms) = height_field_fit("hyperbolic paraboloid", &|x, y| {
        0.03 * (x - 5.0) * (y - 5.0)
    });
    // Measured with the quick settings: max 1.0e-1 / 1.1e-1, RMS 3.1e-2 (8.0e-2 /
    // 1.0e-1, RMS 2.8e-2 when BOBYQA polished the stalled least squares, in place of
    // the θ restarts, five times as long); before the boundary start took the target's
    // true corners, 3.0e-1 / 8.6e-2 (its sides overhung the plan by 0.3 of the size,
    // which the height field extended beyond the plan did not count: it read 3.7e-2).
    assert!(
        to_max <= 0.12 && from_max <= 0.16 && from_rms <= 3.5e-2,
        "{to_max:e} {from_max:e} {from_rms:e}"
    );
}

#[test]
fn a_dome_whose_edges_lie_flat_gets_a_start_along_its_edges() {
    // The commonest roof: a bicubic Bézier dome over a 10 × 8 plan, its boundary control
    // points at height 0 (its four edges straight, at z = 0) and its four inner ones at
    // 1.5. Its corners are saddles (their principal directions along the diagonals).
    let dome = |x: f64, y: f64| {
        let (u, v) = (x / 10.0, y / 8.0);
        13.5 * u * (1.0 - u) * v * (1.0 - v)
    };
    let (to_max, from_max, from_rms) = height_field_fit_over("flat-edge dome", &dome, 8.0);
    // Measured with the quick settings: max 2.2e-2 / 2.4e-2, RMS 7.4e-3 (from the
    // corners' own quadrics and the boundary alone, along the diagonals: max 6.6e-2 /
    // 2.6e-1, RMS 6.2e-2).
    assert!(to_max <= 0.04 && from_max <= 0.05 && from_rms <= 0.015);
}

#[test]
fn a_freeform_bezier_patch_gets_a_measured_bounded_deviation() {
    // A bicubic Bézier patch (a NURBS patch of degree 3 with unit weights) over
    // [0, 10]², heights of its 4 × 4 control points chosen by hand.
    const HEIGHTS: [[f64; 4]; 4] = [
        [0.0, 1.0, 1.5, 1.0],
        [0.8, 2.5, 3.0, 2.0],
        [1.2, 3.0, 4.0, 2.6],
        [0.6, 2.2, 2.8, 1.4],
    ];
    let bernstein = |t: f64| {
        let s = 1.0 - t;
        [s * s * s, 3.0 * s * s * t, 3.0 * s * t * t, t * t * t]
    };
    let patch = |x: f64, y: f64| {
        let (bu, bv) = (bernstein(x / 10.0), bernstein(y / 10.0));
        (0..4)
            .flat_map(|i| (0..4).map(move |j| (i, j)))
            .map(|(i, j)| bu[i] * bv[j] * HEIGHTS[i][j])
            .sum()
    };
    let (to_max, from_max, from_rms) = height_field_fit("Bézier patch", &patch);
    // Measured 2026-11-25 with the quick settings: max 6.5e-2 / 3.5e-1, RMS 8.2e-2: one
    // patch does not follow this target (its rows crowd into a corner and a third of
    // the target's extent stays uncovered); `monge approximate` says so.
    assert!(to_max <= 0.09 && from_max <= 0.45 && from_rms <= 0.11);
}

#[test]
fn the_library_distances_equal_brute_force() {
    let fine = generate(&roof(21), &GenerateOptions::default())
        .unwrap()
        .grid;
    let coarse = generate(
        &Design {
            theta_deg: 60.0,
            ..roof(9)
        },
        &GenerateOptions::default(),
    )
    .unwrap()
    .grid;
    let cloud = TargetCloud::new(&fine.vertices).unwrap();
    let d = cloud.deviation(&coarse);
    let size = cloud.size();
    let (max, rms) = to_mesh(&fine.vertices, &coarse, size);
    assert!(
        (d.target_to_mesh_max - max).abs() <= 1e-12 && (d.target_to_mesh_rms - rms).abs() <= 1e-12
    );
}

#[test]
fn a_sphere_cap_umbilic_everywhere_is_fitted() {
    // A sphere's principal directions are nowhere defined: the corners' quadrics give no
    // start, the sides of its square plan, its boundary and its whole quadric do.
    let radius = 2.0;
    let cap: Vec<DVec3> = (0..400)
        .map(|k| {
            let (a, b) = ((k % 20) as f64 / 19.0 - 0.5, (k / 20) as f64 / 19.0 - 0.5);
            DVec3::new(a, b, (radius * radius - a * a - b * b).sqrt())
        })
        .collect();
    let size = monge_core::grid::bbox_diagonal(&cap);
    let r = approximate(&cap, &quick(8), &mut |_| {}).unwrap();
    // Independently: the result's vertices' distance to the sphere, and the target's to
    // the result's faces (brute force).
    let (to_max, _) = max_rms(
        r.grid
            .vertices
            .iter()
            .map(|v| (v.length() - radius).abs() / size),
    );
    let (from_max, _) = to_mesh(&cap, &r.grid, size);
    eprintln!("sphere cap: mesh → sphere max {to_max:.2e}, cap → mesh max {from_max:.2e}");
    // Measured with the quick settings: 1.7e-6 and 1.6e-3 (the cap's points to the 8 × 8
    // faces, their sag included).
    assert!(
        to_max <= 1e-4 && from_max <= 3e-3,
        "{to_max:e} {from_max:e}"
    );
}

#[test]
fn every_error_is_triggered() {
    let plane: Vec<DVec3> = (0..100)
        .map(|k| DVec3::new((k % 10) as f64, (k / 10) as f64, 0.0))
        .collect();
    let run = |points: &[DVec3], options: &ApproxOptions| {
        approximate(points, options, &mut |_| {}).unwrap_err()
    };
    assert!(matches!(
        run(&plane[..10], &quick(8)),
        ApproxError::TooFewPoints { found: 10, .. }
    ));
    let mut bad = plane.clone();
    bad[7].y = f64::NAN;
    assert!(matches!(
        run(&bad, &quick(8)),
        ApproxError::NotFinite { index: 7, .. }
    ));
    assert_eq!(run(&plane, &quick(3)), ApproxError::GridTooSmall(3, 3));
    // Once "no design found can be generated without folds", after the whole search.
    let limit = GenerateOptions::default().max_vertices;
    assert_eq!(
        run(&plane, &quick(100_000)),
        ApproxError::GridTooLarge(100_000, 100_000, limit)
    );
    // Points of size 1e160 once kept the search running past its time limit.
    for scale in [1e160, 1e-120] {
        let scaled: Vec<DVec3> = plane.iter().map(|p| *p * scale).collect();
        assert!(matches!(
            run(&scaled, &quick(8)),
            ApproxError::ScaleOutOfRange { .. }
        ));
    }
    assert!(matches!(run(&plane, &quick(8)), ApproxError::Flat { .. }));
    let target = generate(&roof(11), &GenerateOptions::default())
        .unwrap()
        .grid
        .vertices;
    let past = ApproxOptions {
        deadline: Some(Instant::now()),
        ..quick(8)
    };
    assert_eq!(run(&target, &past), ApproxError::TimeLimit);
    // Five points along one side of every corner: too few to fit a boundary guide.
    let mut short = roof(11);
    let GuideSpec::BSpline { bspline, .. } = &mut short.guide_u else {
        panic!("a B-spline guide");
    };
    bspline.samples = 5;
    let target = generate(&short, &GenerateOptions::default())
        .unwrap()
        .grid
        .vertices;
    let keep = ApproxOptions {
        keep_boundary: true,
        ..quick(8)
    };
    assert_eq!(run(&target, &keep), ApproxError::NoBoundary);
    // A half cylinder's straight edges as guides: no design can be generated.
    let cylinder: Vec<DVec3> = (0..31 * 31)
        .map(|k| {
            let (a, y) = (0.3 + 2.5 * (k % 31) as f64 / 30.0, (k / 31) as f64 / 3.0);
            DVec3::new(5.0 * a.cos(), y, 5.0 * a.sin())
        })
        .collect();
    assert_eq!(run(&cylinder, &keep), ApproxError::NoStart);
}

/// Distance from `p` to the polyline `line`.
fn to_polyline(p: DVec3, line: &[DVec3]) -> f64 {
    line.windows(2)
        .map(|w| {
            let e = w[1] - w[0];
            let t = ((p - w[0]).dot(e) / e.length_squared()).clamp(0.0, 1.0);
            p.distance(w[0] + t * e)
        })
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn keep_boundary_keeps_the_targets_boundary_curves_as_guides() {
    let (fine, size, target) = noised_roof(31);
    let options = ApproxOptions {
        keep_boundary: true,
        ..quick(10)
    };
    let r = approximate(&target, &options, &mut |_| {}).unwrap();
    // The result's guides (its row 0 and column 0) on the truth's boundary, whose four
    // sides are its first and last rows and columns.
    let sides: Vec<Vec<DVec3>> = vec![
        fine.row(0).collect(),
        fine.row(fine.rows - 1).collect(),
        fine.column(0).collect(),
        fine.column(fine.cols - 1).collect(),
    ];
    let to_boundary = |p: DVec3| {
        sides
            .iter()
            .map(|s| to_polyline(p, s))
            .fold(f64::INFINITY, f64::min)
            / size
    };
    let worst = r
        .grid
        .row(0)
        .chain(r.grid.column(0))
        .map(to_boundary)
        .fold(0.0, f64::max);
    // The whole surface near the truth too (θ is searched).
    let (to_max, _) = to_mesh(&r.grid.vertices, &fine, size);
    eprintln!("keep boundary: guides to the boundary {worst:.2e}, mesh → surface {to_max:.2e}");
    // Measured 2026-11-25: 5.5e-4 and 6.0e-4 of the size.
    assert!(worst <= 1e-3, "{worst:e}");
    assert!(to_max <= 2e-3, "{to_max:e}");
    assert!(measure(&r.grid).max_error() <= 1e-9);
}

#[test]
fn a_time_limit_keeps_the_best_design_found_so_far() {
    // The limit is reached after a given number of meshes, not after a time: the same
    // stop whatever the machine's speed. One start: one order of the meshes.
    let (_, _, target) = noised_roof(16);
    let options = ApproxOptions {
        starts: 1,
        max_evaluations: 60,
        ..quick(8)
    };
    let objective = |r: &Approximation| r.objective.1;
    let stopped_after = |meshes: usize| {
        let asked = AtomicUsize::new(0);
        let stop = || asked.fetch_add(1, Ordering::Relaxed) >= meshes;
        approximate_until(&target, &options, &stop, &mut |_| {})
    };
    // Unstopped: the meshes of the scan and the coarse start (counted at the first
    // progress), then those of the refinement.
    let mut first_progress = None;
    let full = approximate_until(&target, &options, &|| false, &mut |p| {
        first_progress.get_or_insert(p.evaluations);
    })
    .unwrap();
    let refinement_from = first_progress.unwrap();
    assert!(!full.timed_out && full.starts == 1);
    assert!(refinement_from < full.evaluations);
    // Before any mesh: nothing to keep.
    assert_eq!(stopped_after(0).unwrap_err(), ApproxError::TimeLimit);
    // During the scan, the start; during the coarse search, its best so far; during
    // the refinement, its best so far. Each exact, and never worse than an earlier stop.
    let mut previous = f64::INFINITY;
    for meshes in [
        refinement_from / 4,
        refinement_from + 1,
        (refinement_from + full.evaluations) / 2,
    ] {
        let r = stopped_after(meshes).unwrap();
        assert!(r.timed_out, "stopped after {meshes} meshes");
        assert_eq!(r.evaluations, meshes);
        assert_eq!(r.starts, usize::from(meshes > refinement_from));
        let error = measure(&r.grid).max_error();
        assert!(error <= 1e-9, "{error:e} after {meshes} meshes");
        let f = objective(&r);
        assert!(f.is_finite(), "{:?}", r.after);
        if meshes > refinement_from {
            assert!(
                f <= previous,
                "{f:e} after {meshes} meshes, {previous:e} before"
            );
            previous = f;
        }
    }
    assert!(objective(&full) <= previous);
}

#[test]
fn a_scans_noise_is_averaged_out_of_the_distance_and_a_meshs_own_vertices_are_on_it() {
    let torus = crate::heldout::target("torus patch");
    // Vertices exactly on the torus (at distance 0 from it), away from its edges,
    // measured against a scan of it noised by 1e-4 of its size: the quadric around each
    // nearest point averages its neighbours' noise; measured through the point itself,
    // it would carry that point's noise whole (RMS about 1e-4 of the size).
    let exact = torus.grid(41);
    let inner: Vec<DVec3> = (0..41 * 41)
        .filter(|k| (5..36).contains(&(k / 41)) && (5..36).contains(&(k % 41)))
        .map(|k| exact[k])
        .collect();
    let grid = QuadGrid::new(31, 31, inner, vec![DVec3::Z; 31 * 31]);
    let scan = TargetCloud::new(&torus.scan(2000, 1e-4, 7)).unwrap();
    let (max, rms) = max_rms(scan.distances(&grid).iter().map(|d| d / scan.size()));
    eprintln!("exact vertices → noised scan: max {max:.2e} RMS {rms:.2e}");
    assert!(rms <= 5e-5, "RMS {rms:e}");
    // The torus's own vertices as the target: they are on it.
    let mesh = TargetCloud::new(&exact).unwrap();
    let grid = QuadGrid::new(41, 41, exact.clone(), vec![DVec3::Z; exact.len()]);
    let (max, _) = max_rms(mesh.distances(&grid).iter().map(|d| d / mesh.size()));
    eprintln!("exact vertices → themselves: max {max:.2e}");
    assert!(max <= 1e-12, "max {max:e}");
}

/// A moulding surface (§4.1.2): the planar rail `(s, 0.3 s², 0)` and, in its normal
/// planes, the profile `(0.8 t, 0.5 (1 − t²) + 0.2 t³)` (the first held-out target's),
/// scaled by 10 and sampled on `n × n` parameters, and its point at `(s, t)`.
fn moulding(s: f64, t: f64) -> DVec3 {
    let tangent = DVec3::new(1.0, 0.6 * s, 0.0).normalize();
    let normal = DVec3::new(-tangent.y, tangent.x, 0.0);
    10.0 * (DVec3::new(s, 0.3 * s * s, 0.0)
        + 0.8 * t * normal
        + (0.5 * (1.0 - t * t) + 0.2 * t * t * t) * DVec3::Z)
}

/// θ of a design up to the Gauss map's symmetries (−θ, 180° − θ), in [0°, 90°].
fn folded(theta_deg: f64) -> f64 {
    let t = theta_deg.rem_euclid(180.0);
    t.min(180.0 - t)
}

#[test]
fn a_moulding_is_recovered_with_theta_zero() {
    // A moulding's rail lies level, off the surface's normal by the profile's slope (63°
    // at one edge): its guide plane is tilted, θ = 0° (or 180°) is an end of the
    // admissible range. Its corners' normal sections, scanned every 10°, missed it
    // (2.0e-1 of its size off, θ 57° off); its curvature lines give its own guides.
    let samples = |n: usize| -> Vec<DVec3> {
        (0..n * n)
            .map(|k| {
                let (s, t) = ((k / n) as f64, (k % n) as f64);
                moulding(
                    2.0 * s / (n - 1) as f64 - 1.0,
                    2.0 * t / (n - 1) as f64 - 1.0,
                )
            })
            .collect()
    };
    let target = samples(21);
    let size = monge_core::grid::bbox_diagonal(&target);
    let r = approximate(&target, &quick(10), &mut |_| {}).unwrap();
    // Independently: the result's vertices to the closed form's fine triangulation, the
    // target's points to the result's faces, by brute force.
    let m = 81;
    let truth = QuadGrid::new(m, m, samples(m), vec![DVec3::Z; m * m]);
    // The design found regenerated finer (40 × 40 faces), so that the comparison is of
    // the surfaces, not of the 10 × 10 faces' sag.
    let result = finer(&r.design, 41);
    let (to_max, _) = to_mesh(&result.vertices, &truth, size);
    let (from_max, _) = to_mesh(&target, &result, size);
    let theta = folded(r.design.theta_deg);
    eprintln!("moulding: mesh → target {to_max:.2e}, target → mesh {from_max:.2e}, θ {theta:.3}°");
    // Measured with the quick settings (10 × 10 faces, 300 meshes a run): 4.5e-4 and
    // 1.5e-3, θ 0.05° (the held-out measurement, 40 × 40 faces: within 2e-4).
    assert!(
        to_max <= 1e-3 && from_max <= 2e-3,
        "{to_max:e} {from_max:e}"
    );
    assert!(theta <= 0.5, "θ {theta}");
}

/// The held-out target `name` approximated from `sample` of it (its mesh or a scan) with
/// `options`, measured independently: the design regenerated at 40 × 40 faces against
/// the closed form's fine triangulation, both ways by brute force, and θ folded.
fn held_out_fit(
    name: &str,
    sample: impl Fn(&crate::heldout::Target) -> Vec<DVec3>,
    options: &ApproxOptions,
) -> (f64, f64, f64) {
    use crate::heldout::{fold_theta, max_both_ways, target};
    let target = target(name);
    let r = approximate(&sample(&target), options, &mut |_| {}).unwrap();
    let (to_max, from_max) = max_both_ways(&target, &finer(&r.design, 41));
    let theta = fold_theta(r.design.theta_deg);
    eprintln!("{name}: mesh → target {to_max:.2e}, target → mesh {from_max:.2e}, θ {theta:.3}°");
    (to_max, from_max, theta)
}

#[test]
fn an_onion_domes_side_is_recovered_from_its_own_corner() {
    // The held-out onion dome's side (a surface of revolution cut along its curvature
    // lines, θ = 0°), rotated and far from the origin, every vertex of a 41 × 41 mesh.
    // Its meridians bulge out halfway up, where the boundary start had taken its corner:
    // it traced one side both ways and the search settled away from θ = 0° (here 3.9e-2
    // of the size off, θ 1.7°; the held-out measurement at 40 × 40 faces: 4.0e-2, θ 12°).
    let (to_max, from_max, theta) = held_out_fit("onion dome", |t| t.grid(41), &quick(20));
    // Measured with 20 × 20 faces: 8.6e-4 and 4.3e-4, θ 0.000°.
    assert!(
        to_max <= 1e-3 && from_max <= 1e-3,
        "{to_max:e} {from_max:e}"
    );
    assert!(theta <= 0.5, "θ {theta}");
}

#[test]
fn a_scanned_moulding_comes_back_a_moulding() {
    // The held-out sine moulding (θ = 0°) scanned: 2 000 random points noised by 1e-4 of
    // its size. With θ free its fit settled at θ 2.7° (θ 177.3°), 6.2e-4 / 1.6e-3 of the
    // size from the surface: near an end of its range θ moves by degrees for a small gain.
    let (to_max, from_max, theta) = held_out_fit(
        "sine moulding",
        |t| t.scan(2000, 1e-4, 7),
        &ApproxOptions::default(),
    );
    // Measured: 9.9e-4 and 1.5e-3, θ 0.000°.
    assert!(theta <= 0.5, "θ {theta}");
    assert!(
        to_max <= 2e-3 && from_max <= 2e-3,
        "{to_max:e} {from_max:e}"
    );
}

#[test]
fn scans_of_a_moulding_are_recovered_whatever_their_sampling() {
    // The held-out moulding (θ = 0°) scanned with other random samplings than the tests'
    // (2 000 points noised by 1e-4 of its size): every start but the boundary's fell off
    // the target, and the boundary start folded at every θ, its guides tied into loops
    // through the scan's outermost points (2.3e-1 to 3.7e-1 of the size off, measured
    // both ways; seeds 3, 4 and 8 of eight).
    for seed in [4, 8] {
        let (to_max, from_max, _) = held_out_fit(
            "moulding",
            |t| t.scan(2000, 1e-4, seed),
            &ApproxOptions::default(),
        );
        // Measured: 2.8e-3 and 3.2e-3 (the scan's edges, set by its outermost points).
        assert!(
            to_max <= 5e-3 && from_max <= 5e-3,
            "seed {seed}: {to_max:e} {from_max:e}"
        );
    }
}

#[test]
fn scans_whose_boundary_traced_step_by_step_folds_are_started_from_it_traced_along_chords() {
    // Two held-out scans (2 000 points noised by 1e-4 of the size, seed 14) on which the
    // boundary traced step by step through the outermost points turned off the boundary
    // at every corner (a point far out to one side turned each step): their boundary
    // starts folded at every θ, the other starts led the least squares off the target,
    // 4.1e-1 (the torus patch, θ 76°) and 6.1e-1 (the onion dome, θ 59°) of the size off,
    // measured both ways. Traced again along the chord of three steps, the boundary
    // starts hold.
    for name in ["torus patch", "onion dome"] {
        let (to_max, from_max, theta) =
            held_out_fit(name, |t| t.scan(2000, 1e-4, 14), &ApproxOptions::default());
        // Measured: 3.6e-3 (the torus patch) and 3.2e-3 (the onion dome), θ 0°.
        assert!(
            to_max <= 5e-3 && from_max <= 5e-3,
            "{name}: {to_max:e} {from_max:e}"
        );
        assert!(theta <= 0.5, "{name}: θ {theta}");
    }
}

#[test]
fn a_scanned_onion_dome_whose_coarse_fit_folds_on_the_full_grid_is_recovered() {
    // The held-out onion dome scanned with a sampling (seed 4) whose best coarse design
    // (5.9e-4 RMS, θ 1.3°) folds two faces on the full grid: the search fell back to its
    // start and settled at θ 5.7°, 2.0e-2 of the size off (measured both ways).
    let (to_max, from_max, theta) = held_out_fit(
        "onion dome",
        |t| t.scan(2000, 1e-4, 4),
        &ApproxOptions::default(),
    );
    // Measured: 2.7e-3 and 3.6e-3, θ 0.000° (1.1e-3 and 1.0e-3 before the least squares
    // counted the scan's points the mesh leaves uncovered, which brought 8 more of 120
    // held-out scans within 1e-3; this sampling's corners it left farther).
    assert!(
        to_max <= 5e-3 && from_max <= 5e-3,
        "{to_max:e} {from_max:e}"
    );
    assert!(theta <= 0.5, "θ {theta}");
}

#[test]
fn a_shallow_dome_of_revolution_is_not_refused_and_is_fitted() {
    // A paraboloid of revolution over a square plan, its axis off the centre (rise 0.31
    // over a span of 2): its centre and one corner are umbilic to 5 %, which refused it.
    let dome = |x: f64, y: f64| -0.1 * ((x - 0.3).powi(2) + (y + 0.2).powi(2));
    let (to_max, from_max, _) =
        height_field_fit_on("dome of revolution", &dome, [-1.0, -1.0], [1.0, 1.0]);
    // Measured with the quick settings: 1.2e-2 (a corner overhangs the plan: its edges
    // are not curvature lines) and 1.4e-3 (the target's points to the 10 × 10 faces,
    // their sag included).
    assert!(
        to_max <= 1.5e-2 && from_max <= 3e-3,
        "{to_max:e} {from_max:e}"
    );
}
