//! Multi-patch meshes (§4.7): every patch exact, shared lines identical, one error test per variant.

use glam::DVec3;
use monge_core::design::Tolerances;
use monge_core::measure::measure;
use monge_core::multipatch::{build, Attach, MultiPatchDesign, MultiPatchError, PatchSpec, Side};
use monge_core::{GenerateError, GuideSpec};

use crate::common;
use common::{arc_u, bits, opts};

const R_V: f64 = 3.0;

/// [`arc_u`] in the plane x = 0, radius `R_V` (towards +y for positive angles).
fn arc_v(from_deg: f64, angle_deg: f64, samples: usize) -> GuideSpec {
    let a = from_deg.to_radians();
    GuideSpec::arc(
        [0.0, 0.0, -R_V],
        [0.0, R_V * a.sin(), R_V * a.cos() - R_V],
        [-angle_deg.signum(), 0.0, 0.0],
        angle_deg.abs(),
        samples,
    )
}

fn first(theta: f64) -> PatchSpec {
    PatchSpec {
        theta_deg: theta,
        guide_u: Some(arc_u(0.0, 20.0, 9)),
        guide_v: Some(arc_v(0.0, 30.0, 11)),
        attach: None,
        guide: None,
        guide_from: None,
    }
}

fn attached(theta: f64, patch: usize, side: Side, guide: GuideSpec) -> PatchSpec {
    PatchSpec {
        theta_deg: theta,
        guide_u: None,
        guide_v: None,
        attach: Some(Attach { patch, side }),
        guide: Some(guide),
        guide_from: None,
    }
}

fn design(patches: Vec<PatchSpec>) -> MultiPatchDesign {
    MultiPatchDesign {
        patches,
        tolerance: None,
        fit: None,
        symmetry: vec![],
    }
}

/// Patch 0, patch 1 after it, patch 2 after patch 1, patch 3 before patch 0 (backwards).
fn chain() -> MultiPatchDesign {
    design(vec![
        first(30.0),
        attached(-40.0, 0, Side::LastRow, arc_u(20.0, 15.0, 7)),
        attached(10.0, 1, Side::LastRow, arc_u(35.0, 25.0, 8)),
        attached(60.0, 0, Side::FirstRow, arc_u(0.0, -12.0, 5)),
    ])
}

#[test]
fn every_patch_is_exact_and_shared_lines_are_identical() {
    let mp = build(&chain(), &opts()).unwrap();
    assert!(mp.along_rows);
    // 9 + 7 + 8 + 5 samples along u, three seams.
    assert_eq!((mp.grid.rows, mp.grid.cols), (9 + 7 + 8 + 5 - 3, 11));
    assert_eq!(mp.patches[3].range, (0, 4));
    assert_eq!(mp.patches[0].range, (4, 12));
    assert_eq!(mp.patches[1].range, (12, 18));
    assert_eq!(mp.patches[2].range, (18, 25));
    assert!(mp.patches[3].reversed && !mp.patches[1].reversed);
    for k in 0..4 {
        let m = measure(&mp.patch_grid(k));
        assert!(m.max_error() <= 1e-9, "patch {k}: {m:?}");
        let p = &mp.patches[k];
        assert!(
            p.seam_gap <= 1e-14 && p.axis_gap <= 1e-13,
            "patch {k}: {p:?}"
        );
        // The bottom guide is one circle: the continuation's own tangent is the forced one.
        assert!(p.kink_deg < 1e-6, "patch {k}: kink {}", p.kink_deg);
    }
    // Shared lines: the same bits seen from both patches (they are stored once).
    for (child, parent, cs, ps) in [
        (1, 0, Side::FirstRow, Side::LastRow),
        (2, 1, Side::FirstRow, Side::LastRow),
        (3, 0, Side::FirstRow, Side::FirstRow),
    ] {
        assert_eq!(
            bits(&mp.boundary(child, cs)),
            bits(&mp.boundary(parent, ps))
        );
    }
    // Node axes point to one side everywhere, and are continuous along the bottom guide.
    let n = &mp.grid.normals;
    for i in 0..mp.grid.rows {
        for j in 0..mp.grid.cols {
            assert!(n[mp.grid.index(i, j)].z > 0.0, "({i}, {j})");
        }
    }
    for i in 1..mp.grid.rows {
        let (a, b) = (n[mp.grid.index(i - 1, 0)], n[mp.grid.index(i, 0)]);
        assert!(a.angle_between(b) < 0.1, "axis jump at row {i}");
    }
}

#[test]
fn lines_across_seams_lie_in_one_plane_per_patch() {
    let mp = build(&chain(), &opts()).unwrap();
    let lines = mp.line_planes();
    assert_eq!(lines.len(), mp.grid.rows + mp.grid.cols);
    for l in &lines {
        for p in &l.planes {
            assert!(p.deviation <= 1e-9, "{l:?}");
        }
        if l.row {
            // A row lies in one patch, or in two (a seam), in the same plane.
            assert!(matches!(l.planes.len(), 1 | 2), "{l:?}");
            if l.planes.len() == 2 {
                let (a, b) = (
                    DVec3::from(l.planes[0].normal),
                    DVec3::from(l.planes[1].normal),
                );
                assert!(a.cross(b).length() < 1e-9, "{l:?}");
            }
        } else {
            // A column crosses the four patches: four planes; except the bottom guide
            // (one circle), they turn at the seams.
            assert_eq!(l.planes.len(), 4);
            let normals: Vec<DVec3> = l.planes.iter().map(|p| DVec3::from(p.normal)).collect();
            let turn = normals
                .windows(2)
                .map(|w| w[0].cross(w[1]).length())
                .fold(0.0, f64::max);
            if l.index == 0 {
                assert!(turn < 1e-9, "bottom guide: {turn}");
            } else {
                assert!(turn > 1e-4, "column {}: {turn}", l.index);
            }
        }
    }
}

#[test]
fn column_chains_are_transposed_row_chains() {
    let d = design(vec![
        first(-30.0),
        attached(20.0, 0, Side::LastColumn, arc_v(30.0, 20.0, 6)),
        attached(-70.0, 0, Side::FirstColumn, arc_v(0.0, -15.0, 4)),
    ]);
    let mp = build(&d, &opts()).unwrap();
    assert!(!mp.along_rows);
    assert_eq!((mp.grid.rows, mp.grid.cols), (9, 11 + 6 + 4 - 2));
    assert_eq!(mp.patches[2].range, (0, 3));
    assert_eq!(mp.patches[0].range, (3, 13));
    for k in 0..3 {
        let m = measure(&mp.patch_grid(k));
        assert!(m.max_error() <= 1e-9, "patch {k}: {m:?}");
    }
    assert_eq!(
        bits(&mp.boundary(1, Side::FirstColumn)),
        bits(&mp.boundary(0, Side::LastColumn))
    );
    assert_eq!(
        bits(&mp.boundary(2, Side::FirstColumn)),
        bits(&mp.boundary(0, Side::FirstColumn))
    );
}

#[test]
fn a_bottom_guide_in_another_plane_keeps_the_normals() {
    // The continuation may turn its plane about the forced tangent: the beam is still C¹.
    let mp0 = build(&design(vec![first(30.0)]), &opts()).unwrap();
    let (rows, _) = mp0.patches[0].size;
    let corner = mp0.grid.vertex(rows - 1, 0);
    let n = mp0.grid.normals[mp0.grid.index(rows - 1, 0)];
    let t = DVec3::new(n.z, 0.0, -n.x); // in the plane y = 0, orthogonal to n
    let tilt = DVec3::Y * 0.3 + n; // the plane spanned by t and this contains t
    let pts: Vec<[f64; 3]> = (0..6)
        .map(|k| {
            let s = k as f64 * 0.2;
            (corner + s * t + s * s * 0.4 * (tilt - tilt.dot(t) * t).normalize() * -1.0).to_array()
        })
        .collect();
    let mp = build(
        &design(vec![
            first(30.0),
            attached(-20.0, 0, Side::LastRow, GuideSpec::points(pts)),
        ]),
        &opts(),
    )
    .unwrap();
    for k in 0..2 {
        assert!(measure(&mp.patch_grid(k)).max_error() <= 1e-9);
    }
    assert!(mp.patches[1].axis_gap < 1e-13);
}

fn err(d: &MultiPatchDesign) -> MultiPatchError {
    build(d, &opts()).unwrap_err()
}

#[test]
fn error_no_patches() {
    let e = err(&design(vec![]));
    assert_eq!(e, MultiPatchError::NoPatches);
    assert!(e.to_string().contains("at least one patch"));
}

#[test]
fn error_first_patch() {
    let mut p = first(30.0);
    p.guide_v = None;
    let e = err(&design(vec![p]));
    assert!(matches!(e, MultiPatchError::FirstPatch { .. }));
    assert!(e.to_string().contains("`guide_v` is missing"), "{e}");
}

#[test]
fn error_later_patch() {
    let mut p = attached(10.0, 0, Side::LastRow, arc_u(20.0, 10.0, 5));
    p.guide_v = Some(arc_v(0.0, 10.0, 5));
    let e = err(&design(vec![first(30.0), p]));
    assert!(
        matches!(e, MultiPatchError::LaterPatch { patch: 1, .. }),
        "{e}"
    );
    assert!(e.to_string().contains("it has `guide_v`"), "{e}");
}

#[test]
fn error_attach_not_earlier() {
    let e = err(&design(vec![
        first(30.0),
        attached(10.0, 1, Side::LastRow, arc_u(20.0, 10.0, 5)),
    ]));
    assert_eq!(e, MultiPatchError::AttachNotEarlier { patch: 1, to: 1 });
}

#[test]
fn error_hole_in_the_layout() {
    // Below and beside patch 0, nothing at the far corner: an L, not one grid.
    let e = err(&design(vec![
        first(30.0),
        attached(10.0, 0, Side::LastRow, arc_u(20.0, 10.0, 5)),
        attached(10.0, 0, Side::LastColumn, arc_v(30.0, 10.0, 5)),
    ]));
    assert_eq!(
        e,
        MultiPatchError::Hole {
            blocks: (2, 2),
            missing: (1, 1),
            patches: 3
        }
    );
    assert!(e.to_string().contains("incompatible boundaries"), "{e}");
    assert!(e.to_string().contains("block (1, 1) has no patch"), "{e}");
}

#[test]
fn error_side_taken() {
    let e = err(&design(vec![
        first(30.0),
        attached(10.0, 0, Side::LastRow, arc_u(20.0, 10.0, 5)),
        attached(-30.0, 0, Side::LastRow, arc_u(20.0, 12.0, 5)),
    ]));
    assert!(
        matches!(
            e,
            MultiPatchError::SideTaken {
                patch: 2,
                to: 0,
                taken_by: 1,
                ..
            }
        ),
        "{e}"
    );
}

#[test]
fn error_boundary() {
    // With a planarity tolerance of 0 the generated boundary row (planar to round-off) is refused.
    let mut d = design(vec![
        first(30.0),
        attached(10.0, 0, Side::LastRow, arc_u(20.0, 10.0, 5)),
    ]);
    d.tolerance = Some(Tolerances {
        planarity: 0.0,
        ..Default::default()
    });
    let e = err(&d);
    assert!(
        matches!(
            e,
            MultiPatchError::Boundary {
                patch: 1,
                to: 0,
                ..
            }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("incompatible boundary"), "{e}");
}

#[test]
fn error_guide() {
    let e = err(&design(vec![
        first(30.0),
        attached(10.0, 0, Side::LastRow, GuideSpec::points(vec![])),
    ]));
    assert!(matches!(e, MultiPatchError::Guide { patch: 1, .. }), "{e}");
    assert!(e.to_string().contains("has 0 sample(s)"), "{e}");
}

#[test]
fn error_start_mismatch() {
    let e = err(&design(vec![
        first(30.0),
        attached(10.0, 0, Side::LastRow, arc_u(21.0, 10.0, 5)),
    ]));
    assert!(
        matches!(e, MultiPatchError::StartMismatch { patch: 1, .. }),
        "{e}"
    );
    assert!(
        e.to_string()
            .contains("start the continuation at that corner"),
        "{e}"
    );
}

#[test]
fn error_tangent_off_plane() {
    // A continuation in the plane x = const through the corner: its plane misses the forced tangent.
    let mp = build(&design(vec![first(30.0)]), &opts()).unwrap();
    let c = mp.grid.vertex(8, 0);
    let pts = vec![
        c.to_array(),
        (c + DVec3::new(0.0, 0.5, -0.1)).to_array(),
        (c + DVec3::new(0.0, 1.0, -0.4)).to_array(),
    ];
    let e = err(&design(vec![
        first(30.0),
        attached(10.0, 0, Side::LastRow, GuideSpec::points(pts)),
    ]));
    assert!(
        matches!(e, MultiPatchError::TangentOffPlane { patch: 1, .. }),
        "{e}"
    );
}

#[test]
fn error_turns_back() {
    // The continuation runs back over patch 0 along the same circle.
    let e = err(&design(vec![
        first(30.0),
        attached(10.0, 0, Side::LastRow, arc_u(20.0, -10.0, 5)),
    ]));
    assert!(
        matches!(
            e,
            MultiPatchError::TurnsBack {
                patch: 1,
                to: 0,
                ..
            }
        ),
        "{e}"
    );
}

#[test]
fn error_generate() {
    let e = err(&design(vec![
        first(30.0),
        attached(90.0, 0, Side::LastRow, arc_u(20.0, 10.0, 5)),
    ]));
    assert!(
        matches!(
            e,
            MultiPatchError::Generate {
                patch: 1,
                source: GenerateError::ThetaSingular { .. }
            }
        ),
        "{e}"
    );
    assert!(e.to_string().starts_with("patch 1: "), "{e}");
    // An attached patch too large for the limit is refused before its guide is
    // sampled (7.8e11 samples would take 19 TB; found by the fuzzer).
    let e = err(&design(vec![
        first(30.0),
        attached(-40.0, 0, Side::LastRow, arc_u(20.0, 15.0, 777_777_777_779)),
    ]));
    match e {
        MultiPatchError::Generate {
            patch: 1,
            source:
                GenerateError::GridTooLarge {
                    rows: 777_777_777_779,
                    cols: 11,
                    ..
                },
        } => {}
        e => panic!("{e}"),
    }
}

/// Patch 3 of a 2 × 2 layout: attached to patch 1's last column, its other guide
/// patch 2's last row (`guide_from`).
fn interior(theta: f64, from: Attach) -> PatchSpec {
    PatchSpec {
        theta_deg: theta,
        guide_u: None,
        guide_v: None,
        attach: Some(Attach {
            patch: 1,
            side: Side::LastColumn,
        }),
        guide: None,
        guide_from: Some(from),
    }
}

/// 2 × 2 patches: 0 first, 1 below it, 2 beside it, 3 at the far corner taking both
/// its guides from 1 and 2.
fn two_by_two(theta3: f64) -> MultiPatchDesign {
    design(vec![
        first(30.0),
        attached(-20.0, 0, Side::LastRow, arc_u(20.0, 15.0, 7)),
        attached(15.0, 0, Side::LastColumn, arc_v(30.0, 20.0, 8)),
        interior(
            theta3,
            Attach {
                patch: 2,
                side: Side::LastRow,
            },
        ),
    ])
}

/// `|AC|·|BD| − |AB|·|CD| − |BC|·|DA|` relative to `|AC|·|BD|`: zero iff the
/// convex quadrilateral ABCD is inscribed in a circle (Ptolemy), with the distance
/// of D from the plane ABC relative to the face's size.
fn planar_and_cyclic(q: [DVec3; 4]) -> (f64, f64) {
    let [a, b, c, d] = q;
    let n = (b - a).cross(c - a).normalize();
    let size = a.distance(c).max(b.distance(d));
    let planar = (d - a).dot(n).abs() / size;
    let diagonals = a.distance(c) * b.distance(d);
    let sides = a.distance(b) * c.distance(d) + b.distance(c) * d.distance(a);
    (planar, (diagonals - sides).abs() / diagonals)
}

#[test]
fn a_two_by_two_layout_is_one_circular_grid_with_shared_seams() {
    let mp = build(&two_by_two(30.0), &opts()).unwrap();
    assert_eq!(mp.layout, (2, 2));
    assert_eq!((mp.grid.rows, mp.grid.cols), (9 + 7 - 1, 11 + 8 - 1));
    assert_eq!(mp.patches[3].block, (1, 1));
    assert_eq!(
        (mp.patches[3].rows, mp.patches[3].cols),
        ((8, 14), (10, 17))
    );
    // Every face, across all four seams, planar and inscribed in a circle.
    let g = &mp.grid;
    let mut worst = (0.0f64, 0.0f64);
    for i in 0..g.rows - 1 {
        for j in 0..g.cols - 1 {
            let (p, c) = planar_and_cyclic(g.face(i, j));
            worst = (worst.0.max(p), worst.1.max(c));
        }
    }
    assert!(worst.0 < 1e-9 && worst.1 < 1e-9, "{worst:?}");
    // The seams, stored once: the same bits seen from both patches.
    for (a, sa, b, sb) in [
        (0, Side::LastRow, 1, Side::FirstRow),
        (0, Side::LastColumn, 2, Side::FirstColumn),
        (1, Side::LastColumn, 3, Side::FirstColumn),
        (2, Side::LastRow, 3, Side::FirstRow),
    ] {
        assert_eq!(bits(&mp.boundary(a, sa)), bits(&mp.boundary(b, sb)));
    }
    // Each patch as generated meets the lines kept in the grid, node axes included.
    for (k, p) in mp.patches.iter().enumerate() {
        assert!(
            p.seam_gap <= 1e-14 && p.axis_gap <= 1e-12,
            "patch {k}: {p:?}"
        );
    }
    // The two lines of patch 3 leave the corner a little off 90° on a mesh.
    let k3 = mp.patches[3].kink_deg;
    println!("patch 3 turned by {k3}°");
    assert!(k3 < 5.0, "{k3}");
    // Node axes point to one side and turn smoothly across every seam.
    let n = &g.normals;
    for i in 0..g.rows {
        for j in 0..g.cols {
            assert!(n[g.index(i, j)].z > 0.0, "({i}, {j})");
            if i > 0 {
                assert!(n[g.index(i, j)].angle_between(n[g.index(i - 1, j)]) < 0.2);
            }
            if j > 0 {
                assert!(n[g.index(i, j)].angle_between(n[g.index(i, j - 1)]) < 0.2);
            }
        }
    }
}

#[test]
fn error_unjoined_neighbour() {
    // Patch 3 at the far corner with a continuation of its own: it would meet patch 2
    // along a line of its own, not patch 2's last row.
    let mut d = two_by_two(30.0);
    d.patches[3].guide_from = None;
    d.patches[3].guide = Some(arc_v(30.0, 20.0, 8));
    let e = err(&d);
    assert_eq!(
        e,
        MultiPatchError::Unjoined {
            patch: 3,
            other: 2,
            kind: "row"
        }
    );
    assert!(
        e.to_string().contains("`guide_from` that row of patch 2"),
        "{e}"
    );
}

#[test]
fn error_guide_from_elsewhere() {
    // Patch 2's first column is patch 0's last column: not through patch 3's corner.
    let mut d = two_by_two(30.0);
    d.patches[3].guide_from = Some(Attach {
        patch: 2,
        side: Side::FirstRow,
    });
    let e = err(&d);
    assert!(
        matches!(
            e,
            MultiPatchError::GuideFromElsewhere {
                patch: 3,
                from: 2,
                to: 1,
                ..
            }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("must be a row side"), "{e}");
}

#[test]
fn error_guide_from_and_guide() {
    let mut d = two_by_two(30.0);
    d.patches[3].guide = Some(arc_v(30.0, 20.0, 8));
    let e = err(&d);
    assert!(
        e.to_string().contains("both `guide` and `guide_from`"),
        "{e}"
    );
}

#[test]
fn a_two_by_two_design_file_reads_and_builds() {
    let text = serde_json::to_string(&two_by_two(30.0)).unwrap();
    assert!(
        text.contains(r#""guide_from":{"patch":2,"side":"last_row"}"#),
        "{text}"
    );
    let back: MultiPatchDesign = serde_json::from_str(&text).unwrap();
    assert_eq!(back, two_by_two(30.0));
}
