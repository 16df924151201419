//! Cyclidic nets (§4.4, §4.6, §5.3), measured independently of the construction:
//! circles and planes are fitted to sampled points here (three-point circles,
//! nalgebra SVD planes), never taken from the patch formulas.
//!
//! `cargo test -p monge-core --test cyclidic -- --nocapture` prints the worst values.

use glam::DVec3;
use monge_core::cyclidic::{
    Arc, CyclidicError, CyclidicNet, CyclidicOptions, Family, FoldReason, Frame, Patch,
};
use monge_core::design::{ArcSpec, BSplineSpec};
use monge_core::{generate, Design, GenerateOptions, GuideSpec, QuadGrid};
use nalgebra::DMatrix;

/// An arc guide starting at the origin.
fn arc(center: [f64; 3], normal: [f64; 3], angle_deg: f64, samples: usize) -> GuideSpec {
    GuideSpec::Arc(ArcSpec {
        center,
        start: [0.0; 3],
        normal,
        angle_deg,
        samples,
    })
}

/// A clamped uniform cubic B-spline guide.
fn bspline(control_points: Vec<[f64; 3]>, samples: usize) -> GuideSpec {
    GuideSpec::BSpline {
        bspline: BSplineSpec {
            degree: 3,
            control_points,
            knots: None,
            weights: None,
            samples,
        },
        parameters: None,
    }
}

fn design(theta_deg: f64, guide_u: GuideSpec, guide_v: GuideSpec) -> Design {
    Design {
        mesh: Default::default(),
        theta_deg,
        guide_u,
        guide_v,
        tolerance: None,
    }
}

fn mesh(d: &Design) -> QuadGrid {
    generate(d, &GenerateOptions::default()).unwrap().grid
}

/// The torus design (θ = 0, two circular-arc guides).
fn torus() -> Design {
    design(
        0.0,
        arc([0.0, 0.0, -10.0], [0.0, 1.0, 0.0], 80.0, 9),
        arc([0.0, 0.0, -3.0], [-1.0, 0.0, 0.0], 70.0, 7),
    )
}

/// The Dupin cyclide design of Figure 12 (θ = 30°), coarser.
fn dupin30() -> Design {
    Design {
        theta_deg: 30.0,
        ..torus()
    }
}

/// A free-form design (Figure 13's B-spline guides, coarser).
fn freeform() -> Design {
    design(
        -30.0,
        bspline(
            vec![
                [0.0, 0.0, 0.0],
                [4.0, 0.0, 0.0],
                [8.0, 0.0, 2.5],
                [12.0, 0.0, 1.0],
                [16.0, 0.0, 3.5],
            ],
            13,
        ),
        bspline(
            vec![
                [0.0, 0.0, 0.0],
                [0.0, 3.0, 0.0],
                [0.0, 6.0, -1.5],
                [0.0, 10.0, 1.0],
            ],
            9,
        ),
    )
}

/// guide_u a circular arc, guide_v a B-spline: every u-line is inscribed in a circle (§4.6).
fn circular_u() -> Design {
    design(
        20.0,
        arc([0.0, 0.0, -10.0], [0.0, 1.0, 0.0], 80.0, 9),
        bspline(
            vec![
                [0.0, 0.0, 0.0],
                [0.0, 3.0, 0.0],
                [0.0, 6.0, -1.5],
                [0.0, 10.0, 1.0],
            ],
            8,
        ),
    )
}

/// Rotation of `p` about the y axis through `c` by `phi` (right-hand rule).
fn rot_y(p: DVec3, c: DVec3, phi: f64) -> DVec3 {
    let q = p - c;
    c + DVec3::new(
        q.x * phi.cos() + q.z * phi.sin(),
        q.y,
        -q.x * phi.sin() + q.z * phi.cos(),
    )
}

/// guide_u a bi-arc in the plane y = 0: 4 edges on a circle of radius 10, then 4
/// on a tangent circle of radius 5, the junction at vertex 4 (§4.6, Figure 25).
const BIARC_JUNCTION: usize = 4;
fn biarc() -> Design {
    let c1 = DVec3::new(0.0, 0.0, -10.0);
    let step1 = 10f64.to_radians();
    let mut pts: Vec<DVec3> = (0..=BIARC_JUNCTION)
        .map(|k| rot_y(DVec3::ZERO, c1, step1 * k as f64))
        .collect();
    let junction = pts[BIARC_JUNCTION];
    let c2 = junction + (c1 - junction) * 0.5;
    let step2 = 12f64.to_radians();
    pts.extend((1..=4).map(|k| rot_y(junction, c2, step2 * k as f64)));
    design(
        20.0,
        GuideSpec::Points {
            points: pts.iter().map(|p| p.to_array()).collect(),
            tangent: Some([1.0, 0.0, 0.0]),
        },
        arc([0.0, 0.0, -3.0], [-1.0, 0.0, 0.0], 60.0, 7),
    )
}

/// The §4.4 net of a design.
fn net_of(d: &Design) -> (QuadGrid, CyclidicNet) {
    let g = mesh(d);
    let net = CyclidicNet::from_normals(&g, &CyclidicOptions::default()).unwrap();
    (g, net)
}

/// Apply an inversion in the sphere of radius `r` about `c`: a circular mesh stays
/// circular but its lines stop being planar.
fn invert(g: &QuadGrid, c: DVec3, r: f64) -> QuadGrid {
    let v = g
        .vertices
        .iter()
        .map(|p| c + (*p - c) * (r * r / (*p - c).length_squared()))
        .collect();
    QuadGrid::new(g.rows, g.cols, v, vec![])
}

/// Circle through three points: centre, unit normal, radius.
fn circle3(a: DVec3, b: DVec3, c: DVec3) -> (DVec3, DVec3, f64) {
    let (ab, ac) = (b - a, c - a);
    let n = ab.cross(ac);
    let center = a
        + (n.cross(ab) * ac.length_squared() + ac.cross(n) * ab.length_squared())
            / (2.0 * n.length_squared());
    (center, n.normalize(), center.distance(a))
}

/// Distance of `p` from the circle `(center, normal, radius)`.
fn circle_distance(p: DVec3, (center, normal, radius): (DVec3, DVec3, f64)) -> f64 {
    let q = p - center;
    let h = q.dot(normal);
    let r = (q - h * normal).length();
    (h * h + (r - radius).powi(2)).sqrt()
}

/// Largest distance of `points` from their least-squares plane (nalgebra SVD).
fn plane_deviation(points: &[DVec3]) -> f64 {
    let centroid = points.iter().sum::<DVec3>() / points.len() as f64;
    let m = DMatrix::from_fn(points.len(), 3, |r, c| (points[r] - centroid)[c]);
    let v_t = m.svd(false, true).v_t.expect("V^T requested");
    let n = DVec3::new(v_t[(2, 0)], v_t[(2, 1)], v_t[(2, 2)]);
    points
        .iter()
        .map(|p| (*p - centroid).dot(n).abs())
        .fold(0.0, f64::max)
}

/// The faces of a net.
fn faces(net: &CyclidicNet) -> impl Iterator<Item = (usize, usize)> {
    let c = net.cols() - 1;
    (0..(net.rows() - 1) * c).map(move |k| (k / c, k % c))
}

/// The four nets most tests run on: §4.4 nets of the torus, the Dupin cyclide,
/// the free-form design, and a carried-frame net on an inverted (non-planar-line) mesh.
fn nets() -> Vec<(&'static str, QuadGrid, CyclidicNet)> {
    let mut out: Vec<_> = [
        ("torus", torus()),
        ("dupin30", dupin30()),
        ("freeform", freeform()),
    ]
    .into_iter()
    .map(|(name, d)| {
        let (g, n) = net_of(&d);
        (name, g, n)
    })
    .collect();
    let inv = invert(&mesh(&freeform()), DVec3::new(3.0, 2.0, 6.0), 8.0);
    let t1 = (inv.vertex(1, 0) - inv.vertex(0, 0)).normalize();
    let t2 = (inv.vertex(0, 1) - inv.vertex(0, 0))
        .reject_from(t1)
        .normalize();
    let net =
        CyclidicNet::from_frame(&inv, Frame::new(t1, t2), &CyclidicOptions::default()).unwrap();
    out.push(("inverted freeform, carried frame", inv, net));
    out
}

/// `n` equally spaced values in [0, 1].
fn params(n: usize) -> Vec<f64> {
    (0..n).map(|k| k as f64 / (n - 1) as f64).collect()
}

#[test]
fn closed_form_and_bezier_agree_and_interpolate_corners() {
    for (name, g, net) in nets() {
        let size = g.bbox_diagonal();
        let (mut agree, mut corners) = (0f64, 0f64);
        for (i, j) in faces(&net) {
            let p = net.patch(i, j);
            for u in params(9) {
                for v in params(9) {
                    agree = agree.max(p.point(u, v).distance(p.bezier().point(u, v)) / size);
                }
            }
            let quad = g.face(i, j);
            for (k, (u, v)) in [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
                .into_iter()
                .enumerate()
            {
                corners = corners
                    .max(p.point(u, v).distance(quad[k]) / size)
                    .max(p.bezier().point(u, v).distance(quad[k]) / size);
            }
        }
        println!("{name}: closed form vs Bézier {agree:.2e}, corners {corners:.2e}");
        assert!(agree <= 1e-9 && corners <= 1e-12, "{name}");
    }
}

/// A small deterministic generator for random quads.
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn unit(&mut self) -> DVec3 {
        loop {
            let v = DVec3::new(self.next(), self.next(), self.next()) * 2.0 - DVec3::ONE;
            if (0.1..1.0).contains(&v.length()) {
                return v.normalize();
            }
        }
    }
}

/// Random circular quads (four points in cyclic order on a random circle) with a
/// random orthonormal frame at the first corner.
fn random_patches(seed: u64) -> impl Iterator<Item = ([DVec3; 4], Frame)> {
    let mut rng = Lcg(seed);
    std::iter::repeat_with(move || {
        let (c, n) = (rng.unit() * 3.0, rng.unit());
        let x = n.any_orthonormal_vector();
        let y = n.cross(x);
        let r = 0.5 + 2.0 * rng.next();
        let mut angles: Vec<f64> = (0..4).map(|_| rng.next() * std::f64::consts::TAU).collect();
        angles.sort_by(f64::total_cmp);
        let quad: [DVec3; 4] =
            std::array::from_fn(|k| c + r * (angles[k].cos() * x + angles[k].sin() * y));
        let t1 = rng.unit();
        let t2 = rng.unit().reject_from(t1).normalize();
        (quad, Frame::new(t1, t2))
    })
}

#[test]
fn random_patches_closed_form_matches_bezier_and_isolines_are_circles() {
    let (mut agree, mut circ, mut unfolded) = (0f64, 0f64, 0);
    for (quad, frame) in random_patches(7).take(1000) {
        let r = quad[0].distance(quad[2]).max(quad[1].distance(quad[3])) / 2.0;
        let p = Patch::new(quad, frame).unwrap();
        assert_ne!(
            p.fold(),
            Some(FoldReason::Crossed),
            "cyclic order is not crossed"
        );
        if p.fold().is_some() {
            continue; // arcs over 180° with a random frame: the Bézier form needs positive weights
        }
        unfolded += 1;
        let size = 2.0 * r;
        let ts = params(7);
        for &u in &ts {
            for &v in &ts {
                agree = agree.max(p.point(u, v).distance(p.bezier().point(u, v)) / size);
            }
            let iso_u: Vec<DVec3> = ts.iter().map(|&v| p.point(u, v)).collect();
            let iso_v: Vec<DVec3> = ts.iter().map(|&v| p.point(v, u)).collect();
            for line in [iso_u, iso_v] {
                let circle = circle3(line[0], line[3], line[6]);
                for q in &line {
                    circ = circ.max(circle_distance(*q, circle) / size);
                }
            }
        }
    }
    println!("{unfolded} unfolded random patches: closed form vs Bézier {agree:.2e}, isolines off circles {circ:.2e}");
    assert!(unfolded > 100 && agree <= 1e-9 && circ <= 1e-9);
}

/// The design note's closed-form Bézier patch of a quad with the frame `f` at A
/// (embedded quads: σ = σ_B = σ_D = +1), written out independently of the library.
fn note_bezier([a, b, c, d]: [DVec3; 4], f: Frame) -> ([[DVec3; 3]; 3], [[f64; 3]; 3]) {
    let unit = |x: DVec3, y: DVec3| (y - x).normalize();
    let (e1, e2, ef, g) = (unit(a, b), unit(a, d), unit(b, c), unit(d, c));
    let k = b.distance(d) / a.distance(c);
    let refl = |x: DVec3, e: DVec3| x - 2.0 * x.dot(e) * e;
    let det = |x: DVec3, y: DVec3, z: DVec3| x.dot(y.cross(z));
    let (t2b, t1d) = (refl(f.t2, e1), refl(f.t1, e2));
    let (w10, w01) = (f.t1.dot(e1), f.t2.dot(e2));
    let (w21, w12) = (k * t2b.dot(ef), k * t1d.dot(g));
    let p10 = a + f.t1 * a.distance(b) / (2.0 * w10);
    let p01 = a + f.t2 * a.distance(d) / (2.0 * w01);
    let p21 = b + t2b * b.distance(c) / (2.0 * t2b.dot(ef));
    let p12 = d + t1d * d.distance(c) / (2.0 * t1d.dot(g));
    let n = f.n;
    let w = -k * det(ef, e1, n);
    let omega = k * (ef.dot(n) * e1 - e1.dot(n) * ef - ef.dot(e1) * n);
    let q0 = det(e1, e2, n);
    let q = e1.dot(e2) * n - n.dot(e2) * e1 - n.dot(e1) * e2;
    let w11 = (w + q0) / 2.0;
    let p11 = (w * (a + c) + (c - a).cross(omega) + q0 * (b + d) + (b - d).cross(q)) / (4.0 * w11);
    (
        [[a, p01, d], [p10, p11, p12], [b, p21, c]],
        [[1.0, w01, 1.0], [w10, w11, w12], [1.0, w21, k * k]],
    )
}

#[test]
fn bezier_form_is_the_design_notes_and_the_naive_centre_is_wrong() {
    let (mut points, mut weights, mut naive, mut naive_circle, mut n) =
        (0f64, 0f64, f64::INFINITY, 0f64, 0);
    for (quad, frame) in random_patches(5).take(1000) {
        let p = Patch::new(quad, frame).unwrap();
        if p.fold().is_some() {
            continue;
        }
        n += 1;
        let size = quad[0].distance(quad[2]).max(quad[1].distance(quad[3]));
        let (np, nw) = note_bezier(quad, frame);
        let b = p.bezier();
        for s in 0..3 {
            for t in 0..3 {
                points = points.max(b.points[s][t].distance(np[s][t]) / size);
                weights = weights.max((b.weights[s][t] - nw[s][t]).abs() / nw[s][t].abs().max(1.0));
            }
        }
        // The naive tensor-product centre: w11 = w10·w01, P11 = P10 + P01 − A.
        let mut bad = *b;
        bad.weights[1][1] = nw[1][0] * nw[0][1];
        bad.points[1][1] = np[1][0] + np[0][1] - quad[0];
        naive = naive.min(bad.points[1][1].distance(b.points[1][1]) / size);
        let iso: Vec<DVec3> = params(7).iter().map(|&v| bad.point(0.5, v)).collect();
        let circle = circle3(iso[0], iso[3], iso[6]);
        let off = iso
            .iter()
            .map(|q| circle_distance(*q, circle))
            .fold(0.0, f64::max);
        naive_circle = naive_circle.max(off / size);
    }
    println!(
        "{n} random embedded patches: Bézier vs the note's formulas: points {points:.2e}, weights {weights:.2e}; \
         naive centre off by at least {naive:.2e}, its u = 1/2 isoline off a circle by up to {naive_circle:.2e}"
    );
    assert!(n > 100 && points <= 1e-9 && weights <= 1e-9 && naive > 0.0 && naive_circle > 1e-3);
}

#[test]
fn crossed_patches_closed_form_matches_bezier_away_from_poles() {
    // With `allow_folded`, a crossed quad (σ = −1) still gets a patch whose two forms agree.
    let (mut worst, mut n) = (0f64, 0);
    for (q, frame) in random_patches(3).take(300) {
        let quad = [q[0], q[2], q[1], q[3]];
        let p = Patch::new(quad, frame).unwrap();
        assert_eq!(p.fold(), Some(FoldReason::Crossed));
        let b = p.bezier();
        let wmax = b
            .weights
            .iter()
            .flatten()
            .fold(0.0f64, |m, w| m.max(w.abs()));
        let size = quad[0].distance(quad[2]).max(quad[1].distance(quad[3]));
        for u in params(7) {
            for v in params(7) {
                let (bu, bv) = (
                    [(1.0 - u) * (1.0 - u), 2.0 * u * (1.0 - u), u * u],
                    [(1.0 - v) * (1.0 - v), 2.0 * v * (1.0 - v), v * v],
                );
                let w: f64 = (0..9)
                    .map(|s| b.weights[s / 3][s % 3] * bu[s / 3] * bv[s % 3])
                    .sum();
                if w.abs() > 1e-2 * wmax {
                    n += 1;
                    let x = p.point(u, v);
                    worst = worst.max(x.distance(b.point(u, v)) / size.max(x.length()));
                }
            }
        }
    }
    println!("crossed patches: closed form vs Bézier {worst:.2e} at {n} samples away from poles");
    assert!(n > 5000 && worst <= 1e-9);
}

#[test]
fn isoparametric_lines_are_circular_arcs() {
    let k = 9;
    for (name, g, net) in nets() {
        let size = g.bbox_diagonal();
        let mut worst = 0f64;
        for (i, j) in faces(&net) {
            let s = net.sample_patch(i, j, k);
            for a in 0..k {
                let along_v: Vec<DVec3> = (0..k).map(|b| s[a * k + b]).collect();
                let along_u: Vec<DVec3> = (0..k).map(|b| s[b * k + a]).collect();
                for line in [along_u, along_v] {
                    let circle = circle3(line[0], line[k / 2], line[k - 1]);
                    for q in &line {
                        worst = worst.max(circle_distance(*q, circle) / size);
                    }
                }
            }
        }
        println!("{name}: isolines off their circles {worst:.2e}");
        assert!(worst <= 1e-9, "{name}");
    }
}

#[test]
fn sample_patch_contract_and_shared_boundaries() {
    let k = 6;
    for (name, g, net) in nets() {
        let size = g.bbox_diagonal();
        let mut worst = 0f64;
        for (i, j) in faces(&net) {
            let s = net.sample_patch(i, j, k);
            assert_eq!(s.len(), k * k);
            // (0,0) at (i,j), u towards (i+1,j), v towards (i,j+1).
            for (idx, (di, dj)) in [
                (0, (0, 0)),
                ((k - 1) * k, (1, 0)),
                (k - 1, (0, 1)),
                (k * k - 1, (1, 1)),
            ] {
                assert!(
                    s[idx].distance(g.vertex(i + di, j + dj)) <= 1e-12 * size,
                    "{name}"
                );
            }
            if i + 2 < g.rows {
                let t = net.sample_patch(i + 1, j, k);
                for b in 0..k {
                    worst = worst.max(s[(k - 1) * k + b].distance(t[b]) / size);
                }
            }
            if j + 2 < g.cols {
                let t = net.sample_patch(i, j + 1, k);
                for a in 0..k {
                    worst = worst.max(s[a * k + k - 1].distance(t[a * k]) / size);
                }
            }
        }
        println!("{name}: shared boundary samples differ by {worst:.2e}");
        assert!(worst <= 1e-12, "{name}");
    }
}

#[test]
fn tangent_planes_agree_across_patch_edges() {
    let ts = params(7);
    for (name, _, net) in nets() {
        let mut worst = 0f64;
        let angle = |a: DVec3, b: DVec3| a.cross(b).length().atan2(a.dot(b));
        for (i, j) in faces(&net) {
            let here = *net.patch(i, j).bezier();
            if i + 2 < net.rows() {
                let there = *net.patch(i + 1, j).bezier();
                for &t in &ts {
                    worst = worst.max(angle(here.normal(1.0, t), there.normal(0.0, t)));
                }
            }
            if j + 2 < net.cols() {
                let there = *net.patch(i, j + 1).bezier();
                for &t in &ts {
                    worst = worst.max(angle(here.normal(t, 1.0), there.normal(t, 0.0)));
                }
            }
        }
        println!("{name}: tangent planes across edges differ by {worst:.2e} rad");
        assert!(worst <= 1e-9, "{name}");
    }
}

#[test]
fn torus_net_lies_on_the_torus() {
    let (g, net) = net_of(&torus());
    let size = g.bbox_diagonal();
    // Tube of radius 3 around the circle of radius 7 about the y axis through (0, 0, −10).
    let dist = |p: DVec3| {
        let q = p - DVec3::new(0.0, 0.0, -10.0);
        let rho = (q.x * q.x + q.z * q.z).sqrt();
        (((rho - 7.0).powi(2) + q.y * q.y).sqrt() - 3.0).abs()
    };
    let mut worst = 0f64;
    for (i, j) in faces(&net) {
        for p in net.sample_patch(i, j, 7) {
            worst = worst.max(dist(p) / size);
        }
    }
    println!("torus: distance of the net from the torus {worst:.2e}");
    assert!(worst <= 1e-9);
}

/// Largest distance from its plane of the samples of every curvature line of a net
/// (boundary samples of the patches along each mesh line).
fn line_planarity(g: &QuadGrid, net: &CyclidicNet) -> f64 {
    let k = 7;
    let mut worst = 0f64;
    for j in 0..g.cols {
        let (pj, b) = if j + 1 < g.cols {
            (j, 0)
        } else {
            (j - 1, k - 1)
        };
        let pts: Vec<DVec3> = (0..g.rows - 1)
            .flat_map(|i| {
                let s = net.sample_patch(i, pj, k);
                (0..k).map(move |a| s[a * k + b])
            })
            .collect();
        worst = worst.max(plane_deviation(&pts));
    }
    for i in 0..g.rows {
        let (pi, a) = if i + 1 < g.rows {
            (i, 0)
        } else {
            (i - 1, k - 1)
        };
        let pts: Vec<DVec3> = (0..g.cols - 1)
            .flat_map(|j| {
                let s = net.sample_patch(pi, j, k);
                (0..k).map(move |b| s[a * k + b])
            })
            .collect();
        worst = worst.max(plane_deviation(&pts));
    }
    worst / g.bbox_diagonal()
}

#[test]
fn curvature_lines_are_planar_on_planar_line_meshes() {
    for (name, d) in [("dupin30", dupin30()), ("freeform", freeform())] {
        let (g, net) = net_of(&d);
        let planar = line_planarity(&g, &net);
        // Control: the same mesh with the §4.4 frame at (0, 0) turned by 0.2 rad
        // about the normal keeps C¹ but loses planar lines (§4.4).
        let f = net.frame(0, 0);
        let (c, s) = (0.2f64.cos(), 0.2f64.sin());
        let turned = Frame::new(c * f.t1 + s * f.t2, c * f.t2 - s * f.t1);
        let other = CyclidicNet::from_frame(&g, turned, &CyclidicOptions::default()).unwrap();
        let control = line_planarity(&g, &other);
        println!(
            "{name}: curvature lines off their planes {planar:.2e} (turned frame: {control:.2e})"
        );
        assert!(planar <= 1e-9 && control > 1e-4, "{name}");
        // The arcs of one line have parallel normals.
        for line in net.curvature_lines() {
            for w in line.arcs.windows(2) {
                assert!(w[0].normal.cross(w[1].normal).length() <= 1e-9, "{name}");
            }
        }
    }
}

/// Check that the arcs of a line pass through the mesh vertices of the line and
/// that the boundary samples of the patches lie on them.
fn check_arcs(g: &QuadGrid, net: &CyclidicNet) -> f64 {
    let size = g.bbox_diagonal();
    let mut worst = 0f64;
    for line in net.curvature_lines() {
        let verts: Vec<DVec3> = match line.family {
            Family::U => g.column(line.index).collect(),
            Family::V => g.row(line.index).collect(),
        };
        assert!(line.arcs[0].start.distance(verts[0]) <= 1e-12 * size);
        assert!(
            line.arcs
                .last()
                .unwrap()
                .end
                .distance(*verts.last().unwrap())
                <= 1e-12 * size
        );
        for w in line.arcs.windows(2) {
            assert!(w[0].end.distance(w[1].start) <= 1e-12 * size);
        }
        // Every vertex on some arc's circle.
        for v in &verts {
            let d = line
                .arcs
                .iter()
                .map(|a| (v.distance(a.center) - a.radius).abs())
                .fold(f64::INFINITY, f64::min);
            worst = worst.max(d / size);
        }
    }
    worst
}

#[test]
fn circular_guide_gives_one_arc_per_line() {
    let (g, net) = net_of(&circular_u());
    let lines = net.curvature_lines();
    let u: Vec<usize> = lines
        .iter()
        .filter(|l| l.family == Family::U)
        .map(|l| l.arcs.len())
        .collect();
    let v: Vec<usize> = lines
        .iter()
        .filter(|l| l.family == Family::V)
        .map(|l| l.arcs.len())
        .collect();
    println!("circular guide_u: arcs per u-line {u:?}, per v-line {v:?}");
    assert_eq!(u, vec![1; g.cols]);
    assert!(
        v.iter().all(|&n| n == g.cols - 1),
        "the B-spline guide's family is not circular"
    );
    // Independently: all boundary samples of a u-line on one circle.
    let size = g.bbox_diagonal();
    let mut worst = 0f64;
    for j in 0..g.cols {
        let (pj, b) = if j + 1 < g.cols { (j, 0) } else { (j - 1, 4) };
        let pts: Vec<DVec3> = (0..g.rows - 1)
            .flat_map(|i| {
                let s = net.sample_patch(i, pj, 5);
                (0..5).map(move |a| s[a * 5 + b])
            })
            .collect();
        let circle = circle3(pts[0], pts[pts.len() / 2], pts[pts.len() - 1]);
        for p in &pts {
            worst = worst.max(circle_distance(*p, circle) / size);
        }
    }
    let on_arcs = check_arcs(&g, &net);
    println!("circular guide_u: u-line samples off one circle {worst:.2e}; vertices off their arcs {on_arcs:.2e}");
    assert!(worst <= 1e-9 && on_arcs <= 1e-9);
}

#[test]
fn biarc_guide_gives_biarcs() {
    let (g, net) = net_of(&biarc());
    let size = g.bbox_diagonal();
    for line in net
        .curvature_lines()
        .iter()
        .filter(|l| l.family == Family::U)
    {
        assert_eq!(line.arcs.len(), 2, "u-line {}", line.index);
        let junction = g.vertex(BIARC_JUNCTION, line.index);
        assert!(line.arcs[0].end.distance(junction) <= 1e-12 * size);
        // A bi-arc: the two circles are tangent at the junction (collinear centres).
        let (a, b) = (line.arcs[0], line.arcs[1]);
        let off = (a.center - junction).cross(b.center - junction).length() / size / size;
        assert!(
            off <= 1e-9,
            "u-line {}: circles not tangent, {off:e}",
            line.index
        );
    }
    let on_arcs = check_arcs(&g, &net);
    println!("bi-arc guide: every u-line two tangent arcs; vertices off their arcs {on_arcs:.2e}");
    assert!(on_arcs <= 1e-9);
}

#[test]
fn nurbs_matches_the_patches() {
    for (name, g, net) in nets() {
        let size = g.bbox_diagonal();
        let nurbs = net.nurbs();
        assert_eq!((nurbs.rows, nurbs.cols), (2 * g.rows - 1, 2 * g.cols - 1));
        assert_eq!(nurbs.knots_u.len(), nurbs.rows + 3);
        assert_eq!(nurbs.knots_v.len(), nurbs.cols + 3);
        assert_eq!(&nurbs.knots_u[..5], &[0.0, 0.0, 0.0, 1.0, 1.0]);
        assert!(nurbs.weights.iter().all(|w| *w > 0.0), "{name}");
        let mut worst = 0f64;
        for (i, j) in faces(&net) {
            let p = net.patch(i, j);
            for u in params(5) {
                for v in params(5) {
                    let q = nurbs.point(i as f64 + u, j as f64 + v);
                    worst = worst.max(q.distance(p.point(u, v)) / size);
                }
            }
            // Neighbouring patches' Bézier edges, scaled to the whole net, are the
            // NURBS's: its vertex control points are the mesh vertices.
            assert!(
                nurbs.control_points[2 * i * nurbs.cols + 2 * j].distance(g.vertex(i, j))
                    <= 1e-12 * size
            );
        }
        println!("{name}: NURBS vs patches {worst:.2e}");
        assert!(worst <= 1e-9, "{name}");
    }
}

#[test]
fn carried_frames_do_not_depend_on_the_path_and_match_the_gauss_frames() {
    for (name, g, net) in nets() {
        // Carry the net's frame at (0, 0) along row 0 first, then down every column.
        let (rows, cols) = (g.rows, g.cols);
        let mut frames = vec![net.frame(0, 0); rows * cols];
        for j in 1..cols {
            frames[j] = frames[j - 1].carried(g.vertex(0, j - 1), g.vertex(0, j), Family::V);
        }
        for i in 1..rows {
            for j in 0..cols {
                frames[i * cols + j] = frames[(i - 1) * cols + j].carried(
                    g.vertex(i - 1, j),
                    g.vertex(i, j),
                    Family::U,
                );
            }
        }
        let mut worst = 0f64;
        for i in 0..rows {
            for j in 0..cols {
                let (a, b) = (net.frame(i, j), frames[i * cols + j]);
                worst = worst
                    .max(a.t1.distance(b.t1))
                    .max(a.t2.distance(b.t2))
                    .max(a.n.distance(b.n));
            }
        }
        println!(
            "{name}: frames carried along two paths (or §4.4 vs carried) differ by {worst:.2e}"
        );
        assert!(worst <= 1e-9, "{name}");
        // The §4.4 normal is the Gauss map.
        if !g.normals.is_empty() {
            let off = (0..rows * cols)
                .map(|k| net.frame(k / cols, k % cols).n.distance(g.normals[k]))
                .fold(0.0, f64::max);
            assert!(off <= 1e-9, "{name}: frame normal vs node axis {off:e}");
        }
    }
}

#[test]
fn dense_mesh_is_the_patch_samples() {
    let (g, net) = net_of(&dupin30());
    let k = 4;
    let dense = net.dense(k);
    assert_eq!(
        (dense.rows, dense.cols),
        ((g.rows - 1) * (k - 1) + 1, (g.cols - 1) * (k - 1) + 1)
    );
    let size = g.bbox_diagonal();
    for (i, j) in faces(&net) {
        let s = net.sample_patch(i, j, k);
        for a in 0..k {
            for b in 0..k {
                let d = dense.vertex(i * (k - 1) + a, j * (k - 1) + b);
                assert!(d.distance(s[a * k + b]) <= 1e-12 * size);
            }
        }
    }
    for i in 0..g.rows {
        for j in 0..g.cols {
            assert!(
                dense
                    .vertex(i * (k - 1), j * (k - 1))
                    .distance(g.vertex(i, j))
                    <= 1e-12 * size
            );
            // The net's normal at a vertex is the node axis (§4.4).
            let n = dense.normals[i * (k - 1) * dense.cols + j * (k - 1)];
            assert!(n.distance(g.normals[i * g.cols + j]) <= 1e-9);
        }
    }
}

fn square_grid() -> QuadGrid {
    QuadGrid::new(
        2,
        2,
        vec![DVec3::ZERO, DVec3::Y, DVec3::X, DVec3::X + DVec3::Y],
        vec![],
    )
}

#[test]
fn errors() {
    let opts = CyclidicOptions::default();
    let frame = Frame::new(DVec3::X, DVec3::Y);
    // TooSmall.
    let line = QuadGrid::new(1, 3, vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![]);
    let e = CyclidicNet::from_frame(&line, frame, &opts).unwrap_err();
    assert_eq!(e, CyclidicError::TooSmall { rows: 1, cols: 3 });
    assert!(e.to_string().contains("1 × 3") && e.to_string().contains("at least 2 × 2"));
    // NoNormals.
    let e = CyclidicNet::from_normals(&square_grid(), &opts).unwrap_err();
    assert_eq!(e, CyclidicError::NoNormals);
    assert!(e.to_string().contains("from_frame"));
    // GaussUndetermined.
    let mut sq = square_grid();
    sq.normals = vec![DVec3::Z; 4];
    let e = CyclidicNet::from_normals(&sq, &opts).unwrap_err();
    assert_eq!(e, CyclidicError::GaussUndetermined { rows: 2, cols: 2 });
    assert!(e.to_string().contains("2 × 2") && e.to_string().contains("3 or more"));
    // GaussLineDegenerate: a flat 3 × 3 grid, all normals equal.
    let flat = QuadGrid::new(
        3,
        3,
        (0..9)
            .map(|k| DVec3::new((k / 3) as f64, (k % 3) as f64, 0.0))
            .collect(),
        vec![DVec3::Z; 9],
    );
    let e = CyclidicNet::from_normals(&flat, &opts).unwrap_err();
    assert!(
        matches!(
            e,
            CyclidicError::GaussLineDegenerate {
                family: Family::U,
                index: 0,
                ..
            }
        ),
        "{e:?}"
    );
    assert!(
        e.to_string().contains("u-line (along guide_u, fixed j) 0"),
        "{e}"
    );
    // GaussNotOrthogonal: tilt one node axis off the Gauss map.
    let (g, _) = net_of(&dupin30());
    let mut tilted = g.clone();
    let k = tilted.index(1, 1);
    tilted.normals[k] = (tilted.normals[k] + DVec3::new(0.05, 0.0, 0.0)).normalize();
    let e = CyclidicNet::from_normals(&tilted, &opts).unwrap_err();
    assert!(
        matches!(e, CyclidicError::GaussNotOrthogonal { vertex: (1, 1), .. }),
        "{e:?}"
    );
    assert!(e.to_string().contains("vertex (1, 1)") && e.to_string().contains("not 90°"));
    // FrameNotOrthonormal.
    let e = CyclidicNet::from_frame(
        &square_grid(),
        Frame::new(DVec3::X, DVec3::new(0.1, 1.0, 0.0)),
        &opts,
    )
    .unwrap_err();
    assert!(
        matches!(e, CyclidicError::FrameNotOrthonormal { .. }),
        "{e:?}"
    );
    assert!(e.to_string().contains("t1·t2 = 1.0e-1"), "{e}");
    // A NaN frame (once accepted: `f64::max` dropped the NaN, and 339 853 nulls
    // were written).
    let e = CyclidicNet::from_frame(
        &square_grid(),
        Frame::new(DVec3::new(f64::NAN, 0.0, 0.0), DVec3::Y),
        &opts,
    )
    .unwrap_err();
    assert!(
        matches!(e, CyclidicError::FrameNotOrthonormal { .. }),
        "{e:?}"
    );
    // NotCircular: move one vertex off the circle of its face.
    let mut off = g.clone();
    let k = off.index(2, 3);
    off.vertices[k] += DVec3::new(0.0, 0.0, 1e-3);
    let e = CyclidicNet::from_normals(&off, &opts).unwrap_err();
    assert!(
        matches!(e, CyclidicError::NotCircular { face: (1, 2), .. }),
        "{e:?}"
    );
    assert!(e.to_string().contains("face (1, 2) is not circular"), "{e}");
    // Folded: a bow-tie, an arc over 180°, and both accepted with allow_folded.
    let bow = QuadGrid::new(
        2,
        2,
        vec![DVec3::ZERO, DVec3::Y, DVec3::X + DVec3::Y, DVec3::X],
        vec![],
    );
    let e = CyclidicNet::from_frame(&bow, frame, &opts).unwrap_err();
    assert_eq!(
        e,
        CyclidicError::Folded {
            face: (0, 0),
            reason: FoldReason::Crossed
        }
    );
    assert!(
        e.to_string().contains("face (0, 0) is folded") && e.to_string().contains("bow-tie"),
        "{e}"
    );
    let backwards = Frame::new(-DVec3::X, DVec3::Y);
    let e = CyclidicNet::from_frame(&square_grid(), backwards, &opts).unwrap_err();
    assert!(
        matches!(
            e,
            CyclidicError::Folded {
                face: (0, 0),
                reason: FoldReason::ArcOver180 { edge: "AB", .. }
            }
        ),
        "{e:?}"
    );
    assert!(e.to_string().contains("360.000°"), "{e}");
    let allow = CyclidicOptions {
        allow_folded: true,
        ..opts
    };
    let net = CyclidicNet::from_frame(&bow, frame, &allow).unwrap();
    assert_eq!(net.folded(), vec![((0, 0), FoldReason::Crossed)]);
    // A unit square and beside it a square with two corners swapped: only the
    // second is named, with the fold its patch (computed on demand) carries.
    let pair = QuadGrid::new(
        2,
        3,
        vec![
            DVec3::ZERO,
            DVec3::Y,
            DVec3::X + 2.0 * DVec3::Y,
            DVec3::X,
            DVec3::X + DVec3::Y,
            2.0 * DVec3::Y,
        ],
        vec![],
    );
    let net = CyclidicNet::from_frame(&pair, frame, &allow).unwrap();
    assert_eq!(net.patch(0, 0).fold(), None);
    let fold = net.patch(0, 1).fold().expect("the second face is folded");
    assert_eq!(net.folded(), vec![((0, 1), fold)]);
    // A centre weight that is not positive: the first random circular quad and
    // frame that give one (found deterministically).
    let (quad, frame) = random_patches(11)
        .find(|(q, f)| {
            matches!(
                Patch::new(*q, *f).unwrap().fold(),
                Some(FoldReason::CentreWeight { .. })
            )
        })
        .expect("a random patch with a non-positive centre weight");
    let [a, b, c, d] = quad;
    let grid = QuadGrid::new(2, 2, vec![a, d, b, c], vec![]);
    let e = CyclidicNet::from_frame(&grid, frame, &opts).unwrap_err();
    assert!(
        matches!(e, CyclidicError::Folded { face: (0, 0), reason: FoldReason::CentreWeight { weight } } if weight <= 0.0),
        "{e:?}"
    );
    assert!(
        e.to_string().contains("centre weight") && e.to_string().contains("allow_folded"),
        "{e}"
    );
}

#[test]
fn gauss_frames_on_a_strip_of_one_face_row() {
    // The first two rows of the Dupin mesh: t1 comes from orthogonality to the
    // v-lines' Gauss circles.
    let full = mesh(&dupin30());
    let n = 2 * full.cols;
    let g = QuadGrid::new(
        2,
        full.cols,
        full.vertices[..n].to_vec(),
        full.normals[..n].to_vec(),
    );
    let net = CyclidicNet::from_normals(&g, &CyclidicOptions::default()).unwrap();
    let carried =
        CyclidicNet::from_frame(&g, net.frame(0, 0), &CyclidicOptions::default()).unwrap();
    let mut worst = 0f64;
    for i in 0..g.rows {
        for j in 0..g.cols {
            let (a, b) = (net.frame(i, j), carried.frame(i, j));
            worst = worst.max(a.t1.distance(b.t1)).max(a.t2.distance(b.t2));
        }
    }
    println!("2 × 7 strip: §4.4 frames vs carried {worst:.2e}");
    assert!(worst <= 1e-9);
}

#[test]
fn arc_points_turn_from_start_to_end_on_the_circle() {
    // A circle of radius 2.5 about (1, 2, 3) in a tilted plane, parametrised
    // here with std's cos and sin, not with the arc's own formula.
    let (center, radius) = (DVec3::new(1.0, 2.0, 3.0), 2.5);
    let normal = DVec3::new(1.0, -2.0, 0.5).normalize();
    let x = normal.any_orthonormal_vector();
    let y = normal.cross(x);
    let at = |phi: f64| center + radius * (phi.cos() * x + phi.sin() * y);
    for sweep in [0.3, 2.0, 4.0, 6.0] {
        let arc = Arc {
            center,
            radius,
            normal,
            start: at(0.0),
            end: at(sweep),
        };
        assert!((arc.sweep() - sweep).abs() < 1e-14);
        for t in [0.0, 0.25, 0.5, 0.9, 1.0] {
            let p = arc.point(t);
            assert!(((p - center).length() - radius).abs() < 1e-14);
            assert!(normal.dot(p - center).abs() < 1e-14);
            assert!((p - at(t * sweep)).length() < 1e-14, "sweep {sweep}, t {t}");
        }
    }
}

/// A design of the Dupin family whose guides are polylines sampled from two
/// circular arcs (radius 1, 120° and 300°), θ = 30°, 25 × 21 vertices: the
/// mesh folds (§5.2) in two columns of bow-ties and a band turned over.
fn sampled_dupin() -> Design {
    let points = |n: usize, angle_deg: f64, along: fn(f64) -> [f64; 3]| {
        let t = |k: usize| (angle_deg * k as f64 / (n - 1) as f64).to_radians();
        GuideSpec::points((0..n).map(|k| along(t(k))).collect())
    };
    design(
        30.0,
        points(25, 120.0, |t| [t.sin(), 0.0, t.cos() - 1.0]),
        points(21, 300.0, |t| [0.0, t.sin(), t.cos() - 1.0]),
    )
}

/// Faces `(i, j)` of a grid.
type Faces = Vec<(usize, usize)>;

/// Folded faces of `g` found independently of `QuadGrid::folds`: each face is
/// projected on the plane orthogonal to the sum of its node axes; it is crossed
/// when two opposite edges intersect there (segment tests), and otherwise
/// turns by the sign of its shoelace area. Returns the crossed faces and the
/// faces turning the way fewer faces turn.
fn folds_by_hand(g: &QuadGrid) -> [Faces; 2] {
    let (mut crossed, mut ways) = (Vec::new(), [Vec::new(), Vec::new()]);
    for i in 0..g.rows - 1 {
        for j in 0..g.cols - 1 {
            let ids = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)];
            let axis: DVec3 = ids.iter().map(|&(a, b)| g.normals[g.index(a, b)]).sum();
            let e1 = axis.any_orthonormal_vector();
            let e2 = axis.normalize().cross(e1);
            let p: Vec<[f64; 2]> = ids
                .iter()
                .map(|&(a, b)| g.vertex(a, b))
                .map(|v| [v.dot(e1), v.dot(e2)])
                .collect();
            let side = |a: [f64; 2], b: [f64; 2], c: [f64; 2]| {
                ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])).signum()
            };
            let cross = |a, b, c, d| {
                side(a, b, c) * side(a, b, d) < 0.0 && side(c, d, a) * side(c, d, b) < 0.0
            };
            if cross(p[0], p[1], p[2], p[3]) || cross(p[1], p[2], p[3], p[0]) {
                crossed.push((i, j));
                continue;
            }
            let area: f64 = (0..4)
                .map(|k| p[k][0] * p[(k + 1) % 4][1] - p[(k + 1) % 4][0] * p[k][1])
                .sum();
            ways[usize::from(area < 0.0)].push((i, j));
        }
    }
    ways.sort_by_key(Vec::len);
    let [fewer, _] = ways;
    [crossed, fewer]
}

#[test]
fn a_folded_mesh_is_refused_by_the_same_fold_test_as_every_mesh() {
    // Once built without a word: the cross-ratio sign saw only the bow-ties
    // whose edges AB and CD cross, and no face turned over.
    let g = mesh(&sampled_dupin());
    let [crossed, turned] = folds_by_hand(&g);
    assert_eq!((crossed.len(), turned.len()), (48, 96));
    let first = *crossed.iter().chain(&turned).min().unwrap();
    let e = CyclidicNet::from_normals(&g, &CyclidicOptions::default()).unwrap_err();
    assert_eq!(
        e,
        CyclidicError::Folded {
            face: first,
            reason: FoldReason::TurnedOver
        }
    );
    assert!(e.to_string().starts_with("face (0, 0) is folded"), "{e}");
    let allow = CyclidicOptions {
        allow_folded: true,
        ..CyclidicOptions::default()
    };
    let net = CyclidicNet::from_normals(&g, &allow).unwrap();
    let folded = net.folded();
    let named = |reason| -> Vec<(usize, usize)> {
        folded
            .iter()
            .filter(|f| f.1 == reason)
            .map(|f| f.0)
            .collect()
    };
    assert_eq!(named(FoldReason::Crossed), crossed);
    assert_eq!(named(FoldReason::TurnedOver), turned);
    assert_eq!(folded.len(), g.folds().count());
}
