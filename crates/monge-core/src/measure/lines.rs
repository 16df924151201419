//! Planarity of a polyline (§2.2): the planar curvature lines of a mesh.

use glam::DVec3;
use nalgebra::DMatrix;

use super::Worst;

/// Planarity of a polyline (§2.2): the largest distance of a point from the
/// least-squares plane of all points, and the index of that point (absolute
/// length units).
///
/// The plane passes through the centroid; its normal is the right singular
/// vector of the smallest singular value of the centred `n × 3` point matrix.
/// The SVD of the points themselves (not an eigen-decomposition of their
/// covariance, which squares the condition number) keeps the error of every
/// distance at the rounding level of the coordinates even for nearly straight
/// polylines, where the plane is barely determined; a straight polyline measures
/// 0 up to rounding, a polyline of at most 3 points exactly 0. A non-finite point
/// yields NaN (at that point).
///
/// ```
/// use glam::DVec3;
/// use monge_core::measure::polyline_planarity;
/// let mut p: Vec<DVec3> = (0..7).map(|k| DVec3::new(k as f64, (k * k) as f64, 0.0)).collect();
/// assert!(polyline_planarity(&p).0 < 1e-14);
/// p[3].z = 1.0; // the least-squares plane tilts; point 3 stays the farthest
/// let (d, k) = polyline_planarity(&p);
/// assert_eq!(k, 3);
/// assert!(d > 0.5 && d < 1.0);
/// ```
pub fn polyline_planarity(points: &[DVec3]) -> (f64, usize) {
    if let Some(bad) = points.iter().position(|p| !p.is_finite()) {
        return (f64::NAN, bad); // the SVD would not converge; report, never hide
    }
    if points.len() < 4 {
        // Three points always lie in a plane, however close to a line they are.
        return (0.0, 0);
    }
    // Relative to the first point, then to the centroid (never added back), to
    // keep the rounding error relative to the polyline's size rather than its
    // distance to the origin.
    let origin = points[0];
    let centroid = points.iter().map(|p| *p - origin).sum::<DVec3>() / points.len() as f64;
    let local = |p: &DVec3| (*p - origin) - centroid;
    let m = DMatrix::from_fn(points.len(), 3, |r, c| local(&points[r])[c]);
    if let Some(bad) = (0..points.len()).find(|&r| !local(&points[r]).is_finite()) {
        // Finite points whose differences overflow (beyond ±9e307): the SVD
        // would panic ("Singular value was NaN"); report, never hide.
        return (f64::NAN, bad);
    }
    // Golub–Kahan converges in a few sweeps per singular value; the cap only
    // guards against pathological input, which is then reported as NaN.
    let Some(svd) = m.try_svd(false, true, f64::EPSILON, 10_000) else {
        return (f64::NAN, 0);
    };
    let v_t = svd.v_t.expect("v_t was requested");
    let k = svd.singular_values.imin();
    let normal = DVec3::new(v_t[(k, 0)], v_t[(k, 1)], v_t[(k, 2)]);
    let mut worst = Worst::NONE;
    for (idx, p) in points.iter().enumerate() {
        worst.update(local(p).dot(normal).abs(), (idx, 0));
    }
    (worst.value, worst.at.0)
}
