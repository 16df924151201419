//! The target → mesh side of the least squares' residuals (§4.7, monge's extension):
//! the target's points a mesh leaves uncovered, on a scan's fit and on a fit to be
//! trimmed to the target's outline.

use crate::grid::QuadGrid;

use super::distance::{triangle_offsets, Triangle};
use super::index::{Matches, TargetCloud};

/// How far beyond the target's edge, in mean spacings of its points, a vertex of a mesh
/// to be trimmed still counts for its distance to the target
/// ([`TargetCloud::cover_residuals`]): its weight falls from whole at the edge to nil
/// there. The trimming cuts the overhang away, and only the faces across the edge are
/// kept in part (their part within is measured by the target points on them). Counted
/// whole, the overhang's distance to the target's quadrics carried on held the mesh
/// short of the target's corners wherever its curvature lines cross the edge at a
/// slant: held-out meshes of 41 × 41 vertices fitted by one trimmed patch, brute force
/// both ways, a paraboloid 2.2e-3 → 3.9e-4 of the size, a bicubic Bézier roof 3.2e-2 →
/// 1.3e-2; a quarter of a dome with flat edges 1.4e-2 → 1.5e-3 to 2.7e-3 of the whole
/// dome's size (one, four and eight spacings gave the same within a factor of 1.5).
const TRIMMED_SPACINGS: f64 = 2.0;

impl TargetCloud {
    /// The residuals of the approximation's least squares where the result is to be
    /// trimmed to the target's outline ([`trim`](super::trim())), against `matches`: the
    /// mesh is to cover the target, not to end on its edges. For every vertex its signed
    /// distance to the surface near its matched target point, counting less the farther
    /// the vertex lies beyond the target's edge and nothing past [`TRIMMED_SPACINGS`]
    /// spacings (the trimming cuts it away), and for every `stride`-th target point its
    /// distance to its matched triangle of the mesh (beyond the mesh's edge, the whole
    /// way to it; not the other points near the target's edge that the matches hold,
    /// which would weigh the edge more than the rest), each part weighted by one over
    /// the square root of its number. The
    /// faces' sag below a curved target (`κh²/8` for faces of width `h`) is in the
    /// second part: at 40 × 40 faces it is of the order of 1e-4 of the size.
    pub(super) fn cover_residuals(&self, grid: &QuadGrid, matches: &Matches) -> Vec<f64> {
        let w_vertices = 1.0 / (self.size * (grid.vertices.len() as f64).sqrt());
        let vertices = grid.vertices.iter().zip(&matches.vertices).map(|(v, i)| {
            let (across, beyond) = self.offsets(*v, *i, 0.0);
            w_vertices * across * (1.0 - beyond / (TRIMMED_SPACINGS * self.spacing)).max(0.0)
        });
        vertices
            .chain(self.to_mesh_beyond(grid, matches, 0.0))
            .collect()
    }

    /// For every `stride`-th target point of `matches`, its distance to its matched
    /// triangle of `grid` less `allowance` (model units; nil within it), relative to the
    /// target's size and weighted by one over the square root of their number.
    pub(super) fn to_mesh_beyond(
        &self,
        grid: &QuadGrid,
        matches: &Matches,
        allowance: f64,
    ) -> Vec<f64> {
        let strided: Vec<&(usize, Triangle)> = matches
            .points
            .iter()
            .filter(|(k, _)| k % matches.stride == 0)
            .collect();
        let weight = 1.0 / (self.size * (strided.len() as f64).sqrt());
        strided
            .into_iter()
            .map(|(k, t)| {
                weight * (triangle_offsets(grid, *t, self.points[*k]).0 - allowance).max(0.0)
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::super::edge::tests::{square, unit_square};
    use super::super::index::OVERHANG_SPACINGS;
    use super::*;

    #[test]
    fn a_scans_points_the_mesh_leaves_uncovered_count_beyond_the_allowance() {
        // 2 000 random points of the unit square; a mesh of all of it, and of its half
        // x ≤ 0.5: each point's residual is its distance beyond x = 0.5 (closed form)
        // less the allowance, relative to the size, over the root of their number.
        let scan = square(&mut fastrand::Rng::with_seed(3), 2000);
        let target = TargetCloud::new(&scan).unwrap();
        let allowance = OVERHANG_SPACINGS * target.spacing;
        let whole = unit_square();
        let m = target.matches(&whole, 1);
        assert!(target
            .to_mesh_beyond(&whole, &m, allowance)
            .iter()
            .all(|r| *r == 0.0));
        let mut half = unit_square();
        half.vertices.iter_mut().for_each(|v| v.x *= 0.5);
        let m = target.matches(&half, 1);
        let residuals = target.to_mesh_beyond(&half, &m, allowance);
        let weight = 1.0 / (target.size * (m.points.len() as f64).sqrt());
        let mut counted = 0;
        for ((k, _), r) in m.points.iter().zip(&residuals) {
            let expected = weight * ((scan[*k].x - 0.5).max(0.0) - allowance).max(0.0);
            assert!((r - expected).abs() < 1e-12, "{r:e} {expected:e}");
            counted += usize::from(*r > 0.0);
        }
        // About the points beyond 0.5 + the allowance (3 spacings, about 0.035).
        assert!(counted > 800 && counted < 1000, "{counted}");
        // And the least squares' residuals hold them.
        let all = target.residuals(&half, &m);
        assert!(all.ends_with(&residuals));
    }
}
