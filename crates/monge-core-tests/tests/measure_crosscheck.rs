//! Cross-check of `monge_core::measure` against independent nalgebra computations (§2.2).
//!
//! Random quads and polylines, perturbed off their plane / circle, are measured
//! by `measure` and by textbook linear algebra that shares nothing with it:
//! closest points of the diagonal lines by least squares, least-squares planes
//! by SVD and by the covariance eigen-decomposition, circumcircles by solving
//! the circle equation with LU, and a geometric least-squares circle fit by
//! Gauss–Newton. `crosscheck_report` prints the largest disagreements seen
//! (`cargo test -p monge-core-tests --test integration measure_crosscheck:: -- --nocapture`).

use glam::DVec3;
use monge_core::measure::measure;
use monge_core::QuadGrid;
use nalgebra::{DMatrix, DVector, Matrix3, UnitQuaternion, Vector3};
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use proptest::test_runner::RngSeed;
use proptest::test_runner::TestRunner;

fn na(p: DVec3) -> Vector3<f64> {
    Vector3::new(p.x, p.y, p.z)
}

/// Largest coordinate magnitude: the rounding of the inputs is relative to it.
fn extent(points: &[DVec3]) -> f64 {
    points
        .iter()
        .map(|p| p.abs().max_element())
        .fold(0.0, f64::max)
}

/// Two computations of one length compared. They must agree to 1e-6 relative,
/// up to rounding of the inputs (1e-14 × the coordinates' magnitude).
#[derive(Clone, Copy, Debug, Default)]
struct Agreement {
    /// `|ours − theirs| / extent`.
    absolute: f64,
    /// `|ours − theirs| / (1e-6 · theirs + 1e-14 · extent)`: must be ≤ 1.
    tolerance_used: f64,
    /// `|ours − theirs| / theirs`, only for values above `1e-7 · extent` (else 0).
    relative: f64,
}

impl Agreement {
    fn of(ours: f64, theirs: f64, extent: f64) -> Agreement {
        let d = (ours - theirs).abs();
        Agreement {
            absolute: d / extent,
            tolerance_used: d / (1e-6 * theirs + 1e-14 * extent),
            relative: if theirs > 1e-7 * extent {
                d / theirs
            } else {
                0.0
            },
        }
    }
    fn max(self, o: Agreement) -> Agreement {
        Agreement {
            absolute: self.absolute.max(o.absolute),
            tolerance_used: self.tolerance_used.max(o.tolerance_used),
            relative: self.relative.max(o.relative),
        }
    }
}

/// A one-face grid with corners `A, B, C, D` = `(0,0), (1,0), (1,1), (0,1)`.
fn one_face([a, b, c, d]: [DVec3; 4]) -> QuadGrid {
    QuadGrid::new(2, 2, vec![a, d, b, c], vec![])
}

/// A random placement: origin and orthonormal frame `(u, w, ν)`.
#[derive(Clone, Debug)]
struct Frame {
    origin: Vector3<f64>,
    rot: UnitQuaternion<f64>,
}

impl Frame {
    fn at(&self, x: f64, y: f64, z: f64) -> DVec3 {
        let p = self.origin + self.rot * Vector3::new(x, y, z);
        DVec3::new(p.x, p.y, p.z)
    }
}

fn frame() -> impl Strategy<Value = Frame> {
    let a = -std::f64::consts::PI..std::f64::consts::PI;
    (
        prop::array::uniform3(-10.0..10.0f64),
        a.clone(),
        a.clone(),
        a,
    )
        .prop_map(|(o, r, p, y)| Frame {
            origin: Vector3::new(o[0], o[1], o[2]),
            rot: UnitQuaternion::from_euler_angles(r, p, y),
        })
}

/// `10^e` for `e` uniform in `lo..hi`.
fn log_uniform(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (lo..hi).prop_map(|e| 10f64.powf(e))
}

// ---------------------------------------------------------------- planarity

/// A convex quad near a plane: a rectangle `2a × 2b` with corners moved in the
/// plane by up to `min(a, b)/4`, then lifted off it by `eps · z_k`.
#[derive(Clone, Debug)]
struct NearPlanarQuad {
    corners: [DVec3; 4],
}

fn near_planar_quad() -> impl Strategy<Value = NearPlanarQuad> {
    (
        frame(),
        0.5..2.0f64,
        0.5..2.0f64,
        prop::array::uniform4((-0.25..0.25f64, -0.25..0.25f64, -1.0..1.0f64)),
        log_uniform(-9.0, -3.0),
    )
        .prop_map(|(f, a, b, moves, eps)| {
            let base = [(-a, -b), (a, -b), (a, b), (-a, b)];
            let m = a.min(b);
            let corners = std::array::from_fn(|k| {
                let (x, y) = base[k];
                let (dx, dy, z) = moves[k];
                f.at(x + m * dx, y + m * dy, eps * z)
            });
            NearPlanarQuad { corners }
        })
}

/// Distance between the diagonal lines `AC`, `BD`: closest points by least squares
/// `min |A + s·AC − B − t·BD|` (nalgebra SVD solve).
fn diagonal_distance(q: &[DVec3; 4]) -> f64 {
    let [a, b, c, d] = q.map(na);
    let m = DMatrix::from_columns(&[
        DVector::from_column_slice((c - a).as_slice()),
        DVector::from_column_slice((b - d).as_slice()),
    ]);
    let rhs = DVector::from_column_slice((b - a).as_slice());
    let st = m
        .clone()
        .svd(true, true)
        .solve(&rhs, 0.0)
        .expect("solvable");
    (m * st - rhs).norm()
}

/// Distances of points from their least-squares plane, by SVD of the centred points.
fn svd_plane_distances(points: &[DVec3]) -> Vec<f64> {
    let c = points.iter().map(|p| na(*p)).sum::<Vector3<f64>>() / points.len() as f64;
    let m = DMatrix::from_fn(points.len(), 3, |r, k| na(points[r])[k] - c[k]);
    let svd = m.clone().svd(false, true);
    let v_t = svd.v_t.unwrap();
    let k = svd.singular_values.imin();
    let n = v_t.row(k).transpose();
    (m * n).iter().map(|x| x.abs()).collect()
}

/// (agreement with the closest-point distance, `d / max LS residual`).
fn check_face_planarity(q: &NearPlanarQuad) -> (Agreement, f64) {
    let m = measure(&one_face(q.corners));
    let ours = m.face_planarity.value * m.scale;
    let theirs = diagonal_distance(&q.corners);
    let res = svd_plane_distances(&q.corners)
        .into_iter()
        .fold(0.0, f64::max);
    (Agreement::of(ours, theirs, extent(&q.corners)), ours / res)
}

proptest! {
    #![proptest_config(ProptestConfig {
        failure_persistence: None,
        rng_seed: RngSeed::Fixed(0x6d6f6e6765),
        ..ProptestConfig::default()
    })]
    /// Face planarity = distance of the diagonal lines, and for a convex nearly
    /// planar quad it lies between the max and twice the max distance from the
    /// SVD plane (the LS residuals are ∝ the affine weights (1−s, −(1−t), s, −t)).
    #[test]
    fn measure_face_planarity_matches_nalgebra(q in near_planar_quad()) {
        let (agree, ratio) = check_face_planarity(&q);
        prop_assert!(agree.tolerance_used <= 1.0, "{agree:?}");
        prop_assert!((0.999..=2.001).contains(&ratio), "d / max residual = {ratio}");
    }
}

// ---------------------------------------------------------------- line planarity

/// A polyline near a plane: well spread in the plane, `eps · z_k` off it.
#[derive(Clone, Debug)]
struct NearPlanarPolyline {
    points: Vec<DVec3>,
    exact: bool,
}

fn near_planar_polyline() -> impl Strategy<Value = NearPlanarPolyline> {
    (
        frame(),
        prop::collection::vec((-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64), 3..40),
        log_uniform(-10.0, -2.0),
        any::<bool>(),
    )
        .prop_map(|(f, xyz, eps, exact)| NearPlanarPolyline {
            points: xyz
                .iter()
                .map(|&(x, y, z)| f.at(x, y, if exact { 0.0 } else { eps * z }))
                .collect(),
            exact,
        })
}

/// Distances of points from their least-squares plane by the covariance eigen-decomposition.
fn eigen_plane_distances(points: &[DVec3]) -> Vec<f64> {
    let c = points.iter().map(|p| na(*p)).sum::<Vector3<f64>>() / points.len() as f64;
    let cov = points.iter().fold(Matrix3::zeros(), |m, p| {
        let d = na(*p) - c;
        m + d * d.transpose()
    });
    let eig = cov.symmetric_eigen();
    let n = eig.eigenvectors.column(eig.eigenvalues.imin()).into_owned();
    points.iter().map(|p| (na(*p) - c).dot(&n).abs()).collect()
}

/// Agreement of row and column planarity with the eigen solution (default for
/// exactly planar polylines, which must measure ≤ 1e-14).
fn check_line_planarity(l: &NearPlanarPolyline) -> Result<Agreement, TestCaseError> {
    let n = l.points.len();
    let theirs = eigen_plane_distances(&l.points);
    let max = theirs.iter().cloned().fold(0.0, f64::max);
    let ext = extent(&l.points);
    let mut worst = Agreement::default();
    for (grid, row) in [
        (QuadGrid::new(1, n, l.points.clone(), vec![]), true),
        (QuadGrid::new(n, 1, l.points.clone(), vec![]), false),
    ] {
        let m = measure(&grid);
        let (w, other) = if row {
            (m.row_planarity, m.column_planarity)
        } else {
            (m.column_planarity, m.row_planarity)
        };
        prop_assert_eq!(other.value, 0.0);
        if l.exact {
            prop_assert!(
                w.value <= 1e-14,
                "exactly planar polyline measures {}",
                w.value
            );
            continue;
        }
        let ours = w.value * m.scale;
        worst = worst.max(Agreement::of(ours, max, ext));
        // The reported vertex is (up to a near-tie) the farthest one.
        let k = if row { w.at.1 } else { w.at.0 };
        prop_assert!(
            theirs[k] >= max * (1.0 - 1e-6) - 1e-12 * ext,
            "at {k}: {} vs max {max}",
            theirs[k]
        );
    }
    Ok(worst)
}

proptest! {
    #![proptest_config(ProptestConfig {
        failure_persistence: None,
        rng_seed: RngSeed::Fixed(0x6d6f6e6765),
        ..ProptestConfig::default()
    })]
    /// Row/column planarity = max distance from the least-squares plane.
    #[test]
    fn measure_line_planarity_matches_nalgebra(l in near_planar_polyline()) {
        let agree = check_line_planarity(&l)?;
        prop_assert!(agree.tolerance_used <= 1.0, "{agree:?}");
    }

    /// Nearly straight polylines lying exactly in a plane stay at rounding level
    /// (where a covariance eigen-decomposition would lose half the digits).
    #[test]
    fn measure_nearly_straight_planar_polyline_is_planar(
        f in frame(),
        xy in prop::collection::vec((-1.0..1.0f64, -1.0..1.0f64), 3..40),
        bend in log_uniform(-14.0, 0.0),
    ) {
        let pts: Vec<DVec3> = xy.iter().map(|&(x, y)| f.at(x, bend * y, 0.0)).collect();
        let m = measure(&QuadGrid::new(1, pts.len(), pts, vec![]));
        prop_assert!(m.row_planarity.value <= 1e-14, "{}", m.row_planarity.value);
    }
}

// ---------------------------------------------------------------- circularity

/// A quad inscribed in a circle of radius `r` (corner angles at least ~0.57 rad
/// apart), each corner then moved by `eps · r` in a random direction (in the
/// circle's plane only when `in_plane`).
#[derive(Clone, Debug)]
struct NearCircularQuad {
    corners: [DVec3; 4],
    /// The circle's frame and radius, for the in-plane least-squares fit.
    frame: Frame,
    radius: f64,
    in_plane: bool,
}

fn near_circular_quad() -> impl Strategy<Value = NearCircularQuad> {
    (
        frame(),
        0.5..5.0f64,
        0.0..std::f64::consts::TAU,
        prop::array::uniform4(0.3..1.0f64),
        prop::array::uniform4((-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64)),
        log_uniform(-9.0, -3.0),
        any::<bool>(),
    )
        .prop_map(|(frame, radius, phase, gaps, moves, eps, in_plane)| {
            let total: f64 = gaps.iter().sum();
            let mut angle = phase;
            let corners = std::array::from_fn(|k| {
                let (dx, dy, dz) = moves[k];
                let dz = if in_plane { 0.0 } else { dz };
                let p = frame.at(
                    radius * angle.cos() + eps * radius * dx,
                    radius * angle.sin() + eps * radius * dy,
                    eps * radius * dz,
                );
                angle += std::f64::consts::TAU * gaps[k] / total;
                p
            });
            NearCircularQuad {
                corners,
                frame,
                radius,
                in_plane,
            }
        })
}

/// Distance of `p` from the circle through `a, b, c`: plane by SVD of the
/// centred triple, circumcircle from `2x·cx + 2y·cy + κ = x² + y²` by LU.
fn distance_from_circumcircle([a, b, c]: [DVec3; 3], p: DVec3) -> f64 {
    let o = (na(a) + na(b) + na(c)) / 3.0;
    let m = Matrix3::from_rows(&[
        (na(a) - o).transpose(),
        (na(b) - o).transpose(),
        (na(c) - o).transpose(),
    ]);
    let svd = m.svd(false, true);
    let v_t = svd.v_t.unwrap();
    let k = svd.singular_values.imin();
    let n = v_t.row(k).transpose();
    let (e1, e2) = (
        v_t.row((k + 1) % 3).transpose(),
        v_t.row((k + 2) % 3).transpose(),
    );
    let xy = |q: DVec3| ((na(q) - o).dot(&e1), (na(q) - o).dot(&e2));
    let rows: Vec<_> = [a, b, c].iter().map(|q| xy(*q)).collect();
    let lhs = Matrix3::from_fn(|r, col| [2.0 * rows[r].0, 2.0 * rows[r].1, 1.0][col]);
    let rhs = Vector3::from_fn(|r, _| rows[r].0 * rows[r].0 + rows[r].1 * rows[r].1);
    let sol = lhs.lu().solve(&rhs).expect("non-collinear triple");
    let radius = (sol[2] + sol[0] * sol[0] + sol[1] * sol[1]).sqrt();
    let (x, y) = xy(p);
    let h = (na(p) - o).dot(&n);
    h.hypot((x - sol[0]).hypot(y - sol[1]) - radius)
}

/// `2·area / longest edge²` of a triangle — the conditioning of its circumcircle.
fn shape([a, b, c]: [DVec3; 3]) -> f64 {
    let longest = (b - a)
        .length_squared()
        .max((c - b).length_squared())
        .max((a - c).length_squared());
    (b - a).cross(c - a).length() / longest
}

/// Residuals of the geometric least-squares circle through the (planar) corners,
/// by Gauss–Newton on `(cx, cy, r)` in the circle's plane (nalgebra SVD solves).
fn ls_circle_residuals(q: &NearCircularQuad) -> Vec<f64> {
    let inv = q.frame.rot.inverse();
    let pts: Vec<(f64, f64)> = q
        .corners
        .iter()
        .map(|p| {
            let l = inv * (na(*p) - q.frame.origin);
            (l.x, l.y)
        })
        .collect();
    let mut x = DVector::from_vec(vec![0.0, 0.0, q.radius]);
    let residuals = |x: &DVector<f64>| -> Vec<f64> {
        pts.iter()
            .map(|&(px, py)| (px - x[0]).hypot(py - x[1]) - x[2])
            .collect()
    };
    for _ in 0..30 {
        let r = DVector::from_vec(residuals(&x));
        let j = DMatrix::from_fn(pts.len(), 3, |k, col| {
            let (dx, dy) = (pts[k].0 - x[0], pts[k].1 - x[1]);
            let d = dx.hypot(dy);
            [-dx / d, -dy / d, -1.0][col]
        });
        let step = j.svd(true, true).solve(&r, 0.0).expect("solvable");
        x -= step;
    }
    residuals(&x)
}

/// (agreement with the independent circumcircle of the best-shaped triple,
/// `m / max |LS residual|` and `LS rms / (m/2)`, both NaN when not in plane).
fn check_circularity(q: &NearCircularQuad) -> Result<(Agreement, f64, f64), TestCaseError> {
    let m = measure(&one_face(q.corners));
    let ours = m.circularity.value * m.scale;
    let c = &q.corners;
    let triples: Vec<([DVec3; 3], DVec3)> = (0..4)
        .map(|k| ([c[(k + 1) % 4], c[(k + 2) % 4], c[(k + 3) % 4]], c[k]))
        .collect();
    let best = triples.iter().map(|(t, _)| shape(*t)).fold(0.0, f64::max);
    // The measured value is the independent one of the best-shaped triple (or of one tied with it).
    let ext = extent(c);
    let agree = triples
        .iter()
        .filter(|(t, _)| shape(*t) >= best * (1.0 - 1e-9))
        .map(|(t, p)| Agreement::of(ours, distance_from_circumcircle(*t, *p), ext))
        .min_by(|a, b| a.tolerance_used.total_cmp(&b.tolerance_used))
        .expect("the best triple");
    if !q.in_plane {
        return Ok((agree, f64::NAN, f64::NAN));
    }
    let e = ls_circle_residuals(q);
    let max_e = e.iter().map(|x| x.abs()).fold(0.0, f64::max);
    let rms = (e.iter().map(|x| x * x).sum::<f64>() / 4.0).sqrt();
    prop_assert!(
        rms <= ours / 2.0 * (1.0 + 1e-6) + 1e-14 * q.radius,
        "LS rms {rms} > m/2 = {}",
        ours / 2.0
    );
    Ok((agree, ours / max_e, rms / (ours / 2.0)))
}

proptest! {
    #![proptest_config(ProptestConfig {
        failure_persistence: None,
        rng_seed: RngSeed::Fixed(0x6d6f6e6765),
        ..ProptestConfig::default()
    })]
    /// Circularity = distance of a corner from the circle through the best-shaped
    /// other three (independent 3D circumcircle); and for planar quads it brackets
    /// the geometric least-squares circle fit: rms ≤ m/2 (the three-point circle is
    /// a candidate fit) and m ≤ 8·max residual (well-spread corners).
    #[test]
    fn measure_circularity_matches_nalgebra(q in near_circular_quad()) {
        let (agree, ratio, _) = check_circularity(&q)?;
        prop_assert!(agree.tolerance_used <= 1.0, "{agree:?}");
        prop_assert!(ratio.is_nan() || ratio <= 8.0, "m / max LS residual = {ratio}");
    }
}

/// Sample each strategy deterministically and print the largest disagreements
/// seen (run with `--nocapture`); asserts the same tolerances as the proptests.
#[test]
fn measure_crosscheck_report() {
    const N: usize = 3000;
    fn sample<S: Strategy>(s: S, runner: &mut TestRunner) -> S::Value {
        s.new_tree(runner).expect("strategy").current()
    }
    let mut runner = TestRunner::deterministic();
    let (mut face, mut ratio_lo, mut ratio_hi) = (Agreement::default(), f64::INFINITY, 0.0f64);
    for _ in 0..N {
        let (agree, ratio) = check_face_planarity(&sample(near_planar_quad(), &mut runner));
        face = face.max(agree);
        ratio_lo = ratio_lo.min(ratio);
        ratio_hi = ratio_hi.max(ratio);
    }
    let mut line = Agreement::default();
    for _ in 0..N {
        line =
            line.max(check_line_planarity(&sample(near_planar_polyline(), &mut runner)).unwrap());
    }
    let (mut circ, mut m_over_e, mut rms_over) = (Agreement::default(), 0.0f64, 0.0f64);
    for _ in 0..N {
        let (agree, ratio, rms) =
            check_circularity(&sample(near_circular_quad(), &mut runner)).unwrap();
        circ = circ.max(agree);
        if !ratio.is_nan() {
            m_over_e = m_over_e.max(ratio);
            rms_over = rms_over.max(rms);
        }
    }
    for (name, a) in [
        ("face planarity vs closest points of diagonals", face),
        ("row/column planarity vs covariance eigen plane", line),
        ("circularity vs independent circumcircle", circ),
    ] {
        println!(
            "{name}: max |Δ|/extent {:.2e}, max |Δ|/value (value > 1e-7·extent) {:.2e}, tolerance used {:.3}",
            a.absolute, a.relative, a.tolerance_used
        );
    }
    println!("face planarity / max SVD-plane residual: in [{ratio_lo:.4}, {ratio_hi:.4}]");
    println!(
        "circularity / max LS-circle residual: max {m_over_e:.3}; LS rms / (circularity/2): max {rms_over:.4}"
    );
    assert!(face.tolerance_used <= 1.0 && line.tolerance_used <= 1.0 && circ.tolerance_used <= 1.0);
    assert!(ratio_lo >= 0.999 && ratio_hi <= 2.001);
    assert!(m_over_e <= 8.0 && rms_over <= 1.0 + 1e-6);
}
