//! The layers of a gridshell (§6, Figure 25): node offsets of a circular mesh
//! (§2.2), face offsets of a conical mesh (§2.3), their edges checked and their
//! deviation from constant distance to the base mesh measured.

use crate::grid::QuadGrid;
use crate::offset::{face_offset, vertex_offset};

use super::input::{BaseMesh, FabricationError};

/// One layer of the gridshell: the base mesh offset by `distance` (§2.2, §2.3).
#[derive(Clone, Debug, PartialEq)]
pub struct LayerMesh {
    /// The offset distance.
    pub distance: f64,
    /// The offset mesh; its normals are the node axes.
    pub grid: QuadGrid,
}

/// The offset layers; each grid carries the unit node axes as its normals.
pub(super) fn build_layers(base: BaseMesh<'_>, distances: &[f64]) -> Vec<LayerMesh> {
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
pub(super) fn check_edges(k: usize, layer: &LayerMesh, tol: f64) -> Result<(), FabricationError> {
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

/// Largest deviation of each layer from constant distance `|d|` to the base mesh
/// (§2.2, §2.3): vertex distances for node offsets, distances between the
/// corresponding face planes (through the conical mesh's vertices) for face offsets.
pub(super) fn offset_deviation(base: BaseMesh<'_>, layers: &[LayerMesh]) -> f64 {
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
