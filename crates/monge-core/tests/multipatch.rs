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
    }
}

fn attached(theta: f64, patch: usize, side: Side, guide: GuideSpec) -> PatchSpec {
    PatchSpec {
        theta_deg: theta,
        guide_u: None,
        guide_v: None,
        attach: Some(Attach { patch, side }),
        guide: Some(guide),
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
fn error_mixed_sides() {
    let e = err(&design(vec![
        first(30.0),
        attached(10.0, 0, Side::LastRow, arc_u(20.0, 10.0, 5)),
        attached(10.0, 0, Side::LastColumn, arc_v(30.0, 10.0, 5)),
    ]));
    assert!(
        matches!(
            e,
            MultiPatchError::MixedSides {
                patch: 2,
                first: 1,
                ..
            }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("incompatible boundaries"), "{e}");
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
