//! The initial guesses of an approximation (§4.7, monge's extension, step 1): corner,
//! principal frame and guides fitted to the target's sections at each corner.

use glam::DVec3;

use super::boundary_trace::boundary_start;
use super::fit_guide::section_guide;
use super::index::TargetCloud;
use super::quadric::{check_curvature, principal_axes, Quadric};
use super::{ApproxError, MIN_POINTS};

/// The initial guess: corner, frame and each guide's control points in its plane.
#[derive(Clone, Debug)]
pub(super) struct Start {
    pub(super) corner: DVec3,
    /// guide_u's start tangent, guide_v's, and their normal.
    pub(super) frame: [DVec3; 3],
    /// Per guide: the second control point's distance along the tangent, then
    /// `(along, up)` of each later control point.
    pub(super) guides: [Vec<f64>; 2],
    /// Tilt of each guide's plane about its start tangent (see [`design_of`]).
    pub(super) tilts: [f64; 2],
    /// Whether the guides are the target's own boundary curves ([`boundary_start`]).
    pub(super) on_boundary: bool,
    pub(super) curvatures: (f64, f64),
}

/// Corner, principal frame and guides fitted to the target's sections (step 1), at
/// each of the target's four corners along the principal directions at its centre.
pub(super) fn initial_guesses(target: &TargetCloud) -> Result<Vec<Start>, ApproxError> {
    let points = &target.points;
    let size = target.size;
    let centroid = points.iter().copied().sum::<DVec3>() / points.len() as f64;
    let global = Quadric::fit(points, centroid, principal_axes(points).2);
    let (u, v) = global.uv(centroid);
    let centre = global.principal(u, v);
    check_curvature(&centre, size, "the centre")?;
    let mut starts = Vec::with_capacity(4);
    let mut refused = None;
    for (s1, s2) in [(1.0, 1.0), (-1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)] {
        let (d1, d2) = (s1 * centre.d1, s2 * centre.d2);
        // The corner: least coordinates along the principal directions at the centre.
        let low = |d: DVec3| {
            points
                .iter()
                .map(|p| (*p - centre.point).dot(d))
                .fold(f64::INFINITY, f64::min)
        };
        let guess = centre.point + low(d1) * d1 + low(d2) * d2;
        // The corner's own quadric, from its nearest tenth of the target.
        let count = (points.len() / 10).max(MIN_POINTS);
        let near: Vec<DVec3> = target
            .tree
            .nearest_neighbor_iter(guess.to_array())
            .take(count)
            .map(|n| DVec3::from_array(*n.geom()))
            .collect();
        let (cu, cv) = global.uv(guess);
        let local = Quadric::fit(&near, global.principal(cu, cv).point, centre.normal);
        let (lu, lv) = local.uv(guess);
        let corner = local.principal(lu, lv);
        if let Err(e) = check_curvature(&corner, size, "a corner") {
            refused.get_or_insert(e);
            continue;
        }
        // Start tangents pointing into the target: the corner's principal direction
        // nearer each of the centre's, turned along it.
        let (a, b) = if corner.d1.dot(d1).abs() >= corner.d1.dot(d2).abs() {
            (corner.d1, corner.d2)
        } else {
            (corner.d2, corner.d1)
        };
        let t_u = a * a.dot(d1).signum();
        let t_v = b * b.dot(d2).signum();
        let n = t_u.cross(t_v);
        let guide = |t: DVec3, other: DVec3| section_guide(points, corner.point, t, other, n, size);
        starts.push(Start {
            corner: corner.point,
            frame: [t_u, t_v, n],
            guides: [guide(t_u, t_v), guide(t_v, t_u)],
            tilts: [0.0; 2],
            on_boundary: false,
            curvatures: (corner.k1, corner.k2),
        });
        // The target's own corner there, and its boundary curves from it.
        if let Some(start) = boundary_start(target, d1, d2, (corner.k1, corner.k2)) {
            starts.push(start);
        }
    }
    match refused {
        Some(e) if starts.is_empty() => Err(e),
        _ => Ok(starts),
    }
}
