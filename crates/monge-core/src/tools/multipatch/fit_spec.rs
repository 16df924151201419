//! The fit of a multi-patch design (§4.7): the `fit` key of a design file, which
//! [`crate::optimise::fit`] runs — the free parameters, the boundary and its target.

use serde::{Deserialize, Serialize};

use crate::design::Xyz;

use super::side::Side;

/// The fit of a multi-patch design (§4.7): the `fit` key of a design file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FitSpec {
    /// The parameters to choose.
    pub free: Vec<FreeParameter>,
    /// The boundary to bring to the target.
    pub boundary: BoundaryRef,
    /// The target.
    pub target: Target,
    /// If given: the fit fails
    /// ([`FitError::Unreachable`](crate::optimise::FitError::Unreachable)) when the
    /// largest distance from the fitted boundary to the target exceeds it (absolute,
    /// model units).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_distance: Option<f64>,
    /// Budget of mesh generations (default `1000 × number of free parameters + 200`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_evaluations: Option<usize>,
}

/// A boundary line of a patch (§4.7).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoundaryRef {
    /// The patch (index in `patches`).
    pub patch: usize,
    /// The side of its own grid.
    pub side: Side,
}

/// What the boundary should reach (§4.7).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum Target {
    /// A polyline (the HippoHaus' G3): each boundary vertex is measured to its nearest point.
    Polyline(Vec<Xyz>),
    /// A plane, e.g. the plane of symmetry a patch must end in (Figure 20).
    Plane {
        /// A point of the plane.
        point: Xyz,
        /// Its normal (need not be unit).
        normal: Xyz,
    },
}

/// Which guide of a patch a coordinate belongs to (§4.7).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GuideKey {
    /// `guide_u` of the first patch.
    GuideU,
    /// `guide_v` of the first patch.
    GuideV,
    /// `guide` (the continuation) of a later patch.
    Guide,
}

/// A free parameter of a fit (§4.7).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum FreeParameter {
    /// θ of a patch.
    Theta {
        /// The patch.
        patch: usize,
        /// Optional `[low, high]` in degrees, intersected with the admissible range.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        bounds: Option<[f64; 2]>,
    },
    /// One coordinate of a control point of a `bspline` guide or of a point of a `points` guide.
    ControlPoint {
        /// The patch.
        patch: usize,
        /// Which of its guides.
        guide: GuideKey,
        /// Index of the control point (or point).
        index: usize,
        /// 0, 1 or 2 for x, y, z.
        coordinate: usize,
        /// `[low, high]`.
        bounds: [f64; 2],
    },
}

impl FreeParameter {
    /// A short name for reports, e.g. `theta[2]` or `patch 0 guide_u point 3 z` (§4.7).
    pub fn name(&self) -> String {
        match self {
            FreeParameter::Theta { patch, .. } => format!("theta[{patch}]"),
            FreeParameter::ControlPoint {
                patch,
                guide,
                index,
                coordinate,
                ..
            } => format!(
                "patch {patch} {} point {index} {}",
                match guide {
                    GuideKey::GuideU => "guide_u",
                    GuideKey::GuideV => "guide_v",
                    GuideKey::Guide => "guide",
                },
                ["x", "y", "z"].get(*coordinate).unwrap_or(&"?")
            ),
        }
    }
}
