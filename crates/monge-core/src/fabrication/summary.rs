//! The summary of a fabrication (§6): worst values and counts, per line family.

use serde::Serialize;

use super::arcs::SegmentShape;
use super::beams::{beams_per_layer, nth_beam, Beam, LineFamily};
use super::input::{BaseMesh, FabricationOptions};
use super::layers::{offset_deviation, LayerMesh};
use super::nodes::{distinct, NodeSummary};
use super::panels::PanelSummary;

/// Worst values and counts of a fabrication (§6).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Summary {
    /// Model size: the bounding-box diagonal of the base mesh.
    pub size: f64,
    /// Layer distances.
    pub layers: Vec<f64>,
    /// Number of panels (all layers).
    pub panels: usize,
    /// Number of beams (all layers).
    pub beams: usize,
    /// Number of nodes.
    pub nodes: usize,
    /// Rows and columns on their own.
    pub families: Vec<FamilySummary>,
    /// Distinct arc radii over all beams (within `radius_tol · size`), ascending.
    pub radii: Vec<f64>,
    /// Number of distinct node types.
    pub node_types: usize,
    /// Smallest and largest node height.
    pub node_height: (f64, f64),
    /// Largest deviation of a layer from constant distance to the base mesh
    /// (vertex distance for node offsets, face-plane distance for face offsets).
    pub max_offset_deviation: f64,
    /// Largest panel planarity residual.
    pub max_panel_planarity: f64,
    /// Largest panel circularity residual (§2.2); `None` for a conical mesh,
    /// whose panels need not be circular (§2.3).
    pub max_panel_circularity: Option<f64>,
    /// Largest distance of a beam's node from its plane.
    pub max_beam_plane_residual: f64,
    /// Largest distance of a beam's node from its segment's arc or line.
    pub max_arc_residual: f64,
    /// Largest edge torsion (dimensionless).
    pub max_torsion: f64,
}

/// Statistics of one family of beams (§4.6).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FamilySummary {
    /// Rows or columns.
    pub family: LineFamily,
    /// Beams of this family (all layers).
    pub beams: usize,
    /// Fewest segments in one beam.
    pub min_segments: usize,
    /// Most segments in one beam.
    pub max_segments: usize,
    /// Most distinct radii in one beam.
    pub max_radii_per_beam: usize,
    /// Distinct radii over the family.
    pub distinct_radii: usize,
    /// Straight segments in the family.
    pub straight_segments: usize,
}

/// What the summary needs of one beam (§4.6, §6).
struct BeamFacts {
    family: LineFamily,
    segments: usize,
    straight_segments: usize,
    /// Radii of its arcs, in order.
    radii: Vec<f64>,
    /// Its distinct radii (within the radius tolerance).
    distinct_radii: usize,
    plane_residual: f64,
    arc_residual: f64,
}

impl BeamFacts {
    /// The facts of `beam`, radii within `rtol` counted as one.
    fn of(beam: &Beam, rtol: f64) -> Self {
        let radii: Vec<f64> = beam
            .segments
            .iter()
            .filter_map(|s| match s.shape {
                SegmentShape::Arc { radius, .. } => Some(radius),
                SegmentShape::Straight { .. } => None,
            })
            .collect();
        BeamFacts {
            family: beam.family,
            segments: beam.segments.len(),
            straight_segments: beam.segments.len() - radii.len(),
            distinct_radii: distinct(radii.clone(), rtol).len(),
            radii,
            plane_residual: beam.plane_residual,
            arc_residual: beam.segments.iter().map(|s| s.residual).fold(0.0, f64::max),
        }
    }
}

/// The summary (§6); the beams are computed here on every core, each one
/// dropped once its [`BeamFacts`] are taken.
pub(super) fn summarise(
    base: BaseMesh<'_>,
    layers: &[LayerMesh],
    arc_tol: f64,
    panels: PanelSummary,
    nodes: NodeSummary,
    size: f64,
    options: &FabricationOptions,
) -> Summary {
    let rtol = options.radius_tol * size;
    let beams = crate::tasks::map(layers.len() * beams_per_layer(layers), |n| {
        BeamFacts::of(&nth_beam(layers, arc_tol, n), rtol)
    });
    let radii = |fam: &mut dyn Iterator<Item = &BeamFacts>| {
        distinct(fam.flat_map(|b| b.radii.iter().copied()).collect(), rtol)
    };
    let families = [LineFamily::Row, LineFamily::Column]
        .into_iter()
        .map(|family| {
            let fam: Vec<&BeamFacts> = beams.iter().filter(|b| b.family == family).collect();
            let counts = fam.iter().map(|b| b.segments);
            FamilySummary {
                family,
                beams: fam.len(),
                min_segments: counts.clone().min().unwrap_or(0),
                max_segments: counts.max().unwrap_or(0),
                max_radii_per_beam: fam.iter().map(|b| b.distinct_radii).max().unwrap_or(0),
                distinct_radii: radii(&mut fam.iter().copied()).len(),
                straight_segments: fam.iter().map(|b| b.straight_segments).sum(),
            }
        })
        .collect();
    let max = |it: &mut dyn Iterator<Item = f64>| it.fold(0.0, f64::max);
    Summary {
        size,
        layers: layers.iter().map(|l| l.distance).collect(),
        panels: panels.count,
        beams: beams.len(),
        nodes: nodes.count,
        families,
        radii: radii(&mut beams.iter()),
        node_types: nodes.types,
        node_height: nodes.height,
        max_offset_deviation: offset_deviation(base, layers),
        max_panel_planarity: panels.max_planarity,
        max_panel_circularity: matches!(base, BaseMesh::Circular(_))
            .then_some(panels.max_circularity),
        max_beam_plane_residual: max(&mut beams.iter().map(|b| b.plane_residual)),
        max_arc_residual: max(&mut beams.iter().map(|b| b.arc_residual)),
        max_torsion: nodes.max_torsion,
    }
}
