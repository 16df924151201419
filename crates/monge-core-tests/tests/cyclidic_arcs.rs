//! Cyclidic nets (§4.4, §4.6, §5.3): the curvature lines as circular arcs,
//! planar on planar-line meshes, one arc per line along a circular guide,
//! bi-arcs along a bi-arc. Measured independently of the construction: circles
//! and planes are fitted to sampled points here (three-point circles, nalgebra
//! SVD planes), never taken from the patch formulas.
//!
//! `cargo test -p monge-core-tests --test integration cyclidic_arcs:: -- --nocapture` prints the worst values.

use glam::DVec3;
use monge_core::cyclidic::{Arc, CyclidicNet, CyclidicOptions, Family, Frame};
use monge_core::{Design, GuideSpec, QuadGrid};

use crate::common;
use common::cyclidic::{coarse_freeform, dupin30, net_of};
use common::{arc, circle3, circle_distance, design, freeform_guide_v, plane_fit};

/// guide_u a circular arc, guide_v a B-spline: every u-line is inscribed in a circle (§4.6).
fn circular_u() -> Design {
    design(
        20.0,
        arc([0.0, 0.0, -10.0], [0.0, 1.0, 0.0], 80.0, 9),
        freeform_guide_v(8),
    )
}

/// Rotation of `p` about the y axis through `c` by `phi` (right-hand rule).
fn rot_y(p: DVec3, c: DVec3, phi: f64) -> DVec3 {
    let q = p - c;
    c + DVec3::new(
        q.x * phi.cos() + q.z * phi.sin(),
        q.y,
        -q.x * phi.sin() + q.z * phi.cos(),
    )
}

/// guide_u a bi-arc in the plane y = 0: 4 edges on a circle of radius 10, then 4
/// on a tangent circle of radius 5, the junction at vertex 4 (§4.6, Figure 25).
const BIARC_JUNCTION: usize = 4;
fn biarc() -> Design {
    let c1 = DVec3::new(0.0, 0.0, -10.0);
    let step1 = 10f64.to_radians();
    let mut pts: Vec<DVec3> = (0..=BIARC_JUNCTION)
        .map(|k| rot_y(DVec3::ZERO, c1, step1 * k as f64))
        .collect();
    let junction = pts[BIARC_JUNCTION];
    let c2 = junction + (c1 - junction) * 0.5;
    let step2 = 12f64.to_radians();
    pts.extend((1..=4).map(|k| rot_y(junction, c2, step2 * k as f64)));
    design(
        20.0,
        GuideSpec::Points {
            points: pts.iter().map(|p| p.to_array()).collect(),
            tangent: Some([1.0, 0.0, 0.0]),
        },
        arc([0.0, 0.0, -3.0], [-1.0, 0.0, 0.0], 60.0, 7),
    )
}

/// Largest distance from its plane of the samples of every curvature line of a net
/// (boundary samples of the patches along each mesh line).
fn line_planarity(g: &QuadGrid, net: &CyclidicNet) -> f64 {
    let k = 7;
    let mut worst = 0f64;
    for j in 0..g.cols {
        let (pj, b) = if j + 1 < g.cols {
            (j, 0)
        } else {
            (j - 1, k - 1)
        };
        let pts: Vec<DVec3> = (0..g.rows - 1)
            .flat_map(|i| {
                let s = net.sample_patch(i, pj, k);
                (0..k).map(move |a| s[a * k + b])
            })
            .collect();
        worst = worst.max(plane_fit(&pts).2);
    }
    for i in 0..g.rows {
        let (pi, a) = if i + 1 < g.rows {
            (i, 0)
        } else {
            (i - 1, k - 1)
        };
        let pts: Vec<DVec3> = (0..g.cols - 1)
            .flat_map(|j| {
                let s = net.sample_patch(pi, j, k);
                (0..k).map(move |b| s[a * k + b])
            })
            .collect();
        worst = worst.max(plane_fit(&pts).2);
    }
    worst / g.bbox_diagonal()
}

#[test]
fn curvature_lines_are_planar_on_planar_line_meshes() {
    for (name, d) in [("dupin30", dupin30()), ("freeform", coarse_freeform())] {
        let (g, net) = net_of(&d);
        let planar = line_planarity(&g, &net);
        // Control: the same mesh with the §4.4 frame at (0, 0) turned by 0.2 rad
        // about the normal keeps C¹ but loses planar lines (§4.4).
        let f = net.frame(0, 0);
        let (c, s) = (0.2f64.cos(), 0.2f64.sin());
        let turned = Frame::new(c * f.t1 + s * f.t2, c * f.t2 - s * f.t1);
        let other = CyclidicNet::from_frame(&g, turned, &CyclidicOptions::default()).unwrap();
        let control = line_planarity(&g, &other);
        println!(
            "{name}: curvature lines off their planes {planar:.2e} (turned frame: {control:.2e})"
        );
        assert!(planar <= 1e-9 && control > 1e-4, "{name}");
        // The arcs of one line have parallel normals.
        for line in net.curvature_lines() {
            for w in line.arcs.windows(2) {
                assert!(w[0].normal.cross(w[1].normal).length() <= 1e-9, "{name}");
            }
        }
    }
}

/// Check that the arcs of a line pass through the mesh vertices of the line and
/// that the boundary samples of the patches lie on them.
fn check_arcs(g: &QuadGrid, net: &CyclidicNet) -> f64 {
    let size = g.bbox_diagonal();
    let mut worst = 0f64;
    for line in net.curvature_lines() {
        let verts: Vec<DVec3> = match line.family {
            Family::U => g.column(line.index).collect(),
            Family::V => g.row(line.index).collect(),
        };
        assert!(line.arcs[0].start.distance(verts[0]) <= 1e-12 * size);
        assert!(
            line.arcs
                .last()
                .unwrap()
                .end
                .distance(*verts.last().unwrap())
                <= 1e-12 * size
        );
        for w in line.arcs.windows(2) {
            assert!(w[0].end.distance(w[1].start) <= 1e-12 * size);
        }
        // Every vertex on some arc's circle.
        for v in &verts {
            let d = line
                .arcs
                .iter()
                .map(|a| (v.distance(a.center) - a.radius).abs())
                .fold(f64::INFINITY, f64::min);
            worst = worst.max(d / size);
        }
    }
    worst
}

#[test]
fn circular_guide_gives_one_arc_per_line() {
    let (g, net) = net_of(&circular_u());
    let lines = net.curvature_lines();
    let u: Vec<usize> = lines
        .iter()
        .filter(|l| l.family == Family::U)
        .map(|l| l.arcs.len())
        .collect();
    let v: Vec<usize> = lines
        .iter()
        .filter(|l| l.family == Family::V)
        .map(|l| l.arcs.len())
        .collect();
    println!("circular guide_u: arcs per u-line {u:?}, per v-line {v:?}");
    assert_eq!(u, vec![1; g.cols]);
    assert!(
        v.iter().all(|&n| n == g.cols - 1),
        "the B-spline guide's family is not circular"
    );
    // Independently: all boundary samples of a u-line on one circle.
    let size = g.bbox_diagonal();
    let mut worst = 0f64;
    for j in 0..g.cols {
        let (pj, b) = if j + 1 < g.cols { (j, 0) } else { (j - 1, 4) };
        let pts: Vec<DVec3> = (0..g.rows - 1)
            .flat_map(|i| {
                let s = net.sample_patch(i, pj, 5);
                (0..5).map(move |a| s[a * 5 + b])
            })
            .collect();
        let circle = circle3(pts[0], pts[pts.len() / 2], pts[pts.len() - 1]);
        for p in &pts {
            worst = worst.max(circle_distance(*p, circle) / size);
        }
    }
    let on_arcs = check_arcs(&g, &net);
    println!("circular guide_u: u-line samples off one circle {worst:.2e}; vertices off their arcs {on_arcs:.2e}");
    assert!(worst <= 1e-9 && on_arcs <= 1e-9);
}

#[test]
fn biarc_guide_gives_biarcs() {
    let (g, net) = net_of(&biarc());
    let size = g.bbox_diagonal();
    for line in net
        .curvature_lines()
        .iter()
        .filter(|l| l.family == Family::U)
    {
        assert_eq!(line.arcs.len(), 2, "u-line {}", line.index);
        let junction = g.vertex(BIARC_JUNCTION, line.index);
        assert!(line.arcs[0].end.distance(junction) <= 1e-12 * size);
        // A bi-arc: the two circles are tangent at the junction (collinear centres).
        let (a, b) = (line.arcs[0], line.arcs[1]);
        let off = (a.center - junction).cross(b.center - junction).length() / size / size;
        assert!(
            off <= 1e-9,
            "u-line {}: circles not tangent, {off:e}",
            line.index
        );
    }
    let on_arcs = check_arcs(&g, &net);
    println!("bi-arc guide: every u-line two tangent arcs; vertices off their arcs {on_arcs:.2e}");
    assert!(on_arcs <= 1e-9);
}

#[test]
fn arc_points_turn_from_start_to_end_on_the_circle() {
    // A circle of radius 2.5 about (1, 2, 3) in a tilted plane, parametrised
    // here with std's cos and sin, not with the arc's own formula.
    let (center, radius) = (DVec3::new(1.0, 2.0, 3.0), 2.5);
    let normal = DVec3::new(1.0, -2.0, 0.5).normalize();
    let x = normal.any_orthonormal_vector();
    let y = normal.cross(x);
    let at = |phi: f64| center + radius * (phi.cos() * x + phi.sin() * y);
    for sweep in [0.3, 2.0, 4.0, 6.0] {
        let arc = Arc {
            center,
            radius,
            normal,
            start: at(0.0),
            end: at(sweep),
        };
        assert!((arc.sweep() - sweep).abs() < 1e-14);
        for t in [0.0, 0.25, 0.5, 0.9, 1.0] {
            let p = arc.point(t);
            assert!(((p - center).length() - radius).abs() < 1e-14);
            assert!(normal.dot(p - center).abs() < 1e-14);
            assert!((p - at(t * sweep)).length() < 1e-14, "sweep {sweep}, t {t}");
        }
    }
}
