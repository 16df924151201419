//! The conical error of a grid (§2.3): how far the face normals around each interior
//! vertex are from concyclic.

use crate::QuadGrid;

use super::faces::face_planarity;
use super::Worst;

/// Conical error of a quad grid (§2.3): at every interior vertex, how far the
/// unit normals of its four faces are from lying on one circle of the unit sphere.
///
/// A conical mesh has, at each vertex, four face planes tangent to one cone of
/// revolution, i.e. the four unit face normals lie on a circle of S², i.e. they
/// are coplanar as points. The face normal is the normalised cross product of
/// the face's diagonals `(C − A) × (D − B)`. The four normals, taken in cyclic
/// order around the vertex (faces `(i−1, j−1), (i, j−1), (i, j), (i−1, j)`),
/// form a quad on S² whose [`face_planarity`] (distance between its diagonal
/// lines — symmetric in the four normals) is the error at the vertex. It is
/// dimensionless (a distance on the unit sphere's scale) and not divided by
/// the grid's scale. `at` = the vertex `(i, j)`.
///
/// Vertices next to a degenerate face (zero diagonal cross product, no normal)
/// are skipped. `None` when the grid has no interior vertex (fewer than 3 rows
/// or columns).
pub fn conical_error(grid: &QuadGrid) -> Option<Worst> {
    if grid.rows < 3 || grid.cols < 3 {
        return None;
    }
    let normal = |i: usize, j: usize| {
        let [a, b, c, d] = grid.face(i, j);
        (c - a).cross(d - b).try_normalize()
    };
    let mut worst = Worst::NONE;
    for i in 1..grid.rows - 1 {
        for j in 1..grid.cols - 1 {
            let around = [
                normal(i - 1, j - 1),
                normal(i, j - 1),
                normal(i, j),
                normal(i - 1, j),
            ];
            if let [Some(a), Some(b), Some(c), Some(d)] = around {
                worst.update(face_planarity(&[a, b, c, d]), (i, j));
            }
        }
    }
    Some(worst)
}
