//! Distance from a point to a triangle, and to the nearest face of a mesh (§4.7,
//! monge's extension: the approximation's objective).

use glam::DVec3;
use rstar::primitives::GeomWithData;
use rstar::RTree;

use crate::grid::QuadGrid;

/// A point (of a target or a mesh) in a spatial index, with its index.
pub(super) type Indexed = GeomWithData<[f64; 3], usize>;

/// A mesh's vertices in a spatial index, to find the nearest face of a point.
pub(super) struct MeshFaces<'a> {
    grid: &'a QuadGrid,
    tree: RTree<Indexed>,
    /// Each face's bounding sphere (centre, radius): a point lies no nearer to the face
    /// than to the sphere.
    spheres: Vec<(DVec3, f64)>,
}

/// A face whose bounding sphere lies farther from a point than the nearest triangle
/// found so far by more than this share of its radius is not measured (a margin above
/// round-off, so that a face the sphere's bound only rounds past is measured).
const SPHERE_MARGIN: f64 = 1e-6;

/// Nearest vertices whose faces are searched for a point's nearest face.
const FACE_CANDIDATES: usize = 4;

impl<'a> MeshFaces<'a> {
    pub(super) fn new(grid: &'a QuadGrid) -> Self {
        let tree = RTree::bulk_load(
            grid.vertices
                .iter()
                .enumerate()
                .map(|(i, p)| Indexed::new(p.to_array(), i))
                .collect(),
        );
        let (rows, cols) = (grid.rows, grid.cols);
        let spheres = (0..rows.saturating_sub(1) * cols.saturating_sub(1))
            .map(|k| {
                let corners = grid.face(k / (cols - 1), k % (cols - 1));
                let centre = corners.iter().copied().sum::<DVec3>() / 4.0;
                let radius = corners
                    .iter()
                    .map(|c| c.distance(centre))
                    .fold(0.0, f64::max);
                (centre, radius)
            })
            .collect();
        MeshFaces {
            grid,
            tree,
            spheres,
        }
    }

    /// The faces `(i, j)` around vertex `k` of the grid (none on a grid of one row or
    /// column).
    fn faces_around(&self, k: usize) -> impl Iterator<Item = (usize, usize)> {
        let (rows, cols) = (self.grid.rows, self.grid.cols);
        let (i, j) = (k / cols, k % cols);
        let fi = i.saturating_sub(1)..(i + 1).min(rows.saturating_sub(1));
        let fj = j.saturating_sub(1)..(j + 1).min(cols.saturating_sub(1));
        fi.flat_map(move |a| fj.clone().map(move |b| (a, b)))
    }

    /// The [`FACE_CANDIDATES`] vertices nearest to `p`, nearest first, into `out`
    /// (fewer if the mesh has fewer); how many. The nearest vertex and the other corners
    /// of a face around it are as many vertices, so the nearest ones lie no farther than
    /// the farthest of those: they are sought within that radius (of the faces around the
    /// nearest vertex, the one that makes it least), without the nearest-first iterator's
    /// heap.
    fn nearest_vertices(&self, p: DVec3, out: &mut [usize; FACE_CANDIDATES]) -> usize {
        let q = p.to_array();
        let Some(first) = self.tree.nearest_neighbor(q) else {
            return 0;
        };
        // (A grid of one row has no face: every vertex is then within the radius.)
        let squared_radius = self
            .faces_around(first.data)
            .map(|(fi, fj)| {
                self.grid
                    .face(fi, fj)
                    .iter()
                    .map(|c| c.distance_squared(p))
                    .fold(0.0, f64::max)
            })
            .fold(f64::INFINITY, f64::min);
        // The nearest ones within the radius, nearest first (ties in the order met).
        let mut best = [(f64::INFINITY, usize::MAX); FACE_CANDIDATES];
        for n in self.tree.locate_within_distance(q, squared_radius) {
            let d = DVec3::from_array(*n.geom()).distance_squared(p);
            if d < best[FACE_CANDIDATES - 1].0 {
                let mut k = FACE_CANDIDATES - 1;
                while k > 0 && d < best[k - 1].0 {
                    best[k] = best[k - 1];
                    k -= 1;
                }
                best[k] = (d, n.data);
            }
        }
        let count = best.iter().take_while(|b| b.1 != usize::MAX).count();
        for (o, b) in out.iter_mut().zip(&best[..count]) {
            *o = b.1;
        }
        count
    }

    /// Distance from `p` to the nearest face around its nearest vertices (each planar
    /// face split into two triangles), and the part of it along that face.
    pub(super) fn distance_from(&self, p: DVec3) -> (f64, f64) {
        self.nearest(p).1
    }

    /// The triangle nearest to `p` among the faces around its nearest vertices, and
    /// [`triangle_offsets`] to it.
    pub(super) fn nearest(&self, p: DVec3) -> (Triangle, (f64, f64)) {
        let cols = self.grid.cols;
        let mut best = ((0, 0, 0), (f64::INFINITY, f64::INFINITY));
        // The faces around the nearest vertices, each once (neighbouring vertices share
        // them), in the order they are met.
        let mut seen = [(usize::MAX, usize::MAX); 4 * FACE_CANDIDATES];
        let mut count = 0;
        let mut nearest = [0; FACE_CANDIDATES];
        let found = self.nearest_vertices(p, &mut nearest);
        for &n in &nearest[..found] {
            for (fi, fj) in self.faces_around(n) {
                if seen[..count].contains(&(fi, fj)) {
                    continue;
                }
                seen[count] = (fi, fj);
                count += 1;
                let (centre, radius) = self.spheres[fi * (cols - 1) + fj];
                if p.distance(centre) - radius > best.1 .0 + SPHERE_MARGIN * radius {
                    continue;
                }
                for half in 0..2 {
                    let offsets = triangle_offsets(self.grid, (fi, fj, half), p);
                    if offsets.0 < best.1 .0 {
                        best = ((fi, fj, half), offsets);
                    }
                }
            }
        }
        best
    }
}

/// A triangle of a quad grid: face `(i, j)` and which half of it (`0`: corners 0, 1, 2;
/// `1`: corners 0, 2, 3).
pub(super) type Triangle = (usize, usize, u8);

/// Distance from `p` to the triangle `t` of `grid`, and the part of it along the
/// triangle's plane (zero when `p` lies over the triangle).
pub(super) fn triangle_offsets(grid: &QuadGrid, t: Triangle, p: DVec3) -> (f64, f64) {
    let [a, b, c, d] = grid.face(t.0, t.1);
    offsets(p, if t.2 == 0 { [a, b, c] } else { [a, c, d] })
}

/// Distance from `p` to the triangle `[x, y, z]`, and the part of it along the
/// triangle's plane.
fn offsets(p: DVec3, [x, y, z]: [DVec3; 3]) -> (f64, f64) {
    let offset = p - closest_on_triangle(p, x, y, z);
    let normal = (y - x).cross(z - x).normalize_or_zero();
    let along = offset - offset.dot(normal) * normal;
    (offset.length(), along.length())
}

/// Any triangles (a trimmed mesh's faces, [`TrimmedMesh::triangles`](super::TrimmedMesh::triangles)), for the exact
/// nearest of them to a point: an R-tree of their bounding boxes. [`MeshFaces`] seeks
/// among the faces around a grid's nearest vertices, which for a trimmed mesh may be
/// faces cut away.
pub(super) struct Triangles(RTree<Corners>);

/// A triangle's corners, in an R-tree.
struct Corners([DVec3; 3]);

impl rstar::RTreeObject for Corners {
    type Envelope = rstar::AABB<[f64; 3]>;

    fn envelope(&self) -> Self::Envelope {
        let [a, b, c] = self.0;
        rstar::AABB::from_corners(a.min(b).min(c).to_array(), a.max(b).max(c).to_array())
    }
}

impl rstar::PointDistance for Corners {
    fn distance_2(&self, p: &[f64; 3]) -> f64 {
        let (p, [a, b, c]) = (DVec3::from_array(*p), self.0);
        p.distance_squared(closest_on_triangle(p, a, b, c))
    }
}

impl Triangles {
    /// The index of `triangles`.
    pub(super) fn new(triangles: Vec<[DVec3; 3]>) -> Self {
        Triangles(RTree::bulk_load(
            triangles.into_iter().map(Corners).collect(),
        ))
    }

    /// Distance from `p` to the nearest triangle, and the part of it along that
    /// triangle's plane (as [`MeshFaces::distance_from`]); infinite without triangles.
    pub(super) fn distance_from(&self, p: DVec3) -> (f64, f64) {
        self.0
            .nearest_neighbor(p.to_array())
            .map_or((f64::INFINITY, f64::INFINITY), |t| offsets(p, t.0))
    }
}

/// Distance from `p` to the triangle `abc` (closest point by regions, Ericson,
/// *Real-Time Collision Detection*, §5.1.5).
pub fn point_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> f64 {
    p.distance(closest_on_triangle(p, a, b, c))
}

/// The point of the triangle `abc` nearest to `p` (Ericson, §5.1.5).
fn closest_on_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> DVec3 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = 1.0 / (va + vb + vc);
    a + ab * (vb * denom) + ac * (vc * denom)
}

/// Distances between a mesh and a target both ways, relative to the target's size.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Deviation {
    /// Largest distance from a mesh vertex to the target.
    pub mesh_to_target_max: f64,
    /// Root-mean-square distance from the mesh vertices to the target.
    pub mesh_to_target_rms: f64,
    /// Largest distance from a target point to the mesh (one-sided Hausdorff).
    pub target_to_mesh_max: f64,
    /// Root-mean-square distance from the target points to the mesh.
    pub target_to_mesh_rms: f64,
    /// Root-mean-square distance by which the target points lie beyond the mesh's
    /// boundary: the part of their distance to the nearest face along that face, what
    /// the mesh fails to cover (zero inside, whatever the faces' sag).
    pub beyond_mesh_rms: f64,
    /// The target's size (bounding-box diagonal) the distances are divided by.
    pub size: f64,
}

impl Deviation {
    /// The larger of the two largest distances (the Hausdorff distance, relative).
    pub fn max(&self) -> f64 {
        self.mesh_to_target_max.max(self.target_to_mesh_max)
    }

    /// Whether a mesh of this deviation is closer to the target than one of `other`:
    /// the one criterion of every choice between fits (patches, layouts, the initial
    /// guess), the largest distance both ways ([`Deviation::max`]).
    ///
    /// ```
    /// use monge_core::approximate::Deviation;
    /// let d = |max: f64, rms: f64| Deviation {
    ///     mesh_to_target_max: max, mesh_to_target_rms: rms, target_to_mesh_max: 0.0,
    ///     target_to_mesh_rms: rms, beyond_mesh_rms: 0.0, size: 1.0,
    /// };
    /// // A smaller largest distance wins, whatever the RMS.
    /// assert!(d(0.01, 0.009).closer_than(&d(0.02, 0.001)));
    /// assert!(!d(0.02, 0.001).closer_than(&d(0.02, 0.009)));
    /// ```
    pub fn closer_than(&self, other: &Deviation) -> bool {
        self.max() < other.max()
    }

    /// The objective: the mean of the mean squared distances from the mesh's vertices
    /// to the target and of the target's points beyond the mesh (relative). Not the
    /// target's distances to the faces: flat faces sag below a curved target by
    /// `κh²/8`, and fitting that sag would move the vertices off the target.
    pub(super) fn objective(&self) -> f64 {
        0.5 * (self.mesh_to_target_rms.powi(2) + self.beyond_mesh_rms.powi(2))
    }
}

/// `f` of every `stride`-th point of `points`, in order, blocks of them side by side
/// ([`crate::tasks`]): a mesh's nearest faces to a target's points.
pub(super) fn strided<T: Send>(
    points: &[DVec3],
    stride: usize,
    f: impl Fn(DVec3) -> T + Sync + Send,
) -> Vec<T> {
    map_blocks(points.len().div_ceil(stride.max(1)), |k| {
        f(points[k * stride])
    })
}

/// `f` of `0..count`, in order, blocks of [`STRIDED_BLOCK`] side by side
/// ([`crate::tasks`]).
pub(super) fn map_blocks<T: Send>(count: usize, f: impl Fn(usize) -> T + Sync + Send) -> Vec<T> {
    crate::tasks::ranges(count, STRIDED_BLOCK, |r| r.map(&f).collect::<Vec<T>>())
        .into_iter()
        .flatten()
        .collect()
}

/// Points per task of [`map_blocks`]: a few tenths of a millisecond of nearest faces.
const STRIDED_BLOCK: usize = 256;

/// Largest and root-mean-square value (NaN wins the maximum).
pub(super) fn max_rms(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (mut max, mut sum, mut n) = (0.0f64, 0.0, 0usize);
    for d in values {
        max = if d.is_nan() { d } else { max.max(d) };
        sum += d * d;
        n += 1;
    }
    (max, (sum / n.max(1) as f64).sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_nearest_faces_are_those_of_the_nearest_vertices_by_brute_force() {
        // A curved, unevenly spaced grid (part of a cylinder, its rows bunched towards one
        // end), and points on it, near it, and far from it.
        let (rows, cols) = (13, 9);
        let vertices: Vec<DVec3> = (0..rows * cols)
            .map(|k| {
                let (i, j) = ((k / cols) as f64, (k % cols) as f64);
                let a = 0.12 * j;
                DVec3::new(0.05 * i * i, 3.0 * a.cos(), 3.0 * a.sin())
            })
            .collect();
        let grid = QuadGrid::new(rows, cols, vertices.clone(), vec![DVec3::Z; rows * cols]);
        let faces = MeshFaces::new(&grid);
        let mut rng = fastrand::Rng::with_seed(7);
        for k in 0..600 {
            let far = [0.01, 0.3, 3.0, 30.0][k % 4];
            let p = vertices[rng.usize(..vertices.len())]
                + far * DVec3::new(rng.f64() - 0.5, rng.f64() - 0.5, rng.f64() - 0.5);
            // The four nearest vertices, by sorting them all.
            let mut order: Vec<usize> = (0..vertices.len()).collect();
            order.sort_by(|a, b| {
                vertices[*a]
                    .distance_squared(p)
                    .total_cmp(&vertices[*b].distance_squared(p))
            });
            let mut nearest = [0; FACE_CANDIDATES];
            assert_eq!(faces.nearest_vertices(p, &mut nearest), FACE_CANDIDATES);
            assert_eq!(nearest, order[..FACE_CANDIDATES], "point {k}");
            // The nearest of every triangle of the faces around them.
            let mut distance = f64::INFINITY;
            for n in &order[..FACE_CANDIDATES] {
                let (i, j) = (n / cols, n % cols);
                for fi in i.saturating_sub(1)..=i.min(rows - 2) {
                    for fj in j.saturating_sub(1)..=j.min(cols - 2) {
                        for half in 0..2 {
                            distance = distance.min(triangle_offsets(&grid, (fi, fj, half), p).0);
                        }
                    }
                }
            }
            assert_eq!(faces.distance_from(p).0, distance, "point {k}");
        }
    }
}
