//! `monge.generate` and `monge.Mesh`: the circular mesh (§2.2) or its conical
//! dual (§2.3) of a design, its arrays shared with numpy without copies.

use glam::DVec3;
use monge_core::combescure::CombescureReport;
use monge_core::conical::{conical_dual, conical_folds, ConicalMesh};
use monge_core::measure::{conical_error, measure, Measurements, Worst};
use monge_core::offset::{face_offset, vertex_offset};
use monge_core::{
    generate as core_generate, BasePoint, GenerateOptions, MeshKind, Mode, QuadGrid, Tolerances,
};
use numpy::ndarray::ArrayView3;
use numpy::{PyArray1, PyArray2, PyArray3, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::args;
use crate::design::{kind_name, parse_kind, Design};
use crate::errors::{
    generate_error, py_float, py_short, warn_far_from_origin, warn_inexact, DesignError, MeshError,
};

/// The geometry of a mesh: a circular mesh with its node axes, or a conical mesh
/// with its face normals and offset directions.
#[derive(Clone, Debug)]
pub enum Geometry {
    /// A circular mesh (§2.2): vertices and unit node axes.
    Circular(QuadGrid),
    /// A conical mesh (§2.3).
    Conical(ConicalMesh),
}

impl Geometry {
    /// The quad grid of vertices.
    pub fn grid(&self) -> &QuadGrid {
        match self {
            Geometry::Circular(g) => g,
            Geometry::Conical(c) => &c.grid,
        }
    }

    /// The face normals of a conical mesh (§2.3).
    pub fn face_normals(&self) -> Option<&[DVec3]> {
        match self {
            Geometry::Circular(_) => None,
            Geometry::Conical(c) => Some(&c.face_normals),
        }
    }
}

/// A generated mesh (§2.2, §2.3): `vertices` and `normals` are read-only numpy
/// views, shape (rows, cols, 3), of the mesh's own memory.
#[pyclass(module = "monge", frozen)]
pub struct Mesh {
    /// The vertices and what offsets need.
    pub geometry: Geometry,
    /// θ in degrees, reduced to (−180, 180].
    theta_deg: f64,
    /// The generation mode (§3.1, §3.2).
    mode: Mode,
    /// Folds and pinches seen by the Combescure transform (§5.2).
    report: CombescureReport,
    /// The largest error `check` measures on this mesh ([`measurements`]).
    max_error: f64,
    /// The offset distance from the generated mesh (§2.2, §2.3); 0 for it.
    offset: f64,
    /// The point the coordinates are relative to (`generate(base_point=…)`), if any.
    base_point: Option<DVec3>,
}

/// What `monge check --kind KIND` measures (§2.2, §2.3): for a conical mesh the
/// conical condition takes the place of `circularity`, which such a mesh need
/// not satisfy. Returns the measurements and their `max_error`, the largest of
/// the metrics the kind requires ([`Measurements::max_error_conical`] for a
/// conical mesh), as `monge check --json` reports it; a conical mesh's folds
/// are those `monge check --kind conical` finds ([`conical_folds`], about its
/// `face_normals` when known).
pub fn measurements(
    grid: &QuadGrid,
    kind: MeshKind,
    face_normals: Option<&[DVec3]>,
) -> (Measurements, f64) {
    let mut m = measure(grid);
    if kind != MeshKind::Conical {
        let max_error = m.max_error();
        return (m, max_error);
    }
    let folds = conical_folds(grid, face_normals);
    (m.folded_faces, m.first_fold) = (folds.count(), folds.first());
    let conical = conical_error(grid);
    let max_error = m.max_error_conical(conical);
    m.circularity = conical.unwrap_or(Worst {
        value: 0.0,
        at: (0, 0),
    });
    (m, max_error)
}

/// The quad faces of `grid` as rows of four 0-based indices (`Mesh.faces`).
pub fn faces_array<'py>(py: Python<'py>, grid: &QuadGrid) -> PyResult<Bound<'py, PyArray2<u64>>> {
    let faces: Vec<u64> = grid
        .oriented_faces()
        .flat_map(|f| f.map(|k| k as u64))
        .collect();
    PyArray1::from_vec(py, faces).reshape([grid.face_count(), 4])
}

/// The `(rows, cols, 3)` read-only numpy view of `points`, kept alive by `owner`.
fn view<'py>(
    owner: &Bound<'py, Mesh>,
    points: &[DVec3],
    rows: usize,
    cols: usize,
) -> PyResult<Bound<'py, PyArray3<f64>>> {
    const _: () = assert!(std::mem::size_of::<DVec3>() == 3 * std::mem::size_of::<f64>());
    if points.len() != rows * cols {
        return Err(DesignError::new_err(format!(
            "{} points cannot be viewed as a {rows} × {cols} grid",
            points.len()
        )));
    }
    // SAFETY: DVec3 is `repr(C)` with three f64 fields (size checked above), so
    // `points` is `rows · cols · 3` contiguous, aligned f64 values.
    let array = unsafe { ArrayView3::from_shape_ptr((rows, cols, 3), points.as_ptr().cast()) };
    // SAFETY: `points` belongs to the frozen `owner`, which never changes or
    // reallocates it, and becomes the array's base, so it outlives the array.
    let array = unsafe { PyArray3::borrow_from_array(&array, owner.clone().into_any()) };
    array.readwrite().make_nonwriteable();
    Ok(array)
}

impl Mesh {
    /// Warns (`InexactWarning`) as the commands do when this mesh's measured
    /// `max_error` exceeds `tolerance`.
    fn warn_inexact(&self, py: Python<'_>, tolerance: f64) -> PyResult<()> {
        warn_inexact(
            py,
            "the mesh",
            (self.max_error, tolerance),
            &self.geometry.grid().vertices,
            self.report.folded_faces,
            Some(self.theta_deg),
        )
    }

    /// The mesh of `kind` (§2.2, §2.3) generated from `design`, relative to
    /// `base` if given ([`BasePoint::apply`]).
    pub(crate) fn generate(
        design: &Design,
        kind: MeshKind,
        options: &GenerateOptions,
        base: Option<BasePoint>,
    ) -> PyResult<Mesh> {
        let (inner, base_point) = match base {
            Some(b) => b.apply(design.inner.clone()),
            None => (design.inner.clone(), None),
        };
        let g = core_generate(&inner, options).map_err(|e| generate_error(design.context(), &e))?;
        let geometry = match kind {
            MeshKind::Circular => Geometry::Circular(g.grid),
            // Guides have at least 3 samples (2 would be straight), so the
            // circular mesh has the 3 × 3 vertices a conical dual needs.
            MeshKind::Conical => Geometry::Conical(conical_dual(&g.grid)),
        };
        Ok(Mesh::new(
            geometry,
            g.info.theta_deg,
            g.info.mode,
            g.report,
            (0.0, base_point.map(DVec3::from_array)),
            false,
        ))
    }

    /// The mesh of `geometry`, measured, at `(offset distance, base point)`.
    /// `report` is the generation's (§5.2); with `measured_folds` (an offset,
    /// which the generation did not build) its folded faces are replaced by
    /// those `check` finds on this mesh, and for a conical mesh by its own
    /// ([`conical_folds`] about its face normals, as `monge generate` reports
    /// them). The smallest crossing sine is a property of the Gauss map, which
    /// an offset or a conical dual shares.
    fn new(
        geometry: Geometry,
        theta_deg: f64,
        mode: Mode,
        report: CombescureReport,
        (offset, base_point): (f64, Option<DVec3>),
        measured_folds: bool,
    ) -> Mesh {
        let kind = match geometry {
            Geometry::Circular(_) => MeshKind::Circular,
            Geometry::Conical(_) => MeshKind::Conical,
        };
        let (m, max_error) = measurements(geometry.grid(), kind, geometry.face_normals());
        let report = if measured_folds || kind == MeshKind::Conical {
            CombescureReport {
                folded_faces: m.folded_faces,
                first_fold: m.first_fold,
                ..report
            }
        } else {
            report
        };
        Mesh {
            geometry,
            theta_deg,
            mode,
            report,
            max_error,
            offset,
            base_point,
        }
    }
}

#[pymethods]
impl Mesh {
    /// Vertex (i, j) at `[i, j]`: i along guide_u, j along guide_v (read-only view).
    #[getter]
    fn vertices<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyArray3<f64>>> {
        let g = slf.get().geometry.grid();
        view(slf, &g.vertices, g.rows, g.cols)
    }

    /// The unit node axes (§2.2), the mesh's Gauss map, for a circular mesh;
    /// None for a conical mesh (see `face_normals`).
    #[getter]
    fn normals<'py>(slf: &Bound<'py, Self>) -> PyResult<Option<Bound<'py, PyArray3<f64>>>> {
        match &slf.get().geometry {
            Geometry::Circular(g) => view(slf, &g.normals, g.rows, g.cols).map(Some),
            Geometry::Conical(_) => Ok(None),
        }
    }

    /// The unit face normals of a conical mesh (§2.3), shape (rows − 1, cols − 1, 3),
    /// face (i, j) at `[i, j]`; None for a circular mesh.
    #[getter]
    fn face_normals<'py>(slf: &Bound<'py, Self>) -> PyResult<Option<Bound<'py, PyArray3<f64>>>> {
        match &slf.get().geometry {
            Geometry::Circular(_) => Ok(None),
            Geometry::Conical(c) => {
                view(slf, &c.face_normals, c.grid.rows - 1, c.grid.cols - 1).map(Some)
            }
        }
    }

    /// The quad faces as rows of four 0-based indices into `vertices.reshape(-1, 3)`,
    /// face (i, j) at row `i·(cols − 1) + j`, wound as in the OBJ, PLY and glTF
    /// files of `monge generate` (the same function decides): corners (i, j),
    /// (i+1, j), (i+1, j+1), (i, j+1), counter-clockwise about the node axes, or
    /// the other way round, (i, j), (i, j+1), (i+1, j+1), (i+1, j), when most faces
    /// turn the other way about them (an offset through the focal surface; §2.2).
    #[getter]
    fn faces<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<u64>>> {
        faces_array(py, self.geometry.grid())
    }

    /// Number of rows (samples of guide_u, or one less for a conical mesh).
    #[getter]
    fn rows(&self) -> usize {
        self.geometry.grid().rows
    }

    /// Number of columns (samples of guide_v, or one less for a conical mesh).
    #[getter]
    fn cols(&self) -> usize {
        self.geometry.grid().cols
    }

    /// `"circular"` (§2.2) or `"conical"` (§2.3).
    #[getter]
    fn kind(&self) -> &'static str {
        kind_name(match self.geometry {
            Geometry::Circular(_) => MeshKind::Circular,
            Geometry::Conical(_) => MeshKind::Conical,
        })
    }

    /// θ in degrees, reduced to (−180, 180].
    #[getter]
    fn theta_deg(&self) -> f64 {
        self.theta_deg
    }

    /// `"characteristic"` (§3.1) or `"arbitrary"` (§3.2).
    #[getter]
    fn mode(&self) -> &'static str {
        match self.mode {
            Mode::Characteristic => "characteristic",
            Mode::Arbitrary => "arbitrary",
        }
    }

    /// The distance of this mesh from the generated one (`offset(d)`); 0 for it.
    #[getter]
    fn offset_distance(&self) -> f64 {
        self.offset
    }

    /// The point `(x, y, z)` the coordinates are relative to
    /// (`generate(design, base_point=…)`): the true coordinates are `vertices`
    /// plus it. None when they are absolute.
    #[getter]
    fn base_point(&self) -> Option<(f64, f64, f64)> {
        self.base_point.map(|b| b.into())
    }

    /// What the generation found (§5.2): `folded_faces`, `first_fold` ((i, j) or
    /// None), `min_crossing_sine`, `min_crossing_face`, and `max_error`, the
    /// largest error `check(mesh)` measures on this mesh (planarity, circularity
    /// or the conical condition, planar lines, torsion; lengths relative to its size).
    /// For an offset (`offset(d)`), `folded_faces` and `first_fold` are those
    /// `check` finds on the offset mesh itself; the crossing, a property of the
    /// Gauss map it shares, is the generated mesh's.
    #[getter]
    fn report<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let r = &self.report;
        let d = PyDict::new(py);
        d.set_item("folded_faces", r.folded_faces)?;
        d.set_item("first_fold", r.first_fold)?;
        d.set_item("min_crossing_sine", r.min_crossing.sine)?;
        d.set_item("min_crossing_face", r.min_crossing.face)?;
        d.set_item("max_error", self.max_error)?;
        Ok(d)
    }

    /// The offset mesh at distance `d` (§2.2, §2.3): for a circular mesh the node
    /// offset along the node axes, for a conical mesh the face offset. Refused
    /// (`MeshError`) if its coordinates or its size (the bounding-box diagonal that
    /// `check` measures against) are not finite in f64.
    fn offset(&self, py: Python<'_>, d: f64) -> PyResult<Mesh> {
        if !d.is_finite() {
            return Err(DesignError::new_err(format!(
                "offset distance {d}: give a finite distance"
            )));
        }
        let geometry = match &self.geometry {
            Geometry::Circular(g) => Geometry::Circular(vertex_offset(g, d)),
            Geometry::Conical(c) => Geometry::Conical(face_offset(c, d)),
        };
        check_offset(self.geometry.grid(), geometry.grid(), d)?;
        let mesh = Mesh::new(
            geometry,
            self.theta_deg,
            self.mode,
            self.report,
            (self.offset + d, self.base_point),
            true,
        );
        mesh.warn_inexact(py, Tolerances::default().planarity)?;
        Ok(mesh)
    }

    fn __repr__(&self) -> String {
        let g = self.geometry.grid();
        format!(
            "Mesh(kind={:?}, rows={}, cols={}, theta_deg={}, offset={})",
            self.kind(),
            g.rows,
            g.cols,
            self.theta_deg,
            self.offset
        )
    }
}

/// Refuses the offset `offset` of `base` at distance `d` if a vertex is not
/// finite, or if its size (the bounding-box diagonal every measurement is
/// relative to) is not: it could not be measured.
fn check_offset(base: &QuadGrid, offset: &QuadGrid, d: f64) -> PyResult<()> {
    let size = base.bbox_diagonal();
    let advice = format!(
        "give a smaller |d| (this mesh's own size is {}; the offset's size, about 2|d|, must \
         stay below about 1e154, where its square overflows)",
        py_short(size)
    );
    if let Some(k) = offset.vertices.iter().position(|p| !p.is_finite()) {
        let (i, j) = (k / offset.cols, k % offset.cols);
        return Err(MeshError::new_err(format!(
            "offset(d={}): vertex [{i}, {j}] of the offset mesh is not finite ({}): {advice}",
            py_float(d),
            offset.vertices[k]
        )));
    }
    let offset_size = offset.bbox_diagonal();
    if !offset_size.is_finite() {
        let far = offset
            .vertices
            .iter()
            .map(|p| p.abs().max_element())
            .fold(0.0, f64::max);
        return Err(MeshError::new_err(format!(
            "offset(d={}): the offset mesh's size (its bounding-box diagonal) is not finite in \
             f64, its coordinates reaching {far:.1e}, so it cannot be measured: {advice}",
            py_float(d)
        )));
    }
    Ok(())
}

/// Generates the mesh of a design (§3): `kind` `"circular"` (§2.2) or
/// `"conical"` (§2.3), by default the design's own `mesh`. Warns
/// (`FarFromOriginWarning`) as `monge generate` does when the mesh lies so far
/// from the origin that the rounding of f64 coordinates can put its error
/// above 1e-9 of its size.
///
/// `max_vertices` (default 25 000 000, about 1.2 GB of vertices and normals, as
/// the command's `--max-vertices`) bounds the grid: a design whose guides have
/// more samples is refused before anything is allocated.
///
/// `base_point` (`"start"`, the guides' common start point, or `(x, y, z)`), as
/// the command's `--base-point`: the mesh is computed and returned relative to
/// that point (`Mesh.base_point`), which keeps it exact far from the origin.
#[pyfunction]
#[pyo3(
    signature = (design, kind = None, max_vertices = GenerateOptions::default().max_vertices, base_point = None),
    text_signature = "(design, kind=None, max_vertices=25000000, base_point=None)"
)]
pub fn generate(
    py: Python<'_>,
    design: &Design,
    kind: Option<&str>,
    #[pyo3(from_py_with = args::max_vertices)] max_vertices: usize,
    #[pyo3(from_py_with = args::base_point)] base_point: Option<BasePoint>,
) -> PyResult<Mesh> {
    let kind = parse_kind(kind, design.inner.mesh)?;
    let design = design.clone();
    let tolerance = design.inner.tolerance.unwrap_or_default().planarity;
    let options = GenerateOptions { max_vertices };
    let mesh = py.detach(move || Mesh::generate(&design, kind, &options, base_point))?;
    warn_far_from_origin(py, &mesh.geometry.grid().vertices)?;
    mesh.warn_inexact(py, tolerance)?;
    Ok(mesh)
}
