//! The `monge` command's integration tests, one binary: each module is one command
//! or one concern.
//! One binary links and compiles the shared helpers once and runs every test in
//! one pool of threads: `cargo test -p monge-cli --test integration MODULE::`
//! runs one module.

mod align;
mod approximate;
mod base_point;
mod bench;
mod check;
mod citation;
mod common;
mod design_errors;
mod design_tools;
mod docs_commands;
mod explore;
mod fabricate;
mod faults;
mod first_use;
mod gallery;
mod generate;
mod hostile_input;
mod info;
mod layering;
mod orientation;
mod outputs;
mod patches;
mod render;
mod smooth;
mod trimmed;
