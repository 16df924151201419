//! Folded and crossed faces (§5.2, issue 10 item 2): a bow-tie face, whose
//! diagonals' cross product vanishes, is found by the generator's report and by
//! `measure`, checked against an independent test of crossing edges.

use glam::DVec3;
use monge_core::design::GuideSpec;
use monge_core::grid::{quad_turn, Turn};
use monge_core::measure::{circularity, face_planarity, measure};
use monge_core::{generate, Design, QuadGrid};

use crate::common;
use common::{design, figure22};

/// Whether two opposite edges of the quad cross, independently of the code
/// under test: the corners are projected on the plane of the largest of the
/// four corner triangles, and segments AB, CD (and BC, DA) cross when each
/// one's ends lie strictly on both sides of the other's line.
fn edges_cross(q: &[DVec3; 4]) -> bool {
    let c: Vec<[f64; 3]> = q.iter().map(|p| p.to_array()).collect();
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let normal = (0..4)
        .map(|k| cross(sub(c[(k + 1) % 4], c[k]), sub(c[(k + 2) % 4], c[k])))
        .max_by(|a, b| dot(*a, *a).total_cmp(&dot(*b, *b)))
        .unwrap();
    let u = sub(c[1], c[0]);
    let v = cross(normal, u);
    let flat: Vec<[f64; 2]> = c
        .iter()
        .map(|p| [dot(sub(*p, c[0]), u), dot(sub(*p, c[0]), v)])
        .collect();
    let side = |a: [f64; 2], b: [f64; 2], p: [f64; 2]| {
        ((b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])).signum()
    };
    let segments_cross =
        |a, b, p, q| side(a, b, p) * side(a, b, q) < 0.0 && side(p, q, a) * side(p, q, b) < 0.0;
    segments_cross(flat[0], flat[1], flat[2], flat[3])
        || segments_cross(flat[1], flat[2], flat[3], flat[0])
}

/// Faces of `grid` whose edges cross, by [`edges_cross`].
fn crossed_faces(grid: &QuadGrid) -> Vec<(usize, usize)> {
    (0..grid.rows - 1)
        .flat_map(|i| (0..grid.cols - 1).map(move |j| (i, j)))
        .filter(|&(i, j)| edges_cross(&grid.face(i, j)))
        .collect()
}

/// A 4 × 4 grid of unit squares, rotated and moved off the axes, whose last row
/// has vertices (3, 1) and (3, 2) exchanged: face (2, 1) becomes a symmetric
/// bow-tie (its edges (2, 1)–(3, 1) and (3, 2)–(2, 2) cross at their midpoints),
/// its neighbours (2, 0) and (2, 2) stay convex.
fn bow_tie_grid(normals: bool) -> QuadGrid {
    let axis = DVec3::new(1.0, 2.0, 2.0) / 3.0;
    let (e1, e2) = (
        DVec3::new(2.0, -2.0, 1.0) / 3.0,
        DVec3::new(2.0, 1.0, -2.0) / 3.0,
    );
    assert!(e1.cross(e2).abs_diff_eq(axis, 1e-15));
    let origin = DVec3::new(10.0, -3.0, 7.0);
    let mut vertices: Vec<DVec3> = (0..16)
        .map(|k| origin + (k / 4) as f64 * e1 + (k % 4) as f64 * e2)
        .collect();
    vertices.swap(13, 14);
    let normals = if normals { vec![axis; 16] } else { vec![] };
    QuadGrid::new(4, 4, vertices, normals)
}

#[test]
fn a_symmetric_bow_tie_is_a_folded_face() {
    for normals in [true, false] {
        let g = bow_tie_grid(normals);
        let [a, b, c, d] = g.face(2, 1);
        // The diagonals are parallel: the old fold test (their cross product) sees nothing.
        assert!((c - a).cross(d - b).length() < 1e-14);
        assert_eq!(crossed_faces(&g), vec![(2, 1)]);
        let m = measure(&g);
        assert_eq!(
            (m.folded_faces, m.first_fold),
            (1, Some((2, 1))),
            "normals: {normals}"
        );
        // Planar, even circular (a crossed rectangle is inscribed in a circle):
        // only the fold count tells.
        let q = g.face(2, 1);
        assert!(face_planarity(&q) < 1e-14 && circularity(&q) < 1e-14);
    }
    let mut fair = bow_tie_grid(true);
    fair.vertices.swap(13, 14);
    assert!(crossed_faces(&fair).is_empty());
    assert_eq!(measure(&fair).folded_faces, 0);
}

/// What `monge optimise-panels` wrote for `examples/fig22-panels.json` before
/// issue 10: its mesh has face (7, 11) crossed.
fn crossed_figure22() -> Design {
    let guide = |guide, parameters: &[f64]| match guide {
        GuideSpec::BSpline { bspline, .. } => GuideSpec::BSpline {
            bspline,
            parameters: Some(parameters.to_vec()),
        },
        other => other,
    };
    let uniform = figure22(13);
    design(
        uniform.theta_deg,
        guide(
            uniform.guide_u,
            &[
                0.0,
                0.2208782254371717,
                0.34790833573749613,
                0.44649691729899604,
                0.5024466172629757,
                0.5854054272143034,
                0.6261056719958805,
                0.6990263446895904,
                0.7342380967180174,
                0.8065543870162897,
                0.8509856061772179,
                0.9343866039693598,
                1.0,
            ],
        ),
        guide(
            uniform.guide_v,
            &[
                0.0,
                0.11234906020073467,
                0.26110989254545997,
                0.37268618151400185,
                0.46868583625056176,
                0.5562964227924424,
                0.6373823866683406,
                0.7126824011225366,
                0.7813373603327596,
                0.8444541091468666,
                0.9010924489797841,
                0.9528022233636012,
                1.0,
            ],
        ),
    )
}

#[test]
fn the_crossed_face_of_the_old_figure_22_optimum_is_reported() {
    let g = generate(&crossed_figure22(), &Default::default()).unwrap();
    assert_eq!(crossed_faces(&g.grid), vec![(7, 11)]);
    assert_eq!(
        (g.report.folded_faces, g.report.first_fold),
        (1, Some((7, 11)))
    );
    let m = measure(&g.grid);
    assert_eq!((m.folded_faces, m.first_fold), (1, Some((7, 11))));
    assert!(
        m.max_error() < 1e-14,
        "exact, yet folded: {}",
        m.max_error()
    );
}

/// The definition of [`quad_turn`], written out by hand: the sign of
/// `(e_in × e_out) · axis` at each of the four corners.
fn corner_signs(q: &[DVec3; 4], axis: DVec3) -> [f64; 4] {
    let p: Vec<[f64; 3]> = q.iter().map(|v| v.to_array()).collect();
    let a = axis.to_array();
    let mut signs = [0.0; 4];
    for (k, s) in signs.iter_mut().enumerate() {
        let (prev, here, next) = (p[(k + 3) % 4], p[k], p[(k + 1) % 4]);
        let e_in = [here[0] - prev[0], here[1] - prev[1], here[2] - prev[2]];
        let e_out = [next[0] - here[0], next[1] - here[1], next[2] - here[2]];
        let det = a[0] * (e_in[1] * e_out[2] - e_in[2] * e_out[1])
            + a[1] * (e_in[2] * e_out[0] - e_in[0] * e_out[2])
            + a[2] * (e_in[0] * e_out[1] - e_in[1] * e_out[0]);
        *s = det.signum();
    }
    signs
}

/// quad_turn (which uses the diagonals) agrees with the corner definition on
/// 20 000 random quads, skew or planar, convex, crossed or darts, random axes
/// (a fixed-seed generator; quads whose corner turns are within round-off of
/// zero are left out, where either answer is right).
#[test]
fn quad_turn_is_the_sign_of_the_four_corner_turns() {
    let mut rng = fastrand::Rng::with_seed(7);
    let mut uniform = move || rng.f64() * 2.0 - 1.0;
    let mut point = || DVec3::new(uniform(), uniform(), uniform());
    let mut seen = [0; 3];
    for k in 0..20_000 {
        let axis = point();
        let mut q = [point(), point(), point(), point()];
        if k % 2 == 0 {
            // Flatten into the plane orthogonal to the axis: planar quads.
            for p in &mut q {
                *p -= p.dot(axis) / axis.length_squared() * axis;
            }
        }
        let margin = (0..4).all(|c| {
            let (e_in, e_out) = (q[c] - q[(c + 3) % 4], q[(c + 1) % 4] - q[c]);
            e_in.cross(e_out).dot(axis).abs() > 1e-9
        });
        if !margin {
            continue;
        }
        let signs = corner_signs(&q, axis);
        let expected = if signs.iter().all(|s| *s > 0.0) {
            Turn::Positive
        } else if signs.iter().all(|s| *s < 0.0) {
            Turn::Negative
        } else {
            Turn::Crossed
        };
        assert_eq!(quad_turn(&q, axis), expected, "{q:?} about {axis}");
        seen[expected as usize] += 1;
    }
    println!("positive, negative, crossed: {seen:?}");
    assert!(seen.iter().all(|n| *n > 1000), "{seen:?}");
    // NaN turns neither way.
    let mut q = [DVec3::ZERO, DVec3::X, DVec3::X + DVec3::Y, DVec3::Y];
    q[2].x = f64::NAN;
    assert_eq!(quad_turn(&q, DVec3::Z), Turn::Crossed);
}
