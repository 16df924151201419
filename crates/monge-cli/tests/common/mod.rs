//! Helpers shared by the integration tests of the `monge` binary.
//!
//! Every test file compiles this module into its own test binary and uses only
//! some of it, hence the `allow`.
#![allow(dead_code)]

use std::path::{Path, PathBuf};

use assert_cmd::Command;

/// The bundled example designs.
pub fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

/// An example design by file name.
pub fn example(name: &str) -> PathBuf {
    examples().join(name)
}

/// The `monge` binary.
pub fn monge() -> Command {
    Command::new(env!("CARGO_BIN_EXE_monge"))
}
