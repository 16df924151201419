//! `approximate` on held-out targets built independently of monge-core (closed forms
//! in `heldout/`), as meshes and as noised scans, rotated and far from the origin;
//! every distance measured by brute force on fine samplings of both surfaces.

use crate::heldout;

use std::time::Instant;

use glam::DVec3;
use heldout::{fold_theta, max_both_ways, max_both_ways_trimmed, target, targets, Triangles};
use monge_core::approximate::{approximate, ApproxOptions};
use monge_core::QuadGrid;

#[test]
fn the_brute_force_distance_measures_a_known_offset() {
    // A flat 2 × 2 grid at z = 0, points 0.3 above and 0.4 beside it.
    let vertices = (0..9)
        .map(|k| DVec3::new((k / 3) as f64, (k % 3) as f64, 0.0))
        .collect();
    let grid = QuadGrid::new(3, 3, vertices, vec![DVec3::Z; 9]);
    let faces = Triangles::of_grid(&grid);
    assert!((faces.distance(DVec3::new(0.7, 1.2, 0.3)) - 0.3).abs() < 1e-12);
    assert!((faces.distance(DVec3::new(2.4, 1.0, 0.0)) - 0.4).abs() < 1e-12);
}

#[test]
fn the_held_out_targets_have_the_theta_of_their_family() {
    let all = targets();
    let theta = |name: &str| all.iter().find(|t| t.name == name).unwrap().theta_folded;
    // Surfaces of revolution and moulding surfaces: θ = 0° or ±180° (§4.1).
    assert!(theta("torus patch") < 1e-3, "{}", theta("torus patch"));
    for name in ["moulding", "sine moulding", "onion dome"] {
        assert!(theta(name) < 1e-3, "{name}: {}", theta(name));
    }
    // A Dupin cyclide that is not a torus: between.
    let cyclide = theta("Dupin cyclide");
    assert!(cyclide > 5.0 && cyclide < 85.0, "{cyclide}");
    assert_eq!(fold_theta(-30.0), 30.0);
    assert_eq!(fold_theta(150.0), 30.0);
    assert_eq!(fold_theta(-179.0), 1.0);
}

/// The measurement on every held-out target, meshes and scans (default settings):
/// `cargo test -p monge-core-tests --test integration approximate_heldout:: -- --ignored --nocapture`
/// (`HELDOUT=torus` measures only the targets whose name contains it).
#[test]
#[ignore = "a measurement (a few minutes); prints the table"]
fn measure_every_held_out_target() {
    println!(
        "| target | sampling | result → target | target → result | read by monge | θ found (folded) | θ true | time s | meshes |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    let only = std::env::var("HELDOUT").unwrap_or_default();
    for target in targets().into_iter().filter(|t| t.name.contains(&only)) {
        let samplings = [
            ("mesh 41 × 41", target.grid(41)),
            ("scan 2000, 1e-4", target.scan(2000, 1e-4, 7)),
        ];
        for (sampling, points) in samplings {
            let clock = Instant::now();
            let result = approximate(&points, &ApproxOptions::default(), &mut |_| {});
            let seconds = clock.elapsed().as_secs_f64();
            match result {
                Ok(a) => {
                    let (to_target, to_result) = max_both_ways(&target, &a.grid);
                    println!(
                        "| {} | {sampling} | {to_target:.1e} | {to_result:.1e} | {:.1e} / {:.1e} | {:.2} | {:.2} | {seconds:.1} | {} |",
                        target.name,
                        a.after.mesh_to_target_max,
                        a.after.target_to_mesh_max,
                        fold_theta(a.design.theta_deg),
                        target.theta_folded,
                        a.evaluations
                    );
                }
                Err(e) => println!(
                    "| {} | {sampling} | refused: {e} | | | | | {seconds:.1} | |",
                    target.name
                ),
            }
        }
    }
}

/// What the scan measurements measure, from the environment: the held-out targets with
/// planar curvature lines whose name contains `HELDOUT` (all), scans of `HELDOUT_POINTS`
/// points (2 000), and eight seeds from `HELDOUT_FIRST_SEED` (1).
fn scans_chosen() -> (Vec<heldout::Target>, usize, std::ops::Range<u64>) {
    let only = std::env::var("HELDOUT").unwrap_or_default();
    let count = std::env::var("HELDOUT_POINTS").map_or(2000, |n| n.parse().unwrap());
    let first: u64 = std::env::var("HELDOUT_FIRST_SEED").map_or(1, |n| n.parse().unwrap());
    let chosen = targets()
        .into_iter()
        .filter(|t| t.pcl && t.name.contains(&only))
        .collect();
    (chosen, count, first..first + 8)
}

/// The scans of the held-out surfaces with planar curvature lines on eight random
/// samplings each (seeds 1 to 8; 2 000 points, noise 1e-4 of the size, default
/// settings): per sampling the larger of the two largest distances (brute force), `*`
/// within 1e-3. One sampling hides a search that falls off the target on another, and
/// the searches were tuned on these eight: measure others too (`HELDOUT_FIRST_SEED=9`,
/// seeds 9 to 16):
/// `cargo test -p monge-core-tests --test integration approximate_heldout:: -- --ignored --nocapture`
/// (`HELDOUT=onion` measures only the targets whose name contains it,
/// `HELDOUT_POINTS=20000` scans of that many points).
#[test]
#[ignore = "a measurement (a few minutes); prints one line per surface"]
fn measure_scans_on_eight_samplings() {
    let (chosen, count, seeds) = scans_chosen();
    for target in chosen {
        let mut line = format!("{}:", target.name);
        let (mut within, mut theta_within) = (0, 0);
        for seed in seeds.clone() {
            let points = target.scan(count, 1e-4, seed);
            match approximate(&points, &ApproxOptions::default(), &mut |_| {}) {
                Ok(a) => {
                    let (to_target, to_result) = max_both_ways(&target, &a.grid);
                    let largest = to_target.max(to_result);
                    within += usize::from(largest <= 1e-3);
                    let mark = if largest <= 1e-3 { "*" } else { "" };
                    let theta = (fold_theta(a.design.theta_deg) - target.theta_folded).abs();
                    theta_within += usize::from(theta <= 0.5);
                    line += &format!(" {largest:.1e}{mark}");
                }
                Err(e) => line += &format!(" refused ({e})"),
            }
        }
        println!("{line}; {within} of 8 within 1e-3, θ within 0.5° {theta_within} of 8");
    }
}

/// Asserts that a scan of `count` points of the held-out surface `name` (noised by 1e-4 of
/// its size, from `seed`) is recovered: within 1e-3 of its size both ways by brute force,
/// θ within 0.5°.
fn assert_scan_recovered(name: &str, count: usize, seed: u64) {
    assert_scan_near(name, count, seed, 1e-3);
}

/// [`assert_scan_recovered`] within `bound` of the size both ways.
fn assert_scan_near(name: &str, count: usize, seed: u64, bound: f64) {
    let target = target(name);
    let points = target.scan(count, 1e-4, seed);
    let a = approximate(&points, &ApproxOptions::default(), &mut |_| {}).unwrap();
    let (to_target, to_result) = max_both_ways(&target, &a.grid);
    assert!(
        to_target.max(to_result) <= bound,
        "{name}: {to_target:e} {to_result:e}"
    );
    let theta = fold_theta(a.design.theta_deg);
    assert!(
        (theta - target.theta_folded).abs() <= 0.5,
        "{name}: {theta}"
    );
}

#[test]
fn dense_scans_are_recovered_to_their_edges() {
    // Scans denser than the 2 000 points the starts were made on, noised by 1e-4 of the
    // size: a fit reads every fifth point of 20 000 and every point near the edges, and
    // starts from 2 000 of them. Measured by brute force: the moulding 3.3e-4 both ways
    // (2.7e-3 reading every fifth point alone), the Dupin cyclide 2.4e-4 (3.5e-1 started
    // from all 8 000 points and its sides cut into five windows: off the target).
    assert_scan_recovered("moulding", 20_000, 2);
    assert_scan_recovered("Dupin cyclide", 8000, 2);
}

#[test]
fn a_scan_whose_least_squares_stall_at_a_wrong_theta_is_restarted_from_another() {
    // 8 000 points of the moulding: from every start the least squares stall at θ 22.7°,
    // 3.3e-2 of the size off (brute force). Run again from θ 0°, the best of a scan every
    // 10° with the rest of their result kept, they come to 1.03e-3 both ways, θ 0° (7.8e-4
    // while the sides of a scan were read in windows rather than whole, which brought
    // half as many held-out scans of 2 000 points within 1e-3; BOBYQA from the starts,
    // before: 1.6e-3 in 23 s).
    assert_scan_near("moulding", 8000, 5, 1.5e-3);
}

#[test]
fn a_scan_within_a_tolerance_but_at_its_edge_keeps_its_one_patch_and_says_so() {
    // 2 000 points of the torus patch under a tolerance of 1e-3: one patch comes 1.4e-3
    // from the surface both ways (brute force), and every scan point within 1e-3 of it,
    // but its corners read 1.0e-2 beyond the scan's outermost points, which leave the
    // corners bare. Compared by that reading, four patches came nearer (5.9e-3 read) and
    // were kept, 6.1e-3 from the surface: their corners pulled in to the outermost points.
    use monge_core::approximate::{
        approximate_to_tolerance, Chosen, Stop, TargetCloud, Tolerance, ToleranceOptions,
    };
    let target = target("torus patch");
    let points = target.scan(2000, 1e-4, 7);
    let options = ToleranceOptions {
        tolerance: Tolerance::Relative(1e-3),
        ..Default::default()
    };
    let fit = approximate_to_tolerance(&points, &options, &mut |_| {}).unwrap();
    assert_eq!(fit.chosen, Chosen::OnePatch);
    let overread = TargetCloud::new(&points).unwrap().edge_overread();
    assert_eq!(fit.stop, Stop::ScanEdge { overread });
    assert!(!fit.met() && fit.stop.scan_edge_reason(1.0).is_some());
    // Read beyond the tolerance, within it less what the reading may overstate.
    let read = fit.deviation;
    assert!(read.mesh_to_target_max > 1e-3 && read.target_to_mesh_max <= 1e-3);
    assert!(read.mesh_to_target_max - overread <= 1e-3);
    let (to_target, to_result) = max_both_ways(&target, &fit.grid);
    assert!(
        to_target.max(to_result) <= 2e-3,
        "{to_target:e} {to_result:e}"
    );
}

/// The free-form held-out targets (no planar curvature lines), as meshes and scans,
/// fitted to cover them and trimmed to their outline (`trim`, default settings
/// otherwise): the largest distances both ways, brute force, against the untrimmed
/// fit's: `cargo test -p monge-core-tests --test integration approximate_heldout:: --
/// --ignored --nocapture` (`HELDOUT=Bézier` measures only the targets whose name
/// contains it).
#[test]
#[ignore = "a measurement (a few minutes); prints the table"]
fn measure_free_form_trimmed() {
    println!("| target | sampling | trimmed: result → target | target → result | read by monge | untrimmed (max both ways) | time s |");
    println!("|---|---|---|---|---|---|---|");
    let only = std::env::var("HELDOUT").unwrap_or_default();
    for target in targets()
        .into_iter()
        .filter(|t| !t.pcl && t.name.contains(&only))
    {
        for (sampling, points) in [
            ("mesh 41 × 41", target.grid(41)),
            ("scan 2000, 1e-4", target.scan(2000, 1e-4, 7)),
        ] {
            let clock = Instant::now();
            let trim = ApproxOptions {
                trim: true,
                ..Default::default()
            };
            let result = approximate(&points, &trim, &mut |_| {});
            let seconds = clock.elapsed().as_secs_f64();
            let untrimmed = approximate(&points, &ApproxOptions::default(), &mut |_| {})
                .map(|a| {
                    let (a, b) = max_both_ways(&target, &a.grid);
                    format!("{:.1e}", a.max(b))
                })
                .unwrap_or_else(|e| format!("refused: {e}"));
            match result {
                Ok(a) => {
                    let trimmed = a.trimmed.as_ref().expect("a trimmed mesh");
                    let (to_target, to_result) = max_both_ways_trimmed(&target, trimmed);
                    println!(
                        "| {} | {sampling} | {to_target:.1e} | {to_result:.1e} | {:.1e} / {:.1e} | {untrimmed} | {seconds:.1} |",
                        target.name, a.after.mesh_to_target_max, a.after.target_to_mesh_max,
                    );
                }
                Err(e) => println!(
                    "| {} | {sampling} | refused: {e} | | | {untrimmed} | {seconds:.1} |",
                    target.name
                ),
            }
        }
    }
}

/// A held-out free-form target `name` (every vertex of a 41 × 41 mesh) fitted with
/// `--trim` at default settings: its trimmed mesh's largest distances both ways, brute
/// force against the closed form, and the untrimmed fit's (the larger of the two).
fn trimmed_against_untrimmed(name: &str) -> ((f64, f64), f64) {
    let target = target(name);
    let points = target.grid(41);
    let trim = ApproxOptions {
        trim: true,
        ..Default::default()
    };
    let a = approximate(&points, &trim, &mut |_| {}).unwrap();
    let trimmed = max_both_ways_trimmed(&target, a.trimmed.as_ref().unwrap());
    let b = approximate(&points, &ApproxOptions::default(), &mut |_| {}).unwrap();
    let (x, y) = max_both_ways(&target, &b.grid);
    eprintln!(
        "{name}: trimmed {:.1e} / {:.1e}, untrimmed {:.1e}",
        trimmed.0,
        trimmed.1,
        x.max(y)
    );
    (trimmed, x.max(y))
}

#[test]
fn roofs_whose_edges_are_not_curvature_lines_are_met_once_trimmed() {
    // A hyperbolic paraboloid and a spherical cap over rectangles: no grid of curvature
    // lines ends on their edges (untrimmed, measured 2.0e-1 and 1.8e-2 of the size).
    // Measured trimmed: 1.2e-4 / 1.8e-4 and 8.2e-5 / 2.4e-4.
    for name in ["hyperbolic paraboloid", "spherical cap"] {
        let ((to_target, to_result), untrimmed) = trimmed_against_untrimmed(name);
        assert!(
            to_target <= 1e-3 && to_result <= 1e-3,
            "{name}: {to_target:e} {to_result:e}"
        );
        assert!(untrimmed > 1e-2, "{name}: {untrimmed:e}");
    }
}

#[test]
fn a_trimmed_patch_reaches_the_targets_corners() {
    // The held-out paraboloid, whose curvature lines cross its plan's edges at a slant: a
    // patch covering it overhangs its edges far, and the trimming cuts the overhang
    // away. Brute force both ways, measured 3.7e-4 / 3.9e-4 of the size (1.4e-3 / 2.2e-3,
    // the corners left uncovered, while the overhang's distance to the target carried
    // on counted whole).
    let target = target("paraboloid");
    let trim = ApproxOptions {
        trim: true,
        ..Default::default()
    };
    let a = approximate(&target.grid(41), &trim, &mut |_| {}).unwrap();
    let (to_target, to_result) = max_both_ways_trimmed(&target, a.trimmed.as_ref().unwrap());
    assert!(
        to_target <= 1e-3 && to_result <= 1e-3,
        "{to_target:e} {to_result:e}"
    );
}

/// The free-form held-out meshes (41 × 41 vertices) fitted to 5e-3 of their size
/// (`--tolerance 5e-3`, default settings otherwise): what the fit chose and its largest
/// distances both ways, brute force (the trimmed mesh where it chose one):
/// `cargo test -p monge-core-tests --test integration approximate_heldout:: --
/// --ignored --nocapture` (`HELDOUT=Bézier` measures only the targets whose name
/// contains it).
#[test]
#[ignore = "a measurement (ten minutes or more); prints the table"]
fn measure_free_form_to_a_tolerance() {
    use monge_core::approximate::{
        approximate_to_tolerance, FitDesign, Tolerance, ToleranceOptions,
    };
    use monge_core::multipatch::build;
    println!("| target | chosen | result → target | target → result | read by monge | within 5e-3 | time s |");
    println!("|---|---|---|---|---|---|---|");
    let only = std::env::var("HELDOUT").unwrap_or_default();
    for target in targets()
        .into_iter()
        .filter(|t| !t.pcl && t.name.contains(&only))
    {
        let clock = Instant::now();
        let options = ToleranceOptions {
            tolerance: Tolerance::Relative(5e-3),
            ..Default::default()
        };
        let fit = approximate_to_tolerance(&target.grid(41), &options, &mut |_| {}).unwrap();
        let seconds = clock.elapsed().as_secs_f64();
        let (chosen, (a, b)) = match &fit.design {
            FitDesign::Trimmed(_, mesh) => {
                ("1 patch, trimmed", max_both_ways_trimmed(&target, mesh))
            }
            FitDesign::Single(_) => ("1 patch", max_both_ways(&target, &fit.grid)),
            FitDesign::Patches(d) => {
                let mp = build(d, &Default::default()).unwrap();
                ("patches", max_both_ways(&target, &mp.grid))
            }
            FitDesign::TrimmedPatches(_, mesh) => {
                ("patches, trimmed", max_both_ways_trimmed(&target, mesh))
            }
        };
        println!(
            "| {} | {chosen} ({}) | {a:.1e} | {b:.1e} | {:.1e} | {} | {seconds:.0} |",
            target.name,
            fit.design.patches(),
            fit.deviation.max(),
            if a.max(b) <= 5e-3 { "yes" } else { "no" },
        );
    }
}

#[test]
fn patches_from_a_trimmed_patch_are_trimmed_and_read_as_measured() {
    // The held-out paraboloid, one patch covering it on a coarse grid and a short search,
    // then two patches from it: they cover the target too, and are trimmed.
    use monge_core::approximate::{approximate_patches, PatchLayout};
    let target = target("paraboloid");
    let points = target.grid(41);
    let options = ApproxOptions {
        trim: true,
        faces: (16, 16),
        starts: 1,
        max_evaluations: 200,
        ..Default::default()
    };
    let single = approximate(&points, &options, &mut |_| {}).unwrap();
    let two = PatchLayout { u: 2, v: 1 };
    let p = approximate_patches(&points, &single, two, &options, &mut |_| {}).unwrap();
    let mesh = p
        .trimmed
        .as_ref()
        .expect("patches from a trimmed patch are trimmed");
    // Brute force both ways, against the closed form: as monge reads them (within the
    // sampling of the brute force, 5 %), and never farther than the single patch.
    let (to_target, to_result) = max_both_ways_trimmed(&target, mesh);
    let read = (p.after.mesh_to_target_max, p.after.target_to_mesh_max);
    assert!(
        (to_target - read.0).abs() <= 0.05 * read.0 && (to_result - read.1).abs() <= 0.05 * read.1,
        "{to_target:e} {to_result:e} read {read:?}"
    );
    // The patches' figures and the picture's colours read the target → mesh distance
    // as the deviation does: to the trimmed mesh.
    let per_patch = p.per_patch.iter().map(|f| f.max).fold(0.0, f64::max);
    let cloud = monge_core::approximate::TargetCloud::new(&points).unwrap();
    let colours = monge_core::approximate::target_distances(&cloud, &p.grid, Some(mesh));
    let colours = colours.iter().copied().fold(0.0, f64::max) / p.after.size;
    for figure in [per_patch, colours] {
        assert!((figure - read.1).abs() <= 1e-12, "{figure:e} read {read:?}");
    }
    let (a, b) = max_both_ways_trimmed(&target, single.trimmed.as_ref().unwrap());
    assert!(
        to_target.max(to_result) <= 1.05 * a.max(b),
        "{to_target:e} {to_result:e} {a:e} {b:e}"
    );
    // Each panel planar (the smallest singular value of its corners about their centroid).
    for f in &mesh.faces {
        let c = f.iter().map(|k| mesh.vertices[*k]).sum::<glam::DVec3>() / f.len() as f64;
        let m = nalgebra::DMatrix::from_fn(f.len(), 3, |i, j| (mesh.vertices[f[i]] - c)[j]);
        assert!(m.singular_values().min() < 1e-12 * target.size);
    }
    eprintln!(
        "one patch {:.1e}, two {:.1e} (brute force), {} panels",
        a.max(b),
        to_target.max(to_result),
        mesh.faces.len()
    );
}

/// What a scan's points tell of its edges, at best: the true surface (its shape known
/// exactly), its parameter domain read from the points' own true parameters (not
/// noised) as the unbiased estimate of a uniform sample's range (the least value less
/// range / (n − 1), the largest plus as much), on a 41 × 41 grid as a fit's; beside it
/// the true domain on the same grid (the faces' sag alone). Measured as
/// [`measure_scans_on_eight_samplings`] measures fits (same samplings, same settings):
/// 37 of 40 within 1e-3 on seeds 1 to 8, 31 of 40 on seeds 9 to 16, against 23 and 20
/// for the fits (11 and 9 with their sides read in windows). A fit must also find the
/// shape, so this is a bound, not a target.
#[test]
#[ignore = "a measurement (half a minute); prints one line per surface"]
fn measure_an_oracle_of_the_scans_edges() {
    let (chosen, count, seeds) = scans_chosen();
    let grid_of = |target: &heldout::Target, u: (f64, f64), v: (f64, f64)| {
        QuadGrid::new(41, 41, target.grid_over(41, u, v), vec![DVec3::Z; 41 * 41])
    };
    for target in chosen {
        let (a, b) = max_both_ways(&target, &grid_of(&target, (0.0, 1.0), (0.0, 1.0)));
        let mut line = format!("{} (true domain {:.1e}):", target.name, a.max(b));
        let mut within = 0;
        for seed in seeds.clone() {
            let (u, v): (Vec<f64>, Vec<f64>) = target
                .scan_with_parameters(count, 1e-4, seed)
                .into_iter()
                .map(|(uv, _)| uv)
                .unzip();
            let range = |x: &[f64]| {
                let lo = x.iter().copied().fold(f64::INFINITY, f64::min);
                let hi = x.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                let gap = (hi - lo) / (x.len() - 1) as f64;
                (lo - gap, hi + gap)
            };
            let (a, b) = max_both_ways(&target, &grid_of(&target, range(&u), range(&v)));
            let largest = a.max(b);
            within += usize::from(largest <= 1e-3);
            line += &format!(" {largest:.1e}{}", if largest <= 1e-3 { "*" } else { "" });
        }
        println!("{line}; {within} of 8 within 1e-3");
    }
}

/// Where a scan's fit goes wrong, its shape or its edges: per sampling (as
/// [`measure_scans_on_eight_samplings`]) the larger of the two largest distances, then the
/// largest distance from the result's vertices to the target's surface extended by 0.3
/// of its parameters each way (its shape alone, wherever its edges stand). Measured on
/// seeds 1 to 8 with the sides read in windows: shapes 1.1e-4 to 5.2e-4 of the size (one
/// 8.8e-4), distances 6.5e-4 to 6.1e-3: the edges, not the shapes, put the scans beyond
/// 1e-3.
#[test]
#[ignore = "a measurement (two minutes); prints one line per surface"]
fn measure_the_shape_apart_from_the_edges() {
    let (chosen, count, seeds) = scans_chosen();
    for target in chosen {
        let (n, beyond) = (161, (-0.3, 1.3));
        let extended = target.grid_over(n, beyond, beyond);
        let extended = Triangles::of_grid(&QuadGrid::new(n, n, extended, vec![DVec3::Z; n * n]));
        let mut line = format!("{} (largest both ways / shape):", target.name);
        for seed in seeds.clone() {
            let points = target.scan(count, 1e-4, seed);
            let a = approximate(&points, &ApproxOptions::default(), &mut |_| {}).unwrap();
            let (x, y) = max_both_ways(&target, &a.grid);
            let shape = a
                .grid
                .vertices
                .iter()
                .map(|v| extended.distance(*v))
                .fold(0.0, f64::max)
                / target.size;
            line += &format!(" {:.1e}/{shape:.1e}", x.max(y));
        }
        println!("{line}");
    }
}
