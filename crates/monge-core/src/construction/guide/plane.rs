//! The least-squares plane and line of a guide's samples (§3).

use glam::DVec3;

/// A least-squares plane and line through a point set.
pub(super) struct Fit {
    /// The centroid.
    pub(super) centroid: DVec3,
    /// Unit normal of the best-fit plane (smallest singular direction).
    pub(super) normal: DVec3,
    /// Unit direction of the best-fit line (largest singular direction).
    pub(super) axis: DVec3,
}

/// Least-squares plane and line of `points` (finite, bounding-box diagonal
/// `size` finite and non-zero): the right singular vectors of the centred
/// points, by one-sided Jacobi on the `N × 3` matrix itself (no covariance
/// matrix, so no squaring of the condition number). Exactly planar input in an
/// axis-aligned plane gives that axis exactly.
pub(super) fn fit(points: &[DVec3], size: f64) -> Fit {
    let (lo, hi) = points.iter().fold((points[0], points[0]), |(lo, hi), &p| {
        (lo.min(p), hi.max(p))
    });
    let mid = 0.5 * lo + 0.5 * hi;
    let mean = points.iter().map(|&p| p - mid).sum::<DVec3>() / points.len() as f64;
    let centroid = mid + mean;
    // A power of two, so scaling is exact and keeps the sums in range.
    let scale = libm::ldexp(1.0, -(libm::log2(size).floor() as i32));
    let mut a: Vec<[f64; 3]> = points
        .iter()
        .map(|&p| ((p - centroid) * scale).to_array())
        .collect();
    let mut vt = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]; // columns of V
    for _sweep in 0..64 {
        let mut rotated = false;
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            let (mut alpha, mut beta, mut gamma) = (0.0, 0.0, 0.0);
            for row in &a {
                alpha += row[p] * row[p];
                beta += row[q] * row[q];
                gamma += row[p] * row[q];
            }
            if gamma == 0.0 || gamma.abs() <= f64::EPSILON * (alpha * beta).sqrt() {
                continue;
            }
            rotated = true;
            let zeta = (beta - alpha) / (2.0 * gamma);
            let t = zeta.signum() / (zeta.abs() + libm::hypot(zeta, 1.0));
            let c = 1.0 / libm::hypot(t, 1.0);
            let s = c * t;
            for row in a.iter_mut().chain(vt.iter_mut()) {
                let (x, y) = (row[p], row[q]);
                row[p] = c * x - s * y;
                row[q] = s * x + c * y;
            }
        }
        if !rotated {
            break;
        }
    }
    let norms: [f64; 3] = std::array::from_fn(|j| a.iter().map(|row| row[j] * row[j]).sum::<f64>());
    let column = |j: usize| DVec3::new(vt[0][j], vt[1][j], vt[2][j]).normalize();
    let order = {
        let mut o = [0, 1, 2];
        o.sort_by(|&i, &j| norms[i].total_cmp(&norms[j]));
        o
    };
    let mut normal = column(order[0]);
    let largest = (0..3)
        .max_by(|&i, &j| normal[i].abs().total_cmp(&normal[j].abs()).then(j.cmp(&i)))
        .unwrap_or(0);
    if normal[largest] < 0.0 {
        normal = -normal;
    }
    Fit {
        centroid,
        normal,
        axis: column(order[2]),
    }
}
