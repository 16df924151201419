//! The distances between a target and a mesh both ways, a [`Deviation`] (§4.7, monge's
//! extension: how every fit is measured and compared).

use std::sync::atomic::{AtomicBool, Ordering};

use glam::DVec3;

use crate::grid::QuadGrid;

use super::distance::{map_blocks, max_rms, strided, Deviation, MeshFaces};
use super::index::TargetCloud;

/// The distances between a target and a mesh, both ways.
impl TargetCloud {
    /// Distances both ways between `grid` and the target, relative to the target's size;
    /// target points are taken every `stride`-th.
    pub(super) fn deviation_strided(&self, grid: &QuadGrid, stride: usize) -> Deviation {
        let faces = MeshFaces::new(grid);
        let vertices = &grid.vertices;
        self.deviation_below(
            (vertices.len(), |k| self.distance_from(vertices[k])),
            |p| faces.distance_from(p),
            stride,
            f64::INFINITY,
        )
        .expect("no bound")
    }

    /// [`TargetCloud::deviation_strided`] with the vertices' [`TargetCloud::distances`]
    /// given, and `to_mesh`, a target point's distance to the mesh and its part along the
    /// nearest face's plane.
    pub(super) fn deviation_given(
        &self,
        distances: &[f64],
        to_mesh: impl Fn(DVec3) -> (f64, f64) + Sync + Send,
        stride: usize,
    ) -> Deviation {
        self.deviation_below(
            (distances.len(), |k| distances[k]),
            to_mesh,
            stride,
            f64::INFINITY,
        )
        .expect("no bound")
    }

    /// [`TargetCloud::deviation_given`], the vertices' distances `distance(0)`,
    /// `distance(1)`, … of `vertices` computed only where the deviation may come closer
    /// than `than` (relative; infinite: always): `None` as soon as a largest distance,
    /// target → mesh or mesh → target, reaches it (then not
    /// [`closer_than`](Deviation::closer_than) a deviation of largest distance `than`),
    /// the rest unmeasured.
    pub(super) fn deviation_below(
        &self,
        (vertices, distance): (usize, impl Fn(usize) -> f64 + Sync + Send),
        to_mesh: impl Fn(DVec3) -> (f64, f64) + Sync + Send,
        stride: usize,
        than: f64,
    ) -> Option<Deviation> {
        // Set once a distance reaches `than`: the blocks side by side skip the rest.
        let reached = AtomicBool::new(false);
        let bounded = |d: f64| {
            if than.is_finite() && d / self.size >= than {
                reached.store(true, Ordering::Relaxed);
            }
            d
        };
        let nearest = strided(&self.points, stride, |p| {
            if reached.load(Ordering::Relaxed) {
                return (f64::NAN, f64::NAN);
            }
            let d = to_mesh(p);
            (bounded(d.0), d.1)
        });
        if reached.load(Ordering::Relaxed) {
            return None;
        }
        let (t_max, t_rms) = max_rms(nearest.iter().map(|d| d.0));
        let (_, b_rms) = max_rms(nearest.iter().map(|d| d.1));
        let distances = map_blocks(vertices, |k| {
            if reached.load(Ordering::Relaxed) {
                return f64::NAN;
            }
            bounded(distance(k))
        });
        if reached.load(Ordering::Relaxed) {
            return None;
        }
        let (m_max, m_rms) = max_rms(distances.into_iter());
        Some(Deviation {
            mesh_to_target_max: m_max / self.size,
            mesh_to_target_rms: m_rms / self.size,
            target_to_mesh_max: t_max / self.size,
            target_to_mesh_rms: t_rms / self.size,
            beyond_mesh_rms: b_rms / self.size,
            size: self.size,
        })
    }

    /// The distance from each vertex of `grid` to the target (model units), as
    /// [`Deviation::mesh_to_target_max`] measures it: to the quadric fitted around the
    /// nearest target point, and beyond the target's boundary.
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::approximate::TargetCloud;
    /// use monge_core::QuadGrid;
    /// // A 10 × 10 sampling of the plane z = 0, and a square 0.5 above it.
    /// let plane: Vec<DVec3> =
    ///     (0..100).map(|k| DVec3::new((k % 10) as f64, (k / 10) as f64, 0.0)).collect();
    /// let target = TargetCloud::new(&plane).unwrap();
    /// let square = [DVec3::new(3.0, 3.0, 0.5), DVec3::new(3.0, 4.0, 0.5),
    ///               DVec3::new(4.0, 3.0, 0.5), DVec3::new(4.0, 4.0, 0.5)];
    /// let grid = QuadGrid::new(2, 2, square.to_vec(), vec![DVec3::Z; 4]);
    /// for d in target.distances(&grid) {
    ///     assert!((d - 0.5).abs() < 1e-12);
    /// }
    /// ```
    pub fn distances(&self, grid: &QuadGrid) -> Vec<f64> {
        map_blocks(grid.vertices.len(), |k| {
            self.distance_from(grid.vertices[k])
        })
    }

    /// Distances both ways between `grid` and the target, relative to the target's size.
    pub fn deviation(&self, grid: &QuadGrid) -> Deviation {
        self.deviation_strided(grid, 1)
    }

    /// [`TargetCloud::distances`] and [`TargetCloud::deviation`] together, the
    /// vertices' distances computed once (for a picture coloured by them and its caption).
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::approximate::TargetCloud;
    /// use monge_core::QuadGrid;
    /// let plane: Vec<DVec3> =
    ///     (0..100).map(|k| DVec3::new((k % 10) as f64, (k / 10) as f64, 0.0)).collect();
    /// let target = TargetCloud::new(&plane).unwrap();
    /// let square = [DVec3::new(3.0, 3.0, 0.5), DVec3::new(3.0, 4.0, 0.2),
    ///               DVec3::new(4.0, 3.0, 0.5), DVec3::new(4.0, 4.0, 0.1)];
    /// let grid = QuadGrid::new(2, 2, square.to_vec(), vec![DVec3::Z; 4]);
    /// let (distances, deviation) = target.distances_and_deviation(&grid);
    /// assert_eq!(distances, target.distances(&grid));
    /// assert_eq!(deviation, target.deviation(&grid));
    /// ```
    pub fn distances_and_deviation(&self, grid: &QuadGrid) -> (Vec<f64>, Deviation) {
        let distances = self.distances(grid);
        let faces = MeshFaces::new(grid);
        let deviation = self.deviation_given(&distances, |p| faces.distance_from(p), 1);
        (distances, deviation)
    }
}

#[cfg(test)]
mod tests {
    use super::super::edge::tests::unit_square;
    use super::*;

    #[test]
    fn a_deviation_bounded_by_a_closer_one_is_not_measured_past_it_either_way() {
        // A 11 × 11 mesh's vertices as the target; every target point at 0.1 of the size
        // from the mesh, and two vertices, at 0.2 and 0.4 of it from the target.
        let target = TargetCloud::new(&unit_square().vertices).unwrap();
        let size = target.size;
        let vertices = [0.2 * size, 0.4 * size];
        let measure = |than: f64| {
            target.deviation_below((2, |k| vertices[k]), |_| (0.1 * size, 0.0), 1, than)
        };
        let d = measure(f64::INFINITY).unwrap();
        assert!((d.target_to_mesh_max - 0.1).abs() < 1e-12);
        assert!((d.mesh_to_target_max - 0.4).abs() < 1e-12);
        assert_eq!(measure(0.5), Some(d));
        // Reached target → mesh, or only mesh → target: not closer, not measured.
        assert_eq!(measure(0.1), None);
        assert_eq!(measure(0.3), None);
        assert_eq!(measure(0.4), None);
    }
}
