//! The target of an approximation (§4.7, monge's extension): its points in a spatial
//! index, with a normal at each and an outward direction at its boundary, and the
//! distances between it and a mesh both ways.

use glam::{DVec2, DVec3};
use rstar::RTree;

use crate::grid::{bbox_diagonal, point_segment, QuadGrid, MAX_SIZE, MIN_SIZE};

use super::distance::{map_blocks, Deviation, Indexed, MeshFaces, Triangle};
use super::edge::{
    beyond_edge, edge_residuals, edge_windows, regular_edge, side_windows, EDGE_NEIGHBOURS,
};
use super::error::{ApproxError, MIN_POINTS};
use super::quadric::{misfits, principal_axes, through_point_share, Quadric, SHARE_POINTS};
use super::stray::stray_points;

/// The target: its points, a spatial index, a normal for each point and an outward
/// direction for each point of its boundary.
#[derive(Clone, Debug)]
pub struct TargetCloud {
    /// The points kept: all but the stray ones.
    pub(super) points: Vec<DVec3>,
    /// The indices of the stray points set aside ([`TargetCloud::stray`]).
    stray: Vec<usize>,
    pub(super) tree: RTree<Indexed>,
    /// Unit normal of the plane fitted to each point's neighbours.
    pub(super) normals: Vec<DVec3>,
    /// The quadric fitted to each point's neighbours in the frame of its normal: the
    /// surface near it to second order (a tangent plane alone is off by `κd²/2` at a
    /// distance `d` from the point, as much as a random sampling's spacing makes it).
    patches: Vec<Quadric>,
    /// Unit outward direction in the tangent plane at a boundary point, zero inside.
    pub(super) outward: Vec<DVec3>,
    /// The boundary points (those with an outward direction), indexed: whether a point
    /// is near the target's edge.
    boundary: RTree<Indexed>,
    /// Whether each point lies within [`EDGE_BAND`] spacings of a boundary point: the
    /// points that set the target's edge, which [`TargetCloud::matches`] keeps all of.
    near_edge: Vec<bool>,
    /// Mean distance from a point to its nearest neighbour.
    pub(super) spacing: f64,
    /// How much of each point's height above its own quadric is the surface's rather than
    /// noise ([`through_point_share`]): the quadric is moved by that much of it.
    through: f64,
    /// The normal of the plane fitted to all the points: the side to which
    /// [`TargetCloud::residuals`] turns the normals, so that a signed distance does not
    /// flip sign from one target point to the next.
    pub(super) up: DVec3,
    pub(super) size: f64,
    /// Whether the boundary points lie on the target's edge, evenly spaced (a mesh's
    /// boundary vertices, [`regular_edge`]), not inside it by the gaps of a random
    /// sampling: then a vertex beyond the edge is measured to their polyline too, and
    /// the sides' windows read its edge exactly ([`edge_residuals`]).
    pub(super) edge_on_points: bool,
}

/// `points` indexed by their positions.
pub(super) fn index_of(points: &[DVec3]) -> RTree<Indexed> {
    RTree::bulk_load(
        points
            .iter()
            .enumerate()
            .map(|(i, p)| Indexed::new(p.to_array(), i))
            .collect(),
    )
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
        let scale = |size: f64| {
            if (MIN_SIZE..=MAX_SIZE).contains(&size) {
                Ok(size)
            } else {
                Err(ApproxError::ScaleOutOfRange {
                    size,
                    min: MIN_SIZE,
                    max: MAX_SIZE,
                })
            }
        };
        // The stray points set aside (their indices in `points`), the rest kept.
        let all = index_of(points);
        let stray = stray_points(points, &all, scale(bbox_diagonal(points))?);
        let kept: Vec<DVec3>;
        let (points, tree) = if stray.is_empty() {
            (points, all)
        } else {
            kept = points
                .iter()
                .enumerate()
                .filter(|(k, _)| stray.binary_search(k).is_err())
                .map(|(_, p)| *p)
                .collect();
            if kept.len() < MIN_POINTS {
                return Err(ApproxError::TooFewPoints {
                    found: kept.len(),
                    needed: MIN_POINTS,
                });
            }
            (&kept[..], index_of(&kept))
        };
        let size = scale(bbox_diagonal(points))?;
        let mut normals = Vec::with_capacity(points.len());
        let mut patches = Vec::with_capacity(points.len());
        let mut outward = Vec::with_capacity(points.len());
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
        }
        let through = through_point_share(sums, dof, size);
        let spacing = nearest / points.len() as f64;
        let boundary = RTree::bulk_load(
            points
                .iter()
                .zip(&outward)
                .enumerate()
                .filter(|(_, (_, o))| **o != DVec3::ZERO)
                .map(|(i, (p, _))| Indexed::new(p.to_array(), i))
                .collect(),
        );
        let edge_on_points = regular_edge(&boundary);
        let near_edge = points
            .iter()
            .map(|p| {
                boundary.nearest_neighbor(p.to_array()).is_some_and(|b| {
                    DVec3::from_array(*b.geom()).distance(*p) <= EDGE_BAND * spacing
                })
            })
            .collect();
        Ok(TargetCloud {
            stray,
            near_edge,
            edge_on_points,
            through,
            points: points.to_vec(),
            tree,
            normals,
            patches,
            outward,
            boundary,
            spacing,
            up: principal_axes(points).2,
            size,
        })
    }

    /// The target read from `count` of its points spread over it (a pseudo-random
    /// choice, the same every time, whatever order the points come in: a scanner's rows
    /// are not thinned to stripes), or `None` where it has no more, or where its points
    /// are a mesh's vertices (evenly spaced along its edge), whose boundary lies on them,
    /// or where the chosen points are not a target ([`TargetCloud::new`] refuses them):
    /// then the whole target is read.
    pub(super) fn thinned(&self, count: usize) -> Option<TargetCloud> {
        if self.points.len() <= count || self.edge_on_points {
            return None;
        }
        // splitmix64 of each index: a pseudo-random order of the points.
        let mix = |k: usize| {
            let mut z = (k as u64).wrapping_add(0x9E37_79B9_7F4A_7C15);
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            z ^ (z >> 31)
        };
        let mut order: Vec<usize> = (0..self.points.len()).collect();
        order.sort_by_key(|k| mix(*k));
        let points: Vec<DVec3> = order[..count].iter().map(|k| self.points[*k]).collect();
        TargetCloud::new(&points).ok()
    }

    /// The `count` target points nearest to `p`, nearest first.
    pub(super) fn nearest(&self, p: DVec3, count: usize) -> Vec<DVec3> {
        self.tree
            .nearest_neighbor_iter(p.to_array())
            .take(count)
            .map(|n| DVec3::from_array(*n.geom()))
            .collect()
    }

    /// The target's size: the diagonal of its bounding box (of the points it keeps).
    pub fn size(&self) -> f64 {
        self.size
    }

    /// The indices (in the points it was given, increasing) of the stray points the
    /// target sets aside: points isolated from the rest, or off the surface their
    /// nearest others make (a bird, a crane, a reflection in a scan). Every fit,
    /// distance and outline is of the points it keeps.
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::approximate::TargetCloud;
    /// let mut points: Vec<DVec3> = (0..400)
    ///     .map(|k| {
    ///         let (x, y) = (f64::from(k % 20) * 0.5, f64::from(k / 20) * 0.5);
    ///         DVec3::new(x, y, 0.04 * x * x + 0.1 * y * y)
    ///     })
    ///     .collect();
    /// points.push(DVec3::new(5.0, 5.0, 6.0)); // 2.5 above the surface
    /// let target = TargetCloud::new(&points).unwrap();
    /// assert_eq!(target.stray(), &[400]);
    /// ```
    pub fn stray(&self) -> &[usize] {
        &self.stray
    }

    /// The points the target keeps: those it was given but the [stray](TargetCloud::stray)
    /// ones, in their order. [`target_distances`](super::target_distances) gives one
    /// distance for each.
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::approximate::TargetCloud;
    /// let mut points: Vec<DVec3> = (0..400)
    ///     .map(|k| {
    ///         let (x, y) = (f64::from(k % 20) * 0.5, f64::from(k / 20) * 0.5);
    ///         DVec3::new(x, y, 0.04 * x * x + 0.1 * y * y)
    ///     })
    ///     .collect();
    /// points.insert(7, DVec3::new(5.0, 5.0, 6.0)); // 2.5 above the surface
    /// let target = TargetCloud::new(&points).unwrap();
    /// assert_eq!(target.stray(), &[7]);
    /// assert_eq!(target.points().len(), 400);
    /// assert_eq!(target.points()[7], points[8]);
    /// ```
    pub fn points(&self) -> &[DVec3] {
        &self.points
    }

    /// Distance from `v` to the target: to the quadric fitted around the nearest target
    /// point, combined with how far `v` lies beyond the target's edge ([`beyond_edge`]).
    pub(super) fn distance_from(&self, v: DVec3) -> f64 {
        self.distance_less(v, 0.0)
    }

    /// [`TargetCloud::distance_from`], `v`'s reading beyond the target's edge less
    /// `overread` (model units).
    fn distance_less(&self, v: DVec3, overread: f64) -> f64 {
        let i = self
            .tree
            .nearest_neighbor(v.to_array())
            .expect("a target has points")
            .data;
        let beyond = (self.beyond_edge(v, i) - overread).max(0.0);
        let d = self.across(v, i).hypot(beyond);
        if beyond > 0.0 && self.edge_on_points {
            // The edge read in the tangent plane cuts a curved edge's chords; the
            // boundary points of a mesh are on it.
            d.max(self.to_boundary(v))
        } else {
            d
        }
    }

    /// How much a reading beyond the target's edge may overstate how far a vertex lies
    /// beyond its true edge (at nine corners in ten), relative to its size:
    /// [`SCAN_EDGE_OVERREAD`] mean spacings of a scan's points, nil for a mesh's
    /// vertices, which lie on its edge.
    pub fn edge_overread(&self) -> f64 {
        if self.edge_on_points {
            0.0
        } else {
            SCAN_EDGE_OVERREAD * self.spacing / self.size
        }
    }

    /// `deviation`, of a mesh of vertices `vertices`, as far as the target's points tell
    /// its edge: each vertex's reading beyond it less [`TargetCloud::edge_overread`] (on a
    /// scan, whose sampling leaves its corners bare; the same on a mesh). Compared by it, a
    /// design whose corners sit at a scan's true corners is not read farther than one
    /// pulled in to its outermost points.
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::{approximate::TargetCloud, QuadGrid};
    /// // 2 000 random points of the unit square, and a mesh of its four corners.
    /// let mut rng = fastrand::Rng::with_seed(1);
    /// let scan: Vec<DVec3> = (0..2000).map(|_| DVec3::new(rng.f64(), rng.f64(), 0.0)).collect();
    /// let target = TargetCloud::new(&scan).unwrap();
    /// let square = vec![DVec3::ZERO, DVec3::Y, DVec3::X, DVec3::new(1.0, 1.0, 0.0)];
    /// let grid = QuadGrid::new(2, 2, square, vec![DVec3::Z; 4]);
    /// let (read, over) = (target.deviation(&grid), target.edge_overread());
    /// let resolved = target.resolved(&read, &grid.vertices).mesh_to_target_max;
    /// assert!(over > 0.0 && resolved < read.mesh_to_target_max);
    /// assert!(resolved >= read.mesh_to_target_max - over);
    /// ```
    pub fn resolved(&self, deviation: &Deviation, vertices: &[DVec3]) -> Deviation {
        if self.edge_on_points {
            return *deviation;
        }
        let overread = self.edge_overread() * self.size;
        let max = vertices
            .iter()
            .map(|v| self.distance_less(*v, overread))
            .fold(0.0, f64::max);
        Deviation {
            mesh_to_target_max: max / self.size,
            ..*deviation
        }
    }

    /// Distance from `v` to the polyline of the boundary points near it: to the two
    /// segments from the nearest boundary point to its own two nearest.
    fn to_boundary(&self, v: DVec3) -> f64 {
        let Some(b) = self.boundary.nearest_neighbor(v.to_array()) else {
            return 0.0;
        };
        let b0 = DVec3::from_array(*b.geom());
        self.boundary
            .nearest_neighbor_iter(*b.geom())
            .skip(1)
            .take(2)
            .map(|n| point_segment(v, b0, DVec3::from_array(*n.geom())))
            .fold(v.distance(b0), f64::min)
    }

    /// How far `v`, whose nearest target point is `i`, lies beyond the target's edge, in
    /// the tangent plane at `i` ([`beyond_edge`]): 0 unless a boundary point is about as
    /// near to `v` as `i` is (within [`EDGE_REACH`] spacings).
    fn beyond_edge(&self, v: DVec3, i: usize) -> f64 {
        let origin = self.points[i];
        let reach = v.distance(origin) + EDGE_REACH * self.spacing;
        let near_edge = self
            .boundary
            .nearest_neighbor(v.to_array())
            .is_some_and(|b| DVec3::from_array(*b.geom()).distance(v) <= reach);
        if !near_edge {
            return 0.0;
        }
        let x = self.normals[i].any_orthonormal_vector();
        let y = self.normals[i].cross(x);
        let flat = |p: DVec3| DVec2::new((p - origin).dot(x), (p - origin).dot(y));
        let near: Vec<DVec2> = self
            .nearest(v, EDGE_NEIGHBOURS)
            .into_iter()
            .map(flat)
            .collect();
        beyond_edge(flat(v), &near, self.spacing)
    }

    /// The signed distance from `v` to the surface near target point `i`: its quadric,
    /// moved towards the point by the share of the point's height above it that is not
    /// noise ([`through_point_share`]), along its normal turned to the side of
    /// [`TargetCloud::up`] (so that the sign does not flip from one point to the next).
    fn across(&self, v: DVec3, i: usize) -> f64 {
        // The quadric through the point itself, as far as the point's height above it is
        // not noise: a mesh's own vertices are at distance 0 from it, a scan's noise is
        // averaged over its neighbours.
        let patch = &self.patches[i];
        (patch.height_above(v) - self.through * patch.height_above(self.points[i]))
            * self.normals[i].dot(self.up).signum()
    }

    /// [`TargetCloud::across`], and, where `i` is on the target's boundary, how far `v`
    /// lies beyond it by more than `allowance` along its outward direction (the least
    /// squares' guard against a side swinging out; for a mesh to be trimmed, how much
    /// less the vertex counts).
    pub(super) fn offsets(&self, v: DVec3, i: usize, allowance: f64) -> (f64, f64) {
        let d = v - self.points[i];
        let along = d - d.dot(self.normals[i]) * self.normals[i];
        (
            self.across(v, i),
            (along.dot(self.outward[i]) - allowance).max(0.0),
        )
    }

    /// Which target point is nearest to each vertex of `grid`, and which triangle of
    /// `grid` is nearest to every `stride`-th target point and to every point near the
    /// target's edge: what [`TargetCloud::residuals`] measures against. The spatial
    /// searches are all here, so the residuals of designs near `grid` (a Jacobian's
    /// columns) cost none.
    ///
    /// Every point near the edge counts, however dense the target: a side is set by the
    /// outermost points along it, whose gap to the true edge shrinks with the density
    /// only if none is left out (a scan of 20 000 points read through every fifth fell
    /// 1e-3 to 4e-3 of its size short of its edges, θ of a moulding off by 1.5° without
    /// noise; with every point near the edge, 2e-4 to 1e-3, θ exact).
    pub(super) fn matches(&self, grid: &QuadGrid, stride: usize) -> Matches {
        let faces = MeshFaces::new(grid);
        let sample: Vec<usize> = (0..self.points.len())
            .filter(|k| k % stride == 0 || self.near_edge[*k])
            .collect();
        Matches {
            windows: side_windows(grid, self.spacing),
            vertices: map_blocks(grid.vertices.len(), |k| {
                self.tree
                    .nearest_neighbor(grid.vertices[k].to_array())
                    .expect("a target has points")
                    .data
            }),
            points: map_blocks(sample.len(), |j| {
                (sample[j], faces.nearest(self.points[sample[j]]).0)
            }),
            stride,
        }
    }

    /// The residuals of the approximation's least squares at `grid` (relative to the
    /// target's size; their sum of squares is the objective), against `matches` (those
    /// of `grid` itself, or of a design near it):
    ///
    /// - the surface: for every vertex, its signed distance to the surface near its
    ///   matched target point and how far it overhangs the target's boundary by more
    ///   than [`OVERHANG_SPACINGS`] spacings on a mesh, [`SCAN_OVERHANG_SPACINGS`] on a
    ///   scan, whose true corners lie bare ([`TargetCloud::offsets`]: a guard against a
    ///   side swinging out, not the edge's measure, which a random sampling's gaps would
    ///   bias inwards), weighted by one over the square root of their number;
    /// - the edges: each side of the mesh is cut into windows ([`side_windows`]), and in
    ///   each the target points matched to the faces within [`EDGE_DEPTH`](super::edge) rows of
    ///   that side give their offsets beyond it (in the surface, across the side). The
    ///   target's true edge lies beyond its outermost points by a gap that a sampling
    ///   leaves (nil for a mesh's vertices, which are on the edge; for `n` random points
    ///   over an area `A`, about `A / (n·L)` along a window of length `L`), estimated as
    ///   for the largest of a uniform sample (the maximum plus the mean spacing of the
    ///   largest values): the mean spacing of each window's [`EDGE_ORDER`](super::edge) outermost
    ///   offsets gives the area per point, from all the windows together. On a mesh the
    ///   residual of a window is its outermost offset plus that gap; on a scan that of a
    ///   side, from its outermost point along its whole length, with a one-sided guard
    ///   per window ([`edge_residuals`]): the side is fitted to the envelope of the points
    ///   as a whole, two-sided, not vertex by vertex; each weighted by one over the square
    ///   root of their number;
    /// - on a scan, the cover: for every `stride`-th target point, how much farther than
    ///   [`OVERHANG_SPACINGS`] spacings it lies from its matched triangle of the mesh
    ///   ([`TargetCloud::to_mesh_beyond`]), weighted by one over the square root of their
    ///   number. Nil where the mesh reaches the target's edges; the windows see only the
    ///   points of their strips, not a corner cut off beyond them nor a part of the target
    ///   the mesh does not reach, whose points are nearer its inside (a least squares
    ///   that covered half a scanned moulding read 5e-4 RMS, as if recovered). Held-out
    ///   scans of 2 000 points on 120 samplings (seeds 1 to 24), brute force: within
    ///   1e-3 both ways 20 → 28 times; free-form scans to 5e-3 the same. Not on a mesh,
    ///   whose edges the windows read exactly: there it pulled the one-patch fit of a
    ///   hyperbolic paraboloid, which one patch cannot follow, farther (RMS 3.1e-2 →
    ///   5.2e-2).
    pub(super) fn residuals(&self, grid: &QuadGrid, matches: &Matches) -> Vec<f64> {
        let weight = |n: usize| 1.0 / (self.size * (n as f64).sqrt());
        let w_vertices = weight(grid.vertices.len());
        let windows = edge_windows(grid, &self.points, &matches.points, matches.windows);
        let mut out = Vec::with_capacity(2 * grid.vertices.len() + windows.len() + 4);
        let overhang = if self.edge_on_points {
            OVERHANG_SPACINGS
        } else {
            SCAN_OVERHANG_SPACINGS
        };
        for (v, i) in grid.vertices.iter().zip(&matches.vertices) {
            let (across, beyond) = self.offsets(*v, *i, overhang * self.spacing);
            out.extend([w_vertices * across, w_vertices * beyond]);
        }
        let edges = edge_residuals(&windows, !self.edge_on_points);
        let w_edges = EDGE_WEIGHT * weight(edges.len());
        out.extend(edges.into_iter().map(|r| w_edges * r));
        if !self.edge_on_points {
            out.extend(self.to_mesh_beyond(grid, matches, OVERHANG_SPACINGS * self.spacing));
        }
        out
    }
}

/// A vertex is measured against the target's edge when a boundary point is within this
/// many mean spacings of as near to it as its nearest target point: a random sampling's
/// outermost points lie up to about two spacings apart along its edge.
const EDGE_REACH: f64 = 3.0;

/// How far, in mean spacings of a scan's points, its reading of a vertex beyond its edge
/// lies beyond the truth at nine corners in ten (of 200 samplings of a rectangle: 0.85 at
/// the median, 4.0 at 99 in 100; on a side 0.06, 0.40 and 0.79).
pub const SCAN_EDGE_OVERREAD: f64 = 2.5;

/// What the residuals of a mesh are measured against ([`TargetCloud::matches`]).
pub(super) struct Matches {
    /// The nearest target point of each vertex.
    pub(super) vertices: Vec<usize>,
    /// The nearest triangle of every `stride`-th target point and of every point near
    /// the target's edge, each with the point's index.
    pub(super) points: Vec<(usize, Triangle)>,
    /// How many windows each side of the mesh is cut into ([`side_windows`]): fixed
    /// with the matches, so that designs near the mesh have as many residuals.
    pub(super) windows: [usize; 4],
    /// Every `stride`-th target point is matched (and those near the edge).
    pub(super) stride: usize,
}

/// Distance from a boundary point, in mean spacings, within which every target point
/// is matched to the mesh ([`TargetCloud::matches`]): a window's outermost points lie
/// within a fraction of a spacing of the edge, and a random sampling's boundary points
/// up to about one spacing inside it and two apart along it.
const EDGE_BAND: f64 = 3.0;

/// Overhang of a vertex beyond the target's boundary point nearest to it, in mean
/// spacings of the target's points, that the least squares leave unpenalised: a random
/// sampling's outermost points lie inside the true edge by up to about two. So far too
/// may a target point lie from the mesh before the cover's residual counts it
/// ([`TargetCloud::residuals`]).
pub(super) const OVERHANG_SPACINGS: f64 = 3.0;

/// On a scan, the overhang of a vertex beyond the target point nearest to it, in mean
/// spacings, that the least squares leave unpenalised (on a mesh [`OVERHANG_SPACINGS`]):
/// a random sampling leaves the true corners bare, up to 8.5 spacings from their nearest
/// point on the held-out scans, and a guard of three pulled a true design's corners in
/// (2.5e-6 of its objective of 2.6e-6 on one of them, which a design off the target by
/// 4e-3 of its size undercut). The sides are held by their own residuals
/// ([`edge_residuals`]).
const SCAN_OVERHANG_SPACINGS: f64 = 10.0;

/// Weight of the edges' residuals against the surface's: each window's outermost point is
/// random (for `n` points, by about `1/n` of the size), and the sides' positions, which
/// only the edges set, need no more; the surface's shape, which sets the sides' shapes,
/// is left to the surface.
const EDGE_WEIGHT: f64 = 0.3;

#[cfg(test)]
mod tests {
    use super::super::edge::tests::unit_square;
    use super::*;

    #[test]
    fn a_large_scan_is_thinned_evenly_and_a_mesh_not_at_all() {
        // 5 000 random points of the unit square sorted by y, as a scanner's rows come:
        // 2 000 of them spread over the whole square (each quarter holds about a
        // quarter), the same every time.
        let mut rng = fastrand::Rng::with_seed(3);
        let mut scan: Vec<DVec3> = (0..5000)
            .map(|_| DVec3::new(rng.f64(), rng.f64(), 0.0))
            .collect();
        scan.sort_by(|a, b| a.y.total_cmp(&b.y));
        let target = TargetCloud::new(&scan).unwrap();
        let sparse = target.thinned(2000).unwrap();
        assert_eq!(sparse.points.len(), 2000);
        assert_eq!(sparse.points, target.thinned(2000).unwrap().points);
        for (x, y) in [(0.0, 0.0), (0.5, 0.0), (0.0, 0.5), (0.5, 0.5)] {
            let quarter = sparse
                .points
                .iter()
                .filter(|p| (x..x + 0.5).contains(&p.x) && (y..y + 0.5).contains(&p.y))
                .count();
            assert!((400..=600).contains(&quarter), "{quarter}");
        }
        assert!(target.thinned(5000).is_none());
        // A mesh's 70 × 70 vertices (its boundary evenly spaced on its edge): never
        // thinned.
        let rows: Vec<DVec3> = (0..4900)
            .map(|k| DVec3::new((k % 70) as f64 / 69.0, (k / 70) as f64 / 69.0, 0.0))
            .collect();
        let mesh = TargetCloud::new(&rows).unwrap();
        assert!(mesh.thinned(2000).is_none());
    }

    /// The distance from a point of the plane z = 0 to the unit square (closed form).
    fn to_unit_square(p: DVec3) -> f64 {
        let d = |t: f64| (-t).max(t - 1.0).max(0.0);
        d(p.x).hypot(d(p.y))
    }

    /// Points around the unit square's boundary, `beyond` outside it (its offset curve:
    /// beside the sides and around the corners), 0.01 apart.
    fn around_unit_square(beyond: f64) -> Vec<DVec3> {
        let mut out = Vec::new();
        for k in 0..=100 {
            let t = k as f64 / 100.0;
            out.extend([
                (t, -beyond),
                (t, 1.0 + beyond),
                (-beyond, t),
                (1.0 + beyond, t),
            ]);
        }
        for (cx, cy) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)] {
            for k in 0..=8 {
                let a = std::f64::consts::FRAC_PI_2 * k as f64 / 8.0;
                let (x, y) = (a.cos() * beyond, a.sin() * beyond);
                out.push((
                    cx + if cx > 0.5 { x } else { -x },
                    cy + if cy > 0.5 { y } else { -y },
                ));
            }
        }
        out.into_iter()
            .map(|(x, y)| DVec3::new(x, y, 0.0))
            .collect()
    }

    /// Beyond a mesh's edge every overhang counts, in any direction: measured against
    /// the true distance to the unit square (its points are a 11 × 11 grid, 0.1 apart),
    /// from 0.02 to 0.3 beyond its sides and corners.
    #[test]
    fn a_vertex_beyond_a_meshs_edge_is_measured_from_the_edge() {
        let target = TargetCloud::new(&unit_square().vertices).unwrap();
        for beyond in [0.0, 0.02, 0.05, 0.1, 0.3] {
            for p in around_unit_square(beyond) {
                let d = target.distance_from(p);
                assert!((d - to_unit_square(p)).abs() < 1e-9, "{p}: {d}");
            }
        }
    }

    /// A mesh whose edge curves (a disc of radius 5 on the paraboloid z = 0.05 r², 12
    /// rings of 8 to 96 vertices): a vertex on the surface carried beyond the rim by 0.05 to
    /// 0.5 is measured from the rim, as the closed form has it, never short by more than
    /// 1 % and long by at most the sag of the rim's chords; read in the
    /// tangent plane alone, the rim's chords put it about 20 % short (a held-out dome's
    /// single patch read 4.1e-3 of its size off, 5.1e-3 by brute force).
    #[test]
    fn a_vertex_beyond_a_meshs_curved_edge_is_measured_from_it() {
        let z = |r: f64| 0.05 * r * r;
        let mut points = vec![DVec3::ZERO];
        for ring in 1..=12 {
            let r = 5.0 * ring as f64 / 12.0;
            for k in 0..8 * ring {
                let a = k as f64 / (8 * ring) as f64 * std::f64::consts::TAU;
                points.push(DVec3::new(r * a.cos(), r * a.sin(), z(r)));
            }
        }
        let target = TargetCloud::new(&points).unwrap();
        assert!(target.edge_on_points);
        for beyond in [0.05, 0.1, 0.2, 0.5] {
            for a in [0.0, 0.3, 1.0, 2.0] {
                let r = 5.0 + beyond;
                let v = DVec3::new(r * f64::cos(a), r * f64::sin(a), z(r));
                let rim = DVec3::new(5.0 * f64::cos(a), 5.0 * f64::sin(a), z(5.0));
                let (d, truth) = (target.distance_from(v), v.distance(rim));
                // Never short; long by at most the sag of the rim's chords between its
                // vertices, 5 (1 − cos(π / 96)).
                let sag = 5.0 * (1.0 - (std::f64::consts::PI / 96.0).cos());
                assert!(
                    d >= 0.99 * truth && d <= truth + sag,
                    "{beyond} {a}: {d} {truth}"
                );
            }
        }
        // A random sampling's boundary points are not on its edge.
        let mut rng = fastrand::Rng::with_seed(2);
        let scan: Vec<DVec3> = (0..2000)
            .map(|_| DVec3::new(rng.f64(), rng.f64(), 0.1 * rng.f64().powi(2)))
            .collect();
        assert!(!TargetCloud::new(&scan).unwrap().edge_on_points);
    }

    /// [`SCAN_EDGE_OVERREAD`]: a vertex on a corner of a random sampling of a rectangle
    /// reads beyond it by more at about one corner in ten; on a side, never by a spacing.
    #[test]
    fn a_scans_corner_is_read_beyond_by_the_overread_at_one_corner_in_ten() {
        let (mut over, mut corners, mut side) = (0, 0, 0.0f64);
        for seed in 0..60 {
            let mut rng = fastrand::Rng::with_seed(seed);
            let points: Vec<DVec3> = (0..2000)
                .map(|_| DVec3::new(rng.f64(), 0.7 * rng.f64(), 0.0))
                .collect();
            let scan = TargetCloud::new(&points).unwrap();
            let read = |x: f64, y: f64| scan.distance_from(DVec3::new(x, y, 0.0)) / scan.spacing;
            for (x, y) in [(0.0, 0.0), (1.0, 0.0), (0.0, 0.7), (1.0, 0.7)] {
                corners += 1;
                over += usize::from(read(x, y) > SCAN_EDGE_OVERREAD);
            }
            side = side.max(read(0.5, 0.0)).max(read(0.0, 0.35));
        }
        let share = over as f64 / corners as f64;
        assert!((0.03..=0.2).contains(&share), "{share}");
        assert!(side < 1.0, "{side}");
    }

    /// A scan's outermost points lie inside its true edge, by up to about a spacing along
    /// its sides and more at its corners, where they thin out: the edge read from them
    /// is the true one within a share of a spacing along the sides, and within about two
    /// at the corners (read beyond it, never short of it by more than half a spacing),
    /// at the edge and beyond it. Uniform random points of the unit square, and a random
    /// half of a grid's (as a scan resampled from a mesh), against the closed form.
    #[test]
    fn a_vertex_beyond_a_scans_edge_is_measured_from_its_true_edge() {
        let mut rng = fastrand::Rng::with_seed(3);
        let uniform: Vec<DVec3> = (0..2000)
            .map(|_| DVec3::new(rng.f64(), rng.f64(), 0.0))
            .collect();
        let lattice: Vec<DVec3> = (0..61 * 61)
            .filter(|_| rng.f64() < 0.54)
            .map(|k| DVec3::new((k / 61) as f64 / 60.0, (k % 61) as f64 / 60.0, 0.0))
            .collect();
        for (name, points) in [("uniform", uniform), ("lattice", lattice)] {
            let scan = TargetCloud::new(&points).unwrap();
            let (mut sides, mut corners) = ((0.0f64, 0.0f64), (0.0f64, 0.0f64));
            for beyond in [0.0, 0.01, 0.05] {
                for p in around_unit_square(beyond) {
                    let error = (scan.distance_from(p) - to_unit_square(p)) / scan.spacing;
                    // Within a tenth of the side of a corner, or not.
                    let near_corner = [p.x, p.y].iter().all(|t| !(0.1..=0.9).contains(t));
                    let range = if near_corner {
                        &mut corners
                    } else {
                        &mut sides
                    };
                    *range = (range.0.min(error), range.1.max(error));
                }
            }
            assert!(
                sides.0 > -0.5 && sides.1 < 0.75,
                "{name}: sides {sides:?} spacings"
            );
            assert!(
                corners.0 > -0.5 && corners.1 < SCAN_EDGE_OVERREAD,
                "{name}: corners {corners:?} spacings"
            );
        }
    }
}
