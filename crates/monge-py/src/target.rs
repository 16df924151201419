//! The target of `approximate` as points, from what a designer has: an array,
//! a list of points, a file, a Rhino (RhinoCommon inside Rhino 8, or rhino3dm)
//! mesh, point cloud, surface or Brep, or a COMPAS mesh. Recognised by the
//! members the objects have (nothing is imported), in one place.

use std::path::PathBuf;

use glam::DVec3;
use monge_io::{read_points, surface_parameters};
use numpy::{PyArray1, PyArrayDyn, PyArrayMethods, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyList, PyTuple};

use crate::errors::{io_error, OptimiseError};

/// What `approximate` accepts, for its error messages.
const ACCEPTED: &str = "give the target as an array of shape (..., 3) or a list of points, a \
                        Rhino or rhino3dm Mesh, PointCloud, Surface or Brep, a COMPAS Mesh, or \
                        the path of a file `monge approximate` reads (OBJ, PLY, JSON, STL, \
                        points one a line: .xyz, .pts, .csv, .txt; IGES)";

/// `obj.X`, `obj.Y`, `obj.Z` (a RhinoCommon or rhino3dm `Point3d` or `Point3f`).
fn xyz(p: &Bound<'_, PyAny>) -> PyResult<DVec3> {
    Ok(DVec3::new(
        p.getattr("X")?.extract()?,
        p.getattr("Y")?.extract()?,
        p.getattr("Z")?.extract()?,
    ))
}

/// Every item of `points` (an iterable of Rhino points).
fn rhino_points(points: &Bound<'_, PyAny>) -> PyResult<Vec<DVec3>> {
    points.try_iter()?.map(|p| xyz(&p?)).collect()
}

/// Whether `obj` has the member `name`.
fn has(obj: &Bound<'_, PyAny>, name: &str) -> bool {
    obj.hasattr(name).unwrap_or(false)
}

/// Whether `obj` has the method `name`.
fn has_method(obj: &Bound<'_, PyAny>, name: &str) -> bool {
    obj.getattr(name).is_ok_and(|m| m.is_callable())
}

/// The items of a list, a tuple or a Rhino collection (`Count`: a `Point3dList`, a
/// .NET list in Grasshopper) whose first item is a Rhino point (`X`); None otherwise.
fn point_items<'py>(target: &Bound<'py, PyAny>) -> PyResult<Option<Vec<Bound<'py, PyAny>>>> {
    let collection = target.is_instance_of::<PyList>()
        || target.is_instance_of::<PyTuple>()
        || has(target, "Count");
    let Some(items) = collection.then(|| target.try_iter()).and_then(Result::ok) else {
        return Ok(None);
    };
    let items: Vec<_> = items.collect::<PyResult<_>>()?;
    Ok(items.first().is_some_and(|p| has(p, "X")).then_some(items))
}

/// A Rhino surface's parameter range in `direction` (0: u, 1: v).
fn domain(surface: &Bound<'_, PyAny>, direction: i32) -> PyResult<[f64; 2]> {
    let d = surface.call_method1("Domain", (direction,))?;
    Ok([d.getattr("T0")?.extract()?, d.getattr("T1")?.extract()?])
}

/// Points on Rhino surfaces (`Domain(direction)`, `PointAt(u, v)`), each on a grid of
/// its parameter range, as the command samples the surfaces of an IGES target.
fn surface_points(surfaces: &[Bound<'_, PyAny>]) -> PyResult<Vec<DVec3>> {
    let mut points = Vec::new();
    for s in surfaces {
        for (u, v) in surface_parameters(surfaces.len(), domain(s, 0)?, domain(s, 1)?) {
            points.push(xyz(&s.call_method1("PointAt", (u, v))?)?);
        }
    }
    Ok(points)
}

/// `obj`'s type as `module.name`, for messages.
fn type_name(obj: &Bound<'_, PyAny>) -> String {
    let t = obj.get_type();
    let module = t.module().map(|m| m.to_string()).unwrap_or_default();
    let name = t.qualname().map(|n| n.to_string()).unwrap_or_default();
    if module.is_empty() || module == "builtins" {
        name
    } else {
        format!("{module}.{name}")
    }
}

/// The points of a Rhino object (RhinoCommon or rhino3dm): a Brep's faces and a
/// surface sampled on a grid of their parameters ([`surface_parameters`]: about
/// [`monge_io::IGES_TARGET_POINTS`] points, trims ignored, as for an IGES target), a
/// point cloud's points, a mesh's vertices (in double precision where it keeps them
/// so), a list of points; None for anything else.
fn rhino_geometry(target: &Bound<'_, PyAny>) -> PyResult<Option<Vec<DVec3>>> {
    let points = if has(target, "Faces") && has(target, "Surfaces") {
        let faces: Vec<_> = target
            .getattr("Faces")?
            .try_iter()?
            .collect::<PyResult<_>>()?;
        surface_points(&faces)?
    } else if has_method(target, "Domain") && has_method(target, "PointAt") {
        // A surface (a curve's `Domain` is a property, not a method).
        surface_points(std::slice::from_ref(target))?
    } else if has_method(target, "GetPoints") {
        rhino_points(&target.call_method0("GetPoints")?)?
    } else if let Some(vertices) = target
        .getattr("Vertices")
        .ok()
        .filter(|v| has_method(v, "ToPoint3dArray"))
    {
        rhino_points(&vertices.call_method0("ToPoint3dArray")?)?
    } else if let Some(items) = point_items(target)? {
        items.iter().map(xyz).collect::<PyResult<_>>()?
    } else {
        return Ok(None);
    };
    Ok(Some(points))
}

/// The points of a target (see the module's documentation); for a file, what `monge
/// approximate` reads; for a COMPAS mesh, its vertices. An array must have x, y, z
/// along its last axis.
pub fn points_of(target: &Bound<'_, PyAny>) -> PyResult<Vec<DVec3>> {
    let py = target.py();
    if let Ok(path) = target.extract::<PathBuf>() {
        return read_points(&path).map_err(io_error);
    }
    let not_a_target =
        || OptimiseError::new_err(format!("the target is a {}: {ACCEPTED}", type_name(target)));
    if target.is_none() {
        return Err(not_a_target());
    }
    if let Some(points) = rhino_geometry(target)? {
        return Ok(points);
    }
    let array_like = match has_method(target, "vertices_attributes") {
        true => target.call_method1("vertices_attributes", ("xyz",))?,
        false => target.clone(),
    };
    let array = py
        .import("numpy")?
        .call_method1("asarray", (&array_like, "float64"))
        .map_err(|e| match has(&array_like, "__len__") {
            true => OptimiseError::new_err(format!(
                "points must be numbers, an array of shape (..., 3): {}",
                e.value(py)
            )),
            false => not_a_target(),
        })?;
    // x, y, z along the last axis: any other shape is refused, never reshaped.
    let shape: Vec<usize> = array.getattr("shape")?.extract()?;
    if shape.last() != Some(&3) {
        let shape: Vec<String> = shape.iter().map(usize::to_string).collect();
        return Err(OptimiseError::new_err(format!(
            "points must be an array of shape (..., 3), x, y, z along the last axis; got shape \
             ({}{}): give the target's points as an (N, 3) array",
            shape.join(", "),
            if shape.len() == 1 { "," } else { "" }
        )));
    }
    let array: PyReadonlyArray2<f64> = array.call_method1("reshape", (-1, 3))?.extract()?;
    Ok(array
        .as_array()
        .rows()
        .into_iter()
        .map(|r| DVec3::new(r[0], r[1], r[2]))
        .collect())
}

/// The points `approximate` takes from `target`, as an array (N, 3): a
/// surface's or Brep's samples (about 4000 on a grid of each surface's
/// parameters, as the command samples IGES surfaces), a mesh's vertices, a
/// point cloud's points, a COMPAS mesh's vertices, a file's points (OBJ, PLY,
/// JSON, IGES), an array's points (x, y, z along its last axis).
#[pyfunction]
pub fn target_points<'py>(
    py: Python<'py>,
    target: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let points = points_of(target)?;
    points_array(py, &points, &[points.len()])
}

/// `points` copied into a numpy array of `shape` (whose product times 3 is the
/// number of coordinates; the last axis, 3, is appended).
pub(crate) fn points_array<'py>(
    py: Python<'py>,
    points: &[DVec3],
    shape: &[usize],
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let flat: Vec<f64> = points.iter().flat_map(|p| p.to_array()).collect();
    let mut dims = shape.to_vec();
    dims.push(3);
    PyArray1::from_vec(py, flat).reshape(dims)
}
