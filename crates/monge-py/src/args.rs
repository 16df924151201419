//! Arguments whose errors name the argument: pyo3 turns a negative int given
//! for a `usize` into a bare `OverflowError: can't convert negative int to
//! unsigned`, which says neither which argument nor what to give. Each
//! function here is a `from_py_with` extractor of one argument.

use monge_core::approximate::{PatchLayout, Tolerance, ToleranceError};
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

/// `approximate(patches=...)`: `"UxV"` or `"K"` as the command's `--patches`, an
/// int K (K × 1), or a pair (U, V); all parsed by [`PatchLayout`]'s own parser, so
/// that the messages are the command's.
pub fn patches(obj: &Bound<'_, PyAny>) -> PyResult<Option<PatchLayout>> {
    if obj.is_none() {
        return Ok(None);
    }
    let text = if let Ok(s) = obj.extract::<String>() {
        s
    } else if let Ok(k) = obj.extract::<i64>() {
        k.to_string()
    } else if let Ok((u, v)) = obj.extract::<(i64, i64)>() {
        format!("{u}x{v}")
    } else {
        return Err(OptimiseError::new_err(format!(
            "patches = {}: give \"UxV\" (e.g. \"2x3\"), K (K × 1) or (U, V), whole numbers of \
             patches along guide_u and guide_v",
            obj.repr()?
        )));
    };
    let repr = obj.repr()?;
    text.parse()
        .map(Some)
        .map_err(|e: String| OptimiseError::new_err(format!("patches = {repr}: {e}")))
}

/// `approximate(tolerance=...)`: a number relative to the target's size, or a
/// string as the command's `--tolerance` (`"5e-3"`, `"0.05m"`, `"5cm"`, `"50mm"`);
/// both parsed by [`Tolerance`]'s own parser (a number as its shortest decimal
/// text), so that the checks and messages are the command's.
pub fn tolerance(obj: &Bound<'_, PyAny>) -> PyResult<Option<Tolerance>> {
    if obj.is_none() {
        return Ok(None);
    }
    let text = if let Ok(s) = obj.extract::<String>() {
        s
    } else if let Ok(x) = obj.extract::<f64>() {
        x.to_string()
    } else {
        return Err(OptimiseError::new_err(format!(
            "tolerance = {}: give a number relative to the target's size (e.g. 5e-3) or a \
             length with its unit (e.g. \"0.05m\", \"5cm\", \"50mm\")",
            obj.repr()?
        )));
    };
    text.parse()
        .map(Some)
        .map_err(|e: ToleranceError| OptimiseError::new_err(format!("tolerance: {e}")))
}

/// `approximate(max_patches=N)`: at least 1.
pub fn max_patches(obj: &Bound<'_, PyAny>) -> PyResult<Option<usize>> {
    if obj.is_none() {
        return Ok(None);
    }
    let hint = "give a whole number of patches, at least 1 (default 6)";
    match whole(obj, "max_patches", hint, OptimiseError::new_err)? {
        0 => Err(OptimiseError::new_err(format!("max_patches = 0: {hint}"))),
        n => Ok(Some(n)),
    }
}
