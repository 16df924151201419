//! monge-io's integration tests, one binary (but `design_memory`, which counts
//! allocations with its own global allocator): each module is one topic.
//! One binary links and compiles the shared helpers once and runs every test in
//! one pool of threads: `cargo test -p monge-io --test integration MODULE::`
//! runs one module.

mod atomic;
mod common;
mod design;
mod fabrication_outputs;
mod fuzz_corpus;
mod iges_read;
mod iges_write;
mod mesh_read;
mod mesh_write;
mod points_read;
mod scan;
mod trimmed;
