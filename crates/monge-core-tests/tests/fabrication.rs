//! Gridshell fabrication (§6, Figure 25), measured independently: every value
//! reported by `fabricate` is checked against the layer meshes' own vertices and
//! node axes with elementary formulas (and an SVD plane fit from nalgebra).

use glam::{DVec2, DVec3};
use monge_core::conical::conical_dual;
use monge_core::fabrication::{
    fabricate, BaseMesh, Fabrication, FabricationError, FabricationOptions, LineFamily,
    SegmentShape,
};
use monge_core::{Design, GuideSpec, QuadGrid};

use crate::common;
use common::{arc, design, freeform, mesh, plane_fit, two_circles, TOL};

/// The discrete Dupin cyclide of Figure 12 (θ = 30°), smaller than the example file.
fn dupin(theta_deg: f64) -> Design {
    two_circles(theta_deg, 90.0, 13, 80.0, 11)
}

/// Number of edges on each arc of the bi-arc guide.
const BIARC_EDGES: usize = 8;

/// A Figure-25-like design: guide_u a circular arc, guide_v a bi-arc of two
/// tangent circular arcs (radius 3 over 40°, then radius 6 over 30°) given as
/// points with its exact start tangent.
fn biarc() -> Design {
    let c1 = DVec3::new(0.0, 0.0, -3.0);
    let on = |c: DVec3, r: f64, phi: f64| c + r * DVec3::new(0.0, phi.sin(), phi.cos());
    let mut points: Vec<[f64; 3]> = (0..=BIARC_EDGES)
        .map(|k| on(c1, 3.0, (40.0 * k as f64 / BIARC_EDGES as f64).to_radians()).to_array())
        .collect();
    let join = on(c1, 3.0, 40f64.to_radians());
    let c2 = join + 2.0 * (c1 - join);
    for k in 1..=BIARC_EDGES {
        let phi = (40.0 + 30.0 * k as f64 / BIARC_EDGES as f64).to_radians();
        points.push(on(c2, 6.0, phi).to_array());
    }
    design(
        30.0,
        arc([0.0, 0.0, -10.0], [0.0, 1.0, 0.0], 60.0, 13),
        GuideSpec::Points {
            points,
            tangent: Some([0.0, 1.0, 0.0]),
        },
    )
}

fn options(layers: &[f64]) -> FabricationOptions {
    FabricationOptions {
        layers: layers.to_vec(),
        ..Default::default()
    }
}

/// Every measured property of a fabrication, returning the worst relative values.
fn check_all(f: &Fabrication, base: &QuadGrid, circular: bool) {
    let size = base.bbox_diagonal();
    // Offsets: node offsets move every vertex by exactly |d|.
    if circular {
        for layer in &f.layers {
            for (a, b) in base.vertices.iter().zip(&layer.grid.vertices) {
                let dev = ((*b - *a).length() - layer.distance.abs()).abs();
                assert!(
                    dev <= TOL * size,
                    "offset {} deviates by {dev}",
                    layer.distance
                );
            }
        }
    }
    // Panels: the flat outline reproduces the 3D edges and diagonals.
    for p in f.panels() {
        let quad = f.layers[p.layer].grid.face(p.i, p.j);
        for (a, b) in [(0, 1), (1, 2), (2, 3), (3, 0), (0, 2), (1, 3)] {
            let d3 = (quad[b] - quad[a]).length();
            let d2 = (p.outline[b] - p.outline[a]).length();
            assert!(
                (d3 - d2).abs() <= TOL * size,
                "panel ({}, {}) of layer {}: {a}-{b} is {d3} in space, {d2} flat",
                p.i,
                p.j,
                p.layer
            );
        }
        // Independently: the shoelace formula on the flat outline.
        let o = &p.outline;
        let area = 0.5 * (0..4).map(|c| o[c].perp_dot(o[(c + 1) % 4])).sum::<f64>();
        assert!((p.area - area).abs() <= TOL * size * size);
        let angle_sum: f64 = p.angles.iter().sum();
        assert!((angle_sum - std::f64::consts::TAU).abs() < 1e-9);
    }
    // Beams: nodes in the plane, plane coordinates that give the nodes back,
    // planar by an independent SVD fit, arcs through their nodes.
    let mut worst_arc: f64 = 0.0;
    for b in f.beams() {
        let g = &f.layers[b.layer].grid;
        let points: Vec<DVec3> = match b.family {
            LineFamily::Row => g.row(b.index).collect(),
            LineFamily::Column => g.column(b.index).collect(),
        };
        assert_eq!(points.len(), b.nodes.len());
        let fr = &b.frame;
        assert!((fr.normal.length() - 1.0).abs() < 1e-12);
        assert!(fr.normal.dot(fr.x_axis).abs() < 1e-12 && fr.x_axis.dot(fr.y_axis).abs() < 1e-12);
        for (p, q) in points.iter().zip(&b.nodes) {
            assert!((*p - fr.origin).dot(fr.normal).abs() <= TOL * size);
            let back = fr.origin + q.x * fr.x_axis + q.y * fr.y_axis;
            assert!((back - *p).length() <= TOL * size);
        }
        assert!(plane_fit(&points).2 <= TOL * size);
        for s in &b.segments {
            worst_arc = worst_arc.max(s.residual);
            match s.shape {
                SegmentShape::Arc {
                    center_3d,
                    radius,
                    sweep,
                    length,
                    ..
                } => {
                    for p in &points[s.start..=s.end] {
                        let off = ((*p - center_3d).length() - radius).abs();
                        assert!(off <= TOL * size, "node off its arc by {off}");
                    }
                    // The sweep is the angle swept at the centre by the end nodes.
                    let (a, c) = (points[s.start] - center_3d, points[s.end] - center_3d);
                    let chord_angle = a.cross(c).length().atan2(a.dot(c));
                    if sweep.abs() <= std::f64::consts::PI {
                        assert!((sweep.abs() - chord_angle).abs() < 1e-9);
                    }
                    assert!((length - radius * sweep.abs()).abs() <= TOL * size);
                }
                SegmentShape::Straight { length } => {
                    let (a, c) = (points[s.start], points[s.end]);
                    assert!(((c - a).length() - length).abs() <= TOL * size);
                    for p in &points[s.start..=s.end] {
                        let d = (*p - a).cross((c - a).normalize()).length();
                        assert!(d <= TOL * size);
                    }
                }
            }
        }
        // Consecutive segments share a node and cover the beam.
        assert_eq!(b.segments[0].start, 0);
        assert_eq!(b.segments.last().unwrap().end, b.nodes.len() - 1);
        for w in b.segments.windows(2) {
            assert_eq!(w[0].end, w[1].start);
        }
    }
    // The summary, made from the beams computed one at a time, is theirs.
    assert_eq!(f.summary.max_arc_residual, worst_arc);
    assert_eq!(f.summary.beams, f.beams().len());
    // Nodes: torsion-free edges, measured on every layer.
    for layer in &f.layers {
        let g = &layer.grid;
        for i in 0..g.rows {
            for j in 0..g.cols {
                let n = g.normals[g.index(i, j)];
                for (ni, nj) in [(i + 1, j), (i, j + 1)] {
                    if ni < g.rows && nj < g.cols {
                        let e = (g.vertex(ni, nj) - g.vertex(i, j)).normalize();
                        let m = g.normals[g.index(ni, nj)];
                        assert!(e.dot(n.cross(m)).abs() <= TOL, "torsion at ({i}, {j})");
                    }
                }
            }
        }
    }
    assert!(f.summary.max_torsion <= TOL);
}

#[test]
fn dupin_cyclide_has_circular_beams_and_identical_node_heights() {
    let base = mesh(&dupin(30.0));
    let f = fabricate(BaseMesh::Circular(&base), &options(&[0.0, 0.1, 0.2, -0.15])).unwrap();
    check_all(&f, &base, true);
    let s = &f.summary;
    assert_eq!(s.panels, 4 * 12 * 10);
    assert_eq!(s.beams, 4 * (13 + 11));
    assert_eq!(s.nodes, 13 * 11);
    // Proposition 4: every line of a Dupin cyclide is one circular arc.
    for fam in &s.families {
        assert_eq!((fam.min_segments, fam.max_segments), (1, 1), "{fam:?}");
        assert_eq!(fam.straight_segments, 0);
    }
    // One radius per line: at most (rows + cols) radii per layer.
    assert!(s.radii.len() <= 4 * (13 + 11));
    // Identical node heights: the distance between the outer layers, 0.35, measured here.
    for n in f.nodes() {
        let k = base.index(n.i, n.j);
        let h = (f.layers[2].grid.vertices[k] - f.layers[3].grid.vertices[k]).length();
        assert!((h - 0.35).abs() < 1e-12 && (n.height - h).abs() < 1e-12);
    }
    assert!(s.node_height.1 - s.node_height.0 < 1e-12);
}

#[test]
fn biarc_guide_gives_biarc_rows_and_circular_columns() {
    let base = mesh(&biarc());
    let f = fabricate(BaseMesh::Circular(&base), &options(&[0.0, 0.1, 0.2])).unwrap();
    check_all(&f, &base, true);
    let rows = f
        .summary
        .families
        .iter()
        .find(|x| x.family == LineFamily::Row)
        .unwrap();
    let cols = f
        .summary
        .families
        .iter()
        .find(|x| x.family == LineFamily::Column)
        .unwrap();
    // Columns follow the circular guide_u: one arc, one radius each (Proposition 4).
    assert_eq!(
        (
            cols.min_segments,
            cols.max_segments,
            cols.max_radii_per_beam
        ),
        (1, 1, 1)
    );
    // Rows follow the bi-arc guide_v: two arcs each, split at the join node.
    assert_eq!(
        (
            rows.min_segments,
            rows.max_segments,
            rows.max_radii_per_beam
        ),
        (2, 2, 2)
    );
    for b in f.beams().filter(|b| b.family == LineFamily::Row) {
        assert_eq!(b.splits(), vec![BIARC_EDGES]);
        // Tangent continuity at the split: the centres and the join are collinear.
        let (SegmentShape::Arc { center_3d: c1, .. }, SegmentShape::Arc { center_3d: c2, .. }) =
            (b.segments[0].shape, b.segments[1].shape)
        else {
            panic!("rows are arcs");
        };
        let g = &f.layers[b.layer].grid;
        let join = g.vertex(b.index, BIARC_EDGES);
        assert!((c1 - join).cross(c2 - join).length() <= 1e-9 * (c2 - join).length_squared());
    }
    let (lo, hi) = f.summary.node_height;
    assert!((lo - 0.2).abs() < 1e-12 && (hi - 0.2).abs() < 1e-12);
}

#[test]
fn torus_nodes_repeat_around_the_axis() {
    // θ = 0 with two arcs: a torus (moulding surface on a circular rail). Nodes of
    // one column j are congruent by the rotation, so the types are at most one per
    // column for each of the first row, the last row and the interior rows.
    let base = mesh(&dupin(0.0));
    let f = fabricate(BaseMesh::Circular(&base), &options(&[0.0, 0.3])).unwrap();
    check_all(&f, &base, true);
    assert!(
        f.summary.node_types <= 3 * base.cols,
        "{}",
        f.summary.node_types
    );
    // Interior nodes of one column have the same beam angles (to 1e-12).
    for j in 0..base.cols {
        let column: Vec<_> = f
            .nodes()
            .filter(|n| n.j == j && n.i > 0 && n.i + 1 < base.rows)
            .collect();
        for n in &column {
            assert_eq!(n.node_type, column[0].node_type);
            for (a, b) in n.beam_angles.iter().zip(&column[0].beam_angles) {
                assert!((a - b).abs() < 1e-12);
            }
        }
    }
}

#[test]
fn conical_layers_are_face_offsets() {
    let circular = mesh(&dupin(30.0));
    let conical = conical_dual(&circular);
    let f = fabricate(BaseMesh::Conical(&conical), &options(&[0.0, 0.25])).unwrap();
    check_all(&f, &conical.grid, false);
    // Face planes at constant distance 0.25, measured on every interior face.
    let (g0, g1) = (&f.layers[0].grid, &f.layers[1].grid);
    for (k, n) in conical.face_normals.iter().enumerate() {
        let (i, j) = (k / (g0.cols - 1), k % (g0.cols - 1));
        for (a, b) in g0.face(i, j).iter().zip(g1.face(i, j)) {
            assert!(((b - *a).dot(*n) - 0.25).abs() < TOL);
        }
    }
    assert!(f.summary.max_offset_deviation < TOL);
}

#[test]
fn flat_grid_has_straight_beams() {
    let v = (0..3)
        .flat_map(|i| (0..4).map(move |j| DVec3::new(i as f64, j as f64 * 0.5, 0.0)))
        .collect();
    let g = QuadGrid::new(3, 4, v, vec![DVec3::Z; 12]);
    let f = fabricate(BaseMesh::Circular(&g), &options(&[0.0])).unwrap();
    check_all(&f, &g, true);
    assert!(f.summary.radii.is_empty());
    for b in f.beams() {
        assert_eq!(b.segments.len(), 1);
        assert!(matches!(b.segments[0].shape, SegmentShape::Straight { .. }));
        assert!(b.turning_angles.iter().all(|a| *a == 0.0));
    }
    // Four corners, four kinds of boundary node, one interior node.
    assert_eq!(f.summary.node_types, 9);
    assert_eq!(f.panel(0, 0, 0).outline[2], DVec2::new(1.0, 0.5));
}

fn square(normals: bool) -> QuadGrid {
    let v = vec![DVec3::ZERO, DVec3::Y, DVec3::X, DVec3::X + DVec3::Y];
    QuadGrid::new(
        2,
        2,
        v,
        if normals {
            vec![DVec3::Z; 4]
        } else {
            Vec::new()
        },
    )
}

fn error(grid: &QuadGrid, options: &FabricationOptions) -> FabricationError {
    let e = fabricate(BaseMesh::Circular(grid), options).unwrap_err();
    assert!(!e.to_string().is_empty());
    e
}

#[test]
fn error_no_normals() {
    assert_eq!(
        error(&square(false), &options(&[0.0])),
        FabricationError::NoNormals
    );
}

#[test]
fn error_too_small() {
    let g = QuadGrid::new(1, 2, vec![DVec3::ZERO, DVec3::X], vec![DVec3::Z; 2]);
    assert_eq!(
        error(&g, &options(&[0.0])),
        FabricationError::TooSmall { rows: 1, cols: 2 }
    );
}

#[test]
fn error_no_layers() {
    assert_eq!(
        error(&square(true), &options(&[])),
        FabricationError::NoLayers
    );
}

#[test]
fn error_non_finite_layer() {
    let e = error(&square(true), &options(&[0.0, f64::INFINITY]));
    assert!(
        matches!(e, FabricationError::NonFiniteLayer { index: 1, .. }),
        "{e}"
    );
    // Finite, but its offset overflows (it once wrote -2.69e308 in panels.csv).
    let e = error(&square(true), &options(&[1e308]));
    assert!(
        matches!(e, FabricationError::NonFiniteLayer { index: 0, .. }),
        "{e}"
    );
}

#[test]
fn error_bad_tolerance() {
    let o = FabricationOptions {
        angle_tol: -1.0,
        ..Default::default()
    };
    let e = error(&square(true), &o);
    assert!(matches!(
        e,
        FabricationError::BadTolerance {
            name: "angle_tol",
            ..
        }
    ));
    assert!(e.to_string().contains("angle_tol"));
}

#[test]
fn error_degenerate_edge() {
    // Axes converging at (0.5, 0.5, 1): the offset at distance |(0.5, 0.5, 1)| collapses the square.
    let mut g = square(true);
    let apex = DVec3::new(0.5, 0.5, 1.0);
    g.normals = g.vertices.iter().map(|v| (apex - *v).normalize()).collect();
    let d = (apex - DVec3::ZERO).length();
    let e = error(&g, &options(&[0.0, d]));
    assert!(
        matches!(e, FabricationError::DegenerateEdge { layer: 1, .. }),
        "{e}"
    );
}

#[test]
fn error_degenerate_face() {
    // All four corners on one line: edges of non-zero length, no plane.
    let v = vec![DVec3::ZERO, DVec3::X, 3.0 * DVec3::X, 2.0 * DVec3::X];
    let g = QuadGrid::new(2, 2, v, vec![DVec3::Z; 4]);
    let e = error(&g, &options(&[0.0]));
    assert_eq!(
        e,
        FabricationError::DegenerateFace {
            layer: 0,
            distance: 0.0,
            face: (0, 0)
        }
    );
}

#[test]
fn error_degenerate_face_is_the_first_of_several() {
    // Rows are computed side by side: of two degenerate faces, (1, 0) and
    // (2, 0), the first (row-major) is the error. Face (0, 0) is a square.
    let v = [
        [0.0, -1.0],
        [1.0, -1.0],
        [0.0, 0.0],
        [1.0, 0.0],
        [3.0, 0.0],
        [2.0, 0.0],
        [5.0, 0.0],
        [4.0, 0.0],
    ]
    .map(|[x, y]| DVec3::new(x, y, 0.0))
    .to_vec();
    let g = QuadGrid::new(4, 2, v, vec![DVec3::Z; 8]);
    let e = error(&g, &options(&[0.0]));
    assert_eq!(
        e,
        FabricationError::DegenerateFace {
            layer: 0,
            distance: 0.0,
            face: (1, 0)
        }
    );
}

/// Node types of `f` by the definition (§6), by brute force: each node, in
/// order, takes the smallest type whose first node has the same directions and
/// all angles within `angle_tol`, else a new type.
fn brute_force_types(f: &Fabrication, angle_tol: f64) -> Vec<usize> {
    let sig = |n: &monge_core::fabrication::Node| -> Vec<f64> {
        n.beam_angles
            .iter()
            .chain(&n.axis_angles)
            .copied()
            .collect()
    };
    let mut firsts: Vec<usize> = Vec::new();
    let nodes: Vec<_> = f.nodes().collect();
    let mut types = Vec::with_capacity(nodes.len());
    for (k, n) in nodes.iter().enumerate() {
        let s = sig(n);
        let found = firsts.iter().position(|&r| {
            let rep = &nodes[r];
            let t = sig(rep);
            rep.directions == n.directions
                && t.len() == s.len()
                && t.iter().zip(&s).all(|(a, b)| (a - b).abs() <= angle_tol)
        });
        types.push(found.unwrap_or_else(|| {
            firsts.push(k);
            firsts.len() - 1
        }));
    }
    types
}

#[test]
fn node_types_agree_with_brute_force_grouping() {
    // The Figure 13 guides on a fine grid: every interior beam angle is near 90°,
    // the case where a one-angle lookup degenerates. Tolerances from none merged
    // to most merged.
    let base = mesh(&freeform(-30.0, 41, 41));
    let mut counts = Vec::new();
    for angle_tol in [1e-9, 1e-3, 5e-3, 2e-2, 1e-1] {
        let opts = FabricationOptions {
            angle_tol,
            ..options(&[0.0])
        };
        let f = fabricate(BaseMesh::Circular(&base), &opts).unwrap();
        let types: Vec<usize> = f.nodes().map(|n| n.node_type).collect();
        assert_eq!(
            types,
            brute_force_types(&f, angle_tol),
            "angle_tol {angle_tol}"
        );
        counts.push(f.summary.node_types);
    }
    // The tolerances span the cases: all nodes distinct, some merged, few types.
    assert_eq!(counts[0], base.vertices.len());
    assert!(counts.windows(2).all(|w| w[0] >= w[1]), "{counts:?}");
    assert!(counts[4] < base.vertices.len() / 10, "{counts:?}");
}

#[test]
#[should_panic(expected = "no Column 2")]
fn a_beam_that_is_not_there_is_refused() {
    let v = (0..3)
        .flat_map(|i| (0..2).map(move |j| DVec3::new(i as f64, j as f64, 0.0)))
        .collect();
    let g = QuadGrid::new(3, 2, v, vec![DVec3::Z; 6]);
    let f = fabricate(BaseMesh::Circular(&g), &options(&[0.0])).unwrap();
    f.beam(0, LineFamily::Column, 2);
}

/// A fit whose mesh pinches is still reported (its panels and deviation), with
/// fabrication's refusal as the reason its node types are not counted: a surface of
/// revolution (θ = 0°, §4.1.1) whose meridian ends on the axis, so that its last
/// parallel is a single point.
#[test]
fn a_fit_report_says_why_a_pinched_mesh_has_no_node_types() {
    use monge_core::approximate::{fit_report, FitDesign, TargetCloud};
    let pinched = design(
        0.0,
        arc([0.0, 0.0, -6.0], [0.0, 1.0, 0.0], 90.0, 7),
        common::bspline(
            vec![
                [0.0, 0.0, 0.0],
                [0.0, 3.0, 0.0],
                [0.0, 6.0, -3.0],
                [0.0, 6.0, -6.0],
            ],
            7,
        ),
    );
    let g = mesh(&pinched);
    // The last parallel, on the axis (the line through (0, 0, −6) along y), is one point.
    let last: Vec<DVec3> = (0..7).map(|i| g.vertex(i, 6)).collect();
    assert!(last
        .iter()
        .all(|p| (*p - DVec3::new(0.0, 6.0, -6.0)).length() < 1e-12));
    let target = TargetCloud::new(&g.vertices).unwrap();
    let report = fit_report(&target, &FitDesign::Single(pinched), 0.5f64.to_radians()).unwrap();
    assert_eq!(report.panels, 36);
    assert!(report.deviation.mesh_to_target_max < 1e-12);
    match report.node_types {
        Err(FabricationError::DegenerateEdge { layer: 0, .. }) => {}
        other => panic!("expected the pinch as the reason, got {other:?}"),
    }
}
