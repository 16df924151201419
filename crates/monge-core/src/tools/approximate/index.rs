//! The target of an approximation (§4.7, monge's extension): its points in a spatial
//! index, with a normal at each and an outward direction at its boundary, and the
//! distances between it and a mesh both ways.

use glam::DVec3;
use rstar::RTree;

use crate::grid::{bbox_diagonal, QuadGrid, MAX_SIZE, MIN_SIZE};

use super::distance::{Deviation, Indexed, MeshFaces};
use super::error::{ApproxError, MIN_POINTS};
use super::quadric::principal_axes;

/// The target: its points, a spatial index, a normal for each point and an outward
/// direction for each point of its boundary.
#[derive(Clone, Debug)]
pub struct TargetCloud {
    pub(super) points: Vec<DVec3>,
    pub(super) tree: RTree<Indexed>,
    /// Unit normal of the plane fitted to each point's neighbours.
    pub(super) normals: Vec<DVec3>,
    /// Unit outward direction in the tangent plane at a boundary point, zero inside.
    outward: Vec<DVec3>,
    /// Mean distance from a point to its nearest neighbour.
    pub(super) spacing: f64,
    pub(super) size: f64,
}

/// Neighbours used for each target point's normal.
const NEIGHBOURS: usize = 8;

/// Neighbours used for each target point's boundary test: enough to bridge the holes
/// of a random sampling.
const BOUNDARY_NEIGHBOURS: usize = 24;

/// A point is on the target's boundary when its neighbours, seen from it in its
/// tangent plane, leave a gap wider than this angle (radians, 150°): half a turn on a
/// straight boundary, three quarters at a corner, while inside even a random sampling
/// leaves gaps well under it.
const BOUNDARY_GAP: f64 = 2.6;

impl TargetCloud {
    /// Index the points of a target (a mesh's vertices or a point cloud).
    pub fn new(points: &[DVec3]) -> Result<Self, ApproxError> {
        if points.len() < MIN_POINTS {
            return Err(ApproxError::TooFewPoints {
                found: points.len(),
                needed: MIN_POINTS,
            });
        }
        if let Some(index) = points.iter().position(|p| !p.is_finite()) {
            return Err(ApproxError::NotFinite {
                index,
                point: points[index].to_array(),
            });
        }
        let size = bbox_diagonal(points);
        if !(MIN_SIZE..=MAX_SIZE).contains(&size) {
            return Err(ApproxError::ScaleOutOfRange {
                size,
                min: MIN_SIZE,
                max: MAX_SIZE,
            });
        }
        let tree = RTree::bulk_load(
            points
                .iter()
                .enumerate()
                .map(|(i, p)| Indexed::new(p.to_array(), i))
                .collect(),
        );
        let mut normals = Vec::with_capacity(points.len());
        let mut outward = Vec::with_capacity(points.len());
        let mut nearest = 0.0;
        for p in points {
            let near: Vec<DVec3> = tree
                .nearest_neighbor_iter(p.to_array())
                .take(BOUNDARY_NEIGHBOURS + 1)
                .map(|n| DVec3::from_array(*n.geom()))
                .collect();
            let normal = principal_axes(&near[..=NEIGHBOURS]).2;
            nearest += near.get(1).map_or(0.0, |q| q.distance(*p));
            // The widest gap between the neighbours' directions in the tangent plane.
            let x = normal.any_orthonormal_vector();
            let y = normal.cross(x);
            let mut angles: Vec<f64> = near[1..]
                .iter()
                .map(|q| (*q - *p).dot(y).atan2((*q - *p).dot(x)))
                .collect();
            angles.sort_by(f64::total_cmp);
            let (gap, middle) = angles
                .iter()
                .zip(angles.iter().cycle().skip(1))
                .map(|(a, b)| {
                    let gap = (b - a).rem_euclid(std::f64::consts::TAU);
                    (gap, a + 0.5 * gap)
                })
                .fold((0.0, 0.0), |best, g| if g.0 > best.0 { g } else { best });
            normals.push(normal);
            outward.push(if gap > BOUNDARY_GAP {
                middle.cos() * x + middle.sin() * y
            } else {
                DVec3::ZERO
            });
        }
        Ok(TargetCloud {
            points: points.to_vec(),
            tree,
            normals,
            outward,
            spacing: nearest / points.len() as f64,
            size: bbox_diagonal(points),
        })
    }

    /// The target's size: the diagonal of its bounding box.
    pub fn size(&self) -> f64 {
        self.size
    }

    /// Distance from `v` to the target: to the tangent plane of the nearest target
    /// point, combined, at the target's boundary, with how far `v` lies beyond it
    /// (more than the sampling's mean spacing).
    pub(super) fn distance_from(&self, v: DVec3) -> f64 {
        let nearest = self
            .tree
            .nearest_neighbor(v.to_array())
            .expect("a target has points");
        let i = nearest.data;
        let d = v - self.points[i];
        let normal = d.dot(self.normals[i]);
        let along = d - normal * self.normals[i];
        // Beyond the boundary by more than the sampling resolves (a boundary point's
        // outward direction is only known to its neighbours' spacing).
        let excess = (along.dot(self.outward[i]) - self.spacing).max(0.0);
        normal.hypot(excess)
    }

    /// Distances both ways between `grid` and the target, relative to the target's size;
    /// target points are taken every `stride`-th.
    pub(super) fn deviation_strided(&self, grid: &QuadGrid, stride: usize) -> Deviation {
        self.deviation_given(grid, &self.distances(grid), stride)
    }

    /// [`TargetCloud::deviation_strided`] with the vertices' [`TargetCloud::distances`] given.
    fn deviation_given(&self, grid: &QuadGrid, distances: &[f64], stride: usize) -> Deviation {
        let (m_max, m_rms) = max_rms(distances.iter().copied());
        let faces = MeshFaces::new(grid);
        let nearest: Vec<(f64, f64)> = self
            .points
            .iter()
            .step_by(stride)
            .map(|p| faces.distance_from(*p))
            .collect();
        let (t_max, t_rms) = max_rms(nearest.iter().map(|d| d.0));
        let (_, b_rms) = max_rms(nearest.iter().map(|d| d.1));
        Deviation {
            mesh_to_target_max: m_max / self.size,
            mesh_to_target_rms: m_rms / self.size,
            target_to_mesh_max: t_max / self.size,
            target_to_mesh_rms: t_rms / self.size,
            beyond_mesh_rms: b_rms / self.size,
            size: self.size,
        }
    }

    /// The distance from each vertex of `grid` to the target (model units), as
    /// [`Deviation::mesh_to_target_max`] measures it: to the tangent plane of the
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
        grid.vertices
            .iter()
            .map(|v| self.distance_from(*v))
            .collect()
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
        let deviation = self.deviation_given(grid, &distances, 1);
        (distances, deviation)
    }
}

/// Largest and root-mean-square value (NaN wins the maximum).
fn max_rms(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (mut max, mut sum, mut n) = (0.0f64, 0.0, 0usize);
    for d in values {
        max = if d.is_nan() { d } else { max.max(d) };
        sum += d * d;
        n += 1;
    }
    (max, (sum / n.max(1) as f64).sqrt())
}
