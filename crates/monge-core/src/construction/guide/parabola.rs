//! The `parabola` kind of guide (§3): `start + t·tangent + t²·quadratic`.

use glam::DVec3;

use super::{check_count, check_finite, v, GuideError, GuideName, Sampled, TangentSource};
use crate::design::ParabolaSpec;

/// The `parabola` kind: `start + t·tangent + t²·quadratic` at `t = k / (samples − 1)`.
pub(super) fn sample_parabola(p: &ParabolaSpec, name: GuideName) -> Result<Sampled, GuideError> {
    check_count(p.samples, "parabola.samples", name)?;
    check_finite(&p.start, "parabola.start", None, name)?;
    check_finite(&p.tangent, "parabola.tangent", None, name)?;
    check_finite(&p.quadratic, "parabola.quadratic", None, name)?;
    let (start, tangent, quadratic) = (v(&p.start), v(&p.tangent), v(&p.quadratic));
    if tangent == DVec3::ZERO {
        return Err(GuideError::ZeroTangent {
            guide: name,
            from: TangentSource::Parabola,
        });
    }
    let last = (p.samples - 1) as f64;
    let points = (0..p.samples)
        .map(|k| {
            let t = k as f64 / last;
            start + t * tangent + (t * t) * quadratic
        })
        .collect();
    Ok((points, Some((tangent, TangentSource::Parabola))))
}
