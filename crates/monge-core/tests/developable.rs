//! Developable circular meshes with planar curvature lines (§3.3, Figure 11),
//! measured independently of their construction: isosceles trapezoid faces
//! around the meeting point of two rows (computed here from the rows alone),
//! `measure` (planar, circular faces, planar rows and columns, torsion-free unit
//! node axes), columns in their cutting planes, helix segments at slope α; one
//! test per error variant; a property test over random projection curves.

use std::f64::consts::TAU;

use glam::DVec3;
use monge_core::developable::{
    developable, DevelopableError, DevelopableMesh, DevelopableSpec, Field,
};
use monge_core::measure::measure;
use monge_core::offset::vertex_offset;
use monge_core::{GenerateError, GenerateOptions, QuadGrid};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed, TestRunner};

const TOL: f64 = 1e-9;

type Xyz = [f64; 3];

/// The point of line `p + s·d` closest to the line `q + t·e` (the lines meet).
fn meet(p: DVec3, d: DVec3, q: DVec3, e: DVec3) -> DVec3 {
    // Minimise |p + s d − q − t e|²: [d·d −d·e; d·e −e·e] (s, t) = ((q−p)·d, (q−p)·e).
    let w = q - p;
    let (dd, de, ee) = (d.dot(d), d.dot(e), e.dot(e));
    let (wd, we) = (w.dot(d), w.dot(e));
    let s = (wd * ee - we * de) / (dd * ee - de * de);
    p + s * d
}

/// Worst values measured on a mesh; every one must be ≤ [`TOL`].
#[derive(Debug, Default)]
struct Worst {
    /// `|OA − OD|`, `|OB − OC|` / size (O: where rows i and i+1 meet).
    apex: f64,
    /// `| |AB| − |DC| |`, `| |AC| − |BD| |` / size (legs and diagonals).
    isosceles: f64,
    /// `|AD × BC|` / (|AD| |BC|): the two bases are parallel.
    bases: f64,
    /// `measure`: face planarity, circularity, row and column planarity.
    measured: f64,
    /// `measure`: torsion and unit length of the node axes.
    axes: f64,
    /// `|x · N − h_j|` / size over the vertices of column j.
    in_plane: f64,
    /// `|angle(segment, reference plane) − α|` in radians over the helix segments.
    slope: f64,
}

impl Worst {
    fn max(&self) -> f64 {
        [
            self.apex,
            self.isosceles,
            self.bases,
            self.measured,
            self.axes,
            self.in_plane,
            self.slope,
        ]
        .into_iter()
        .fold(0.0, f64::max)
    }
}

/// Measure `mesh` against `heights`, `normal` and `alpha_deg` without using how
/// it was made.
fn check(mesh: &DevelopableMesh, heights: &[f64], normal: DVec3, alpha_deg: f64) -> Worst {
    let g = &mesh.grid;
    let n = normal.normalize();
    let size = g.bbox_diagonal();
    let mut w = Worst::default();
    assert_eq!(g.cols, heights.len());
    assert_eq!(g.rows, mesh.helix.len() - 1);
    let line = |i: usize| (g.vertex(i, 0), g.vertex(i, g.cols - 1) - g.vertex(i, 0));
    for i in 0..g.rows - 1 {
        let (p, d) = line(i);
        let (q, e) = line(i + 1);
        let o = meet(p, d, q, e);
        for j in 0..g.cols - 1 {
            let [a, b, c, dd] = g.face(i, j);
            // Face corners: A = (i, j), B = (i+1, j), C = (i+1, j+1), D = (i, j+1):
            // A, D on row i; B, C on row i + 1; the bases AB and DC lie in the cutting planes.
            w.apex = w
                .apex
                .max(((a - o).length() - (b - o).length()).abs() / size)
                .max(((dd - o).length() - (c - o).length()).abs() / size);
            w.isosceles = w
                .isosceles
                .max(((dd - a).length() - (c - b).length()).abs() / size)
                .max(((c - a).length() - (dd - b).length()).abs() / size);
            let (ab, dc) = ((b - a) / size, (c - dd) / size);
            w.bases = w
                .bases
                .max(ab.cross(dc).length() / (ab.length() * dc.length()));
        }
    }
    let m = measure(g);
    w.measured = [
        m.face_planarity.value,
        m.circularity.value,
        m.row_planarity.value,
        m.column_planarity.value,
    ]
    .into_iter()
    .fold(0.0, f64::max);
    w.axes = m.torsion.unwrap().value.max(m.normal_length.unwrap().value);
    for (j, &h) in heights.iter().enumerate() {
        for x in g.column(j) {
            w.in_plane = w.in_plane.max((x.dot(n) - h).abs() / size);
        }
    }
    for s in mesh.helix.windows(2) {
        let d = s[1] - s[0];
        let angle = d.dot(n).atan2((d - d.dot(n) * n).length());
        w.slope = w.slope.max((angle - alpha_deg.to_radians()).abs());
    }
    w
}

/// The points of `f` at `k` values from `t0` to `t1`, ends included.
fn curve(k: usize, t0: f64, t1: f64, f: impl Fn(f64) -> Xyz) -> Vec<Xyz> {
    (0..k)
        .map(|i| f(t0 + (t1 - t0) * i as f64 / (k - 1) as f64))
        .collect()
}

fn generate_checked(spec: &DevelopableSpec, alpha_deg: f64) -> (DevelopableMesh, Worst) {
    let mesh = developable(spec, &GenerateOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    let w = check(
        &mesh,
        &spec.heights,
        DVec3::from_array(spec.reference_normal),
        alpha_deg,
    );
    assert!(w.max() <= TOL, "{w:?}");
    (mesh, w)
}

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

// ---------------------------------------------------------------- errors

fn square() -> Vec<Xyz> {
    vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
    ]
}

fn err(spec: &DevelopableSpec) -> (DevelopableError, String) {
    let e = developable(spec, &GenerateOptions::default()).expect_err("must be refused");
    let msg = e.to_string();
    (e, msg)
}

#[test]
fn error_curve_choice() {
    let mut s = DevelopableSpec::projection(square(), 30.0, vec![-1.0, -2.0]);
    s.helix = DevelopableSpec::helix(square(), vec![]).helix;
    let (e, msg) = err(&s);
    assert_eq!(e, DevelopableError::CurveChoice { given: 2 });
    assert!(msg.contains("exactly one of `helix`") && msg.contains("2 were given"));
    s.helix = None;
    s.projection = None;
    assert_eq!(err(&s).0, DevelopableError::CurveChoice { given: 0 });
}

#[test]
fn error_not_finite() {
    let mut pts = square();
    pts[2][1] = f64::NAN;
    let (e, msg) = err(&DevelopableSpec::projection(
        pts.clone(),
        30.0,
        vec![-1.0, -2.0],
    ));
    assert!(matches!(
        e,
        DevelopableError::NotFinite { field: Field::ProjectionPoint, index: 2, value } if value.is_nan()
    ));
    assert!(
        msg.contains("projection.points[2]") && msg.contains("NaN"),
        "{msg}"
    );
    let (e, _) = err(&DevelopableSpec::helix(pts, vec![-1.0, -2.0]));
    assert!(matches!(
        e,
        DevelopableError::NotFinite {
            field: Field::HelixPoint,
            index: 2,
            ..
        }
    ));
    let (e, msg) = err(&DevelopableSpec::projection(
        square(),
        f64::INFINITY,
        vec![-1.0, -2.0],
    ));
    assert_eq!(
        e,
        DevelopableError::NotFinite {
            field: Field::Alpha,
            index: 0,
            value: f64::INFINITY
        }
    );
    assert!(msg.contains("alpha_deg") && msg.contains("inf"), "{msg}");
    let (e, msg) = err(&DevelopableSpec::projection(
        square(),
        30.0,
        vec![-1.0, f64::NEG_INFINITY],
    ));
    assert!(matches!(
        e,
        DevelopableError::NotFinite {
            field: Field::Height,
            index: 1,
            ..
        }
    ));
    assert!(msg.contains("heights[1]"), "{msg}");
    let mut s = DevelopableSpec::projection(square(), 30.0, vec![-1.0, -2.0]);
    s.reference_normal = [0.0, f64::NAN, 1.0];
    let (e, msg) = err(&s);
    assert!(matches!(
        e,
        DevelopableError::NotFinite {
            field: Field::ReferenceNormal,
            ..
        }
    ));
    assert!(msg.contains("reference_normal"), "{msg}");
}

#[test]
fn error_zero_normal() {
    let mut s = DevelopableSpec::projection(square(), 30.0, vec![-1.0, -2.0]);
    s.reference_normal = [0.0; 3];
    let (e, msg) = err(&s);
    assert_eq!(e, DevelopableError::ZeroNormal);
    assert!(msg.contains("[0, 0, 1]"), "{msg}");
    // A tiny normal is only a direction.
    s.reference_normal = [0.0, 0.0, 1e-300];
    generate_checked(&s, 30.0);
}

#[test]
fn error_too_few_segments_and_heights() {
    let (e, msg) = err(&DevelopableSpec::projection(
        square()[..2].to_vec(),
        30.0,
        vec![-1.0, -2.0],
    ));
    assert_eq!(
        e,
        DevelopableError::TooFewSegments {
            points: 2,
            segments: 1
        }
    );
    assert!(msg.contains("at least 3 points"), "{msg}");
    let (e, msg) = err(&DevelopableSpec::projection(square(), 30.0, vec![-1.0]));
    assert_eq!(e, DevelopableError::TooFewHeights { heights: 1 });
    assert!(msg.contains("at least 2"), "{msg}");
}

#[test]
fn error_too_many_points_and_a_crossing_at_the_limit() {
    // An Archimedean spiral of the most points accepted: a mesh of 999 rulings.
    let spiral = |k: usize| {
        curve(k, 0.0, 3.0 * TAU, |t| {
            let r = 1.0 + 0.4 * t;
            [r * t.cos(), r * t.sin(), 2.0]
        })
    };
    let max = monge_core::developable::MAX_HELIX_POINTS;
    let spec = DevelopableSpec::projection(spiral(max), 20.0, vec![-1.0, -2.0]);
    let mesh = developable(&spec, &GenerateOptions::default()).unwrap();
    assert_eq!((mesh.grid.rows, mesh.grid.cols), (max - 1, 2));
    // An open polygon of as many points on a circle, its last segment turned
    // to run from its first point through the middle of segment 0 and on: the
    // crossing is still found, segment 0 with the last segment.
    let mut arc = curve(max, 0.0, 0.9 * TAU, |t| [t.cos(), t.sin(), 0.0]);
    let middle = (DVec3::from(arc[0]) + DVec3::from(arc[1])) / 2.0;
    arc[max - 1] = (2.0 * middle - DVec3::from(arc[max - 2])).to_array();
    let (e, _) = err(&DevelopableSpec::projection(arc, 20.0, vec![-1.0, -2.0]));
    assert!(
        matches!(e, DevelopableError::SelfCrossing { a: 0, b, distance, .. }
            if b == max - 2 && distance == 0.0),
        "{e:?}"
    );
    // One point more is refused, by its count.
    let (e, msg) = err(&DevelopableSpec::projection(
        spiral(max + 1),
        20.0,
        vec![-1.0, -2.0],
    ));
    assert_eq!(e, DevelopableError::TooManyPoints { points: max + 1 });
    assert!(
        msg.contains("1001 points") && msg.contains("limit of 1000"),
        "{msg}"
    );
}

#[test]
fn error_grid_too_large_names_the_limit_and_the_option() {
    // 3 rulings × 3 cutting planes = 9 vertices.
    let spec = DevelopableSpec::projection(square(), 30.0, vec![-1.0, -2.0, -3.0]);
    let limit = |max_vertices| GenerateOptions { max_vertices };
    assert_eq!(
        developable(&spec, &limit(9)).unwrap().grid.vertices.len(),
        9
    );
    let e = developable(&spec, &limit(8)).unwrap_err();
    assert_eq!(
        e,
        DevelopableError::GridTooLarge(GenerateError::GridTooLarge {
            rows: 3,
            cols: 3,
            vertices: 9,
            limit: 8
        })
    );
    let msg = e.to_string();
    for part in [
        "3 × 3 = 9 vertices",
        "limit of 8",
        "helix points",
        "`--max-vertices`",
    ] {
        assert!(msg.contains(part), "{part}: {msg}");
    }
    // A mesh of 999 × 200 000 ≈ 2e8 vertices (9.6 GB) is refused by the default
    // limit before it is built.
    let pts = curve(1000, 0.0, 0.9 * TAU, |t| [t.cos(), t.sin(), 0.0]);
    let heights: Vec<f64> = (1..=200_000).map(|k| -f64::from(k)).collect();
    let e = developable(
        &DevelopableSpec::projection(pts, 30.0, heights),
        &GenerateOptions::default(),
    )
    .unwrap_err();
    assert!(
        matches!(
            e,
            DevelopableError::GridTooLarge(GenerateError::GridTooLarge {
                rows: 999,
                cols: 200_000,
                vertices: 199_800_000,
                limit: 25_000_000
            })
        ),
        "{e:?}"
    );
}

#[test]
fn error_projection_not_planar() {
    let mut pts = square();
    pts[3][2] = 0.01;
    pts[1][2] = -0.001;
    let (e, msg) = err(&DevelopableSpec::projection(pts, 30.0, vec![-1.0, -2.0]));
    let DevelopableError::ProjectionNotPlanar {
        index,
        offset,
        relative,
    } = e
    else {
        panic!("{e:?}")
    };
    assert_eq!(index, 3);
    assert_eq!(offset, 0.01);
    assert!(relative > 1e-4 && relative < 1e-2);
    assert!(
        msg.contains("projection.points[3]") && msg.contains("1.000e-2"),
        "{msg}"
    );
}

#[test]
fn error_repeated_point() {
    let mut pts = square();
    pts.insert(2, pts[2]);
    let (e, msg) = err(&DevelopableSpec::projection(
        pts.clone(),
        30.0,
        vec![-1.0, -2.0],
    ));
    assert!(
        matches!(e, DevelopableError::RepeatedPoint { index: 2, distance, .. } if distance == 0.0)
    );
    assert!(msg.contains("helix points 2 and 3 coincide"), "{msg}");
    let helix: Vec<Xyz> = pts.iter().map(|p| [p[0], p[1], p[0] + p[1]]).collect();
    let (e, _) = err(&DevelopableSpec::helix(helix, vec![-1.0, -2.0]));
    assert!(matches!(
        e,
        DevelopableError::RepeatedPoint { index: 2, .. }
    ));
}

#[test]
fn error_flat_and_vertical_slopes() {
    let (e, msg) = err(&DevelopableSpec::projection(
        square(),
        0.0,
        vec![-1.0, -2.0],
    ));
    assert_eq!(e, DevelopableError::Flat { alpha_deg: 0.0 });
    assert!(msg.contains("α = 0°") && msg.contains("parallel"), "{msg}");
    let (e, msg) = err(&DevelopableSpec::projection(
        square(),
        -90.0,
        vec![-1.0, -2.0],
    ));
    assert_eq!(e, DevelopableError::Vertical { alpha_deg: -90.0 });
    assert!(
        msg.contains("α = -90°") && msg.contains("cylinder"),
        "{msg}"
    );
    let (e, msg) = err(&DevelopableSpec::projection(
        square(),
        120.0,
        vec![-1.0, -2.0],
    ));
    assert_eq!(e, DevelopableError::AlphaOutOfRange { alpha_deg: 120.0 });
    assert!(msg.contains("120°"), "{msg}");
    // Given directly: a flat polyline, and a vertical one.
    let (e, _) = err(&DevelopableSpec::helix(square(), vec![-1.0, -2.0]));
    assert_eq!(e, DevelopableError::Flat { alpha_deg: 0.0 });
    let vertical = vec![[0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 0.0, 2.0]];
    let (e, msg) = err(&DevelopableSpec::helix(vertical, vec![-1.0, -2.0]));
    assert_eq!(e, DevelopableError::Vertical { alpha_deg: 90.0 });
    assert!(msg.contains("α = 90°"), "{msg}");
}

#[test]
fn error_non_constant_slope_reports_the_worst_segment() {
    // Rises 1, 1, 1.1 over unit runs: segment 2 is the outlier.
    let helix = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 1.0],
        [1.0, 1.0, 2.0],
        [0.0, 1.0, 3.1],
    ];
    let (e, msg) = err(&DevelopableSpec::helix(helix.clone(), vec![-1.0, -2.0]));
    let DevelopableError::NonConstantSlope {
        segment,
        angle_deg,
        alpha_deg,
        deviation,
    } = e
    else {
        panic!("{e:?}")
    };
    assert_eq!(segment, 2);
    assert!((angle_deg - 1.1f64.atan().to_degrees()).abs() < 1e-12);
    assert!((alpha_deg - (3.1f64 / 3.0).atan().to_degrees()).abs() < 1e-12);
    assert!(deviation > 1e-2);
    assert!(msg.contains("segment 2 (points 2..3)"), "{msg}");
    // Within the tolerance the helix is accepted and re-lifted exactly.
    let mut close = helix;
    close[3][2] = 3.0 + 1e-11;
    let spec = DevelopableSpec::helix(close, vec![-1.0, -2.0]);
    generate_checked(&spec, (3.0f64 + 1e-11).atan2(3.0).to_degrees());
    // A zigzag at ±45° has a mean slope of 0° but is not a helix.
    let zigzag = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 1.0], [1.0, 1.0, 0.0]];
    let (e, _) = err(&DevelopableSpec::helix(zigzag, vec![-1.0, -2.0]));
    assert!(
        matches!(e, DevelopableError::NonConstantSlope { .. }),
        "{e:?}"
    );
}

#[test]
fn error_straight_vertex() {
    let pts = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [2.0, 1.0, 0.0],
    ];
    let (e, msg) = err(&DevelopableSpec::projection(pts, 30.0, vec![-1.0, -2.0]));
    assert!(
        matches!(e, DevelopableError::Straight { vertex: 1, .. }),
        "{e:?}"
    );
    assert!(msg.contains("segments 0 and 1 are collinear"), "{msg}");
}

#[test]
fn error_self_crossing() {
    // A bow tie: segments 0 and 2 cross at (1, 0.5).
    let pts = vec![
        [0.0, 0.0, 0.0],
        [2.0, 1.0, 0.0],
        [2.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
    ];
    let (e, msg) = err(&DevelopableSpec::projection(pts, 30.0, vec![-1.0, -2.0]));
    assert!(
        matches!(e, DevelopableError::SelfCrossing { a: 0, b: 2, distance, .. } if distance == 0.0),
        "{e:?}"
    );
    assert!(
        msg.contains("segments 0 (points 0..1) and 2 (points 2..3)"),
        "{msg}"
    );
    // Folding back onto the previous segment.
    let pts = vec![[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0, 0.0, 0.0]];
    let (e, _) = err(&DevelopableSpec::projection(pts, 30.0, vec![-1.0, -2.0]));
    assert!(
        matches!(e, DevelopableError::SelfCrossing { a: 0, b: 1, .. }),
        "{e:?}"
    );
    // More than one turn of a circular helix: its projection overlaps itself.
    let pts = curve(20, 0.0, 1.5 * TAU, |t| [t.cos(), t.sin(), 0.0]);
    let (e, _) = err(&DevelopableSpec::projection(pts, 30.0, vec![-1.0, -2.0]));
    assert!(matches!(e, DevelopableError::SelfCrossing { .. }), "{e:?}");
}

#[test]
fn error_heights_not_monotonic() {
    let (e, msg) = err(&DevelopableSpec::projection(
        square(),
        30.0,
        vec![-1.0, -2.0, -1.5],
    ));
    assert_eq!(
        e,
        DevelopableError::HeightsNotMonotonic {
            index: 2,
            previous: -2.0,
            height: -1.5
        }
    );
    assert!(
        msg.contains("heights[2] = -1.5") && msg.contains("heights[1] = -2"),
        "{msg}"
    );
    let (e, _) = err(&DevelopableSpec::projection(
        square(),
        30.0,
        vec![-1.0, -1.0],
    ));
    assert!(matches!(
        e,
        DevelopableError::HeightsNotMonotonic { index: 1, .. }
    ));
}

#[test]
fn error_height_at_a_helix_vertex() {
    // α = 45° over the unit square: helix vertices at heights 0, 1, 2, 3.
    let (e, msg) = err(&DevelopableSpec::projection(
        square(),
        45.0,
        vec![2.0 + 1e-12, 2.5],
    ));
    let DevelopableError::HeightAtHelixVertex {
        height_index,
        vertex,
        vertex_height,
        ..
    } = e
    else {
        panic!("{e:?}")
    };
    assert_eq!((height_index, vertex), (0, 2));
    assert!((vertex_height - 2.0).abs() < 1e-14);
    assert!(
        msg.contains("helix vertex 2") && msg.contains("rulings 1 and 2 meet"),
        "{msg}"
    );
}

#[test]
fn error_face_crosses_the_helix() {
    let (e, msg) = err(&DevelopableSpec::projection(square(), 45.0, vec![0.5, 1.5]));
    let DevelopableError::FaceCrossesHelix {
        vertex,
        j,
        below,
        above,
        ..
    } = e
    else {
        panic!("{e:?}")
    };
    assert_eq!((vertex, j, below, above), (1, 0, 0.5, 1.5));
    assert!(
        msg.contains("helix vertex 1") && msg.contains("rulings 0 and 1"),
        "{msg}"
    );
}

#[test]
fn error_scale_and_extreme_scales() {
    let scaled = |k: f64| {
        let pts = square().iter().map(|p| p.map(|x| x * k)).collect();
        DevelopableSpec::projection(pts, 30.0, vec![-k, -2.0 * k])
    };
    for k in [1e-90, 1e-40, 1e-5, 1e5, 1e40, 1e90] {
        generate_checked(&scaled(k), 30.0);
    }
    for k in [1e-120, 1e120, 1e300] {
        let (e, msg) = err(&scaled(k));
        assert_eq!(e, DevelopableError::Scale { extent: 2.0 * k });
        assert!(msg.contains("rescale"), "{msg}");
    }
}

#[test]
fn garbage_never_panics() {
    // Random, often invalid specs: refused with an error or measured exact.
    let num = prop_oneof![
        -3.0f64..3.0,
        Just(0.0),
        Just(1.0),
        Just(90.0),
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(1e200),
        Just(1e-200),
    ];
    let xyz = [num.clone(), num.clone(), num.clone()];
    let strategy = (
        prop::collection::vec(xyz.clone(), 0..7),
        num.clone(),
        prop::collection::vec(num.clone(), 0..5),
        xyz,
        any::<bool>(),
    );
    let mut runner = TestRunner::new(Config {
        rng_seed: RngSeed::Fixed(0x646576),
        failure_persistence: None,
        cases: 2000,
        ..Config::default()
    });
    runner
        .run(&strategy, |(points, alpha, heights, normal, direct)| {
            let mut spec = if direct {
                DevelopableSpec::helix(points, heights)
            } else {
                DevelopableSpec::projection(points, alpha, heights)
            };
            spec.reference_normal = normal;
            if let Ok(mesh) = developable(&spec, &GenerateOptions::default()) {
                let w = check(
                    &mesh,
                    &spec.heights,
                    DVec3::from_array(normal),
                    mesh.alpha_deg,
                );
                prop_assert!(w.max() <= TOL, "{:?} {:?}", spec, w);
            }
            Ok(())
        })
        .unwrap();
}

// ---------------------------------------------------------------- property test

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
