//! `monge fit`: fitting θ and guide coordinates of a multi-patch design to a
//! target with BOBYQA (§4.7, HippoHaus).

use std::path::PathBuf;

use anyhow::Context;
use monge_core::multipatch::build;
use monge_core::optimise::fit;
use monge_core::GenerateOptions;
use monge_io::{check_output, read_multipatch, write_multipatch};

use crate::shared::help::EXIT;
use crate::shared::output::{eprint, num, print};
use crate::shared::warnings::patch_warnings;
use crate::shared::Outcome;

/// Fit θ (and guide coordinates) of a multi-patch design to a target with BOBYQA (§4.7).
#[derive(Debug, clap::Args)]
#[command(
    long_about = format!(
        "Choose free parameters of a multi-patch design so that a patch boundary comes as \
         close as possible to a target (§4.7, the HippoHaus of Figure 21), with BOBYQA \
         (Powell 2009), and write the design with the fitted values to FITTED_DESIGN (the \
         `fit` section is kept, so the file can be fitted again or built with `monge \
         patches`). Prints the largest and rms distances before and after, and each value.\n\n\
         The design's `fit` key: `free`: a list of {{\"theta\": {{\"patch\": K, \"bounds\": \
         [lo, hi]}}}} (bounds optional) and {{\"control_point\": {{\"patch\": K, \"guide\": \
         \"guide_u\"|\"guide_v\"|\"guide\", \"index\": I, \"coordinate\": 0|1|2, \"bounds\": \
         [lo, hi]}}}} (a point of a `points` guide or a control point of a `bspline`); \
         `boundary`: {{\"patch\": K, \"side\": S}}; `target`: {{\"polyline\": [[x, y, z], …]}} \
         or {{\"plane\": {{\"point\", \"normal\"}}}} (e.g. the plane a patch must end in for a \
         mirror, Figure 20); optional `max_distance` (fail above it) and `max_evaluations`. \
         θ stays in its patch's admissible range at the start values (on the start's side of \
         0 when the range excludes 0) and 1° away from the singular +90°."
    ),
    after_help = format!(
        "Examples:\n  \
         monge fit examples/fig21-hippohaus-fit.patches.json -o fitted.json\n  \
         monge patches fitted.json -o hippo.obj\n\n{EXIT}"
    )
)]
pub struct FitArgs {
    /// The multi-patch design file with a `fit` key (`.json` or `.toml`).
    #[arg(value_name = "DESIGN")]
    pub design: PathBuf,
    /// Where to write the fitted design (`.json` or `.toml`).
    #[arg(short, long, value_name = "FITTED_DESIGN")]
    pub output: PathBuf,
    /// Refuse patches of more than N grid vertices each.
    #[arg(long, value_name = "N", default_value_t = GenerateOptions::default().max_vertices)]
    pub max_vertices: usize,
}

/// Runs `monge fit`.
pub fn run(args: &FitArgs) -> anyhow::Result<Outcome> {
    let file = args.design.display().to_string();
    check_output(&args.output, &[&args.design])?;
    let design = read_multipatch(&args.design)?;
    let options = GenerateOptions {
        max_vertices: args.max_vertices,
    };
    let r = fit(&design, &options).with_context(|| file.clone())?;
    write_multipatch(&r.design, &args.output)?;
    let mut s = format!(
        "before: largest distance {} (rms {}, {} of the model size)\n\
         after:  largest distance {} (rms {}, {} of the model size)\n",
        num(r.before.max),
        num(r.before.rms),
        num(r.before.relative),
        num(r.after.max),
        num(r.after.rms),
        num(r.after.relative)
    );
    for (name, start, end, bounds) in &r.values {
        s.push_str(&format!(
            "{name}: {} -> {} (bounds [{}, {}])\n",
            num(*start),
            num(*end),
            num(bounds[0]),
            num(bounds[1])
        ));
    }
    s.push_str(&format!(
        "BOBYQA: {} meshes generated; {}\nwrote {}\n",
        r.evaluations,
        r.status,
        args.output.display()
    ));
    print(&s)?;
    // The fitted design's patches, measured as `monge patches` measures them.
    let fitted = build(&r.design, &options).with_context(|| file.clone())?;
    eprint(&patch_warnings(&fitted));
    Ok(Outcome::Success)
}
