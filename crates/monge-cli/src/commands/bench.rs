//! `monge bench`: time the generator in-process on a bundled design, or with
//! `--all` every command as a child process (wall time, bytes, peak RSS).

use std::hint::black_box;
use std::time::{Duration, Instant};

use anyhow::Context;
use glam::DVec3;
use monge_core::approximate::{fit_report, FitDesign, TargetCloud};
use monge_core::fabrication::DESIGN_ANGLE_TOL_DEG;
use monge_core::{generate, Design, GenerateOptions, GuideSpec};
use monge_io::{read_any_design, read_multipatch, read_points, AnyDesign};

use crate::shared::help::EXIT;
use crate::shared::output::print;
use crate::shared::Outcome;

/// Time the generator in-process on standard designs of n × n faces.
#[derive(Debug, clap::Args)]
#[command(
    long_about = format!(
        "Time the generator in-process on standard designs of n × n faces.\n\n\
         The design is built in code (no file I/O): two cubic B-spline guides in the \
         characteristic case (§3.1), guide_u with control points (0,0,0) (4,0,0) (8,0,2.5) \
         (12,0,1) (16,0,3.5) in the plane y = 0, guide_v with control points (0,0,0) (0,3,0) \
         (0,6,−1.5) (0,10,1) in the plane x = 0, θ = 30°, each guide sampled at n + 1 points. \
         Each timed run is a whole `generate` call, guide sampling included. After a warm-up, \
         prints one JSON line per size: \
         {{\"faces\":\"NxN\",\"median_ms\":M,\"runs\":R,\"min_ms\":A,\"max_ms\":B}}."
    ),
    after_help = format!(
        "Examples:\n  \
         monge bench\n  \
         monge bench --sizes 10,100 --runs 20\n  \
         monge bench --all\n\n{EXIT}"
    )
)]
pub struct BenchArgs {
    /// Timed runs per size [default: enough for about 1 s per size, at least 5; with
    /// --all, runs of each command and size: 1].
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub runs: Option<u32>,
    /// Comma-separated grid sizes n (n × n faces, n + 1 samples per guide), each ≥ 2
    /// (a curved guide has 3 samples or more) [default: 100,1000; with --all 100,400,1000].
    #[arg(
        long,
        value_name = "N,N,…",
        value_delimiter = ',',
        value_parser = clap::value_parser!(u32).range(2..)
    )]
    pub sizes: Option<Vec<u32>>,
    /// Time every command instead (generate to .json/.obj/.ply (ASCII and binary)/.glb, check, fabricate,
    /// smooth to .json and .igs), each run --runs times as a child process of this binary
    /// in a temporary directory, each time into a new output (the last run's removed
    /// first, untimed): one JSON line per command and size with the median wall
    /// time, bytes written, time per million faces, the largest peak RSS, and the ratio to
    /// the median raw-write time of as many bytes (`write_all` and `sync_all` of a new file in
    /// the same directory, after each run).
    #[arg(long)]
    pub all: bool,
    /// Time `monge approximate` as a child process, on the default 40 × 40 grid: one patch
    /// of the shipped 10 m roof target (2000 points), then the shipped paraboloid (a
    /// free-form roof, 1681 points) to a tolerance of 5e-3 of its size (--tolerance), then
    /// in six patches covering it, trimmed (--patches 3x2 --trim): one JSON line each with wall and
    /// processor time and peak RSS, the last two also with the patches of the result, its
    /// largest distance both ways (relative, measured again here) and whether that is
    /// within 5e-3 (after the lines of --all when both are given).
    #[arg(long)]
    pub approximate: bool,
    /// Refuse grids of more than N vertices.
    #[arg(long, value_name = "N", default_value_t = GenerateOptions::default().max_vertices)]
    pub max_vertices: usize,
}

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
    if args.all || args.approximate {
        let exe = std::env::current_exe().context("cannot find the monge binary to run")?;
        if args.all {
            let sizes = args.sizes.as_deref().unwrap_or(&[100, 400, 1000]);
            run_all(&exe, sizes, args.runs.unwrap_or(1), args.max_vertices)?;
        }
        if args.approximate {
            run_approximate(&exe)?;
        }
        return Ok(Outcome::Success);
    }
    let options = GenerateOptions {
        max_vertices: args.max_vertices,
    };
    for &n in args.sizes.as_deref().unwrap_or(&[100, 1000]) {
        let design = standard_design(n as usize + 1);
        // The mesh's vertices, and as many normals.
        let len = (n as usize + 1).pow(2);
        // One generation, then one fill of as many bytes, in the same conditions.
        let once = || -> anyhow::Result<(f64, f64)> {
            let start = Instant::now();
            let generated = generate(black_box(&design), &options)
                .with_context(|| format!("bench design with {n} × {n} faces"))?;
            let elapsed = start.elapsed();
            black_box(generated);
            Ok((elapsed.as_secs_f64() * 1e3, fill(len) * 1e3))
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
        let (mut times, mut fills) = (Vec::new(), Vec::new());
        for _ in 0..runs {
            let (t, f) = once()?;
            times.push(t);
            fills.push(f);
        }
        print(&format!("{}\n", json_line(n, &mut times, &mut fills)))?;
    }
    Ok(Outcome::Success)
}

/// The commands of `monge bench --all`: a name, and the arguments after `monge`
/// with `{design}`, `{dir}` standing for the design file and the temporary directory.
const COMMANDS: [(&str, &[&str]); 9] = [
    (
        "generate .json",
        &["generate", "{design}", "-o", "{dir}/mesh.json"],
    ),
    (
        "generate .obj",
        &["generate", "{design}", "-o", "{dir}/mesh.obj"],
    ),
    (
        "generate .ply",
        &["generate", "{design}", "-o", "{dir}/mesh.ply"],
    ),
    (
        "generate .ply binary",
        &[
            "generate",
            "{design}",
            "-o",
            "{dir}/mesh-binary.ply",
            "--format",
            "ply-binary",
        ],
    ),
    (
        "generate .glb",
        &["generate", "{design}", "-o", "{dir}/mesh.glb"],
    ),
    ("check .obj", &["check", "{dir}/mesh.obj"]),
    ("fabricate", &["fabricate", "{design}", "-o", "{dir}/fab"]),
    (
        "smooth .json",
        &["smooth", "{design}", "-o", "{dir}/net.json"],
    ),
    (
        "smooth .igs",
        &["smooth", "{design}", "-o", "{dir}/net.igs"],
    ),
];

/// The shipped target of `monge approximate` (`examples/targets/roof-pcl.obj`: a 10 m
/// roof, 2000 points), for `monge bench --approximate`.
const ROOF_TARGET: &str = include_str!("../../../../examples/targets/roof-pcl.obj");

/// The shipped free-form target (`examples/targets/paraboloid.obj`: z = 0.04 x² + 0.1 y²
/// over [0, 10]², 1681 points), for `monge bench --approximate`.
const FREEFORM_TARGET: &str = include_str!("../../../../examples/targets/paraboloid.obj");

/// The tolerance of the free-form fits of `monge bench --approximate`.
const FREEFORM_TOLERANCE: &str = "5e-3";

/// The layout of the six-patch free-form fit of `monge bench --approximate`.
const FREEFORM_PATCHES: &str = "3x2";

/// `monge bench --approximate`: `monge approximate` of the shipped 10 m roof on its
/// default 40 × 40 grid, as a child process of this binary.
fn run_approximate(exe: &std::path::Path) -> anyhow::Result<()> {
    let dir = tempfile::tempdir().context("cannot create a temporary directory")?;
    let target = dir.path().join("roof-pcl.obj");
    std::fs::write(&target, ROOF_TARGET)
        .with_context(|| format!("cannot write `{}`", target.display()))?;
    let args = [
        "approximate".to_owned(),
        target.to_string_lossy().into_owned(),
        "-o".to_owned(),
        dir.path().join("fit.json").to_string_lossy().into_owned(),
    ];
    let run = run_child(exe, &args, &[0])
        .context("`monge approximate` of the shipped roof target (40 × 40 faces)")?;
    print(&format!(
        "{{\"command\":\"approximate\",\"faces\":\"40x40\",\"target_points\":2000,\
         \"wall_ms\":{:.1},\"cpu_ms\":{:.1},\"peak_rss_mb\":{:.1}}}\n",
        run.wall * 1e3,
        run.cpu * 1e3,
        run.peak_rss_kb as f64 / 1024.0,
    ))?;
    // The free-form roof to a tolerance (exit status 1 when not within it), then in the
    // six patches of a fixed layout, covering it and trimmed.
    let tolerance = ["--tolerance", FREEFORM_TOLERANCE];
    run_free_form(exe, dir.path(), &tolerance, false)?;
    let layout = ["--patches", FREEFORM_PATCHES];
    run_free_form(exe, dir.path(), &layout, true)
}

/// One run of `monge approximate` of the shipped paraboloid with `extra` arguments (and
/// `--trim`, with `trim`), in `dir`, as a child process: a JSON line with its wall and
/// processor time, peak RSS, the patches of its result, their largest distance to the
/// target both ways (relative, measured again here) and whether that is within
/// [`FREEFORM_TOLERANCE`].
fn run_free_form(
    exe: &std::path::Path,
    dir: &std::path::Path,
    extra: &[&str],
    trim: bool,
) -> anyhow::Result<()> {
    let target = dir.join("paraboloid.obj");
    std::fs::write(&target, FREEFORM_TARGET)
        .with_context(|| format!("cannot write `{}`", target.display()))?;
    let design = dir.join("free-form.json");
    let trimmed = design.with_extension("trimmed.obj");
    for stale in [&design, &trimmed] {
        if stale.exists() {
            std::fs::remove_file(stale)
                .with_context(|| format!("cannot remove `{}`", stale.display()))?;
        }
    }
    let mut args = vec![
        "approximate".to_owned(),
        target.to_string_lossy().into_owned(),
        "-o".to_owned(),
        design.to_string_lossy().into_owned(),
    ];
    let mut label = format!("approximate {}", extra.join(" "));
    args.extend(extra.iter().map(|a| (*a).to_owned()));
    if trim {
        args.extend(["--trim".to_owned(), trimmed.to_string_lossy().into_owned()]);
        label += " --trim";
    }
    let context = || format!("`monge {label}` of the shipped paraboloid (40 × 40 faces)");
    let run = run_child(exe, &args, &[0, 1]).with_context(context)?;
    let points = read_points(&target)?;
    // The result as DESIGN has it: a multi-patch design, a trimmed design (its mesh cut
    // as `monge generate` cuts it), or a design.
    let fit = match read_any_design(&design) {
        Ok(AnyDesign::Surface(d)) => FitDesign::Single(*d),
        Ok(AnyDesign::Trimmed(t)) => {
            let (_, mesh) = t.mesh(&GenerateOptions::default()).with_context(context)?;
            t.design.into_fit(mesh)
        }
        _ => FitDesign::Patches(read_multipatch(&design)?),
    };
    let cloud = TargetCloud::new(&points).with_context(context)?;
    let report =
        fit_report(&cloud, &fit, DESIGN_ANGLE_TOL_DEG.to_radians()).with_context(context)?;
    let max = report.deviation.max();
    let tolerance: f64 = FREEFORM_TOLERANCE.parse().expect("a number");
    print(&format!(
        "{{\"command\":\"{label}\",\"target\":\"paraboloid\",\
         \"faces\":\"40x40\",\"target_points\":{},\"wall_ms\":{:.1},\"cpu_ms\":{:.1},\
         \"peak_rss_mb\":{:.1},\"patches\":{},\"max_deviation\":{max:.3e},\"within\":{}}}\n",
        points.len(),
        run.wall * 1e3,
        run.cpu * 1e3,
        run.peak_rss_kb as f64 / 1024.0,
        fit.patches(),
        max <= tolerance,
    ))?;
    Ok(())
}

/// `monge bench --all`: every command of [`COMMANDS`] on the bundled design at
/// each size, `runs` times each, as a child process of this binary.
fn run_all(
    exe: &std::path::Path,
    sizes: &[u32],
    runs: u32,
    max_vertices: usize,
) -> anyhow::Result<()> {
    for &n in sizes {
        let dir = tempfile::tempdir().context("cannot create a temporary directory")?;
        let design = dir.path().join("design.json");
        let text = serde_json::to_string(&standard_design(n as usize + 1))?;
        std::fs::write(&design, text)
            .with_context(|| format!("cannot write `{}`", design.display()))?;
        let vertices = (n as usize + 1).pow(2);
        if vertices > max_vertices {
            anyhow::bail!(
                "{n} × {n} faces have {vertices} vertices, more than --max-vertices {max_vertices}"
            );
        }
        for (name, template) in COMMANDS {
            let args: Vec<String> = template
                .iter()
                .map(|a| {
                    a.replace("{design}", &design.to_string_lossy())
                        .replace("{dir}", &dir.path().to_string_lossy())
                })
                .collect();
            let (mut walls, mut raws, mut peak_rss_kb, mut bytes) = (Vec::new(), Vec::new(), 0, 0);
            for run in 0..runs {
                // Every run writes a new output, as the raw write writes a new
                // file: replacing one would add the file system's freeing of
                // the old one (14 ms for 65 MB on ext4 here) to the command only.
                remove_output(&args)?;
                let before = dir_bytes(dir.path())?;
                let child = run_child(exe, &args, &[0])
                    .with_context(|| format!("`monge {}` on {n} × {n} faces", args.join(" ")))?;
                if run == 0 {
                    bytes = dir_bytes(dir.path())?.saturating_sub(before);
                }
                walls.push(child.wall);
                peak_rss_kb = peak_rss_kb.max(child.peak_rss_kb);
                // Nothing written (check): no raw-write time to compare with.
                if bytes > 0 {
                    raws.push(raw_write(dir.path(), bytes)?);
                }
            }
            let wall = median(&mut walls);
            let raw = if raws.is_empty() {
                0.0
            } else {
                median(&mut raws)
            };
            let mfaces = (n as f64).powi(2) / 1e6;
            print(&format!(
                "{{\"command\":\"{name}\",\"faces\":\"{n}x{n}\",\"runs\":{runs},\"wall_ms\":{:.1},\
                 \"bytes\":{bytes},\"ms_per_mface\":{:.1},\"peak_rss_mb\":{:.1},\"raw_write_ms\":{:.1},\
                 \"ratio_to_raw\":{}}}\n",
                wall * 1e3,
                wall * 1e3 / mfaces,
                peak_rss_kb as f64 / 1024.0,
                raw * 1e3,
                if raw > 0.0 {
                    format!("{:.2}", wall / raw)
                } else {
                    "null".to_owned()
                }
            ))?;
        }
    }
    Ok(())
}

/// What [`run_child`] measured of a child process.
struct ChildRun {
    /// Wall time, seconds.
    wall: f64,
    /// Processor time (user and system, all threads), seconds: what the run costs on
    /// a machine shared with other work, where the wall time also counts the waits.
    cpu: f64,
    /// Peak resident set size, kB (from `wait4`; Linux counts the spawning process's
    /// own 10-15 MB from before `exec` in it).
    peak_rss_kb: i64,
}

/// Runs `exe args` with its output discarded, and measures it. A command that fails
/// or exits with a status not in `expected` is an error.
fn run_child(exe: &std::path::Path, args: &[String], expected: &[i32]) -> anyhow::Result<ChildRun> {
    use std::process::{Command, Stdio};
    let start = Instant::now();
    let child = Command::new(exe)
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()?;
    let pid = child.id() as libc::pid_t;
    let mut stderr = child.stderr.context("no standard error of the child")?;
    let mut message = String::new();
    std::io::Read::read_to_string(&mut stderr, &mut message)?;
    let mut status = 0;
    // SAFETY: `rusage` is plain data, zero is a valid value; `wait4` reaps our own
    // child `pid` exactly once (`Child` is not waited on afterwards) and fills both.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    let reaped = unsafe { libc::wait4(pid, &mut status, 0, &mut usage) };
    let wall = start.elapsed().as_secs_f64();
    if reaped != pid {
        return Err(std::io::Error::last_os_error().into());
    }
    if !libc::WIFEXITED(status) || !expected.contains(&libc::WEXITSTATUS(status)) {
        anyhow::bail!("it failed: {}", message.trim_end());
    }
    let seconds = |t: libc::timeval| t.tv_sec as f64 + t.tv_usec as f64 * 1e-6;
    Ok(ChildRun {
        wall,
        cpu: seconds(usage.ru_utime) + seconds(usage.ru_stime),
        peak_rss_kb: usage.ru_maxrss,
    })
}

/// Removes the output (file or directory) that `args` name after `-o`, if any,
/// and if it exists.
fn remove_output(args: &[String]) -> anyhow::Result<()> {
    let Some(k) = args.iter().position(|a| a == "-o") else {
        return Ok(());
    };
    let path = std::path::Path::new(&args[k + 1]);
    let removed = if path.is_dir() {
        std::fs::remove_dir_all(path)
    } else {
        std::fs::remove_file(path)
    };
    match removed {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
            Err(e).with_context(|| format!("cannot remove `{}`", path.display()))
        }
        _ => Ok(()),
    }
}

/// Total size of the files under `dir`, in bytes.
fn dir_bytes(dir: &std::path::Path) -> anyhow::Result<u64> {
    let mut total = 0;
    for entry in std::fs::read_dir(dir)? {
        let entry = entry?;
        let meta = entry.metadata()?;
        total += if meta.is_dir() {
            dir_bytes(&entry.path())?
        } else {
            meta.len()
        };
    }
    Ok(total)
}

/// Seconds to write `bytes` bytes into a new file in `dir` (1 MiB `write_all`
/// calls from one buffer, then `sync_all`, as the commands' atomic writer does).
fn raw_write(dir: &std::path::Path, bytes: u64) -> anyhow::Result<f64> {
    use std::io::Write;
    let chunk = vec![b'x'; 1 << 20];
    let path = dir.join("raw-write.bin");
    let start = Instant::now();
    let mut file = std::fs::File::create(&path)?;
    let mut left = bytes as usize;
    while left > 0 {
        let k = left.min(chunk.len());
        file.write_all(&chunk[..k])?;
        left -= k;
    }
    file.sync_all()?;
    let elapsed = start.elapsed().as_secs_f64();
    std::fs::remove_file(&path)?;
    Ok(elapsed)
}

/// Enough runs of `per_run` for about [`TARGET`], within [`MIN_RUNS`]..=[`MAX_RUNS`].
fn default_runs(per_run: Duration) -> u32 {
    let runs = TARGET.as_secs_f64() / per_run.as_secs_f64().max(1e-9);
    (runs.ceil() as u32).clamp(MIN_RUNS, MAX_RUNS)
}

/// Seconds to fill two fresh `Vec<DVec3>` of `len` elements each, every
/// element written once (one thread): what writing the mesh's bytes (its
/// vertices and its normals) costs on this machine, allocated as the mesh is.
fn fill(len: usize) -> f64 {
    let start = Instant::now();
    let make = || -> Vec<DVec3> { (0..len).map(|k| DVec3::splat(k as f64)).collect() };
    let filled = (make(), make());
    black_box(&filled);
    let elapsed = start.elapsed().as_secs_f64();
    drop(filled);
    elapsed
}

/// The median of `times` (at least one; sorted in place).
fn median(times: &mut [f64]) -> f64 {
    times.sort_by(f64::total_cmp);
    let k = times.len();
    if k % 2 == 1 {
        times[k / 2]
    } else {
        0.5 * (times[k / 2 - 1] + times[k / 2])
    }
}

/// `{"faces":"NxN","median_ms":…,"runs":…,"min_ms":…,"max_ms":…,"fill_ms":…,"ratio_to_fill":…}`
/// for the generator's run times and the fill times of its mesh's bytes
/// (milliseconds, as many; sorted in place): `fill_ms` is their median, the
/// ratio that of the medians.
fn json_line(n: u32, times: &mut [f64], fills: &mut [f64]) -> String {
    let (time, fill) = (median(times), median(fills));
    let k = times.len();
    format!(
        "{{\"faces\":\"{n}x{n}\",\"median_ms\":{time:.4},\"runs\":{k},\"min_ms\":{:.4},\"max_ms\":{:.4},\
         \"fill_ms\":{fill:.4},\"ratio_to_fill\":{:.2}}}",
        times[0],
        times[k - 1],
        time / fill
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
        let line = json_line(10, &mut [3.0, 1.0, 2.0, 10.0], &mut [2.0, 0.5, 0.1, 9.0]);
        assert_eq!(
            line,
            r#"{"faces":"10x10","median_ms":2.5000,"runs":4,"min_ms":1.0000,"max_ms":10.0000,"fill_ms":1.2500,"ratio_to_fill":2.00}"#
        );
        let v: serde_json::Value = serde_json::from_str(&line).unwrap();
        assert_eq!(v["median_ms"], 2.5);
        assert_eq!(v["ratio_to_fill"], 2.0);
    }
}
