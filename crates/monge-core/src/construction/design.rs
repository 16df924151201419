//! Design (§3): two planar guide curves that meet at 90° and the angle θ.
//!
//! A [`Design`] is plain data (it deserialises from the design-file format,
//! JSON or TOML, in `monge-io`). Nothing is validated here: [`crate::generate()`]
//! validates everything and says what is wrong, where, and by how much.

use serde::{Deserialize, Serialize};

/// A point or vector as written in a design file.
pub type Xyz = [f64; 3];

/// A design: the input of the generator (§3).
///
/// θ convention (see the README): in the characteristic case the pencil axis in
/// the plane of guide_v's Gauss circle is the line `{tan(θ/2)·N_p + s·t_v}`,
/// where `N_p = t_u × t_v / |t_u × t_v|` and `t_u`, `t_v` are the unit start
/// tangents; θ = 0 makes guide_u the rail of a moulding surface; θ = +90° is
/// singular (every Gauss circle passes through the corner normal).
///
/// ```
/// use monge_core::design::{Design, GuideSpec};
/// let d = Design {
///     mesh: Default::default(),
///     theta_deg: 30.0,
///     guide_u: GuideSpec::points(vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.2], [2.0, 0.0, 0.7]]),
///     guide_v: GuideSpec::points(vec![[0.0, 0.0, 0.0], [0.0, 1.0, 0.1], [0.0, 2.0, 0.5]]),
///     tolerance: None,
/// };
/// assert_eq!(d.guide_u.sample_count(), 3);
/// ```
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Design {
    /// The angle θ in degrees, in (−180, 180] (other values are taken modulo 360).
    pub theta_deg: f64,
    /// The guide along which the first grid index `i` runs (rows).
    pub guide_u: GuideSpec,
    /// The guide along which the second grid index `j` runs (columns).
    pub guide_v: GuideSpec,
    /// Which mesh to build from the guides and θ: circular (default) or conical.
    #[serde(default, skip_serializing_if = "MeshKind::is_circular")]
    pub mesh: MeshKind,
    /// Tolerances for validating the input; `None` means [`Tolerances::default`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tolerance: Option<Tolerances>,
}

/// The kind of mesh a design asks for (§2.2, §2.3); `"mesh": "conical"` in a design file.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum MeshKind {
    /// A circular mesh: planar, circular faces, node axes and node offsets (§2.2).
    #[default]
    Circular,
    /// Its conical dual: planar faces tangent to a cone at every vertex, face
    /// offsets (§2.3). See [`crate::conical`].
    Conical,
}

impl MeshKind {
    /// Whether this is the default, [`MeshKind::Circular`].
    pub fn is_circular(&self) -> bool {
        *self == MeshKind::Circular
    }
}

/// Relative tolerances used to accept a design (all relative to the size of the
/// guide, or in radians for angles).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Tolerances {
    /// Largest distance of a guide sample from the guide's best-fit plane,
    /// relative to the guide's bounding-box diagonal. Default `1e-9`.
    /// Samples within it are projected onto the plane, so the output stays exact.
    pub planarity: f64,
    /// Largest deviation, in radians, of the angle between the two start
    /// tangents from 90°. Default `1e-9`.
    pub angle: f64,
    /// Largest distance between the two guides' start points, relative to the
    /// larger guide's bounding-box diagonal. Default `1e-9`.
    pub start: f64,
}

impl Default for Tolerances {
    fn default() -> Self {
        Tolerances {
            planarity: 1e-9,
            angle: 1e-9,
            start: 1e-9,
        }
    }
}

/// One guide curve (§3): a polyline, a B-spline, an arc or a parabola.
///
/// In a design file it is a table with exactly one of `points`, `bspline`,
/// `arc` or `parabola`; `tangent` is only allowed with `points` (the start
/// tangent of a polyline: without it, the tangent of the circle through the
/// first three points, or the first chord if there are only two), and
/// `parameters` only with `bspline`. Anything else is refused when the file is
/// read ([`GuideSpecError`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "RawGuideSpec", into = "RawGuideSpec")]
pub enum GuideSpec {
    /// A polyline, used exactly as given (`points`).
    Points {
        /// The points.
        points: Vec<Xyz>,
        /// Its start tangent (`tangent`), if given.
        tangent: Option<Xyz>,
    },
    /// A clamped B-spline or NURBS curve (`bspline`).
    BSpline {
        /// The curve.
        bspline: BSplineSpec,
        /// The parameter values at which it is sampled (§4.8), instead of
        /// `samples` uniformly spaced ones: strictly increasing, within the knot
        /// range, one per sample (its length must equal `bspline.samples`).
        /// Chosen by the panel-size optimisation (`monge optimise-panels`).
        parameters: Option<Vec<f64>>,
    },
    /// A circular arc (`arc`).
    Arc(ArcSpec),
    /// A parabola arc (`parabola`).
    Parabola(ParabolaSpec),
}

/// The words for "the guide" that begin every [`GuideSpecError`] message: a
/// reader that knows the guide's key (`guide_u`) puts it in their place.
pub const THIS_GUIDE: &str = "this guide";

/// Why a guide's table in a design file is not one guide curve (§3).
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum GuideSpecError {
    /// None of `points`, `bspline`, `arc`, `parabola` is given.
    #[error(
        "this guide has no curve: give exactly one of `points`, `bspline`, `arc` or `parabola`."
    )]
    NoKind,
    /// More than one of `points`, `bspline`, `arc`, `parabola` is given.
    #[error(
        "this guide has several curves ({}): give exactly one of `points`, `bspline`, `arc` or `parabola`.",
        .found.join(", ")
    )]
    SeveralKinds {
        /// The keys found, in the order `points`, `bspline`, `arc`, `parabola`.
        found: Vec<&'static str>,
    },
    /// `tangent` is given with a kind other than `points`.
    #[error(
        "this guide: `tangent` is only allowed with `points`; this guide is a `{kind}`, whose start tangent is given by the curve itself. Remove `tangent`."
    )]
    TangentWithoutPoints {
        /// The kind given (`bspline`, `arc` or `parabola`).
        kind: &'static str,
    },
    /// `parameters` is given with a kind other than `bspline`.
    #[error(
        "this guide: `parameters` (sample parameters, §4.8) is only allowed with `bspline`; this guide is a `{kind}`. Remove `parameters`."
    )]
    ParametersWithoutBSpline {
        /// The kind given (`points`, `arc` or `parabola`).
        kind: &'static str,
    },
}

/// A guide as written in a design file: the keys of every kind, each optional.
#[derive(Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawGuideSpec {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    points: Option<Vec<Xyz>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    tangent: Option<Xyz>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    parameters: Option<Vec<f64>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    bspline: Option<BSplineSpec>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    arc: Option<ArcSpec>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    parabola: Option<ParabolaSpec>,
}

impl TryFrom<RawGuideSpec> for GuideSpec {
    type Error = GuideSpecError;

    fn try_from(raw: RawGuideSpec) -> Result<Self, GuideSpecError> {
        let found: Vec<&'static str> = [
            ("points", raw.points.is_some()),
            ("bspline", raw.bspline.is_some()),
            ("arc", raw.arc.is_some()),
            ("parabola", raw.parabola.is_some()),
        ]
        .iter()
        .filter(|k| k.1)
        .map(|k| k.0)
        .collect();
        if found.len() > 1 {
            return Err(GuideSpecError::SeveralKinds { found });
        }
        let RawGuideSpec {
            points,
            tangent,
            parameters,
            bspline,
            arc,
            parabola,
        } = raw;
        let (has_tangent, has_parameters) = (tangent.is_some(), parameters.is_some());
        let spec = match (points, bspline, arc, parabola) {
            (Some(points), ..) => GuideSpec::Points { points, tangent },
            (_, Some(bspline), ..) => GuideSpec::BSpline {
                bspline,
                parameters,
            },
            (_, _, Some(a), _) => GuideSpec::Arc(a),
            (.., Some(p)) => GuideSpec::Parabola(p),
            (None, None, None, None) => return Err(GuideSpecError::NoKind),
        };
        if has_tangent && !matches!(spec, GuideSpec::Points { .. }) {
            return Err(GuideSpecError::TangentWithoutPoints { kind: spec.kind() });
        }
        if has_parameters && !matches!(spec, GuideSpec::BSpline { .. }) {
            return Err(GuideSpecError::ParametersWithoutBSpline { kind: spec.kind() });
        }
        Ok(spec)
    }
}

impl From<GuideSpec> for RawGuideSpec {
    fn from(spec: GuideSpec) -> Self {
        match spec {
            GuideSpec::Points { points, tangent } => RawGuideSpec {
                points: Some(points),
                tangent,
                ..Default::default()
            },
            GuideSpec::BSpline {
                bspline,
                parameters,
            } => RawGuideSpec {
                bspline: Some(bspline),
                parameters,
                ..Default::default()
            },
            GuideSpec::Arc(arc) => RawGuideSpec {
                arc: Some(arc),
                ..Default::default()
            },
            GuideSpec::Parabola(parabola) => RawGuideSpec {
                parabola: Some(parabola),
                ..Default::default()
            },
        }
    }
}

/// A clamped B-spline / NURBS guide, sampled at `samples` uniformly spaced
/// parameter values from the first to the last knot, inclusive.
/// Its start tangent is `P1 − P0`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BSplineSpec {
    /// Polynomial degree (≥ 1).
    pub degree: usize,
    /// Control points P0 … Pn (at least `degree + 1`).
    pub control_points: Vec<Xyz>,
    /// Knot vector (`n + degree + 2` values, non-decreasing, clamped);
    /// default: clamped uniform.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub knots: Option<Vec<f64>>,
    /// Positive weights, one per control point; default: all 1 (a B-spline).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub weights: Option<Vec<f64>>,
    /// Number of samples (≥ 2).
    pub samples: usize,
}

/// A circular arc from `start`, turning about the axis through `center` along
/// `normal` by `angle_deg` (right-hand rule), sampled at `samples` uniformly
/// spaced angles, ends included. Its start tangent is `normal × (start − center)`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ArcSpec {
    /// Centre of the circle.
    pub center: Xyz,
    /// First point of the arc (the guides' common start point).
    pub start: Xyz,
    /// Normal of the arc's plane (need not be unit; orthogonal to `start − center`).
    pub normal: Xyz,
    /// Swept angle in degrees (non-zero, |angle| < 360).
    pub angle_deg: f64,
    /// Number of samples (≥ 2).
    pub samples: usize,
}

/// The parabola `P(t) = start + t·tangent + t²·quadratic`, `t ∈ [0, 1]`,
/// sampled at `samples` uniformly spaced values of `t`, ends included.
/// Its start tangent is `tangent`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ParabolaSpec {
    /// `P(0)`.
    pub start: Xyz,
    /// `P'(0)` (non-zero).
    pub tangent: Xyz,
    /// Half the second derivative (not parallel to `tangent`, or zero for a segment).
    pub quadratic: Xyz,
    /// Number of samples (≥ 2).
    pub samples: usize,
}

impl GuideSpec {
    /// A polyline guide given point by point, without `tangent`.
    pub fn points(points: Vec<Xyz>) -> Self {
        GuideSpec::Points {
            points,
            tangent: None,
        }
    }

    /// A clamped B-spline guide with default (clamped uniform) knots and unit
    /// weights, sampled at `samples` points (§3).
    ///
    /// ```
    /// use monge_core::GuideSpec;
    /// let g = GuideSpec::bspline(2, vec![[0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 1.0]], 11);
    /// assert_eq!(g.sample_count(), 11);
    /// ```
    pub fn bspline(degree: usize, control_points: Vec<Xyz>, samples: usize) -> Self {
        GuideSpec::BSpline {
            bspline: BSplineSpec {
                degree,
                control_points,
                knots: None,
                weights: None,
                samples,
            },
            parameters: None,
        }
    }

    /// A circular-arc guide (§3): see [`ArcSpec`].
    pub fn arc(center: Xyz, start: Xyz, normal: Xyz, angle_deg: f64, samples: usize) -> Self {
        GuideSpec::Arc(ArcSpec {
            center,
            start,
            normal,
            angle_deg,
            samples,
        })
    }

    /// The key of its kind in a design file: `points`, `bspline`, `arc` or `parabola`.
    pub fn kind(&self) -> &'static str {
        match self {
            GuideSpec::Points { .. } => "points",
            GuideSpec::BSpline { .. } => "bspline",
            GuideSpec::Arc(_) => "arc",
            GuideSpec::Parabola(_) => "parabola",
        }
    }

    /// Number of samples the guide will have, known without sampling it
    /// (so that a grid too large for memory is refused before any allocation).
    pub fn sample_count(&self) -> usize {
        match self {
            GuideSpec::Points { points, .. } => points.len(),
            GuideSpec::BSpline { bspline, .. } => bspline.samples,
            GuideSpec::Arc(a) => a.samples,
            GuideSpec::Parabola(p) => p.samples,
        }
    }
}

/// `p − by`, coordinate by coordinate.
fn minus(p: Xyz, by: Xyz) -> Xyz {
    [p[0] - by[0], p[1] - by[1], p[2] - by[2]]
}

impl GuideSpec {
    /// The guide's first point, known without sampling it: the first point, the
    /// first control point (a clamped B-spline starts there), or the `start` of
    /// an arc or a parabola. `None` for a guide without points.
    pub fn start_point(&self) -> Option<Xyz> {
        match self {
            GuideSpec::Points { points, .. } => points.first().copied(),
            GuideSpec::BSpline { bspline, .. } => bspline.control_points.first().copied(),
            GuideSpec::Arc(a) => Some(a.start),
            GuideSpec::Parabola(p) => Some(p.start),
        }
    }

    /// The same guide moved by `−by`: its points, control points, centres and
    /// starts, every direction, weight, knot and parameter kept. Each
    /// coordinate `x − b` is rounded by at most ε |x − b|, so near `by` the
    /// moved guide is the same curve to rounding of its own size.
    pub fn translated(&self, by: Xyz) -> GuideSpec {
        let mut g = self.clone();
        match &mut g {
            GuideSpec::Points { points, .. } => {
                for p in points {
                    *p = minus(*p, by);
                }
            }
            GuideSpec::BSpline { bspline, .. } => {
                for p in &mut bspline.control_points {
                    *p = minus(*p, by);
                }
            }
            GuideSpec::Arc(a) => {
                a.center = minus(a.center, by);
                a.start = minus(a.start, by);
            }
            GuideSpec::Parabola(p) => p.start = minus(p.start, by),
        }
        g
    }
}

impl Design {
    /// The same design moved by `−by` (both guides, [`GuideSpec::translated`]).
    /// The construction commutes with translations (§2.2), so the mesh of the
    /// moved design is the design's mesh moved by `−by`, computed without the
    /// rounding of coordinates of magnitude |by| (§5.2).
    ///
    /// ```
    /// use monge_core::{generate, Design, GenerateOptions, GuideSpec};
    /// let at = |x: f64, y: f64, z: f64| [1e6 + x, 2e6 + y, z];
    /// let d = Design {
    ///     mesh: Default::default(),
    ///     theta_deg: 30.0,
    ///     guide_u: GuideSpec::Points {
    ///         points: vec![at(0.0, 0.0, 0.0), at(1.0, 0.0, 0.2), at(2.0, 0.0, 0.7)],
    ///         tangent: Some([1.0, 0.0, 0.0]),
    ///     },
    ///     guide_v: GuideSpec::points(vec![at(0.0, 0.0, 0.0), at(0.0, 1.0, 0.1), at(0.0, 2.0, 0.5)]),
    ///     tolerance: None,
    /// };
    /// let start = d.start_point().unwrap();
    /// assert_eq!(start, [1e6, 2e6, 0.0]);
    /// let mesh = generate(&d.translated(start), &GenerateOptions::default()).unwrap().grid;
    /// assert_eq!(mesh.vertex(2, 0).to_array(), [2.0, 0.0, 0.7]);
    /// ```
    pub fn translated(&self, by: Xyz) -> Design {
        Design {
            guide_u: self.guide_u.translated(by),
            guide_v: self.guide_v.translated(by),
            ..self.clone()
        }
    }

    /// The guides' common start point: guide_u's first point
    /// ([`GuideSpec::start_point`]); `None` for a guide_u without points.
    pub fn start_point(&self) -> Option<Xyz> {
        self.guide_u.start_point()
    }
}

/// The point that output coordinates are written relative to (§5.2): the
/// guides' common start point, or a given point. Far from the origin the mesh
/// is then computed and written without the rounding of large coordinates, and
/// the files record the point to add back.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BasePoint {
    /// The guides' common start point ([`Design::start_point`]).
    Start,
    /// A given point.
    At(Xyz),
}

impl BasePoint {
    /// The point for `design`: `None` only for [`BasePoint::Start`] of a
    /// guide_u without points (which generation then refuses with its own words).
    pub fn of(&self, design: &Design) -> Option<Xyz> {
        match self {
            BasePoint::Start => design.start_point(),
            BasePoint::At(p) => Some(*p),
        }
    }
}

impl BasePoint {
    /// `design` moved by −the point ([`Design::translated`]), and the point;
    /// `design` itself and `None` when there is no point ([`BasePoint::of`]).
    pub fn apply(&self, design: Design) -> (Design, Option<Xyz>) {
        match self.of(&design) {
            Some(p) => (design.translated(p), Some(p)),
            None => (design, None),
        }
    }
}

impl std::str::FromStr for BasePoint {
    type Err = String;

    /// `start`, or `X,Y,Z` (three finite numbers).
    ///
    /// ```
    /// use monge_core::design::BasePoint;
    /// assert_eq!("start".parse(), Ok(BasePoint::Start));
    /// assert_eq!("1e6,-2,0.5".parse(), Ok(BasePoint::At([1e6, -2.0, 0.5])));
    /// assert!("1,2".parse::<BasePoint>().is_err());
    /// ```
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        if s.trim() == "start" {
            return Ok(BasePoint::Start);
        }
        let numbers: Vec<f64> = s
            .split(',')
            .map(|x| x.trim().parse::<f64>())
            .collect::<Result<_, _>>()
            .map_err(|e| format!("`{s}`: {e}; give `start` or X,Y,Z (three numbers)"))?;
        match numbers[..] {
            [x, y, z] if numbers.iter().all(|v| v.is_finite()) => Ok(BasePoint::At([x, y, z])),
            [_, _, _] => Err(format!("`{s}`: give three finite numbers")),
            _ => Err(format!(
                "`{s}` has {} number(s): give `start` or X,Y,Z (three numbers)",
                numbers.len()
            )),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The guide of the JSON table `json`, or why it is refused.
    fn parse(json: &str) -> Result<GuideSpec, String> {
        serde_json::from_str(json).map_err(|e| e.to_string())
    }

    const POINTS: &str = r#""points": [[0, 0, 0], [1, 0, 0.2], [2, 0, 0.7]]"#;
    const ARC: &str = r#""arc": {"center": [0, 0, -1], "start": [0, 0, 0], "normal": [0, 1, 0], "angle_deg": 30, "samples": 5}"#;
    const PARABOLA: &str = r#""parabola": {"start": [0, 0, 0], "tangent": [1, 0, 0], "quadratic": [0, 0, 1], "samples": 3}"#;

    #[test]
    fn no_kind() {
        for json in ["{}", r#"{"tangent": [1, 0, 0]}"#] {
            let e = parse(json).unwrap_err();
            assert!(e.starts_with("this guide has no curve: give exactly one of `points`, `bspline`, `arc` or `parabola`."), "{e}");
        }
    }

    #[test]
    fn several_kinds() {
        let e = parse(&format!("{{{POINTS}, {ARC}, {PARABOLA}}}")).unwrap_err();
        assert!(
            e.starts_with(
                "this guide has several curves (points, arc, parabola): give exactly one of"
            ),
            "{e}"
        );
    }

    #[test]
    fn tangent_without_points() {
        let e = parse(&format!(r#"{{{ARC}, "tangent": [1, 0, 0]}}"#)).unwrap_err();
        assert!(
            e.starts_with(
                "this guide: `tangent` is only allowed with `points`; this guide is a `arc`"
            ),
            "{e}"
        );
        assert!(e.contains("Remove `tangent`"), "{e}");
    }

    #[test]
    fn parameters_without_bspline() {
        for (kind, json) in [("points", POINTS), ("arc", ARC), ("parabola", PARABOLA)] {
            let e = parse(&format!(r#"{{{json}, "parameters": [0, 1]}}"#)).unwrap_err();
            let expected = format!("this guide: `parameters` (sample parameters, §4.8) is only allowed with `bspline`; this guide is a `{kind}`. Remove `parameters`.");
            assert!(e.starts_with(&expected), "{e}");
        }
    }

    #[test]
    fn messages_begin_with_the_guide() {
        let errors = [
            GuideSpecError::NoKind,
            GuideSpecError::SeveralKinds {
                found: vec!["points", "arc"],
            },
            GuideSpecError::TangentWithoutPoints { kind: "arc" },
            GuideSpecError::ParametersWithoutBSpline { kind: "arc" },
        ];
        for e in errors {
            assert!(e.to_string().starts_with(THIS_GUIDE), "{e}");
        }
    }

    #[test]
    fn every_kind_is_written_with_the_keys_it_is_read_from() {
        let tangent = format!(r#"{{{POINTS}, "tangent": [1, 0, 0]}}"#);
        let bspline = r#"{"parameters": [0, 0.5, 1], "bspline": {"degree": 1, "control_points": [[0, 0, 0], [1, 0, 0]], "samples": 3}}"#;
        let keys = |json: &str| -> Vec<String> {
            let value: serde_json::Value = serde_json::from_str(json).unwrap();
            value.as_object().unwrap().keys().cloned().collect()
        };
        let tables = [
            format!("{{{POINTS}}}"),
            tangent,
            bspline.to_owned(),
            format!("{{{ARC}}}"),
            format!("{{{PARABOLA}}}"),
        ];
        for json in tables {
            let spec = parse(&json).unwrap();
            let written = serde_json::to_string(&spec).unwrap();
            assert_eq!(keys(&written), keys(&json), "{written}");
            assert_eq!(parse(&written).unwrap(), spec);
        }
    }
}
