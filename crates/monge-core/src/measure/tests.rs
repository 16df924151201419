//! Tests of the measures against hand-computed values and exact surfaces (§2.2, §2.3).

use glam::DVec3;

use super::*;

fn v(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

/// A one-face grid with corners `A, B, C, D` = `(0,0), (1,0), (1,1), (0,1)`.
fn one_face([a, b, c, d]: [DVec3; 4]) -> QuadGrid {
    QuadGrid::new(2, 2, vec![a, d, b, c], vec![])
}

#[test]
fn finite_points_whose_differences_overflow_are_nan_not_a_panic() {
    // Once "Singular value was NaN" (a Python offset of 1.5e308).
    let p = [
        v(-1.5e308, 0.0, 0.0),
        v(1.5e308, 0.0, 0.0),
        v(0.0, 1.0, 0.0),
        v(0.0, 0.0, 1.0),
    ];
    assert!(polyline_planarity(&p).0.is_nan());
    let g = QuadGrid::new(2, 2, p.to_vec(), vec![]);
    let _ = measure(&g); // no panic; `measurable` says why it means nothing:
    assert!(matches!(
        measurable(&g),
        Err(MeasureError::ScaleOutOfRange { .. })
    ));
    let mut g = g;
    g.vertices[3].y = f64::INFINITY;
    assert!(matches!(
        measurable(&g),
        Err(MeasureError::NotFinite {
            what: "vertex",
            at: (1, 1),
            ..
        })
    ));
    g.vertices[3].y = 0.0;
    g.normals = vec![DVec3::Z, DVec3::Z, DVec3::NAN, DVec3::Z];
    assert!(matches!(
        measurable(&g),
        Err(MeasureError::NotFinite {
            what: "node axis",
            at: (1, 0),
            ..
        })
    ));
}

#[test]
fn the_first_of_equal_worst_elements_is_reported_and_a_nan_wins() {
    // A flat 6 × 3 grid; faces (1, 1) and (3, 1) twisted alike (corner
    // (i + 1, 2) lifted): rows are measured side by side and merged in order.
    let flat = |i: usize, j: usize| v(i as f64, j as f64, 0.0);
    let mut g = QuadGrid::new(6, 3, (0..18).map(|k| flat(k / 3, k % 3)).collect(), vec![]);
    for i in [1, 3] {
        g.vertices[(i + 1) * 3 + 2].z = 0.25;
    }
    let m = measure(&g);
    assert!(m.face_planarity.value > 0.0);
    assert_eq!(m.face_planarity.at, (1, 1));
    // A NaN in row 5 (the last) beats every number, wherever it is.
    g.vertices[5 * 3].x = f64::NAN;
    let m = measure(&g);
    assert!(m.face_planarity.value.is_nan());
    assert_eq!(m.face_planarity.at, (4, 0));
    assert!(m.row_planarity.value.is_nan() && m.row_planarity.at == (5, 0));
}

const TORUS_R: f64 = 3.0;
const TORUS_TUBE: f64 = 1.0;

fn torus_u(i: usize) -> f64 {
    0.3 + 0.07 * i as f64
}
fn torus_v(j: usize) -> f64 {
    -1.2 + 0.09 * j as f64
}

/// A torus patch: `i ↦ u` (around the axis), `j ↦ v` (around the tube),
/// normals radial from the tube's centre circle.
fn torus(rows: usize, cols: usize) -> QuadGrid {
    let mut vertices = Vec::new();
    let mut normals = Vec::new();
    for i in 0..rows {
        for j in 0..cols {
            let (u, w) = (torus_u(i), torus_v(j));
            let n = v(w.cos() * u.cos(), w.cos() * u.sin(), w.sin());
            vertices.push(TORUS_R * v(u.cos(), u.sin(), 0.0) + TORUS_TUBE * n);
            normals.push(n);
        }
    }
    QuadGrid::new(rows, cols, vertices, normals)
}

#[test]
fn measure_rectangle_and_isosceles_trapezoid_are_circular() {
    let rect = one_face([
        v(0.0, 0.0, 0.0),
        v(3.0, 0.0, 0.0),
        v(3.0, 1.0, 0.0),
        v(0.0, 1.0, 0.0),
    ]);
    let trap = one_face([
        v(-2.0, 0.0, 1.0),
        v(2.0, 0.0, 1.0),
        v(0.7, 1.3, 1.0),
        v(-0.7, 1.3, 1.0),
    ]);
    for g in [rect, trap] {
        let m = measure(&g);
        assert!(m.face_planarity.value <= 1e-15, "{m:?}");
        assert!(m.circularity.value <= 1e-15, "{m:?}");
        assert!(m.max_error() <= 1e-15, "{m:?}");
    }
}

#[test]
fn measure_kite_has_hand_computed_circularity() {
    // Best triple BCD (shape 4/5 vs 1/2 for ABD, 1/3 for ABC and CDA):
    // circle centre (3/4, 0), radius 5/4; A = (−1, 0) is 7/4 from the centre.
    let g = one_face([
        v(-1.0, 0.0, 0.0),
        v(0.0, -1.0, 0.0),
        v(2.0, 0.0, 0.0),
        v(0.0, 1.0, 0.0),
    ]);
    let m = measure(&g);
    assert_eq!(m.scale, 13f64.sqrt());
    assert!((m.circularity.value - 0.5 / 13f64.sqrt()).abs() < 1e-16);
    assert!(m.face_planarity.value <= 1e-16);
}

#[test]
fn circularity_scales_with_the_quad_at_every_accepted_size() {
    // The kite (circularity 1/2) at the extremes of the accepted design sizes
    // and beyond: lengths to the fifth power would overflow or underflow.
    let kite = [
        v(-1.0, 0.0, 0.0),
        v(0.0, -1.0, 0.0),
        v(2.0, 0.0, 0.0),
        v(0.0, 1.0, 0.0),
    ];
    for s in [1e-150, 1e-100, 1e-60, 1.0, 1e60, 1e100, 1e150] {
        let c = circularity(&kite.map(|p| p * s));
        assert!((c / s - 0.5).abs() < 1e-15, "size {s:e}: {c:e}");
    }
    // At a power of two the value is the same to the last bit.
    let c = circularity(&kite.map(|p| p * 2f64.powi(200)));
    assert_eq!(c, 0.5 * 2f64.powi(200));
}

#[test]
fn measure_twisted_quad_has_expected_diagonal_distance() {
    // Square of side 2 with B and D lifted by h, A and C lowered by h: the
    // diagonals are horizontal lines at heights −h and +h, crossing in plan.
    let h = 0.3;
    let g = one_face([
        v(0.0, 0.0, -h),
        v(2.0, 0.0, h),
        v(2.0, 2.0, -h),
        v(0.0, 2.0, h),
    ]);
    let m = measure(&g);
    assert!((m.face_planarity.value * m.scale - 2.0 * h).abs() < 1e-15);
    // Not planar, hence not circular either.
    assert!(m.circularity.value > 0.0);
}

#[test]
fn measure_parallel_diagonals_fall_back_to_plane_distance() {
    // Diagonals AC and BD both along x: a degenerate (crossed) face.
    let strip = [
        v(0.0, 0.0, 0.0),
        v(0.0, 1.0, 0.5),
        v(2.0, 0.0, 0.0),
        v(2.0, 1.0, 0.5),
    ];
    assert!(face_planarity(&strip) < 1e-16); // two parallel lines span a plane
                                             // Lift D by 0.5 off that plane (normal (0, −1, 2)/√5): the diagonals are
                                             // no longer parallel, so the line distance applies again and is positive.
    let mut lifted = strip;
    lifted[3] += 0.5 * v(0.0, -1.0, 2.0) / 5f64.sqrt();
    assert!(face_planarity(&lifted) > 0.0);
    // A crossed face, diagonals at an angle 1e-9 (below the 1e-6
    // threshold): their lines are 1 apart, yet the corners are only 2e-9
    // off a plane. The fallback (all four triples tie; A off plane BCD) says so.
    let nearly = [
        v(0.0, 0.0, 0.0),
        v(0.0, 1.0, 0.0),
        v(2.0, 0.0, 0.0),
        v(2.0, 1.0, 2e-9),
    ];
    assert!(
        (face_planarity(&nearly) - 2e-9).abs() < 1e-15,
        "{}",
        face_planarity(&nearly)
    );
    // Collinear corners: planar and (generalised) circular.
    let line = [
        v(0.0, 0.0, 0.0),
        v(1.0, 1.0, 1.0),
        v(3.0, 3.0, 3.0),
        v(2.0, 2.0, 2.0),
    ];
    assert_eq!(face_planarity(&line), 0.0);
    assert_eq!(circularity(&line), 0.0);
}

#[test]
fn measure_long_thin_face_has_no_spurious_circularity() {
    let l = 1e4;
    let eps = 1e-9;
    let rect = [
        v(0.0, 0.0, 0.0),
        v(l, 0.0, 0.0),
        v(l, 1.0, 0.0),
        v(0.0, 1.0, 0.0),
    ];
    assert!(circularity(&rect) <= 1e-15 * l);
    // D moved along the circle's normal direction (≈ x): error ≈ eps.
    let mut q = rect;
    q[3].x += eps;
    let c = circularity(&q);
    assert!((c - eps).abs() < 1e-3 * eps, "{c}");
    // Any corner moved by eps in any direction: error at most ≈ eps.
    for k in 0..4 {
        for d in [DVec3::X, DVec3::Y, DVec3::Z, -DVec3::X, -DVec3::Y] {
            let mut q = rect;
            q[k] += eps * d;
            let c = circularity(&q);
            assert!(c <= 1.01 * eps, "corner {k} dir {d}: {c}");
        }
    }
}

#[test]
fn measure_exact_torus_patch_is_clean() {
    let g = torus(12, 9);
    let m = measure(&g);
    assert!(m.max_error() <= 1e-14, "{m:?}");
    assert!(m.torsion.unwrap().value <= 1e-14);
    assert!(m.normal_length.unwrap().value <= 1e-14);
    let t = measure(&g.transposed());
    assert!(t.max_error() <= 1e-14, "{t:?}");
}

#[test]
fn measure_vertex_moved_off_its_face_plane_is_located() {
    let mut g = torus(12, 9);
    // Vertex (0, 0) is corner A of face (0, 0) only; move it along the face normal.
    let [a, b, c, d] = g.face(0, 0);
    let nu = (c - a).cross(d - b).normalize();
    let delta = 1e-7;
    g.vertices[0] += delta * nu;
    let m = measure(&g);
    // The diagonals of the isosceles trapezoid cross at A + s (C − A),
    // s = |AB| / (|AB| + |DC|); the lifted line AC moves there by (1 − s) δ.
    let s = (b - a).length() / ((b - a).length() + (c - d).length());
    let expect = (1.0 - s) * delta / m.scale;
    assert_eq!(m.face_planarity.at, (0, 0));
    assert!(
        (m.face_planarity.value - expect).abs() < 1e-5 * expect,
        "{m:?}"
    );
    // One corner δ out of the plane of the other three.
    assert_eq!(m.circularity.at, (0, 0));
    let rel = m.circularity.value * m.scale / delta;
    assert!((0.9..1.1).contains(&rel), "{rel}");
}

#[test]
fn measure_bent_row_is_caught_with_its_index() {
    let mut g = torus(12, 9);
    let (i0, j0) = (7, 4);
    let u = torus_u(i0);
    // Perpendicular to row i0's meridian plane (tangent to column j0's circle).
    let delta = 1e-6;
    let k = g.index(i0, j0);
    g.vertices[k] += delta * v(-u.sin(), u.cos(), 0.0);
    let m = measure(&g);
    assert_eq!(m.row_planarity.at, (i0, j0));
    let rel = m.row_planarity.value * m.scale / delta;
    assert!((0.5..=1.0).contains(&rel), "{rel}");
    assert!(m.column_planarity.value <= 1e-14, "{m:?}");
    let t = measure(&g.transposed());
    assert_eq!(t.column_planarity.at, (j0, i0));
    assert_eq!(t.column_planarity.value, m.row_planarity.value);
    assert!(t.row_planarity.value <= 1e-14);
}

#[test]
fn measure_long_normal_is_reported() {
    let mut g = torus(6, 5);
    let k = g.index(2, 3);
    g.normals[k] *= 1.1;
    let m = measure(&g);
    let l = m.normal_length.unwrap();
    assert_eq!(l.at, (2, 3));
    assert!((l.value - 0.1).abs() < 1e-15);
    assert!(m.torsion.unwrap().value <= 1e-14);
    assert_eq!(m.max_error(), l.value);
}

#[test]
fn measure_normal_rotated_about_its_edge_gives_torsion() {
    let mut g = torus(6, 5);
    let (i0, j0) = (2, 2);
    let (p, q) = (g.index(i0, j0), g.index(i0, j0 + 1));
    let e = (g.vertices[q] - g.vertices[p]).normalize();
    let phi: f64 = 0.01;
    let n = g.normals[p];
    let rotated = n * phi.cos() + e.cross(n) * phi.sin() + e * e.dot(n) * (1.0 - phi.cos());
    g.normals[p] = rotated;
    let m = measure(&g);
    let t = m.torsion.unwrap();
    let edge = (g.vertices[q] - g.vertices[p]).length() / m.scale;
    let expect = e.dot(rotated.cross(g.normals[q])).abs() * edge;
    assert!(expect > 0.9 * phi.sin() * edge);
    // The worst edge is the one rotated about, or the other row edge at the vertex.
    assert!([(i0, j0), (i0, j0 - 1)].contains(&t.at), "{t:?}");
    assert!(
        t.value >= expect * (1.0 - 1e-12) && t.value <= phi.sin() * edge * (1.0 + 1e-12),
        "{t:?}"
    );
    assert!(m.normal_length.unwrap().value <= 1e-15);
}

#[test]
fn measure_straight_and_planar_polylines_measure_zero() {
    let o = v(1e3, -2e3, 5e2);
    let d = v(1.0, 2.0, -0.5).normalize();
    let e = d.cross(v(0.3, -1.0, 0.2)).normalize();
    let ts: Vec<f64> = (0..50).map(|k| (k as f64 * 0.37).powf(1.3)).collect();
    let size = ts[49];
    let straight: Vec<DVec3> = ts.iter().map(|t| o + *t * d).collect();
    assert!(polyline_planarity(&straight).0 <= 1e-14 * size);
    // Nearly straight (1e-9 off the line) but exactly in a plane: the plane
    // is barely determined, yet the distances must stay at rounding level.
    for bend in [1e-3, 1e-6, 1e-9, 1e-12] {
        let nearly: Vec<DVec3> = ts
            .iter()
            .map(|t| o + *t * d + bend * (t * 0.4).sin() * e)
            .collect();
        let (dist, _) = polyline_planarity(&nearly);
        assert!(dist <= 1e-14 * size, "bend {bend}: {dist}");
    }
    let circle: Vec<DVec3> = (0..100)
        .map(|k| o + 7.0 * ((k as f64 * 0.05).cos() * d + (k as f64 * 0.05).sin() * e))
        .collect();
    assert!(polyline_planarity(&circle).0 <= 1e-14 * 14.0);
    assert_eq!(polyline_planarity(&circle[..2]), (0.0, 0));
}

#[test]
fn measure_degenerate_grids() {
    let empty = QuadGrid::new(0, 0, vec![], vec![]);
    let m = measure(&empty);
    assert_eq!(m.scale, 1.0);
    assert_eq!(m.max_error(), 0.0);
    let row = QuadGrid::new(
        1,
        3,
        vec![DVec3::ZERO, DVec3::X, DVec3::Y],
        vec![DVec3::Z; 3],
    );
    let m = measure(&row);
    assert_eq!(
        m.face_planarity,
        Worst {
            value: 0.0,
            at: (0, 0)
        }
    );
    assert_eq!(m.torsion.unwrap().value, 0.0);
    assert!(conical_error(&row).is_none());
    let mut nan = row.clone();
    nan.vertices[2].z = f64::NAN;
    assert!(measure(&nan).max_error().is_nan());
}

/// A surface of revolution on its meridian/parallel grid is conical too: the
/// four face normals at a vertex are two mirror pairs across the meridian
/// plane, i.e. an isosceles trapezoid — coplanar, hence on one circle of S².
#[test]
fn measure_conical_error_on_torus_and_perturbed() {
    let g = torus(8, 7);
    let c = conical_error(&g).unwrap();
    assert!(c.value <= 1e-14, "{c:?}");
    let mut bent = g.clone();
    let k = bent.index(3, 3);
    bent.vertices[k] += 1e-4 * bent.normals[k];
    let c = conical_error(&bent).unwrap();
    assert!(c.value > 1e-9, "{c:?}");
    assert!(
        (2..=4).contains(&c.at.0) && (2..=4).contains(&c.at.1),
        "{c:?}"
    );
}

#[test]
fn a_mesh_of_polygons_reports_its_least_planar_face_and_never_hides_a_nan() {
    use super::measure_polygons;
    // A unit square and a hexagon beside it, planar, then the hexagon's fourth corner
    // lifted by 0.01: the plane fitted to its corners is off each corner by less.
    let mut vertices = vec![
        v(0.0, 0.0, 0.0),
        v(1.0, 0.0, 0.0),
        v(1.0, 1.0, 0.0),
        v(0.0, 1.0, 0.0),
    ];
    vertices.extend((0..6).map(|k| {
        let a = k as f64 * std::f64::consts::PI / 3.0;
        v(3.0 + a.cos(), 0.5 + a.sin(), 0.0)
    }));
    let faces = vec![vec![0, 1, 2, 3], (4..10).collect::<Vec<_>>()];
    assert_eq!(measure_polygons(&vertices, &faces).planarity.value, 0.0);
    vertices[7].z = 0.01;
    let m = measure_polygons(&vertices, &faces);
    assert_eq!(m.planarity.at.0, 1);
    let off = m.planarity.value * m.scale;
    assert!(off > 0.001 && off < 0.01, "{off}");
    vertices[1].x = f64::NAN;
    assert!(measure_polygons(&vertices, &faces).planarity.value.is_nan());
}
