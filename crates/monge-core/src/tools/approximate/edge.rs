//! The target's edge (§4.7, monge's extension): where a mesh's sides stand against the
//! envelope of the target's points, for the least squares (windows along each side), and
//! how far a point lies beyond the target's edge, for the distance (the local hull of
//! the target's points, its sides moved out by the gap a sampling leaves).

use glam::{DVec2, DVec3};
use rstar::RTree;

use crate::grid::QuadGrid;

use super::distance::{Indexed, Triangle};

/// Windows along each side of the mesh in which the edge residuals are measured, at
/// least.
const EDGE_WINDOWS: usize = 2;

/// Windows along each side, at most: each window lets the side bend to its own
/// outermost points, and a side held in many follows their scatter rather than the
/// surface. Held-out scans of 8 000 points, their sides cut into four to six windows by
/// [`WINDOW_SPACINGS`], fell off the target on 2 of 40 samplings (3.5e-1 and 3.7e-2 of
/// the size), 31 within 1e-3; with three at most, 1 (2.5e-2), 34 within 1e-3; with the
/// starts also made from 2 000 of the points (`START_POINTS`), none, 34 within 1e-3,
/// the largest 1.6e-3. Scans of 20 000 points, cut into eight: 2.3e-4–1.1e-3 → with
/// both, 1.9e-4–8.6e-4.
const EDGE_WINDOWS_MAX: usize = 3;

/// Length of an edge window, at least, in mean spacings of the target's points (about
/// as many outermost points as lie along it): a window's outermost offset is the
/// largest of a random sampling's, off by the gap `A / (n·L)` that grows as the window
/// shortens, so a sparse scan keeps long windows; a denser one, whose gaps are small, is
/// held in more (up to [`EDGE_WINDOWS_MAX`]), which follow its edges' shape closer (θ of
/// held-out scans of 2 000 points within 0.3° with three windows on their long sides,
/// 0.9° with two; a scan of 1 500 points of a square roof keeps two, with three its
/// edges are missed by 2.2e-3 of its size).
const WINDOW_SPACINGS: f64 = 35.0;

/// How many windows a side of length `length` is cut into, the target's points being
/// `spacing` apart: one per [`WINDOW_SPACINGS`] spacings, [`EDGE_WINDOWS`] to
/// [`EDGE_WINDOWS_MAX`].
fn windows_along(length: f64, spacing: f64) -> usize {
    let count = length / (WINDOW_SPACINGS * spacing);
    if count.is_finite() {
        (count as usize).clamp(EDGE_WINDOWS, EDGE_WINDOWS_MAX)
    } else {
        EDGE_WINDOWS
    }
}

/// How many windows each side of `grid` is cut into ([`windows_along`]), the target's
/// points being `spacing` apart.
pub(super) fn side_windows(grid: &QuadGrid, spacing: f64) -> [usize; 4] {
    sides(grid).map(|(side, _, _)| {
        let length: f64 = side
            .windows(2)
            .map(|k| grid.vertices[k[0]].distance(grid.vertices[k[1]]))
            .sum();
        windows_along(length, spacing)
    })
}

/// Rows of faces along a side whose matched target points count for its edge.
const EDGE_DEPTH: usize = 3;

/// Outermost offsets of each window whose mean spacing estimates the sampling's gap.
const EDGE_ORDER: usize = 4;

/// On a scan, how many gaps a window's side may stand beyond the outermost point there
/// before its guard counts ([`edge_residuals`]): a window's reading lies inside the
/// truth by more than three gaps (beyond its expected one) once in 55 (e⁻⁴), so the guard
/// leaves a side where the points put it, and holds a side that swings out at one end,
/// which the side's one residual does not see (its outermost point is at the other).
const WINDOW_GUARD_GAPS: f64 = 3.0;

/// One window of a side of the mesh: which side (0 to 3), its length, the offsets of its
/// target points beyond the side (negative inside), and how deep its strip of faces
/// reaches.
pub(super) struct EdgeWindow {
    side: usize,
    length: f64,
    offsets: Vec<f64>,
    depth: f64,
}

/// For a triangle (face `i`, `j`) of a grid of `rows` × `cols` vertices, its place along
/// a side and its depth in rows from it.
type Place = fn(usize, usize, usize, usize) -> (usize, usize);

/// The four sides of `grid`: each its vertices from one end, their neighbours one row
/// inside, and its [`Place`].
fn sides(grid: &QuadGrid) -> [(Vec<usize>, Vec<usize>, Place); 4] {
    let (rows, cols) = (grid.rows, grid.cols);
    [
        (
            (0..cols).collect(),
            (0..cols).map(|j| cols + j).collect(),
            |i, j, _, _| (j, i),
        ),
        (
            (0..cols).map(|j| (rows - 1) * cols + j).collect(),
            (0..cols).map(|j| (rows - 2) * cols + j).collect(),
            |i, j, rows, _| (j, rows - 2 - i),
        ),
        (
            (0..rows).map(|i| i * cols).collect(),
            (0..rows).map(|i| i * cols + 1).collect(),
            |i, j, _, _| (i, j),
        ),
        (
            (0..rows).map(|i| i * cols + cols - 1).collect(),
            (0..rows).map(|i| i * cols + cols - 2).collect(),
            |i, j, _, cols| (i, cols - 2 - j),
        ),
    ]
}

/// The windows of each side of `grid` (`counts` of them: [`side_windows`]), with the
/// offsets of the target points (those of `points` whose index is in `matched`, each
/// with its triangle) matched to faces of their strip.
pub(super) fn edge_windows(
    grid: &QuadGrid,
    points: &[DVec3],
    matched: &[(usize, Triangle)],
    counts: [usize; 4],
) -> Vec<EdgeWindow> {
    let (rows, cols) = (grid.rows, grid.cols);
    let mut windows = Vec::new();
    for (which, ((side, inner, place), count)) in sides(grid).iter().zip(counts).enumerate() {
        let v = |k: usize| grid.vertices[side[k]];
        let m = side.len() - 1;
        // The outward direction at each vertex of the side: from its inner neighbour,
        // across the side.
        let outward: Vec<DVec3> = (0..=m)
            .map(|k| {
                let tangent = (v(k.min(m - 1) + 1) - v(k.saturating_sub(1))).normalize_or_zero();
                let out = v(k) - grid.vertices[inner[k]];
                (out - out.dot(tangent) * tangent).normalize_or_zero()
            })
            .collect();
        let row = (0..=m)
            .map(|k| v(k).distance(grid.vertices[inner[k]]))
            .sum::<f64>()
            / (m + 1) as f64;
        // No shorter than one edge of the mesh.
        let count = count.min(m);
        let window_of = |k: usize| (k * count / m).min(count - 1);
        let mut these: Vec<EdgeWindow> = (0..count)
            .map(|_| EdgeWindow {
                side: which,
                length: 0.0,
                offsets: Vec::new(),
                depth: EDGE_DEPTH as f64 * row,
            })
            .collect();
        for k in 0..m {
            these[window_of(k)].length += v(k).distance(v(k + 1));
        }
        for (k, t) in matched {
            let p = &points[*k];
            let (along, depth) = place(t.0, t.1, rows, cols);
            if depth >= EDGE_DEPTH {
                continue;
            }
            // The nearer of the face's two vertices on the side.
            let k = if p.distance(v(along)) <= p.distance(v(along + 1)) {
                along
            } else {
                along + 1
            };
            these[window_of(along)]
                .offsets
                .push((*p - v(k)).dot(outward[k]));
        }
        windows.extend(these);
    }
    windows
}

/// The residuals of the sides ([`TargetCloud::residuals`](super::TargetCloud::residuals)),
/// in model units: where each side stands against the outermost target points along it
/// plus the gap the sampling leaves beyond them (nil on a mesh, whose vertices lie on its
/// edges). A window without points (the mesh reaches far beyond the target there) has
/// its outermost point at least its strip's depth inside.
///
/// On a mesh (`sampled` false), one residual a window: the windows read its edge
/// exactly. On a random sampling (`sampled`), one residual a side, from its outermost
/// point along its whole length, and one a window, nil unless the side stands more than
/// [`WINDOW_GUARD_GAPS`] gaps beyond the window's outermost point (a guard against a
/// side swinging out at one end). A side is one curvature line of the surface, so its
/// place is one number once the surface is found; the windows each read their edge off
/// by their own gap (`A / (n·L)` along a length `L`: half a side's, twice its gap), and a
/// side held in each bends the surface to their scatter. Held-out scans of 2 000 points
/// on 80 samplings (seeds 1 to 16), brute force: within 1e-3 both ways
/// 20 → 43 times (with the vertices' corner allowance,
/// [`TargetCloud::residuals`](super::TargetCloud::residuals)), the largest 8.8e-3 →
/// 8.0e-3; of 8 000 points (seeds 1 to 8) 34 → 35 of 40, but the largest 1.6e-3 →
/// 6.0e-3 (a moulding; reading only the sides of dense scans in windows was no better:
/// 2 000 points 18 of 40 on seeds 1 to 8, where some sides hold three windows).
pub(super) fn edge_residuals(windows: &[EdgeWindow], sampled: bool) -> Vec<f64> {
    // Each window's outermost offset.
    let outer: Vec<f64> = windows
        .iter()
        .map(|w| {
            w.offsets
                .iter()
                .copied()
                .reduce(f64::max)
                .unwrap_or(-w.depth)
        })
        .collect();
    // Area per point: the mean spacing of the outermost offsets times the window's length.
    let (mut sum, mut count) = (0.0, 0usize);
    for (w, first) in windows.iter().zip(&outer) {
        if w.offsets.len() >= EDGE_ORDER {
            let mut o = w.offsets.clone();
            let last = *o
                .select_nth_unstable_by(EDGE_ORDER - 1, |a, b| b.total_cmp(a))
                .1;
            sum += (first - last) / (EDGE_ORDER - 1) as f64 * w.length;
            count += 1;
        }
    }
    let area_per_point = sum / count.max(1) as f64;
    let gap = |length: f64| area_per_point / length.max(f64::MIN_POSITIVE);
    let mut out = Vec::with_capacity(windows.len() + 4);
    for side in 0..4 {
        let these = || {
            windows
                .iter()
                .zip(&outer)
                .filter(move |(w, _)| w.side == side)
        };
        if !sampled {
            out.extend(these().map(|(w, o)| o + gap(w.length)));
            continue;
        }
        let length: f64 = these().map(|(w, _)| w.length).sum();
        // Every side has a window at least.
        let outermost = these().map(|(_, o)| *o).fold(f64::NEG_INFINITY, f64::max);
        out.push(outermost + gap(length));
        out.extend(these().map(|(w, o)| {
            let reading = o + gap(w.length);
            (reading + WINDOW_GUARD_GAPS * gap(w.length)).min(0.0)
        }));
    }
    out
}

/// Target points around a vertex among which the target's edge near it is sought: on a
/// random sampling a half disc about 16 mean spacings in radius at a side, 22 at a
/// corner, enough for each side to hold several outermost points away from the ends of
/// the window, which its disc thins (with half as many, a scan's edge was read 4
/// spacings short in places); on a mesh six or seven rows.
pub(super) const EDGE_NEIGHBOURS: usize = 96;

/// A side of the points' convex hull stands for the target's edge when the points lie
/// thick along it: its fifth outermost point within this many mean spacings of it. Along
/// a side of a random sampling that depth is about half a spacing (the points of a strip
/// of the half disc a side sees), at a corner's cut about two (a corner's points thin
/// out as a triangle towards its tip), on a mesh's sides nil, at its corners (the cut of
/// a mesh's corner has a single point on it) √2.
const SIDE_DEPTH: f64 = 1.0;

/// How far `q` lies beyond the target's edge near it (model units, 0 within): `near` are
/// the target's points around `q` ([`EDGE_NEIGHBOURS`]), in a plane (its tangent plane),
/// `spacing` their mean distance to their nearest.
///
/// The edge is the intersection of the half-planes of the sides of `near`'s convex hull
/// along which the points lie thick ([`SIDE_DEPTH`]), each side moved out by the gap the
/// sampling leaves beyond its outermost points (the mean spacing of the next three, as
/// for the largest of a uniform sample: nil on a mesh's edge, whose vertices are on it):
/// a corner is where its two sides meet, not the chord across the corner that a random
/// sampling's hull cuts; `q`'s distance to it is measured in any direction (beyond a
/// corner as beyond a side). A concave edge is bridged by the hull over the width of
/// `near`.
pub(super) fn beyond_edge(q: DVec2, near: &[DVec2], spacing: f64) -> f64 {
    let hull = convex_hull(near);
    if hull.len() < 3 {
        return 0.0;
    }
    let sides: Vec<(DVec2, DVec2)> = (0..hull.len())
        .map(|k| (hull[k], hull[(k + 1) % hull.len()]))
        .collect();
    if sides.iter().all(|(a, b)| (*b - *a).perp_dot(q - *a) >= 0.0) {
        return 0.0;
    }
    // Each side as a line `n · x = c`, `n` its outward normal, moved out by its gap, with
    // the depth of its fifth outermost point.
    let lines: Vec<(DVec2, f64, f64)> = sides
        .iter()
        .map(|(a, b)| {
            let d = (*b - *a).normalize();
            let n = DVec2::new(d.y, -d.x);
            let mut depths: Vec<f64> = near.iter().map(|p| n.dot(*a - *p)).collect();
            let k = depths.len().min(5) - 1;
            let fifth = *depths.select_nth_unstable_by(k, f64::total_cmp).1;
            (n, n.dot(*a) + fifth / 3.0, fifth)
        })
        .collect();
    let thick = lines.iter().filter(|l| l.2 <= SIDE_DEPTH * spacing);
    let edge: Vec<(DVec2, f64)> = if thick.clone().next().is_some() {
        thick.map(|l| (l.0, l.1)).collect()
    } else {
        lines.iter().map(|l| (l.0, l.1)).collect()
    };
    distance_to_polygon(q, &edge, 1e-9 * spacing)
}

/// The distance from `q` to the intersection of the half-planes `n · x ≤ c` of `lines`
/// (0 within): the nearest of the feet of `q` on the lines and of the lines' crossings
/// that lie within all of them (within `tolerance`).
fn distance_to_polygon(q: DVec2, lines: &[(DVec2, f64)], tolerance: f64) -> f64 {
    let outside = |x: DVec2| {
        lines
            .iter()
            .map(|(n, c)| n.dot(x) - c)
            .fold(f64::NEG_INFINITY, f64::max)
    };
    let beyond = outside(q);
    if beyond <= 0.0 {
        return 0.0;
    }
    let feet = lines.iter().map(|(n, c)| q - (n.dot(q) - c) * *n);
    let crossings = lines.iter().enumerate().flat_map(|(k, (n, c))| {
        lines[k + 1..].iter().filter_map(move |(m, e)| {
            let det = n.perp_dot(*m);
            (det.abs() > 1e-12).then(|| DVec2::new(c * m.y - e * n.y, n.x * e - m.x * c) / det)
        })
    });
    let nearest = feet
        .chain(crossings)
        .filter(|x| outside(*x) <= tolerance)
        .map(|x| x.distance(q))
        .fold(f64::INFINITY, f64::min);
    // Rounding could leave no candidate within: the largest excess, a lower bound.
    if nearest.is_finite() {
        nearest
    } else {
        beyond
    }
}

/// The convex hull of `points`, counter-clockwise, without collinear points (Andrew's
/// monotone chain).
fn convex_hull(points: &[DVec2]) -> Vec<DVec2> {
    // `+ 0.0` makes -0 +0, which the order below would put first.
    let mut sorted: Vec<DVec2> = points.iter().map(|p| *p + 0.0).collect();
    sorted.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    sorted.dedup();
    if sorted.len() < 3 {
        return sorted;
    }
    let mut hull: Vec<DVec2> = Vec::with_capacity(2 * sorted.len());
    let turns_left = |hull: &[DVec2], p: DVec2| {
        let (a, b) = (hull[hull.len() - 2], hull[hull.len() - 1]);
        (b - a).perp_dot(p - a) > 0.0
    };
    for p in &sorted {
        while hull.len() >= 2 && !turns_left(&hull, *p) {
            hull.pop();
        }
        hull.push(*p);
    }
    let lower = hull.len() + 1;
    for p in sorted.iter().rev().skip(1) {
        while hull.len() >= lower && !turns_left(&hull, *p) {
            hull.pop();
        }
        hull.push(*p);
    }
    hull.pop();
    hull
}

/// Whether the boundary points of a target are evenly spaced along its edge, as a
/// mesh's boundary vertices are: the distances from each to its nearest boundary point
/// vary by less than [`REGULAR_EDGE`] of their mean (a random sampling's by about half).
pub(super) fn regular_edge(boundary: &RTree<Indexed>) -> bool {
    let gaps: Vec<f64> = boundary
        .iter()
        .filter_map(|b| {
            boundary
                .nearest_neighbor_iter(*b.geom())
                .nth(1)
                .map(|n| DVec3::from_array(*n.geom()).distance(DVec3::from_array(*b.geom())))
        })
        .collect();
    if gaps.len() < 8 {
        return false;
    }
    let mean = gaps.iter().sum::<f64>() / gaps.len() as f64;
    let var = gaps.iter().map(|g| (g - mean).powi(2)).sum::<f64>() / gaps.len() as f64;
    mean > 0.0 && var.sqrt() < REGULAR_EDGE * mean
}

/// Largest coefficient of variation of the boundary points' spacing of a target whose
/// boundary points lie on its edge ([`regular_edge`]).
const REGULAR_EDGE: f64 = 0.25;

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::approximate::TargetCloud;

    /// A flat mesh of 10 × 10 faces over the unit square (z = 0).
    pub(in crate::tools::approximate) fn unit_square() -> QuadGrid {
        let vertices: Vec<DVec3> = (0..121)
            .map(|k| DVec3::new((k / 11) as f64 / 10.0, (k % 11) as f64 / 10.0, 0.0))
            .collect();
        QuadGrid::new(11, 11, vertices, vec![DVec3::Z; 121])
    }

    /// `n` uniform random points of the unit square (z = 0).
    pub(in crate::tools::approximate) fn square(rng: &mut fastrand::Rng, n: usize) -> Vec<DVec3> {
        (0..n)
            .map(|_| DVec3::new(rng.f64(), rng.f64(), 0.0))
            .collect()
    }

    /// The edge residuals of `grid` against `points` (model units), read as the target
    /// is (a mesh's or a scan's).
    fn edges_of(grid: &QuadGrid, points: &[DVec3]) -> Vec<f64> {
        let target = TargetCloud::new(points).unwrap();
        let m = target.matches(grid, 1);
        let windows = edge_windows(grid, &target.points, &m.points, m.windows);
        edge_residuals(&windows, !target.edge_on_points)
    }

    /// The edge residuals of the unit square against `points` (model units).
    fn edges(points: &[DVec3]) -> Vec<f64> {
        edges_of(&unit_square(), points)
    }

    #[test]
    fn a_sides_residual_is_nil_on_a_meshs_boundary_and_unbiased_on_a_random_sampling() {
        // A 21 × 21 grid on the square: its boundary points lie on the sides, no gap.
        let grid: Vec<DVec3> = (0..441)
            .map(|k| DVec3::new((k / 21) as f64 / 20.0, (k % 21) as f64 / 20.0, 0.0))
            .collect();
        for r in edges(&grid) {
            assert!(r.abs() < 1e-12, "{r:e}");
        }
        // 2 000 uniform random points: the outermost point of a side (length 1) lies
        // inside it by 1/2000 on average, of a window of length L (half a side) by
        // 1/(2000·L) = 1e-3; with the gap estimated from the spacing of the outermost
        // points, a side's residual (its offset from the estimated edge) is nil on
        // average, and its windows' guards nil but where a window's outermost point lies
        // more than four gaps inside (e⁻⁴, 1.8 %). 40 samplings, 4 sides of 2 windows.
        let mut rng = fastrand::Rng::with_seed(7);
        let (mut with_gap, mut outermost, mut count) = (0.0, 0.0, 0.0);
        let (mut guards, mut held) = (0, 0);
        for _ in 0..40 {
            let points = square(&mut rng, 2000);
            let residuals = edges(&points);
            assert_eq!(residuals.len(), 4 * 3);
            for side in residuals.chunks(3) {
                with_gap += side[0];
                count += 1.0;
                guards += 2;
                held += side[1..].iter().filter(|g| **g != 0.0).count();
                assert!(side[1..].iter().all(|g| *g <= 0.0));
            }
            // The outermost offset alone, from the mesh's windows, less its expected gap.
            let grid = unit_square();
            let target = TargetCloud::new(&points).unwrap();
            let m = target.matches(&grid, 1);
            for w in edge_windows(&grid, &target.points, &m.points, m.windows) {
                outermost += w.offsets.iter().copied().fold(f64::NEG_INFINITY, f64::max)
                    + 1.0 / (2000.0 * w.length);
            }
        }
        let (with_gap, outermost) = (with_gap / count, outermost / (2.0 * count));
        // Standard errors of the means: 5e-4 / √160 ≈ 4e-5 (sides), 1e-3 / √320 ≈ 6e-5.
        assert!(with_gap.abs() < 1.5e-4, "{with_gap:e}");
        assert!(outermost.abs() < 2e-4, "{outermost:e}");
        // 1.8 % of 320 guards: about 6 (fewer than 20 but at one in a thousand).
        assert!(held < 20, "{held} of {guards}");
    }

    #[test]
    fn a_scans_side_swung_out_at_one_end_is_held_by_its_windows_guard() {
        // The unit square's first side (x = 0) turned out about its end at y = 0, to
        // x = −0.05 at y = 1, against 2 000 random points of the square: the side's
        // outermost point, near its end that stays, reads it about where it was (within
        // a fifth of the swing, its outermost point's place along it); the guard of
        // the window at the far end, where it stands 0.025 to 0.05 beyond the points,
        // holds it (by the 0.025 it stands out less four gaps of about 1e-3).
        let mut rng = fastrand::Rng::with_seed(3);
        let points = square(&mut rng, 2000);
        let mut grid = unit_square();
        for j in 0..11 {
            grid.vertices[j].x = -0.05 * grid.vertices[j].y;
        }
        let swung = edges_of(&grid, &points);
        assert!(swung[0].abs() < 1e-2, "{:e}", swung[0]);
        assert!(swung[1] > -0.01 && swung[2] < -0.015, "{:?}", &swung[..3]);
        let square = edges(&points);
        assert!(square[1] == 0.0 && square[2] == 0.0, "{:?}", &square[..3]);
    }

    #[test]
    fn a_dense_scans_edges_are_read_from_every_point_near_them() {
        // 20 000 random points, matched every fifth (as a fit reads a dense target): the
        // windows' residuals are those of all the points, because every point near the
        // target's edge is matched; every fifth alone leaves the edges about five times
        // the gap inside.
        let mut rng = fastrand::Rng::with_seed(5);
        let points = square(&mut rng, 20_000);
        let grid = unit_square();
        let target = TargetCloud::new(&points).unwrap();
        let residuals = |stride: usize| {
            let m = target.matches(&grid, stride);
            // Every point, or every fifth and those near the edge: fewer than half.
            assert!(
                stride == 1 || m.points.len() < points.len() / 2,
                "{}",
                m.points.len()
            );
            let windows = edge_windows(&grid, &target.points, &m.points, m.windows);
            edge_residuals(&windows, !target.edge_on_points)
        };
        let (every, fifth) = (residuals(1), residuals(5));
        assert_eq!(every.len(), fifth.len());
        for (a, b) in every.iter().zip(&fifth) {
            assert!((a - b).abs() < 1e-12, "{a:e} {b:e}");
        }
    }

    #[test]
    fn a_dense_scan_holds_each_side_in_more_windows_than_a_sparse_one() {
        // Points of a planar Poisson sampling of density n are 1/(2√n) from their nearest
        // on average: a unit side is about 2√n spacings long, 89 for 2 000 points of the
        // unit square and 200 for 10 000 (fewer near the edges, where the nearest lie
        // on one side only). A window is at least 35 spacings long, and a side has three
        // at most.
        let grid = unit_square();
        let count = |points: &[DVec3]| {
            let target = TargetCloud::new(points).unwrap();
            let m = target.matches(&grid, 1);
            edge_windows(&grid, &target.points, &m.points, m.windows).len()
        };
        let mut rng = fastrand::Rng::with_seed(11);
        assert_eq!(count(&square(&mut rng, 2000)), 4 * 2);
        assert_eq!(count(&square(&mut rng, 10_000)), 4 * 3);
        // A mesh's 21 × 21 vertices: 20 spacings a side, two windows.
        let vertices: Vec<DVec3> = (0..441)
            .map(|k| DVec3::new((k / 21) as f64 / 20.0, (k % 21) as f64 / 20.0, 0.0))
            .collect();
        assert_eq!(count(&vertices), 4 * 2);
    }
}
