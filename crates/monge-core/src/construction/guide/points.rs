//! The `points` kind of guide (§3): a polyline, with an optional start tangent.

use glam::DVec3;

use super::{check_count, check_finite, v, GuideError, GuideName, Sampled, TangentSource};
use crate::design::Xyz;

/// The `points` kind: the points as given.
pub(super) fn polyline(
    points: &[Xyz],
    tangent: Option<Xyz>,
    name: GuideName,
) -> Result<Sampled, GuideError> {
    check_count(points.len(), "points", name)?;
    for (i, p) in points.iter().enumerate() {
        check_finite(p, "points", Some(i), name)?;
    }
    let points: Vec<DVec3> = points.iter().map(v).collect();
    if let Some(t) = &tangent {
        check_finite(t, "tangent", None, name)?;
    }
    Ok((points, tangent.map(|t| (v(&t), TangentSource::Given))))
}
