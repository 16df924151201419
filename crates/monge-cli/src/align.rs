//! `monge align`: a design whose mesh has its boundaries in four given planes (§4.5, Figures 16–18).

use std::path::PathBuf;

use anyhow::Context;
use monge_core::boundary::{align, AlignOptions};
use monge_io::{check_output, read_planes, write_design};

use crate::output::{num, print};
use crate::Outcome;

/// Arguments of `monge align`.
#[derive(Debug, clap::Args)]
pub struct AlignArgs {
    /// The planes file (JSON or TOML): `first_row`, `last_row`, `first_column`, `last_column`, each
    /// `{"point": [x, y, z], "normal": [x, y, z]}`; optional `theta_deg`, `corner`,
    /// `samples`, `rise`, `facade`.
    #[arg(value_name = "PLANES")]
    pub planes: PathBuf,
    /// Where to write the design (`.json` or `.toml`), for `monge generate`.
    #[arg(short, long, value_name = "DESIGN")]
    pub output: PathBuf,
    /// Samples per guide (≥ 3); overrides the file's `samples` [default: 21].
    #[arg(long, value_name = "N")]
    pub samples: Option<usize>,
    /// The vertical-façade case (Figure 16): four vertical planes forming a rectangle in
    /// plan; the guides are S-shaped bi-arcs with horizontal end tangents.
    #[arg(long)]
    pub facade: bool,
    /// θ in degrees; overrides the file's `theta_deg` [default: chosen by a scan].
    #[arg(long, value_name = "DEG", allow_hyphen_values = true)]
    pub theta: Option<f64>,
}

/// Runs `monge align`.
pub fn run(args: &AlignArgs) -> anyhow::Result<Outcome> {
    let file = args.planes.display().to_string();
    check_output(&args.output, &[&args.planes])?;
    let mut spec = read_planes(&args.planes)?;
    if args.samples.is_some() {
        spec.samples = args.samples;
    }
    if args.theta.is_some() {
        spec.theta_deg = args.theta;
    }
    let options = AlignOptions {
        facade: args.facade,
        ..Default::default()
    };
    let aligned = align(&spec, &options).with_context(|| file.clone())?;
    write_design(&aligned.design, &args.output)?;
    let run = match aligned.theta_run {
        Some((a, b)) if a > b => {
            format!(" (middle of the working run {a}° … 180° … {b}°, scanned in 1° steps)")
        }
        Some((a, b)) => format!(" (middle of the working run {a}° … {b}°, scanned in 1° steps)"),
        None => String::new(),
    };
    let [d1, d2, d3, d4] = aligned.boundary_distance;
    let [c1, c2, c3, c4] = aligned.c;
    print(&format!(
        "θ = {}°{run}\n\
         Gauss circles n·p = c: first_row {}, last_row {}, first_column {}, last_column {}\n\
         boundary distance / size: first_row {}, last_row {}, first_column {}, last_column {}\n\
         measured max error {}\nwrote {}\n",
        aligned.design.theta_deg,
        num(c1),
        num(c2),
        num(c3),
        num(c4),
        num(d1),
        num(d2),
        num(d3),
        num(d4),
        num(aligned.max_error),
        args.output.display()
    ))?;
    Ok(Outcome::Success)
}
