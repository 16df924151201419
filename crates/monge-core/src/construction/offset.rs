//! Offsets (§2.2, §2.3): node offsets of circular meshes along their node axes,
//! face offsets of conical meshes.

use crate::conical::ConicalMesh;
use crate::grid::QuadGrid;

/// The vertex (node) offset of a circular mesh at `distance` along its node
/// axes (§2.2).
///
/// Every vertex moves by `distance · N`. The result is again a circular mesh
/// with planar lines and the same node axes: its edges stay parallel to the Gauss
/// map's (it is another Combescure transform of it).
///
/// # Panics
/// If the grid has no normals.
///
/// ```
/// use glam::DVec3;
/// use monge_core::{offset::vertex_offset, QuadGrid};
/// let g = QuadGrid::new(1, 2, vec![DVec3::ZERO, DVec3::X], vec![DVec3::Z; 2]);
/// assert_eq!(vertex_offset(&g, 0.5).vertices[1], DVec3::new(1.0, 0.0, 0.5));
/// ```
pub fn vertex_offset(grid: &QuadGrid, distance: f64) -> QuadGrid {
    assert_eq!(
        grid.normals.len(),
        grid.vertices.len(),
        "node axes are needed"
    );
    let vertices = grid
        .vertices
        .iter()
        .zip(&grid.normals)
        .map(|(x, n)| *x + distance * *n)
        .collect();
    QuadGrid::new(grid.rows, grid.cols, vertices, grid.normals.clone())
}

/// The face offset of a conical mesh at `distance` (§2.3): every face plane
/// moves by `distance` along its unit normal, and the faces stay planar and
/// meet again at conical vertices (each vertex moves by `distance · K`).
///
/// ```
/// use glam::DVec3;
/// use monge_core::{conical::ConicalMesh, offset::face_offset, QuadGrid};
/// let c = ConicalMesh {
///     grid: QuadGrid::new(1, 1, vec![DVec3::ZERO], Vec::new()),
///     face_normals: Vec::new(),
///     offset_directions: vec![DVec3::Z],
/// };
/// assert_eq!(face_offset(&c, 2.0).grid.vertices[0], DVec3::new(0.0, 0.0, 2.0));
/// ```
pub fn face_offset(conical: &ConicalMesh, distance: f64) -> ConicalMesh {
    let vertices = conical
        .grid
        .vertices
        .iter()
        .zip(&conical.offset_directions)
        .map(|(x, k)| *x + distance * *k)
        .collect();
    ConicalMesh {
        grid: QuadGrid::new(conical.grid.rows, conical.grid.cols, vertices, Vec::new()),
        ..conical.clone()
    }
}
