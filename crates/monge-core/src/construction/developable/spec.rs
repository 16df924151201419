//! The developable design file (§3.3): a discrete general helix, given directly or
//! by its projection and slope, and the heights of the cutting planes.

use serde::{Deserialize, Serialize};

use crate::design::Xyz;

/// A design file holding a developable mesh (§3.3): `{"developable": {…}}`.
///
/// ```
/// use monge_core::developable::{DevelopableDesign, DevelopableSpec};
/// let d = DevelopableDesign {
///     developable: DevelopableSpec::projection(
///         vec![[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]],
///         30.0,
///         vec![-2.0, -1.0],
///     ),
/// };
/// assert!(d.developable.projection.is_some());
/// ```
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DevelopableDesign {
    /// The developable mesh (§3.3).
    pub developable: DevelopableSpec,
}

/// A developable circular mesh with planar curvature lines (§3.3): a discrete
/// general helix, given directly (`helix`) or by its projection curve and slope
/// (`projection`) — exactly one of the two — and the heights of the cutting planes.
///
/// ```
/// use monge_core::developable::DevelopableSpec;
/// let s = DevelopableSpec::helix(
///     vec![[1.0, 0.0, 0.0], [0.0, 1.0, 1.0], [-1.0, 0.0, 2.0]],
///     vec![-2.0, -1.0],
/// );
/// assert_eq!(s.reference_normal, [0.0, 0.0, 1.0]);
/// ```
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DevelopableSpec {
    /// The discrete general helix, given directly.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub helix: Option<HelixSpec>,
    /// The discrete general helix, lifted from a planar projection curve.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub projection: Option<ProjectionSpec>,
    /// Heights of the cutting planes: signed distances from the origin along the
    /// reference normal, strictly increasing or strictly decreasing, at least 2.
    /// Column `j` of the mesh lies in the plane at `heights[j]`.
    pub heights: Vec<f64>,
    /// Normal of the reference plane (need not be unit). Default `[0, 0, 1]`.
    #[serde(default = "default_reference_normal")]
    pub reference_normal: Xyz,
}

/// A discrete general helix given directly (§3.3): at least 3 points whose
/// segments all make the same angle α with the reference plane (to
/// [`TOLERANCE`](super::limits::TOLERANCE) relative in `sin α`), all rising or all falling.
///
/// Within the tolerance, vertex heights are recomputed from the mean slope
/// (first and last vertex kept), so the mesh is exact to round-off.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HelixSpec {
    /// The helix vertices.
    pub points: Vec<Xyz>,
}

/// A discrete general helix built from its projection (§3.3): a planar polyline
/// in a plane orthogonal to the reference normal, lifted from its first point so
/// that every segment rises by `tan(α) · (its length)`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProjectionSpec {
    /// The projection curve (at least 3 points, all at the same height).
    pub points: Vec<Xyz>,
    /// The slope α of every helix segment, in degrees, in (−90°, 90°) without 0°;
    /// negative values make the helix descend along the curve.
    pub alpha_deg: f64,
}

fn default_reference_normal() -> Xyz {
    [0.0, 0.0, 1.0]
}

impl DevelopableSpec {
    /// A spec with the helix given directly and the default reference normal (§3.3).
    ///
    /// ```
    /// use monge_core::developable::DevelopableSpec;
    /// let s = DevelopableSpec::helix(vec![[0.0; 3], [1.0, 0.0, 1.0], [1.0, 1.0, 2.0]], vec![-1.0, -2.0]);
    /// assert_eq!(s.helix.unwrap().points.len(), 3);
    /// ```
    pub fn helix(points: Vec<Xyz>, heights: Vec<f64>) -> Self {
        DevelopableSpec {
            helix: Some(HelixSpec { points }),
            projection: None,
            heights,
            reference_normal: default_reference_normal(),
        }
    }

    /// A spec with the helix built from a projection curve and α in degrees,
    /// and the default reference normal (§3.3).
    ///
    /// ```
    /// use monge_core::developable::DevelopableSpec;
    /// let s = DevelopableSpec::projection(vec![[0.0; 3], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]], 45.0, vec![-1.0, -2.0]);
    /// assert_eq!(s.projection.unwrap().alpha_deg, 45.0);
    /// ```
    pub fn projection(points: Vec<Xyz>, alpha_deg: f64, heights: Vec<f64>) -> Self {
        DevelopableSpec {
            helix: None,
            projection: Some(ProjectionSpec { points, alpha_deg }),
            heights,
            reference_normal: default_reference_normal(),
        }
    }
}
