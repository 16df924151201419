//! Stray points of a scan (monge's extension): points that are not of the surface the
//! rest of the target makes — a bird, a crane, a reflection — which the approximation
//! sets aside ([`TargetCloud::stray`](super::TargetCloud::stray)) rather than bending
//! the mesh and its outline to them.

use glam::DVec3;
use rstar::RTree;

use super::distance::{map_blocks, Indexed};
use super::quadric::{principal_axes, Quadric};
use crate::grid::bbox_diagonal;

/// The other points each point is compared with: its nearest ones.
const OTHERS: usize = 12;

/// Which nearest other point measures how isolated a point is: the 4th, so that two or
/// three stray points together are as isolated as one.
const ISOLATION_RANK: usize = 4;

/// A point is isolated when its [`ISOLATION_RANK`]-th nearest other point is farther
/// than this many times the median of that distance among its nearest others: at the
/// corner of a random sampling or of a grid it is about twice theirs.
const ISOLATED: f64 = 5.0;

/// A point is off the surface when its height above the quadric fitted to its nearest
/// others exceeds this many times their own root-mean-square height above it (noise
/// and the quadric's misfit)…
const OFF_SURFACE: f64 = 20.0;

/// … and this share of the size of the target's points not isolated (the floor for a
/// noiseless target, whose points' heights are round-off: a vertex of a coarse mesh of a
/// curved surface lies off the quadric of its neighbours by the surface's third-order
/// terms, far less).
const OFF_SURFACE_SIZE: f64 = 1e-2;

/// Points closer than this share of the target's size are copies of one point.
const COPIES: f64 = 1e-9;

/// The indices of the stray points of `points` (indexed by `tree`, the target of size
/// `size`), in increasing order: each point isolated from the others (see [`ISOLATED`])
/// or off the surface its nearest others make (see [`OFF_SURFACE`]).
pub(super) fn stray_points(points: &[DVec3], tree: &RTree<Indexed>, size: f64) -> Vec<usize> {
    if points.len() <= OTHERS {
        return Vec::new();
    }
    // Each point's nearest others, nearest first: not its copies (a mesh whose faces
    // do not share their vertices repeats each one).
    let apart = COPIES * size;
    let others: Vec<Vec<usize>> = map_blocks(points.len(), |k| {
        let p = points[k];
        tree.nearest_neighbor_iter(p.to_array())
            .map(|n| n.data)
            .filter(|&j| points[j].distance(p) > apart)
            .take(OTHERS)
            .collect()
    });
    if others.iter().any(|o| o.len() < OTHERS) {
        // Fewer distinct points than that: nothing to compare with.
        return Vec::new();
    }
    let reach: Vec<f64> = points
        .iter()
        .zip(&others)
        .map(|(p, o)| p.distance(points[o[ISOLATION_RANK - 1]]))
        .collect();
    let isolated = map_blocks(points.len(), |k| {
        let mut around: Vec<f64> = others[k][..OTHERS / 2].iter().map(|&j| reach[j]).collect();
        around.sort_by(f64::total_cmp);
        reach[k] > ISOLATED * around[around.len() / 2]
    });
    // The floor of the off-surface test is of the size of the points not isolated: one
    // point far off (a wrong unit, a point at the origin) would raise it past every
    // point a little off the surface.
    let rest: Vec<DVec3> = (0..points.len())
        .filter(|&k| !isolated[k])
        .map(|k| points[k])
        .collect();
    let floor = OFF_SURFACE_SIZE * bbox_diagonal(&rest);
    let stray = map_blocks(points.len(), |k| {
        if isolated[k] {
            return true;
        }
        let near: Vec<DVec3> = others[k].iter().map(|&j| points[j]).collect();
        let centre = near.iter().copied().sum::<DVec3>() / near.len() as f64;
        let quadric = Quadric::fit(&near, centre, principal_axes(&near).2);
        let rms = (near
            .iter()
            .map(|q| quadric.height_above(*q).powi(2))
            .sum::<f64>()
            / near.len() as f64)
            .sqrt();
        let height = quadric.height_above(points[k]).abs();
        height > OFF_SURFACE * rms && height > floor
    });
    (0..points.len()).filter(|&k| stray[k]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `n` random points of `z = 0.04 x² + 0.1 y²` over `[0, 10]²` (seeded), noised by
    /// `noise`.
    fn scan(n: usize, noise: f64, seed: u64) -> Vec<DVec3> {
        let mut rng = fastrand::Rng::with_seed(seed);
        (0..n)
            .map(|_| {
                let (x, y) = (10.0 * rng.f64(), 10.0 * rng.f64());
                let z = 0.04 * x * x + 0.1 * y * y + noise * (2.0 * rng.f64() - 1.0);
                DVec3::new(x, y, z)
            })
            .collect()
    }

    fn stray(points: &[DVec3]) -> Vec<usize> {
        let size = crate::grid::bbox_diagonal(points);
        stray_points(points, &super::super::index::index_of(points), size)
    }

    #[test]
    fn points_off_the_surface_or_apart_are_stray_and_no_other() {
        for seed in 1..=40 {
            let mut points = scan(2000, 2e-3, seed);
            assert_eq!(stray(&points), Vec::<usize>::new(), "seed {seed}");
            let surface = |x: f64, y: f64| 0.04 * x * x + 0.1 * y * y;
            // Above and below the surface by 3 % to 5 % of its size (about 18); beyond
            // its edge on its continuation, 2.5 away (ten spacings); a pair together,
            // three away.
            points.extend([
                DVec3::new(5.0, 5.0, surface(5.0, 5.0) + 1.0),
                DVec3::new(2.0, 8.0, surface(2.0, 8.0) - 0.8),
                DVec3::new(7.0, 3.0, surface(7.0, 3.0) + 0.6),
                DVec3::new(5.0, -2.5, surface(5.0, -2.5)),
                DVec3::new(13.0, 5.0, surface(13.0, 5.0)),
                DVec3::new(13.0, 5.1, surface(13.0, 5.1)),
            ]);
            assert_eq!(
                stray(&points),
                (2000..2006).collect::<Vec<_>>(),
                "seed {seed}"
            );
        }
    }

    #[test]
    fn a_point_far_off_does_not_hide_the_points_a_little_off_the_surface() {
        // A point 1 000 units away (a wrong unit, a point left at the origin of another
        // frame) makes the points' box 50 times larger: the points 0.8 and 1 below and
        // above the surface (4 % and 5 % of its size) are stray all the same.
        let surface = |x: f64, y: f64| 0.04 * x * x + 0.1 * y * y;
        let mut points = scan(2000, 2e-3, 3);
        points.extend([
            DVec3::new(5.0, 5.0, surface(5.0, 5.0) + 1.0),
            DVec3::new(2.0, 8.0, surface(2.0, 8.0) - 0.8),
            DVec3::new(600.0, 600.0, 600.0),
        ]);
        assert_eq!(stray(&points), vec![2000, 2001, 2002]);
    }

    #[test]
    fn a_mesh_whose_faces_repeat_their_vertices_has_no_stray_point() {
        // A 9 × 9 grid's quads each with its own four corners (as a mesh exported
        // without shared vertices): inner vertices four times, edges twice, corners
        // once; and a stray point, twice, above it.
        let at = |i: i32, j: i32| {
            let (x, y) = (f64::from(i), f64::from(j));
            DVec3::new(x, y, 0.2 * x * x - 0.1 * x * y)
        };
        let mut points: Vec<DVec3> = (0..8)
            .flat_map(|i| {
                (0..8).flat_map(move |j| [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)])
            })
            .collect();
        assert_eq!(stray(&points), Vec::<usize>::new());
        let n = points.len();
        points.extend([DVec3::new(4.0, 4.0, 9.0); 2]);
        assert_eq!(stray(&points), vec![n, n + 1]);
    }

    #[test]
    fn a_grid_and_a_graded_sampling_have_no_stray_point() {
        // A coarse grid of a curved surface (its corners, its edges), and a sampling
        // ten times denser on one half than on the other.
        let grid: Vec<DVec3> = (0..81)
            .map(|k| {
                let (x, y) = (f64::from(k % 9), f64::from(k / 9));
                DVec3::new(x, y, 0.2 * x * x - 0.1 * x * y + 0.05 * y * y * y)
            })
            .collect();
        assert_eq!(stray(&grid), Vec::<usize>::new());
        let mut rng = fastrand::Rng::with_seed(9);
        let graded: Vec<DVec3> = (0..3000)
            .map(|k| {
                let x = if k < 2700 {
                    5.0 * rng.f64()
                } else {
                    5.0 + 5.0 * rng.f64()
                };
                let y = 10.0 * rng.f64();
                DVec3::new(x, y, 0.04 * x * x + 0.1 * y * y)
            })
            .collect();
        assert_eq!(stray(&graded), Vec::<usize>::new());
    }
}
