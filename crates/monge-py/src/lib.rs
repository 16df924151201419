//! Python bindings of monge (module `monge`, built with maturin as an abi3
//! wheel for CPython ≥ 3.9).
//!
//! A front end like the `monge` command: it calls monge-core (and monge-io for
//! design files, so that error messages are the command's) and adds no geometry.
//! Meshes are numpy arrays of shape (rows, cols, 3) that view the mesh's own
//! memory; the typed errors of the libraries are Python exceptions under
//! `monge.MongeError`. The pure-Python modules (`monge.rhino`, `monge.compas`)
//! and the type stubs are in `python/monge`.

use pyo3::prelude::*;

mod approximate;
mod args;
mod design;
mod errors;
mod mesh;
mod target;
mod tools;
mod trimmed;

/// The native module `monge._monge`, re-exported by the package `monge`.
#[pymodule]
fn _monge(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    errors::register(m)?;
    m.add_class::<design::Design>()?;
    m.add_class::<design::PatchesDesign>()?;
    m.add_class::<trimmed::TrimmedDesign>()?;
    m.add_class::<mesh::Mesh>()?;
    m.add_function(wrap_pyfunction!(mesh::generate, m)?)?;
    m.add_function(wrap_pyfunction!(tools::info, m)?)?;
    m.add_function(wrap_pyfunction!(tools::check, m)?)?;
    m.add_function(wrap_pyfunction!(tools::smooth, m)?)?;
    m.add_function(wrap_pyfunction!(tools::fabricate, m)?)?;
    m.add_function(wrap_pyfunction!(tools::scan, m)?)?;
    m.add_function(wrap_pyfunction!(tools::fit, m)?)?;
    m.add_function(wrap_pyfunction!(tools::optimise_panels, m)?)?;
    m.add_function(wrap_pyfunction!(approximate::approximate, m)?)?;
    m.add_function(wrap_pyfunction!(target::target_points, m)?)?;
    Ok(())
}
