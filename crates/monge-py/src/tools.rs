//! The other commands of `monge` as functions: `info`, `check`, `smooth`,
//! `fabricate`, `scan`, `fit`, `optimise_panels` (and `approximate`, in its own
//! module). Each calls monge-core as the
//! command does and returns plain Python data (dicts, lists, numpy arrays).

use std::path::PathBuf;

use glam::DVec3;
use monge_core::conical::conical_dual;
use monge_core::cyclidic::{CyclidicNet, CyclidicOptions, Family};
use monge_core::fabrication::{fabricate as core_fabricate, BaseMesh, FabricationOptions};
use monge_core::guide::Guide;
use monge_core::measure::measurable;
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
use crate::design::{json_to_python, parse_dict, parse_kind, Design};
use crate::errors::{
    generate_error, io_error, py_float, text, warn_far_from_origin, warn_inexact, FabricationError,
    MeshError, OptimiseError, ScanError, SmoothError,
};
use crate::mesh::{measurements, Geometry, Mesh};
use crate::target::points_array;

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
