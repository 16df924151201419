//! Design-space scans (§4.3, Figure 14; §5.2): sweep θ, or any numeric parameter
//! of a design addressed by a path such as `guide_v.bspline.control_points[2][2]`,
//! over a range of values, generate the mesh at each value and report what a
//! designer needs to choose one: admissibility (§3.2), the generator's error if
//! any, folded faces (pinching and self-intersection, §5.2), the spread of panel
//! areas, the longest edge and the measured exactness.
//!
//! The values are evaluated in parallel (rayon, with the `parallel` feature), each independently of the
//! others, and collected in order: the result does not depend on the number of
//! threads. The scan is data only: `monge_io` writes it as a CSV table and an SVG plot.

use std::borrow::Cow;

#[cfg(feature = "parallel")]
use rayon::prelude::*;
use serde::Serialize;
use serde_json::Value;

use crate::conical::{conical_dual, conical_folds};
use crate::design::Design;
use crate::design::MeshKind;
use crate::generate::{generate, GenerateError, GenerateOptions};
use crate::grid::QuadGrid;
use crate::measure::{conical_error, measure};

/// Largest number of values a scan accepts (a typo such as `0:360:1e-6` would
/// otherwise try to build hundreds of millions of meshes).
pub const MAX_VALUES: usize = 100_000;

/// Why a scan cannot be run (§4.3).
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum ScanError {
    /// The range is not `START:END:STEP` with finite numbers.
    #[error("`{range}` is not a range: write START:END:STEP with finite numbers, e.g. -180:180:2")]
    BadRange {
        /// The text given.
        range: String,
    },
    /// The step is zero or points away from the end.
    #[error(
        "the range {start}:{end}:{step} never reaches its end: the step must be non-zero and \
         have the sign of END − START"
    )]
    BadStep {
        /// First value.
        start: f64,
        /// Last value.
        end: f64,
        /// Step.
        step: f64,
    },
    /// The range has more than [`MAX_VALUES`] values.
    #[error("the range has {count} values, more than the limit of {limit}: use a larger step")]
    TooManyValues {
        /// Number of values.
        count: usize,
        /// [`MAX_VALUES`].
        limit: usize,
    },
    /// The parameter path does not name a number of the design.
    #[error("`{path}` does not name a number of the design: {problem}")]
    BadPath {
        /// The path given.
        path: String,
        /// What is wrong.
        problem: String,
    },
}

/// The values `start, start + step, …` up to `end` inclusive (within a
/// millionth of a step, so that `0:1:0.1` ends at 1), each computed as
/// `start + k·step` (no accumulated round-off).
///
/// ```
/// use monge_core::scan::values;
/// assert_eq!(values(-180.0, 180.0, 90.0).unwrap(), vec![-180.0, -90.0, 0.0, 90.0, 180.0]);
/// assert!(values(0.0, 1.0, -0.5).is_err());
/// ```
pub fn values(start: f64, end: f64, step: f64) -> Result<Vec<f64>, ScanError> {
    if !(start.is_finite() && end.is_finite() && step.is_finite()) {
        return Err(ScanError::BadRange {
            range: format!("{start}:{end}:{step}"),
        });
    }
    if step == 0.0 || (end - start) * step < 0.0 {
        return Err(ScanError::BadStep { start, end, step });
    }
    let steps = ((end - start) / step + 1e-6).floor();
    if steps >= MAX_VALUES as f64 {
        return Err(ScanError::TooManyValues {
            count: if steps < usize::MAX as f64 {
                steps as usize + 1
            } else {
                usize::MAX
            },
            limit: MAX_VALUES,
        });
    }
    Ok((0..=steps as usize)
        .map(|k| start + k as f64 * step)
        .collect())
}

/// Parses `START:END:STEP` (e.g. `-180:180:2`) into its values (see [`values`]).
///
/// ```
/// use monge_core::scan::parse_range;
/// assert_eq!(parse_range("0:10:5").unwrap(), vec![0.0, 5.0, 10.0]);
/// assert!(parse_range("0:10").is_err());
/// ```
pub fn parse_range(text: &str) -> Result<Vec<f64>, ScanError> {
    let bad = || ScanError::BadRange {
        range: text.to_owned(),
    };
    let parts: Vec<f64> = text
        .split(':')
        .map(|s| s.trim().parse::<f64>().map_err(|_| bad()))
        .collect::<Result<_, _>>()?;
    let [start, end, step] = parts.as_slice() else {
        return Err(bad());
    };
    if !(start.is_finite() && end.is_finite() && step.is_finite()) {
        return Err(bad());
    }
    values(*start, *end, *step)
}

/// One step of a parameter path.
#[derive(Clone, Debug, PartialEq)]
enum Step {
    Key(String),
    Index(usize),
}

/// Splits `guide_v.bspline.control_points[2][2]` into its keys and indices.
fn parse_path(path: &str) -> Result<Vec<Step>, ScanError> {
    let bad = |problem: &str| ScanError::BadPath {
        path: path.to_owned(),
        problem: problem.to_owned(),
    };
    let mut steps = Vec::new();
    for part in path.split('.') {
        let (key, mut rest) = part.split_at(part.find('[').unwrap_or(part.len()));
        if key.is_empty() {
            return Err(bad("every `.` must be followed by a key"));
        }
        steps.push(Step::Key(key.to_owned()));
        while !rest.is_empty() {
            let close = rest.find(']').ok_or_else(|| bad("a `[` is not closed"))?;
            let index = rest[1..close]
                .trim()
                .parse::<usize>()
                .map_err(|_| bad("an index in `[…]` is not a non-negative integer"))?;
            steps.push(Step::Index(index));
            rest = &rest[close + 1..];
            if !rest.is_empty() && !rest.starts_with('[') {
                return Err(bad("write indices as `[i]` right after a key"));
            }
        }
    }
    Ok(steps)
}

/// `design` with the number at `path` set to `value` (§4.3). `theta` is short
/// for `theta_deg`; any other path names a number in the design's JSON form,
/// keys separated by `.`, list indices in brackets.
///
/// ```
/// use monge_core::scan::set_parameter;
/// use monge_core::{Design, GuideSpec};
/// let d = Design {
///     mesh: Default::default(),
///     theta_deg: 30.0,
///     guide_u: GuideSpec::points(vec![[0.0; 3], [1.0, 0.0, 0.2], [2.0, 0.0, 0.7]]),
///     guide_v: GuideSpec::bspline(2, vec![[0.0; 3], [0.0, 1.0, 0.0], [0.0, 2.0, 1.0]], 5),
///     tolerance: None,
/// };
/// let e = set_parameter(&d, "guide_v.bspline.control_points[2][2]", 1.5).unwrap();
/// let GuideSpec::BSpline { bspline, .. } = e.guide_v else { panic!("a B-spline") };
/// assert_eq!(bspline.control_points[2][2], 1.5);
/// assert_eq!(set_parameter(&d, "theta", -20.0).unwrap().theta_deg, -20.0);
/// assert!(set_parameter(&d, "guide_u.points[7][0]", 1.0).is_err());
/// ```
pub fn set_parameter(design: &Design, path: &str, value: f64) -> Result<Design, ScanError> {
    if path == "theta" || path == "theta_deg" {
        return Ok(Design {
            theta_deg: value,
            ..design.clone()
        });
    }
    let steps = parse_path(path)?;
    let bad = |problem: String| ScanError::BadPath {
        path: path.to_owned(),
        problem,
    };
    let mut json = serde_json::to_value(design).map_err(|e| bad(e.to_string()))?;
    let mut at = &mut json;
    for step in &steps {
        at = match step {
            Step::Key(k) => at
                .as_object_mut()
                .and_then(|o| o.get_mut(k))
                .ok_or_else(|| bad(format!("there is no key `{k}` there")))?,
            Step::Index(i) => {
                let list = at
                    .as_array_mut()
                    .ok_or_else(|| bad(format!("[{i}] indexes something that is not a list")))?;
                let len = list.len();
                list.get_mut(*i)
                    .ok_or_else(|| bad(format!("index {i} is out of range (the list has {len})")))?
            }
        };
    }
    if !at.is_number() {
        return Err(bad(format!("it names `{at}`, not a number")));
    }
    *at = serde_json::Number::from_f64(value)
        .map(Value::Number)
        .ok_or_else(|| bad(format!("{value} is not a finite number")))?;
    serde_json::from_value(json).map_err(|e| bad(e.to_string()))
}

/// What happened at one value of a scan (§4.3, §5.2).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// A mesh without folds.
    Fair,
    /// A mesh with folded faces: it pinches or intersects itself (§5.2).
    Folded,
    /// θ is outside the admissible range of the guides (§3.2) or singular (θ = +90°).
    Inadmissible,
    /// The generator stopped: a degenerate Gauss quad (pinch to a point, §5.2).
    Degenerate,
    /// The design is invalid at this value (e.g. a moved control point made a guide non-planar).
    Invalid,
}

impl Status {
    /// The name used in CSV files and plots.
    pub fn name(self) -> &'static str {
        match self {
            Status::Fair => "fair",
            Status::Folded => "folded",
            Status::Inadmissible => "inadmissible",
            Status::Degenerate => "degenerate",
            Status::Invalid => "invalid",
        }
    }
}

/// Panel statistics of a mesh (§4.8): face areas, their spread, the longest edge.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PanelStats {
    /// Smallest face area.
    pub area_min: f64,
    /// Largest face area.
    pub area_max: f64,
    /// Mean face area.
    pub area_mean: f64,
    /// Variance of the face areas (population variance).
    pub area_variance: f64,
    /// Longest edge.
    pub max_edge: f64,
}

impl PanelStats {
    /// `area_max / area_min` (infinite if a face has zero area).
    pub fn spread(&self) -> f64 {
        self.area_max / self.area_min
    }
}

/// Panel statistics of a grid with at least one face (§4.8); the areas are
/// [`QuadGrid::face_areas`].
pub fn panel_stats(grid: &QuadGrid) -> PanelStats {
    let areas = grid.face_areas();
    let n = areas.len().max(1) as f64;
    let mean = areas.iter().sum::<f64>() / n;
    let variance = areas.iter().map(|a| (a - mean).powi(2)).sum::<f64>() / n;
    let mut max_edge: f64 = 0.0;
    for i in 0..grid.rows {
        for j in 0..grid.cols {
            let p = grid.vertex(i, j);
            if i + 1 < grid.rows {
                max_edge = max_edge.max(p.distance(grid.vertex(i + 1, j)));
            }
            if j + 1 < grid.cols {
                max_edge = max_edge.max(p.distance(grid.vertex(i, j + 1)));
            }
        }
    }
    PanelStats {
        area_min: areas.iter().copied().fold(f64::INFINITY, f64::min),
        area_max: areas.iter().copied().fold(0.0, f64::max),
        area_mean: mean,
        area_variance: variance,
        max_edge,
    }
}

/// One row of a scan (§4.3).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ScanRow {
    /// The parameter's value.
    pub value: f64,
    /// What happened.
    pub status: Status,
    /// The generator's message when there is no mesh.
    pub error: Option<String>,
    /// Folded faces (§5.2) of the mesh the design asks for (a conical
    /// mesh's: [`conical_folds`]); 0 without a mesh.
    pub folded_faces: usize,
    /// Smallest sine of the angle between the two lines that defined a vertex (§5.2):
    /// near 0, the mesh pinches. NaN without a mesh.
    pub min_crossing_sine: f64,
    /// Panel statistics of the mesh the design asks for; `None` without a mesh.
    pub panels: Option<PanelStats>,
    /// The measured largest error of that mesh (`measure(..).max_error()`, or
    /// `max_error_conical` for a conical mesh, relative to the model size);
    /// NaN without a mesh.
    pub max_error: f64,
}

impl ScanRow {
    /// Whether the value is admissible (§3.2): not outside the θ range and not singular.
    pub fn admissible(&self) -> bool {
        self.status != Status::Inadmissible
    }
}

/// A whole scan: the parameter and one row per value, in the order of the values.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Scan {
    /// The parameter path (`theta_deg` for θ).
    pub parameter: String,
    /// The rows.
    pub rows: Vec<ScanRow>,
}

impl Scan {
    /// Maximal runs of consecutive rows with `status` as `(first value, last value)`.
    pub fn intervals(&self, status: Status) -> Vec<(f64, f64)> {
        let mut out: Vec<(f64, f64)> = Vec::new();
        let mut open = false;
        for r in &self.rows {
            if r.status == status {
                match (open, out.last_mut()) {
                    (true, Some(last)) => last.1 = r.value,
                    _ => out.push((r.value, r.value)),
                }
                open = true;
            } else {
                open = false;
            }
        }
        out
    }
}

/// Generates `design` at one value and reports it.
fn evaluate(design: &Design, value: f64, options: &GenerateOptions) -> ScanRow {
    let empty = |status, error: String| ScanRow {
        value,
        status,
        error: Some(error),
        folded_faces: 0,
        min_crossing_sine: f64::NAN,
        panels: None,
        max_error: f64::NAN,
    };
    match generate(design, options) {
        Ok(g) => {
            // The mesh the design asks for: a conical mesh folds on its own (§2.3).
            let (folded, mesh, max_error) = match design.mesh {
                MeshKind::Circular => {
                    let max_error = measure(&g.grid).max_error();
                    (g.report.folded_faces, Cow::Borrowed(&g.grid), max_error)
                }
                MeshKind::Conical => {
                    let c = conical_dual(&g.grid);
                    let folds = conical_folds(&c.grid, Some(&c.face_normals));
                    let max_error = measure(&c.grid).max_error_conical(conical_error(&c.grid));
                    (folds.count(), Cow::Owned(c.grid), max_error)
                }
            };
            ScanRow {
                value,
                status: if folded > 0 {
                    Status::Folded
                } else {
                    Status::Fair
                },
                error: None,
                folded_faces: folded,
                min_crossing_sine: g.report.min_crossing.sine,
                panels: (mesh.face_count() > 0).then(|| panel_stats(&mesh)),
                max_error,
            }
        }
        Err(e) => {
            let status = match e {
                GenerateError::ThetaInadmissible { .. } | GenerateError::ThetaSingular { .. } => {
                    Status::Inadmissible
                }
                GenerateError::Degenerate { .. } | GenerateError::NormalStill { .. } => {
                    Status::Degenerate
                }
                _ => Status::Invalid,
            };
            empty(status, e.to_string())
        }
    }
}

/// Scans `design` over `values` of the parameter at `path` (`theta` for θ; see
/// [`set_parameter`]), in parallel (§4.3). `progress` is called once per value
/// as it completes (from any thread), e.g. to advance a progress bar.
///
/// The path is checked on the first value before anything is generated.
///
/// ```
/// use monge_core::scan::{scan, Status};
/// use monge_core::{Design, GuideSpec};
/// let d = Design {
///     mesh: Default::default(),
///     theta_deg: 0.0,
///     guide_u: GuideSpec::bspline(2, vec![[0.0; 3], [5.0, 0.0, 0.0], [10.0, 0.0, 4.0]], 9),
///     guide_v: GuideSpec::bspline(2, vec![[0.0; 3], [0.0, 4.0, 0.0], [0.0, 8.0, 3.0]], 9),
///     tolerance: None,
/// };
/// let s = scan(&d, "theta", &[-30.0, 0.0, 90.0], &Default::default(), &|| {}).unwrap();
/// assert_eq!(s.rows[1].status, Status::Fair);
/// assert_eq!(s.rows[2].status, Status::Inadmissible); // θ = +90° is singular
/// ```
pub fn scan(
    design: &Design,
    path: &str,
    values: &[f64],
    options: &GenerateOptions,
    progress: &(dyn Fn() + Sync),
) -> Result<Scan, ScanError> {
    if let Some(&first) = values.first() {
        set_parameter(design, path, first)?;
    }
    #[cfg(feature = "parallel")]
    let values_iter = values.par_iter();
    #[cfg(not(feature = "parallel"))]
    let values_iter = values.iter();
    let rows = values_iter
        .map(|&value| {
            let row = match set_parameter(design, path, value) {
                Ok(d) => evaluate(&d, value, options),
                Err(e) => ScanRow {
                    value,
                    status: Status::Invalid,
                    error: Some(e.to_string()),
                    folded_faces: 0,
                    min_crossing_sine: f64::NAN,
                    panels: None,
                    max_error: f64::NAN,
                },
            };
            progress();
            row
        })
        .collect();
    Ok(Scan {
        parameter: if path == "theta" {
            "theta_deg".to_owned()
        } else {
            path.to_owned()
        },
        rows,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_parse() {
        assert_eq!(
            parse_path("a.b[2][0]").unwrap(),
            vec![
                Step::Key("a".into()),
                Step::Key("b".into()),
                Step::Index(2),
                Step::Index(0)
            ]
        );
        for bad in ["a..b", "a[1", "a[x]", "a[1]b", ".a"] {
            assert!(parse_path(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn ranges_end_within_a_millionth_of_a_step() {
        let v = values(0.0, 1.0, 0.1).unwrap();
        assert_eq!(v.len(), 11);
        assert_eq!(v[10], 1.0);
        assert_eq!(values(5.0, 5.0, 1.0).unwrap(), vec![5.0]);
        assert_eq!(values(10.0, 0.0, -5.0).unwrap(), vec![10.0, 5.0, 0.0]);
    }

    #[test]
    fn intervals_are_maximal_runs() {
        let row = |value, status| ScanRow {
            value,
            status,
            error: None,
            folded_faces: 0,
            min_crossing_sine: 1.0,
            panels: None,
            max_error: 0.0,
        };
        let s = Scan {
            parameter: "theta_deg".into(),
            rows: vec![
                row(0.0, Status::Folded),
                row(1.0, Status::Fair),
                row(2.0, Status::Folded),
                row(3.0, Status::Folded),
            ],
        };
        assert_eq!(s.intervals(Status::Folded), vec![(0.0, 0.0), (2.0, 3.0)]);
    }
}
