//! What fabrication takes (§6): the base mesh, the options, and what it refuses.

use crate::conical::ConicalMesh;
use crate::grid::QuadGrid;

/// The mesh a gridshell is built on (§2.2, §2.3).
#[derive(Clone, Copy, Debug)]
pub enum BaseMesh<'a> {
    /// A circular mesh with node axes: layers are node offsets (§2.2).
    Circular(&'a QuadGrid),
    /// A conical mesh: layers are face offsets (§2.3); node axes are the cone
    /// axes (the directions of its offset vectors).
    Conical(&'a ConicalMesh),
}

/// Options of [`fabricate`](super::fabricate) (§6).
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

/// The node-type tolerance a designer groups nodes at, in degrees: nodes whose beam
/// angles and angles to the node axis agree within 0.5° are one type, as a façade
/// engineer counts the node connectors of a free-form roof (on the shipped paraboloid's
/// approximation at 40 × 40 faces: 75 types for 1681 nodes, against 451 at 0.1° and
/// 1681 at `monge fabricate`'s 1e-4°, which tells apart every node of a curved mesh).
/// The approximation report counts node types at it (`monge approximate --angle-tol`,
/// `monge.approximate(..., angle_tol_deg=...)`).
pub const DESIGN_ANGLE_TOL_DEG: f64 = 0.5;

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

/// Why [`fabricate`](super::fabricate) refused a mesh or its options (§6).
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
    /// A layer distance is NaN, infinite or beyond [`MAX_SIZE`](crate::grid::MAX_SIZE) (§2.2).
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
