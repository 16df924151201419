//! One Dupin cyclide patch on a circular quad (§4.4): its closed QB form and its
//! rational biquadratic Bézier patch.

use glam::DVec3;

use crate::grid::{quad_turn_alone, Turn};

use super::frame::Frame;
use super::quat::{cross_ratio, unit_from, Quat};
use super::{CyclidicError, CyclidicOptions, FoldReason};

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
pub(super) struct QuadFrame {
    corners: [DVec3; 4],
    frame: Frame,
    /// Cross-ratio sign σ.
    sigma: f64,
    /// `|BD| / |AC|`.
    k: f64,
}

impl QuadFrame {
    /// Quaternion weights `W00, W10, W11, W01` (corner order A, B, C, D), `W00 = 1`.
    pub(super) fn qb_weights(&self) -> [Quat; 4] {
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
    pub(super) fn arc_fold(&self, bez: &RationalBezier) -> Option<FoldReason> {
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
pub(super) fn bezier_of(corners: [DVec3; 4], qb: [Quat; 4]) -> RationalBezier {
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
    pub(super) corners: [DVec3; 4],
    /// QB weights in corner order A, B, C, D.
    pub(super) qb: [Quat; 4],
    pub(super) bezier: RationalBezier,
    pub(super) fold: Option<FoldReason>,
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
pub(super) fn quad_frame(
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
