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

use glam::DVec3;
use monge_core::design::BSplineSpec;
use monge_core::developable::{developable, DevelopableSpec};
use monge_core::grid::{bbox_diagonal, origin_ratio};
use monge_core::{generate, Design, GenerateOptions, GuideSpec, QuadGrid, Tolerances};
use nalgebra::{DMatrix, Vector2};

/// Where every property must hold (relative to the size) when f64 can hold it.
const TOL: f64 = 1e-9;

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
    GuideSpec {
        bspline: Some(BSplineSpec {
            degree: 3,
            control_points: points
                .iter()
                .map(|p| (size / 9.0 * DVec3::from_array(*p) + corner).to_array())
                .collect(),
            knots: None,
            weights: None,
            samples: 81,
        }),
        ..Default::default()
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

/// ulp of `x`.
fn ulp(x: f64) -> f64 {
    if x == 0.0 {
        0.0
    } else {
        (f64::from_bits(x.to_bits() + 1) - x).abs()
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
            let g = developable(&spec).unwrap().grid;
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
