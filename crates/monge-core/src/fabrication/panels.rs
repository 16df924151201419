//! The panels of a gridshell (§2.2, §6): every face of every layer flattened in its
//! own plane, with its edge lengths, angles, area, circumradius and residuals.

use glam::{DVec2, DVec3};
use serde::Serialize;

use crate::grid::quad_area;
use crate::measure::{circularity, face_planarity};

use super::arcs::PlaneFrame;
use super::input::FabricationError;
use super::layers::LayerMesh;

/// A face as a flat panel (§2.2, §6), numbered by its grid indices.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Panel {
    /// Index of the layer it belongs to.
    pub layer: usize,
    /// Face index along guide_u.
    pub i: usize,
    /// Face index along guide_v.
    pub j: usize,
    /// The face plane: origin at corner `(i, j)`, `x_axis` along the edge to `(i+1, j)`,
    /// `normal` along the cross product of the diagonals.
    pub frame: PlaneFrame,
    /// The outline in plane coordinates, corners `(i, j), (i+1, j), (i+1, j+1), (i, j+1)`.
    pub outline: [DVec2; 4],
    /// 3D edge lengths: corner k to corner k+1.
    pub edge_lengths: [f64; 4],
    /// Interior corner angles, radians (sum 2π for a convex panel).
    pub angles: [f64; 4],
    /// Area of the panel ([`quad_area`]: half the diagonals' cross product).
    pub area: f64,
    /// Radius of the circle through corners 0, 1 and 2 (the circumcircle of a circular face).
    pub circumradius: f64,
    /// Distance between the lines of the two diagonals ([`face_planarity`]).
    pub planarity: f64,
    /// Distance of a corner from the circle through the other three ([`circularity`]).
    pub circularity: f64,
}

/// What the summary needs of the panels (§6): their count and worst residuals.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct PanelSummary {
    pub(super) count: usize,
    pub(super) max_planarity: f64,
    pub(super) max_circularity: f64,
}

impl PanelSummary {
    /// Counts `other` in (maxima as `f64::max`, so in any order).
    pub(super) fn add(&mut self, other: PanelSummary) {
        self.count += other.count;
        self.max_planarity = self.max_planarity.max(other.max_planarity);
        self.max_circularity = self.max_circularity.max(other.max_circularity);
    }
}

/// Checks every face of a layer and summarises its panels (§6), rows side by
/// side; the first degenerate face (row-major) is the error.
pub(super) fn layer_panels(k: usize, layer: &LayerMesh) -> Result<PanelSummary, FabricationError> {
    let rows = crate::tasks::map(layer.grid.rows - 1, |i| row_panels(k, layer, i));
    let mut sum = PanelSummary::default();
    for row in rows {
        sum.add(row?);
    }
    Ok(sum)
}

/// Checks the faces of row `i` of layer `k` and summarises their panels (§6).
fn row_panels(k: usize, layer: &LayerMesh, i: usize) -> Result<PanelSummary, FabricationError> {
    let g = &layer.grid;
    let mut sum = PanelSummary::default();
    for j in 0..g.cols - 1 {
        let quad = g.face(i, j);
        let normal = (quad[2] - quad[0]).cross(quad[3] - quad[1]);
        let edge = quad[1] - quad[0];
        if normal.length() <= 1e-12 * (quad[2] - quad[0]).length() * (quad[3] - quad[1]).length()
            || normal.cross(edge) == DVec3::ZERO
        {
            return Err(FabricationError::DegenerateFace {
                layer: k,
                distance: layer.distance,
                face: (i, j),
            });
        }
        let p = flat_panel(k, quad, i, j);
        sum.add(PanelSummary {
            count: 1,
            max_planarity: p.planarity,
            max_circularity: p.circularity,
        });
    }
    Ok(sum)
}

/// Face `(i, j)` of layer `k`, with corners `quad`, as a flat panel (§6).
pub(super) fn flat_panel(k: usize, quad: [DVec3; 4], i: usize, j: usize) -> Panel {
    let normal = (quad[2] - quad[0]).cross(quad[3] - quad[1]);
    let frame = PlaneFrame::new(quad[0], normal, quad[1] - quad[0]);
    let edge_lengths = [0, 1, 2, 3].map(|c| (quad[(c + 1) % 4] - quad[c]).length());
    let angles = [0, 1, 2, 3].map(|c| {
        let (prev, next) = (quad[(c + 3) % 4] - quad[c], quad[(c + 1) % 4] - quad[c]);
        angle_between(prev, next)
    });
    Panel {
        layer: k,
        i,
        j,
        frame,
        outline: quad.map(|p| frame.to_plane(p)),
        edge_lengths,
        angles,
        area: quad_area(&quad),
        circumradius: circumradius(quad[0], quad[1], quad[2]),
        planarity: face_planarity(&quad),
        circularity: circularity(&quad),
    }
}

/// Angle between two non-zero vectors, radians, accurate near 0 and π.
pub(super) fn angle_between(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().atan2(a.dot(b))
}

/// Radius of the circle through three points (infinite if collinear).
fn circumradius(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let (ab, bc, ca) = ((b - a).length(), (c - b).length(), (a - c).length());
    ab * bc * ca / (2.0 * (b - a).cross(c - a).length())
}
