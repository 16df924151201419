//! `monge.TrimmedDesign`: a design, or a multi-patch design, and the outline its mesh
//! is cut by, read and written in the design-file format by monge-io.

use std::path::PathBuf;

use monge_core::approximate::TrimmedMesh;
use monge_core::GenerateOptions;
use monge_io::{read_any_design, write_trimmed, AnyDesign, Trimmable};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::design::{Design, PatchesDesign};
use crate::errors::{io_error, DesignError};
use crate::target::points_array;

/// A trimmed design: a design (or a multi-patch design) and the outline its mesh is
/// cut by, as `monge approximate` writes a trimmed result and `monge generate` reads
/// it. `approximate(...)` returns one where its result is trimmed.
#[pyclass(module = "monge", frozen)]
#[derive(Clone)]
pub struct TrimmedDesign {
    /// The design itself.
    pub inner: monge_io::TrimmedDesign,
}

#[pymethods]
impl TrimmedDesign {
    /// Reads a trimmed design file (the keys `design` and `trim`), JSON or TOML by its
    /// extension.
    #[staticmethod]
    fn from_file(path: PathBuf) -> PyResult<TrimmedDesign> {
        match read_any_design(&path).map_err(io_error)? {
            AnyDesign::Trimmed(inner) => Ok(TrimmedDesign { inner: *inner }),
            _ => Err(DesignError::new_err(format!(
                "`{}` is not a trimmed design (the keys `design` and `trim`): read it with \
                 Design.from_file",
                path.display()
            ))),
        }
    }

    /// Writes the trimmed design file, pretty JSON or TOML by the extension,
    /// atomically, as `monge approximate` writes it.
    fn to_file(&self, path: PathBuf) -> PyResult<()> {
        write_trimmed(&self.inner, &path).map_err(io_error)
    }

    /// The design before trimming: a `Design`, or a `PatchesDesign` of several patches.
    #[getter]
    fn design(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        Ok(match &self.inner.design {
            Trimmable::Surface(d) => Bound::new(
                py,
                Design {
                    inner: (**d).clone(),
                    source: None,
                },
            )?
            .into_any()
            .unbind(),
            Trimmable::Patches(d) => Bound::new(py, PatchesDesign { inner: d.clone() })?
                .into_any()
                .unbind(),
        })
    }

    /// The outline's corners in space, (n, 3): a polygon in a plane, seen along its
    /// normal, that the mesh is cut by.
    #[getter]
    fn outline<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let corners = self.inner.trim.polygon();
        Ok(points_array(py, &corners, &[corners.len()])?.into_any())
    }

    /// The mesh cut by the outline, as `monge generate` writes it: a dict of its
    /// `vertices` (n, 3), `faces` (polygons), `cut`, `from` and `mesh_faces`, as
    /// `approximate`'s `trimmed`.
    fn mesh<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let (_, mesh) = py
            .detach(|| self.inner.mesh(&GenerateOptions::default()))
            .map_err(|e| DesignError::new_err(e.to_string()))?;
        trimmed_dict(py, &mesh)
    }

    fn __repr__(&self) -> String {
        let what = match &self.inner.design {
            Trimmable::Surface(_) => "1 patch".to_owned(),
            Trimmable::Patches(d) => format!("{} patches", d.patches.len()),
        };
        format!(
            "TrimmedDesign({what}, outline of {} corners)",
            self.inner.trim.polygon().len()
        )
    }

    fn __eq__(&self, other: &TrimmedDesign) -> bool {
        self.inner == other.inner
    }
}

/// A trimmed mesh as a dict: its `vertices` (n, 3), `faces` (lists of vertex indices)
/// and `cut` (per face, whether the outline cut it).
pub(crate) fn trimmed_dict<'py>(
    py: Python<'py>,
    mesh: &TrimmedMesh,
) -> PyResult<Bound<'py, PyDict>> {
    let dict = PyDict::new(py);
    dict.set_item(
        "vertices",
        points_array(py, &mesh.vertices, &[mesh.vertices.len()])?,
    )?;
    dict.set_item("faces", mesh.faces.clone())?;
    dict.set_item("cut", mesh.cut.clone())?;
    dict.set_item("from", mesh.from.clone())?;
    dict.set_item("mesh_faces", mesh.mesh_faces())?;
    Ok(dict)
}
