//! `monge bench`: time the generator in-process on a bundled design.

use std::hint::black_box;
use std::time::{Duration, Instant};

use anyhow::Context;
use monge_core::{generate, Design, GenerateOptions, GuideSpec};

use crate::cli::BenchArgs;
use crate::output::print;
use crate::Outcome;

/// Time spent warming up each size.
const WARM_UP: Duration = Duration::from_millis(200);
/// Time the default number of runs aims at, per size.
const TARGET: Duration = Duration::from_secs(1);
/// The fewest default runs.
const MIN_RUNS: u32 = 5;
/// The most default runs (for tiny sizes).
const MAX_RUNS: u32 = 100_000;

/// Runs `monge bench`.
pub fn run(args: &BenchArgs) -> anyhow::Result<Outcome> {
    let options = GenerateOptions {
        max_vertices: args.max_vertices,
    };
    for &n in &args.sizes {
        let design = standard_design(n as usize + 1);
        let once = || -> anyhow::Result<Duration> {
            let start = Instant::now();
            let generated = generate(black_box(&design), &options)
                .with_context(|| format!("bench design with {n} × {n} faces"))?;
            let elapsed = start.elapsed();
            black_box(generated);
            Ok(elapsed)
        };
        let warm_start = Instant::now();
        let mut warm_runs = 0u32;
        while warm_runs == 0 || warm_start.elapsed() < WARM_UP {
            once()?;
            warm_runs += 1;
        }
        let runs = args
            .runs
            .unwrap_or_else(|| default_runs(warm_start.elapsed() / warm_runs));
        let mut times = Vec::with_capacity(runs as usize);
        for _ in 0..runs {
            times.push(once()?.as_secs_f64() * 1e3);
        }
        print(&format!("{}\n", json_line(n, &mut times)))?;
    }
    Ok(Outcome::Success)
}

/// Enough runs of `per_run` for about [`TARGET`], within [`MIN_RUNS`]..=[`MAX_RUNS`].
fn default_runs(per_run: Duration) -> u32 {
    let runs = TARGET.as_secs_f64() / per_run.as_secs_f64().max(1e-9);
    (runs.ceil() as u32).clamp(MIN_RUNS, MAX_RUNS)
}

/// `{"faces":"NxN","median_ms":…,"runs":…,"min_ms":…,"max_ms":…}` for the run times
/// (milliseconds, at least one; sorted in place).
fn json_line(n: u32, times: &mut [f64]) -> String {
    times.sort_by(f64::total_cmp);
    let k = times.len();
    let median = if k % 2 == 1 {
        times[k / 2]
    } else {
        0.5 * (times[k / 2 - 1] + times[k / 2])
    };
    format!(
        "{{\"faces\":\"{n}x{n}\",\"median_ms\":{median:.4},\"runs\":{k},\"min_ms\":{:.4},\"max_ms\":{:.4}}}",
        times[0],
        times[k - 1]
    )
}

/// The bundled design: two cubic B-spline guides in the characteristic case
/// (§3.1; guide_u in the plane y = 0 leaving along x, guide_v in the plane x = 0
/// leaving along y), θ = 30°, each sampled at `samples` points.
fn standard_design(samples: usize) -> Design {
    let cubic = |control_points: Vec<[f64; 3]>| GuideSpec::bspline(3, control_points, samples);
    Design {
        mesh: Default::default(),
        theta_deg: 30.0,
        guide_u: cubic(vec![
            [0.0, 0.0, 0.0],
            [4.0, 0.0, 0.0],
            [8.0, 0.0, 2.5],
            [12.0, 0.0, 1.0],
            [16.0, 0.0, 3.5],
        ]),
        guide_v: cubic(vec![
            [0.0, 0.0, 0.0],
            [0.0, 3.0, 0.0],
            [0.0, 6.0, -1.5],
            [0.0, 10.0, 1.0],
        ]),
        tolerance: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use monge_core::{inspect, Mode};

    #[test]
    fn the_standard_design_is_characteristic_and_generates_cleanly() {
        let d = standard_design(51);
        let info = inspect(&d, &GenerateOptions::default()).unwrap();
        assert_eq!(info.mode, Mode::Characteristic);
        assert_eq!(info.grid_size(), (51, 51));
        let g = generate(&d, &GenerateOptions::default()).unwrap();
        assert_eq!(g.report.folded_faces, 0);
        assert!(g.report.min_crossing.sine > 0.1);
    }

    #[test]
    fn default_runs_aim_at_one_second() {
        assert_eq!(default_runs(Duration::from_millis(10)), 100);
        assert_eq!(default_runs(Duration::from_secs(1)), MIN_RUNS);
        assert_eq!(default_runs(Duration::ZERO), MAX_RUNS);
    }

    #[test]
    fn the_line_starts_with_the_required_keys() {
        let line = json_line(10, &mut [3.0, 1.0, 2.0, 10.0]);
        assert_eq!(
            line,
            r#"{"faces":"10x10","median_ms":2.5000,"runs":4,"min_ms":1.0000,"max_ms":10.0000}"#
        );
        let v: serde_json::Value = serde_json::from_str(&line).unwrap();
        assert_eq!(v["median_ms"], 2.5);
    }
}
