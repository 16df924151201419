//! `monge.Design`: a design (§3), read and written in the design-file format by monge-io.

use std::path::PathBuf;

use monge_core::MeshKind;
use monge_io::{parse_design, read_design, write_design, DesignFormat};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use serde::Serialize;

use crate::errors::{io_error, DesignError};

/// A design (§3): two planar guide curves that meet at 90° and the angle θ.
///
/// Build it with `Design.from_file(path)` (JSON or TOML) or
/// `Design.from_dict(d)` (the same keys as a design file); `to_dict()` gives the
/// keys back. Errors name the file, line and column, as `monge` does.
#[pyclass(module = "monge")]
#[derive(Clone)]
pub struct Design {
    /// The design itself.
    pub inner: monge_core::Design,
    /// The file it was read from, as given: the context of error messages,
    /// like the `monge` command's `FILE: message`.
    pub source: Option<String>,
}

impl Design {
    /// The context of error messages about this design.
    pub fn context(&self) -> Option<&str> {
        self.source.as_deref()
    }
}

/// `obj.tolist()`: lets `json.dumps` write numpy arrays and numbers.
#[pyfunction]
fn tolist<'py>(obj: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
    obj.call_method0("tolist")
}

/// `d` as JSON text (numpy arrays as lists), indented so that an error's line
/// and column point at one key.
pub fn dict_to_json(d: &Bound<'_, PyAny>) -> PyResult<String> {
    let py = d.py();
    let kwargs = PyDict::new(py);
    kwargs.set_item("indent", 2)?;
    kwargs.set_item("allow_nan", false)?;
    kwargs.set_item("default", wrap_pyfunction!(tolist, py)?)?;
    let json = py.import("json")?;
    let text = json
        .call_method("dumps", (d,), Some(&kwargs))
        .map_err(|e| {
            DesignError::new_err(format!(
                "the design is not JSON-like data (dicts, lists, numbers, strings; numpy arrays are \
                 accepted): {}",
                e.value(py)
            ))
        })?;
    text.extract()
}

/// `value` as the Python data `json.loads` makes of its JSON: dicts and lists,
/// as in a design file (non-finite numbers become None).
pub fn json_to_python<'py, T: Serialize>(
    py: Python<'py>,
    value: &T,
) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value)
        .map_err(|e| DesignError::new_err(format!("cannot convert to JSON: {e}")))?;
    py.import("json")?.call_method1("loads", (text,))
}

#[pymethods]
impl Design {
    /// Reads a design file, JSON or TOML by its extension (§3).
    #[staticmethod]
    fn from_file(path: PathBuf) -> PyResult<Design> {
        let inner = read_design(&path).map_err(io_error)?;
        Ok(Design {
            inner,
            source: Some(path.display().to_string()),
        })
    }

    /// A design from a dict with the keys of a design file (§3); numpy arrays
    /// are accepted wherever the file has lists.
    #[staticmethod]
    fn from_dict(d: &Bound<'_, PyAny>) -> PyResult<Design> {
        let text = dict_to_json(d)?;
        let inner = parse_design(&text, DesignFormat::Json).map_err(io_error)?;
        Ok(Design {
            inner,
            source: None,
        })
    }

    /// The design as a dict with the keys of a design file (lists, as in the file).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        json_to_python(py, &self.inner)
    }

    /// Writes the design file, pretty JSON or TOML by the extension, atomically.
    fn to_file(&self, path: PathBuf) -> PyResult<()> {
        write_design(&self.inner, &path).map_err(io_error)
    }

    /// θ in degrees (§3.1, §3.2).
    #[getter]
    fn theta_deg(&self) -> f64 {
        self.inner.theta_deg
    }

    #[setter]
    fn set_theta_deg(&mut self, theta_deg: f64) {
        self.inner.theta_deg = theta_deg;
    }

    /// `"circular"` (§2.2) or `"conical"` (§2.3): the mesh `generate` builds by default.
    #[getter]
    fn mesh(&self) -> &'static str {
        kind_name(self.inner.mesh)
    }

    /// The file the design was read from, or None.
    #[getter]
    fn source(&self) -> Option<String> {
        self.source.clone()
    }

    fn __repr__(&self) -> String {
        format!(
            "Design(theta_deg={}, mesh={:?}, grid={}x{}{})",
            self.inner.theta_deg,
            kind_name(self.inner.mesh),
            self.inner.guide_u.sample_count(),
            self.inner.guide_v.sample_count(),
            self.source
                .as_ref()
                .map(|s| format!(", source={s:?}"))
                .unwrap_or_default()
        )
    }

    fn __eq__(&self, other: &Design) -> bool {
        self.inner == other.inner
    }
}

/// `"circular"` or `"conical"`.
pub fn kind_name(kind: MeshKind) -> &'static str {
    match kind {
        MeshKind::Circular => "circular",
        MeshKind::Conical => "conical",
    }
}

/// The mesh kind named `name`, or the design's own when `None` (§2.2, §2.3).
pub fn parse_kind(name: Option<&str>, default: MeshKind) -> PyResult<MeshKind> {
    match name {
        None => Ok(default),
        Some("circular") => Ok(MeshKind::Circular),
        Some("conical") => Ok(MeshKind::Conical),
        Some(other) => Err(DesignError::new_err(format!(
            "kind = {other:?}: give \"circular\" (§2.2) or \"conical\" (§2.3)"
        ))),
    }
}
