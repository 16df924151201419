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

use rustc_hash::FxHashMap;

use glam::{DVec2, DVec3};
use nalgebra::{Matrix3, SymmetricEigen};
use serde::Serialize;

use crate::conical::ConicalMesh;
use crate::grid::{quad_area, QuadGrid};
use crate::measure::{circularity, face_planarity};
use crate::offset::{face_offset, vertex_offset};

/// The mesh a gridshell is built on (§2.2, §2.3).
#[derive(Clone, Copy, Debug)]
pub enum BaseMesh<'a> {
    /// A circular mesh with node axes: layers are node offsets (§2.2).
    Circular(&'a QuadGrid),
    /// A conical mesh: layers are face offsets (§2.3); node axes are the cone
    /// axes (the directions of its offset vectors).
    Conical(&'a ConicalMesh),
}

/// Options of [`fabricate`] (§6).
#[derive(Clone, Debug, PartialEq)]
pub struct FabricationOptions {
    /// Offset distances of the layers (§2.2, §2.3), in model units; at least one.
    pub layers: Vec<f64>,
    /// Length tolerance relative to the model size (§4.6): a node lies on a
    /// segment's circle if its distance from it is at most `tol · size`.
    pub tol: f64,
    /// Radii within `radius_tol · size` of each other count as one radius (§6).
    pub radius_tol: f64,
    /// Nodes whose beam angles agree within this many radians share a type (§6).
    pub angle_tol: f64,
}

impl Default for FabricationOptions {
    /// One layer at distance 0, `tol = radius_tol = 1e-9`, `angle_tol` = 1e-6 rad.
    fn default() -> Self {
        FabricationOptions {
            layers: vec![0.0],
            tol: 1e-9,
            radius_tol: 1e-9,
            angle_tol: 1e-6,
        }
    }
}

/// Why [`fabricate`] refused a mesh or its options (§6).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum FabricationError {
    /// A circular mesh without node axes has no node offsets (§2.2).
    #[error(
        "the circular mesh has no node axes: node offsets (§2.2) need one unit normal per vertex"
    )]
    NoNormals,
    /// The mesh has fewer than 2 × 2 vertices: no face, no beam with an edge (§6).
    #[error("the mesh has {rows} × {cols} vertices; fabrication needs at least 2 × 2 (one face)")]
    TooSmall {
        /// Vertices along guide_u.
        rows: usize,
        /// Vertices along guide_v.
        cols: usize,
    },
    /// No layer distance was given (§2.2).
    #[error("no layer: give at least one offset distance (0 for the mesh itself)")]
    NoLayers,
    /// A layer distance is NaN, infinite or beyond [`MAX_SIZE`](crate::generate::MAX_SIZE) (§2.2).
    #[error(
        "layer {index} has distance {value}; distances must be finite and at most 1e100 in \
         size (beyond, the offset's coordinates overflow double precision)"
    )]
    NonFiniteLayer {
        /// Position of the distance in [`FabricationOptions::layers`].
        index: usize,
        /// The distance given.
        value: f64,
    },
    /// A tolerance is negative, NaN or infinite (§6).
    #[error("tolerance `{name}` is {value}; it must be finite and non-negative")]
    BadTolerance {
        /// Which option: `tol`, `radius_tol` or `angle_tol`.
        name: &'static str,
        /// The value given.
        value: f64,
    },
    /// An edge of a layer is no longer than `tol · size`, so it has no reliable
    /// direction: the mesh or its offset pinches there (§5.2).
    #[error(
        "layer {layer} (offset {distance}): edge from vertex ({}, {}) to ({}, {}) is {length:.3e} \
         long, at most tol × size = {limit:.3e}, so it has no reliable direction: the mesh pinches \
         there (§5.2), or tol is too large; choose other layer distances, another θ or a smaller tol",
        from.0, from.1, to.0, to.1
    )]
    DegenerateEdge {
        /// Index of the layer.
        layer: usize,
        /// Offset distance of the layer.
        distance: f64,
        /// Grid indices of the first vertex.
        from: (usize, usize),
        /// Grid indices of the second vertex.
        to: (usize, usize),
        /// The edge's length.
        length: f64,
        /// `tol · size`.
        limit: f64,
    },
    /// A face of a layer has crossing diagonals of zero cross product: no plane.
    #[error(
        "layer {layer} (offset {distance}): face ({}, {}) has parallel or zero diagonals, so it \
         has no plane to be flattened in",
        face.0, face.1
    )]
    DegenerateFace {
        /// Index of the layer.
        layer: usize,
        /// Offset distance of the layer.
        distance: f64,
        /// Grid indices of the face.
        face: (usize, usize),
    },
}

/// One layer of the gridshell: the base mesh offset by `distance` (§2.2, §2.3).
#[derive(Clone, Debug, PartialEq)]
pub struct LayerMesh {
    /// The offset distance.
    pub distance: f64,
    /// The offset mesh; its normals are the node axes.
    pub grid: QuadGrid,
}

/// A local orthonormal frame of a plane (§6): `point = origin + x·x_axis + y·y_axis`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PlaneFrame {
    /// Origin of the plane coordinates.
    pub origin: DVec3,
    /// First axis (unit).
    pub x_axis: DVec3,
    /// Second axis (unit, orthogonal to the first).
    pub y_axis: DVec3,
    /// Unit normal, `x_axis × y_axis`.
    pub normal: DVec3,
}

impl PlaneFrame {
    /// A frame with origin `origin`, normal along `normal` and first axis along
    /// the part of `x` orthogonal to it (§6). Both must be non-zero and not parallel.
    fn new(origin: DVec3, normal: DVec3, x: DVec3) -> Self {
        let normal = normal.normalize();
        let x_axis = (x - x.dot(normal) * normal).normalize();
        PlaneFrame {
            origin,
            x_axis,
            y_axis: normal.cross(x_axis),
            normal,
        }
    }

    /// Plane coordinates of `p` (its orthogonal projection) (§6).
    pub fn to_plane(&self, p: DVec3) -> DVec2 {
        let d = p - self.origin;
        DVec2::new(d.dot(self.x_axis), d.dot(self.y_axis))
    }

    /// The 3D point at plane coordinates `q` (§6).
    pub fn to_space(&self, q: DVec2) -> DVec3 {
        self.origin + q.x * self.x_axis + q.y * self.y_axis
    }

    /// Signed distance of `p` from the plane (§6).
    pub fn height(&self, p: DVec3) -> f64 {
        (p - self.origin).dot(self.normal)
    }
}

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

/// Which family of mesh lines a beam belongs to (§6).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum LineFamily {
    /// Row `i`: vertices `(i, 0), (i, 1), …`, along guide_v.
    Row,
    /// Column `j`: vertices `(0, j), (1, j), …`, along guide_u.
    Column,
}

/// The shape of one piece of a beam between two split nodes (§4.6).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "lowercase", tag = "kind")]
pub enum SegmentShape {
    /// A circular arc through the segment's nodes.
    Arc {
        /// Centre in the beam's plane coordinates.
        center: DVec2,
        /// Centre in space.
        center_3d: DVec3,
        /// Radius.
        radius: f64,
        /// Signed sweep angle from the first to the last node, radians
        /// (positive counter-clockwise about the plane normal).
        sweep: f64,
        /// Arc length, `radius · |sweep|`.
        length: f64,
    },
    /// A straight piece: the nodes are collinear.
    Straight {
        /// Length from the first to the last node.
        length: f64,
    },
}

/// A piece of a beam that is one circular arc or one straight bar (§4.6).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct BeamSegment {
    /// Index of its first node in the beam.
    pub start: usize,
    /// Index of its last node in the beam (the first node of the next segment).
    pub end: usize,
    /// Its shape.
    pub shape: SegmentShape,
    /// Largest distance of its nodes from the arc or line (absolute).
    pub residual: f64,
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

/// A node of the gridshell (§2.2, §6).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Node {
    /// Index along guide_u.
    pub i: usize,
    /// Index along guide_v.
    pub j: usize,
    /// Position on the layer at distance 0 (the base mesh).
    pub position: DVec3,
    /// Unit node axis.
    pub axis: DVec3,
    /// Directions present, in the order `+i, +j, −i, −j` (which neighbours exist).
    pub directions: Vec<&'static str>,
    /// Angles between consecutive present edges (in that cyclic order), radians.
    pub beam_angles: Vec<f64>,
    /// Angle between each present edge and the node axis, radians.
    pub axis_angles: Vec<f64>,
    /// Distance between the node's positions on the first and the last layer.
    pub height: f64,
    /// Largest torsion of its edges (see [`Beam::torsion`]).
    pub torsion: f64,
    /// Its node type: nodes of one type agree within `angle_tol`.
    pub node_type: usize,
}

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
        .find(|(_, d)| d.is_nan() || d.abs() > crate::generate::MAX_SIZE)
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

/// The offset layers; each grid carries the unit node axes as its normals.
fn build_layers(base: BaseMesh<'_>, distances: &[f64]) -> Vec<LayerMesh> {
    distances
        .iter()
        .map(|&distance| {
            let grid = match base {
                BaseMesh::Circular(g) => vertex_offset(g, distance),
                BaseMesh::Conical(c) => {
                    let mut g = face_offset(c, distance).grid;
                    g.normals = c.offset_directions.iter().map(|k| k.normalize()).collect();
                    g
                }
            };
            LayerMesh { distance, grid }
        })
        .collect()
}

/// Refuses edges of length at most `tol` (they have no reliable direction).
fn check_edges(k: usize, layer: &LayerMesh, tol: f64) -> Result<(), FabricationError> {
    let g = &layer.grid;
    for i in 0..g.rows {
        for j in 0..g.cols {
            for (di, dj) in [(1, 0), (0, 1)] {
                let (a, b) = ((i, j), (i + di, j + dj));
                if b.0 >= g.rows || b.1 >= g.cols {
                    continue;
                }
                let length = (g.vertex(a.0, a.1) - g.vertex(b.0, b.1)).length();
                if length <= tol {
                    return Err(FabricationError::DegenerateEdge {
                        layer: k,
                        distance: layer.distance,
                        from: a,
                        to: b,
                        length,
                        limit: tol,
                    });
                }
            }
        }
    }
    Ok(())
}

/// What the summary needs of the panels (§6): their count and worst residuals.
#[derive(Clone, Copy, Debug, Default)]
struct PanelSummary {
    count: usize,
    max_planarity: f64,
    max_circularity: f64,
}

impl PanelSummary {
    /// Counts `other` in (maxima as `f64::max`, so in any order).
    fn add(&mut self, other: PanelSummary) {
        self.count += other.count;
        self.max_planarity = self.max_planarity.max(other.max_planarity);
        self.max_circularity = self.max_circularity.max(other.max_circularity);
    }
}

/// Checks every face of a layer and summarises its panels (§6), rows side by
/// side; the first degenerate face (row-major) is the error.
fn layer_panels(k: usize, layer: &LayerMesh) -> Result<PanelSummary, FabricationError> {
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
fn flat_panel(k: usize, quad: [DVec3; 4], i: usize, j: usize) -> Panel {
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
fn angle_between(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().atan2(a.dot(b))
}

/// Radius of the circle through three points (infinite if collinear).
fn circumradius(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let (ab, bc, ca) = ((b - a).length(), (c - b).length(), (a - c).length());
    ab * bc * ca / (2.0 * (b - a).cross(c - a).length())
}

/// Beam `n` of [`Fabrication::beams`]: every row, then every column, of
/// every layer, layer by layer.
fn nth_beam(layers: &[LayerMesh], tol: f64, n: usize) -> Beam {
    let (k, b) = (n / beams_per_layer(layers), n % beams_per_layer(layers));
    let g = &layers[k].grid;
    let (family, index) = layer_line(g, b);
    line_beam(k, g, family, index, tol)
}

/// The line of beam `b` of a layer of grid `g`: its rows, then its columns.
fn layer_line(g: &QuadGrid, b: usize) -> (LineFamily, usize) {
    if b < g.rows {
        (LineFamily::Row, b)
    } else {
        (LineFamily::Column, b - g.rows)
    }
}

/// Rows and columns of one layer (every layer has the base mesh's).
fn beams_per_layer(layers: &[LayerMesh]) -> usize {
    let g = &layers[0].grid;
    g.rows + g.cols
}

/// Row or column `index` of `g`, layer `k`, as a beam.
fn line_beam(k: usize, g: &QuadGrid, family: LineFamily, index: usize, tol: f64) -> Beam {
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

/// A segment in plane coordinates, before its 3D centre is known.
struct PlaneSegment {
    start: usize,
    end: usize,
    /// `Some((centre, radius))` for an arc, `None` for a straight piece.
    circle: Option<(DVec2, f64)>,
}

/// The arc or line through three points (§4.6): `None` when they are collinear within `tol`.
fn circle_through(a: DVec2, b: DVec2, c: DVec2, tol: f64) -> Option<(DVec2, f64)> {
    let (ab, ac) = (b - a, c - a);
    let d = 2.0 * ab.perp_dot(ac);
    // Distance of b from the line a–c.
    let chord = ac.length();
    if chord == 0.0 || (ab.perp_dot(ac) / chord).abs() <= tol {
        return None;
    }
    let centre = a + DVec2::new(
        ac.y * ab.length_squared() - ab.y * ac.length_squared(),
        ab.x * ac.length_squared() - ac.x * ab.length_squared(),
    ) / d;
    let radius = ((a - centre).length() + (b - centre).length() + (c - centre).length()) / 3.0;
    Some((centre, radius))
}

/// Distance of `p` from a circle or from the line through `a` and `b`.
fn off(p: DVec2, circle: Option<(DVec2, f64)>, a: DVec2, b: DVec2) -> f64 {
    match circle {
        Some((c, r)) => ((p - c).length() - r).abs(),
        None => {
            let d = b - a;
            (p - a).perp_dot(d).abs() / d.length()
        }
    }
}

/// Splits plane nodes into maximal circular (or straight) pieces (§4.6): the
/// circle through three consecutive nodes is extended while the next node is
/// within `tol` of it; the next piece starts at the last node of this one. A
/// final piece of one edge continues the previous piece's tangent.
fn segments(nodes: &[DVec2], tol: f64) -> Vec<PlaneSegment> {
    let n = nodes.len();
    let mut out: Vec<PlaneSegment> = Vec::new();
    let mut s = 0;
    while s + 1 < n {
        if s + 2 >= n {
            out.push(PlaneSegment {
                start: s,
                end: s + 1,
                circle: tangent_circle(out.last(), nodes, s),
            });
            break;
        }
        let circle = circle_through(nodes[s], nodes[s + 1], nodes[s + 2], tol);
        let mut e = s + 2;
        while e + 1 < n && off(nodes[e + 1], circle, nodes[s], nodes[s + 1]) <= tol {
            e += 1;
        }
        out.push(PlaneSegment {
            start: s,
            end: e,
            circle,
        });
        s = e;
    }
    out
}

/// The circle through nodes `s` and `s + 1` tangent to the previous piece at
/// node `s`; `None` (straight) if there is no previous piece or the tangent
/// points at the next node.
fn tangent_circle(prev: Option<&PlaneSegment>, nodes: &[DVec2], s: usize) -> Option<(DVec2, f64)> {
    let prev = prev?;
    let a = nodes[s];
    let tangent = match prev.circle {
        Some((c, _)) => {
            let radial = a - c;
            // Orient along the direction of travel.
            let t = radial.perp();
            if t.dot(a - nodes[s - 1]) < 0.0 {
                -t
            } else {
                t
            }
        }
        None => a - nodes[prev.start],
    }
    .normalize();
    let chord = nodes[s + 1] - a;
    let normal = tangent.perp();
    let h = chord.dot(normal);
    if h.abs() <= 1e-12 * chord.length() {
        return None;
    }
    let rho = chord.length_squared() / (2.0 * h);
    Some((a + rho * normal, rho.abs()))
}

/// Adds the shape (3D centre, sweep, length) and the residual to a plane segment.
fn finish_segment(s: PlaneSegment, nodes: &[DVec2], frame: &PlaneFrame) -> BeamSegment {
    let part = &nodes[s.start..=s.end];
    let (a, b) = (part[0], part[part.len() - 1]);
    let (shape, residual) = match s.circle {
        Some((center, radius)) => {
            let sweep: f64 = part
                .windows(2)
                .map(|w| {
                    let (p, q) = (w[0] - center, w[1] - center);
                    p.perp_dot(q).atan2(p.dot(q))
                })
                .sum();
            let shape = SegmentShape::Arc {
                center,
                center_3d: frame.to_space(center),
                radius,
                sweep,
                length: radius * sweep.abs(),
            };
            (shape, max_off(part, s.circle, a, b))
        }
        None => (
            SegmentShape::Straight {
                length: (b - a).length(),
            },
            max_off(part, None, a, b),
        ),
    };
    BeamSegment {
        start: s.start,
        end: s.end,
        shape,
        residual,
    }
}

/// Largest distance of `part` from a circle or from the line through `a` and `b`.
fn max_off(part: &[DVec2], circle: Option<(DVec2, f64)>, a: DVec2, b: DVec2) -> f64 {
    part.iter()
        .map(|&p| off(p, circle, a, b))
        .fold(0.0, f64::max)
}

/// Neighbour offsets in the cyclic order `+i, +j, −i, −j`, with their names.
const DIRECTIONS: [((isize, isize), &str); 4] = [
    ((1, 0), "+i"),
    ((0, 1), "+j"),
    ((-1, 0), "-i"),
    ((0, -1), "-j"),
];

/// The node at vertex `(i, j)` (§6), its type 0; `extremes` are the layers of
/// the smallest and the largest distance ([`extreme_layers`]).
fn node_at(layers: &[LayerMesh], (lo, hi): (usize, usize), i: usize, j: usize) -> Node {
    let base = &layers[0].grid;
    let x = base.vertex(i, j);
    let axis = base.normals[base.index(i, j)];
    let mut edges = Vec::new();
    let mut directions = Vec::new();
    let mut torsion: f64 = 0.0;
    for ((di, dj), name) in DIRECTIONS {
        let (ni, nj) = (i as isize + di, j as isize + dj);
        if ni < 0 || nj < 0 || ni as usize >= base.rows || nj as usize >= base.cols {
            continue;
        }
        let (ni, nj) = (ni as usize, nj as usize);
        let e = base.vertex(ni, nj) - x;
        let other = base.normals[base.index(ni, nj)];
        torsion = torsion.max(e.normalize().dot(axis.cross(other)).abs());
        edges.push(e);
        directions.push(name);
    }
    let beam_angles = if edges.len() < 2 {
        Vec::new()
    } else {
        let pairs = if edges.len() == 2 { 1 } else { edges.len() };
        (0..pairs)
            .map(|k| angle_between(edges[k], edges[(k + 1) % edges.len()]))
            .collect()
    };
    let axis_angles = edges.iter().map(|&e| angle_between(e, axis)).collect();
    let k = base.index(i, j);
    let height = (layers[hi].grid.vertices[k] - layers[lo].grid.vertices[k]).length();
    Node {
        i,
        j,
        position: x,
        axis,
        directions,
        beam_angles,
        axis_angles,
        height,
        torsion,
        node_type: 0,
    }
}

/// What the summary needs of the nodes (§6).
struct NodeSummary {
    count: usize,
    types: usize,
    height: (f64, f64),
    max_torsion: f64,
}

/// The type of every node, row-major, and their summary (§6): nodes computed
/// a block of rows at a time (rows side by side), typed in order.
fn build_nodes(layers: &[LayerMesh], angle_tol: f64) -> (Vec<usize>, NodeSummary) {
    let base = &layers[0].grid;
    let extremes = extreme_layers(layers);
    let mut types = NodeTypes::new(angle_tol);
    let mut node_types = Vec::with_capacity(base.vertices.len());
    let (mut height, mut max_torsion): ((f64, f64), f64) = ((f64::INFINITY, 0.0), 0.0);
    let block = (crate::tasks::BLOCK / base.cols).max(1);
    for first in (0..base.rows).step_by(block) {
        let rows = crate::tasks::map(block.min(base.rows - first), |r| {
            (0..base.cols)
                .map(|j| node_at(layers, extremes, first + r, j))
                .collect::<Vec<_>>()
        });
        for n in rows.iter().flatten() {
            node_types.push(types.of(n));
            height = (height.0.min(n.height), height.1.max(n.height));
            max_torsion = max_torsion.max(n.torsion);
        }
    }
    let sum = NodeSummary {
        count: node_types.len(),
        types: types.count,
        height,
        max_torsion,
    };
    (node_types, sum)
}

/// Indices of the layers with the smallest and the largest distance.
fn extreme_layers(layers: &[LayerMesh]) -> (usize, usize) {
    let by =
        |a: &(usize, &LayerMesh), b: &(usize, &LayerMesh)| a.1.distance.total_cmp(&b.1.distance);
    let lo = layers.iter().enumerate().min_by(by).map_or(0, |p| p.0);
    let hi = layers.iter().enumerate().max_by(by).map_or(0, |p| p.0);
    (lo, hi)
}

/// Groups nodes whose directions agree and whose angles agree within
/// `angle_tol` (§6): greedy, each node joins the matching type of smallest
/// index (a type is represented by its first node). Candidates are looked up in
/// a hash grid of cell `angle_tol` over two of the angles (every signature has
/// at least three), so each node compares with the types in the 3 × 3 cells
/// around it, kept side by side with their angles: on a fine curvature-line
/// mesh every angle is close to 90° and a cell holds many types, so comparing
/// must not chase pointers.
struct NodeTypes {
    angle_tol: f64,
    /// Types so far.
    count: usize,
    cells: FxHashMap<(i64, i64), Vec<Type>>,
}

/// A node type: its index, its first node's directions (a bit per entry of
/// [`DIRECTIONS`]) and angles (beam angles then axis angles, the first `len`
/// of `angles`).
struct Type {
    index: usize,
    directions: u8,
    len: usize,
    angles: [f64; SIGNATURE],
}

impl NodeTypes {
    fn new(angle_tol: f64) -> Self {
        NodeTypes {
            angle_tol,
            count: 0,
            cells: FxHashMap::default(),
        }
    }

    /// The type of `node`: the first matching one, or a new one.
    fn of(&mut self, node: &Node) -> usize {
        let angle_tol = self.angle_tol;
        let cell_width = angle_tol.max(1e-15);
        let cell = |a: f64| (a / cell_width).floor() as i64;
        let mut angles = [0.0; SIGNATURE];
        let sig = node.beam_angles.iter().chain(&node.axis_angles);
        // At most one beam angle and one axis angle per direction.
        let len = sig.clone().count();
        for (slot, &a) in angles.iter_mut().zip(sig) {
            *slot = a;
        }
        let directions = DIRECTIONS
            .iter()
            .enumerate()
            .filter(|(_, (_, name))| node.directions.contains(name))
            .fold(0, |mask, (k, _)| mask | 1 << k);
        // The first beam angle and the first axis angle: on a curvature-line
        // mesh the beam angles are nearly equal (all near 90°), the axis
        // angles tell more apart (42 candidates per node at 1000 × 1000 faces
        // against 184 with the first two beam angles).
        let key = match angles[..len] {
            [a, _, ..] => (cell(a), cell(angles[len / 2])),
            [a] => (cell(a), 0),
            [] => (0, 0),
        };
        let matches = |t: &&Type| {
            // The angles first: they tell most candidates apart, and cheaply.
            t.len == len
                && t.angles[..len]
                    .iter()
                    .zip(&angles[..len])
                    .all(|(a, b)| (a - b).abs() <= angle_tol)
                && t.directions == directions
        };
        let found = (key.0 - 1..=key.0 + 1)
            .flat_map(|a| (key.1 - 1..=key.1 + 1).map(move |b| (a, b)))
            .filter_map(|c| self.cells.get(&c))
            .flatten()
            .filter(matches)
            .map(|t| t.index)
            .min();
        found.unwrap_or_else(|| {
            let index = self.count;
            self.count += 1;
            let cell = self.cells.entry(key).or_default();
            // Most cells hold one type or a few: grown by a quarter, not
            // doubled (a doubled cell has room for four types at least; the
            // 684 000 types of 1000 × 1000 faces took 99 MB so, about 60 now).
            if cell.len() == cell.capacity() {
                cell.reserve_exact(cell.len() / 4 + 1);
            }
            cell.push(Type {
                index,
                directions,
                len,
                angles,
            });
            index
        })
    }
}

/// Most angles that tell node types apart: a beam angle and an axis angle
/// per direction.
const SIGNATURE: usize = 2 * DIRECTIONS.len();

/// Distinct values within `tol` of their group's smallest member, ascending.
fn distinct(mut values: Vec<f64>, tol: f64) -> Vec<f64> {
    values.sort_by(f64::total_cmp);
    let mut out: Vec<f64> = Vec::new();
    for v in values {
        match out.last() {
            Some(&first) if v - first <= tol => {}
            _ => out.push(v),
        }
    }
    out
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
fn summarise(
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

/// Largest deviation of each layer from constant distance `|d|` to the base mesh
/// (§2.2, §2.3): vertex distances for node offsets, distances between the
/// corresponding face planes (through the conical mesh's vertices) for face offsets.
fn offset_deviation(base: BaseMesh<'_>, layers: &[LayerMesh]) -> f64 {
    let mut worst: f64 = 0.0;
    match base {
        BaseMesh::Circular(g) => {
            for layer in layers {
                for (a, b) in g.vertices.iter().zip(&layer.grid.vertices) {
                    worst = worst.max(((*b - *a).length() - layer.distance.abs()).abs());
                }
            }
        }
        BaseMesh::Conical(c) => {
            let g = &c.grid;
            for layer in layers {
                for (f, n) in c.face_normals.iter().enumerate() {
                    let (i, j) = (f / (g.cols - 1), f % (g.cols - 1));
                    for (a, b) in g.face(i, j).iter().zip(layer.grid.face(i, j)) {
                        worst = worst.max(((b - *a).dot(*n) - layer.distance).abs());
                    }
                }
            }
        }
    }
    worst
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arcs_split_where_the_circle_changes() {
        // A bi-arc: radius 1 about the origin for 60°, then radius 3 tangent to it.
        let mut nodes: Vec<DVec2> = (0..=6)
            .map(|k| DVec2::from_angle(k as f64 * 10f64.to_radians()))
            .collect();
        let join = nodes[6];
        let c2 = join * -2.0; // centre of the second circle, on the same normal
        for k in 1..=4 {
            let a = 60f64.to_radians() + k as f64 * 5f64.to_radians();
            nodes.push(c2 + 3.0 * DVec2::from_angle(a));
        }
        let segs = segments(&nodes, 1e-12);
        assert_eq!(segs.len(), 2);
        assert_eq!((segs[0].start, segs[0].end, segs[1].end), (0, 6, 10));
        let (c, r) = segs[1].circle.unwrap();
        assert!((r - 3.0).abs() < 1e-12 && (c - c2).length() < 1e-12);
    }

    #[test]
    fn a_last_single_edge_continues_the_tangent() {
        let nodes = [
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, 0.0),
            DVec2::new(2.0, 0.0),
            DVec2::new(3.0, 1.0),
            DVec2::new(4.0, 3.0),
        ];
        let segs = segments(&nodes, 1e-12);
        // Straight 0–2, then an arc 2–4 (three nodes), nothing left over.
        assert_eq!(segs.len(), 2);
        assert!(segs[0].circle.is_none() && segs[1].circle.is_some());
        // Two nodes after a straight piece: tangent to it at node 2.
        let segs = segments(&nodes[..4], 1e-12);
        let (c, r) = segs[1].circle.unwrap();
        assert!(((nodes[3] - c).length() - r).abs() < 1e-12);
        assert!((c - DVec2::new(2.0, 1.0)).length() < 1e-12);
    }

    #[test]
    fn distinct_groups_within_tolerance() {
        assert_eq!(
            distinct(vec![3.0, 1.0, 1.0 + 1e-12, 2.0], 1e-9),
            vec![1.0, 2.0, 3.0]
        );
    }
}
