//! Cyclidic nets (§4.4, §5.3): every refusal, with the words of its message,
//! and folded faces named by the fold test of every mesh, checked against
//! folds found here by segment tests and shoelace areas.

use glam::DVec3;
use monge_core::cyclidic::{
    CyclidicError, CyclidicNet, CyclidicOptions, Family, FoldReason, Frame, Patch,
};
use monge_core::{Design, GuideSpec, QuadGrid};

use crate::common;
use common::cyclidic::{dupin30, net_of, random_patches};
use common::{design, mesh};

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
