//! Principal axes of a point set and the quadric fitted near a point, with its
//! principal curvatures and directions (§4.7, monge's extension: the initial guess).

use glam::DVec3;
use nalgebra::{Matrix3, SymmetricEigen};

use crate::grid::bbox_diagonal;

use super::error::{ApproxError, FLAT_CURVATURE, UMBILIC_RATIO};

/// Principal axes of a point set: the unit eigenvectors of its covariance, largest
/// variance first (the last is the normal of the best-fit plane).
pub(super) fn principal_axes(points: &[DVec3]) -> (DVec3, DVec3, DVec3) {
    let n = points.len().max(1) as f64;
    principal_axes_about(points, points.iter().copied().sum::<DVec3>() / n)
}

/// The unit eigenvectors of the second moments of `points` about `c`, largest first
/// (the last is the normal of the plane through `c` nearest to the points).
pub(super) fn principal_axes_about(points: &[DVec3], c: DVec3) -> (DVec3, DVec3, DVec3) {
    let mut m = Matrix3::zeros();
    for p in points {
        let d = *p - c;
        let v = nalgebra::Vector3::new(d.x, d.y, d.z);
        m += v * v.transpose();
    }
    let eig = SymmetricEigen::new(m);
    let mut order = [0, 1, 2];
    order.sort_by(|&a, &b| eig.eigenvalues[b].total_cmp(&eig.eigenvalues[a]));
    let axis = |k: usize| {
        let v = eig.eigenvectors.column(order[k]);
        DVec3::new(v[0], v[1], v[2])
    };
    (axis(0), axis(1), axis(2))
}

/// The sides of the smallest rectangle enclosing the points' projections on the plane
/// through their centroid normal to `normal` (rotating calipers over the hull's edges):
/// two orthogonal unit directions in that plane, the longer side's first. The directions
/// of a target's plan (a square dome's edges) where its curvature gives none.
pub(super) fn plan_sides(points: &[DVec3], normal: DVec3) -> (DVec3, DVec3) {
    let x = normal.any_orthonormal_vector();
    let y = normal.cross(x);
    let mut plan: Vec<(f64, f64)> = points.iter().map(|p| (p.dot(x), p.dot(y))).collect();
    // Andrew's monotone chain: the convex hull, counter-clockwise.
    plan.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    let turn = |o: (f64, f64), a: (f64, f64), b: (f64, f64)| {
        (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
    };
    let mut hull: Vec<(f64, f64)> = Vec::with_capacity(plan.len() + 1);
    let backwards: Vec<(f64, f64)> = plan.iter().rev().copied().collect();
    for chain in [&plan, &backwards] {
        let floor = hull.len();
        for p in chain.iter() {
            while hull.len() >= floor + 2
                && turn(hull[hull.len() - 2], hull[hull.len() - 1], *p) <= 0.0
            {
                hull.pop();
            }
            hull.push(*p);
        }
        hull.pop();
    }
    // The hull edge along which the enclosing rectangle is smallest.
    let mut best = (f64::INFINITY, (1.0, 0.0));
    for k in 0..hull.len() {
        let (a, b) = (hull[k], hull[(k + 1) % hull.len()]);
        let length = (b.0 - a.0).hypot(b.1 - a.1);
        if length <= 0.0 {
            continue;
        }
        let (c, s) = ((b.0 - a.0) / length, (b.1 - a.1) / length);
        let extent = |f: &dyn Fn(&(f64, f64)) -> f64| {
            hull.iter()
                .map(f)
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                    (lo.min(v), hi.max(v))
                })
        };
        let along = extent(&|p| p.0 * c + p.1 * s);
        let across = extent(&|p| p.1 * c - p.0 * s);
        let area = (along.1 - along.0) * (across.1 - across.0);
        if area < best.0 {
            let direction = if along.1 - along.0 >= across.1 - across.0 {
                (c, s)
            } else {
                (-s, c)
            };
            best = (area, direction);
        }
    }
    let (c, s) = best.1;
    let first = c * x + s * y;
    (first, normal.cross(first))
}

/// A height function `z = a x² + b xy + c y² + d x + e y + f` over a frame.
#[derive(Clone, Debug)]
pub(super) struct Quadric {
    origin: DVec3,
    x: DVec3,
    y: DVec3,
    z: DVec3,
    k: [f64; 6],
}

/// A surface point with its principal curvatures and directions (larger first).
pub(super) struct Principal {
    pub(super) point: DVec3,
    pub(super) normal: DVec3,
    pub(super) k1: f64,
    pub(super) k2: f64,
    pub(super) d1: DVec3,
    pub(super) d2: DVec3,
}

impl Quadric {
    /// Least-squares fit of `points` in the frame at `origin` with normal `z`.
    pub(super) fn fit(points: &[DVec3], origin: DVec3, z: DVec3) -> Quadric {
        let x = z.any_orthonormal_vector();
        let y = z.cross(x);
        let (c, scale, _) = height_fit(points, origin, [x, y, z], 2);
        // Back to model units: z = s·w(u/s, v/s).
        let k = [
            c[0] / scale,
            c[1] / scale,
            c[2] / scale,
            c[3],
            c[4],
            c[5] * scale,
        ];
        Quadric { origin, x, y, z, k }
    }

    /// How far `p` lies above the quadric along its frame's normal (negative below).
    pub(super) fn height_above(&self, p: DVec3) -> f64 {
        let (u, v) = self.uv(p);
        let [a, b, c, d, e, f] = self.k;
        (p - self.origin).dot(self.z) - (a * u * u + b * u * v + c * v * v + d * u + e * v + f)
    }

    /// Local coordinates `(u, v)` of the projection of `p` on the frame's plane.
    pub(super) fn uv(&self, p: DVec3) -> (f64, f64) {
        let d = p - self.origin;
        (d.dot(self.x), d.dot(self.y))
    }

    /// Principal curvatures and directions at `(u, v)` (shape operator `I⁻¹ II`).
    pub(super) fn principal(&self, u: f64, v: f64) -> Principal {
        let [a, b, c, d, e, f] = self.k;
        let h = a * u * u + b * u * v + c * v * v + d * u + e * v + f;
        let (p, q) = (2.0 * a * u + b * v + d, b * u + 2.0 * c * v + e);
        let xu = self.x + p * self.z;
        let xv = self.y + q * self.z;
        let normal = xu.cross(xv).normalize();
        let w = (1.0 + p * p + q * q).sqrt();
        let first = nalgebra::Matrix2::new(1.0 + p * p, p * q, p * q, 1.0 + q * q);
        let second = nalgebra::Matrix2::new(2.0 * a, b, b, 2.0 * c) / w;
        let shape = first.try_inverse().unwrap_or_else(nalgebra::Matrix2::zeros) * second;
        // Eigenvalues of the 2 × 2 shape operator, and eigenvectors in (u, v).
        let (tr, det) = (shape.trace(), shape.determinant());
        let disc = (0.25 * tr * tr - det).max(0.0).sqrt();
        let (k1, k2) = (0.5 * tr + disc, 0.5 * tr - disc);
        let direction = |k: f64| {
            let (s11, s12, s21, s22) = (shape[(0, 0)], shape[(0, 1)], shape[(1, 0)], shape[(1, 1)]);
            let (r1, r2) = ((s12, k - s11), (k - s22, s21));
            let (du, dv) = if r1.0.hypot(r1.1) >= r2.0.hypot(r2.1) {
                r1
            } else {
                r2
            };
            (du * xu + dv * xv).normalize_or_zero()
        };
        let d1 = direction(k1);
        // Principal directions are orthogonal: take d2 from d1 so the frame is exact.
        let d1 = if d1 == DVec3::ZERO {
            xu.normalize()
        } else {
            d1
        };
        let d2 = normal.cross(d1);
        Principal {
            point: self.origin + u * self.x + v * self.y + h * self.z,
            normal,
            k1,
            k2,
            d1,
            d2,
        }
    }
}

/// The least-squares height `w(u, v)` of `degree` (2 or 3) over the frame `[x, y, z]`
/// at `origin`, in units of the points' extent: its coefficients (`u², uv, v², u, v, 1`,
/// then `u³, u²v, uv², v³`), that extent, and the sum of the squared residuals (model
/// units).
fn height_fit(
    points: &[DVec3],
    origin: DVec3,
    [x, y, z]: [DVec3; 3],
    degree: usize,
) -> (Vec<f64>, f64, f64) {
    let scale = bbox_diagonal(points).max(f64::MIN_POSITIVE);
    let terms = if degree >= 3 { 10 } else { 6 };
    let row = |p: &DVec3| {
        let d = (*p - origin) / scale;
        let (u, v) = (d.dot(x), d.dot(y));
        let all = [
            u * u,
            u * v,
            v * v,
            u,
            v,
            1.0,
            u * u * u,
            u * u * v,
            u * v * v,
            v * v * v,
        ];
        (
            nalgebra::DVector::from_column_slice(&all[..terms]),
            d.dot(z),
        )
    };
    let mut ata = nalgebra::DMatrix::<f64>::zeros(terms, terms);
    let mut atb = nalgebra::DVector::<f64>::zeros(terms);
    for p in points {
        let (r, w) = row(p);
        ata += &r * r.transpose();
        atb += r * w;
    }
    let c = ata
        .svd(true, true)
        .solve(&atb, 1e-14)
        .unwrap_or_else(|_| nalgebra::DVector::zeros(terms));
    let residual = points
        .iter()
        .map(|p| {
            let (r, w) = row(p);
            (scale * (w - r.dot(&c))).powi(2)
        })
        .sum();
    (c.as_slice().to_vec(), scale, residual)
}

/// The sums of the squared residuals of the least-squares quadratic and cubic heights
/// of `points` over the plane through `origin` with normal `z` (model units): a
/// sampling's noise leaves both alike, a smooth surface's third-order terms only the
/// first.
pub(super) fn misfits(points: &[DVec3], origin: DVec3, z: DVec3) -> (f64, f64) {
    let x = z.any_orthonormal_vector();
    let frame = [x, z.cross(x), z];
    (
        height_fit(points, origin, frame, 2).2,
        height_fit(points, origin, frame, 3).2,
    )
}

/// Refuses a flat or umbilic point of the target.
pub(super) fn check_curvature(
    p: &Principal,
    size: f64,
    where_: &'static str,
) -> Result<(), ApproxError> {
    let big = p.k1.abs().max(p.k2.abs());
    if big * size <= FLAT_CURVATURE {
        return Err(ApproxError::Flat {
            where_,
            point: p.point.to_array(),
            k1: p.k1,
            k2: p.k2,
            limit: FLAT_CURVATURE,
        });
    }
    let ratio = (p.k1 - p.k2).abs() / big;
    if ratio < UMBILIC_RATIO {
        return Err(ApproxError::Umbilic {
            where_,
            point: p.point.to_array(),
            k1: p.k1,
            k2: p.k2,
            percent: 100.0 * ratio,
            limit_percent: 100.0 * UMBILIC_RATIO,
        });
    }
    Ok(())
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
pub(super) fn through_point_share(
    (quadratic, cubic): (f64, f64),
    (dof2, dof3): (f64, f64),
    size: f64,
) -> f64 {
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
pub(super) const SHARE_POINTS: usize = 256;

/// Relative residual of the neighbours' quadrics below which a target is exact.
const ROUNDING: f64 = 1e-12;
