//! Darboux's construction (§2.1.1, Figure 2): a smooth surface with planar
//! curvature lines as the envelope of the radical planes of two families of
//! spheres centred on focal parabolas. Independent of the generator; used to
//! cross-check it.
//!
//! With a scale `p > 0`, the two focal parabolas are
//!
//! * `c1(s) = p·(s, 0, s²/2)` in the plane `y = 0` (vertex `O`, focus `(0, 0, p/2)`),
//! * `c2(t) = p·(0, t, (1 − t²)/2)` in the plane `x = 0` (vertex `(0, 0, p/2)`, focus `O`),
//!
//! so the vertex of each is the focus of the other, and
//! `|c2(t) − c1(s)| = p·(1 + s² + t²)/2`. Sphere `s` of the first family has
//! centre `c1(s)` and the constant radius `r1`, sphere `t` of the second family
//! centre `c2(t)` and radius `r2`. Their radical plane (the points of equal power
//! `|X − c|² − r²` with respect to both spheres) is
//!
//! `F(X; s, t) = (c2 − c1)·X − (|c2|² − |c1|² + r1² − r2²)/2 = 0`.
//!
//! The point where this two-parameter family of planes touches its envelope
//! solves `F = ∂F/∂s = ∂F/∂t = 0`, three linear equations in `X`:
//!
//! * `∂F/∂s = −c1′(s)·(X − c1(s))`: `X` lies in the normal plane of the first
//!   parabola at `c1(s)` — a plane that depends on `s` only, so the parameter
//!   line `s = const` is a planar curve;
//! * `∂F/∂t = c2′(t)·(X − c2(t))`: likewise the line `t = const` lies in the
//!   normal plane of the second parabola at `c2(t)`.
//!
//! The unit normal of the envelope is that of the radical plane,
//! `N = (c2 − c1)/|c2 − c1| = (−2s, 2t, 1 − s² − t²)/(1 + s² + t²)`: the inverse
//! stereographic projection of `(s, t)` from the pole `(0, 0, −1)`, Enneper's Gauss
//! map. Solving the system in closed form gives
//! `X = (3p/4)·(s − s³/3 + s t², t − t³/3 + s² t, s² − t²) + (0, 0, p/4) + ρ/(2p)·(N + e_z)`
//! with `ρ = r1² − r2²`: Enneper's minimal surface (`r1 = r2`), or for `r1 ≠ r2`
//! its parallel surface at distance `ρ/(2p)`, translated — the radii enter only
//! through `ρ`. The parameter lines are curvature lines; their Gauss images are
//! circles of the two pencils with axes `{(0, λ, −1)}` (lines `s = const`) and
//! `{(λ, 0, −1)}` (lines `t = const`), both tangent to S² at the pole (§2.1.2).

use glam::DVec3;

use crate::projective::Plane;
use crate::QuadGrid;

/// A sphere (§2.1.1): centre and radius.
///
/// ```
/// use glam::DVec3;
/// use monge_core::darboux::Sphere;
/// let s = Sphere { center: DVec3::X, radius: 2.0 };
/// assert_eq!(s.power(DVec3::ZERO), 1.0 - 4.0);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    /// Centre.
    pub center: DVec3,
    /// Radius.
    pub radius: f64,
}

impl Sphere {
    /// Power of the point `x` with respect to the sphere, `|x − c|² − r²` (§2.1.1).
    pub fn power(&self, x: DVec3) -> f64 {
        (x - self.center).length_squared() - self.radius * self.radius
    }
}

/// The radical plane of two spheres with distinct centres (§2.1.1): the points of
/// equal power with respect to both, `(c_b − c_a)·X = (|c_b|² − |c_a|² + r_a² − r_b²)/2`.
/// For intersecting spheres it is the plane of their intersection circle.
///
/// ```
/// use glam::DVec3;
/// use monge_core::darboux::{radical_plane, Sphere};
/// let a = Sphere { center: DVec3::ZERO, radius: 1.0 };
/// let b = Sphere { center: DVec3::new(2.0, 0.0, 0.0), radius: 1.0 };
/// let plane = radical_plane(&a, &b);
/// assert_eq!(plane.signed_distance(DVec3::new(1.0, 5.0, -3.0)), 0.0);
/// let x = DVec3::new(1.0, 0.5, 0.25);
/// assert!((a.power(x) - b.power(x)).abs() < 1e-15);
/// ```
pub fn radical_plane(a: &Sphere, b: &Sphere) -> Plane {
    Plane {
        normal: b.center - a.center,
        offset: 0.5
            * (b.center.length_squared() - a.center.length_squared() + a.radius * a.radius
                - b.radius * b.radius),
    }
}

/// The common point of three planes (§2.1.1), by Cramer's rule; non-finite when
/// their normals are linearly dependent.
///
/// ```
/// use glam::DVec3;
/// use monge_core::darboux::intersect_planes;
/// use monge_core::projective::Plane;
/// let plane = |normal: DVec3, offset: f64| Plane { normal, offset };
/// let x = intersect_planes([plane(DVec3::X, 1.0), plane(DVec3::Y, 2.0), plane(DVec3::new(1.0, 1.0, 1.0), 6.0)]);
/// assert_eq!(x, DVec3::new(1.0, 2.0, 3.0));
/// ```
pub fn intersect_planes([a, b, c]: [Plane; 3]) -> DVec3 {
    let (bc, ca, ab) = (
        b.normal.cross(c.normal),
        c.normal.cross(a.normal),
        a.normal.cross(b.normal),
    );
    (a.offset * bc + b.offset * ca + c.offset * ab) / a.normal.dot(bc)
}

/// Darboux's envelope of Figure 2 (§2.1.1): the envelope of the radical planes of
/// spheres of constant radii `r1`, `r2` centred on the focal parabolas
/// `c1(s) = p·(s, 0, s²/2)` and `c2(t) = p·(0, t, (1 − t²)/2)` (see the module
/// documentation for the formulas). The parameter lines `s = const` and
/// `t = const` are planar curvature lines.
///
/// ```
/// use glam::DVec3;
/// use monge_core::darboux::EnneperEnvelope;
/// // Equal radii: Enneper's surface (3/4)·(s − s³/3 + st², t − t³/3 + s²t, s² − t²) + (0, 0, 1/4).
/// let e = EnneperEnvelope { p: 1.0, r1: 0.5, r2: 0.5 };
/// let x = e.point(1.0, 0.0);
/// assert!(x.distance(DVec3::new(0.5, 0.0, 1.0)) < 1e-15);
/// assert!(e.normal(1.0, 0.0).distance(DVec3::new(-1.0, 0.0, 0.0)) < 1e-15);
/// // The point lies on the radical plane and on both curvature-line planes.
/// for plane in [e.radical_plane(0.3, -0.7), e.plane_of_s_line(0.3), e.plane_of_t_line(-0.7)] {
///     assert!(plane.signed_distance(e.point(0.3, -0.7)).abs() < 1e-14);
/// }
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EnneperEnvelope {
    /// Scale of the focal parabolas (`p > 0`): the distance between their vertices is `p/2`.
    pub p: f64,
    /// Radius of the spheres centred on the first parabola `c1`.
    pub r1: f64,
    /// Radius of the spheres centred on the second parabola `c2`.
    pub r2: f64,
}

impl EnneperEnvelope {
    /// The first focal parabola (§2.1.1), in the plane `y = 0`: `c1(s) = p·(s, 0, s²/2)`.
    pub fn center_1(&self, s: f64) -> DVec3 {
        self.p * DVec3::new(s, 0.0, 0.5 * s * s)
    }

    /// The second focal parabola (§2.1.1), in the plane `x = 0`: `c2(t) = p·(0, t, (1 − t²)/2)`.
    pub fn center_2(&self, t: f64) -> DVec3 {
        self.p * DVec3::new(0.0, t, 0.5 * (1.0 - t * t))
    }

    /// `c1′(s) = p·(1, 0, s)`.
    fn center_1_ds(&self, s: f64) -> DVec3 {
        self.p * DVec3::new(1.0, 0.0, s)
    }

    /// `c2′(t) = p·(0, 1, −t)`.
    fn center_2_dt(&self, t: f64) -> DVec3 {
        self.p * DVec3::new(0.0, 1.0, -t)
    }

    /// Sphere `s` of the first family (§2.1.1): centre `c1(s)`, radius `r1`.
    pub fn sphere_1(&self, s: f64) -> Sphere {
        Sphere {
            center: self.center_1(s),
            radius: self.r1,
        }
    }

    /// Sphere `t` of the second family (§2.1.1): centre `c2(t)`, radius `r2`.
    pub fn sphere_2(&self, t: f64) -> Sphere {
        Sphere {
            center: self.center_2(t),
            radius: self.r2,
        }
    }

    /// The radical plane of sphere `s` of the first family and sphere `t` of the
    /// second (§2.1.1): `F(X; s, t) = 0`, normal `c2(t) − c1(s)`.
    pub fn radical_plane(&self, s: f64, t: f64) -> Plane {
        radical_plane(&self.sphere_1(s), &self.sphere_2(t))
    }

    /// `∂F/∂s = 0` (§2.1.1): with constant radii, `∂F/∂s = −c1′·X + c1·c1′`, i.e.
    /// the normal plane `c1′(s)·X = c1(s)·c1′(s)` of the first parabola. It does
    /// not depend on `t`: it is the plane of the curvature line `s = const`.
    pub fn plane_of_s_line(&self, s: f64) -> Plane {
        let d = self.center_1_ds(s);
        Plane {
            normal: d,
            offset: d.dot(self.center_1(s)),
        }
    }

    /// `∂F/∂t = 0` (§2.1.1): `∂F/∂t = c2′·X − c2·c2′`, the normal plane
    /// `c2′(t)·X = c2(t)·c2′(t)` of the second parabola, the plane of the
    /// curvature line `t = const`.
    pub fn plane_of_t_line(&self, t: f64) -> Plane {
        let d = self.center_2_dt(t);
        Plane {
            normal: d,
            offset: d.dot(self.center_2(t)),
        }
    }

    /// The three planes `F = 0`, `∂F/∂s = 0`, `∂F/∂t = 0` whose common point is the
    /// envelope point. Their normals `c2 − c1`, `c1′`, `c2′` have the triple
    /// product `p³·(1 + s² + t²)/2 > 0`, so the point always exists.
    fn planes(&self, s: f64, t: f64) -> [Plane; 3] {
        [
            self.radical_plane(s, t),
            self.plane_of_s_line(s),
            self.plane_of_t_line(t),
        ]
    }

    /// The point `X(s, t)` where the radical plane touches its envelope (§2.1.1).
    pub fn point(&self, s: f64, t: f64) -> DVec3 {
        intersect_planes(self.planes(s, t))
    }

    /// The unit normal of the envelope at `(s, t)` (§2.1.1, §2.1.2): the unit
    /// normal of the radical plane, `(c2 − c1)/|c2 − c1|`.
    pub fn normal(&self, s: f64, t: f64) -> DVec3 {
        (self.center_2(t) - self.center_1(s)).normalize()
    }

    /// The partial derivatives `(∂X/∂s, ∂X/∂t)` (§2.1.1), differentiated
    /// analytically: differentiating the three plane equations `A·X = b` gives
    /// `A·∂X/∂s = (0, |c1′|² − c1″·(X − c1), 0)` and
    /// `A·∂X/∂t = (0, 0, |c2′|² − c2″·(X − c2))`, with `c1″ = p·e_z`, `c2″ = −p·e_z`.
    /// They are the tangents of the curvature lines `t = const` and `s = const`.
    ///
    /// ```
    /// use monge_core::darboux::EnneperEnvelope;
    /// let e = EnneperEnvelope { p: 2.0, r1: 1.0, r2: 0.5 };
    /// let (x_s, x_t) = e.derivatives(0.4, 0.9);
    /// let h = 1e-6;
    /// let fd_s = (e.point(0.4 + h, 0.9) - e.point(0.4 - h, 0.9)) / (2.0 * h);
    /// let fd_t = (e.point(0.4, 0.9 + h) - e.point(0.4, 0.9 - h)) / (2.0 * h);
    /// assert!(x_s.distance(fd_s) < 1e-8 && x_t.distance(fd_t) < 1e-8);
    /// assert!(x_s.dot(x_t).abs() < 1e-12); // curvature lines are orthogonal
    /// ```
    pub fn derivatives(&self, s: f64, t: f64) -> (DVec3, DVec3) {
        let planes = self.planes(s, t);
        let x = intersect_planes(planes);
        let (c1, c2) = (self.center_1(s), self.center_2(t));
        let (d1, d2) = (self.center_1_ds(s), self.center_2_dt(t));
        let dd1 = self.p * DVec3::Z;
        let dd2 = -self.p * DVec3::Z;
        let with_offsets = |offsets: [f64; 3]| -> [Plane; 3] {
            [0, 1, 2].map(|k| Plane {
                normal: planes[k].normal,
                offset: offsets[k],
            })
        };
        let x_s = intersect_planes(with_offsets([
            0.0,
            d1.length_squared() - dd1.dot(x - c1),
            0.0,
        ]));
        let x_t = intersect_planes(with_offsets([
            0.0,
            0.0,
            d2.length_squared() - dd2.dot(x - c2),
        ]));
        (x_s, x_t)
    }

    /// The envelope sampled on the parameter grid `s × t` (§2.1.1): vertex `(i, j)`
    /// is `X(s[i], t[j])` with normal `N(s[i], t[j])`; rows are curvature lines
    /// `s = const`, columns curvature lines `t = const`.
    ///
    /// ```
    /// use monge_core::darboux::EnneperEnvelope;
    /// let e = EnneperEnvelope { p: 1.0, r1: 0.0, r2: 0.0 };
    /// let g = e.sample(&[0.0, 0.5, 1.0], &[-0.5, 0.0]);
    /// assert_eq!((g.rows, g.cols), (3, 2));
    /// assert_eq!(g.vertex(2, 0), e.point(1.0, -0.5));
    /// assert_eq!(g.normals[g.index(1, 1)], e.normal(0.5, 0.0));
    /// ```
    pub fn sample(&self, s: &[f64], t: &[f64]) -> QuadGrid {
        let params = || s.iter().flat_map(|&si| t.iter().map(move |&tj| (si, tj)));
        QuadGrid::new(
            s.len(),
            t.len(),
            params().map(|(si, tj)| self.point(si, tj)).collect(),
            params().map(|(si, tj)| self.normal(si, tj)).collect(),
        )
    }
}
