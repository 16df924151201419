//! The command line of `monge`: the program's help and the list of its
//! commands. Each command's arguments, help text and run are in its own file
//! under `commands/`.

use clap::{Parser, Subcommand};

use crate::commands::{
    align, approximate, bench, check, explore, fabricate, fit, generate, info, optimise_panels,
    patches, render, scan, smooth,
};
use crate::shared::help::{EXIT, THETA};
use crate::shared::Outcome;

/// `monge`: exact circular meshes with planar curvature lines.
#[derive(Debug, Parser)]
#[command(
    name = "monge",
    version,
    about = "Exact circular quad meshes with planar curvature lines, from two planar guide curves and an angle θ",
    long_about = format!(
        "Exact circular quad meshes with planar curvature lines (Tellier et al. 2019, \"Surfaces \
         with planar curvature lines\", Automation in Construction 106, 102880), generated from two planar guide curves that start at the same \
         point and meet at 90°, and one angle θ.\n\n\
         A design file (JSON or TOML) gives `theta_deg`, `guide_u` and `guide_v`; each guide is one \
         of `points`, `bspline`, `arc` or `parabola`. Vertex (i, j) of the mesh lies on row i \
         (along guide_v) and column j (along guide_u): vertex (i, 0) is guide_u's sample i and \
         vertex (0, j) is guide_v's sample j.\n\n{THETA}"
    ),
    after_help = format!(
        "Examples:\n  \
         monge info examples/fig13-freeform.json\n  \
         monge generate examples/fig13-freeform.json -o mesh.obj\n  \
         monge check mesh.obj\n  \
         monge bench --sizes 100,1000\n\n{EXIT}"
    )
)]
pub struct Cli {
    /// The command to run.
    #[command(subcommand)]
    pub command: Command,
}

/// The commands of `monge`; each one's help is on its arguments.
#[derive(Debug, Subcommand)]
pub enum Command {
    Generate(generate::GenerateArgs),
    Smooth(smooth::SmoothArgs),
    Check(check::CheckArgs),
    Info(info::InfoArgs),
    Bench(bench::BenchArgs),
    Render(render::RenderArgs),
    Fabricate(fabricate::FabricateArgs),
    Patches(patches::PatchesArgs),
    Fit(fit::FitArgs),
    Explore(explore::ExploreArgs),
    Scan(scan::ScanArgs),
    Approximate(approximate::ApproximateArgs),
    OptimisePanels(optimise_panels::OptimisePanelsArgs),
    Align(align::AlignArgs),
}

impl Command {
    /// Runs the command.
    pub fn run(self) -> anyhow::Result<Outcome> {
        match self {
            Command::Generate(args) => generate::run(&args),
            Command::Smooth(args) => smooth::run(&args),
            Command::Check(args) => check::run(&args),
            Command::Info(args) => info::run(&args),
            Command::Bench(args) => bench::run(&args),
            Command::Render(args) => render::run(&args),
            Command::Fabricate(args) => fabricate::run(&args),
            Command::Patches(args) => patches::run(&args),
            Command::Fit(args) => fit::run(&args),
            Command::Explore(args) => explore::run(&args),
            Command::Scan(args) => scan::run(&args),
            Command::Approximate(args) => approximate::run(&args),
            Command::OptimisePanels(args) => optimise_panels::run(&args),
            Command::Align(args) => align::run(&args),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    #[test]
    fn command_line_is_consistent() {
        Cli::command().debug_assert();
    }
}
