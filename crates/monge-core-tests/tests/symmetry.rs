//! Symmetry and assembly (§4.5 Figure 18, §4.7 Figure 20): copies exact, no duplicate vertices.

use glam::DVec3;
use monge_core::measure::measure;
use monge_core::symmetry::{assemble, isometries, Assembly, SymmetryError, SymmetrySpec};
use monge_core::QuadGrid;

use crate::common;
use common::{arc, design, mesh};

/// A characteristic patch: guide_u in the plane y = 0, guide_v in the plane x = 0,
/// starting at the origin; its node axes along guide_u lie in y = 0 and along guide_v in x = 0.
fn patch(rows: usize, cols: usize) -> QuadGrid {
    mesh(&design(
        -35.0,
        arc([0.0, 0.0, -4.0], [0.0, 1.0, 0.0], 30.0, rows),
        arc([0.0, 0.0, -3.0], [-1.0, 0.0, 0.0], 40.0, cols),
    ))
}

fn mirror(normal: [f64; 3]) -> SymmetrySpec {
    SymmetrySpec::Mirror {
        point: [0.0; 3],
        normal,
    }
}

/// Independent check: no two mesh vertices within the merge distance, every copy vertex
/// at its mesh vertex, and the number of mesh vertices = the number of clusters.
fn check_merge(a: &Assembly) {
    let v = &a.mesh.vertices;
    for i in 0..v.len() {
        for j in i + 1..v.len() {
            assert!(v[i].distance(v[j]) > a.merge_distance, "duplicate {i} {j}");
        }
    }
    for c in &a.copies {
        for (k, p) in c.grid.vertices.iter().enumerate() {
            assert!(p.distance(v[c.vertex_map[k]]) <= a.merge_distance);
        }
    }
    // Every quad turns counter-clockwise about its node axes.
    for q in &a.mesh.quads {
        let [p0, p1, p2, p3] = q.map(|k| v[k]);
        let face = (p2 - p0).cross(p3 - p1);
        let axis: DVec3 = q.iter().map(|&k| a.mesh.normals[k]).sum();
        assert!(face.dot(axis) > 0.0, "{q:?}");
    }
}

#[test]
fn two_mirrors_share_the_guides_and_keep_every_property() {
    let (r, c) = (9, 11);
    let g = patch(r, c);
    let isos = isometries(
        &[mirror([1.0, 0.0, 0.0]), mirror([0.0, 1.0, 0.0])],
        usize::MAX,
    )
    .unwrap();
    assert_eq!(isos.len(), 4);
    let a = assemble(&[g], &isos);
    // guide_v (row 0) lies in x = 0 and guide_u (column 0) in y = 0: shared once.
    assert_eq!(a.mesh.vertices.len(), 4 * r * c - 2 * r - 2 * c + 1);
    assert_eq!(a.mesh.quads.len(), 4 * (r - 1) * (c - 1));
    check_merge(&a);
    for copy in &a.copies {
        let m = measure(&copy.grid);
        assert!(m.max_error() <= 1e-9, "{m:?}");
    }
    // Characteristic guides: the node axes lie in the mirror planes, so they agree there.
    assert!(a.max_axis_gap < 1e-12, "{}", a.max_axis_gap);
    assert!(a.max_merge_gap <= a.merge_distance);
}

#[test]
fn order_five_rotation_with_a_mirror_makes_ten_exact_copies() {
    // Figure 18: a mirror and a rotation of order 5 about an axis through the patch's corner.
    let g = patch(7, 8);
    let ops = [
        mirror([0.0, 1.0, 0.0]),
        SymmetrySpec::Rotate {
            point: [0.0; 3],
            axis: [0.0, 0.0, 1.0],
            order: 5,
        },
    ];
    let isos = isometries(&ops, usize::MAX).unwrap();
    assert_eq!(isos.len(), 10);
    let a = assemble(&[g], &isos);
    check_merge(&a);
    for copy in &a.copies {
        assert!(measure(&copy.grid).max_error() <= 1e-9);
    }
    // Each mirror pair shares column 0 (7 vertices); the origin is shared by all ten.
    assert_eq!(a.mesh.vertices.len(), 5 * (2 * 7 * 8 - 7) - 4);
    assert_eq!(a.mesh.quads.len(), 10 * 6 * 7);
}

#[test]
fn error_bad_direction() {
    let e = isometries(&[mirror([0.0; 3])], usize::MAX).unwrap_err();
    assert!(
        matches!(e, SymmetryError::BadDirection { index: 0, .. }),
        "{e}"
    );
    assert!(e.to_string().contains("mirror normal"));
}

#[test]
fn error_too_many_copies() {
    // The same rotation of order 5 twelve times: 5¹² copies, refused before any is made
    // (it once aborted, out of memory).
    let rotation = SymmetrySpec::Rotate {
        point: [0.0; 3],
        axis: [0.0, 0.0, 1.0],
        order: 5,
    };
    let e = isometries(&vec![rotation.clone(); 12], 1_000_000).unwrap_err();
    assert_eq!(
        e,
        SymmetryError::TooManyCopies {
            copies: 5f64.powi(12),
            max: 1_000_000
        }
    );
    assert!(e.to_string().contains("244140625 copies"), "{e}");
    assert_eq!(
        isometries(&[rotation.clone(), rotation], 25).unwrap().len(),
        25
    );
}

#[test]
fn error_zero_order() {
    let e = isometries(
        &[SymmetrySpec::Rotate {
            point: [0.0; 3],
            axis: [0.0, 0.0, 1.0],
            order: 0,
        }],
        usize::MAX,
    )
    .unwrap_err();
    assert_eq!(e, SymmetryError::ZeroOrder { index: 0 });
}

#[test]
fn error_bad_point() {
    let e = isometries(
        &[SymmetrySpec::Mirror {
            point: [f64::NAN, 0.0, 0.0],
            normal: [1.0, 0.0, 0.0],
        }],
        usize::MAX,
    )
    .unwrap_err();
    assert!(matches!(e, SymmetryError::BadPoint { index: 0, .. }), "{e}");
}
