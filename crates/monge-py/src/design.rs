//! `monge.Design`: a design (§3), read and written in the design-file format by monge-io.

use std::path::PathBuf;

use monge_core::MeshKind;
use monge_io::{parse_design, read_design, write_design, write_multipatch, DesignFormat, IoError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use serde::Serialize;

use crate::errors::{io_error, py_float, DesignError};

/// A design (§3): two planar guide curves that meet at 90° and the angle θ.
///
/// Build it with `Design.from_file(path)` (JSON or TOML) or
/// `Design.from_dict(d)` (the same keys as a design file); `to_dict()` gives the
/// keys back. Errors name the file, line and column, as `monge` does, or for a
/// dict the key (`guide_u.bspline.samples`).
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

/// JSON text of Python data, one value a line, with the key path of each line:
/// what a dict given for a design file becomes, so that an error located by
/// its line can name the key instead (`guide_u.bspline.samples`).
struct Json {
    text: String,
    /// The key path of each line (the container's on its closing line).
    paths: Vec<String>,
}

impl Json {
    fn newline(&mut self, depth: usize, path: &str) {
        self.text.push('\n');
        self.text.push_str(&" ".repeat(2 * depth));
        self.paths.push(path.to_owned());
    }

    /// Writes `obj` (dicts with string keys, lists, tuples, numbers, strings,
    /// booleans, None; numpy arrays and scalars through `tolist()`).
    fn value(&mut self, obj: &Bound<'_, PyAny>, path: &str, depth: usize) -> PyResult<()> {
        let key = |name: &str| {
            if path.is_empty() {
                name.to_owned()
            } else {
                format!("{path}.{name}")
            }
        };
        let at = |path: &str| {
            if path.is_empty() {
                String::new()
            } else {
                format!(" at `{path}`")
            }
        };
        if obj.is_none() {
            self.text.push_str("null");
        } else if let Ok(b) = obj.cast::<PyBool>() {
            self.text
                .push_str(if b.is_true() { "true" } else { "false" });
        } else if obj.is_instance_of::<PyInt>() {
            self.text.push_str(&obj.str()?.to_cow()?);
        } else if let Ok(x) = obj.cast::<PyFloat>() {
            let x = x.value();
            if !x.is_finite() {
                return Err(DesignError::new_err(format!(
                    "a number is not finite{} ({}): give a finite number",
                    at(path),
                    py_float(x)
                )));
            }
            self.text
                .push_str(&serde_json::to_string(&x).unwrap_or_default());
        } else if let Ok(t) = obj.cast::<PyString>() {
            let t = t.to_cow()?;
            self.text
                .push_str(&serde_json::to_string(&*t).unwrap_or_default());
        } else if let Ok(d) = obj.cast::<PyDict>() {
            self.text.push('{');
            for (k, (name, v)) in d.iter().enumerate() {
                let name = name.cast::<PyString>().map_err(|_| {
                    DesignError::new_err(format!(
                        "the keys of a design are strings; got {}{}",
                        name.repr()
                            .map_or_else(|_| "another key".into(), |r| r.to_string()),
                        at(path)
                    ))
                })?;
                let name = name.to_cow()?;
                if k > 0 {
                    self.text.push(',');
                }
                let child = key(&name);
                self.newline(depth + 1, &child);
                self.text
                    .push_str(&serde_json::to_string(&*name).unwrap_or_default());
                self.text.push_str(": ");
                self.value(&v, &child, depth + 1)?;
            }
            if !d.is_empty() {
                self.newline(depth, path);
            }
            self.text.push('}');
        } else if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
            self.text.push('[');
            for (k, v) in obj.try_iter()?.enumerate() {
                if k > 0 {
                    self.text.push(',');
                }
                let child = format!("{path}[{k}]");
                self.newline(depth + 1, &child);
                self.value(&v?, &child, depth + 1)?;
            }
            if obj.len()? > 0 {
                self.newline(depth, path);
            }
            self.text.push(']');
        } else if obj.hasattr("tolist")? {
            // numpy arrays and scalars
            self.value(&obj.call_method0("tolist")?, path, depth)?;
        } else {
            return Err(DesignError::new_err(format!(
                "the design is not JSON-like data (dicts, lists, numbers, strings; numpy arrays \
                 are accepted): {} is {}{}",
                obj.repr()?,
                obj.get_type().name()?,
                at(path)
            )));
        }
        Ok(())
    }
}

/// `d` parsed by `parse` (monge-io's parser of a design file's text) as a dict
/// of the file's keys: errors say `function: at `key.path`: what`, not the line
/// of a text the caller never saw.
pub fn parse_dict<T>(
    d: &Bound<'_, PyAny>,
    function: &str,
    parse: impl FnOnce(&str) -> Result<T, IoError>,
) -> PyResult<T> {
    if !d.is_instance_of::<PyDict>() {
        return Err(DesignError::new_err(format!(
            "{function}: give a dict with the keys of the file, got {} {}",
            d.get_type().name()?,
            d.repr()?
        )));
    }
    let mut json = Json {
        text: String::new(),
        paths: vec![String::new()],
    };
    json.value(d, "", 0)
        .map_err(|e| DesignError::new_err(format!("{function}: {}", e.value(d.py()))))?;
    parse(&json.text).map_err(|e| match e {
        IoError::Parse { line, message, .. } => {
            let path = line
                .checked_sub(1)
                .and_then(|l| json.paths.get(l))
                .map_or("", String::as_str);
            DesignError::new_err(if path.is_empty() || message.contains(path) {
                format!("{function}: {message}")
            } else {
                format!("{function}: at `{path}`: {message}")
            })
        }
        // The kind of the data (`WrongKind`): the text is named `<input>`.
        e => {
            let message = e.to_string();
            let message = message.strip_prefix("<input>").unwrap_or(&message);
            DesignError::new_err(format!("{function}: the dict{message}"))
        }
    })
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
    /// are accepted wherever the file has lists. Errors name the key, e.g.
    /// `guide_u.bspline.control_points[1][0]`.
    #[staticmethod]
    fn from_dict(d: &Bound<'_, PyAny>) -> PyResult<Design> {
        let inner = parse_dict(d, "Design.from_dict", |text| {
            parse_design(text, DesignFormat::Json)
        })?;
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

/// A multi-patch design (§4.7): patches with piecewise planar curvature lines, each
/// attached to an earlier one, in the format `monge patches` and `monge fit` read
/// (`.patches.json`). `approximate(target, patches=...)` or `tolerance=...` returns
/// one when several patches follow the target closer than one.
#[pyclass(module = "monge", frozen)]
#[derive(Clone)]
pub struct PatchesDesign {
    /// The design itself.
    pub inner: monge_core::multipatch::MultiPatchDesign,
}

#[pymethods]
impl PatchesDesign {
    /// The design as a dict with the keys of a multi-patch design file (what
    /// `fit(design)` takes).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        json_to_python(py, &self.inner)
    }

    /// Writes the multi-patch design file (`monge patches` reads it), pretty JSON
    /// or TOML by the extension, atomically, as `monge approximate` writes it.
    fn to_file(&self, path: PathBuf) -> PyResult<()> {
        write_multipatch(&self.inner, &path).map_err(io_error)
    }

    /// θ of each patch in degrees, in design order (each in its own frame).
    #[getter]
    fn theta_deg(&self) -> Vec<f64> {
        self.inner.patches.iter().map(|p| p.theta_deg).collect()
    }

    fn __len__(&self) -> usize {
        self.inner.patches.len()
    }

    fn __repr__(&self) -> String {
        format!(
            "PatchesDesign(patches={}, theta_deg={:?})",
            self.inner.patches.len(),
            self.theta_deg()
        )
    }

    fn __eq__(&self, other: &PatchesDesign) -> bool {
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
