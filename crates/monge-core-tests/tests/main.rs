//! monge-core's integration tests, one binary: each module is one topic.
//! One binary links and compiles the shared helpers once and runs every test in
//! one pool of threads: `cargo test -p monge-core-tests --test integration MODULE::`
//! runs one module.

mod analytic;
mod approximate;
mod approximate_heldout;
mod approximate_patches;
mod boundary;
mod common;
mod conical;
mod cyclidic_arcs;
mod cyclidic_errors;
mod cyclidic_net;
mod cyclidic_patches;
mod darboux;
mod degenerate;
mod developable;
mod developable_errors;
mod errors;
mod fabrication;
mod far_from_origin;
mod folds;
mod garbage_designs;
mod heldout;
mod measure_crosscheck;
mod multipatch;
mod optimise;
mod panels;
mod properties;
mod scan;
mod symmetry;
mod threads;
