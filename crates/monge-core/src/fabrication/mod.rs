//! Gridshell fabrication (§6, Figure 25): layers, panels, beams and nodes.
//!
//! From a circular mesh (§2.2) or its conical dual (§2.3), [`fabricate`] builds
//! what a fabricator orders:
//!
//! * **layers** ([`LayerMesh`]): node offsets of a circular mesh along its node
//!   axes (§2.2), face offsets of a conical mesh (§2.3), at given distances
//!   (Figure 25 uses one for the glass and three for the beams);
//! * **panels** ([`Panel`]): every face of every layer flattened exactly in its
//!   own plane, with edge lengths, corner angles, area, circumradius and the
//!   planarity and circularity residuals;
//! * **beams** ([`Beam`]): every mesh line (row and column) of every layer in its
//!   own plane, with its nodes in plane coordinates and, where its nodes are
//!   inscribed in circles (§4.6, Proposition 4), the circular segments a roller
//!   bender makes ([`BeamSegment`]): centre, radius, sweep and the node indices
//!   where the radius changes (bi-arcs, n-arcs);
//! * **nodes** ([`Node`]): node axis, the angles between the beams meeting there,
//!   node height across the layers, torsion residual, and a node type: nodes
//!   whose angles agree within a tolerance share one connector detail.
//!
//! Everything is pure geometry; the schedules and drawings are written by
//! `monge-io`.

use std::ops::Range;

mod arcs;
mod beams;
mod input;
mod layers;
mod nodes;
mod panels;
mod summary;

use beams::{beams_per_layer, layer_line, line_beam, nth_beam};
use layers::{build_layers, check_edges};
use nodes::{build_nodes, extreme_layers, node_at};
use panels::{flat_panel, layer_panels, PanelSummary};
use summary::summarise;

pub use arcs::{BeamSegment, PlaneFrame, SegmentShape};
pub use beams::{Beam, LineFamily};
pub use input::{BaseMesh, FabricationError, FabricationOptions, DESIGN_ANGLE_TOL_DEG};
pub use layers::LayerMesh;
pub use nodes::Node;
pub use panels::Panel;
pub use summary::{FamilySummary, Summary};

/// Everything a fabricator needs (§6).
#[derive(Clone, Debug, PartialEq)]
pub struct Fabrication {
    /// The layers, in the order of [`FabricationOptions::layers`]; their faces
    /// are the panels ([`Fabrication::panels`]), their rows and columns the
    /// beams ([`Fabrication::beams`]).
    pub layers: Vec<LayerMesh>,
    /// A node lies on a beam segment's circle within this distance:
    /// [`FabricationOptions::tol`] times the model size.
    arc_tol: f64,
    /// The type of every node, row-major; the nodes themselves are computed
    /// when asked for ([`Fabrication::nodes`]).
    node_types: Vec<usize>,
    /// Counts and worst values.
    pub summary: Summary,
}

impl Fabrication {
    /// Every face of every layer as a flat panel (§2.2, §6), layer by layer,
    /// row-major: computed from the layers as they are asked for (a panel takes
    /// 288 bytes, twelve times its vertex).
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::fabrication::{fabricate, BaseMesh, FabricationOptions};
    /// use monge_core::QuadGrid;
    /// let v = (0..3).flat_map(|i| (0..2).map(move |j| DVec3::new(i as f64, j as f64, 0.0))).collect();
    /// let grid = QuadGrid::new(3, 2, v, vec![DVec3::Z; 6]);
    /// let options = FabricationOptions { layers: vec![0.0, 0.5], ..Default::default() };
    /// let f = fabricate(BaseMesh::Circular(&grid), &options).unwrap();
    /// let panels: Vec<_> = f.panels().collect();
    /// assert_eq!(panels.len(), f.summary.panels);
    /// assert_eq!((panels[3].layer, panels[3].i, panels[3].j), (1, 1, 0));
    /// assert_eq!(panels[3], f.panel(1, 1, 0));
    /// ```
    pub fn panels(&self) -> impl ExactSizeIterator<Item = Panel> + Clone + '_ {
        self.panels_in(0..self.layers.len() * self.layers[0].grid.face_count())
    }

    /// The panels numbered `range` of [`Fabrication::panels`] (§6): for
    /// computing them in pieces, side by side.
    ///
    /// # Panics
    /// If `range` ends beyond the panels.
    pub fn panels_in(
        &self,
        range: Range<usize>,
    ) -> impl ExactSizeIterator<Item = Panel> + Clone + '_ {
        // Every layer has the base mesh's faces.
        let (faces, cols) = (
            self.layers[0].grid.face_count(),
            self.layers[0].grid.cols - 1,
        );
        assert!(
            range.end <= faces * self.layers.len(),
            "no panel {}",
            range.end - 1
        );
        range.map(move |n| {
            let (k, f) = (n / faces, n % faces);
            let (i, j) = (f / cols, f % cols);
            flat_panel(k, self.layers[k].grid.face(i, j), i, j)
        })
    }

    /// Every row, then every column, of every layer, layer by layer, as a
    /// planar beam with its circular segments (§4.6, §6): computed from the
    /// layers as they are asked for (a beam of `n` nodes takes about `40 n`
    /// bytes and about 100 more per segment: held, the beams took more than
    /// the layers' vertices).
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::fabrication::{fabricate, BaseMesh, FabricationOptions, LineFamily};
    /// use monge_core::QuadGrid;
    /// let v = (0..3).flat_map(|i| (0..2).map(move |j| DVec3::new(i as f64, j as f64, 0.0))).collect();
    /// let grid = QuadGrid::new(3, 2, v, vec![DVec3::Z; 6]);
    /// let options = FabricationOptions { layers: vec![0.0, 0.5], ..Default::default() };
    /// let f = fabricate(BaseMesh::Circular(&grid), &options).unwrap();
    /// let beams: Vec<_> = f.beams().collect();
    /// // Three rows and two columns a layer.
    /// assert_eq!(beams.len(), f.summary.beams);
    /// assert_eq!((beams[8].layer, beams[8].family, beams[8].index), (1, LineFamily::Column, 0));
    /// assert_eq!(beams[8], f.beam(1, LineFamily::Column, 0));
    /// ```
    pub fn beams(&self) -> impl ExactSizeIterator<Item = Beam> + Clone + '_ {
        self.beams_in(0..self.layers.len() * beams_per_layer(&self.layers))
    }

    /// The beams numbered `range` of [`Fabrication::beams`] (§4.6, §6): for
    /// computing them in pieces.
    ///
    /// # Panics
    /// If `range` ends beyond the beams.
    pub fn beams_in(
        &self,
        range: Range<usize>,
    ) -> impl ExactSizeIterator<Item = Beam> + Clone + '_ {
        let count = self.layers.len() * beams_per_layer(&self.layers);
        assert!(range.end <= count, "no beam {}", range.end - 1);
        range.map(move |n| nth_beam(&self.layers, self.arc_tol, n))
    }

    /// The beams of layer `k`, rows then columns (§4.6, §6).
    ///
    /// # Panics
    /// If there is no such layer.
    pub fn layer_beams(&self, k: usize) -> impl ExactSizeIterator<Item = Beam> + Clone + '_ {
        assert!(k < self.layers.len(), "no layer {k}");
        let per_layer = beams_per_layer(&self.layers);
        self.beams_in(k * per_layer..(k + 1) * per_layer)
    }

    /// The number of nodes of each beam of layer `k`, in the order of
    /// [`Fabrication::layer_beams`] (§6), without computing the beams: what a
    /// drawing of the beams needs to know before their points.
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::fabrication::{fabricate, BaseMesh, FabricationOptions};
    /// use monge_core::QuadGrid;
    /// let v = (0..3).flat_map(|i| (0..2).map(move |j| DVec3::new(i as f64, j as f64, 0.0))).collect();
    /// let grid = QuadGrid::new(3, 2, v, vec![DVec3::Z; 6]);
    /// let f = fabricate(BaseMesh::Circular(&grid), &FabricationOptions::default()).unwrap();
    /// // Three rows of two nodes, then two columns of three.
    /// assert_eq!(f.layer_beam_nodes(0).collect::<Vec<_>>(), [2, 2, 2, 3, 3]);
    /// assert!(f.layer_beams(0).map(|b| b.nodes.len()).eq(f.layer_beam_nodes(0)));
    /// ```
    ///
    /// # Panics
    /// If there is no such layer.
    pub fn layer_beam_nodes(&self, k: usize) -> impl ExactSizeIterator<Item = usize> + Clone + '_ {
        let g = &self.layers[k].grid;
        (0..beams_per_layer(&self.layers)).map(move |b| match layer_line(g, b).0 {
            LineFamily::Row => g.cols,
            LineFamily::Column => g.rows,
        })
    }

    /// Row or column `index` of layer `k` as a beam (§4.6, §6).
    ///
    /// # Panics
    /// If there is no such layer, row or column.
    pub fn beam(&self, k: usize, family: LineFamily, index: usize) -> Beam {
        let g = &self.layers[k].grid;
        let lines = match family {
            LineFamily::Row => g.rows,
            LineFamily::Column => g.cols,
        };
        assert!(index < lines, "no {family:?} {index}");
        line_beam(k, g, family, index, self.arc_tol)
    }

    /// One node per vertex of the base mesh, row-major (§2.2, §6): computed from
    /// the layers as they are asked for, with the types found by [`fabricate`].
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::fabrication::{fabricate, BaseMesh, FabricationOptions};
    /// use monge_core::QuadGrid;
    /// let v = (0..3).flat_map(|i| (0..2).map(move |j| DVec3::new(i as f64, j as f64, 0.0))).collect();
    /// let grid = QuadGrid::new(3, 2, v, vec![DVec3::Z; 6]);
    /// let f = fabricate(BaseMesh::Circular(&grid), &FabricationOptions::default()).unwrap();
    /// let nodes: Vec<_> = f.nodes().collect();
    /// assert_eq!(nodes.len(), 6);
    /// assert_eq!(nodes[3], f.node(1, 1));
    /// // On a 3 × 2 grid each node has other neighbours (directions): six types.
    /// assert_eq!(nodes.iter().map(|n| n.node_type).collect::<Vec<_>>(), [0, 1, 2, 3, 4, 5]);
    /// ```
    pub fn nodes(&self) -> impl ExactSizeIterator<Item = Node> + Clone + '_ {
        self.nodes_in(0..self.node_types.len())
    }

    /// The nodes numbered `range` of [`Fabrication::nodes`] (§6): for computing
    /// them in pieces, side by side.
    ///
    /// # Panics
    /// If `range` ends beyond the nodes.
    pub fn nodes_in(
        &self,
        range: Range<usize>,
    ) -> impl ExactSizeIterator<Item = Node> + Clone + '_ {
        assert!(
            range.end <= self.node_types.len(),
            "no node {}",
            range.end - 1
        );
        let (extremes, cols) = (extreme_layers(&self.layers), self.layers[0].grid.cols);
        range.map(move |k| Node {
            node_type: self.node_types[k],
            ..node_at(&self.layers, extremes, k / cols, k % cols)
        })
    }

    /// The node at vertex `(i, j)` of the base mesh (§2.2, §6).
    ///
    /// # Panics
    /// If there is no such vertex.
    pub fn node(&self, i: usize, j: usize) -> Node {
        let g = &self.layers[0].grid;
        assert!(i < g.rows && j < g.cols, "no vertex ({i}, {j})");
        Node {
            node_type: self.node_types[g.index(i, j)],
            ..node_at(&self.layers, extreme_layers(&self.layers), i, j)
        }
    }

    /// Face `(i, j)` of layer `k` as a flat panel (§2.2, §6).
    ///
    /// # Panics
    /// If there is no such layer or face.
    pub fn panel(&self, k: usize, i: usize, j: usize) -> Panel {
        let g = &self.layers[k].grid;
        assert!(i + 1 < g.rows && j + 1 < g.cols, "no face ({i}, {j})");
        flat_panel(k, g.face(i, j), i, j)
    }
}

/// Builds layers, panels, beams and nodes of a gridshell on `base` (§6).
///
/// ```
/// use glam::DVec3;
/// use monge_core::fabrication::{fabricate, BaseMesh, FabricationOptions};
/// use monge_core::QuadGrid;
/// // A flat 3 × 2 grid: straight beams, square panels.
/// let v = (0..3).flat_map(|i| (0..2).map(move |j| DVec3::new(i as f64, j as f64, 0.0))).collect();
/// let grid = QuadGrid::new(3, 2, v, vec![DVec3::Z; 6]);
/// let options = FabricationOptions { layers: vec![0.0, 0.5], ..Default::default() };
/// let f = fabricate(BaseMesh::Circular(&grid), &options).unwrap();
/// assert_eq!((f.panels().len(), f.beams().len(), f.nodes().len()), (4, 10, 6));
/// assert!((f.panel(0, 0, 0).area - 1.0).abs() < 1e-15);
/// assert_eq!(f.summary.node_height, (0.5, 0.5));
/// ```
pub fn fabricate(
    base: BaseMesh<'_>,
    options: &FabricationOptions,
) -> Result<Fabrication, FabricationError> {
    validate(base, options)?;
    let layers = build_layers(base, &options.layers);
    let base_grid = match base {
        BaseMesh::Circular(g) => g,
        BaseMesh::Conical(c) => &c.grid,
    };
    let size = base_grid.bbox_diagonal();
    for (k, layer) in layers.iter().enumerate() {
        check_edges(k, layer, options.tol * size)?;
    }
    let mut panels = PanelSummary::default();
    for (k, layer) in layers.iter().enumerate() {
        panels.add(layer_panels(k, layer)?);
    }
    let (node_types, nodes) = build_nodes(&layers, options.angle_tol);
    let arc_tol = options.tol * size;
    let summary = summarise(base, &layers, arc_tol, panels, nodes, size, options);
    Ok(Fabrication {
        layers,
        arc_tol,
        node_types,
        summary,
    })
}

fn validate(base: BaseMesh<'_>, options: &FabricationOptions) -> Result<(), FabricationError> {
    let grid = match base {
        BaseMesh::Circular(g) => {
            if g.normals.len() != g.vertices.len() {
                return Err(FabricationError::NoNormals);
            }
            g
        }
        BaseMesh::Conical(c) => &c.grid,
    };
    if grid.rows < 2 || grid.cols < 2 {
        return Err(FabricationError::TooSmall {
            rows: grid.rows,
            cols: grid.cols,
        });
    }
    if options.layers.is_empty() {
        return Err(FabricationError::NoLayers);
    }
    if let Some((index, &value)) = options
        .layers
        .iter()
        .enumerate()
        .find(|(_, d)| d.is_nan() || d.abs() > crate::grid::MAX_SIZE)
    {
        return Err(FabricationError::NonFiniteLayer { index, value });
    }
    for (name, value) in [
        ("tol", options.tol),
        ("radius_tol", options.radius_tol),
        ("angle_tol", options.angle_tol),
    ] {
        if !(value.is_finite() && value >= 0.0) {
            return Err(FabricationError::BadTolerance { name, value });
        }
    }
    Ok(())
}
