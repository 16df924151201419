//! The mesh file of a generated design (§2.2, §2.3, §5.2): which mesh is
//! written (the circular mesh or its conical dual, at each offset) and the keys
//! `monge generate` adds to a JSON mesh. Shared by `monge generate`, the
//! explorer's server and the explorer in the browser (`monge-wasm`), so that a
//! mesh exported from any of them is the same file, byte for byte.

use std::borrow::Cow;

use glam::DVec3;
use monge_core::combescure::CombescureReport;
use monge_core::conical::{conical_dual, conical_folded_faces, conical_folds};
use monge_core::grid::{origin_ratio, rounding_explains, Folds, FAR_FROM_ORIGIN, ROUNDING_GAIN};
use monge_core::measure::{conical_error, measure};
use monge_core::offset::{face_offset, vertex_offset};
use monge_core::{Generated, MeshKind, Mode, QuadGrid};
use serde_json::{json, Map, Value};

/// `"characteristic"` (§3.1) or `"arbitrary"` (§3.2).
pub fn mode_name(mode: Mode) -> &'static str {
    match mode {
        Mode::Characteristic => "characteristic",
        Mode::Arbitrary => "arbitrary",
    }
}

/// `"circular"` (§2.2) or `"conical"` (§2.3).
pub fn kind_name(kind: MeshKind) -> &'static str {
    match kind {
        MeshKind::Circular => "circular",
        MeshKind::Conical => "conical",
    }
}

/// What every front end says when the coordinates lie so far from the origin,
/// compared with their size, that their rounding as f64 numbers can put the
/// mesh's error above 1e-9 of its size ([`origin_ratio`] above
/// [`FAR_FROM_ORIGIN`]); `None` otherwise. It suggests the base point
/// (`--base-point start`, Python `base_point="start"`).
///
/// ```
/// use glam::DVec3;
/// let near = [DVec3::ZERO, DVec3::ONE];
/// assert!(monge_io::generated::far_from_origin(&near).is_none());
/// let far = [DVec3::splat(1e10), DVec3::splat(1e10) + DVec3::ONE];
/// assert!(monge_io::generated::far_from_origin(&far).unwrap().contains("away from the origin"));
/// ```
pub fn far_from_origin(points: &[DVec3]) -> Option<String> {
    let ratio = origin_ratio(points);
    (ratio > FAR_FROM_ORIGIN).then(|| {
        format!(
            "the coordinates are up to {ratio:.1e} times the design's size away from the origin: \
             as f64 numbers they are rounded by up to {:.1e} of the size, which faces can amplify \
             up to {ROUNDING_GAIN} times, past 1e-9 of the size (beyond {FAR_FROM_ORIGIN:.1e} \
             times). Write the coordinates relative to a point near the design: \
             `--base-point start` (Python: `base_point=\"start\"`) computes and writes the mesh \
             relative to the guides' start point and records that point in the file; or model \
             the design near the origin and move it into place afterwards.",
            ratio * f64::EPSILON
        )
    })
}

/// The singular θ (§3.1): every Gauss circle passes through the corner normal.
pub const SINGULAR_DEG: f64 = 90.0;

/// Whether θ is the singular +90° (within 1°, as the generator's own hint has it).
///
/// ```
/// use monge_io::generated::near_singular;
/// assert!(near_singular(89.5) && !near_singular(-90.0));
/// ```
pub fn near_singular(theta_deg: f64) -> bool {
    (theta_deg - SINGULAR_DEG).abs() < 1.0
}

/// What every front end says when its own measurement of a mesh it wrote,
/// `max_error` (relative to the mesh's size, as `monge check` measures it),
/// exceeds `tolerance` (or is NaN), with the likely causes: `folded_faces`
/// (§5.2), coordinates far enough from the origin for their rounding to explain
/// the error ([`rounding_explains`]), θ near
/// the singular +90° ([`near_singular`]; `theta_deg` is `None` for a mesh
/// without one). `None` when the error is within the tolerance. `what` names
/// the mesh (e.g. "the mesh written to `out.obj`").
///
/// ```
/// use glam::DVec3;
/// use monge_io::generated::inexact;
/// let near = [DVec3::ZERO, DVec3::ONE];
/// assert!(inexact("the mesh", 3e-10, 1e-9, &near, 0, Some(30.0)).is_none());
/// let w = inexact("the mesh", 0.2, 1e-9, &near, 4, Some(30.0)).unwrap();
/// assert!(w.contains("error of 2.0e-1") && w.contains("4 folded faces"), "{w}");
/// let far = [DVec3::splat(1e7), DVec3::splat(1e7) + DVec3::ONE];
/// let w = inexact("the mesh", 3e-9, 1e-9, &far, 0, None).unwrap();
/// assert!(w.contains("--base-point start"), "{w}");
/// ```
pub fn inexact(
    what: &str,
    max_error: f64,
    tolerance: f64,
    points: &[DVec3],
    folded_faces: usize,
    theta_deg: Option<f64>,
) -> Option<String> {
    if max_error <= tolerance {
        return None;
    }
    let mut causes = Vec::new();
    if folded_faces > 0 {
        causes.push(format!(
            "its {folded_faces} folded faces (§5.2; change θ or the guides)"
        ));
    }
    let ratio = origin_ratio(points);
    if rounding_explains(ratio, max_error) {
        causes.push(format!(
            "its coordinates, {ratio:.1e} times its size away from the origin, where f64 numbers \
             round by {:.1e} of the size (write them relative to the guides' start: \
             `--base-point start`, Python `base_point=\"start\"`)",
            ratio * f64::EPSILON
        ));
    }
    if let Some(theta) = theta_deg.filter(|t| near_singular(*t)) {
        causes.push(format!(
            "θ = {theta}°, near the singular θ = +{SINGULAR_DEG}° (move θ away from it)"
        ));
    }
    let cause = if causes.is_empty() {
        "no known cause: no folded face, near the origin, θ away from +90°; please report the \
         design"
            .to_owned()
    } else {
        format!("likely cause: {}", causes.join("; "))
    };
    Some(format!(
        "{what} measures an error of {max_error:.1e} of its size, above the tolerance \
         {tolerance:.0e}: {cause}. `monge check` on it says where."
    ))
}

/// The largest error `monge check --kind KIND` measures on `grid` (§2.2,
/// §2.3): [`Measurements::max_error`](monge_core::measure::Measurements::max_error),
/// or `max_error_conical` for a conical mesh.
pub fn max_error(grid: &QuadGrid, kind: MeshKind) -> f64 {
    let m = measure(grid);
    match kind {
        MeshKind::Circular => m.max_error(),
        MeshKind::Conical => m.max_error_conical(conical_error(grid)),
    }
}

/// The Combescure report as JSON (§5.2): `folded_faces`, `first_fold`,
/// `min_crossing_sine`, `min_crossing_face`.
pub fn report_json(r: &CombescureReport) -> Value {
    json!({
        "folded_faces": r.folded_faces,
        "first_fold": r.first_fold.map(|(i, j)| [i, j]),
        "min_crossing_sine": r.min_crossing.sine,
        "min_crossing_face": [r.min_crossing.face.0, r.min_crossing.face.1],
    })
}

/// The keys of a JSON mesh that describe the generation: `theta_deg`, `mode`, `report`.
pub fn json_extras(g: &Generated) -> Map<String, Value> {
    let mut extra = Map::new();
    extra.insert("theta_deg".into(), json!(g.info.theta_deg));
    extra.insert("mode".into(), json!(mode_name(g.info.mode)));
    extra.insert("report".into(), report_json(&g.report));
    extra
}

/// The generation's report (§5.2) with the folded faces of the mesh written,
/// `folds`: an offset or a conical dual folds where the circular mesh need not.
pub fn with_folds(report: &CombescureReport, folds: &Folds) -> CombescureReport {
    CombescureReport {
        folded_faces: folds.count(),
        first_fold: folds.first(),
        ..*report
    }
}

/// One mesh to write: the design's mesh or one of its offsets (§2.2, §2.3).
#[derive(Clone, Debug)]
pub struct Layer<'a> {
    /// The offset distance (0 for the mesh itself).
    pub offset: f64,
    /// The mesh: borrowed for the circular mesh itself (no copy of a large
    /// grid), owned for an offset or a conical dual.
    pub grid: Cow<'a, QuadGrid>,
    /// Keys of the JSON output that describe this layer: `kind`, `offset`, and
    /// `face_normals` (the Gauss vertices) for a conical mesh.
    pub extra: Map<String, Value>,
    /// The face normals of a conical mesh (§2.3), `None` for a circular one.
    pub face_normals: Option<Vec<DVec3>>,
    /// What the JSON `report` says of this mesh (§5.2), [`layers`]: the
    /// generation's, with the folded faces of this mesh ([`Layer::folds`]) for
    /// an offset or a conical mesh. `None` without a generation (developable).
    pub report: Option<CombescureReport>,
}

impl<'a> Layer<'a> {
    /// The layer at distance `offset`, of `kind` (`circular`, `conical`,
    /// `developable`), with its face normals if any.
    pub fn new(
        offset: f64,
        grid: Cow<'a, QuadGrid>,
        kind: &str,
        face_normals: Option<&[DVec3]>,
    ) -> Layer<'a> {
        Layer {
            offset,
            extra: layer_extras(offset, kind, face_normals),
            face_normals: face_normals.map(<[DVec3]>::to_vec),
            report: None,
            grid,
        }
    }

    /// The folded faces of this mesh (§5.2): [`QuadGrid::folds`] of a circular
    /// mesh, [`conical_folds`] (about its face normals) of a conical one.
    pub fn folds(&self) -> Folds {
        match &self.face_normals {
            Some(n) => conical_folds(&self.grid, Some(n)),
            None => self.grid.folds(),
        }
    }

    /// Whether each face of this mesh is folded (§5.2), row-major: the faces
    /// [`Layer::folds`] counts.
    pub fn folded_faces(&self) -> Vec<bool> {
        match &self.face_normals {
            Some(n) => conical_folded_faces(&self.grid, Some(n)),
            None => self.grid.folded_faces(),
        }
    }
}

/// The keys of a JSON mesh that describe one layer: `kind`, `offset`, and
/// `face_normals` when given.
pub fn layer_extras(offset: f64, kind: &str, face_normals: Option<&[DVec3]>) -> Map<String, Value> {
    let mut extra = Map::new();
    extra.insert("kind".into(), json!(kind));
    extra.insert("offset".into(), json!(offset));
    if let Some(n) = face_normals {
        let n: Vec<[f64; 3]> = n.iter().map(|v| v.to_array()).collect();
        extra.insert("face_normals".into(), json!(n));
    }
    extra
}

/// The design's mesh of `kind` at distance 0, then at each of `offsets`: node
/// offsets of the circular mesh (§2.2), or face offsets of its conical dual
/// (§2.3; the circular mesh has at least 3 × 3 vertices, as every curved guide
/// has at least 3 samples). An offset's JSON `report` counts the folds of the
/// offset itself (an offset through a focal surface folds where the mesh does
/// not), and a conical mesh's those of the conical mesh ([`conical_folds`]:
/// its faces may turn over where the circular mesh does not); the crossing
/// sine is the generation's, whose normals they share.
pub fn layers<'a>(g: &'a Generated, kind: MeshKind, offsets: &[f64]) -> Vec<Layer<'a>> {
    let distances = std::iter::once(0.0).chain(offsets.iter().copied());
    let layers: Vec<Layer<'a>> = match kind {
        MeshKind::Circular => distances
            .map(|d| Layer::new(d, node_offset(&g.grid, d), kind_name(kind), None))
            .collect(),
        MeshKind::Conical => {
            let conical = conical_dual(&g.grid);
            distances
                .map(|d| {
                    let o = face_offset(&conical, d);
                    Layer::new(
                        d,
                        Cow::Owned(o.grid),
                        kind_name(kind),
                        Some(&conical.face_normals),
                    )
                })
                .collect()
        }
    };
    layers
        .into_iter()
        .map(|mut layer| {
            let report = if layer.offset != 0.0 || kind == MeshKind::Conical {
                let report = with_folds(&g.report, &layer.folds());
                layer.extra.insert("report".into(), report_json(&report));
                report
            } else {
                g.report
            };
            layer.report = Some(report);
            layer
        })
        .collect()
}

/// The node offset of `grid` at distance `d` (§2.2): the grid itself, borrowed,
/// at 0.
pub fn node_offset(grid: &QuadGrid, d: f64) -> Cow<'_, QuadGrid> {
    if d == 0.0 {
        Cow::Borrowed(grid)
    } else {
        Cow::Owned(vertex_offset(grid, d))
    }
}

/// The explorer's metrics of a mesh of `kind` (§2.2, §2.3): [`measure`], plus
/// `conical` (the conical error of a conical mesh, whose `folded_faces` and
/// `first_fold` are [`conical_folds`] as `monge check --kind conical` finds
/// them), `max_error`, `faces`, `panel_area` and `edge_length` (`min`, `max`).
pub fn metrics_json(mesh: &QuadGrid, kind: MeshKind) -> Value {
    let measured = measure(mesh);
    let mut metrics = serde_json::to_value(&measured).unwrap_or(Value::Null);
    let m = &mut metrics;
    m["max_error"] = json!(measured.max_error());
    if kind == MeshKind::Conical {
        let conical = conical_error(mesh);
        m["max_error"] = json!(measured.max_error_conical(conical));
        m["conical"] = json!(conical);
        let folds = conical_folds(mesh, None);
        m["folded_faces"] = json!(folds.count());
        m["first_fold"] = json!(folds.first());
    }
    m["faces"] = json!(mesh.face_count());
    let (area, edge) = panel_stats(mesh);
    m["panel_area"] = json!({ "min": area.0, "max": area.1 });
    m["edge_length"] = json!({ "min": edge.0, "max": edge.1 });
    metrics
}

/// Smallest and largest panel area ([`QuadGrid::face_area`]) and edge length
/// of a grid; zeros for an empty grid.
fn panel_stats(grid: &QuadGrid) -> ((f64, f64), (f64, f64)) {
    let extend = |(lo, hi): (f64, f64), x: f64| (lo.min(x), hi.max(x));
    let empty = (f64::INFINITY, f64::NEG_INFINITY);
    let (mut area, mut edge) = (empty, empty);
    for i in 0..grid.rows {
        for j in 0..grid.cols {
            let p = grid.vertex(i, j);
            if j + 1 < grid.cols {
                edge = extend(edge, p.distance(grid.vertex(i, j + 1)));
            }
            if i + 1 < grid.rows {
                edge = extend(edge, p.distance(grid.vertex(i + 1, j)));
            }
            if i + 1 < grid.rows && j + 1 < grid.cols {
                area = extend(area, grid.face_area(i, j));
            }
        }
    }
    let finite = |(lo, hi): (f64, f64)| if lo <= hi { (lo, hi) } else { (0.0, 0.0) };
    (finite(area), finite(edge))
}

#[cfg(test)]
mod tests {
    use super::*;
    use monge_core::combescure::ParallelLines;

    fn report(folded_faces: usize, sine: f64) -> CombescureReport {
        CombescureReport {
            min_crossing: ParallelLines {
                face: (3, 4),
                sine,
                zero_edge: false,
            },
            folded_faces,
            first_fold: (folded_faces > 0).then_some((5, 6)),
        }
    }

    #[test]
    fn report_json_names_every_field() {
        let v = report_json(&report(2, 0.25));
        assert_eq!(v["folded_faces"], 2);
        assert_eq!(v["first_fold"], json!([5, 6]));
        assert_eq!(v["min_crossing_sine"], 0.25);
        assert_eq!(v["min_crossing_face"], json!([3, 4]));
        assert_eq!(report_json(&report(0, 1.0))["first_fold"], Value::Null);
    }

    #[test]
    fn panel_stats_of_a_unit_square_grid() {
        let v = vec![DVec3::ZERO, DVec3::Y, DVec3::X, DVec3::X + DVec3::Y];
        let (area, edge) = panel_stats(&QuadGrid::new(2, 2, v, vec![]));
        assert_eq!(area, (1.0, 1.0));
        assert_eq!(edge, (1.0, 1.0));
    }
}
