//! The `arc` kind of guide (§3): a circular arc given by its center, start, normal and angle.

use super::{
    check_count, check_finite, unit, v, within, GuideError, GuideName, Sampled, TangentSource,
};
use crate::design::{ArcSpec, Tolerances};

/// The `arc` kind: `start` rotated about the axis through `center` along
/// `normal`, each sample computed directly from its angle.
pub(super) fn sample_arc(
    a: &ArcSpec,
    name: GuideName,
    tol: &Tolerances,
) -> Result<Sampled, GuideError> {
    check_count(a.samples, "arc.samples", name)?;
    check_finite(&a.center, "arc.center", None, name)?;
    check_finite(&a.start, "arc.start", None, name)?;
    check_finite(&a.normal, "arc.normal", None, name)?;
    if !a.angle_deg.is_finite() {
        return Err(GuideError::NonFinite {
            guide: name,
            field: "arc.angle_deg",
            index: None,
        });
    }
    if a.angle_deg == 0.0 || a.angle_deg.abs() >= 360.0 {
        return Err(GuideError::ArcAngle {
            guide: name,
            angle_deg: a.angle_deg,
        });
    }
    let n = unit(v(&a.normal)).ok_or(GuideError::ArcZeroNormal { guide: name })?;
    let start = v(&a.start);
    let r = start - v(&a.center);
    let r_unit = unit(r).ok_or(GuideError::ArcZeroRadius { guide: name })?;
    // Deviation from 90° of the angle between the normal and the radius.
    let off = libm::asin(n.dot(r_unit).abs().min(1.0));
    if !within(off, tol.angle) {
        return Err(GuideError::ArcNotOrthogonal {
            guide: name,
            angle: off,
            tolerance: tol.angle,
        });
    }
    // Rodrigues' rotation, written as a displacement from `start` so that
    // sample 0 is `start` exactly: R(φ)r − r = sin φ (n × r) − 2 sin²(φ/2) r⊥.
    let side = n.cross(r);
    let r_perp = r - n * n.dot(r);
    let step = a.angle_deg.to_radians() / (a.samples - 1) as f64;
    let points = (0..a.samples)
        .map(|k| {
            let phi = step * k as f64;
            let half = libm::sin(0.5 * phi);
            start + libm::sin(phi) * side - (2.0 * half * half) * r_perp
        })
        .collect();
    let tangent = side * a.angle_deg.signum();
    Ok((points, Some((tangent, TangentSource::Arc))))
}
