//! Arguments whose errors name the argument: pyo3 turns a negative int given
//! for a `usize` into a bare `OverflowError: can't convert negative int to
//! unsigned`, which says neither which argument nor what to give. Each
//! function here is a `from_py_with` extractor of one argument.

use monge_core::BasePoint;
use pyo3::prelude::*;

use crate::errors::{DesignError, OptimiseError, SmoothError};

/// `obj` as a whole number ≥ 0. An integer (a Python int, or anything with
/// `__index__`, as numpy's) that is negative or too large raises `error` with
/// `name = value: hint`; anything else pyo3's `TypeError`, which pyo3 prefixes
/// with the argument's name.
fn whole(
    obj: &Bound<'_, PyAny>,
    name: &str,
    hint: &str,
    error: fn(String) -> PyErr,
) -> PyResult<usize> {
    obj.extract::<usize>().or_else(|e| {
        match obj.py().import("operator")?.call_method1("index", (obj,)) {
            Ok(int) => Err(error(format!("{name} = {int}: {hint}"))),
            Err(_) => Err(e),
        }
    })
}

/// `smooth(samples=K)`.
pub fn samples(obj: &Bound<'_, PyAny>) -> PyResult<usize> {
    whole(
        obj,
        "samples",
        "give K in 2..=1000 (K × K points a patch)",
        SmoothError::new_err,
    )
}

/// `approximate(starts=N)`.
pub fn starts(obj: &Bound<'_, PyAny>) -> PyResult<usize> {
    whole(
        obj,
        "starts",
        "give a whole number of starts (default 4)",
        OptimiseError::new_err,
    )
}

/// `approximate(max_evaluations=N)`.
pub fn approximate_evaluations(obj: &Bound<'_, PyAny>) -> PyResult<usize> {
    whole(
        obj,
        "max_evaluations",
        "give a whole number of mesh generations for each optimiser run (default 1500)",
        OptimiseError::new_err,
    )
}

/// `optimise_panels(max_evaluations=N or None)`.
pub fn panel_evaluations(obj: &Bound<'_, PyAny>) -> PyResult<Option<usize>> {
    if obj.is_none() {
        return Ok(None);
    }
    whole(
        obj,
        "max_evaluations",
        "give a whole number of evaluations, or None for the optimiser's own budget",
        OptimiseError::new_err,
    )
    .map(Some)
}

/// `generate(max_vertices=N)`.
pub fn max_vertices(obj: &Bound<'_, PyAny>) -> PyResult<usize> {
    whole(
        obj,
        "max_vertices",
        "give a whole number of vertices (default 25000000)",
        DesignError::new_err,
    )
}

/// `generate(base_point=…)`: `"start"` (the guides' common start point), a
/// point `(x, y, z)` of three finite numbers, or None (absolute coordinates).
pub fn base_point(obj: &Bound<'_, PyAny>) -> PyResult<Option<BasePoint>> {
    if obj.is_none() {
        return Ok(None);
    }
    let refuse = || {
        let repr = obj.repr().map(|r| r.to_string()).unwrap_or_default();
        DesignError::new_err(format!(
            "base_point = {repr}: give \"start\" (the guides' common start point) or a point \
             (x, y, z) of three finite numbers"
        ))
    };
    if let Ok(s) = obj.extract::<String>() {
        return (s == "start")
            .then_some(Some(BasePoint::Start))
            .ok_or_else(refuse);
    }
    match obj.extract::<[f64; 3]>() {
        Ok(p) if p.iter().all(|x| x.is_finite()) => Ok(Some(BasePoint::At(p))),
        _ => Err(refuse()),
    }
}

/// `approximate(grid=(U, V))`: faces along guide_u and guide_v.
pub fn grid(obj: &Bound<'_, PyAny>) -> PyResult<(usize, usize)> {
    let (u, v): (Bound<'_, PyAny>, Bound<'_, PyAny>) = obj.extract()?;
    let hint = "give (faces along guide_u, faces along guide_v), whole numbers, e.g. (40, 40)";
    let repr = obj.repr()?.to_string();
    let refuse = |_| OptimiseError::new_err(format!("grid = {repr}: {hint}"));
    let whole = |x: &Bound<'_, PyAny>| whole(x, "grid", hint, OptimiseError::new_err);
    match (whole(&u), whole(&v)) {
        (Ok(u), Ok(v)) => Ok((u, v)),
        (Err(e), _) | (_, Err(e)) if e.is_instance_of::<OptimiseError>(obj.py()) => Err(refuse(e)),
        (Err(e), _) | (_, Err(e)) => Err(e),
    }
}
