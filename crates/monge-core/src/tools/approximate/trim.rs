//! A mesh trimmed to the target's outline (monge's extension of §4.7): where the
//! target's edges are not curvature lines (a roof over a rectangle whose curvature
//! lines run askew), no grid of curvature lines ends on them; the grid is fitted to
//! cover the target instead, and each face is cut by the target's outline, seen along
//! the target's normal ([`Outline`], [`trim`]). A cut face keeps the plane of its face:
//! its new corners are lifted onto it, so the panels stay planar; a panel cut by the
//! edge is no longer circular (its corners inside still are).

use std::collections::HashMap;

use glam::{DVec2, DVec3};

use crate::grid::QuadGrid;

use super::clip::{clip, convex_pieces, polygon_area};
use super::distance::{Deviation, MeshFaces, Triangles};
use super::index::TargetCloud;
use super::outline::Outline;

/// A mesh of planar polygons: a grid trimmed to an outline ([`trim`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TrimmedMesh {
    /// Its vertices: the grid's inside the outline, then the cuts'.
    pub vertices: Vec<DVec3>,
    /// Its faces, each a polygon of vertex indices, counter-clockwise as the grid's
    /// faces run.
    pub faces: Vec<Vec<usize>>,
    /// Of each face, the grid's face `(i, j)` it was cut from.
    pub from: Vec<(usize, usize)>,
    /// Of each face, whether the outline cut it (else it is its grid face whole).
    pub cut: Vec<bool>,
}

impl TrimmedMesh {
    /// Its faces as triangles ([`TrimmedMesh::mesh_faces`], each quad split along its
    /// diagonal from its first corner), their corners.
    pub(super) fn triangles(&self) -> Vec<[DVec3; 3]> {
        let v = |k: usize| self.vertices[k];
        self.mesh_faces()
            .iter()
            .flat_map(|f| (1..f.len() - 1).map(move |k| [v(f[0]), v(f[k]), v(f[k + 1])]))
            .collect()
    }

    /// Its faces as a mesh of triangles and quads, what Rhino, Grasshopper and glTF
    /// take: each face the outline did not cut as it is (a face of the grid), each cut
    /// face split into triangles in its plane (ear clipping), turned as its polygon.
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::approximate::{trim, Outline, TargetCloud};
    /// use monge_core::QuadGrid;
    /// let points: Vec<DVec3> = (0..2000)
    ///     .map(|k| {
    ///         let (r, a) = (4.0 * ((k as f64 + 0.5) / 2000.0).sqrt(), k as f64 * 2.399963);
    ///         DVec3::new(r * a.cos(), r * a.sin(), 0.0)
    ///     })
    ///     .collect();
    /// let outline = Outline::of(&TargetCloud::new(&points).unwrap()).unwrap();
    /// let vertices: Vec<DVec3> = (0..121)
    ///     .map(|k| DVec3::new((k / 11) as f64 - 5.0, (k % 11) as f64 - 5.0, 0.0))
    ///     .collect();
    /// let trimmed = trim(&QuadGrid::new(11, 11, vertices, vec![]), &outline);
    /// let faces = trimmed.mesh_faces();
    /// // The uncut faces' quads, and at least one triangle per cut face.
    /// let quads = faces.iter().filter(|f| f.len() == 4).count();
    /// assert_eq!(quads, trimmed.cut.iter().filter(|c| !**c).count());
    /// assert!(faces.len() - quads >= trimmed.cut.iter().filter(|c| **c).count());
    /// ```
    pub fn mesh_faces(&self) -> Vec<Vec<usize>> {
        let mut earcut = earcut::Earcut::new();
        let (mut flat, mut triangles) = (Vec::new(), Vec::<usize>::new());
        let mut out = Vec::with_capacity(self.faces.len());
        for (face, cut) in self.faces.iter().zip(&self.cut) {
            if !cut {
                out.push(face.clone());
                continue;
            }
            let corners: Vec<[f64; 3]> =
                face.iter().map(|&v| self.vertices[v].to_array()).collect();
            if !earcut::utils3d::project3d_to_2d(&corners, corners.len(), &mut flat) {
                continue; // no area: nothing to show
            }
            earcut.earcut(flat.iter().copied(), &[], &mut triangles);
            let normal = newell(face.iter().map(|&v| self.vertices[v]));
            for t in triangles.chunks_exact(3) {
                let [a, b, c] = [face[t[0]], face[t[1]], face[t[2]]];
                let [p, q, r] = [a, b, c].map(|v| self.vertices[v]);
                out.push(if (q - p).cross(r - p).dot(normal) < 0.0 {
                    vec![a, c, b]
                } else {
                    vec![a, b, c]
                });
            }
        }
        out
    }

    /// Its distances both ways to `target`, relative to the target's size: from every
    /// vertex (its cuts too) to the target, from every target point to its faces, as a
    /// trimmed fit is measured.
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::approximate::{TargetCloud, TrimmedMesh};
    /// // A unit square 0.1 above a target on the plane z = 0 over the same square.
    /// let v = |x: f64, y: f64| DVec3::new(x, y, 0.1);
    /// let mesh = TrimmedMesh {
    ///     vertices: vec![v(0., 0.), v(1., 0.), v(1., 1.), v(0., 1.)],
    ///     faces: vec![vec![0, 1, 2, 3]],
    ///     from: vec![(0, 0)],
    ///     cut: vec![false],
    /// };
    /// let points: Vec<DVec3> = (0..121)
    ///     .map(|k| DVec3::new((k / 11) as f64 / 10.0, (k % 11) as f64 / 10.0, 0.0))
    ///     .collect();
    /// let target = TargetCloud::new(&points).unwrap();
    /// let d = mesh.deviation(&target);
    /// assert!((d.target_to_mesh_max * d.size - 0.1).abs() < 1e-12);
    /// ```
    pub fn deviation(&self, target: &TargetCloud) -> Deviation {
        trimmed_deviation(target, self, 1)
    }

    /// Its edges, each a closed polyline (the first point again at the end): the loops of
    /// the edges in one face only, each run as the faces run (the outline's cuts, and
    /// the grid's sides where it stops short of the outline).
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::approximate::TrimmedMesh;
    /// // Two squares side by side: one loop of six edges round both.
    /// let v = |x: f64, y: f64| DVec3::new(x, y, 0.0);
    /// let mesh = TrimmedMesh {
    ///     vertices: vec![v(0., 0.), v(1., 0.), v(2., 0.), v(0., 1.), v(1., 1.), v(2., 1.)],
    ///     faces: vec![vec![0, 1, 4, 3], vec![1, 2, 5, 4]],
    ///     from: vec![(0, 0), (0, 1)],
    ///     cut: vec![false, false],
    /// };
    /// let loops = mesh.edges();
    /// assert_eq!(loops.len(), 1);
    /// assert_eq!(loops[0].len(), 7);
    /// assert_eq!(loops[0].first(), loops[0].last());
    /// ```
    pub fn edges(&self) -> Vec<Vec<DVec3>> {
        let mut count: HashMap<(usize, usize), usize> = HashMap::new();
        for f in &self.faces {
            for (a, b) in f.iter().zip(f.iter().cycle().skip(1)) {
                *count.entry(((*a).min(*b), (*a).max(*b))).or_default() += 1;
            }
        }
        // Each free edge from its first vertex as its face runs.
        let mut next: HashMap<usize, usize> = HashMap::new();
        for f in &self.faces {
            for (a, b) in f.iter().zip(f.iter().cycle().skip(1)) {
                if count[&((*a).min(*b), (*a).max(*b))] == 1 {
                    next.insert(*a, *b);
                }
            }
        }
        let mut starts: Vec<usize> = next.keys().copied().collect();
        starts.sort_unstable();
        let mut loops = Vec::new();
        for start in starts {
            let Some(mut at) = next.remove(&start) else {
                continue; // already on a loop
            };
            let mut polyline = vec![self.vertices[start], self.vertices[at]];
            while at != start {
                let Some(b) = next.remove(&at) else {
                    break; // an open chain: a mesh whose edges touch at a vertex
                };
                polyline.push(self.vertices[b]);
                at = b;
            }
            loops.push(polyline);
        }
        loops
    }
}

/// Newell's normal of a polygon (not normalised): its area vector, twice its area long.
fn newell(corners: impl Iterator<Item = DVec3> + Clone) -> DVec3 {
    corners
        .clone()
        .zip(corners.cycle().skip(1))
        .map(|(p, q)| p.cross(q))
        .sum()
}

/// `grid` trimmed to `outline` (see the module documentation): the faces inside it
/// whole, the faces across it cut by it (each cut face in the plane of its face: its
/// corners inside the outline are the grid's own vertices, its cuts of the grid's
/// edges lie on those edges, shared with the neighbouring face, and the outline's
/// corners within it are lifted onto its plane along the outline's direction), the
/// faces outside it dropped.
///
/// ```
/// use glam::DVec3;
/// use monge_core::approximate::{trim, Outline, TargetCloud};
/// use monge_core::QuadGrid;
/// // A target over the disc of radius 4, and a flat grid over the square [−5, 5]².
/// let points: Vec<DVec3> = (0..2000)
///     .map(|k| {
///         let (r, a) = (4.0 * ((k as f64 + 0.5) / 2000.0).sqrt(), k as f64 * 2.399963);
///         let (x, y) = (r * a.cos(), r * a.sin());
///         DVec3::new(x, y, 0.05 * (x * x - 0.5 * y * y))
///     })
///     .collect();
/// let outline = Outline::of(&TargetCloud::new(&points).unwrap()).unwrap();
/// let vertices: Vec<DVec3> = (0..121)
///     .map(|k| DVec3::new((k / 11) as f64 - 5.0, (k % 11) as f64 - 5.0, 0.0))
///     .collect();
/// let grid = QuadGrid::new(11, 11, vertices, vec![]);
/// let trimmed = trim(&grid, &outline);
/// // Fewer faces than the grid's 100, every one inside the disc (with its cut points).
/// assert!(trimmed.faces.len() < 100 && trimmed.faces.len() > 40);
/// assert!(trimmed.vertices.iter().all(|v| v.truncate().length() < 4.0 + 1e-9));
/// ```
pub fn trim(grid: &QuadGrid, outline: &Outline) -> TrimmedMesh {
    let size = grid.bbox_diagonal().max(f64::MIN_POSITIVE);
    let eps = TRIM_EPS * size;
    let flat: Vec<DVec2> = grid.vertices.iter().map(|v| outline.flat(*v)).collect();
    let inside: Vec<bool> = flat.iter().map(|q| outline.contains_flat(*q)).collect();
    let mut out = TrimmedMesh::default();
    let mut kept: HashMap<usize, usize> = HashMap::new();
    let mut cuts: HashMap<(usize, usize, i64), usize> = HashMap::new();
    let n = outline.polygon.len();
    for i in 0..grid.rows.saturating_sub(1) {
        for j in 0..grid.cols.saturating_sub(1) {
            let corners = [
                grid.index(i, j),
                grid.index(i + 1, j),
                grid.index(i + 1, j + 1),
                grid.index(i, j + 1),
            ];
            let quad = corners.map(|c| flat[c]);
            let (lo, hi) = quad
                .iter()
                .fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), q| {
                    (lo.min(*q), hi.max(*q))
                });
            let crossing = (0..n).any(|k| {
                let (a, b) = (outline.polygon[k], outline.polygon[(k + 1) % n]);
                a.min(b).cmple(hi + eps).all() && a.max(b).cmpge(lo - eps).all()
            });
            let all_inside = corners.iter().all(|c| inside[*c]);
            let pieces: Vec<Vec<DVec2>> = if !crossing {
                if !all_inside {
                    continue;
                }
                vec![quad.to_vec()]
            } else {
                // A face seen along the outline's direction is a convex quad, or (where
                // the mesh reaches beyond the target, twisted) is clipped as the two
                // triangles either side of a diagonal.
                convex_pieces(&quad)
                    .iter()
                    .map(|window| clip(&outline.polygon, window))
                    .collect()
            };
            let p = corners.map(|c| grid.vertices[c]);
            let normal = (p[2] - p[0]).cross(p[3] - p[1]);
            for polygon in pieces {
                if polygon.len() < 3 || polygon_area(&polygon).abs() <= eps * eps {
                    continue;
                }
                let mut face = Vec::with_capacity(polygon.len());
                let mut cut = false;
                for q in &polygon {
                    let index = if let Some(k) = (0..4).find(|k| q.distance(quad[*k]) <= eps) {
                        *kept.entry(corners[k]).or_insert_with(|| {
                            out.vertices.push(p[k]);
                            out.vertices.len() - 1
                        })
                    } else if let Some((a, b, t)) = on_edge(*q, &quad, eps) {
                        cut = true;
                        // On the grid's edge between corners a and b: the same point for
                        // both faces that share it.
                        let (a, b, t) = if corners[a] < corners[b] {
                            (a, b, t)
                        } else {
                            (b, a, 1.0 - t)
                        };
                        let key = (corners[a], corners[b], (t / TRIM_EPS).round() as i64);
                        *cuts.entry(key).or_insert_with(|| {
                            out.vertices.push(p[a] + t * (p[b] - p[a]));
                            out.vertices.len() - 1
                        })
                    } else {
                        // The outline's corner within the face, lifted onto its plane.
                        cut = true;
                        let at = outline.lift(*q);
                        let h = normal.dot(p[0] - at) / normal.dot(outline.up);
                        out.vertices.push(if h.is_finite() {
                            at + h * outline.up
                        } else {
                            at
                        });
                        out.vertices.len() - 1
                    };
                    if face.last() != Some(&index) && face.first() != Some(&index) {
                        face.push(index);
                    }
                }
                if face.len() >= 3 {
                    out.faces.push(face);
                    out.from.push((i, j));
                    out.cut.push(cut);
                }
            }
        }
    }
    out
}

/// Folded faces (§5.2) of `grid` that its mesh trimmed to `outline` keeps a piece of;
/// without an outline, all of them. A mesh fitted to cover a target may fold where the
/// trimming cuts it away: that is not in the result.
pub(super) fn kept_folds(grid: &QuadGrid, outline: Option<&Outline>) -> usize {
    let folded = grid.folded_faces();
    match outline {
        _ if !folded.contains(&true) => 0,
        None => folded.iter().filter(|f| **f).count(),
        Some(outline) => {
            // The pieces of one face are consecutive in the trimmed mesh.
            let mut kept = trim(grid, outline).from;
            kept.dedup();
            kept.iter()
                .filter(|(i, j)| folded[i * (grid.cols - 1) + j])
                .count()
        }
    }
}

/// The faces a fit's result is measured against, for a target point's distance to it
/// and that distance's part along the nearest face's plane: `grid`'s faces, or where the
/// result is `trimmed`, the trimmed mesh's. One measure for the deviation
/// ([`trimmed_deviation`]), the patches' figures and the picture's colours.
pub(super) enum ResultFaces<'a> {
    /// The grid's faces (around its nearest vertices).
    Grid(MeshFaces<'a>),
    /// The trimmed mesh's faces (exact nearest).
    Trimmed(Triangles),
}

impl<'a> ResultFaces<'a> {
    /// The faces of `grid`, trimmed where `trimmed` is given (the trimmed mesh of `grid`).
    pub(super) fn new(grid: &'a QuadGrid, trimmed: Option<&TrimmedMesh>) -> Self {
        match trimmed {
            Some(mesh) => ResultFaces::Trimmed(Triangles::new(mesh.triangles())),
            None => ResultFaces::Grid(MeshFaces::new(grid)),
        }
    }

    /// Distance from `p` to the nearest face, and its part along that face's plane.
    pub(super) fn distance_from(&self, p: DVec3) -> (f64, f64) {
        match self {
            ResultFaces::Grid(faces) => faces.distance_from(p),
            ResultFaces::Trimmed(faces) => faces.distance_from(p),
        }
    }
}

/// Distances both ways between a mesh trimmed to the target's outline (`trimmed`,
/// [`trim`]) and `target`, relative to the target's size: from every vertex of the
/// trimmed mesh (its cuts too) to the target, and from every target point to the
/// trimmed mesh's faces. (To the grid's faces before trimming, a target point near the
/// outline was read nearer to a face's part cut away than to what is kept: a coarse
/// fit's largest distance read 0.165 for 0.210 by brute force.)
pub(super) fn trimmed_deviation(
    target: &TargetCloud,
    trimmed: &TrimmedMesh,
    stride: usize,
) -> Deviation {
    trimmed_deviation_below(target, trimmed, stride, f64::INFINITY).expect("no bound")
}

/// [`trimmed_deviation`] where it may come closer than a deviation of largest distance
/// `than` ([`TargetCloud::deviation_below`]): the trimmed mesh's vertices are measured
/// only then, what a search's evaluation costs most.
pub(super) fn trimmed_deviation_below(
    target: &TargetCloud,
    trimmed: &TrimmedMesh,
    stride: usize,
    than: f64,
) -> Option<Deviation> {
    let faces = Triangles::new(trimmed.triangles());
    target.deviation_below(
        (trimmed.vertices.len(), |k| {
            target.distance_from(trimmed.vertices[k])
        }),
        |p| faces.distance_from(p),
        stride,
        than,
    )
}

/// How a fit's mesh `grid` is measured against `target` (every `stride`-th point):
/// trimmed to `outline` where there is one ([`trimmed_deviation`], with the trimmed
/// mesh), else as it is.
pub(super) fn measured(
    target: &TargetCloud,
    grid: &QuadGrid,
    outline: Option<&Outline>,
    stride: usize,
) -> (Deviation, Option<TrimmedMesh>) {
    match outline {
        Some(outline) => {
            let trimmed = trim(grid, outline);
            (trimmed_deviation(target, &trimmed, stride), Some(trimmed))
        }
        None => (target.deviation_strided(grid, stride), None),
    }
}

/// `deviation`, of a fit's mesh `grid` (trimmed to `trimmed` where it is), as far as
/// the target's points tell its edge ([`TargetCloud::resolved`]): the figure fits are
/// compared by.
pub(super) fn resolved(
    target: &TargetCloud,
    deviation: &Deviation,
    grid: &QuadGrid,
    trimmed: Option<&TrimmedMesh>,
) -> Deviation {
    let vertices = match trimmed {
        Some(mesh) => &mesh.vertices,
        None => &grid.vertices,
    };
    target.resolved(deviation, vertices)
}

/// Tolerance of [`trim`], relative to the grid's size: a cut this near a face's corner
/// is that corner, this near its edge is on it.
const TRIM_EPS: f64 = 1e-10;

/// Where `q` lies on a side of `quad`: its corners `(a, b)` and the share `t` of the
/// way from `a` to `b`.
fn on_edge(q: DVec2, quad: &[DVec2; 4], eps: f64) -> Option<(usize, usize, f64)> {
    (0..4).find_map(|a| {
        let b = (a + 1) % 4;
        let ab = quad[b] - quad[a];
        let t = (q - quad[a]).dot(ab) / ab.length_squared().max(f64::MIN_POSITIVE);
        ((-1e-9..=1.0 + 1e-9).contains(&t) && q.distance(quad[a] + t * ab) <= eps).then_some((
            a,
            b,
            t.clamp(0.0, 1.0),
        ))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::approximate::TargetCloud;

    #[test]
    fn a_target_point_is_measured_to_what_the_trimming_keeps() {
        // A flat target, the unit square; over it a sheet 0.5 above, whose overhang
        // beyond the edge x = 1 drops steeply to the target's plane. The part cut away
        // passes 0.1 from the target's points on that edge, the part kept 0.5 above them.
        let target: Vec<DVec3> = (0..121)
            .map(|k| DVec3::new((k % 11) as f64 / 10.0, (k / 11) as f64 / 10.0, 0.0))
            .collect();
        let cloud = TargetCloud::new(&target).unwrap();
        let xz = [(-0.1, 0.5), (0.5, 0.5), (1.05, 0.5), (1.1, 0.0)];
        let vertices = [-0.1, 0.5, 1.1]
            .iter()
            .flat_map(|y| xz.iter().map(move |(x, z)| DVec3::new(*x, *y, *z)))
            .collect();
        let grid = QuadGrid::new(3, 4, vertices, vec![DVec3::Z; 12]);
        let trimmed = trim(&grid, &Outline::of(&cloud).unwrap());
        let on_edge = DVec3::new(1.0, 0.5, 0.0);
        let untrimmed = ResultFaces::new(&grid, None).distance_from(on_edge).0;
        assert!(untrimmed < 0.11, "{untrimmed}");
        let kept = ResultFaces::new(&grid, Some(&trimmed))
            .distance_from(on_edge)
            .0;
        assert!((kept - 0.5).abs() < 1e-9, "{kept}");
        // Every target point is 0.5 from the trimmed mesh, as the deviation and the
        // picture's colours read it.
        let d = trimmed_deviation(&cloud, &trimmed, 1);
        assert!((d.target_to_mesh_max * d.size - 0.5).abs() < 1e-9);
        assert!((d.target_to_mesh_rms * d.size - 0.5).abs() < 1e-9);
        // Measured in full while it may come closer than a bound, not once its largest
        // distance target → mesh alone reaches the bound.
        let t = d.target_to_mesh_max;
        assert_eq!(
            trimmed_deviation_below(&cloud, &trimmed, 1, 1.01 * t),
            Some(d)
        );
        assert_eq!(trimmed_deviation_below(&cloud, &trimmed, 1, t), None);
        for c in crate::approximate::target_distances(&cloud, &grid, Some(&trimmed)) {
            assert!((c - 0.5).abs() < 1e-9, "{c}");
        }
    }

    #[test]
    fn only_the_folds_a_trimmed_mesh_keeps_count() {
        // A flat 11 × 11 grid over [−5, 5]², its node axes up, and the outline of a disc
        // of radius 4 round the origin.
        let disc: Vec<DVec3> = (0..2000)
            .map(|k| {
                let (r, a) = (
                    4.0 * ((k as f64 + 0.5) / 2000.0).sqrt(),
                    k as f64 * 2.399963,
                );
                DVec3::new(r * a.cos(), r * a.sin(), 0.01 * r * r)
            })
            .collect();
        let outline = Outline::of(&TargetCloud::new(&disc).unwrap()).unwrap();
        let vertices: Vec<DVec3> = (0..121)
            .map(|k| DVec3::new((k / 11) as f64 - 5.0, (k % 11) as f64 - 5.0, 0.0))
            .collect();
        // Face (i, j) folded: three of its node axes turned down, its fourth's
        // neighbours' faces keeping three up.
        let folded_at = |i: usize, j: usize| {
            let mut normals = vec![DVec3::Z; 121];
            for (a, b) in [(i, j), (i + 1, j), (i, j + 1)] {
                normals[a * 11 + b] = -DVec3::Z;
            }
            QuadGrid::new(11, 11, vertices.clone(), normals)
        };
        // At the grid's corner, beyond the disc: cut away.
        let corner = folded_at(0, 0);
        assert_eq!(corner.folds().count(), 1);
        assert_eq!(kept_folds(&corner, None), 1);
        assert_eq!(kept_folds(&corner, Some(&outline)), 0);
        // In its middle: kept.
        let middle = folded_at(5, 5);
        assert_eq!(kept_folds(&middle, Some(&outline)), middle.folds().count());
        assert!(middle.folds().count() >= 1);
    }

    #[test]
    fn a_grid_trimmed_to_a_disc_has_planar_panels_and_no_cracks() {
        // A parabolic cylinder (planar quads) sampled over a disc of radius 4, and a
        // grid of it over [−5, 5]².
        let z = |x: f64| 0.03 * x * x;
        let points: Vec<DVec3> = (0..3000)
            .map(|k| {
                let (r, a) = (
                    4.0 * ((k as f64 + 0.5) / 3000.0).sqrt(),
                    k as f64 * 2.399963,
                );
                DVec3::new(r * a.cos(), r * a.sin(), z(r * a.cos()))
            })
            .collect();
        let outline = Outline::of(&TargetCloud::new(&points).unwrap()).unwrap();
        let n = 21;
        let vertices: Vec<DVec3> = (0..n * n)
            .map(|k| {
                let (x, y) = (
                    -5.0 + 10.0 * (k / n) as f64 / (n - 1) as f64,
                    -5.0 + 10.0 * (k % n) as f64 / (n - 1) as f64,
                );
                DVec3::new(x, y, z(x))
            })
            .collect();
        let grid = QuadGrid::new(n, n, vertices, vec![]);
        let trimmed = trim(&grid, &outline);
        assert!(trimmed.cut.iter().any(|c| *c) && trimmed.cut.iter().any(|c| !*c));
        // Planar: each face's smallest singular value about its centroid (SVD).
        let mut area = 0.0;
        for f in &trimmed.faces {
            let p: Vec<DVec3> = f.iter().map(|k| trimmed.vertices[*k]).collect();
            let c = p.iter().copied().sum::<DVec3>() / p.len() as f64;
            let m = nalgebra::DMatrix::from_fn(p.len(), 3, |i, j| (p[i] - c)[j]);
            let flat = m.singular_values().min();
            assert!(flat < 1e-12, "{flat:e}");
            for k in 1..p.len() - 1 {
                area += 0.5 * (p[k] - p[0]).cross(p[k + 1] - p[0]).length();
            }
        }
        // Within the disc (seen along z, the target's normal), and covering it: the
        // cylinder's area over the disc is ∫∫ √(1 + (0.06 x)²) ≈ 16π + 0.0018 · π 4⁴ / 4,
        // less a strip of about half a spacing of the points (0.04) inside the outermost
        // points and the outline's chords between them (measured 1.2 % less).
        assert!(trimmed
            .vertices
            .iter()
            .all(|v| v.truncate().length() < 4.0 + 1e-9));
        let pi = std::f64::consts::PI;
        let expected = 16.0 * pi + 0.0018 * pi * 256.0 / 4.0;
        assert!(
            area < expected && area > 0.98 * expected,
            "{area} {expected}"
        );
        // No cracks: every edge in one face or two, and the edges in one form closed
        // loops (each of their vertices in exactly two).
        let mut edges: HashMap<(usize, usize), usize> = HashMap::new();
        for f in &trimmed.faces {
            for (a, b) in f.iter().zip(f.iter().cycle().skip(1)) {
                *edges.entry(((*a).min(*b), (*a).max(*b))).or_default() += 1;
            }
        }
        assert!(edges.values().all(|c| *c <= 2));
        let mut degree: HashMap<usize, usize> = HashMap::new();
        for ((a, b), _) in edges.iter().filter(|(_, c)| **c == 1) {
            *degree.entry(*a).or_default() += 1;
            *degree.entry(*b).or_default() += 1;
        }
        assert!(degree.values().all(|d| *d == 2), "{degree:?}");
        // Those edges as one closed loop round the disc, near its rim (the outline runs
        // through the outermost points, a spacing or less inside it), as long as the rim.
        let loops = trimmed.edges();
        assert_eq!(loops.len(), 1);
        let rim = &loops[0];
        assert_eq!(rim.len(), degree.len() + 1);
        assert!(rim
            .iter()
            .all(|p| (3.8..4.0 + 1e-9).contains(&p.truncate().length())));
        let length: f64 = rim.windows(2).map(|w| w[0].distance(w[1])).sum();
        let circle = 2.0 * pi * 4.0;
        assert!(
            length > 0.97 * circle && length < 1.02 * circle,
            "{length} {circle}"
        );
    }

    #[test]
    fn a_trimmed_mesh_as_triangles_and_quads_covers_its_polygons_once() {
        // A parabolic cylinder (planar quads) sampled over a five-pointed star, whose
        // reflex corners cut faces into polygons that are not convex.
        let z = |x: f64| 0.05 * x * x;
        let points: Vec<DVec3> = (0..4000)
            .map(|k| {
                let a = k as f64 * 2.399963;
                let r = (3.0 + 1.2 * (5.0 * a).cos()) * ((k as f64 + 0.5) / 4000.0).sqrt();
                DVec3::new(r * a.cos(), r * a.sin(), z(r * a.cos()))
            })
            .collect();
        let outline = Outline::of(&TargetCloud::new(&points).unwrap()).unwrap();
        let n = 13;
        let vertices: Vec<DVec3> = (0..n * n)
            .map(|k| {
                let (x, y) = (
                    -4.5 + 9.0 * (k / n) as f64 / (n - 1) as f64,
                    -4.5 + 9.0 * (k % n) as f64 / (n - 1) as f64,
                );
                DVec3::new(x, y, z(x))
            })
            .collect();
        let trimmed = trim(&QuadGrid::new(n, n, vertices, vec![]), &outline);
        // Signed area seen along z (the shoelace formula), of a polygon and of a face.
        let shoelace = |f: &[usize]| {
            let p: Vec<DVec3> = f.iter().map(|k| trimmed.vertices[*k]).collect();
            0.5 * (0..p.len())
                .map(|k| p[k].truncate().perp_dot(p[(k + 1) % p.len()].truncate()))
                .sum::<f64>()
        };
        let faces = trimmed.mesh_faces();
        assert!(faces.iter().all(|f| f.len() == 3 || f.len() == 4));
        let polygons: f64 = trimmed.faces.iter().map(|f| shoelace(f)).sum();
        let pieces: f64 = faces.iter().map(|f| shoelace(f)).sum();
        assert!(
            (pieces - polygons).abs() < 1e-9 * polygons.abs(),
            "{pieces} {polygons}"
        );
        // Every triangle turned as the polygons (no flipped one, whose area would be
        // taken back), and in the plane of a polygon it shares a vertex with.
        let sign = polygons.signum();
        let mut concave = 0;
        for f in &trimmed.faces {
            let q: Vec<DVec2> = f.iter().map(|k| trimmed.vertices[*k].truncate()).collect();
            let m = q.len();
            concave += usize::from((0..m).any(|k| {
                (q[(k + 1) % m] - q[k]).perp_dot(q[(k + 2) % m] - q[(k + 1) % m]) * sign < -1e-12
            }));
        }
        assert!(concave > 0, "the star cuts no polygon that is not convex");
        for f in faces.iter().filter(|f| f.len() == 3) {
            assert!(shoelace(f) * sign > 0.0, "{f:?}");
            let owner = trimmed
                .faces
                .iter()
                .find(|p| f.iter().all(|v| p.contains(v)))
                .expect("a triangle of one polygon");
            let p: Vec<DVec3> = owner.iter().map(|k| trimmed.vertices[*k]).collect();
            let normal = newell(p.iter().copied()).normalize();
            for v in f {
                assert!((trimmed.vertices[*v] - p[0]).dot(normal).abs() < 1e-12);
            }
        }
    }
}
