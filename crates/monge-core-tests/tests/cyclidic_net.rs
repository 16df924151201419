//! Cyclidic nets (§4.4, §4.6, §5.3): the whole net, on the torus, as one
//! NURBS, its carried frames, its dense mesh. Measured independently of the
//! construction: against the torus' equation, the patches' own samples and
//! frames carried along two paths.
//!
//! `cargo test -p monge-core-tests --test integration cyclidic_net:: -- --nocapture` prints the worst values.

use glam::DVec3;
use monge_core::cyclidic::{CyclidicNet, CyclidicOptions, Family};
use monge_core::QuadGrid;

use crate::common;
use common::cyclidic::{dupin30, faces, net_of, nets, params, torus};
use common::mesh;

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
