//! Cyclidic nets (§4.4): one Dupin cyclide patch on every face of a circular mesh.
//!
//! Neighbouring patches share their boundary arcs and their tangent planes (C¹),
//! every curvature line of the net is a chain of circular arcs, and on a circular
//! mesh with planar lines, with the frames of §4.4, those chains are planar (§4.4),
//! one circle or an n-arc when a guide is (§4.6, Proposition 4).
//!
//! Each patch is the quaternionic bilinear (QB) patch
//! `F(u,v) = N(u,v)·D(u,v)⁻¹`, `N = Σ p_ij W_ij B_i(u) B_j(v)`, `D = Σ W_ij B_i(u) B_j(v)`
//! (points are imaginary quaternions), and equally an exact rational biquadratic
//! Bézier patch. The whole net is one degree-(2,2) NURBS surface with double
//! interior knots (§5.3). Conventions: face `(i, j)` has corners
//! `A = (i, j)`, `B = (i+1, j)`, `C = (i+1, j+1)`, `D = (i, j+1)`; its parameter `u`
//! runs from `A` towards `B`, `v` from `A` towards `D`.

use std::fmt;
use std::ops::{Add, Mul, Neg, Sub};

use glam::DVec3;

use crate::bspline;
use crate::grid::{bbox_diagonal, face_corners, quad_turn_alone, QuadGrid, Turn};

/// An orthonormal frame at a mesh vertex (§4.4): `t1` along the u-arc, `t2`
/// along the v-arc, `n = t1 × t2`.
///
/// ```
/// use glam::DVec3;
/// use monge_core::cyclidic::{Family, Frame};
/// let f = Frame::new(DVec3::X, DVec3::Y);
/// assert_eq!(f.n, DVec3::Z);
/// // Carried over a u-edge from the origin to (2, 0, 0): t1 turns back to point along the arc.
/// let g = f.carried(DVec3::ZERO, DVec3::new(2.0, 0.0, 0.0), Family::U);
/// assert_eq!((g.t1, g.t2, g.n), (DVec3::X, DVec3::Y, DVec3::Z));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// Unit tangent of the arc towards vertex `(i+1, j)` (§4.4).
    pub t1: DVec3,
    /// Unit tangent of the arc towards vertex `(i, j+1)` (§4.4).
    pub t2: DVec3,
    /// `t1 × t2`, the normal of the net at the vertex (§4.4).
    pub n: DVec3,
}

impl Frame {
    /// The frame `(t1, t2, t1 × t2)` (§4.4); `t1`, `t2` should be orthonormal.
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::cyclidic::Frame;
    /// assert_eq!(Frame::new(DVec3::Y, DVec3::Z).n, DVec3::X);
    /// ```
    pub fn new(t1: DVec3, t2: DVec3) -> Frame {
        Frame {
            t1,
            t2,
            n: t1.cross(t2),
        }
    }

    /// The frame carried over the edge `from → to` of a family-`family` line (§4.4):
    /// reflected in the perpendicular-bisector plane of the edge, with the tangent
    /// along the edge turned back so that it again points forward along its line.
    /// Over a `U` edge (`(i, j) → (i+1, j)`) `t1` is turned, over a `V` edge `t2`.
    /// Carrying backwards (`to → from`) turns the tangent the same way.
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::cyclidic::{Family, Frame};
    /// let f = Frame::new(DVec3::new(1.0, 1.0, 0.0).normalize(), DVec3::Z.cross(DVec3::new(1.0, 1.0, 0.0)).normalize());
    /// let g = f.carried(DVec3::ZERO, DVec3::X, Family::U);
    /// // t1 at the end of a quarter circle: the tangent turned by 90°.
    /// assert!((g.t1 - DVec3::new(1.0, -1.0, 0.0).normalize()).length() < 1e-15);
    /// ```
    pub fn carried(&self, from: DVec3, to: DVec3, family: Family) -> Frame {
        let e = (to - from).normalize();
        let s = |x: DVec3| x - 2.0 * x.dot(e) * e;
        let (t1, t2) = match family {
            Family::U => (-s(self.t1), s(self.t2)),
            Family::V => (s(self.t1), -s(self.t2)),
        };
        Frame {
            t1,
            t2,
            n: s(self.n),
        }
    }
}

/// The two families of curvature lines of a net (§4.4).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Family {
    /// Lines along guide_u: `j` fixed, `i` running (the net's `u` direction).
    U,
    /// Lines along guide_v: `i` fixed, `j` running (the net's `v` direction).
    V,
}

impl fmt::Display for Family {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Family::U => "u-line (along guide_u, fixed j)",
            Family::V => "v-line (along guide_v, fixed i)",
        })
    }
}

/// Why a quad is folded (§4.4, §5.2). In a net, whether a face is folded is
/// decided as for every mesh, by [`QuadGrid::folds`] (crossed or turned over);
/// the arc and weight reasons are those of a patch whose frame, not its face,
/// turns it over.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FoldReason {
    /// The corners do not all turn the same way ([`Turn::Crossed`]): the quad is
    /// a bow-tie (two of its edges cross) or is not convex.
    Crossed,
    /// The face turns the other way than most faces of its mesh about their
    /// node axes: the mesh folds back over itself there ([`QuadGrid::folds`]).
    TurnedOver,
    /// The arc of an edge turns by 180° or more: the frame tangent at the
    /// edge's start points away from the edge (`tangent · edge = cos(half arc)` ≤ 0).
    ArcOver180 {
        /// The edge: `"AB"`, `"AD"`, `"BC"` or `"DC"`.
        edge: &'static str,
        /// The cosine of half the arc's angle.
        cos_half: f64,
    },
    /// The centre weight of the Bézier form is not positive.
    CentreWeight {
        /// The weight (relative to the corner weight at A).
        weight: f64,
    },
}

impl fmt::Display for FoldReason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FoldReason::Crossed => f.write_str(
                "its corners do not all turn the same way (two of its edges cross like a bow-tie, or it \
                 is not convex)",
            ),
            FoldReason::TurnedOver => f.write_str(
                "it turns the other way than most faces about their node axes (the mesh folds back \
                 over itself there)",
            ),
            FoldReason::ArcOver180 { edge, cos_half } => write!(
                f,
                "the arc of edge {edge} turns by {:.3}° (over 180°: cos of half the arc = {cos_half:.3e})",
                2.0 * cos_half.clamp(-1.0, 1.0).acos().to_degrees()
            ),
            FoldReason::CentreWeight { weight } => write!(
                f,
                "the centre weight of its Bézier form is {weight:.3e} (not positive)"
            ),
        }
    }
}

/// What stops a cyclidic net from being built (§4.4).
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum CyclidicError {
    /// The mesh has no face.
    #[error(
        "the mesh has {rows} × {cols} vertices and no face: a cyclidic net needs at least 2 × 2 vertices"
    )]
    TooSmall {
        /// Vertices along guide_u.
        rows: usize,
        /// Vertices along guide_v.
        cols: usize,
    },
    /// §4.4 frames need the node axes (the Gauss map) and the mesh has none.
    #[error(
        "the mesh carries no normals, so the frames of §4.4 cannot be computed from its Gauss map: \
         build the net from one given frame instead (`monge smooth --frame`, `CyclidicNet::from_frame`)"
    )]
    NoNormals,
    /// Both families have lines of only 2 vertices, so no Gauss circle is known.
    #[error(
        "the mesh has {rows} × {cols} vertices: with fewer than 3 vertices along both families the \
         planes of the Gauss circles are not determined. Use a mesh with 3 or more vertices along one \
         family, or give one frame (`monge smooth --frame`, `CyclidicNet::from_frame`)"
    )]
    GaussUndetermined {
        /// Vertices along guide_u.
        rows: usize,
        /// Vertices along guide_v.
        cols: usize,
    },
    /// The Gauss points of a line are (nearly) collinear, so its plane is unknown.
    #[error(
        "the Gauss map of {family} {index} does not span a plane: the normals of its first, middle and \
         last vertices are (nearly) collinear points, the sine of the angle at the first between the \
         other two being {sine:.1e} (below 1e-12; NaN if two coincide). The line is straight or its \
         normals do not turn. \
         Give one frame instead (`monge smooth --frame`, `CyclidicNet::from_frame`)"
    )]
    GaussLineDegenerate {
        /// The family of the line.
        family: Family,
        /// Its index (`j` for a u-line, `i` for a v-line).
        index: usize,
        /// Sine of the angle at the first Gauss point between the chords to the
        /// middle and the last (0 when the three are collinear; NaN if two coincide).
        sine: f64,
    },
    /// The two Gauss circles through a vertex are not orthogonal: the mesh is not
    /// a circular mesh with planar lines (or its normals are not its Gauss map).
    #[error(
        "at vertex ({}, {}) the tangents of the two Gauss circles make {angle_deg:.6}°, not 90° \
         (tolerance {tolerance_deg:.1e}°): the normals are not the Gauss map of a circular mesh with \
         planar lines (§2.2). Give one frame instead (`monge smooth --frame`, `CyclidicNet::from_frame`)",
        vertex.0, vertex.1
    )]
    GaussNotOrthogonal {
        /// The vertex `(i, j)`.
        vertex: (usize, usize),
        /// Angle between the tangents, degrees.
        angle_deg: f64,
        /// The tolerance, degrees.
        tolerance_deg: f64,
    },
    /// The given frame is not orthonormal.
    #[error(
        "the given frame is not orthonormal: |t1| − 1 = {t1_len:.1e}, |t2| − 1 = {t2_len:.1e}, \
         t1·t2 = {dot:.1e} (tolerance 1e-9). Normalise t1 and t2 and make them orthogonal"
    )]
    FrameNotOrthonormal {
        /// `|t1| − 1`.
        t1_len: f64,
        /// `|t2| − 1`.
        t2_len: f64,
        /// `t1 · t2`.
        dot: f64,
    },
    /// A face is not inscribed in a circle, so it carries no Dupin cyclide patch.
    #[error(
        "face ({}, {}) is not circular: its cross-ratio is off the real line by an angle of {deviation:.3e} rad \
         (tolerance {tolerance:.1e}). A cyclidic net needs a circular mesh (§2.2); raise \
         the tolerance if the mesh is only nearly circular (`monge smooth --circularity-tol`, \
         `CyclidicOptions::circularity_tolerance`)",
        face.0, face.1
    )]
    NotCircular {
        /// The face `(i, j)`.
        face: (usize, usize),
        /// `|Im q| / |q|` for the cross-ratio `q` of the corners.
        deviation: f64,
        /// The tolerance.
        tolerance: f64,
    },
    /// A face is folded.
    #[error(
        "face ({}, {}) is folded (§5.2, the fold `monge generate` and `monge check` count): {reason}. \
         A Dupin cyclide patch on it would cross itself or its neighbours; this happens for some θ with \
         tight curvature. Change θ or the guides, or build it anyway \
         (`monge smooth --allow-folded`, Python `allow_folded=True`, `CyclidicOptions::allow_folded`)",
        face.0, face.1
    )]
    Folded {
        /// The face `(i, j)`.
        face: (usize, usize),
        /// What is folded.
        reason: FoldReason,
    },
}

/// Options of [`CyclidicNet`] (§4.4).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CyclidicOptions {
    /// Build folded quads instead of refusing them. Default `false`.
    pub allow_folded: bool,
    /// Largest accepted `|Im q| / |q|` of the cross-ratio `q` of a face's corners. Default `1e-8`.
    pub circularity_tolerance: f64,
    /// Consecutive arcs of a curvature line are reported as one arc when their
    /// centres and radii agree to this fraction of the net's size and their
    /// normals to this angle (rad). Default `1e-9`.
    pub circle_tolerance: f64,
}

impl Default for CyclidicOptions {
    fn default() -> Self {
        CyclidicOptions {
            allow_folded: false,
            circularity_tolerance: 1e-8,
            circle_tolerance: 1e-9,
        }
    }
}

/// A quaternion `w + v` (a point or vector is the imaginary quaternion `0 + v`).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Quat {
    w: f64,
    v: DVec3,
}

impl Quat {
    const ONE: Quat = Quat {
        w: 1.0,
        v: DVec3::ZERO,
    };

    fn pure(v: DVec3) -> Quat {
        Quat { w: 0.0, v }
    }

    fn conj(self) -> Quat {
        Quat {
            w: self.w,
            v: -self.v,
        }
    }

    fn norm2(self) -> f64 {
        self.w * self.w + self.v.length_squared()
    }

    fn inv(self) -> Quat {
        self.conj() * (1.0 / self.norm2())
    }

    /// The Euclidean inner product in ℝ⁴.
    fn dot(self, o: Quat) -> f64 {
        self.w * o.w + self.v.dot(o.v)
    }
}

impl Mul for Quat {
    type Output = Quat;
    fn mul(self, o: Quat) -> Quat {
        Quat {
            w: self.w * o.w - self.v.dot(o.v),
            v: self.w * o.v + o.w * self.v + self.v.cross(o.v),
        }
    }
}

impl Mul<f64> for Quat {
    type Output = Quat;
    fn mul(self, s: f64) -> Quat {
        Quat {
            w: self.w * s,
            v: self.v * s,
        }
    }
}

impl Add for Quat {
    type Output = Quat;
    fn add(self, o: Quat) -> Quat {
        Quat {
            w: self.w + o.w,
            v: self.v + o.v,
        }
    }
}

impl Sub for Quat {
    type Output = Quat;
    fn sub(self, o: Quat) -> Quat {
        Quat {
            w: self.w - o.w,
            v: self.v - o.v,
        }
    }
}

impl Neg for Quat {
    type Output = Quat;
    fn neg(self) -> Quat {
        self * -1.0
    }
}

/// The cross-ratio `(A−C)(C−B)⁻¹(B−D)(D−A)⁻¹` of a quad's corners (real for concyclic points).
fn cross_ratio([a, b, c, d]: [DVec3; 4]) -> Quat {
    let p = |x: DVec3| Quat::pure(x);
    p(a - c) * p(c - b).inv() * p(b - d) * p(d - a).inv()
}

/// `(x − y) / |x − y|`.
fn unit_from(x: DVec3, y: DVec3) -> DVec3 {
    (y - x).normalize()
}

/// The quadratic Bernstein basis at `t` and its derivative.
fn bernstein2(t: f64) -> ([f64; 3], [f64; 3]) {
    let s = 1.0 - t;
    (
        [s * s, 2.0 * s * t, t * t],
        [-2.0 * s, 2.0 * (s - t), 2.0 * t],
    )
}

/// An exact rational biquadratic Bézier patch (§4.4, §5.3): control point
/// `points[a][b]` with weight `weights[a][b]`, `a` along `u`, `b` along `v`.
///
/// ```
/// use glam::DVec3;
/// use monge_core::cyclidic::{Frame, Patch};
/// let quad = [DVec3::ZERO, DVec3::X, DVec3::X + DVec3::Y, DVec3::Y];
/// let p = Patch::new(quad, Frame::new(DVec3::X, DVec3::Y)).unwrap();
/// let b = p.bezier();
/// assert!((b.point(0.5, 0.5) - DVec3::new(0.5, 0.5, 0.0)).length() < 1e-15);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RationalBezier {
    /// Control points, `[a][b]` (§4.4).
    pub points: [[DVec3; 3]; 3],
    /// Weights, `[a][b]` (§4.4).
    pub weights: [[f64; 3]; 3],
}

impl RationalBezier {
    /// The point at `(u, v)` (§4.4).
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::cyclidic::{Frame, Patch};
    /// let quad = [DVec3::ZERO, DVec3::X, DVec3::X + DVec3::Y, DVec3::Y];
    /// let b = *Patch::new(quad, Frame::new(DVec3::X, DVec3::Y)).unwrap().bezier();
    /// assert_eq!(b.point(1.0, 0.0), DVec3::X);
    /// ```
    pub fn point(&self, u: f64, v: f64) -> DVec3 {
        self.derivatives(u, v).0
    }

    /// The point and its exact first derivatives `(S, ∂S/∂u, ∂S/∂v)` at `(u, v)` (§4.4).
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::cyclidic::{Frame, Patch};
    /// let quad = [DVec3::ZERO, DVec3::X, DVec3::X + DVec3::Y, DVec3::Y];
    /// let b = *Patch::new(quad, Frame::new(DVec3::X, DVec3::Y)).unwrap().bezier();
    /// let (_, su, sv) = b.derivatives(0.0, 0.0);
    /// assert!(su.cross(DVec3::X).length() < 1e-15 && sv.cross(DVec3::Y).length() < 1e-15);
    /// ```
    pub fn derivatives(&self, u: f64, v: f64) -> (DVec3, DVec3, DVec3) {
        let (bu, du) = bernstein2(u);
        let (bv, dv) = bernstein2(v);
        let (mut h, mut hu, mut hv) = (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
        let (mut w, mut wu, mut wv) = (0.0, 0.0, 0.0);
        for a in 0..3 {
            for b in 0..3 {
                let wt = self.weights[a][b];
                let p = self.points[a][b] * wt;
                h += p * (bu[a] * bv[b]);
                hu += p * (du[a] * bv[b]);
                hv += p * (bu[a] * dv[b]);
                w += wt * bu[a] * bv[b];
                wu += wt * du[a] * bv[b];
                wv += wt * bu[a] * dv[b];
            }
        }
        let s = h / w;
        (s, (hu - wu * s) / w, (hv - wv * s) / w)
    }

    /// The unit normal `∂S/∂u × ∂S/∂v`, normalised, at `(u, v)` (§4.4).
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::cyclidic::{Frame, Patch};
    /// let quad = [DVec3::ZERO, DVec3::X, DVec3::X + DVec3::Y, DVec3::Y];
    /// let b = *Patch::new(quad, Frame::new(DVec3::X, DVec3::Y)).unwrap().bezier();
    /// assert!((b.normal(0.3, 0.6) - DVec3::Z).length() < 1e-15);
    /// ```
    pub fn normal(&self, u: f64, v: f64) -> DVec3 {
        let (_, su, sv) = self.derivatives(u, v);
        su.cross(sv).normalize()
    }
}

/// The quantities of a circular quad with a frame at its first corner (§4.4).
struct QuadFrame {
    corners: [DVec3; 4],
    frame: Frame,
    /// Cross-ratio sign σ.
    sigma: f64,
    /// `|BD| / |AC|`.
    k: f64,
}

impl QuadFrame {
    /// Quaternion weights `W00, W10, W11, W01` (corner order A, B, C, D), `W00 = 1`.
    fn qb_weights(&self) -> [Quat; 4] {
        let [a, b, c, d] = self.corners;
        let (e1, e2, f) = (unit_from(a, b), unit_from(a, d), unit_from(b, c));
        let p = Quat::pure;
        [
            Quat::ONE,
            -(p(e1) * p(self.frame.t1)),
            p(f) * p(e1) * p(self.frame.n) * (self.sigma * self.k),
            -(p(e2) * p(self.frame.t2)),
        ]
    }

    /// The first fold of this quad alone, if any (§4.4): crossed corners
    /// ([`quad_turn_alone`]), then [`QuadFrame::arc_fold`].
    fn fold(&self, bez: &RationalBezier) -> Option<FoldReason> {
        if quad_turn_alone(&self.corners) == Turn::Crossed {
            return Some(FoldReason::Crossed);
        }
        self.arc_fold(bez)
    }

    /// How the frame turns the patch over, if it does (§4.4): an arc of 180°
    /// or more, or a non-positive centre weight.
    fn arc_fold(&self, bez: &RationalBezier) -> Option<FoldReason> {
        let wt = bez.weights;
        // A rational quadratic arc with weights w0, w1, w2 turns by 2·acos(w1 / √(w0 w2)).
        let cos = |w0: f64, w1: f64, w2: f64| w1 / (w0 * w2).sqrt();
        let edges = [
            ("AB", cos(wt[0][0], wt[1][0], wt[2][0])),
            ("AD", cos(wt[0][0], wt[0][1], wt[0][2])),
            ("BC", cos(wt[2][0], wt[2][1], wt[2][2])),
            ("DC", cos(wt[0][2], wt[1][2], wt[2][2])),
        ];
        if let Some(&(edge, cos_half)) = edges.iter().find(|(_, c)| *c <= 0.0 || c.is_nan()) {
            return Some(FoldReason::ArcOver180 { edge, cos_half });
        }
        (wt[1][1] <= 0.0 || wt[1][1].is_nan())
            .then_some(FoldReason::CentreWeight { weight: wt[1][1] })
    }
}

/// The rational biquadratic Bézier form of the QB patch with corners `[A, B, C, D]`
/// and quaternion weights `qb` in the same order (§4.4): the Bernstein coefficients
/// of `|D|²` (the weights) and of `N·D̄` (weight × control point). With `W00 = 1`,
/// `|W10| = |W01| = 1` they are the design note's closed forms, centre included.
fn bezier_of(corners: [DVec3; 4], qb: [Quat; 4]) -> RationalBezier {
    // Corner (a, b) of the parameter square is corners[CORNER[a][b]].
    let at = |a: usize, b: usize| CORNER[a][b];
    // Index pairs (i, k) with i + k = s, for the degree-2 Bernstein index s.
    const PAIRS: [&[(usize, usize)]; 3] = [&[(0, 0)], &[(0, 1), (1, 0)], &[(1, 1)]];
    let mut points = [[DVec3::ZERO; 3]; 3];
    let mut weights = [[0.0; 3]; 3];
    for s in 0..3 {
        for t in 0..3 {
            let (mut num, mut den) = (Quat::pure(DVec3::ZERO), Quat::pure(DVec3::ZERO));
            for &(i, k) in PAIRS[s] {
                for &(j, l) in PAIRS[t] {
                    let (c, d) = (at(i, j), at(k, l));
                    let prod = qb[c] * qb[d].conj();
                    num = num + Quat::pure(corners[c]) * prod;
                    den = den + prod;
                }
            }
            // The mean over the pairs; den is real (its pairs are conjugate), num imaginary.
            let m = (PAIRS[s].len() * PAIRS[t].len()) as f64;
            weights[s][t] = den.w / m;
            points[s][t] = num.v / den.w;
        }
    }
    RationalBezier { points, weights }
}

/// Corner `(a, b)` of the parameter square is `corners[CORNER[a][b]]` (corners A, B, C, D).
const CORNER: [[usize; 2]; 2] = [[0, 3], [1, 2]];

/// One Dupin cyclide patch on a circular quad (§4.4), in closed QB form and as a
/// rational biquadratic Bézier patch.
///
/// ```
/// use glam::DVec3;
/// use monge_core::cyclidic::{Frame, Patch};
/// // A square with the frame along its edges is a flat patch.
/// let quad = [DVec3::ZERO, DVec3::X, DVec3::X + DVec3::Y, DVec3::Y];
/// let p = Patch::new(quad, Frame::new(DVec3::X, DVec3::Y)).unwrap();
/// assert!((p.point(0.25, 0.5) - DVec3::new(0.25, 0.5, 0.0)).length() < 1e-15);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Patch {
    corners: [DVec3; 4],
    /// QB weights in corner order A, B, C, D.
    qb: [Quat; 4],
    bezier: RationalBezier,
    fold: Option<FoldReason>,
}

impl Patch {
    /// The patch on the circular quad `corners = [A, B, C, D]` (A → B along `u`,
    /// A → D along `v`) with the frame `frame` at A (§4.4): its boundary arcs at A are
    /// tangent to `frame.t1` and `frame.t2`. Folded quads are built (see [`Patch::fold`]).
    ///
    /// # Errors
    /// [`CyclidicError::NotCircular`] (face `(0, 0)`) if the corners are not
    /// concyclic to 1e-8.
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::cyclidic::{Frame, Patch};
    /// let quad = [DVec3::ZERO, DVec3::X, DVec3::X + DVec3::Y, DVec3::Y];
    /// let p = Patch::new(quad, Frame::new(DVec3::X, DVec3::Y)).unwrap();
    /// assert_eq!(p.corners(), quad);
    /// ```
    pub fn new(corners: [DVec3; 4], frame: Frame) -> Result<Patch, CyclidicError> {
        let quad = quad_frame(
            corners,
            frame,
            (0, 0),
            CyclidicOptions::default().circularity_tolerance,
        )?;
        let qb = quad.qb_weights();
        let bezier = bezier_of(corners, qb);
        Ok(Patch {
            corners,
            qb,
            fold: quad.fold(&bezier),
            bezier,
        })
    }

    /// The corners `[A, B, C, D]` (§4.4).
    pub fn corners(&self) -> [DVec3; 4] {
        self.corners
    }

    /// The point at `(u, v)` from the closed QB form `F = Im(N·D̄)/|D|²` (§4.4).
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::cyclidic::{Frame, Patch};
    /// let quad = [DVec3::ZERO, DVec3::X, DVec3::X + DVec3::Y, DVec3::Y];
    /// let p = Patch::new(quad, Frame::new(DVec3::X, DVec3::Y)).unwrap();
    /// assert_eq!(p.point(1.0, 1.0), DVec3::X + DVec3::Y);
    /// ```
    pub fn point(&self, u: f64, v: f64) -> DVec3 {
        let bu = [1.0 - u, u];
        let bv = [1.0 - v, v];
        let (mut num, mut den) = (Quat::pure(DVec3::ZERO), Quat::pure(DVec3::ZERO));
        for a in 0..2 {
            for b in 0..2 {
                let c = CORNER[a][b];
                let wq = self.qb[c] * (bu[a] * bv[b]);
                num = num + Quat::pure(self.corners[c]) * wq;
                den = den + wq;
            }
        }
        (num * den.conj()).v / den.norm2()
    }

    /// The same patch as an exact rational biquadratic Bézier patch (§4.4, §5.3).
    pub fn bezier(&self) -> &RationalBezier {
        &self.bezier
    }

    /// Why the quad is folded, or `None` for an embedded patch (§4.4, §5.2).
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::cyclidic::{Frame, FoldReason, Patch};
    /// let bow_tie = [DVec3::ZERO, DVec3::X + DVec3::Y, DVec3::X, DVec3::Y];
    /// let p = Patch::new(bow_tie, Frame::new(DVec3::X, DVec3::Y)).unwrap();
    /// assert_eq!(p.fold(), Some(FoldReason::Crossed));
    /// ```
    pub fn fold(&self) -> Option<FoldReason> {
        self.fold
    }
}

/// Check a quad's circularity and compute σ and k (§4.4).
fn quad_frame(
    corners: [DVec3; 4],
    frame: Frame,
    face: (usize, usize),
    tolerance: f64,
) -> Result<QuadFrame, CyclidicError> {
    let q = cross_ratio(corners);
    let deviation = q.v.length() / q.norm2().sqrt();
    if deviation.is_nan() || deviation > tolerance {
        return Err(CyclidicError::NotCircular {
            face,
            deviation,
            tolerance,
        });
    }
    let [a, b, c, d] = corners;
    Ok(QuadFrame {
        corners,
        frame,
        sigma: if q.w < 0.0 { -1.0 } else { 1.0 },
        k: b.distance(d) / a.distance(c),
    })
}

/// A circular arc of a curvature line (§4.4, §4.6): from `start` to `end`,
/// turning positively (right-hand rule) about `normal` around `center`.
///
/// ```
/// use glam::DVec3;
/// use monge_core::cyclidic::Arc;
/// let a = Arc { center: DVec3::ZERO, radius: 1.0, normal: DVec3::Z, start: DVec3::X, end: DVec3::Y };
/// assert!((a.sweep() - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Arc {
    /// Centre of the circle (§4.4).
    pub center: DVec3,
    /// Radius (§4.4).
    pub radius: f64,
    /// Unit normal of the circle's plane, oriented so that the arc turns positively about it.
    pub normal: DVec3,
    /// First point (a mesh vertex).
    pub start: DVec3,
    /// Last point (a mesh vertex).
    pub end: DVec3,
}

impl Arc {
    /// The angle swept from `start` to `end`, in `[0, 2π)` radians (§4.6).
    pub fn sweep(&self) -> f64 {
        let (x, y) = (self.start - self.center, self.end - self.center);
        let s = libm::atan2(self.normal.dot(x.cross(y)), x.dot(y));
        if s < 0.0 {
            s + std::f64::consts::TAU
        } else {
            s
        }
    }

    /// The point a fraction `t ∈ [0, 1]` of the way along the arc (§4.6): `start`
    /// turned by `t · sweep` about `normal` around `center`, exactly on the circle.
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::cyclidic::Arc;
    /// let a = Arc { center: DVec3::ZERO, radius: 1.0, normal: DVec3::Z, start: DVec3::X, end: DVec3::Y };
    /// let half = a.point(0.5);
    /// assert!((half - DVec3::new(1.0, 1.0, 0.0) / 2f64.sqrt()).length() < 1e-15);
    /// assert!((a.point(1.0) - a.end).length() < 1e-15);
    /// ```
    pub fn point(&self, t: f64) -> DVec3 {
        let x = self.start - self.center;
        let y = self.normal.cross(x);
        let (s, c) = libm::sincos(t * self.sweep());
        self.center + c * x + s * y
    }

    /// The arc through `p0` and `p2` tangent to `p1 − p0` at `p0`.
    fn from_control(p0: DVec3, p1: DVec3, p2: DVec3) -> Arc {
        let t = (p1 - p0).normalize();
        let d = p2 - p0;
        let normal = t.cross(d).normalize();
        let s = normal.cross(t);
        let radius = d.length_squared() / (2.0 * d.dot(s));
        Arc {
            center: p0 + radius * s,
            radius,
            normal,
            start: p0,
            end: p2,
        }
    }
}

/// The curvature line of a net along one mesh line, as a chain of circular arcs (§4.4, §4.6).
#[derive(Clone, Debug, PartialEq)]
pub struct CurvatureLine {
    /// Its family.
    pub family: Family,
    /// Its index: `j` for a u-line, `i` for a v-line.
    pub index: usize,
    /// The arcs, consecutive arcs on one circle merged: one arc for a line
    /// inscribed in a circle, two for a bi-arc (§4.6).
    pub arcs: Vec<Arc>,
}

/// The whole net as one NURBS surface of degree (2, 2) with double interior knots (§4.4, §5.3).
///
/// Control point `(a, b)` is `control_points[a * cols + b]`; vertex `(i, j)` of
/// the mesh is control point `(2i, 2j)`. Parameter `u ∈ [0, rows_mesh − 1]`, and
/// `(u, v) = (i + s, j + t)` is the point `(s, t)` of patch `(i, j)`.
#[derive(Clone, Debug, PartialEq)]
pub struct NurbsSurface {
    /// Control points along `u`: `2·(mesh rows) − 1`.
    pub rows: usize,
    /// Control points along `v`: `2·(mesh cols) − 1`.
    pub cols: usize,
    /// Control points, row-major.
    pub control_points: Vec<DVec3>,
    /// Positive weights, row-major.
    pub weights: Vec<f64>,
    /// Knots along `u`: `[0, 0, 0, 1, 1, 2, 2, …, m, m, m]`.
    pub knots_u: Vec<f64>,
    /// Knots along `v`.
    pub knots_v: Vec<f64>,
}

/// Degree of both directions of [`NurbsSurface`].
pub const NURBS_DEGREE: usize = 2;

impl NurbsSurface {
    /// The point at `(u, v)` by the rational Cox–de Boor recursion (§5.3).
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::cyclidic::{CyclidicNet, CyclidicOptions, Frame};
    /// use monge_core::QuadGrid;
    /// let g = QuadGrid::new(2, 2, vec![DVec3::ZERO, DVec3::Y, DVec3::X, DVec3::X + DVec3::Y], vec![]);
    /// let net = CyclidicNet::from_frame(&g, Frame::new(DVec3::X, DVec3::Y), &CyclidicOptions::default()).unwrap();
    /// assert!((net.nurbs().point(0.5, 0.5) - DVec3::new(0.5, 0.5, 0.0)).length() < 1e-15);
    /// ```
    pub fn point(&self, u: f64, v: f64) -> DVec3 {
        let (su, nu) = basis(&self.knots_u, u);
        let (sv, nv) = basis(&self.knots_v, v);
        let (mut h, mut w) = (DVec3::ZERO, 0.0);
        for (a, ba) in nu.iter().enumerate() {
            for (b, bb) in nv.iter().enumerate() {
                let idx = (su - NURBS_DEGREE + a) * self.cols + (sv - NURBS_DEGREE + b);
                let wt = self.weights[idx] * ba * bb;
                h += self.control_points[idx] * wt;
                w += wt;
            }
        }
        h / w
    }
}

/// The knot span `s` of `t` and the three quadratic B-spline basis functions
/// non-zero there ([`bspline::span`], [`bspline::basis`]).
fn basis(knots: &[f64], t: f64) -> (usize, [f64; 3]) {
    let span = bspline::span(knots, NURBS_DEGREE, t);
    let mut n = [0.0; NURBS_DEGREE + 1];
    bspline::basis(knots, span, t, &mut n);
    (span, n)
}

/// A cyclidic net: one Dupin cyclide patch per face of a circular mesh (§4.4).
///
/// ```
/// use monge_core::cyclidic::{CyclidicNet, CyclidicOptions};
/// use monge_core::design::ArcSpec;
/// use monge_core::{generate, Design, GenerateOptions, GuideSpec};
/// let arc = |center, normal, angle_deg| GuideSpec {
///     arc: Some(ArcSpec { center, start: [0.0; 3], normal, angle_deg, samples: 4 }),
///     ..Default::default()
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

/// `[0, 0, 0, 1, 1, …, m − 1, m − 1, m, m, m]`.
fn knots(m: usize) -> Vec<f64> {
    let mut k = vec![0.0; 3];
    for s in 1..m {
        k.extend([s as f64; 2]);
    }
    k.extend([m as f64; 3]);
    k
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

/// Largest angle, in degrees, accepted between the two Gauss-circle tangents
/// and 90° in [`CyclidicNet::from_normals`].
const GAUSS_ORTHOGONALITY_DEG: f64 = 1e-6;

/// The frames of §4.4 from the Gauss map of a circular mesh with planar lines.
fn gauss_frames(grid: &QuadGrid) -> Result<Vec<Frame>, CyclidicError> {
    let (rows, cols) = (grid.rows, grid.cols);
    if grid.normals.is_empty() {
        return Err(CyclidicError::NoNormals);
    }
    if rows < 3 && cols < 3 {
        return Err(CyclidicError::GaussUndetermined { rows, cols });
    }
    let n = |i: usize, j: usize| grid.normals[i * cols + j];
    // Plane normal of the Gauss circle through the first, middle and last Gauss points.
    let plane = |family: Family, index: usize, pts: [DVec3; 3]| {
        let c = (pts[1] - pts[0]).cross(pts[2] - pts[0]);
        let sine = c.length() / (pts[1] - pts[0]).length() / (pts[2] - pts[0]).length();
        if sine > 1e-12 {
            Ok(c.normalize())
        } else {
            Err(CyclidicError::GaussLineDegenerate {
                family,
                index,
                sine,
            })
        }
    };
    let m1: Vec<Option<DVec3>> = (0..cols)
        .map(|j| {
            (rows >= 3)
                .then(|| plane(Family::U, j, [n(0, j), n(rows / 2, j), n(rows - 1, j)]))
                .transpose()
        })
        .collect::<Result<_, _>>()?;
    let m2: Vec<Option<DVec3>> = (0..rows)
        .map(|i| {
            (cols >= 3)
                .then(|| plane(Family::V, i, [n(i, 0), n(i, cols / 2), n(i, cols - 1)]))
                .transpose()
        })
        .collect::<Result<_, _>>()?;
    // Orient a tangent along the mesh line: towards the next vertex (or from the previous one).
    let forward = |t: DVec3, x: &dyn Fn(usize) -> DVec3, at: usize, len: usize| {
        let d = if at + 1 < len {
            x(at + 1) - x(at)
        } else {
            x(at) - x(at - 1)
        };
        if t.dot(d) < 0.0 {
            -t
        } else {
            t
        }
    };
    let mut frames = Vec::with_capacity(rows * cols);
    for (i, m2) in m2.iter().enumerate() {
        for (j, m1) in m1.iter().enumerate() {
            let nv = n(i, j);
            let t1 = m1.map(|m| m.cross(nv).normalize());
            let t2 = m2.map(|m| m.cross(nv).normalize());
            let (t1, t2) = match (t1, t2) {
                (Some(a), Some(b)) => (a, b),
                (Some(a), None) => (a, nv.cross(a).normalize()),
                (None, Some(b)) => (b.cross(nv).normalize(), b),
                (None, None) => unreachable!("rows ≥ 3 or cols ≥ 3"),
            };
            let t1 = forward(t1, &|r| grid.vertex(r, j), i, rows);
            let t2 = forward(t2, &|c| grid.vertex(i, c), j, cols);
            let cos = t1.dot(t2);
            if cos.abs() > GAUSS_ORTHOGONALITY_DEG.to_radians().sin() || cos.is_nan() {
                return Err(CyclidicError::GaussNotOrthogonal {
                    vertex: (i, j),
                    angle_deg: cos.clamp(-1.0, 1.0).acos().to_degrees(),
                    tolerance_deg: GAUSS_ORTHOGONALITY_DEG,
                });
            }
            frames.push(Frame::new(t1, t2));
        }
    }
    Ok(frames)
}
