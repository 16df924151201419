//! `monge align`: a design whose mesh has its boundaries in four given planes (§4.5, Figures 16–18).

use std::path::PathBuf;

use anyhow::Context;
use monge_core::boundary::{align, AlignOptions};
use monge_io::{check_output, read_planes, write_design};

use crate::shared::help::{EXIT, THETA};
use crate::shared::output::{num, print};
use crate::shared::Outcome;

/// Write a design whose mesh has its boundary rows and columns in four planes (§4.5, Figures 16–18).
#[derive(Debug, clap::Args)]
#[command(
    long_about = format!(
        "Write a design (two circular-arc guides and θ) whose mesh, from `monge generate`, has \
         its first row (guide_v) in `first_row` (P1), its last row in `last_row` (P2), its first \
         column (guide_u) in `first_column` (P3) and its last column in `last_column` (P4), to \
         round-off. PLANES is JSON:\n\n  \
         {{\"first_row\":    {{\"point\": [0,0,0], \"normal\": [0,0,1]}},\n   \
         \"last_row\":     {{\"point\": [2,0,0], \"normal\": [1,0,0]}},\n   \
         \"first_column\": {{\"point\": [0,0,0], \"normal\": [0,1,0]}},\n   \
         \"last_column\":  {{\"point\": [0,0,0], \"normal\": [-0.588,0.809,0]}},\n   \
         \"corner\": [5,0,0], \"theta_deg\": -60, \"samples\": 21}}\n\n\
         (a point and a normal per plane; `corner`, `theta_deg`, `samples` optional). The lines \
         P1 ∩ P2 and P3 ∩ P4 must have orthogonal directions (the Gauss circles of the four \
         boundary lines, {{n·p_k = c_k}}, then satisfy c_i·c_j = p_i·p_j, one free scale = θ). The \
         guides start at `corner` projected onto P1 ∩ P3 (default: the point of that line \
         nearest the mean of the planes' points). Without θ, monge scans θ in 1° steps and takes \
         the middle of the longest run that gives an unfolded mesh in the planes.\n\n\
         --facade (Figure 16): four vertical planes forming a rectangle in plan (P1 ∥ P2 ⊥ P3 ∥ P4); \
         the guides are S-shaped bi-arcs with horizontal end tangents, rising by `rise` \
         ({{\"guide_u\": h, \"guide_v\": h}}, default a quarter of each run); every θ but +90° \
         works.\n\n\
         Prints θ, the c_k, each boundary's distance from its plane (relative to the mesh size) \
         and the measured max error.\n\n{THETA}"
    ),
    after_help = format!(
        "Examples:\n  \
         monge align examples/fig17.planes.json -o fig17.json && monge generate fig17.json -o fig17.obj\n  \
         monge align examples/fig16-facade.planes.json --facade --samples 31 -o fig16.json\n\n{EXIT}"
    )
)]
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
