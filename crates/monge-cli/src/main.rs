//! `monge`: the command-line program of the monge workspace.
//!
//! Commands: `generate` (design → OBJ/PLY/JSON mesh), `check` (measure a mesh
//! against a tolerance), `info` (validate a design without generating) and
//! `bench` (time the generator in-process). See `monge --help`.
//!
//! Exit statuses: 0 success, 1 `check` found a metric above its tolerance,
//! 2 any error (printed as `error: <message>` on stderr).

mod bench;
mod check;
mod cli;
mod generate;
mod info;
mod output;

use std::process::ExitCode;

use clap::Parser;

use crate::cli::{Cli, Command};

/// What a command that ran to completion found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// Everything as expected: exit status 0.
    Success,
    /// `check` found a metric above its tolerance: exit status 1.
    Failed,
}

/// Exit status of every error.
const ERROR_STATUS: u8 = 2;

fn main() -> ExitCode {
    // clap prints its own `error: …` and exits with status 2 on bad arguments
    // (0 for --help and --version).
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Generate(args) => generate::run(&args),
        Command::Check(args) => check::run(&args),
        Command::Info(args) => info::run(&args),
        Command::Bench(args) => bench::run(&args),
    };
    match result {
        Ok(Outcome::Success) => ExitCode::SUCCESS,
        Ok(Outcome::Failed) => ExitCode::from(1),
        Err(err) => {
            output::eprint(&format!("error: {err:#}\n"));
            ExitCode::from(ERROR_STATUS)
        }
    }
}
