//! `monge`: the command-line program of the monge workspace.
//!
//! `cli` holds the program's help and the list of commands; each command (its
//! arguments, help text and run) is one file under `commands/`; what commands
//! share is in `shared/`, which knows no command. See `monge --help`.
//!
//! Exit statuses: 0 success, 1 `check` found a metric above its tolerance,
//! 2 any error (printed as `error: <message>` on stderr).

mod cli;
mod commands;
mod http;
mod shared;

use std::process::ExitCode;

use clap::Parser;

use crate::cli::Cli;
use crate::shared::output;
use crate::shared::Outcome;

/// mimalloc keeps freed pages for reuse: generating a large mesh again (the
/// bench, or a designer's repeated runs in one process) does not pay the kernel
/// for tens of megabytes of fresh zeroed pages each time (measured: 50 ms → 25 ms
/// for 1000 × 1000 faces with the system allocator vs mimalloc).
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// Exit status of every error.
const ERROR_STATUS: u8 = 2;

fn main() -> ExitCode {
    // clap prints its own `error: …` and exits with status 2 on bad arguments
    // (0 for --help and --version).
    let cli = Cli::parse();
    let result = cli.command.run();
    match result {
        Ok(Outcome::Success) => ExitCode::SUCCESS,
        Ok(Outcome::Failed) => ExitCode::from(1),
        Err(err) => {
            output::eprint(&format!("error: {}\n", message(&err)));
            ExitCode::from(ERROR_STATUS)
        }
    }
}

/// The message of `err` and of its causes, joined by `: `, leaving out a cause
/// that the message already quotes (the typed errors of monge-io include their
/// source's text).
fn message(err: &anyhow::Error) -> String {
    let mut text = String::new();
    for cause in err.chain() {
        let part = cause.to_string();
        if text.is_empty() {
            text = part;
        } else if !text.contains(&part) {
            text.push_str(": ");
            text.push_str(&part);
        }
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;
    use anyhow::Context;

    #[test]
    fn causes_are_joined_once() {
        let io = std::io::Error::new(std::io::ErrorKind::BrokenPipe, "broken pipe");
        let quoted = format!("cannot write `<stdout>`: {io}");
        let err = Err::<(), _>(io).context(quoted).unwrap_err();
        assert_eq!(message(&err), "cannot write `<stdout>`: broken pipe");
        let err = Err::<(), _>(anyhow::anyhow!("bad guide"))
            .context("design.json")
            .unwrap_err();
        assert_eq!(message(&err), "design.json: bad guide");
    }
}
