//! Closed-form cases of the paper (§4.1, §4.3, §4.6), checked on the output
//! mesh alone (vertex positions and node axes) against analytic surfaces and
//! direct geometric computations: circles through three vertices, least-squares
//! planes (nalgebra SVD), pairwise distances, mirror images.
//!
//! `cargo test -p monge-core-tests --test integration analytic:: -- --nocapture` prints the worst
//! values seen and the refinement rates.

use glam::DVec3;
use monge_core::design::ArcSpec;
use monge_core::measure::measure;
use monge_core::{Design, GuideSpec, QuadGrid};

use crate::common;
use common::{
    bspline, circle3, circle_distance, design, freeform, mesh, plane_fit, two_circles,
    PROFILE_RADIUS as RT, RAIL_RADIUS as R, TOL,
};

/// All measurements of `measure` within the tolerance; returns the largest.
fn assert_exact(grid: &QuadGrid, what: &str) -> f64 {
    let m = measure(grid);
    let worst = m.max_error();
    assert!(worst <= TOL, "{what}: {m:?}");
    worst
}

/// A polyline inscribed in a circle: the circle through its first, middle and
/// last vertices, and the largest distance of a vertex from it.
fn inscribed(points: &[DVec3]) -> ((DVec3, DVec3, f64), f64) {
    let n = points.len();
    let circle = circle3(points[0], points[n / 2], points[n - 1]);
    let d = points
        .iter()
        .map(|&p| circle_distance(p, circle))
        .fold(0.0, f64::max);
    (circle, d)
}

// ---------------------------------------------------------------------------
// Torus (§4.1.1) and Dupin cyclides (§4.1.3, §4.6).
// ---------------------------------------------------------------------------

/// The torus with axis through (0, 0, −R) along y, core radius R − r, tube r:
/// for a point, its signed distance from the torus and the unit outward
/// normal of the torus at its nearest point.
fn torus(p: DVec3) -> (f64, DVec3) {
    let q = p - DVec3::new(0.0, 0.0, -R);
    let rho = q.x.hypot(q.z);
    let core = DVec3::new(0.0, 0.0, -R) + (R - RT) * DVec3::new(q.x, 0.0, q.z) / rho;
    let off = p - core;
    (off.length() - RT, off.normalize())
}

#[test]
fn torus_at_theta_zero() {
    // (rail sweep, rows, profile sweep, cols): profile sweeps stay below 90°, so
    // no sample lies on the top circle (where the normal is the axis).
    let cases = [
        (120.0, 41, 80.0, 33),
        (-100.0, 25, 60.0, 17),
        (200.0, 30, -70.0, 21),
        (300.0, 61, -85.0, 9),
    ];
    let (mut worst_on, mut worst_normal, mut worst_radius, mut worst_measure) =
        (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for (rail, rows, profile, cols) in cases {
        let g = mesh(&two_circles(0.0, rail, rows, profile, cols));
        let size = g.bbox_diagonal();
        worst_measure = worst_measure.max(assert_exact(&g, "torus"));
        // The sign of the normal: N_p = t_u × t_v, outward or inward.
        let sign = g.normals[0].dot(torus(g.vertices[0]).1);
        assert!((sign.abs() - 1.0).abs() < 1e-12);
        for (k, (&p, &n)) in g.vertices.iter().zip(&g.normals).enumerate() {
            let (dist, radial) = torus(p);
            let on = dist.abs() / size;
            let dn = (n - sign * radial).length();
            worst_on = worst_on.max(on);
            worst_normal = worst_normal.max(dn);
            assert!(on <= TOL, "rail {rail}: vertex {k} is {on:e} off the torus");
            assert!(
                dn <= TOL,
                "rail {rail}: normal {k} off the radial by {dn:e}"
            );
        }
        // Rows (v-lines) are circles of radius r, columns (u-lines) parallels of
        // radius R − r + r cos β_j (§4.6 at θ = 0).
        for i in 0..rows {
            let row: Vec<DVec3> = g.row(i).collect();
            let ((_, _, radius), d) = inscribed(&row);
            worst_radius = worst_radius.max((radius - RT).abs() / size).max(d / size);
            assert!(d / size <= TOL && (radius - RT).abs() / size <= TOL);
        }
        for j in 0..cols {
            let col: Vec<DVec3> = g.column(j).collect();
            let ((_, _, radius), d) = inscribed(&col);
            let beta = (profile * j as f64 / (cols - 1) as f64).to_radians();
            let expect = R - RT + RT * beta.cos();
            worst_radius = worst_radius
                .max((radius - expect).abs() / size)
                .max(d / size);
            assert!(d / size <= TOL && (radius - expect).abs() / size <= TOL);
        }
    }
    eprintln!(
        "torus: worst distance from the torus {worst_on:.2e}, normal off the radial {worst_normal:.2e}, \
         rows/columns off their analytic circles {worst_radius:.2e}, measure {worst_measure:.2e}"
    );
}

#[test]
fn dupin_cyclides_have_circular_curvature_lines() {
    // Figure 12: the same two circles, θ = 0° (torus), 30°, 65°; and a few more.
    // 40 samples on guide_u (3.08° steps): at θ = 180° guide_v is the rail and
    // guide_u's sample at 90° (with 41 samples) would lie on the parabolic circle.
    let torus_mesh = mesh(&two_circles(0.0, 120.0, 40, 80.0, 33));
    for theta in [0.0, 30.0, 65.0, -45.0, 150.0, 180.0] {
        let g = mesh(&two_circles(theta, 120.0, 40, 80.0, 33));
        let size = g.bbox_diagonal();
        let worst_measure = assert_exact(&g, &format!("cyclide θ = {theta}"));
        let (mut circ, mut plane) = (0.0f64, 0.0f64);
        let lines = (0..g.rows)
            .map(|i| g.row(i).collect::<Vec<_>>())
            .chain((0..g.cols).map(|j| g.column(j).collect::<Vec<_>>()));
        for (k, line) in lines.enumerate() {
            let ((_, normal, _), d) = inscribed(&line);
            let (_, n, flat) = plane_fit(&line);
            circ = circ.max(d / size);
            plane = plane.max(flat / size);
            assert!(
                d / size <= TOL,
                "θ = {theta}: line {k} is {:e} off its circle",
                d / size
            );
            assert!(
                flat / size <= TOL,
                "θ = {theta}: line {k} not planar ({:e})",
                flat / size
            );
            assert!(
                n.cross(normal).length() < 1e-6,
                "θ = {theta}: circle not in the line's plane"
            );
        }
        eprintln!(
            "cyclide θ = {theta:>4}: rows and columns off their circles ≤ {circ:.2e}, off their planes ≤ {plane:.2e}, measure {worst_measure:.2e}"
        );
        if theta == 0.0 {
            // θ = 0 is the torus.
            assert_eq!(g, torus_mesh);
        }
    }
}

/// The largest distance (relative to the size) of a row's vertices from the
/// circle through three of them, over the rows `i` (fixed i, j varying).
fn rows_off_circles(g: &QuadGrid) -> (f64, f64) {
    let size = g.bbox_diagonal();
    let (mut circ, mut plane) = (0.0f64, 0.0f64);
    for i in 0..g.rows {
        let row: Vec<DVec3> = g.row(i).collect();
        circ = circ.max(inscribed(&row).1 / size);
        plane = plane.max(plane_fit(&row).2 / size);
    }
    (circ, plane)
}

#[test]
fn one_circular_guide_makes_its_whole_family_circular() {
    // §4.6 Proposition 4: guide_v is an arc, guide_u a B-spline: every v-line
    // (row) is inscribed in a circle. Characteristic and arbitrary (guide_v's
    // plane tilted by φ = 30° about its start tangent, §3.2) cases.
    let spline_u = freeform(0.0, 31, 2).guide_u;
    for (phi, thetas) in [
        (0.0f64, vec![-150.0, -60.0, 0.0, 40.0, 130.0, 180.0]),
        (30.0, vec![-150.0, -60.0, 60.0, 130.0, 180.0]),
    ] {
        let (s, c) = phi.to_radians().sin_cos();
        // Centre at −r·d, d = (sin φ, 0, cos φ); normal −(y × d) gives start tangent +y.
        let guide_v = GuideSpec::Arc(ArcSpec {
            center: [-RT * s, 0.0, -RT * c],
            start: [0.0; 3],
            normal: [-c, 0.0, s],
            angle_deg: 75.0,
            samples: 26,
        });
        for theta in thetas {
            let g = mesh(&design(theta, spline_u.clone(), guide_v.clone()));
            let m = assert_exact(&g, &format!("φ = {phi}, θ = {theta}"));
            let (circ, plane) = rows_off_circles(&g);
            eprintln!(
                "one arc guide, φ = {phi:>2}, θ = {theta:>5}: rows off their circles ≤ {circ:.2e}, \
                 off their planes ≤ {plane:.2e}, measure {m:.2e}"
            );
            assert!(
                circ <= TOL && plane <= TOL,
                "φ = {phi}, θ = {theta}: {circ:e} {plane:e}"
            );
        }
    }
}

// ---------------------------------------------------------------------------
// Moulding surfaces (§4.1.2).
// ---------------------------------------------------------------------------

/// The mirror image of `p` in the perpendicular bisector plane of `a b`.
fn mirror(p: DVec3, a: DVec3, b: DVec3) -> DVec3 {
    let e = (b - a).normalize();
    let m = 0.5 * (a + b);
    p - 2.0 * (p - m).dot(e) * e
}

/// What is exactly true of a discrete moulding surface with rail `rail(k)` and
/// profiles `profile(k)` (polylines through rail vertex k), the rail lying in a
/// plane and with node axes `axis(k)` at the rail vertices:
/// - every profile is congruent to profile 0 (all pairwise distances equal);
/// - profile k + 1 is the mirror image of profile k in the perpendicular
///   bisector plane of the rail edge k;
/// - the plane of profile k is orthogonal to the rail's plane and contains the
///   node axis at rail vertex k.
///
/// Returns the worst values (congruence, mirror, orthogonality to the rail
/// plane, node axis in the plane) and, for information, the largest angle
/// (degrees) between a profile plane's normal and the adjacent rail edges.
fn moulding(
    n: usize,
    profile: impl Fn(usize) -> Vec<DVec3>,
    axis: impl Fn(usize) -> DVec3,
    size: f64,
) -> [f64; 5] {
    let rail: Vec<DVec3> = (0..n).map(|k| profile(k)[0]).collect();
    let (_, rail_normal, rail_flat) = plane_fit(&rail);
    assert!(rail_flat / size <= TOL);
    let first = profile(0);
    let mut w = [0.0f64; 5];
    for k in 0..n {
        let p = profile(k);
        for a in 0..p.len() {
            for b in a + 1..p.len() {
                let d = ((p[a] - p[b]).length() - (first[a] - first[b]).length()).abs() / size;
                w[0] = w[0].max(d);
            }
        }
        if k + 1 < n {
            let next = profile(k + 1);
            for (q, q1) in p.iter().zip(&next) {
                w[1] = w[1].max((mirror(*q, rail[k], rail[k + 1]) - *q1).length() / size);
            }
        }
        let (_, normal, _) = plane_fit(&p);
        w[2] = w[2].max(normal.dot(rail_normal).abs());
        w[3] = w[3].max(normal.dot(axis(k)).abs());
        for e in [k.checked_sub(1), Some(k).filter(|&k| k + 1 < n)]
            .into_iter()
            .flatten()
            .map(|e| (rail[e + 1] - rail[e]).normalize())
        {
            w[4] = w[4].max(normal.dot(e).abs().min(1.0).acos().to_degrees());
        }
    }
    w
}

#[test]
fn moulding_surfaces_at_theta_zero_and_180() {
    // θ = 0: guide_u is the rail, the v-lines (rows) are copies of guide_v.
    let g = mesh(&freeform(0.0, 61, 41));
    let size = g.bbox_diagonal();
    let worst_measure = assert_exact(&g, "moulding θ = 0");
    let w0 = moulding(
        g.rows,
        |i| g.row(i).collect(),
        |i| g.normals[g.index(i, 0)],
        size,
    );
    // θ = 180: guide_v is the rail, the u-lines (columns) are copies of guide_u.
    let h = mesh(&freeform(180.0, 61, 41));
    let size_h = h.bbox_diagonal();
    let worst_measure_h = assert_exact(&h, "moulding θ = 180");
    let w180 = moulding(
        h.cols,
        |j| h.column(j).collect(),
        |j| h.normals[h.index(0, j)],
        size_h,
    );
    for (theta, w, m) in [(0, w0, worst_measure), (180, w180, worst_measure_h)] {
        eprintln!(
            "moulding θ = {theta}: profiles congruent to the guide to {:.2e}, each the mirror of the previous \
             in the rail edge's bisector plane to {:.2e}, profile planes ⟂ rail plane to {:.2e}, \
             containing the rail's node axis to {:.2e}; (not exact, for information: angle between a \
             profile plane's normal and the adjacent rail edges up to {:.2}°); measure {m:.2e}",
            w[0], w[1], w[2], w[3], w[4]
        );
        assert!(
            w[0] <= TOL,
            "θ = {theta}: profiles not congruent ({:e})",
            w[0]
        );
        assert!(
            w[1] <= TOL,
            "θ = {theta}: profiles not mirror images ({:e})",
            w[1]
        );
        assert!(
            w[2] <= TOL,
            "θ = {theta}: profile plane not ⟂ rail plane ({:e})",
            w[2]
        );
        assert!(
            w[3] <= TOL,
            "θ = {theta}: node axis not in profile plane ({:e})",
            w[3]
        );
    }
    // The profiles are guide_v itself (θ = 0) and guide_u itself (θ = 180) at
    // the start.
    let row0: Vec<DVec3> = g.row(0).collect();
    let col0: Vec<DVec3> = h.column(0).collect();
    assert_eq!(
        row0,
        mesh(&freeform(30.0, 61, 41)).row(0).collect::<Vec<_>>()
    );
    assert_eq!(
        col0,
        mesh(&freeform(30.0, 61, 41)).column(0).collect::<Vec<_>>()
    );
}

// ---------------------------------------------------------------------------
// θ modulo 360° (§2.1.2).
// ---------------------------------------------------------------------------

#[test]
fn theta_180_equals_minus_180_and_540() {
    for design in [
        freeform(180.0, 31, 21),
        two_circles(180.0, 120.0, 40, 80.0, 33),
    ] {
        let g = mesh(&design);
        let size = g.bbox_diagonal();
        for theta in [-180.0, 540.0, -540.0, 900.0] {
            let h = mesh(&Design {
                mesh: Default::default(),
                theta_deg: theta,
                ..design.clone()
            });
            let dv = g
                .vertices
                .iter()
                .zip(&h.vertices)
                .map(|(a, b)| (*a - *b).length() / size)
                .fold(0.0, f64::max);
            let dn = g
                .normals
                .iter()
                .zip(&h.normals)
                .map(|(a, b)| (*a - *b).length())
                .fold(0.0, f64::max);
            eprintln!(
                "θ = {theta} vs 180: vertices differ by {dv:.1e}, normals by {dn:.1e}, bit for bit: {}",
                g == h
            );
            assert!(dv <= TOL && dn <= TOL, "θ = {theta}: {dv:e} {dn:e}");
        }
    }
}

// ---------------------------------------------------------------------------
// Refinement.
// ---------------------------------------------------------------------------

/// guide_v tilted by 20° from x = 0 about the y axis (§3.2, Figure 10).
fn arbitrary(theta_deg: f64, rows: usize, cols: usize) -> Design {
    let (s, c) = 20f64.to_radians().sin_cos();
    let p = |t: f64, f: f64| [f * s, t, f * c];
    Design {
        mesh: Default::default(),
        guide_v: bspline(
            vec![p(0.0, 0.0), p(3.0, 0.0), p(6.0, 1.0), p(9.0, 2.5)],
            cols,
        ),
        ..freeform(theta_deg, rows, cols)
    }
}

/// A family of designs: θ and the samples of guide_u and guide_v.
type Family = fn(f64, usize, usize) -> Design;

#[test]
fn refinement_converges() {
    let levels = [11usize, 21, 41, 81];
    let designs: [(&str, Family, f64); 4] = [
        ("characteristic θ = -30", freeform, -30.0),
        ("characteristic θ = 20", freeform, 20.0),
        ("characteristic θ = 150", freeform, 150.0),
        ("arbitrary φ = 20°, θ = -60", arbitrary, -60.0),
    ];
    for (name, make, theta) in designs {
        let grids: Vec<QuadGrid> = levels.iter().map(|&n| mesh(&make(theta, n, n))).collect();
        for g in &grids {
            assert_exact(g, name);
        }
        let size = grids[0].bbox_diagonal();
        // Vertex at guide parameters (a/10, b/10): index a·(n − 1)/10.
        let at = |g: &QuadGrid, n: usize, a: usize, b: usize| {
            let k = (n - 1) / 10;
            (g.vertex(a * k, b * k), g.normals[g.index(a * k, b * k)])
        };
        let mut diffs = Vec::new();
        let mut ndiffs = Vec::new();
        for l in 0..levels.len() - 1 {
            let (mut d, mut dn) = (0.0f64, 0.0f64);
            for a in 0..=10 {
                for b in 0..=10 {
                    let (p, n) = at(&grids[l], levels[l], a, b);
                    let (q, m) = at(&grids[l + 1], levels[l + 1], a, b);
                    d = d.max((p - q).length() / size);
                    dn = dn.max((n - m).length());
                }
            }
            diffs.push(d);
            ndiffs.push(dn);
        }
        let rates: Vec<f64> = diffs.windows(2).map(|w| w[0] / w[1]).collect();
        let nrates: Vec<f64> = ndiffs.windows(2).map(|w| w[0] / w[1]).collect();
        eprintln!(
            "refinement {name}: max vertex change 11→21 {:.2e}, 21→41 {:.2e}, 41→81 {:.2e} (of size); \
             rates {:.2}, {:.2}; normals {:.2e}, {:.2e}, {:.2e}, rates {:.2}, {:.2}",
            diffs[0], diffs[1], diffs[2], rates[0], rates[1], ndiffs[0], ndiffs[1], ndiffs[2], nrates[0],
            nrates[1]
        );
        for r in rates.iter().chain(&nrates) {
            assert!(
                *r > 1.6,
                "{name}: not converging (rates {rates:?}, normals {nrates:?})"
            );
        }
    }
}
