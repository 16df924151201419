//! The planes of the curvature lines of a multi-patch mesh (§4.7): one
//! least-squares plane per patch a line runs through.

use glam::DVec3;
use nalgebra::Matrix3;
use serde::Serialize;

use crate::design::Xyz;

use super::mesh::MultiPatch;

/// A least-squares plane of one piece of a curvature line (§4.7).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct LinePlane {
    /// The patch the piece belongs to.
    pub patch: usize,
    /// First and last vertex of the piece along the line (inclusive).
    pub vertices: (usize, usize),
    /// Unit normal of the plane.
    pub normal: Xyz,
    /// A point of the plane (the centroid of the piece).
    pub point: Xyz,
    /// Largest distance of a vertex of the piece from the plane, relative to the grid's size.
    pub deviation: f64,
}

/// The planes a curvature line lies in, one per patch it crosses (§4.7).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LinePlanes {
    /// `true` for row `index` (vertices `(index, 0..cols)`), `false` for column `index`.
    pub row: bool,
    /// The row or column index in the assembled grid.
    pub index: usize,
    /// One plane per patch the line runs through (a shared line has one per patch it bounds).
    pub planes: Vec<LinePlane>,
}

impl MultiPatch {
    /// For every row and column of the assembled grid, the planes it lies in: one
    /// per patch it runs through (§4.7). Lines across the seams lie in one plane per
    /// patch; lines of a single patch in one plane (two entries for a shared line).
    /// A piece of two vertices lies in many planes: the one reported contains it.
    pub fn line_planes(&self) -> Vec<LinePlanes> {
        let scale = self.grid.bbox_diagonal().max(f64::MIN_POSITIVE);
        let mut out = Vec::with_capacity(self.grid.rows + self.grid.cols);
        for row in [true, false] {
            let count = if row { self.grid.rows } else { self.grid.cols };
            for index in 0..count {
                let mut planes = Vec::new();
                for (k, p) in self.patches.iter().enumerate() {
                    // The piece of the line in each patch whose rows (columns) hold it.
                    let (holds, (from, to)) = if row {
                        (p.rows, p.cols)
                    } else {
                        (p.cols, p.rows)
                    };
                    if !(holds.0..=holds.1).contains(&index) {
                        continue;
                    }
                    let points: Vec<DVec3> = (from..=to)
                        .map(|t| {
                            if row {
                                self.grid.vertex(index, t)
                            } else {
                                self.grid.vertex(t, index)
                            }
                        })
                        .collect();
                    let (point, normal, dev) = fit_plane(&points);
                    planes.push(LinePlane {
                        patch: k,
                        vertices: (from, to),
                        normal: normal.to_array(),
                        point: point.to_array(),
                        deviation: dev / scale,
                    });
                }
                planes.sort_by_key(|p| p.vertices.0);
                out.push(LinePlanes { row, index, planes });
            }
        }
        out
    }
}

/// Least-squares plane of `points`: (centroid, unit normal, largest distance).
pub(super) fn fit_plane(points: &[DVec3]) -> (DVec3, DVec3, f64) {
    let origin = points[0];
    let centroid = points.iter().map(|p| *p - origin).sum::<DVec3>() / points.len() as f64 + origin;
    let mut cov = Matrix3::<f64>::zeros();
    for p in points {
        let d = *p - centroid;
        let d = nalgebra::Vector3::new(d.x, d.y, d.z);
        cov += d * d.transpose();
    }
    let eig = cov.symmetric_eigen();
    let k = eig.eigenvalues.imin();
    let v = eig.eigenvectors.column(k);
    let mut normal = DVec3::new(v[0], v[1], v[2]).normalize_or_zero();
    if normal == DVec3::ZERO {
        normal = DVec3::Z;
    }
    let dev = points
        .iter()
        .map(|p| (*p - centroid).dot(normal).abs())
        .fold(0.0, f64::max);
    (centroid, normal, dev)
}
