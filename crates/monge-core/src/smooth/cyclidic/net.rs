//! The cyclidic net (§4.4): one Dupin cyclide patch on every face of a circular
//! mesh, C¹ across the edges.

use glam::DVec3;

use crate::grid::{bbox_diagonal, face_corners, QuadGrid, Turn};

use super::arcs::{Arc, CurvatureLine};
use super::frame::{gauss_frames, Frame};
use super::nurbs::{knots, NurbsSurface};
use super::patch::{bezier_of, quad_frame, Patch, RationalBezier};
use super::quat::{unit_from, Quat};
use super::{CyclidicError, CyclidicOptions, Family, FoldReason};

/// A cyclidic net: one Dupin cyclide patch per face of a circular mesh (§4.4).
///
/// ```
/// use monge_core::cyclidic::{CyclidicNet, CyclidicOptions};
/// use monge_core::design::ArcSpec;
/// use monge_core::{generate, Design, GenerateOptions, GuideSpec};
/// let arc = |center, normal, angle_deg| {
///     GuideSpec::Arc(ArcSpec { center, start: [0.0; 3], normal, angle_deg, samples: 4 })
/// };
/// let design = Design {
///     mesh: Default::default(),
///     theta_deg: 30.0,
///     guide_u: arc([0.0, 0.0, -10.0], [0.0, 1.0, 0.0], 60.0),
///     guide_v: arc([0.0, 0.0, -3.0], [-1.0, 0.0, 0.0], 60.0),
///     tolerance: None,
/// };
/// let grid = generate(&design, &GenerateOptions::default()).unwrap().grid;
/// let net = CyclidicNet::from_normals(&grid, &CyclidicOptions::default()).unwrap();
/// let samples = net.sample_patch(1, 2, 5);
/// assert_eq!(samples.len(), 25);
/// assert!((samples[0] - grid.vertex(1, 2)).length() < 1e-12);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct CyclidicNet {
    /// Mesh vertices along `u`.
    rows: usize,
    /// Mesh vertices along `v`.
    cols: usize,
    /// The mesh's vertices, row-major: the patches' corners.
    vertices: Vec<DVec3>,
    /// The frames at the vertices, row-major.
    frames: Vec<Frame>,
    /// `W(i, j)`, the vertex quaternion weights, row-major: with the corners they
    /// give every patch, which is computed when asked for (a patch takes about
    /// 550 bytes, the net about 130 a vertex).
    weights: Vec<Quat>,
    /// The folded faces and why, in row-major face order.
    folded: Vec<((usize, usize), FoldReason)>,
    /// Grouping tolerance of [`CyclidicNet::curvature_lines`].
    circle_tolerance: f64,
    /// Size of the mesh (bounding-box diagonal).
    size: f64,
}

impl CyclidicNet {
    /// The net with the frames of §4.4 computed at every vertex from the mesh's
    /// Gauss map (its normals): `t1 = unit(m1 × N)`, `t2 = unit(m2 × N)` with `m1`, `m2`
    /// the normals of the planes of the Gauss circles of the two lines through the
    /// vertex (parallel to the planes of the lines), oriented along the mesh.
    /// On a circular mesh with planar lines its curvature lines are planar.
    ///
    /// # Errors
    /// [`CyclidicError::TooSmall`], [`CyclidicError::NoNormals`],
    /// [`CyclidicError::GaussUndetermined`], [`CyclidicError::GaussLineDegenerate`],
    /// [`CyclidicError::GaussNotOrthogonal`], [`CyclidicError::NotCircular`],
    /// [`CyclidicError::Folded`].
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::cyclidic::{CyclidicError, CyclidicNet, CyclidicOptions};
    /// use monge_core::QuadGrid;
    /// let g = QuadGrid::new(2, 2, vec![DVec3::ZERO, DVec3::Y, DVec3::X, DVec3::X + DVec3::Y], vec![]);
    /// assert_eq!(CyclidicNet::from_normals(&g, &CyclidicOptions::default()), Err(CyclidicError::NoNormals));
    /// ```
    pub fn from_normals(
        grid: &QuadGrid,
        options: &CyclidicOptions,
    ) -> Result<CyclidicNet, CyclidicError> {
        check_size(grid)?;
        let frames = gauss_frames(grid)?;
        CyclidicNet::build(grid, frames, options)
    }

    /// The net with `frame` given at vertex `(0, 0)` and carried to every vertex
    /// by reflections (§4.4, [`Frame::carried`]): down column 0, then along each row.
    /// For circular quads the result does not depend on the path. Works on any
    /// circular mesh; normals are not needed.
    ///
    /// # Errors
    /// [`CyclidicError::TooSmall`], [`CyclidicError::FrameNotOrthonormal`],
    /// [`CyclidicError::NotCircular`], [`CyclidicError::Folded`].
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::cyclidic::{CyclidicNet, CyclidicOptions, Frame};
    /// use monge_core::QuadGrid;
    /// let g = QuadGrid::new(2, 2, vec![DVec3::ZERO, DVec3::Y, DVec3::X, DVec3::X + DVec3::Y], vec![]);
    /// let net = CyclidicNet::from_frame(&g, Frame::new(DVec3::X, DVec3::Y), &CyclidicOptions::default()).unwrap();
    /// assert_eq!(net.frame(1, 1), Frame::new(DVec3::X, DVec3::Y));
    /// ```
    pub fn from_frame(
        grid: &QuadGrid,
        frame: Frame,
        options: &CyclidicOptions,
    ) -> Result<CyclidicNet, CyclidicError> {
        check_size(grid)?;
        let (t1_len, t2_len, dot) = (
            frame.t1.length() - 1.0,
            frame.t2.length() - 1.0,
            frame.t1.dot(frame.t2),
        );
        // NaN fails too (`f64::max` would have dropped it).
        if ![t1_len, t2_len, dot].iter().all(|x| x.abs() <= 1e-9) {
            return Err(CyclidicError::FrameNotOrthonormal {
                t1_len,
                t2_len,
                dot,
            });
        }
        let frame = Frame::new(frame.t1, frame.t2);
        let (rows, cols) = (grid.rows, grid.cols);
        let mut frames = vec![frame; rows * cols];
        for i in 1..rows {
            frames[i * cols] =
                frames[(i - 1) * cols].carried(grid.vertex(i - 1, 0), grid.vertex(i, 0), Family::U);
        }
        for i in 0..rows {
            for j in 1..cols {
                frames[i * cols + j] = frames[i * cols + j - 1].carried(
                    grid.vertex(i, j - 1),
                    grid.vertex(i, j),
                    Family::V,
                );
            }
        }
        CyclidicNet::build(grid, frames, options)
    }

    /// Patches from frames: vertex quaternion weights (design note), then one
    /// patch per face with its corner weights relative to its first corner.
    fn build(
        grid: &QuadGrid,
        frames: Vec<Frame>,
        options: &CyclidicOptions,
    ) -> Result<CyclidicNet, CyclidicError> {
        let (rows, cols) = (grid.rows, grid.cols);
        let p = Quat::pure;
        // Vertex weights W: along the guides from the frame tangents, inside from
        // each quad's diagonal weight.
        let mut w = vec![Quat::ONE; rows * cols];
        for i in 1..rows {
            let e = unit_from(grid.vertex(i - 1, 0), grid.vertex(i, 0));
            w[i * cols] = -(p(e) * p(frames[(i - 1) * cols].t1)) * w[(i - 1) * cols];
        }
        for j in 1..cols {
            let e = unit_from(grid.vertex(0, j - 1), grid.vertex(0, j));
            w[j] = -(p(e) * p(frames[j - 1].t2)) * w[j - 1];
        }
        // Whether a face is folded: the one test of every mesh (§5.2), on the
        // mesh as given (its node axes, or without them its faces alone).
        let folds = grid.folds();
        let face_fold = |i: usize, j: usize| {
            let turn = grid.face_turn(i, j);
            folds.is_folded(turn).then_some(if turn == Turn::Crossed {
                FoldReason::Crossed
            } else {
                FoldReason::TurnedOver
            })
        };
        if let (Some((i, j)), false) = (folds.first(), options.allow_folded) {
            let reason = face_fold(i, j).unwrap_or(FoldReason::Crossed);
            return Err(CyclidicError::Folded {
                face: (i, j),
                reason,
            });
        }
        let mut folded = Vec::new();
        for i in 0..rows - 1 {
            for j in 0..cols - 1 {
                let corners = grid.face(i, j);
                let quad = quad_frame(
                    corners,
                    frames[i * cols + j],
                    (i, j),
                    options.circularity_tolerance,
                )?;
                let local = quad.qb_weights();
                let ids = face_corners(cols, i, j);
                let [a, b, c, d] = ids;
                let inv = w[a].inv();
                // λ, μ: the real factors of W(i+1, j)·W(i, j)⁻¹ and W(i, j+1)·W(i, j)⁻¹.
                let lambda = (w[b] * inv).dot(local[1]);
                let mu = (w[d] * inv).dot(local[3]);
                w[c] = local[2] * (lambda * mu) * w[a];
                let qb = face_weights(&w, ids);
                let fold = (folds.count() > 0)
                    .then(|| face_fold(i, j))
                    .flatten()
                    .or_else(|| quad.arc_fold(&bezier_of(corners, qb)));
                if let Some(reason) = fold {
                    if !options.allow_folded {
                        return Err(CyclidicError::Folded {
                            face: (i, j),
                            reason,
                        });
                    }
                    folded.push(((i, j), reason));
                }
            }
        }
        Ok(CyclidicNet {
            rows,
            cols,
            vertices: grid.vertices.clone(),
            frames,
            weights: w,
            folded,
            circle_tolerance: options.circle_tolerance,
            size: bbox_diagonal(&grid.vertices),
        })
    }

    /// Mesh vertices along `u` (§4.4).
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// Mesh vertices along `v` (§4.4).
    pub fn cols(&self) -> usize {
        self.cols
    }

    /// The patch on face `(i, j)` (§4.4). Its parameters are those of the whole
    /// net, so neighbouring patches agree point for point on shared edges.
    /// Computed from the corners and the vertex weights each time it is asked for.
    ///
    /// # Panics
    /// If `i ≥ rows − 1` or `j ≥ cols − 1`.
    pub fn patch(&self, i: usize, j: usize) -> Patch {
        assert!(i + 1 < self.rows && j + 1 < self.cols, "no face ({i}, {j})");
        let ids = face_corners(self.cols, i, j);
        let corners = ids.map(|v| self.vertices[v]);
        let qb = face_weights(&self.weights, ids);
        Patch {
            corners,
            qb,
            bezier: bezier_of(corners, qb),
            fold: self
                .folded
                .binary_search_by_key(&(i, j), |f| f.0)
                .ok()
                .map(|n| self.folded[n].1),
        }
    }

    /// The frame at vertex `(i, j)` (§4.4).
    pub fn frame(&self, i: usize, j: usize) -> Frame {
        self.frames[i * self.cols + j]
    }

    /// Faces that are folded (only with [`CyclidicOptions::allow_folded`]), with the reason (§4.4).
    pub fn folded(&self) -> Vec<((usize, usize), FoldReason)> {
        self.folded.clone()
    }

    /// The points of patch `(i, j)` on a `k × k` uniform grid of its `(u, v)`,
    /// boundaries included, row-major in `u` (entry `a * k + b` is
    /// `(u, v) = (a, b) / (k − 1)`); `(0, 0)` is vertex `(i, j)`, `u` runs towards
    /// `(i+1, j)` and `v` towards `(i, j+1)` (§4.4).
    ///
    /// # Panics
    /// If `k < 2` or the face does not exist.
    pub fn sample_patch(&self, i: usize, j: usize, k: usize) -> Vec<DVec3> {
        assert!(k >= 2, "sample_patch needs k ≥ 2, got {k}");
        let b = *self.patch(i, j).bezier();
        let t = |a: usize| a as f64 / (k - 1) as f64;
        (0..k * k).map(|n| b.point(t(n / k), t(n % k))).collect()
    }

    /// The whole net sampled as one quad grid (§4.4): `k × k` samples per patch,
    /// `(rows − 1)·(k − 1) + 1 × (cols − 1)·(k − 1) + 1` vertices, shared boundaries
    /// identical, with the exact unit normals of the patches.
    ///
    /// # Panics
    /// If `k < 2`.
    pub fn dense(&self, k: usize) -> QuadGrid {
        assert!(k >= 2, "dense needs k ≥ 2, got {k}");
        let (dr, dc) = ((self.rows - 1) * (k - 1) + 1, (self.cols - 1) * (k - 1) + 1);
        let mut vertices = vec![DVec3::ZERO; dr * dc];
        let mut normals = vec![DVec3::ZERO; dr * dc];
        // Each patch fills its samples but the last row and column, which are the
        // next patch's first, except on the last patch of a row or column.
        let own = |face: usize, n: usize| if face + 2 == n { k } else { k - 1 };
        let t = |a: usize| a as f64 / (k - 1) as f64;
        for i in 0..self.rows - 1 {
            for j in 0..self.cols - 1 {
                let bez = *self.patch(i, j).bezier();
                for a in 0..own(i, self.rows) {
                    for b in 0..own(j, self.cols) {
                        let at = (i * (k - 1) + a) * dc + j * (k - 1) + b;
                        vertices[at] = bez.point(t(a), t(b));
                        normals[at] = bez.normal(t(a), t(b));
                    }
                }
            }
        }
        QuadGrid::new(dr, dc, vertices, normals)
    }

    /// The curvature lines along every mesh line (§4.4, §4.6): first the u-lines
    /// `j = 0 … cols − 1`, then the v-lines `i = 0 … rows − 1`; consecutive arcs on
    /// one circle (to [`CyclidicOptions::circle_tolerance`]) are merged.
    pub fn curvature_lines(&self) -> Vec<CurvatureLine> {
        self.curvature_lines_iter().collect()
    }

    /// The curvature lines of [`CyclidicNet::curvature_lines`] (§4.4, §4.6), one at a
    /// time: for writing them without holding them all.
    pub fn curvature_lines_iter(&self) -> impl Iterator<Item = CurvatureLine> + '_ {
        let tol = self.circle_tolerance;
        let size = self.size;
        let merge = move |arcs: Vec<Arc>| {
            let mut out: Vec<Arc> = Vec::with_capacity(arcs.len());
            for arc in arcs {
                match out.last_mut() {
                    Some(last)
                        if last.center.distance(arc.center) <= tol * size
                            && (last.radius - arc.radius).abs() <= tol * size
                            && last.normal.dot(arc.normal) > 0.0
                            && last.normal.cross(arc.normal).length() <= tol =>
                    {
                        last.end = arc.end
                    }
                    _ => out.push(arc),
                }
            }
            out
        };
        let (fr, fc) = (self.rows - 1, self.cols - 1);
        let u_lines = (0..self.cols).map(move |j| {
            let (pj, b) = if j < fc { (j, 0) } else { (j - 1, 2) };
            let arcs = (0..fr)
                .map(|i| {
                    let pts = self.patch(i, pj).bezier().points;
                    Arc::from_control(pts[0][b], pts[1][b], pts[2][b])
                })
                .collect();
            CurvatureLine {
                family: Family::U,
                index: j,
                arcs: merge(arcs),
            }
        });
        let v_lines = (0..self.rows).map(move |i| {
            let (pi, a) = if i < fr { (i, 0) } else { (i - 1, 2) };
            let arcs = (0..fc)
                .map(|j| {
                    let pts = self.patch(pi, j).bezier().points[a];
                    Arc::from_control(pts[0], pts[1], pts[2])
                })
                .collect();
            CurvatureLine {
                family: Family::V,
                index: i,
                arcs: merge(arcs),
            }
        });
        u_lines.chain(v_lines)
    }

    /// The whole net as one degree-(2, 2) NURBS surface with double interior
    /// knots (§4.4, §5.3): the patches' Bézier forms, each scaled by the squared
    /// norm of its first corner's quaternion weight, so that neighbours share their
    /// edge control points and weights (made from [`CyclidicNet::nurbs_columns`]).
    pub fn nurbs(&self) -> NurbsSurface {
        let (nr, nc) = (2 * self.rows - 1, 2 * self.cols - 1);
        let mut control_points = vec![DVec3::ZERO; nr * nc];
        let mut weights = vec![0.0; nr * nc];
        for (c, (points, w)) in self.nurbs_columns().enumerate() {
            for r in 0..nr {
                control_points[r * nc + c] = points[r];
                weights[r * nc + c] = w[r];
            }
        }
        let (knots_u, knots_v) = self.nurbs_knots();
        NurbsSurface {
            rows: nr,
            cols: nc,
            control_points,
            weights,
            knots_u,
            knots_v,
        }
    }

    /// The control points and weights of [`CyclidicNet::nurbs`] a column
    /// (index along `v`) at a time, each along `u`, computed as they are asked
    /// for (§4.4, §5.3): the surface without holding it. A column of patches
    /// is computed on every core for two columns of control points (it takes
    /// about 300 bytes a patch; the whole surface 32 bytes a control point,
    /// four a face). Where neighbouring patches share a control point, the
    /// later one in row-major order gives it.
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::cyclidic::{CyclidicNet, CyclidicOptions, Frame};
    /// use monge_core::QuadGrid;
    /// let v = (0..3).flat_map(|i| (0..3).map(move |j| DVec3::new(i as f64, j as f64, 0.0))).collect();
    /// let g = QuadGrid::new(3, 3, v, vec![]);
    /// let net = CyclidicNet::from_frame(&g, Frame::new(DVec3::X, DVec3::Y), &CyclidicOptions::default()).unwrap();
    /// let nurbs = net.nurbs();
    /// for (c, (points, weights)) in net.nurbs_columns().enumerate() {
    ///     assert_eq!(points.len(), nurbs.rows);
    ///     assert_eq!(points[2], nurbs.control_points[2 * nurbs.cols + c]);
    ///     assert_eq!(weights[2], nurbs.weights[2 * nurbs.cols + c]);
    /// }
    /// ```
    pub fn nurbs_columns(&self) -> impl Iterator<Item = (Vec<DVec3>, Vec<f64>)> + '_ {
        let (nr, nc) = (2 * self.rows - 1, 2 * self.cols - 1);
        // The patch column last computed, with each patch's weight scale.
        let mut strip: (usize, Vec<(RationalBezier, f64)>) = (usize::MAX, Vec::new());
        // The row (column) of patches that gives control-point row (column)
        // `r`, with `n` vertices that way: the later of two that share it.
        let patch_of = |r: usize, n: usize| (r / 2).min(n - 2);
        (0..nc).map(move |c| {
            let j = patch_of(c, self.cols);
            if strip.0 != j {
                let patches = crate::tasks::map(self.rows - 1, |i| {
                    let scale = self.weights[i * self.cols + j].norm2();
                    (self.patch(i, j).bezier, scale)
                });
                strip = (j, patches);
            }
            let b = c - 2 * j;
            (0..nr)
                .map(|r| {
                    let i = patch_of(r, self.rows);
                    let (bezier, scale) = &strip.1[i];
                    let a = r - 2 * i;
                    (bezier.points[a][b], bezier.weights[a][b] * scale)
                })
                .unzip()
        })
    }

    /// The knots of [`CyclidicNet::nurbs`] along `u` and along `v` (§5.3).
    pub fn nurbs_knots(&self) -> (Vec<f64>, Vec<f64>) {
        (knots(self.rows - 1), knots(self.cols - 1))
    }
}

/// The QB weights of the face of corners `ids` (A, B, C, D, as
/// [`face_corners`]) (§4.4): the vertex weights of A, B, C, D times `W(A)⁻¹`.
fn face_weights(w: &[Quat], [a, b, c, d]: [usize; 4]) -> [Quat; 4] {
    let inv = w[a].inv();
    [Quat::ONE, w[b] * inv, w[c] * inv, w[d] * inv]
}

/// At least one face.
fn check_size(grid: &QuadGrid) -> Result<(), CyclidicError> {
    if grid.rows < 2 || grid.cols < 2 {
        return Err(CyclidicError::TooSmall {
            rows: grid.rows,
            cols: grid.cols,
        });
    }
    Ok(())
}
