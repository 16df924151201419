//! What a developable design must satisfy (§3.3): finite numbers, one slope away
//! from 0° and 90°, no repeated or collinear helix points, a projection that does
//! not cross itself, and monotonic heights clear of the helix vertices.

use glam::DVec2;

use super::error::{DevelopableError, Field};
use super::limits::TOLERANCE;

/// Any non-finite component of `v`, entry `index` of `field`.
pub(super) fn finite(field: Field, index: usize, v: &[f64]) -> Result<(), DevelopableError> {
    match v.iter().find(|x| !x.is_finite()) {
        Some(&value) => Err(DevelopableError::NotFinite {
            field,
            index,
            value,
        }),
        None => Ok(()),
    }
}

/// Consecutive helix vertices that coincide.
pub(super) fn repeated(plan: &[DVec2], z: &[f64], size: f64) -> Result<(), DevelopableError> {
    for k in 0..plan.len() - 1 {
        let distance = (plan[k + 1] - plan[k]).length().hypot(z[k + 1] - z[k]);
        if distance.is_nan() || distance <= TOLERANCE * size {
            return Err(DevelopableError::RepeatedPoint {
                index: k,
                distance,
                relative: distance / size,
            });
        }
    }
    Ok(())
}

/// Refuse α (in degrees) of 0°, 90° or (with `range`) beyond ±90°, to
/// [`TOLERANCE`] radians.
pub(super) fn check_alpha(alpha_deg: f64, range: bool) -> Result<(), DevelopableError> {
    let tol = TOLERANCE.to_degrees();
    if range && alpha_deg.abs() > 90.0 + tol {
        Err(DevelopableError::AlphaOutOfRange { alpha_deg })
    } else if alpha_deg.abs() <= tol {
        Err(DevelopableError::Flat { alpha_deg })
    } else if alpha_deg.abs() >= 90.0 - tol {
        Err(DevelopableError::Vertical { alpha_deg })
    } else {
        Ok(())
    }
}

/// The mean slope `(α, tan α)` of a helix given directly, after checking that
/// every segment has it.
pub(super) fn helix_slope(z: &[f64], lengths: &[f64]) -> Result<(f64, f64), DevelopableError> {
    let rise: f64 = z[z.len() - 1] - z[0];
    let run: f64 = lengths.iter().sum();
    let alpha = rise.atan2(run);
    let angles: Vec<f64> = z
        .windows(2)
        .zip(lengths)
        .map(|(w, l)| (w[1] - w[0]).atan2(*l))
        .collect();
    let (abs_rise, total): (f64, f64) =
        z.windows(2)
            .zip(lengths)
            .fold((0.0, 0.0), |(a, t), (w, l)| {
                let dz = w[1] - w[0];
                (a + dz.abs(), t + dz.hypot(*l))
            });
    let mean_sin = abs_rise / total;
    if mean_sin > 0.0 {
        let (segment, deviation) = angles
            .iter()
            .map(|a| (a.sin() - alpha.sin()).abs() / mean_sin)
            .enumerate()
            .fold((0, 0.0), |w, (k, d)| if d > w.1 { (k, d) } else { w });
        if deviation > TOLERANCE {
            return Err(DevelopableError::NonConstantSlope {
                segment,
                angle_deg: angles[segment].to_degrees(),
                alpha_deg: alpha.to_degrees(),
                deviation,
            });
        }
    }
    check_alpha(alpha.to_degrees(), false)?;
    Ok((alpha, rise / run))
}

/// Consecutive collinear segments (same direction): coinciding rulings.
pub(super) fn straight_vertices(directions: &[DVec2]) -> Result<(), DevelopableError> {
    for (k, w) in directions.windows(2).enumerate() {
        let turn = w[0].perp_dot(w[1]).atan2(w[0].dot(w[1]));
        if turn.abs() <= TOLERANCE {
            return Err(DevelopableError::Straight {
                vertex: k + 1,
                turn_deg: turn.to_degrees(),
            });
        }
    }
    Ok(())
}

/// Distance from `p` to the segment `ab`.
fn point_segment(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    let ab = b - a;
    let t = ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0);
    (p - (a + t * ab)).length()
}

/// Distance between the segments `ab` and `cd` (0 if they cross).
fn segment_segment(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> f64 {
    let side = |p: DVec2, q: DVec2, r: DVec2| (q - p).perp_dot(r - p);
    let (s1, s2) = (side(a, b, c), side(a, b, d));
    let (s3, s4) = (side(c, d, a), side(c, d, b));
    if s1 * s2 < 0.0 && s3 * s4 < 0.0 {
        return 0.0;
    }
    point_segment(a, c, d)
        .min(point_segment(b, c, d))
        .min(point_segment(c, a, b))
        .min(point_segment(d, a, b))
}

/// Segments of the projection that cross, touch or overlap, apart from the
/// common end of consecutive segments and the closing point of a closed curve.
pub(super) fn self_crossing(plan: &[DVec2], size: f64) -> Result<(), DevelopableError> {
    let n = plan.len() - 1;
    let tol = TOLERANCE * size;
    let closed = (plan[n] - plan[0]).length() <= tol;
    let fail = |a: usize, b: usize, distance: f64| DevelopableError::SelfCrossing {
        a,
        b,
        distance,
        relative: distance / size,
    };
    for a in 0..n {
        // Consecutive segments share a point: they overlap only by folding back.
        if a + 1 < n {
            let d = point_segment(plan[a], plan[a + 1], plan[a + 2]).min(point_segment(
                plan[a + 2],
                plan[a],
                plan[a + 1],
            ));
            if d <= tol {
                return Err(fail(a, a + 1, d));
            }
        }
        for b in a + 2..n {
            let d = if closed && a == 0 && b == n - 1 {
                point_segment(plan[1], plan[n - 1], plan[n]).min(point_segment(
                    plan[n - 1],
                    plan[0],
                    plan[1],
                ))
            } else {
                segment_segment(plan[a], plan[a + 1], plan[b], plan[b + 1])
            };
            if d <= tol {
                return Err(fail(a, b, d));
            }
        }
    }
    Ok(())
}

/// Strictly monotonic heights, none through (or around) a helix vertex where two
/// rulings meet.
pub(super) fn check_heights(heights: &[f64], z: &[f64], size: f64) -> Result<(), DevelopableError> {
    let tol = TOLERANCE * size;
    let up = heights[1] > heights[0];
    for (k, w) in heights.windows(2).enumerate() {
        let gap = if up { w[1] - w[0] } else { w[0] - w[1] };
        if gap <= tol {
            return Err(DevelopableError::HeightsNotMonotonic {
                index: k + 1,
                previous: w[0],
                height: w[1],
            });
        }
    }
    for (vertex, &zv) in z.iter().enumerate().take(z.len() - 1).skip(1) {
        for (height_index, &height) in heights.iter().enumerate() {
            if (height - zv).abs() <= tol {
                return Err(DevelopableError::HeightAtHelixVertex {
                    height_index,
                    height,
                    vertex,
                    vertex_height: zv,
                    relative: (height - zv).abs() / size,
                });
            }
        }
        for (j, w) in heights.windows(2).enumerate() {
            if (w[0] - zv) * (w[1] - zv) < 0.0 {
                return Err(DevelopableError::FaceCrossesHelix {
                    vertex,
                    vertex_height: zv,
                    j,
                    below: w[0],
                    above: w[1],
                });
            }
        }
    }
    Ok(())
}
