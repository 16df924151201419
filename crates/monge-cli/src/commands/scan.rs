//! `monge scan`: a design-space scan (§4.3, Figure 14) as CSV and an SVG plot.

use std::path::PathBuf;

use anyhow::Context;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use monge_core::scan::{parse_range, scan, Scan, Status};
use monge_core::GenerateOptions;
use monge_io::{check_output, read_design, write_scan_csv, write_scan_svg, Outputs};

use crate::shared::help::{EXIT, THETA};
use crate::shared::output::{eprint, num};
use crate::shared::Outcome;

/// Scan θ (or any number of a design) over a range: CSV table and SVG plot (§4.3, Figure 14).
#[derive(Debug, clap::Args)]
#[command(
    long_about = format!(
        "Generate the design at each value of θ (--theta START:END:STEP) or of any number of \
         the design (--param PATH --range START:END:STEP, PATH as in the design's JSON, e.g. \
         `guide_v.bspline.control_points[2][2]`), in parallel, and write one CSV row per value: \
         status (fair, folded, inadmissible, degenerate, invalid), admissible, folded faces and \
         the smallest crossing sine (pinching and self-intersection, §5.2), panel area min, max, \
         spread (max/min), mean and variance, the longest edge, the measured max error and the \
         generator's error message. --plot draws area spread and folded faces against the \
         value with folded (red), inadmissible (grey), degenerate (orange) and invalid (blue) \
         intervals shaded. A summary of the intervals goes to stderr; a progress bar too when \
         it is a terminal.\n\n{THETA}"
    ),
    after_help = format!(
        "Examples:\n  \
         monge scan examples/fig14-family.toml --theta -180:180:2 -o scan.csv --plot scan.svg\n  \
         monge scan examples/fig14-family.toml --param guide_v.bspline.control_points[2][2] \
         --range 1:5:0.5 -o scan.csv\n\n{EXIT}"
    )
)]
pub struct ScanArgs {
    /// The design file (`.json` or `.toml`).
    #[arg(value_name = "DESIGN")]
    pub design: PathBuf,
    /// Scan θ over START:END:STEP degrees, e.g. -180:180:2 (END included).
    #[arg(long, value_name = "START:END:STEP", allow_hyphen_values = true, conflicts_with_all = ["param", "range"])]
    pub theta: Option<String>,
    /// Scan another number of the design instead, named by its path in the design's JSON,
    /// e.g. `guide_v.bspline.control_points[2][2]`; give its values with --range.
    #[arg(long, value_name = "PATH", requires = "range")]
    pub param: Option<String>,
    /// The values of --param, START:END:STEP (END included).
    #[arg(
        long,
        value_name = "START:END:STEP",
        allow_hyphen_values = true,
        requires = "param"
    )]
    pub range: Option<String>,
    /// The CSV table to write, one row per value.
    #[arg(short, long, value_name = "CSV")]
    pub output: PathBuf,
    /// Also write an SVG plot: area spread and folded faces against the value, bad intervals shaded.
    #[arg(long, value_name = "SVG")]
    pub plot: Option<PathBuf>,
    /// Refuse grids of more than N vertices.
    #[arg(long, value_name = "N", default_value_t = GenerateOptions::default().max_vertices)]
    pub max_vertices: usize,
}

/// Runs `monge scan`.
pub fn run(args: &ScanArgs) -> anyhow::Result<Outcome> {
    let file = args.design.display().to_string();
    for out in std::iter::once(&args.output).chain(&args.plot) {
        check_output(out, &[&args.design])?;
    }
    let design = read_design(&args.design)?;
    let (path, range) = match (&args.theta, &args.param, &args.range) {
        (Some(r), None, None) => ("theta", r.as_str()),
        (None, Some(p), Some(r)) => (p.as_str(), r.as_str()),
        _ => anyhow::bail!(
            "give either --theta START:END:STEP, or --param PATH with --range START:END:STEP"
        ),
    };
    let values = parse_range(range)?;
    let options = GenerateOptions {
        max_vertices: args.max_vertices,
    };
    // Drawn on stderr only when it is a terminal (indicatif hides it otherwise).
    let bar =
        ProgressBar::with_draw_target(Some(values.len() as u64), ProgressDrawTarget::stderr());
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} values, {elapsed} elapsed, {eta} left")
            .expect("a valid progress template"),
    );
    let s = scan(&design, path, &values, &options, &|| bar.inc(1)).with_context(|| file.clone())?;
    bar.finish_and_clear();
    // The table and its plot change together or not at all.
    let mut out = Outputs::new();
    out.write(&args.output, |w| write_scan_csv(&s, w))?;
    if let Some(plot) = &args.plot {
        out.write(plot, |w| write_scan_svg(&s, w))?;
    }
    out.commit()?;
    eprint(&summary(&s));
    Ok(Outcome::Success)
}

/// What a designer reads first: the intervals of each kind and the best value.
fn summary(s: &Scan) -> String {
    let mut text = format!("{} values of {}\n", s.rows.len(), s.parameter);
    for status in [
        Status::Fair,
        Status::Folded,
        Status::Inadmissible,
        Status::Degenerate,
        Status::Invalid,
    ] {
        let runs = s.intervals(status);
        if runs.is_empty() {
            continue;
        }
        let list: Vec<String> = runs
            .iter()
            .map(|&(a, b)| {
                if a == b {
                    num(a)
                } else {
                    format!("{}..{}", num(a), num(b))
                }
            })
            .collect();
        text.push_str(&format!("{}: {}\n", status.name(), list.join(", ")));
    }
    let best = s
        .rows
        .iter()
        .filter(|r| r.status == Status::Fair)
        .filter_map(|r| r.panels.map(|p| (r.value, p.spread())))
        .min_by(|a, b| a.1.total_cmp(&b.1));
    if let Some((value, spread)) = best {
        text.push_str(&format!(
            "most even panels (fair): {} = {} (area max/min {})\n",
            s.parameter,
            num(value),
            num(spread)
        ));
    }
    text
}
