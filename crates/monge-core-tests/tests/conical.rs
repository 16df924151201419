//! Conical meshes (§2.3), their face offsets and the vertex offsets of circular
//! meshes, measured independently on random designs of both modes.

use glam::DVec3;
use monge_core::conical::{conical_dual, ConicalMesh};
use monge_core::design::BSplineSpec;
use monge_core::measure::{conical_error, measure};
use monge_core::offset::{face_offset, vertex_offset};
use monge_core::{generate, Design, GenerateError, GenerateOptions, GuideSpec, QuadGrid};
use std::cell::{Cell, RefCell};

use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};

use crate::common;
use common::{own_face_planarity, TOL};

/// A cubic B-spline guide from the origin with start tangent `t`, bending in the
/// plane spanned by `t` and `d`.
fn guide(t: DVec3, d: DVec3, bends: &[(f64, f64)], samples: usize) -> GuideSpec {
    let mut cps = vec![[0.0; 3], t.to_array()];
    let mut along = 1.0;
    for &(step, off) in bends {
        along += step;
        cps.push((along * t + off * d).to_array());
    }
    GuideSpec::BSpline {
        bspline: BSplineSpec {
            degree: 3,
            control_points: cps,
            knots: None,
            weights: None,
            samples,
        },
        parameters: None,
    }
}

/// Random designs: guide_u in y = 0 (tangent x), guide_v in a plane through the
/// y axis tilted by `phi` from x = 0 (φ = 0: characteristic case).
fn design() -> impl Strategy<Value = Design> {
    let bends = prop::collection::vec((0.3f64..1.5, -1.2f64..1.2), 2..4);
    (
        bends.clone(),
        bends,
        0.0f64..60.0,
        -179.0f64..180.0,
        5usize..16,
        5usize..16,
    )
        .prop_map(|(bu, bv, phi, theta, nu, nv)| {
            let phi = phi.to_radians();
            let tilt = DVec3::new(phi.sin(), 0.0, phi.cos());
            Design {
                mesh: Default::default(),
                theta_deg: theta,
                guide_u: guide(DVec3::X, DVec3::Z, &bu, nu),
                guide_v: guide(DVec3::Y, tilt, &bv, nv),
                tolerance: None,
            }
        })
}

/// Every conical property of `c`, relative to its size; also checks its face
/// normals against the faces themselves.
fn conical_errors(c: &ConicalMesh) -> [f64; 4] {
    let g = &c.grid;
    let scale = g.bbox_diagonal();
    let mut planar: f64 = 0.0;
    let mut normals: f64 = 0.0;
    for i in 0..g.rows - 1 {
        for j in 0..g.cols - 1 {
            let q = g.face(i, j);
            planar = planar.max(own_face_planarity(&q) / scale);
            let n = c.face_normals[i * (g.cols - 1) + j];
            let h = n.dot(q[0]);
            for v in q {
                normals = normals.max((n.dot(v) - h).abs() / scale);
            }
        }
    }
    let m = measure(g);
    let lines = m.row_planarity.value.max(m.column_planarity.value);
    // Conical vertices: the four unit face normals around each interior vertex
    // (from the faces' own diagonals, oriented like the mesh's face normals, since
    // a folded mesh has faces turned over) lie on one circle of S².
    let faces = g.cols - 1;
    let own_normal = |i: usize, j: usize| {
        let [p0, p1, p2, p3] = g.face(i, j);
        let n = (p2 - p0).cross(p3 - p1).normalize();
        n * n.dot(c.face_normals[i * faces + j]).signum()
    };
    let mut cone: f64 = 0.0;
    for i in 1..g.rows - 1 {
        for j in 1..g.cols - 1 {
            let q = [
                own_normal(i - 1, j - 1),
                own_normal(i, j - 1),
                own_normal(i, j),
                own_normal(i - 1, j),
            ];
            cone = cone.max(own_face_planarity(&q));
        }
    }
    // `measure`'s conical error agrees where no face is turned over.
    if let Some(w) = conical_error(g) {
        assert!(w.value <= TOL || w.value >= cone);
    }
    [planar, normals, lines, cone]
}

#[test]
fn conical_meshes_and_offsets_are_exact() {
    let mut runner = TestRunner::new_with_rng(
        Config {
            cases: 600,
            failure_persistence: None,
            ..Config::default()
        },
        TestRng::deterministic_rng(RngAlgorithm::ChaCha),
    );
    let worst = RefCell::new([0.0f64; 7]);
    let built = Cell::new(0);
    runner
        .run(&design(), |d| {
            let circular = match generate(&d, &GenerateOptions::default()) {
                Ok(g) => g.grid,
                Err(GenerateError::ThetaInadmissible { .. }) | Err(GenerateError::Guide(_)) => {
                    return Ok(())
                }
                Err(e) => return Err(TestCaseError::fail(e.to_string())),
            };
            if circular.rows < 3 || circular.cols < 3 {
                return Ok(());
            }
            built.set(built.get() + 1);
            let c = conical_dual(&circular);
            let e = conical_errors(&c);
            // Face offsets: every face plane moves by exactly the distance.
            let scale = c.grid.bbox_diagonal();
            let mut offset_error: f64 = 0.0;
            let mut offset_conical: f64 = 0.0;
            for dist in [-0.3, 0.7] {
                let o = face_offset(&c, dist * scale);
                for (k, n) in c.face_normals.iter().enumerate() {
                    let (i, j) = (k / (c.grid.cols - 1), k % (c.grid.cols - 1));
                    let h = n.dot(c.grid.face(i, j)[0]);
                    for v in o.grid.face(i, j) {
                        offset_error =
                            offset_error.max((n.dot(v) - h - dist * scale).abs() / scale);
                    }
                }
                // Planar faces in the planes checked above, planar lines. (The
                // cone condition follows from the faces keeping their normals; a
                // large offset may flip faces past the focal points, so it is not
                // measured from the faces' own orientation here.)
                let [planar, normals, lines, _] = conical_errors(&o);
                offset_conical = offset_conical.max(planar).max(normals).max(lines);
            }
            // Vertex offsets of the circular mesh stay circular with planar lines.
            let mut vertex_offset_error: f64 = 0.0;
            for dist in [-0.2, 0.5] {
                let o: QuadGrid = vertex_offset(&circular, dist * circular.bbox_diagonal());
                let m = measure(&o);
                vertex_offset_error = vertex_offset_error.max(m.max_error());
            }
            let all = [e[0], e[1], e[2], e[3], offset_error, offset_conical, vertex_offset_error];
            for (w, v) in worst.borrow_mut().iter_mut().zip(all) {
                *w = w.max(v);
            }
            prop_assert!(
                all.iter().all(|&v| v <= TOL),
                "{d:?}: planar, normals, lines, cone, offset distance, offset conical, vertex offset = {all:?}"
            );
            Ok(())
        })
        .unwrap();
    let (worst, built) = (worst.into_inner(), built.get());
    eprintln!(
        "conical: {built} meshes; worst face planarity {:.1e}, face normals {:.1e}, line planarity {:.1e}, \
         conical {:.1e}; face offset distance {:.1e}, offset conical {:.1e}; circular vertex offsets {:.1e}",
        worst[0], worst[1], worst[2], worst[3], worst[4], worst[5], worst[6]
    );
    assert!(built > 300, "too few admissible designs: {built}");
}
