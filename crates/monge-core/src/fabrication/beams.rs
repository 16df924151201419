//! The beams of a gridshell (§4.6, §6): every mesh line of every layer in its own
//! plane, with its nodes in plane coordinates and its circular segments.

use glam::{DVec2, DVec3};
use nalgebra::{Matrix3, SymmetricEigen};
use serde::Serialize;

use crate::grid::QuadGrid;

use super::arcs::{finish_segment, segments, BeamSegment, PlaneFrame, SegmentShape};
use super::layers::LayerMesh;

/// Which family of mesh lines a beam belongs to (§6).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum LineFamily {
    /// Row `i`: vertices `(i, 0), (i, 1), …`, along guide_v.
    Row,
    /// Column `j`: vertices `(0, j), (1, j), …`, along guide_u.
    Column,
}

/// A mesh line as a planar beam (§2.2, §4.6, §6).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Beam {
    /// Index of the layer it belongs to.
    pub layer: usize,
    /// Row or column.
    pub family: LineFamily,
    /// The row index `i` or the column index `j`.
    pub index: usize,
    /// The beam's plane: origin at the first node, `x_axis` along the chord to the
    /// last node, `normal` from a least-squares fit.
    pub frame: PlaneFrame,
    /// Node positions in plane coordinates.
    pub nodes: Vec<DVec2>,
    /// 3D edge lengths, node k to node k+1.
    pub edge_lengths: Vec<f64>,
    /// Signed turning angle at each interior node (radians): the angle from edge
    /// k−1 to edge k in the plane, positive counter-clockwise; 0 for straight.
    pub turning_angles: Vec<f64>,
    /// Largest distance of a node from the plane (absolute).
    pub plane_residual: f64,
    /// Torsion of each edge: `|det(ê, n_p, n_q)|` for the node axes at its ends
    /// (0 when they are coplanar with the edge, §2.2).
    pub torsion: Vec<f64>,
    /// The circular or straight pieces, in order (§4.6).
    pub segments: Vec<BeamSegment>,
}

impl Beam {
    /// Developed length (§4.6): the lengths of its arcs and straight pieces, what
    /// a bent beam is cut to (longer than the polyline through its nodes, the sum
    /// of [`Beam::edge_lengths`]).
    pub fn length(&self) -> f64 {
        self.segments
            .iter()
            .map(|s| match s.shape {
                SegmentShape::Arc { length, .. } | SegmentShape::Straight { length } => length,
            })
            .sum()
    }

    /// Node indices where one segment ends and the next starts (§4.6).
    pub fn splits(&self) -> Vec<usize> {
        self.segments.iter().skip(1).map(|s| s.start).collect()
    }
}

/// Beam `n` of [`Fabrication::beams`](super::Fabrication::beams): every row, then every column, of
/// every layer, layer by layer.
pub(super) fn nth_beam(layers: &[LayerMesh], tol: f64, n: usize) -> Beam {
    let (k, b) = (n / beams_per_layer(layers), n % beams_per_layer(layers));
    let g = &layers[k].grid;
    let (family, index) = layer_line(g, b);
    line_beam(k, g, family, index, tol)
}

/// The line of beam `b` of a layer of grid `g`: its rows, then its columns.
pub(super) fn layer_line(g: &QuadGrid, b: usize) -> (LineFamily, usize) {
    if b < g.rows {
        (LineFamily::Row, b)
    } else {
        (LineFamily::Column, b - g.rows)
    }
}

/// Rows and columns of one layer (every layer has the base mesh's).
pub(super) fn beams_per_layer(layers: &[LayerMesh]) -> usize {
    let g = &layers[0].grid;
    g.rows + g.cols
}

/// Row or column `index` of `g`, layer `k`, as a beam.
pub(super) fn line_beam(
    k: usize,
    g: &QuadGrid,
    family: LineFamily,
    index: usize,
    tol: f64,
) -> Beam {
    let idx: Vec<usize> = match family {
        LineFamily::Row => (0..g.cols).map(|j| g.index(index, j)).collect(),
        LineFamily::Column => (0..g.rows).map(|i| g.index(i, index)).collect(),
    };
    beam(k, family, index, g, &idx, tol)
}

/// One beam: the vertices `idx` of `g`.
fn beam(
    layer: usize,
    family: LineFamily,
    index: usize,
    g: &QuadGrid,
    idx: &[usize],
    tol: f64,
) -> Beam {
    let points: Vec<DVec3> = idx.iter().map(|&v| g.vertices[v]).collect();
    let axes: Vec<DVec3> = idx.iter().map(|&v| g.normals[v]).collect();
    let frame = beam_frame(&points, &axes);
    let nodes: Vec<DVec2> = points.iter().map(|&p| frame.to_plane(p)).collect();
    let plane_residual = points
        .iter()
        .map(|&p| frame.height(p).abs())
        .fold(0.0, f64::max);
    let edge_lengths = points.windows(2).map(|w| (w[1] - w[0]).length()).collect();
    let turning_angles = nodes
        .windows(3)
        .map(|w| {
            let (a, b) = (w[1] - w[0], w[2] - w[1]);
            a.perp_dot(b).atan2(a.dot(b))
        })
        .collect();
    let torsion = (0..points.len() - 1)
        .map(|k| {
            let e = (points[k + 1] - points[k]).normalize();
            e.dot(axes[k].cross(axes[k + 1])).abs()
        })
        .collect();
    let segments = segments(&nodes, tol)
        .into_iter()
        .map(|s| finish_segment(s, &nodes, &frame))
        .collect();
    Beam {
        layer,
        family,
        index,
        frame,
        nodes,
        edge_lengths,
        turning_angles,
        plane_residual,
        torsion,
        segments,
    }
}

/// The plane of a polyline (§2.2): least-squares normal (smallest eigenvector of
/// the covariance); for collinear nodes, the plane through the line that
/// contains the mean node axis. Origin at the first node, x along the chord.
fn beam_frame(points: &[DVec3], axes: &[DVec3]) -> PlaneFrame {
    let first = points[0];
    let last = points[points.len() - 1];
    let chord = last - first;
    let centroid = points.iter().copied().sum::<DVec3>() / points.len() as f64;
    let mut cov = Matrix3::<f64>::zeros();
    for p in points {
        let d = *p - centroid;
        let d = nalgebra::Vector3::new(d.x, d.y, d.z);
        cov += d * d.transpose();
    }
    let eig = SymmetricEigen::new(cov);
    let mut order = [0, 1, 2];
    order.sort_by(|&a, &b| eig.eigenvalues[a].total_cmp(&eig.eigenvalues[b]));
    let (mid, large) = (eig.eigenvalues[order[1]], eig.eigenvalues[order[2]]);
    let collinear = mid <= 1e-24 * large || large == 0.0;
    let normal = if collinear {
        let mean_axis = axes.iter().copied().sum::<DVec3>();
        let n = chord.cross(mean_axis);
        if n.length() > 1e-12 * chord.length() * mean_axis.length() {
            n
        } else {
            chord.any_orthonormal_vector()
        }
    } else {
        let v = eig.eigenvectors.column(order[0]);
        DVec3::new(v[0], v[1], v[2])
    };
    // Put the origin in the fitted plane (through the centroid), at the first node's projection.
    let n = normal.normalize();
    let origin = first - (first - centroid).dot(n) * n;
    // Orient the normal with the node axes, so that frames are consistent across layers.
    let mean_axis = axes.iter().copied().sum::<DVec3>();
    let n = if n.cross(chord).dot(mean_axis) < 0.0 {
        -n
    } else {
        n
    };
    PlaneFrame::new(origin, n, chord)
}
