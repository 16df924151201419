//! Boundary-plane alignment (§4.5, Figures 16–18): the generated mesh's boundary
//! rows and columns lie in the four planes, measured from the plane equations.

use glam::DVec3;
use monge_core::boundary::{align, AlignError, AlignOptions, BoundarySpec, PlaneSpec, Rise};
use monge_core::measure::measure;
use monge_core::symmetry::{assemble, isometries, SymmetrySpec};
use monge_core::{generate, GenerateOptions, QuadGrid};

use crate::common;
use common::Lcg;

fn plane(point: [f64; 3], normal: [f64; 3]) -> PlaneSpec {
    PlaneSpec { point, normal }
}

fn spec(planes: [PlaneSpec; 4]) -> BoundarySpec {
    BoundarySpec {
        first_row: planes[0],
        last_row: planes[1],
        first_column: planes[2],
        last_column: planes[3],
        theta_deg: None,
        corner: None,
        samples: None,
        rise: None,
        facade: false,
    }
}

/// Figure 16: four vertical walls around a 6 × 4 rectangle.
fn facade() -> BoundarySpec {
    BoundarySpec {
        facade: true,
        corner: Some([0.0, 0.0, 1.0]),
        rise: Some(Rise {
            guide_u: 1.5,
            guide_v: -1.0,
        }),
        ..spec([
            plane([0.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
            plane([0.0, 4.0, 0.0], [0.0, -1.0, 0.0]),
            plane([0.0, 0.0, 0.0], [1.0, 0.0, 0.0]),
            plane([6.0, 0.0, 0.0], [1.0, 0.0, 0.0]),
        ])
    }
}

/// Figure 17: the floor and a wall of a pentagonal building (rows), two vertical
/// planes through the building's axis meeting at 36° (columns).
fn fig17() -> BoundarySpec {
    let (s36, c36) = 36f64.to_radians().sin_cos();
    let (s18, c18) = 18f64.to_radians().sin_cos();
    BoundarySpec {
        corner: Some([5.0, 0.0, 0.0]),
        ..spec([
            plane([0.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
            plane([2.0 * c18, 2.0 * s18, 0.0], [c18, s18, 0.0]),
            plane([0.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
            plane([0.0, 0.0, 0.0], [-s36, c36, 0.0]),
        ])
    }
}

/// Distances of the boundary lines from the planes, from the plane equations,
/// relative to the bounding-box diagonal of the vertices.
fn distances(grid: &QuadGrid, s: &BoundarySpec) -> [f64; 4] {
    let n = grid.vertices.len();
    let (r, c) = (grid.rows, grid.cols);
    let lines: [Vec<usize>; 4] = [
        (0..c).collect(),
        ((r - 1) * c..n).collect(),
        (0..r).map(|i| i * c).collect(),
        (0..r).map(|i| i * c + c - 1).collect(),
    ];
    let planes = [s.first_row, s.last_row, s.first_column, s.last_column];
    let (mut lo, mut hi) = (DVec3::splat(f64::MAX), DVec3::splat(f64::MIN));
    for v in &grid.vertices {
        lo = lo.min(*v);
        hi = hi.max(*v);
    }
    let size = (hi - lo).length();
    let mut out = [0.0; 4];
    for k in 0..4 {
        let [a, b, cc] = planes[k].normal;
        let [x0, y0, z0] = planes[k].point;
        let norm = (a * a + b * b + cc * cc).sqrt();
        for &idx in &lines[k] {
            let v = grid.vertices[idx];
            let dist = (a * (v.x - x0) + b * (v.y - y0) + cc * (v.z - z0)).abs() / norm;
            out[k] = f64::max(out[k], dist / size);
        }
    }
    out
}

fn check(s: &BoundarySpec) -> (QuadGrid, f64) {
    let aligned = align(s, &AlignOptions::default()).unwrap();
    let g = generate(&aligned.design, &GenerateOptions::default()).unwrap();
    assert_eq!(g.report.folded_faces, 0);
    let d = distances(&g.grid, s);
    let err = measure(&g.grid).max_error();
    eprintln!(
        "θ = {}, distances {d:?}, measured {err:e}",
        aligned.design.theta_deg
    );
    assert!(d.iter().all(|&x| x <= 1e-9), "{d:?}");
    assert!(err <= 1e-9, "{err}");
    (g.grid, aligned.design.theta_deg)
}

#[test]
fn facade_boundaries_lie_in_the_four_walls() {
    check(&facade());
}

#[test]
fn fig17_boundaries_lie_in_the_planes() {
    check(&fig17());
}

#[test]
fn planes_in_general_position_with_orthogonal_lines() {
    // Random directions d12 ⊥ d34; row planes contain d12, column planes d34. No plane is
    // axis-aligned and every p_i · p_j (i row, j column) is non-zero.
    let (mut ok, mut tried) = (0, 0);
    for seed in 1..=12u64 {
        let mut rng = Lcg(seed);
        let d12 = rng.vec().normalize();
        let d34 = d12.cross(rng.vec()).normalize();
        let normal = |d: DVec3, rng: &mut Lcg| d.cross(rng.vec()).normalize();
        let (p1, p2, p3, p4) = (
            normal(d12, &mut rng),
            normal(d12, &mut rng),
            normal(d34, &mut rng),
            normal(d34, &mut rng),
        );
        let mut pts = || (3.0 * rng.vec()).to_array();
        let mut s = spec([
            plane(pts(), p1.to_array()),
            plane(pts(), p2.to_array()),
            plane(pts(), p3.to_array()),
            plane(pts(), p4.to_array()),
        ]);
        s.samples = Some(11);
        tried += 1;
        match align(&s, &AlignOptions::default()) {
            Ok(_) => {
                check(&s);
                ok += 1;
            }
            Err(AlignError::NoAdmissibleTheta { .. }) => {}
            Err(e) => panic!("seed {seed}: {e}"),
        }
    }
    eprintln!("{ok} of {tried} random configurations aligned");
    assert!(ok >= tried / 2, "{ok} of {tried}");
}

#[test]
fn rigid_motions_of_the_planes_move_the_mesh() {
    // Figure 17's planes turned and shifted: still aligned.
    let mut s = fig17();
    let rot = glam::DQuat::from_axis_angle(DVec3::new(1.0, 2.0, 3.0).normalize(), 0.7);
    let shift = DVec3::new(10.0, -3.0, 2.5);
    for pl in [
        &mut s.first_row,
        &mut s.last_row,
        &mut s.first_column,
        &mut s.last_column,
    ] {
        pl.point = (rot * DVec3::from(pl.point) + shift).to_array();
        pl.normal = (rot * DVec3::from(pl.normal)).to_array();
    }
    s.corner = Some((rot * DVec3::new(5.0, 0.0, 0.0) + shift).to_array());
    check(&s);
}

#[test]
fn requested_theta_is_kept_with_its_sign() {
    for theta in [-80.0, -40.0] {
        let s = BoundarySpec {
            theta_deg: Some(theta),
            ..fig17()
        };
        let (_, got) = check(&s);
        assert_eq!(got, theta);
    }
    for theta in [30.0, -150.0, 0.0, 180.0] {
        let s = BoundarySpec {
            theta_deg: Some(theta),
            ..facade()
        };
        let (_, got) = check(&s);
        assert_eq!(got, theta);
    }
}

#[test]
fn samples_set_the_grid() {
    let s = BoundarySpec {
        samples: Some(7),
        ..fig17()
    };
    let (grid, _) = check(&s);
    assert_eq!((grid.rows, grid.cols), (7, 7));
    let (grid, _) = check(&BoundarySpec {
        samples: Some(30),
        ..facade()
    });
    assert_eq!((grid.rows, grid.cols), (30, 30));
}

#[test]
fn fig18_order_five_structure_has_no_duplicate_vertices() {
    let s = fig17();
    let (grid, _) = check(&s);
    // Mirror in P3 (y = 0), then rotate by multiples of 72° about the z axis: the ten
    // copies of the dihedral group; the mirror image rotated by 72° is the mirror in P4.
    let isos = isometries(
        &[
            SymmetrySpec::Mirror {
                point: [0.0; 3],
                normal: [0.0, 1.0, 0.0],
            },
            SymmetrySpec::Rotate {
                point: [0.0; 3],
                axis: [0.0, 0.0, 1.0],
                order: 5,
            },
        ],
        usize::MAX,
    )
    .unwrap();
    assert_eq!(isos.len(), 10);
    let a = assemble(std::slice::from_ref(&grid), &isos);
    let (r, c) = (grid.rows, grid.cols);
    // Ten patches, ten shared boundary columns of r vertices each.
    assert_eq!(a.mesh.vertices.len(), 10 * r * c - 10 * r);
    assert_eq!(a.mesh.quads.len(), 10 * (r - 1) * (c - 1));
    assert!(
        a.max_merge_gap <= 1e-9 * grid.bbox_diagonal(),
        "{}",
        a.max_merge_gap
    );
    // No two mesh vertices coincide.
    let size = grid.bbox_diagonal();
    for (k, v) in a.mesh.vertices.iter().enumerate() {
        for w in &a.mesh.vertices[k + 1..] {
            assert!(v.distance(*w) > 1e-6 * size);
        }
    }
    for copy in &a.copies {
        assert!(measure(&copy.grid).max_error() <= 1e-9);
    }
}

#[test]
fn lines_that_are_not_orthogonal_are_refused_with_the_angle() {
    let mut s = fig17();
    // Tilt the wall by 1° about a horizontal line: P1 ∩ P2 now climbs 1°... no: turn
    // the floor instead, so P1 ∩ P2 tilts out of the horizontal.
    let t = 1f64.to_radians();
    s.first_row.normal = [0.0, t.sin(), t.cos()];
    s.last_row.normal = [1.0, 0.0, 0.0];
    s.last_row.point = [2.0, 0.0, 0.0];
    match align(&s, &AlignOptions::default()) {
        Err(AlignError::NotOrthogonal { off_deg, .. }) => {
            assert!((off_deg - 1.0).abs() < 1e-9, "{off_deg}")
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn parallel_planes_are_refused() {
    let mut s = fig17();
    s.last_row = plane([0.0, 0.0, 3.0], [0.0, 0.0, 1.0]);
    let e = align(&s, &AlignOptions::default()).unwrap_err();
    assert!(
        matches!(
            e,
            AlignError::ParallelPlanes {
                first: "first_row",
                second: "last_row",
                ..
            }
        ),
        "{e}"
    );
    // The façade planes without --facade: parallel, with a hint.
    let e = align(
        &BoundarySpec {
            facade: false,
            ..facade()
        },
        &AlignOptions::default(),
    )
    .unwrap_err();
    assert!(e.to_string().contains("--facade"), "{e}");
}

#[test]
fn a_corner_that_does_not_exist_is_refused() {
    let mut s = fig17();
    // first_column parallel to the floor: guide_u's plane never meets guide_v's.
    s.first_column = plane([0.0, 0.0, 5.0], [0.0, 0.0, 1.0]);
    s.last_column = plane([0.0, 0.0, 0.0], [1.0, 0.0, 0.0]);
    let e = align(&s, &AlignOptions::default()).unwrap_err();
    assert!(
        matches!(
            e,
            AlignError::NoCorner {
                row_plane: "first_row",
                column_plane: "first_column",
                ..
            }
        ),
        "{e}"
    );
}

#[test]
fn no_admissible_theta_is_refused() {
    // θ so small that the column circles would not exist (|c3| ≥ 1).
    let s = BoundarySpec {
        theta_deg: Some(-0.01),
        ..fig17()
    };
    let e = align(&s, &AlignOptions::default()).unwrap_err();
    assert!(
        matches!(
            e,
            AlignError::NoAdmissibleTheta {
                requested: Some(_),
                ..
            }
        ),
        "{e}"
    );
    let s = BoundarySpec {
        theta_deg: Some(90.0),
        ..facade()
    };
    assert!(matches!(
        align(&s, &AlignOptions::default()),
        Err(AlignError::NoAdmissibleTheta { .. })
    ));
}

#[test]
fn facade_errors() {
    let mut s = facade();
    s.last_column.normal = [1.0, 0.0, 0.1];
    assert!(matches!(
        align(&s, &AlignOptions::default()),
        Err(AlignError::NotVertical {
            plane: "last_column",
            ..
        })
    ));
    let mut s = facade();
    s.last_column.normal = [1.0, 0.1, 0.0];
    assert!(matches!(
        align(&s, &AlignOptions::default()),
        Err(AlignError::NotRectangle { .. })
    ));
    let s = BoundarySpec {
        rise: Some(Rise {
            guide_u: 0.0,
            guide_v: 1.0,
        }),
        ..facade()
    };
    assert!(matches!(
        align(&s, &AlignOptions::default()),
        Err(AlignError::Facade {
            guide: "guide_u",
            ..
        })
    ));
    let s = BoundarySpec {
        samples: Some(2),
        ..facade()
    };
    assert!(matches!(
        align(&s, &AlignOptions::default()),
        Err(AlignError::Samples { given: 2, .. })
    ));
    // Once "no admissible θ … every such mesh folds".
    let s = BoundarySpec {
        samples: Some(100_000),
        ..facade()
    };
    let e = align(&s, &AlignOptions::default()).unwrap_err();
    assert!(
        matches!(e, AlignError::Samples { given: 100_000, max } if max * max <= 25_000_000),
        "{e}"
    );
    let mut s = facade();
    s.first_row.normal = [0.0, 0.0, 0.0];
    assert!(matches!(
        align(&s, &AlignOptions::default()),
        Err(AlignError::InvalidPlane {
            plane: "first_row",
            ..
        })
    ));
}

#[test]
fn the_facade_flag_of_the_options_works_like_the_key() {
    let s = BoundarySpec {
        facade: false,
        ..facade()
    };
    let a = align(
        &s,
        &AlignOptions {
            facade: true,
            ..Default::default()
        },
    )
    .unwrap();
    assert!(a.boundary_distance.iter().all(|&d| d <= 1e-9));
    // Horizontal end tangents: the normals at the four corners are vertical.
    let g = generate(&a.design, &GenerateOptions::default())
        .unwrap()
        .grid;
    for (i, j) in [
        (0, 0),
        (0, g.cols - 1),
        (g.rows - 1, 0),
        (g.rows - 1, g.cols - 1),
    ] {
        let n = g.normals[g.index(i, j)];
        assert!(n.x.abs() < 1e-12 && n.y.abs() < 1e-12, "{n:?}");
    }
}
