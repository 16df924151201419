//! The other commands of `monge` as functions: `info`, `check`, `smooth`,
//! `fabricate`, `scan`, `fit`, `optimise_panels`, `approximate`. Each calls monge-core as the
//! command does and returns plain Python data (dicts, lists, numpy arrays).

use std::path::PathBuf;

use glam::DVec3;
use monge_core::approximate::{
    approximate as core_approximate, approximate_patches, approximate_to_tolerance, deadline_after,
    fit_report, ApproxOptions, Approximation, Chosen, Deviation, FitDesign, FitReport,
    PatchApproximation, PatchLayout, Stop, TargetCloud, Tolerance, ToleranceFit, ToleranceOptions,
};
use monge_core::conical::conical_dual;
use monge_core::cyclidic::{CyclidicNet, CyclidicOptions, Family};
use monge_core::fabrication::{
    fabricate as core_fabricate, BaseMesh, FabricationOptions, DESIGN_ANGLE_TOL_DEG,
};
use monge_core::guide::Guide;
use monge_core::measure::measurable;
use monge_core::multipatch::{build, MultiPatchDesign};
use monge_core::optimise::fit as core_fit;
use monge_core::panels::{optimise_panels as core_optimise_panels, PanelOptions};
use monge_core::scan::scan as core_scan;
use monge_core::{generate, inspect, GenerateOptions, MeshKind, Mode, QuadGrid};
use monge_io::{
    conical_has_no_net, parse_multipatch, read_mesh_and_kind, read_multipatch, write_schedule_json,
    DesignFormat, ScheduleJson,
};
use numpy::ndarray::IxDyn;
use numpy::{PyArray1, PyArrayDyn, PyArrayMethods, PyReadonlyArray3, PyUntypedArrayMethods};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList, PyString};
use pythonize::pythonize;

use crate::args;
use crate::design::{json_to_python, kind_name, parse_dict, parse_kind, Design, PatchesDesign};
use crate::errors::{
    generate_error, io_error, py_float, text, warn_far_from_origin, warn_inexact, FabricationError,
    MeshError, OptimiseError, ScanError, SmoothError,
};
use crate::mesh::{faces_array, measurements, Geometry, Mesh};
use crate::target::{points_array, points_of};

/// `"characteristic"` (§3.1) or `"arbitrary"` (§3.2).
fn mode_name(mode: Mode) -> &'static str {
    match mode {
        Mode::Characteristic => "characteristic",
        Mode::Arbitrary => "arbitrary",
    }
}

/// One validated guide (§3) as a dict.
fn guide_dict<'py>(py: Python<'py>, g: &Guide) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("samples", points_array(py, &g.points, &[g.points.len()])?)?;
    d.set_item("start_tangent", g.tangent.to_array())?;
    d.set_item("plane_normal", g.plane_normal.to_array())?;
    d.set_item("planarity", g.planarity)?;
    d.set_item("size", g.size)?;
    Ok(d)
}

/// Validates a design without generating it (§3.1, §3.2), as `monge info`: the
/// mode, θ and its admissible range, the grid size, and each guide's samples,
/// start tangent, plane normal, planarity and size. Warns
/// (`FarFromOriginWarning`) as the command does when the guides lie far from
/// the origin compared with their size.
#[pyfunction]
pub fn info<'py>(py: Python<'py>, design: &Design) -> PyResult<Bound<'py, PyDict>> {
    let i = inspect(&design.inner, &GenerateOptions::default())
        .map_err(|e| generate_error(design.context(), &e))?;
    let (rows, cols) = i.grid_size();
    let d = PyDict::new(py);
    d.set_item("mode", mode_name(i.mode))?;
    d.set_item("theta_deg", i.theta_deg)?;
    d.set_item("theta_admissible", i.theta_range.contains(i.theta_deg))?;
    d.set_item("theta_abs_min_deg", i.theta_range.min_deg)?;
    d.set_item("theta_abs_max_deg", i.theta_range.max_deg)?;
    d.set_item("rows", rows)?;
    d.set_item("cols", cols)?;
    d.set_item("faces", (rows - 1) * (cols - 1))?;
    d.set_item("guide_u", guide_dict(py, &i.guide_u)?)?;
    d.set_item("guide_v", guide_dict(py, &i.guide_v)?)?;
    warn_far_from_origin(
        py,
        &[i.guide_u.points.as_slice(), &i.guide_v.points].concat(),
    )?;
    Ok(d)
}

/// `(rows, cols, 3)` array-like data as points, refusing other shapes and non-finite values.
fn grid_points(array: &Bound<'_, PyAny>, what: &str) -> PyResult<(usize, usize, Vec<DVec3>)> {
    let numpy = array.py().import("numpy")?;
    let array = numpy.call_method1("asarray", (array, "float64"))?;
    let array: PyReadonlyArray3<f64> = array.extract().map_err(|_| {
        MeshError::new_err(format!(
            "{what} must have shape (rows, cols, 3), got {}",
            array
                .getattr("shape")
                .map_or_else(|_| "no shape".to_owned(), |s| s.to_string())
        ))
    })?;
    let shape = array.shape();
    let (rows, cols) = (shape[0], shape[1]);
    if shape[2] != 3 {
        return Err(MeshError::new_err(format!(
            "{what} must have shape (rows, cols, 3), got ({rows}, {cols}, {})",
            shape[2]
        )));
    }
    let a = array.as_array();
    let mut points = Vec::with_capacity(rows * cols);
    for i in 0..rows {
        for j in 0..cols {
            let p = DVec3::new(a[[i, j, 0]], a[[i, j, 1]], a[[i, j, 2]]);
            if !p.is_finite() {
                return Err(MeshError::new_err(format!(
                    "{what}[{i}, {j}] = {p} is not finite"
                )));
            }
            points.push(p);
        }
    }
    Ok((rows, cols, points))
}

/// The quad grid of a `Mesh`, a mesh file (OBJ, PLY or JSON), or arrays.
fn grid_of(
    vertices: &Bound<'_, PyAny>,
    normals: Option<&Bound<'_, PyAny>>,
) -> PyResult<(QuadGrid, Option<MeshKind>)> {
    if let Ok(mesh) = vertices.cast::<Mesh>() {
        let kind = match mesh.get().geometry {
            Geometry::Conical(_) => MeshKind::Conical,
            _ => MeshKind::Circular,
        };
        return Ok((mesh.get().geometry.grid().clone(), Some(kind)));
    }
    if let Ok(path) = vertices.extract::<PathBuf>() {
        return read_mesh_and_kind(&path).map_err(io_error);
    }
    if let Some(n) = normals.filter(|n| n.is_instance_of::<PyString>()) {
        return Err(PyTypeError::new_err(format!(
            "check(vertices, normals, kind=...): normals is the string {}; give the kind by \
             name, kind={}",
            n.repr()?,
            n.repr()?
        )));
    }
    let (rows, cols, points) = grid_points(vertices, "vertices")?;
    let normals = match normals {
        Some(n) => {
            let (r, c, n) = grid_points(n, "normals")?;
            if (r, c) != (rows, cols) {
                return Err(MeshError::new_err(format!(
                    "normals have shape ({r}, {c}, 3) but vertices ({rows}, {cols}, 3)"
                )));
            }
            n
        }
        None => Vec::new(),
    };
    Ok((QuadGrid::new(rows, cols, points, normals), None))
}

/// Measures a quad mesh independently of how it was made (§2.2, §2.3), as
/// `monge check`: face planarity, circularity (or, for `kind="conical"`, the
/// conical condition at every vertex), row and column planarity, and with
/// normals torsion and normal length; each `{"value": v, "at": (i, j)}`,
/// lengths relative to the bounding-box diagonal `scale`; and `folded_faces`
/// (§5.2: crossed, non-convex or turned-over faces), `{"value": count, "at":
/// first folded face or None}`, which must be 0.
///
/// `vertices` is a `Mesh`, a mesh file path, or an array (rows, cols, 3), with
/// `normals` an array of the same shape (as `monge.compas.from_mesh` gives them:
/// `check(*from_mesh(c))`). `kind` is given by name; by default a `Mesh`'s own kind, the
/// `kind` a JSON mesh file names, else circular. Warns (`FarFromOriginWarning`) as the command does when the mesh lies far
/// from the origin compared with its size.
#[pyfunction]
#[pyo3(signature = (vertices, normals = None, *, kind = None))]
pub fn check<'py>(
    py: Python<'py>,
    vertices: &Bound<'py, PyAny>,
    normals: Option<&Bound<'py, PyAny>>,
    kind: Option<&str>,
) -> PyResult<Bound<'py, PyAny>> {
    let (grid, named) = grid_of(vertices, normals)?;
    let kind = parse_kind(kind, named.unwrap_or(MeshKind::Circular))?;
    measurable(&grid).map_err(|e| MeshError::new_err(e.to_string()))?;
    // A conical Mesh's folds about its face normals, as its report counts them.
    let mesh = vertices.cast::<Mesh>().ok();
    let face_normals = mesh.as_ref().and_then(|m| m.get().geometry.face_normals());
    let (m, max_error) = measurements(&grid, kind, face_normals);
    let d = pythonize(py, &m)?.cast_into::<PyDict>()?;
    if kind == MeshKind::Conical {
        let conical = d.get_item("circularity")?;
        d.del_item("circularity")?;
        d.set_item("conical", conical)?;
    }
    let folded = PyDict::new(py);
    folded.set_item("value", m.folded_faces)?;
    folded.set_item("at", m.first_fold)?;
    d.set_item("folded_faces", folded)?;
    d.del_item("first_fold")?;
    d.set_item("max_error", max_error)?;
    d.set_item("rows", grid.rows)?;
    d.set_item("cols", grid.cols)?;
    warn_far_from_origin(py, &grid.vertices)?;
    Ok(d.into_any())
}

/// The smooth C¹ surface (§4.4): the cyclidic net of Dupin cyclide patches on
/// the circular mesh of a design (or on a circular `Mesh`), as `monge smooth`,
/// which refuses a design that asks for a conical mesh (pass
/// `generate(design, kind="circular")` for its circular mesh's net).
///
/// Returns `patches`, an array (rows − 1, cols − 1, K, K, 3) of each patch
/// sampled on a K × K grid; `lines`, every curvature line as a chain of
/// circular arcs (`center`, `radius`, `normal`, `start`, `end`, `sweep_deg`);
/// and `nurbs`, the whole net as one exact degree-2 NURBS surface
/// (`control_points` (R, C, 3), `weights` (R, C), `knots_u`, `knots_v`).
///
/// `max_bytes` (default 8e9, 8 GB, as the command's `--max-output`) bounds the
/// memory the result takes: a net whose patches, arcs and NURBS surface would
/// take more (about 24 bytes a sample point, 1.2 kB an arc) is refused before
/// anything is built; lower `samples`, or raise `max_bytes`.
#[pyfunction]
#[pyo3(
    signature = (design, samples = 9, allow_folded = false, max_bytes = MAX_BYTES),
    text_signature = "(design, samples=9, allow_folded=False, max_bytes=8e9)"
)]
pub fn smooth<'py>(
    py: Python<'py>,
    design: &Bound<'py, PyAny>,
    #[pyo3(from_py_with = args::samples)] samples: usize,
    allow_folded: bool,
    max_bytes: f64,
) -> PyResult<Bound<'py, PyDict>> {
    if !(2..=1000).contains(&samples) {
        return Err(SmoothError::new_err(format!(
            "samples = {samples}: give K in 2..=1000 (K × K points a patch)"
        )));
    }
    let mesh = design.cast::<Mesh>().ok();
    let design = match mesh {
        Some(_) => None,
        None => Some(design.cast::<Design>()?.borrow()),
    };
    if let Some(d) = design
        .as_ref()
        .filter(|d| d.inner.mesh == MeshKind::Conical)
    {
        // The command's message, without a file name for a design made in Python.
        let message = conical_has_no_net(d.context().unwrap_or(""));
        return Err(SmoothError::new_err(format!(
            "{}; or keep it and pass its circular mesh, smooth(generate(design, \
             kind=\"circular\"))",
            message.trim_start_matches(": ")
        )));
    }
    // The size of the net, known before anything is built.
    let (rows, cols, coarser) = match (&mesh, &design) {
        (Some(m), _) => {
            let g = m.get().geometry.grid();
            (g.rows, g.cols, "pass a coarser mesh")
        }
        (None, Some(d)) => (
            d.inner.guide_u.sample_count(),
            d.inner.guide_v.sample_count(),
            "use fewer guide samples",
        ),
        (None, None) => unreachable!("either a Mesh or a Design"),
    };
    let (what, bytes) = smooth_memory(rows, cols, samples);
    check_memory(
        "smooth",
        bytes,
        max_bytes,
        &what,
        &format!("lower samples (K × K points a patch) or {coarser}"),
        SmoothError::new_err,
    )?;
    // A design's mesh, its θ and tolerance (a Mesh was measured when generated).
    let (grid, context, generated) =
        match (&mesh, &design) {
            (Some(m), _) => match &m.get().geometry {
                Geometry::Circular(g) => (g.clone(), None, None),
                Geometry::Conical(_) => return Err(SmoothError::new_err(
                    "a cyclidic net (§4.4) is built on a circular mesh with node axes, not on a \
                     conical mesh: pass the design, or generate(design, kind=\"circular\")",
                )),
            },
            (None, Some(d)) => {
                let inner = &d.inner;
                let g = py
                    .detach(|| generate(inner, &GenerateOptions::default()))
                    .map_err(|e| generate_error(d.context(), &e))?;
                let tolerance = inner.tolerance.unwrap_or_default().planarity;
                (
                    g.grid,
                    d.source.clone(),
                    Some((g.info.theta_deg, tolerance)),
                )
            }
            (None, None) => unreachable!("either a Mesh or a Design"),
        };
    let options = CyclidicOptions {
        allow_folded,
        ..CyclidicOptions::default()
    };
    let net = py
        .detach(|| CyclidicNet::from_normals(&grid, &options))
        .map_err(|e| {
            let context = context.map(|c| format!("{c}: the cyclidic net"));
            SmoothError::new_err(text(context.as_deref(), e))
        })?;
    if let Some((theta, tolerance)) = generated {
        // As `monge smooth`: the net is as exact as the mesh under it.
        warn_inexact(
            py,
            "the mesh under the net",
            (measurements(&grid, MeshKind::Circular, None).1, tolerance),
            &grid.vertices,
            net.folded().len(),
            Some(theta),
        )?;
    }
    // The patches written straight into the array returned (no copy of it held).
    let (fr, fc, k) = (net.rows() - 1, net.cols() - 1, samples);
    let patches = PyArrayDyn::<f64>::zeros(py, IxDyn(&[fr, fc, k, k, 3]), false);
    {
        let mut array = patches.readwrite();
        let out = array.as_slice_mut()?;
        py.detach(|| {
            for (p, chunk) in out.chunks_exact_mut(k * k * 3).enumerate() {
                let points = net.sample_patch(p / fc, p % fc, k);
                for (c, q) in chunk.chunks_exact_mut(3).zip(points) {
                    c.copy_from_slice(&q.to_array());
                }
            }
        });
    }
    let lines = PyList::empty(py);
    for line in net.curvature_lines_iter() {
        let arcs = PyList::empty(py);
        for a in &line.arcs {
            let arc = PyDict::new(py);
            arc.set_item("center", a.center.to_array())?;
            arc.set_item("radius", a.radius)?;
            arc.set_item("normal", a.normal.to_array())?;
            arc.set_item("start", a.start.to_array())?;
            arc.set_item("end", a.end.to_array())?;
            arc.set_item("sweep_deg", a.sweep().to_degrees())?;
            arcs.append(arc)?;
        }
        let l = PyDict::new(py);
        l.set_item(
            "family",
            match line.family {
                Family::U => "u",
                Family::V => "v",
            },
        )?;
        l.set_item("index", line.index)?;
        l.set_item("arcs", arcs)?;
        lines.append(l)?;
    }
    let s = net.nurbs();
    let nurbs = PyDict::new(py);
    nurbs.set_item("degree", monge_core::cyclidic::NURBS_DEGREE)?;
    nurbs.set_item(
        "control_points",
        points_array(py, &s.control_points, &[s.rows, s.cols])?,
    )?;
    nurbs.set_item(
        "weights",
        PyArray1::from_slice(py, &s.weights).reshape([s.rows, s.cols])?,
    )?;
    nurbs.set_item("knots_u", &s.knots_u)?;
    nurbs.set_item("knots_v", &s.knots_v)?;
    let d = PyDict::new(py);
    d.set_item("patches", patches)?;
    d.set_item("lines", lines)?;
    d.set_item("nurbs", nurbs)?;
    Ok(d)
}

/// Default of `max_bytes` of `smooth` and `fabricate`: 8 GB (10⁹ bytes), the
/// `monge` command's default `--max-output`.
const MAX_BYTES: f64 = 8e9;

/// Bytes of memory a Python arc dict of `smooth` takes (measured: 1.0–1.3 kB).
const SMOOTH_BYTES_PER_ARC: f64 = 1200.0;

/// Bytes of memory `fabricate` takes per face and layer (the panels', beams' and
/// layers' dicts, with the schedule's JSON text while it is parsed), and per face
/// of the base mesh (its nodes): measured (peak resident memory) on
/// examples/fig13-freeform.json made finer (120 × 120 faces: 11.4 kB a face with
/// one layer, 7.7 kB a face and layer with eight).
const FABRICATE_BYTES_PER_FACE_LAYER: f64 = 9_000.0;
const FABRICATE_BYTES_PER_FACE: f64 = 3_000.0;

/// What `smooth` returns for a net on a `rows × cols` mesh with `k × k` samples a
/// patch, and about how many bytes it takes: 24 bytes a sample point, the arcs
/// (at most one a mesh edge) as dicts, the NURBS surface's control points and
/// weights (32 bytes each), and the mesh and the net while they are built (about
/// 3 kB a vertex). Measured (peak resident memory) on examples/fig13-freeform.json
/// made finer (120 × 120 faces): 5.3 kB a face with 2 × 2 samples a patch, 43.6 kB
/// with 40 × 40 (of which 38.4 kB of patches).
fn smooth_memory(rows: usize, cols: usize, k: usize) -> (String, f64) {
    let (fr, fc) = (rows.saturating_sub(1), cols.saturating_sub(1));
    let arcs = rows * fc + cols * fr;
    let nurbs = (2 * rows).saturating_sub(1) * (2 * cols).saturating_sub(1);
    let bytes = 24.0 * (fr * fc) as f64 * (k * k) as f64
        + SMOOTH_BYTES_PER_ARC * arcs as f64
        + 32.0 * nurbs as f64
        + 3000.0 * (rows * cols) as f64;
    (
        format!("{fr} × {fc} patches of {k} × {k} points, {arcs} arcs and the NURBS surface"),
        bytes,
    )
}

/// `bytes` as `1.2 GB` or `345 MB` (10⁹ and 10⁶ bytes).
fn size_text(bytes: f64) -> String {
    if bytes >= 1e9 {
        format!("{:.1} GB", bytes / 1e9)
    } else {
        format!("{:.0} MB", bytes / 1e6)
    }
}

/// Refuses, before any work, a result of `function` estimated at `bytes` of
/// memory above `max_bytes`: `what` says what it holds, `lower` which argument
/// makes it smaller.
fn check_memory(
    function: &str,
    bytes: f64,
    max_bytes: f64,
    what: &str,
    lower: &str,
    error: fn(String) -> PyErr,
) -> PyResult<()> {
    if max_bytes.is_nan() || max_bytes <= 0.0 {
        return Err(error(format!(
            "max_bytes = {}: give a positive number of bytes (default {MAX_BYTES:e}, \
             8 GB; float(\"inf\") for no limit)",
            py_float(max_bytes)
        )));
    }
    if bytes > max_bytes {
        return Err(error(format!(
            "{function} would take about {} of memory ({what}), above max_bytes = {max_bytes:e} \
             ({}): {lower}, or raise max_bytes if the machine has the memory",
            size_text(bytes),
            size_text(max_bytes)
        )));
    }
    Ok(())
}

/// Everything a fabricator needs (§6), as `monge fabricate --full-json`: the contents of its
/// `schedule.json` (`summary`, `layers` (distances), `panels`, `beams`, `nodes`,
/// lists of dicts), and `layer_vertices`, each layer's vertices (rows, cols, 3):
/// node offsets of a circular mesh, face offsets of a conical one.
/// `radius_tol` defaults to `tol`; `angle_tol_deg` is in degrees.
///
/// `max_bytes` (default 8e9, 8 GB, as the command's `--max-output`) bounds the
/// memory the result takes (about 10 kB a face and layer): a result that would
/// take more is refused before anything is built; use fewer `layers` or fewer
/// guide samples, or raise `max_bytes`.
#[pyfunction]
#[pyo3(
    signature = (design, layers = vec![0.0], tol = 1e-9, radius_tol = None, angle_tol_deg = 1e-4, max_bytes = MAX_BYTES),
    text_signature = "(design, layers=[0.0], tol=1e-9, radius_tol=None, angle_tol_deg=1e-4, max_bytes=8e9)"
)]
pub fn fabricate<'py>(
    py: Python<'py>,
    design: &Design,
    layers: Vec<f64>,
    tol: f64,
    radius_tol: Option<f64>,
    angle_tol_deg: f64,
    max_bytes: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let context = design.context();
    // The size of the result, known before anything is built.
    let (fr, fc) = (
        design.inner.guide_u.sample_count().saturating_sub(1),
        design.inner.guide_v.sample_count().saturating_sub(1),
    );
    let faces = (fr * fc) as f64;
    check_memory(
        "fabricate",
        faces * (FABRICATE_BYTES_PER_FACE + FABRICATE_BYTES_PER_FACE_LAYER * layers.len() as f64),
        max_bytes,
        &format!(
            "the panels, beams and nodes of {fr} × {fc} faces and {} layer(s)",
            layers.len()
        ),
        "use fewer layers or fewer guide samples",
        FabricationError::new_err,
    )?;
    let options = FabricationOptions {
        layers,
        tol,
        radius_tol: radius_tol.unwrap_or(tol),
        angle_tol: angle_tol_deg.to_radians(),
    };
    let f = py.detach(|| {
        let grid = generate(&design.inner, &GenerateOptions::default())
            .map_err(|e| generate_error(context, &e))?
            .grid;
        let conical = (design.inner.mesh == MeshKind::Conical).then(|| conical_dual(&grid));
        let base = match &conical {
            Some(c) => BaseMesh::Conical(c),
            None => BaseMesh::Circular(&grid),
        };
        core_fabricate(base, &options).map_err(|e| FabricationError::new_err(text(context, e)))
    })?;
    let mut schedule = Vec::new();
    write_schedule_json(&f, ScheduleJson::Full, None, &mut schedule)
        .map_err(|e| FabricationError::new_err(format!("cannot write the schedule: {e}")))?;
    let meshes = PyList::empty(py);
    for layer in &f.layers {
        let g = &layer.grid;
        meshes.append(points_array(py, &g.vertices, &[g.rows, g.cols])?)?;
    }
    // Neither the fabrication nor a second copy of the text held while it is parsed.
    drop(f);
    let schedule = PyBytes::new(py, &std::mem::take(&mut schedule));
    let d = py
        .import("json")?
        .call_method1("loads", (schedule,))?
        .cast_into::<PyDict>()?;
    d.set_item("layer_vertices", meshes)?;
    Ok(d)
}

/// The design-space scan of §4.3 (Figure 14), as `monge scan`: the design
/// generated at every value of `param` (`"theta"`, or a path such as
/// `"guide_v.bspline.control_points[2][2]"`), in parallel on all cores with the
/// GIL released. Returns columns: `value`, `status` (fair, folded,
/// inadmissible, degenerate, invalid), `folded_faces`, `min_crossing_sine`,
/// `area_min`, `area_max`, `area_mean`, `area_variance`, `max_edge`,
/// `max_error` (NaN without a mesh), `error` (the generator's message or None).
#[pyfunction]
#[pyo3(signature = (design, values, param = "theta"))]
pub fn scan<'py>(
    py: Python<'py>,
    design: &Design,
    values: Vec<f64>,
    param: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let s = py
        .detach(|| {
            core_scan(
                &design.inner,
                param,
                &values,
                &GenerateOptions::default(),
                &|| {},
            )
        })
        .map_err(|e| ScanError::new_err(text(design.context(), e)))?;
    let column = |f: &dyn Fn(&monge_core::scan::ScanRow) -> f64| -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_iter(py, s.rows.iter().map(f))
    };
    let panel = |f: fn(&monge_core::scan::PanelStats) -> f64| {
        column(&move |r| r.panels.as_ref().map_or(f64::NAN, f))
    };
    let d = PyDict::new(py);
    d.set_item("parameter", &s.parameter)?;
    d.set_item("value", column(&|r| r.value))?;
    let status: Vec<&str> = s.rows.iter().map(|r| r.status.name()).collect();
    d.set_item("status", status)?;
    let folded: Vec<usize> = s.rows.iter().map(|r| r.folded_faces).collect();
    d.set_item("folded_faces", PyArray1::from_vec(py, folded))?;
    d.set_item("min_crossing_sine", column(&|r| r.min_crossing_sine))?;
    d.set_item("area_min", panel(|p| p.area_min))?;
    d.set_item("area_max", panel(|p| p.area_max))?;
    d.set_item("area_mean", panel(|p| p.area_mean))?;
    d.set_item("area_variance", panel(|p| p.area_variance))?;
    d.set_item("max_edge", panel(|p| p.max_edge))?;
    d.set_item("max_error", column(&|r| r.max_error))?;
    let errors: Vec<Option<&str>> = s.rows.iter().map(|r| r.error.as_deref()).collect();
    d.set_item("error", errors)?;
    Ok(d)
}

/// Panel-size optimisation (§4.8, Figure 22), as `monge optimise-panels`:
/// chooses where the `bspline` guides are sampled to make the panel areas as
/// even as possible. Returns the optimised `design` (a `Design`), panel
/// statistics `before` and `after`, its measured `max_error`, `folded_faces`,
/// BOBYQA's `evaluations` and `status`.
#[pyfunction]
#[pyo3(signature = (design, max_gap_ratio = 8.0, max_evaluations = None))]
pub fn optimise_panels<'py>(
    py: Python<'py>,
    design: &Design,
    max_gap_ratio: f64,
    #[pyo3(from_py_with = args::panel_evaluations)] max_evaluations: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    let options = PanelOptions {
        max_gap_ratio,
        max_evaluations,
    };
    let r = py
        .detach(|| core_optimise_panels(&design.inner, &GenerateOptions::default(), &options))
        .map_err(|e| OptimiseError::new_err(text(design.context(), e)))?;
    let d = PyDict::new(py);
    let optimised = Design {
        inner: r.design,
        source: None,
    };
    d.set_item("design", Bound::new(py, optimised)?)?;
    d.set_item("before", pythonize(py, &r.before)?)?;
    d.set_item("after", pythonize(py, &r.after)?)?;
    d.set_item("max_error", r.max_error)?;
    d.set_item("folded_faces", r.folded_faces)?;
    d.set_item("evaluations", r.evaluations)?;
    d.set_item("status", r.status)?;
    Ok(d)
}

/// Fits θ of chosen patches (and guide coordinates) of a multi-patch design
/// (§4.7) so that a patch boundary reaches a target, with BOBYQA, as `monge
/// fit`. `design` is a `.patches.json`/`.toml` path or a dict of that format.
/// Returns the fitted `design` (a dict of the format), the fitted mesh's
/// `vertices` and `normals` (rows, cols, 3), the distance to the target
/// `before` and `after`, the fitted `values` (name, start, end, bounds),
/// `evaluations` and `status`.
#[pyfunction]
pub fn fit<'py>(py: Python<'py>, design: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyDict>> {
    let (spec, context) = match design.extract::<PathBuf>() {
        Ok(path) => (
            read_multipatch(&path).map_err(io_error)?,
            Some(path.display().to_string()),
        ),
        Err(_) => (
            parse_dict(design, "fit", |text| {
                parse_multipatch(text, DesignFormat::Json)
            })?,
            None,
        ),
    };
    let r = py
        .detach(|| core_fit(&spec, &GenerateOptions::default()))
        .map_err(|e| OptimiseError::new_err(text(context.as_deref(), e)))?;
    let g = &r.mesh.grid;
    let values = PyList::empty(py);
    for (name, start, end, bounds) in &r.values {
        let v = PyDict::new(py);
        v.set_item("name", name)?;
        v.set_item("start", start)?;
        v.set_item("end", end)?;
        v.set_item("bounds", bounds.to_vec())?;
        values.append(v)?;
    }
    let d = PyDict::new(py);
    d.set_item("design", json_to_python(py, &r.design)?)?;
    d.set_item(
        "vertices",
        points_array(py, &g.vertices, &[g.rows, g.cols])?,
    )?;
    d.set_item("normals", points_array(py, &g.normals, &[g.rows, g.cols])?)?;
    d.set_item("before", pythonize(py, &r.before)?)?;
    d.set_item("after", pythonize(py, &r.after)?)?;
    d.set_item("values", values)?;
    d.set_item("evaluations", r.evaluations)?;
    d.set_item("status", r.status)?;
    Ok(d)
}

/// The design whose exact mesh is nearest to a target, as `monge approximate`
/// (monge's extension of the method). `target` is what a designer has: any
/// array of shape (..., 3) or list of points (a mesh's vertices or a point
/// cloud); a Rhino mesh, point cloud, surface or Brep (RhinoCommon inside Rhino
/// 8, or rhino3dm), a surface or Brep sampled at about 4000 points on a grid of
/// its parameters as the command samples IGES surfaces; a COMPAS mesh (its
/// vertices); or the path of a file the command reads (OBJ, PLY, JSON, IGES):
/// `target_points(target)` gives the points taken.
///
/// `patches` (`"2x3"`, `3` or `(2, 3)`, as `--patches`) then fits that many
/// patches with piecewise planar curvature lines (§4.7), kept if they follow the
/// target closer than one; `tolerance` (as `--tolerance`: a number relative to the
/// target's size, `5e-3`, or a length, `"0.05m"`, `"5cm"`, `"50mm"`) fits one
/// patch, then 2 × 1, 2 × 2, 3 × 2, … patches up to `max_patches` (default 6) until
/// the mesh is within it both ways.
///
/// Returns the `design` found (a `Design`, or a `PatchesDesign` of several patches:
/// `design.to_file(path)` writes it as the command does), the `initial` guess (a
/// `Design`), its `mesh` (a `Mesh`, for `monge.rhino.write_3dm`,
/// `monge.compas.to_mesh`, `monge.blender.add_mesh`; None for several patches), its
/// `kind`, `vertices` (rows, cols, 3), `normals` (its node axes, (rows, cols, 3);
/// None for `kind="conical"`, whose mesh is the conical dual, §2.3) and `faces`
/// (as `Mesh.faces`), `panels` (its number of faces), its `max_error` as `check`
/// measures it (each patch on its own grid: the exactness the command prints), the
/// deviation `before` and `after` (dicts of distances relative to the target's
/// `size`), `deviation` (`after` in model units) and `max_deviation` (the larger of
/// its two largest distances, model units), `patches` (how many), `theta_deg` (None
/// for several patches), `target_points`, `evaluations`, `starts` and `timed_out`.
///
/// With `patches`: `patch_fit`, the fit of the patches (`design`, `after`,
/// `per_patch`, `max_error`, `evaluations`, and `closer`, whether it is the
/// `design` returned). With `tolerance`, the command's report: `tolerance` (model
/// units) and `tolerance_relative`, `met`, `stop` (`"met"`, `"max_patches"`,
/// `"time_limit"` or `"refused"`) and `why` (None when met), `chosen`
/// (`"initial_guess"`, `"one_patch"` or `"patches"`), `steps`, each fit tried
/// (`patches`, its `deviation` or the `error` that kept it from being fitted);
/// `node_types`, nodes whose beam angles and angles to the node axis agree within
/// `node_angle_tol_deg` (`angle_tol_deg`, default 0.5°, a designer's fabrication
/// tolerance) being one type, as `fabricate(angle_tol_deg=...)` groups them; and
/// `per_patch`, each patch's `block`, `theta_deg`, `target_points` (the target
/// points nearest to it) and their `max` and `rms` distance to the mesh (relative).
#[pyfunction]
#[pyo3(
    signature = (target, grid = (40, 40), kind = "circular", starts = 4, max_evaluations = 1500, time_limit = None, keep_boundary = false, patches = None, tolerance = None, max_patches = None, angle_tol_deg = None),
    text_signature = "(target, grid=(40, 40), kind='circular', starts=4, max_evaluations=1500, time_limit=None, keep_boundary=False, patches=None, tolerance=None, max_patches=None, angle_tol_deg=None)"
)]
#[allow(clippy::too_many_arguments)]
pub fn approximate<'py>(
    py: Python<'py>,
    target: &Bound<'py, PyAny>,
    #[pyo3(from_py_with = args::grid)] grid: (usize, usize),
    kind: &str,
    #[pyo3(from_py_with = args::starts)] starts: usize,
    #[pyo3(from_py_with = args::approximate_evaluations)] max_evaluations: usize,
    time_limit: Option<f64>,
    keep_boundary: bool,
    #[pyo3(from_py_with = args::patches)] patches: Option<PatchLayout>,
    #[pyo3(from_py_with = args::tolerance)] tolerance: Option<Tolerance>,
    #[pyo3(from_py_with = args::max_patches)] max_patches: Option<usize>,
    angle_tol_deg: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    if patches.is_some() && tolerance.is_some() {
        return Err(OptimiseError::new_err(
            "patches and tolerance: give one (tolerance chooses the patches itself), as the \
             command's --patches and --tolerance",
        ));
    }
    if max_patches.is_some() && tolerance.is_none() {
        return Err(OptimiseError::new_err(
            "max_patches bounds the patches a tolerance fit tries: give tolerance too",
        ));
    }
    match angle_tol_deg {
        Some(a) if !(a.is_finite() && a >= 0.0) => {
            return Err(OptimiseError::new_err(format!(
                "angle_tol_deg = {}: give a finite, non-negative number of degrees (default \
                 {DESIGN_ANGLE_TOL_DEG})",
                py_float(a)
            )));
        }
        Some(_) if tolerance.is_none() => {
            return Err(OptimiseError::new_err(
                "angle_tol_deg groups the node types of a tolerance fit's report: give \
                 tolerance too",
            ));
        }
        _ => {}
    }
    let points = points_of(target)?;
    let deadline = match time_limit {
        Some(t) => {
            deadline_after(t).map_err(|e| OptimiseError::new_err(format!("time_limit: {e}")))?
        }
        None => None,
    };
    let kind = parse_kind(Some(kind), MeshKind::Circular)?;
    let options = ApproxOptions {
        faces: grid,
        kind,
        starts,
        max_evaluations,
        deadline,
        keep_boundary,
    };
    let error = |e: &dyn std::fmt::Display| OptimiseError::new_err(e.to_string());
    let fit = py.detach(|| -> PyResult<Fit> {
        if let Some(tolerance) = tolerance {
            let options = ToleranceOptions {
                tolerance,
                max_patches: max_patches.unwrap_or(ToleranceOptions::default().max_patches),
                approx: options,
            };
            let fit =
                approximate_to_tolerance(&points, &options, &mut |_| {}).map_err(|e| error(&e))?;
            return Ok(Fit::Tolerance(Box::new(fit)));
        }
        let single = core_approximate(&points, &options, &mut |_| {}).map_err(|e| error(&e))?;
        Ok(match patches {
            Some(layout) => {
                let p = approximate_patches(&points, &single, layout, &options, &mut |_| {})
                    .map_err(|e| error(&e))?;
                Fit::Patches(Box::new((single, p)))
            }
            None => Fit::Single(Box::new(single)),
        })
    })?;
    let (single, design, mesh_grid, after) = fit.kept();
    let (report, max_error) = py.detach(|| -> PyResult<(Option<FitReport>, f64)> {
        // The report of a tolerance fit, as the command prints it.
        let report = match &fit {
            Fit::Tolerance(_) => {
                let cloud = TargetCloud::new(&points).map_err(|e| error(&e))?;
                let angle_tol = angle_tol_deg.unwrap_or(DESIGN_ANGLE_TOL_DEG).to_radians();
                Some(fit_report(&cloud, &design, angle_tol).map_err(|e| error(&e))?)
            }
            _ => None,
        };
        let max_error = match &design {
            FitDesign::Single(_) => measurements(mesh_grid, kind, None).1,
            FitDesign::Patches(d) => patches_max_error(d)?,
        };
        Ok((report, max_error))
    })?;
    let d = PyDict::new(py);
    let g = mesh_grid;
    d.set_item(
        "vertices",
        points_array(py, &g.vertices, &[g.rows, g.cols])?,
    )?;
    // A conical mesh has face normals, not node axes (§2.3).
    let normals = match kind {
        MeshKind::Circular => Some(points_array(py, &g.normals, &[g.rows, g.cols])?),
        MeshKind::Conical => None,
    };
    d.set_item("normals", normals)?;
    d.set_item("faces", faces_array(py, g)?)?;
    d.set_item("kind", kind_name(kind))?;
    d.set_item("panels", g.face_count())?;
    d.set_item("max_error", max_error)?;
    d.set_item("before", pythonize(py, &single.before)?)?;
    d.set_item("after", pythonize(py, &after)?)?;
    d.set_item("deviation", model_units(py, &after)?)?;
    d.set_item("max_deviation", after.max() * after.size)?;
    d.set_item("patches", design.patches())?;
    d.set_item("target_points", points.len())?;
    d.set_item("starts", single.starts)?;
    d.set_item("initial", Bound::new(py, plain(single.initial.clone()))?)?;
    match &design {
        FitDesign::Single(inner) => {
            let found = plain(inner.clone());
            // The mesh as `generate` makes it: the same vertices as the grid, with its report.
            let mesh =
                py.detach(|| Mesh::generate(&found, kind, &GenerateOptions::default(), None))?;
            d.set_item("theta_deg", found.inner.theta_deg)?;
            d.set_item("design", Bound::new(py, found)?)?;
            d.set_item("mesh", Bound::new(py, mesh)?)?;
        }
        FitDesign::Patches(inner) => {
            d.set_item("theta_deg", py.None())?;
            d.set_item(
                "design",
                Bound::new(
                    py,
                    PatchesDesign {
                        inner: inner.clone(),
                    },
                )?,
            )?;
            d.set_item("mesh", py.None())?;
        }
    }
    match &fit {
        Fit::Single(r) => {
            d.set_item("evaluations", r.evaluations)?;
            d.set_item("timed_out", r.timed_out)?;
        }
        Fit::Patches(b) => {
            let (r, p) = &**b;
            d.set_item("evaluations", r.evaluations)?;
            d.set_item("timed_out", r.timed_out)?;
            let pf = PyDict::new(py);
            pf.set_item(
                "design",
                Bound::new(
                    py,
                    PatchesDesign {
                        inner: p.design.clone(),
                    },
                )?,
            )?;
            pf.set_item("after", pythonize(py, &p.after)?)?;
            pf.set_item("per_patch", pythonize(py, &p.per_patch)?)?;
            pf.set_item("max_error", py.detach(|| patches_max_error(&p.design))?)?;
            pf.set_item("evaluations", p.evaluations)?;
            pf.set_item("closer", patches_closer(p, r))?;
            d.set_item("patch_fit", pf)?;
        }
        Fit::Tolerance(f) => {
            d.set_item("evaluations", f.evaluations)?;
            d.set_item("timed_out", f.stop == Stop::TimeLimit)?;
            tolerance_items(py, &d, f)?;
            if let Some(report) = &report {
                d.set_item("node_types", report.node_types)?;
                d.set_item("node_angle_tol_deg", report.node_angle_tol.to_degrees())?;
                d.set_item("per_patch", pythonize(py, &report.per_patch)?)?;
            }
        }
    }
    Ok(d)
}

/// What `approximate` found: one patch; one patch and the fit of patches
/// (`patches=`); or a tolerance fit (`tolerance=`).
enum Fit {
    Single(Box<Approximation>),
    Patches(Box<(Approximation, PatchApproximation)>),
    Tolerance(Box<ToleranceFit>),
}

impl Fit {
    /// The one-patch fit, and the design kept, its mesh and deviation: the fit of
    /// patches when it follows the target closer, as the command keeps it.
    fn kept(&self) -> (&Approximation, FitDesign, &QuadGrid, Deviation) {
        match self {
            Fit::Single(r) => (r, FitDesign::Single(r.design.clone()), &r.grid, r.after),
            Fit::Patches(b) => {
                let (r, p) = &**b;
                if patches_closer(p, r) {
                    (r, FitDesign::Patches(p.design.clone()), &p.grid, p.after)
                } else {
                    (r, FitDesign::Single(r.design.clone()), &r.grid, r.after)
                }
            }
            Fit::Tolerance(f) => (&f.single, f.design.clone(), &f.grid, f.deviation),
        }
    }
}

/// Whether the fit of patches follows the target closer than the single patch, as
/// `monge approximate --patches` decides: the mesh's vertices to the target and the
/// target beyond the mesh (the search's objective), both RMS.
fn patches_closer(patches: &PatchApproximation, single: &Approximation) -> bool {
    let objective = |d: &Deviation| d.mesh_to_target_rms.powi(2) + d.beyond_mesh_rms.powi(2);
    objective(&patches.after) < objective(&single.after)
}

/// The exactness of a multi-patch design: each patch measured on its own grid.
fn patches_max_error(design: &MultiPatchDesign) -> PyResult<f64> {
    let mp = build(design, &GenerateOptions::default())
        .map_err(|e| OptimiseError::new_err(format!("the multi-patch design found: {e}")))?;
    Ok(mp.max_error())
}

/// A design made in Python (no file).
fn plain(inner: monge_core::Design) -> Design {
    Design {
        inner,
        source: None,
    }
}

/// The items of a tolerance fit's report: the tolerance, whether it is met and why
/// not, which design was kept, and every fit tried.
fn tolerance_items(py: Python<'_>, d: &Bound<'_, PyDict>, fit: &ToleranceFit) -> PyResult<()> {
    let size = fit.deviation.size;
    d.set_item("tolerance", fit.limit * size)?;
    d.set_item("tolerance_relative", fit.limit)?;
    d.set_item("met", fit.met())?;
    let (stop, why) = match &fit.stop {
        Stop::Met => ("met", None),
        Stop::MaxPatches(n) => (
            "max_patches",
            Some(format!(
                "{n} patch{} tried (max_patches={n}); allow more patches, give a finer grid or \
                 a larger tolerance",
                if *n == 1 { "" } else { "es" }
            )),
        ),
        Stop::TimeLimit => (
            "time_limit",
            Some("the time limit ended the search (time_limit); give more time".to_owned()),
        ),
        Stop::Refused { patches, error } => (
            "refused",
            Some(format!("{patches} patches cannot be fitted: {error}")),
        ),
    };
    d.set_item("stop", stop)?;
    d.set_item("why", if fit.met() { None } else { why })?;
    d.set_item(
        "chosen",
        match fit.chosen {
            Chosen::InitialGuess => "initial_guess",
            Chosen::OnePatch => "one_patch",
            Chosen::Patches(_) => "patches",
        },
    )?;
    let steps = PyList::empty(py);
    for step in &fit.steps {
        let s = PyDict::new(py);
        s.set_item("patches", step.patches)?;
        match &step.outcome {
            Ok(deviation) => {
                s.set_item("deviation", pythonize(py, deviation)?)?;
                s.set_item("error", py.None())?;
            }
            Err(e) => {
                s.set_item("deviation", py.None())?;
                s.set_item("error", e.to_string())?;
            }
        }
        steps.append(s)?;
    }
    d.set_item("steps", steps)?;
    Ok(())
}

/// The distances of `deviation` in model units: each relative distance times the
/// target's size (`size` itself as it is).
fn model_units<'py>(py: Python<'py>, deviation: &Deviation) -> PyResult<Bound<'py, PyDict>> {
    let d = pythonize(py, deviation)?.cast_into::<PyDict>()?;
    let items: Vec<_> = d.iter().collect();
    for (key, value) in items {
        if key.extract::<String>()? != "size" {
            d.set_item(&key, value.extract::<f64>()? * deviation.size)?;
        }
    }
    Ok(d)
}
