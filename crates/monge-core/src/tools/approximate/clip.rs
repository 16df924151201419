//! Clipping polygons in a plane (Sutherland–Hodgman): how [`trim`](super::trim())
//! cuts each face of a grid by the target's outline.

use glam::DVec2;

/// Signed area of a polygon (positive counter-clockwise).
pub(super) fn polygon_area(polygon: &[DVec2]) -> f64 {
    0.5 * polygon
        .iter()
        .zip(polygon.iter().cycle().skip(1))
        .map(|(a, b)| a.perp_dot(*b))
        .sum::<f64>()
}

/// `quad` as convex pieces: itself if convex, else the two triangles either side of
/// the diagonal through its reflex corner.
pub(super) fn convex_pieces(quad: &[DVec2; 4]) -> Vec<Vec<DVec2>> {
    let turn = polygon_area(quad).signum();
    let reflex = (0..4).find(|k| {
        let (a, b, c) = (quad[(k + 3) % 4], quad[*k], quad[(k + 1) % 4]);
        turn * (b - a).perp_dot(c - b) < 0.0
    });
    match reflex {
        None => vec![quad.to_vec()],
        Some(k) => {
            let (a, b, c, d) = (
                quad[k],
                quad[(k + 1) % 4],
                quad[(k + 2) % 4],
                quad[(k + 3) % 4],
            );
            vec![vec![a, b, c], vec![a, c, d]]
        }
    }
}

/// The part of `subject` (any simple polygon) inside the convex `window`
/// (Sutherland–Hodgman, against each side of the window in turn), in the window's
/// orientation.
pub(super) fn clip(subject: &[DVec2], window: &[DVec2]) -> Vec<DVec2> {
    let turn = polygon_area(window).signum();
    let mut polygon: Vec<DVec2> = if polygon_area(subject).signum() == turn {
        subject.to_vec()
    } else {
        subject.iter().rev().copied().collect()
    };
    let sides = window.len();
    for k in 0..sides {
        let (a, b) = (window[k], window[(k + 1) % sides]);
        let side = |p: DVec2| turn * (b - a).perp_dot(p - a);
        let input = std::mem::take(&mut polygon);
        for (p, q) in input.iter().zip(input.iter().cycle().skip(1)) {
            let (sp, sq) = (side(*p), side(*q));
            if sp >= 0.0 {
                polygon.push(*p);
            }
            if (sp >= 0.0) != (sq >= 0.0) {
                // Where pq crosses the side's line, computed along it, so that a point
                // that ends on the side lies on the grid's edge.
                let d = q - p;
                let s = (a - *p).perp_dot(d);
                let e = b - a;
                let u = s / d.perp_dot(e);
                polygon.push(if u.is_finite() { a + u * e } else { *p });
            }
        }
        if polygon.is_empty() {
            break;
        }
    }
    without_spikes(polygon)
}

/// `polygon` without its repeated points and spikes: where the part of a non-convex
/// subject outside a window comes back along the window's side, Sutherland–Hodgman
/// leaves an edge out and the same edge back (a window's corner outside the subject).
fn without_spikes(mut polygon: Vec<DVec2>) -> Vec<DVec2> {
    let scale = polygon
        .iter()
        .fold(0.0f64, |m, p| m.max(p.abs().max_element()))
        .max(f64::MIN_POSITIVE);
    let tiny = 1e-12 * scale;
    loop {
        let n = polygon.len();
        if n < 3 {
            return polygon;
        }
        let spike = (0..n).find(|k| {
            let (a, b, c) = (polygon[(k + n - 1) % n], polygon[*k], polygon[(k + 1) % n]);
            let (ab, bc) = (b - a, c - b);
            ab.length() <= tiny
                || (ab.perp_dot(bc).abs() <= tiny * (ab.length() + bc.length()) && ab.dot(bc) < 0.0)
        });
        match spike {
            Some(k) => {
                polygon.remove(k);
            }
            None => return polygon,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Whether `q` is inside `polygon`, by its winding number (not the even–odd rule
    /// of the code).
    fn winds(polygon: &[DVec2], q: DVec2) -> bool {
        let turn: f64 = polygon
            .iter()
            .zip(polygon.iter().cycle().skip(1))
            .map(|(a, b)| (*a - q).angle_to(*b - q))
            .sum();
        turn.abs() > std::f64::consts::PI
    }

    /// A concave star of `n` points around the origin.
    fn star(rng: &mut fastrand::Rng, n: usize) -> Vec<DVec2> {
        (0..n)
            .map(|k| {
                let angle = k as f64 / n as f64 * std::f64::consts::TAU;
                let r = 2.0 + rng.f64();
                r * DVec2::new(angle.cos(), angle.sin())
            })
            .collect()
    }

    #[test]
    fn a_concave_outline_clipped_by_convex_windows_keeps_their_common_area() {
        let mut rng = fastrand::Rng::with_seed(5);
        let mut worst = 0.0f64;
        for _ in 0..100 {
            let subject = star(&mut rng, 40);
            // A convex quad near the star's edge (a parallelogram, skewed).
            let centre = (1.5 + 1.5 * rng.f64()) * DVec2::from_angle(rng.f64() * 6.3);
            let (a, b) = (
                DVec2::new(0.3 + 0.5 * rng.f64(), 0.2 * rng.f64()),
                DVec2::new(0.2 * rng.f64(), 0.3 + 0.5 * rng.f64()),
            );
            let window = [
                centre - a - b,
                centre + a - b,
                centre + a + b,
                centre - a + b,
            ];
            let part = clip(&subject, &window);
            // The common area by counting a fine grid's points in both.
            let (lo, hi) = window
                .iter()
                .fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(l, h), p| {
                    (l.min(*p), h.max(*p))
                });
            let n = 150;
            let cell = (hi - lo) / n as f64;
            let mut inside = 0usize;
            for i in 0..n {
                for j in 0..n {
                    let q = lo + DVec2::new(i as f64 + 0.5, j as f64 + 0.5) * cell;
                    inside += usize::from(winds(&window, q) && winds(&subject, q));
                }
            }
            let counted = inside as f64 * cell.x * cell.y;
            let area = if part.len() < 3 {
                0.0
            } else {
                polygon_area(&part).abs()
            };
            let window_area = polygon_area(&window).abs();
            worst = worst.max((area - counted).abs() / window_area);
            // No corner of the part outside the window or the outline (a clipped
            // corner moved onto a side's line beyond its ends was one); an empty part
            // may be left as points on the window's sides, of no area ([`trim`] drops
            // it).
            if area < 1e-12 {
                continue;
            }
            for q in &part {
                let near = |polygon: &[DVec2]| {
                    polygon
                        .iter()
                        .zip(polygon.iter().cycle().skip(1))
                        .any(|(a, b)| {
                            let t = ((*q - *a).dot(*b - *a) / (*b - *a).length_squared())
                                .clamp(0.0, 1.0);
                            q.distance(*a + t * (*b - *a)) < 1e-9
                        })
                };
                assert!(
                    winds(&window, *q) || near(&window),
                    "{q:?} outside {window:?}"
                );
                assert!(
                    winds(&subject, *q) || near(&subject),
                    "{q:?} outside the outline: window {window:?} part {part:?}"
                );
            }
        }
        // The grid's count is exact to about half a cell along the sides.
        assert!(worst < 0.02, "{worst}");
    }

    #[test]
    fn a_square_cut_by_a_triangle_keeps_the_triangles_part() {
        let window = [
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, 0.0),
            DVec2::new(1.0, 1.0),
            DVec2::new(0.0, 1.0),
        ];
        let triangle = [
            DVec2::new(-1.0, -1.0),
            DVec2::new(3.0, -1.0),
            DVec2::new(-1.0, 3.0),
        ];
        // x + y ≤ 2 within the unit square: all of it; shifted to x + y ≤ 1, half.
        let shifted: Vec<DVec2> = triangle.iter().map(|p| *p - DVec2::splat(0.5)).collect();
        let part = clip(&shifted, &window);
        assert!((polygon_area(&part) - 0.5).abs() < 1e-12, "{part:?}");
        assert_eq!(clip(&triangle, &window).len(), 4);
    }
}
