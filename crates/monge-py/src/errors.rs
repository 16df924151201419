//! The typed errors of monge-core and monge-io as Python exceptions, all under
//! `monge.MongeError`, with the messages the `monge` command prints.

use std::ffi::CString;

use glam::DVec3;
use monge_core::GenerateError;
use monge_io::generated::{far_from_origin, inexact};
use monge_io::IoError;
use pyo3::create_exception;
use pyo3::exceptions::{PyException, PyUserWarning};
use pyo3::prelude::*;

create_exception!(
    monge,
    MongeError,
    PyException,
    "Every error raised by monge; the message says what, where, by how much, and how to fix it."
);
create_exception!(
    monge,
    FileError,
    MongeError,
    "A file cannot be found, read or written."
);
create_exception!(
    monge,
    DesignError,
    MongeError,
    "A design is malformed or invalid: its guides, their start point and angle, its size (§3)."
);
create_exception!(
    monge,
    ThetaError,
    DesignError,
    "θ is not finite, outside the admissible range of the guides (§3.2) or singular (θ = +90°)."
);
create_exception!(
    monge,
    DegenerateError,
    MongeError,
    "The Gauss map degenerates: the mesh pinches, a curvature line is straight there, or the normal barely turns along a guide (§5.2)."
);
create_exception!(
    monge,
    MeshError,
    MongeError,
    "A mesh (file or arrays) is not a regular row-major quad grid of finite points."
);
create_exception!(
    monge,
    SmoothError,
    MongeError,
    "The cyclidic net (§4.4) cannot be built on the mesh."
);
create_exception!(
    monge,
    FabricationError,
    MongeError,
    "Panels, beams or nodes (§6) cannot be built."
);
create_exception!(
    monge,
    ScanError,
    MongeError,
    "A design-space scan (§4.3) cannot be run: bad values or parameter path."
);
create_exception!(
    monge,
    OptimiseError,
    MongeError,
    "θ fitting (§4.7) or panel-size optimisation (§4.8) cannot be run."
);

create_exception!(
    monge,
    FarFromOriginWarning,
    PyUserWarning,
    "The coordinates lie so far from the origin, compared with the design's size, that their rounding as f64 numbers can put the mesh's error above 1e-9 of its size: generate with base_point=\"start\" (coordinates relative to the guides' start point), or model the design near the origin."
);

create_exception!(
    monge,
    InexactWarning,
    PyUserWarning,
    "The mesh, measured as `check` measures it, has an error above the design's tolerance (1e-9 of its size by default); the message gives the error and its likely cause (folded faces, coordinates far from the origin, θ near the singular +90°)."
);

/// Registers the exception classes in the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("MongeError", py.get_type::<MongeError>())?;
    m.add("FileError", py.get_type::<FileError>())?;
    m.add("DesignError", py.get_type::<DesignError>())?;
    m.add("ThetaError", py.get_type::<ThetaError>())?;
    m.add("DegenerateError", py.get_type::<DegenerateError>())?;
    m.add("MeshError", py.get_type::<MeshError>())?;
    m.add("SmoothError", py.get_type::<SmoothError>())?;
    m.add("FabricationError", py.get_type::<FabricationError>())?;
    m.add("ScanError", py.get_type::<ScanError>())?;
    m.add("OptimiseError", py.get_type::<OptimiseError>())?;
    m.add(
        "FarFromOriginWarning",
        py.get_type::<FarFromOriginWarning>(),
    )?;
    m.add("InexactWarning", py.get_type::<InexactWarning>())?;
    Ok(())
}

/// Warns (`FarFromOriginWarning`) when `points` lie so far from the origin,
/// compared with their size, that the rounding of f64 coordinates can put
/// their error above 1e-9 of it: the test and words of `monge generate`, `info` and `check`
/// ([`monge_io::generated::far_from_origin`]). Raises instead if warnings are errors (`-W error`).
pub fn warn_far_from_origin(py: Python<'_>, points: &[DVec3]) -> PyResult<()> {
    let Some(message) = far_from_origin(points) else {
        return Ok(());
    };
    let message = CString::new(message).unwrap_or_default();
    PyErr::warn(py, &py.get_type::<FarFromOriginWarning>(), &message, 1)
}

/// Warns (`InexactWarning`) when `max_error`, measured on a mesh as `check`
/// measures it, exceeds `tolerance`: the test and words of the commands
/// ([`monge_io::generated::inexact`]). Raises instead if warnings are errors.
pub fn warn_inexact(
    py: Python<'_>,
    what: &str,
    (max_error, tolerance): (f64, f64),
    points: &[DVec3],
    folded_faces: usize,
    theta_deg: Option<f64>,
) -> PyResult<()> {
    let Some(message) = inexact(what, max_error, tolerance, points, folded_faces, theta_deg) else {
        return Ok(());
    };
    let message = CString::new(message).unwrap_or_default();
    PyErr::warn(py, &py.get_type::<InexactWarning>(), &message, 1)
}

/// `x` as Python's `repr` writes a float: `nan`, `inf`, `-1.0`, `1e+20`.
pub fn py_float(x: f64) -> String {
    if x.is_nan() {
        "nan".to_owned()
    } else if x.is_infinite() {
        if x > 0.0 { "inf" } else { "-inf" }.to_owned()
    } else if x != 0.0 && !(1e-4..1e16).contains(&x.abs()) {
        // Rust's `1.5e308` as Python's `1.5e+308`, `1e-5` as `1e-05`.
        let s = format!("{x:e}");
        let (mantissa, exponent) = s.split_once('e').unwrap_or((&s, "0"));
        let (sign, digits) = match exponent.strip_prefix('-') {
            Some(d) => ('-', d),
            None => ('+', exponent),
        };
        format!("{mantissa}e{sign}{digits:0>2}")
    } else {
        format!("{x:?}")
    }
}

/// `context: message`, as the command line joins a file name and an error;
/// the message alone without a context.
pub fn text(context: Option<&str>, message: impl std::fmt::Display) -> String {
    match context {
        Some(c) => format!("{c}: {message}"),
        None => message.to_string(),
    }
}

/// A monge-io error: missing or unreadable files are `FileError`, mesh files
/// that are not quad grids `MeshError`, everything else about a design file
/// `DesignError`. The message names the file already.
pub fn io_error(e: IoError) -> PyErr {
    let message = e.to_string();
    match e {
        // In Python's words: how to make the folder.
        IoError::NoDirectory { path, dir } => FileError::new_err(format!(
            "cannot write `{}`: the folder `{}` does not exist: create it first (e.g. \
             os.makedirs), or give a path in a folder that exists",
            path.display(),
            dir.display()
        )),
        IoError::NotFound { .. }
        | IoError::Read { .. }
        | IoError::Write { .. }
        | IoError::Full { .. }
        | IoError::Changed { .. }
        | IoError::NotADirectory { .. }
        | IoError::OutputIsInput { .. }
        | IoError::SameOutput { .. } => FileError::new_err(message),
        IoError::Syntax { .. }
        | IoError::CountMismatch { .. }
        | IoError::NotAGrid { .. }
        | IoError::Binary { .. } => MeshError::new_err(message),
        IoError::UnknownExtension { .. }
        | IoError::NeedFormat { .. }
        | IoError::Parse { .. }
        | IoError::NonFinite { .. }
        | IoError::WrongKind { .. }
        | IoError::DesignTooLarge { .. } => DesignError::new_err(message),
    }
}

/// A generation error (§3, §5.2), after `context` (the design file, if any);
/// a grid above the vertex limit says how to raise it in Python.
pub fn generate_error(context: Option<&str>, e: &GenerateError) -> PyErr {
    let message = match e {
        GenerateError::GridTooLarge {
            rows,
            cols,
            vertices,
            limit,
        } => text(
            context,
            format!(
                "the grid would have {rows} × {cols} = {vertices} vertices, more than the limit \
                 of {limit}: lower the `samples` of the guides, or raise the limit with \
                 generate(design, max_vertices=N) if the machine has the memory (48 bytes a \
                 vertex)"
            ),
        ),
        e => text(context, e),
    };
    match e {
        GenerateError::ThetaNotFinite(_)
        | GenerateError::ThetaInadmissible { .. }
        | GenerateError::ThetaSingular { .. } => ThetaError::new_err(message),
        GenerateError::Degenerate { .. } | GenerateError::NormalStill { .. } => {
            DegenerateError::new_err(message)
        }
        GenerateError::Guide(_)
        | GenerateError::BadTolerance { .. }
        | GenerateError::GridTooLarge { .. }
        | GenerateError::ScaleOutOfRange { .. }
        | GenerateError::StartPointsDiffer { .. }
        | GenerateError::NotOrthogonal { .. } => DesignError::new_err(message),
    }
}

/// `x` to 6 significant digits, as Python's `repr` writes it (`19.1068`).
pub fn py_short(x: f64) -> String {
    py_float(format!("{x:.5e}").parse().unwrap_or(x))
}
