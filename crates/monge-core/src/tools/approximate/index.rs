//! The target of an approximation (§4.7, monge's extension): its points in a spatial
//! index, with a normal at each and an outward direction at its boundary, and the
//! distances between it and a mesh both ways.

use glam::DVec3;
use rstar::RTree;

use crate::grid::{bbox_diagonal, QuadGrid, MAX_SIZE, MIN_SIZE};

use super::distance::{Deviation, Indexed, MeshFaces, Triangle};
use super::error::{ApproxError, MIN_POINTS};
use super::quadric::{misfits, principal_axes, Quadric};

/// The target: its points, a spatial index, a normal for each point and an outward
/// direction for each point of its boundary.
#[derive(Clone, Debug)]
pub struct TargetCloud {
    pub(super) points: Vec<DVec3>,
    pub(super) tree: RTree<Indexed>,
    /// Unit normal of the plane fitted to each point's neighbours.
    pub(super) normals: Vec<DVec3>,
    /// The quadric fitted to each point's neighbours in the frame of its normal: the
    /// surface near it to second order (a tangent plane alone is off by `κd²/2` at a
    /// distance `d` from the point, as much as a random sampling's spacing makes it).
    patches: Vec<Quadric>,
    /// Unit outward direction in the tangent plane at a boundary point, zero inside.
    outward: Vec<DVec3>,
    /// How far each boundary point lies behind the outermost of its neighbours along its
    /// outward direction (zero inside, and along a mesh's edges, whose vertices are on
    /// them): where the target's edge is, seen from it, as far as its sampling says.
    behind: Vec<f64>,
    /// How far the target's true edge may lie beyond its outermost points: up to about
    /// the mean spacing for a random sampling, nil for a mesh's vertices
    /// ([`edge_gap`]).
    edge_gap: f64,
    /// Mean distance from a point to its nearest neighbour.
    pub(super) spacing: f64,
    /// How much of each point's height above its own quadric is the surface's rather than
    /// noise ([`through_point_share`]): the quadric is moved by that much of it.
    through: f64,
    /// The normal of the plane fitted to all the points: the side to which
    /// [`TargetCloud::residuals`] turns the normals, so that a signed distance does not
    /// flip sign from one target point to the next.
    up: DVec3,
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
        let mut patches = Vec::with_capacity(points.len());
        let mut outward = Vec::with_capacity(points.len());
        let mut behind = Vec::with_capacity(points.len());
        let mut nearest = 0.0;
        let (mut sums, mut dof) = ((0.0, 0.0), (0.0, 0.0));
        let share_stride = points.len().div_ceil(SHARE_POINTS);
        for (k, p) in points.iter().enumerate() {
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
            patches.push(Quadric::fit(&near, *p, normal));
            if k % share_stride == 0 {
                let (quadratic, cubic) = misfits(&near, *p, normal);
                sums = (sums.0 + quadratic, sums.1 + cubic);
                let n = near.len() as f64;
                dof = (dof.0 + (n - 6.0).max(0.0), dof.1 + (n - 10.0).max(0.0));
            }
            let out = if gap > BOUNDARY_GAP {
                middle.cos() * x + middle.sin() * y
            } else {
                DVec3::ZERO
            };
            outward.push(out);
            behind.push(
                near[1..]
                    .iter()
                    .map(|q| (*q - *p).dot(out))
                    .fold(0.0, f64::max),
            );
        }
        let through = through_point_share(sums, dof, size);
        let spacing = nearest / points.len() as f64;
        let edge_gap = edge_gap(&behind, &outward, spacing);
        Ok(TargetCloud {
            through,
            points: points.to_vec(),
            tree,
            normals,
            patches,
            outward,
            behind,
            edge_gap,
            spacing,
            up: principal_axes(points).2,
            size: bbox_diagonal(points),
        })
    }

    /// The `count` target points nearest to `p`, nearest first.
    pub(super) fn nearest(&self, p: DVec3, count: usize) -> Vec<DVec3> {
        self.tree
            .nearest_neighbor_iter(p.to_array())
            .take(count)
            .map(|n| DVec3::from_array(*n.geom()))
            .collect()
    }

    /// The target's size: the diagonal of its bounding box.
    pub fn size(&self) -> f64 {
        self.size
    }

    /// Distance from `v` to the target: to the quadric fitted around the nearest target
    /// point, combined, at the target's boundary, with how far `v` lies beyond it: beyond
    /// the outermost of that point's neighbours (a mesh's edge itself), or for a random
    /// sampling beyond where its true edge may be ([`edge_gap`]).
    pub(super) fn distance_from(&self, v: DVec3) -> f64 {
        let i = self
            .tree
            .nearest_neighbor(v.to_array())
            .expect("a target has points")
            .data;
        let (across, beyond) = self.offsets(v, i, self.behind[i].max(self.edge_gap));
        across.hypot(beyond)
    }

    /// The signed distance from `v` to the surface near target point `i` (its quadric,
    /// moved towards the point by the share of the point's height above it that is not
    /// noise, [`through_point_share`]), along its normal turned to the side of
    /// [`TargetCloud::up`], so that the sign does
    /// not flip from one point to the next), and, where `i` is on the target's boundary, how far `v` lies
    /// beyond it by more than `allowance` (a boundary point's outward direction is only
    /// known to its neighbours' spacing).
    fn offsets(&self, v: DVec3, i: usize, allowance: f64) -> (f64, f64) {
        let d = v - self.points[i];
        let along = d - d.dot(self.normals[i]) * self.normals[i];
        // The quadric through the point itself, as far as the point's height above it is
        // not noise: a mesh's own vertices are at distance 0 from it, a scan's noise is
        // averaged over its neighbours.
        let patch = &self.patches[i];
        let across = (patch.height_above(v) - self.through * patch.height_above(self.points[i]))
            * self.normals[i].dot(self.up).signum();
        (across, (along.dot(self.outward[i]) - allowance).max(0.0))
    }

    /// Which target point is nearest to each vertex of `grid`, and which triangle of
    /// `grid` is nearest to every `stride`-th target point: what
    /// [`TargetCloud::residuals`] measures against. The spatial searches are all here,
    /// so the residuals of designs near `grid` (a Jacobian's columns) cost none.
    pub(super) fn matches(&self, grid: &QuadGrid, stride: usize) -> Matches {
        let faces = MeshFaces::new(grid);
        Matches {
            windows: sides(grid).map(|(side, _, _)| {
                let length: f64 = side
                    .windows(2)
                    .map(|k| grid.vertices[k[0]].distance(grid.vertices[k[1]]))
                    .sum();
                windows_along(length, self.spacing)
            }),
            vertices: grid
                .vertices
                .iter()
                .map(|v| {
                    self.tree
                        .nearest_neighbor(v.to_array())
                        .expect("a target has points")
                        .data
                })
                .collect(),
            points: self
                .points
                .iter()
                .step_by(stride)
                .map(|p| faces.nearest(*p).0)
                .collect(),
            stride,
        }
    }

    /// The residuals of the approximation's least squares at `grid` (relative to the
    /// target's size; their sum of squares is the objective), against `matches` (those
    /// of `grid` itself, or of a design near it):
    ///
    /// - the surface: for every vertex, its signed distance to the surface near its
    ///   matched target point and how far it overhangs the target's boundary by more
    ///   than [`OVERHANG_SPACINGS`] spacings ([`TargetCloud::offsets`]: a guard against
    ///   a side swinging out, not the edge's measure, which a random sampling's gaps
    ///   would bias inwards), weighted by one over the square root of their number;
    /// - the edges: each side of the mesh is cut into windows ([`windows_along`]), and in
    ///   each the target points matched to the faces within [`EDGE_DEPTH`] rows of
    ///   that side give their offsets beyond it (in the surface, across the side). The
    ///   target's true edge lies beyond its outermost points by a gap that a sampling
    ///   leaves (nil for a mesh's vertices, which are on the edge; for `n` random points
    ///   over an area `A`, about `A / (n·L)` along a window of length `L`), estimated as
    ///   for the largest of a uniform sample (the maximum plus the mean spacing of the
    ///   largest values): the mean spacing of each window's [`EDGE_ORDER`] outermost
    ///   offsets gives the area per point, from all the windows together. The residual
    ///   of a window is its outermost offset plus that gap: the side is fitted to the
    ///   envelope of the points as a whole, two-sided, not vertex by vertex; each weighted
    ///   by one over the square root of the windows' number.
    pub(super) fn residuals(&self, grid: &QuadGrid, matches: &Matches) -> Vec<f64> {
        let weight = |n: usize| 1.0 / (self.size * (n as f64).sqrt());
        let w_vertices = weight(grid.vertices.len());
        let windows = edge_windows(grid, &self.points, matches);
        let mut out = Vec::with_capacity(2 * grid.vertices.len() + windows.len());
        for (v, i) in grid.vertices.iter().zip(&matches.vertices) {
            let (across, beyond) = self.offsets(*v, *i, OVERHANG_SPACINGS * self.spacing);
            out.extend([w_vertices * across, w_vertices * beyond]);
        }
        let w_edges = EDGE_WEIGHT * weight(windows.len());
        out.extend(edge_residuals(&windows).into_iter().map(|r| w_edges * r));
        out
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

/// Mean depth of a random sampling's boundary points behind the outermost of their
/// neighbours, in mean spacings (about 0.3 for uniform random points of a square).
const RANDOM_BEHIND: f64 = 0.3;

/// How far the target's true edge may lie beyond its outermost points, from how far its
/// boundary points lie `behind` the outermost of their neighbours (`outward` zero:
/// inside): a mesh's vertices lie on its edges, and a regular sampling's boundary points
/// on one line, nil; a random sampling's outermost points lie inside the true edge by up
/// to about its mean `spacing`, which its boundary points' depths, about
/// [`RANDOM_BEHIND`] spacings on average, tell. Between, in proportion.
fn edge_gap(behind: &[f64], outward: &[DVec3], spacing: f64) -> f64 {
    let (sum, count) = behind
        .iter()
        .zip(outward)
        .filter(|(_, o)| **o != DVec3::ZERO)
        .fold((0.0, 0usize), |(s, n), (b, _)| (s + b, n + 1));
    if count == 0 {
        return 0.0;
    }
    spacing * (sum / count as f64 / (RANDOM_BEHIND * spacing)).min(1.0)
}

/// The share of a point's height above its own quadric that is the surface's (the
/// quadric's misfit of a smooth surface's higher-order terms) rather than noise, from the
/// sums of the squared residuals of the quadratic and cubic fits to the neighbours of
/// at most [`SHARE_POINTS`] points spread over the target ([`misfits`]) and their
/// degrees of freedom: noise leaves the same variance to both, so the share is what the
/// cubic removes of the quadric's; from one half up, the heights are mostly misfit and
/// the share is 1. 1 for a mesh's vertices (measured
/// 0.7 to 1 on meshes of 11 × 11 to 41 × 41: a target's own vertices are at distance 0
/// from it), under 0.1 for a scan noised by 1e-4 of its size, whose points' own heights
/// are noise that the quadric averages out.
fn through_point_share((quadratic, cubic): (f64, f64), (dof2, dof3): (f64, f64), size: f64) -> f64 {
    // Below rounding, a surface its quadrics follow exactly.
    if quadratic <= (ROUNDING * size).powi(2) * dof2 || dof3 <= 0.0 {
        return 1.0;
    }
    // Mostly the surface's misfit: through the point (a mesh against itself is at 0
    // everywhere, however coarse); mostly noise: averaged.
    let share = 1.0 - (cubic / dof3) / (quadratic / dof2);
    if share >= 0.5 {
        1.0
    } else {
        share.max(0.0)
    }
}

/// Target points, at most, whose neighbours' misfits estimate [`through_point_share`]
/// (every `⌈n / SHARE_POINTS⌉`-th of the `n`): the share is one number for the whole
/// target, which a few hundred points spread over it estimate as well as all of them
/// (measured within 0.03 on the held-out meshes and scans, where it is 0.88 to 1 and
/// 0 to 0.07), at two least-squares fits per point.
const SHARE_POINTS: usize = 256;

/// Relative residual of the neighbours' quadrics below which a target is exact.
const ROUNDING: f64 = 1e-12;

/// What the residuals of a mesh are measured against ([`TargetCloud::matches`]).
pub(super) struct Matches {
    /// The nearest target point of each vertex.
    vertices: Vec<usize>,
    /// The nearest triangle of every `stride`-th target point.
    points: Vec<Triangle>,
    /// How many windows each side of the mesh is cut into ([`windows_along`]): fixed
    /// with the matches, so that designs near the mesh have as many residuals.
    windows: [usize; 4],
    stride: usize,
}

/// Overhang of a vertex beyond the target's boundary point nearest to it, in mean
/// spacings of the target's points, that the least squares leave unpenalised: a random
/// sampling's outermost points lie inside the true edge by up to about two.
const OVERHANG_SPACINGS: f64 = 3.0;

/// Windows along each side of the mesh in which the edge residuals are measured, at
/// least.
const EDGE_WINDOWS: usize = 2;

/// Length of an edge window, at least, in mean spacings of the target's points (about
/// as many outermost points as lie along it): a window's outermost offset is the
/// largest of a random sampling's, off by the gap `A / (n·L)` that grows as the window
/// shortens, so a sparse scan keeps long windows; a dense one, whose gaps are small, is
/// held in more, which follow its edges' shape closer (θ of held-out scans of 2 000
/// points within 0.3° with three windows on their long sides, 0.9° with two; a scan of
/// 1 500 points of a square roof keeps two, with three its edges are missed by 2.2e-3
/// of its size).
const WINDOW_SPACINGS: f64 = 35.0;

/// How many windows a side of length `length` is cut into, the target's points being
/// `spacing` apart: one per [`WINDOW_SPACINGS`] spacings, at least [`EDGE_WINDOWS`].
fn windows_along(length: f64, spacing: f64) -> usize {
    let count = length / (WINDOW_SPACINGS * spacing);
    if count.is_finite() {
        (count as usize).max(EDGE_WINDOWS)
    } else {
        EDGE_WINDOWS
    }
}

/// Weight of the edges' residuals against the surface's: each window's outermost point is
/// random (for `n` points, by about `1/n` of the size), and the sides' positions, which
/// only the edges set, need no more; the surface's shape, which sets the sides' shapes,
/// is left to the surface.
const EDGE_WEIGHT: f64 = 0.3;

/// Rows of faces along a side whose matched target points count for its edge.
const EDGE_DEPTH: usize = 3;

/// Outermost offsets of each window whose mean spacing estimates the sampling's gap.
const EDGE_ORDER: usize = 4;

/// One window of a side of the mesh: its length, the offsets of its target points
/// beyond the side (negative inside), and how deep its strip of faces reaches.
struct EdgeWindow {
    length: f64,
    offsets: Vec<f64>,
    depth: f64,
}

/// For a triangle (face `i`, `j`) of a grid of `rows` × `cols` vertices, its place along
/// a side and its depth in rows from it.
type Place = fn(usize, usize, usize, usize) -> (usize, usize);

/// The four sides of `grid`: each its vertices from one end, their neighbours one row
/// inside, and its [`Place`].
fn sides(grid: &QuadGrid) -> [(Vec<usize>, Vec<usize>, Place); 4] {
    let (rows, cols) = (grid.rows, grid.cols);
    [
        (
            (0..cols).collect(),
            (0..cols).map(|j| cols + j).collect(),
            |i, j, _, _| (j, i),
        ),
        (
            (0..cols).map(|j| (rows - 1) * cols + j).collect(),
            (0..cols).map(|j| (rows - 2) * cols + j).collect(),
            |i, j, rows, _| (j, rows - 2 - i),
        ),
        (
            (0..rows).map(|i| i * cols).collect(),
            (0..rows).map(|i| i * cols + 1).collect(),
            |i, j, _, _| (i, j),
        ),
        (
            (0..rows).map(|i| i * cols + cols - 1).collect(),
            (0..rows).map(|i| i * cols + cols - 2).collect(),
            |i, j, _, cols| (i, cols - 2 - j),
        ),
    ]
}

/// The windows of each side of `grid` ([`Matches::windows`]), with the offsets of the
/// target points (every `stride`-th of `points`) matched to faces of their strip.
fn edge_windows(grid: &QuadGrid, points: &[DVec3], matches: &Matches) -> Vec<EdgeWindow> {
    let (rows, cols) = (grid.rows, grid.cols);
    let mut windows = Vec::new();
    for ((side, inner, place), count) in sides(grid).iter().zip(matches.windows) {
        let v = |k: usize| grid.vertices[side[k]];
        let m = side.len() - 1;
        // The outward direction at each vertex of the side: from its inner neighbour,
        // across the side.
        let outward: Vec<DVec3> = (0..=m)
            .map(|k| {
                let tangent = (v(k.min(m - 1) + 1) - v(k.saturating_sub(1))).normalize_or_zero();
                let out = v(k) - grid.vertices[inner[k]];
                (out - out.dot(tangent) * tangent).normalize_or_zero()
            })
            .collect();
        let row = (0..=m)
            .map(|k| v(k).distance(grid.vertices[inner[k]]))
            .sum::<f64>()
            / (m + 1) as f64;
        // No shorter than one edge of the mesh.
        let count = count.min(m);
        let window_of = |k: usize| (k * count / m).min(count - 1);
        let mut these: Vec<EdgeWindow> = (0..count)
            .map(|_| EdgeWindow {
                length: 0.0,
                offsets: Vec::new(),
                depth: EDGE_DEPTH as f64 * row,
            })
            .collect();
        for k in 0..m {
            these[window_of(k)].length += v(k).distance(v(k + 1));
        }
        for (t, p) in matches
            .points
            .iter()
            .zip(points.iter().step_by(matches.stride))
        {
            let (along, depth) = place(t.0, t.1, rows, cols);
            if depth >= EDGE_DEPTH {
                continue;
            }
            // The nearer of the face's two vertices on the side.
            let k = if p.distance(v(along)) <= p.distance(v(along + 1)) {
                along
            } else {
                along + 1
            };
            these[window_of(along)]
                .offsets
                .push((*p - v(k)).dot(outward[k]));
        }
        windows.extend(these);
    }
    windows
}

/// The residual of each window ([`TargetCloud::residuals`]): its outermost offset plus
/// the gap the sampling leaves beyond it, in model units. A window without points
/// (the mesh reaches far beyond the target there) has its outermost point at least its
/// strip's depth inside.
fn edge_residuals(windows: &[EdgeWindow]) -> Vec<f64> {
    let mut sorted: Vec<Vec<f64>> = windows
        .iter()
        .map(|w| {
            let mut o = w.offsets.clone();
            o.sort_by(|a, b| b.total_cmp(a));
            o
        })
        .collect();
    // Area per point: the mean spacing of the outermost offsets times the window's length.
    let (mut sum, mut count) = (0.0, 0usize);
    for (w, o) in windows.iter().zip(&sorted) {
        if o.len() >= EDGE_ORDER {
            sum += (o[0] - o[EDGE_ORDER - 1]) / (EDGE_ORDER - 1) as f64 * w.length;
            count += 1;
        }
    }
    let area_per_point = sum / count.max(1) as f64;
    windows
        .iter()
        .zip(sorted.iter_mut())
        .map(|(w, o)| {
            let outermost = o.first().copied().unwrap_or(-w.depth);
            outermost + area_per_point / w.length.max(f64::MIN_POSITIVE)
        })
        .collect()
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat mesh of 10 × 10 faces over the unit square (z = 0).
    fn unit_square() -> QuadGrid {
        let vertices: Vec<DVec3> = (0..121)
            .map(|k| DVec3::new((k / 11) as f64 / 10.0, (k % 11) as f64 / 10.0, 0.0))
            .collect();
        QuadGrid::new(11, 11, vertices, vec![DVec3::Z; 121])
    }

    /// Uniform random numbers in [0, 1) (splitmix64 from `state`).
    struct Uniform(u64);

    impl Uniform {
        fn next(&mut self) -> f64 {
            self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = self.0;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
        }

        /// `n` uniform random points of the unit square (z = 0).
        fn square(&mut self, n: usize) -> Vec<DVec3> {
            (0..n)
                .map(|_| DVec3::new(self.next(), self.next(), 0.0))
                .collect()
        }
    }

    /// The edge residuals of the unit square against `points` (model units).
    fn edges(points: &[DVec3]) -> Vec<f64> {
        let grid = unit_square();
        let target = TargetCloud::new(points).unwrap();
        let matches = target.matches(&grid, 1);
        edge_residuals(&edge_windows(&grid, &target.points, &matches))
    }

    /// Beyond a mesh's edge every overhang counts: measured against the true distance
    /// to the unit square's edge (its points are a 11 × 11 grid, 0.1 apart), from 0.02 to
    /// 0.3 beyond a side and beyond a corner; a scan's vertices at its outermost points
    /// read 0.
    #[test]
    fn a_vertex_beyond_the_edge_is_measured_from_the_edge() {
        let target = TargetCloud::new(&unit_square().vertices).unwrap();
        for beyond in [0.02, 0.05, 0.1, 0.3] {
            // Beside the middle of side x = 1, between two of its points.
            let side = DVec3::new(1.0 + beyond, 0.55, 0.0);
            assert!(
                (target.distance_from(side) - beyond).abs() < 1e-9,
                "{beyond}"
            );
            // Beyond the corner (1, 1), along the side y = 1.
            let corner = DVec3::new(1.0 + beyond, 1.0, 0.0);
            let d = target.distance_from(corner);
            assert!(d >= 0.7 * beyond && d <= beyond + 1e-9, "{beyond}: {d}");
        }
        // A random sampling's outermost points lie inside its true edge: a vertex on the
        // edge reads at most a quarter of a spacing (the sampling's own uncertainty).
        let scan = TargetCloud::new(&Uniform(3).square(2000)).unwrap();
        for k in 0..=60 {
            let on_edge = DVec3::new(1.0, 0.2 + 0.01 * k as f64, 0.0);
            let d = scan.distance_from(on_edge);
            assert!(d < 0.3 * scan.spacing, "{on_edge}: {d} ({})", scan.spacing);
        }
    }

    #[test]
    fn a_sides_residual_is_nil_on_a_meshs_boundary_and_unbiased_on_a_random_sampling() {
        // A 21 × 21 grid on the square: its boundary points lie on the sides, no gap.
        let grid: Vec<DVec3> = (0..441)
            .map(|k| DVec3::new((k / 21) as f64 / 20.0, (k % 21) as f64 / 20.0, 0.0))
            .collect();
        for r in edges(&grid) {
            assert!(r.abs() < 1e-12, "{r:e}");
        }
        // 2 000 uniform random points: the outermost point of a window of length L (half
        // a side) lies inside it by 1/(2000·L) = 1e-3 on average; with the gap estimated
        // from the spacing of the outermost points, the residual (the side's offset from
        // the estimated edge) is nil on average. 40 samplings, 8 windows each.
        let mut uniform = Uniform(7);
        let (mut with_gap, mut outermost, mut count) = (0.0, 0.0, 0.0);
        for _ in 0..40 {
            let points = uniform.square(2000);
            for r in edges(&points) {
                with_gap += r;
                count += 1.0;
            }
            // The outermost offset alone, from the mesh's windows, less its expected gap.
            let grid = unit_square();
            let target = TargetCloud::new(&points).unwrap();
            let matches = target.matches(&grid, 1);
            for w in edge_windows(&grid, &target.points, &matches) {
                outermost += w.offsets.iter().copied().fold(f64::NEG_INFINITY, f64::max)
                    + 1.0 / (2000.0 * w.length);
            }
        }
        let (with_gap, outermost) = (with_gap / count, outermost / count);
        // Standard error of the mean: 1e-3 / √320 ≈ 6e-5.
        assert!(with_gap.abs() < 2e-4, "{with_gap:e}");
        assert!(outermost.abs() < 2e-4, "{outermost:e}");
    }

    #[test]
    fn a_dense_scan_holds_each_side_in_more_windows_than_a_sparse_one() {
        // Points of a planar Poisson sampling of density n are 1/(2√n) from their nearest
        // on average: a unit side is about 2√n spacings long, 89 for 2 000 points of the
        // unit square and 200 for 10 000 (fewer near the edges, where the nearest lie
        // on one side only). A window is at least 35 spacings long.
        let grid = unit_square();
        let count = |points: &[DVec3]| {
            let target = TargetCloud::new(points).unwrap();
            edge_windows(&grid, &target.points, &target.matches(&grid, 1)).len()
        };
        let mut uniform = Uniform(11);
        assert_eq!(count(&uniform.square(2000)), 4 * 2);
        let dense = count(&uniform.square(10_000));
        assert!((4 * 4..=4 * 5).contains(&dense), "{dense}");
        // A mesh's 21 × 21 vertices: 20 spacings a side, two windows.
        let vertices: Vec<DVec3> = (0..441)
            .map(|k| DVec3::new((k / 21) as f64 / 20.0, (k % 21) as f64 / 20.0, 0.0))
            .collect();
        assert_eq!(count(&vertices), 4 * 2);
    }
}
