//! Cyclidic nets (§4.4, §4.6): the patches, their closed form against their
//! Bézier form (and the design note's formulas), their isolines, shared edges
//! and tangent planes. Measured independently of the construction: circles are
//! fitted to sampled points here (three-point circles), never taken from the
//! patch formulas.
//!
//! `cargo test -p monge-core-tests --test integration cyclidic_patches:: -- --nocapture` prints the worst values.

use glam::DVec3;
use monge_core::cyclidic::{FoldReason, Frame, Patch};

use crate::common;
use common::cyclidic::{faces, nets, params, random_patches};
use common::{circle3, circle_distance};

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
