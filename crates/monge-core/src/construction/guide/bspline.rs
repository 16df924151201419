//! The `bspline` kind of guide (§3, §4.8): a clamped B-spline or NURBS, its knots and
//! weights checked, sampled at uniform or given parameters by [`crate::bspline::Nurbs`].

use glam::DVec3;

use super::{check_count, check_finite, v, GuideError, GuideName, Sampled, TangentSource};
use crate::bspline::Nurbs;
use crate::design::BSplineSpec;

/// Checks a knot vector for `count` control points of `degree` (see [`BSplineSpec`]).
pub(super) fn check_knots(
    knots: &[f64],
    count: usize,
    degree: usize,
    name: GuideName,
) -> Result<(), GuideError> {
    let expected = count + degree + 1;
    if knots.len() != expected {
        return Err(GuideError::KnotCount {
            guide: name,
            count: knots.len(),
            expected,
            control_points: count,
            degree,
        });
    }
    if let Some(i) = knots.iter().position(|k| !k.is_finite()) {
        return Err(GuideError::NonFinite {
            guide: name,
            field: "bspline.knots",
            index: Some(i),
        });
    }
    if let Some(i) = (1..knots.len()).find(|&i| knots[i] < knots[i - 1]) {
        return Err(GuideError::KnotsDecreasing {
            guide: name,
            index: i,
            previous: knots[i - 1],
            value: knots[i],
        });
    }
    let (first, last) = (knots[0], knots[knots.len() - 1]);
    if first == last {
        return Err(GuideError::EmptyKnotSpan {
            guide: name,
            value: first,
        });
    }
    let at_start = knots.iter().take_while(|&&k| k == first).count();
    let at_end = knots.iter().rev().take_while(|&&k| k == last).count();
    for (end, multiplicity) in [("start", at_start), ("end", at_end)] {
        if multiplicity != degree + 1 {
            return Err(GuideError::KnotsNotClamped {
                guide: name,
                end,
                multiplicity,
                degree,
            });
        }
    }
    let mut i = at_start;
    while i < knots.len() - at_end {
        let multiplicity = knots[i..].iter().take_while(|&&k| k == knots[i]).count();
        if multiplicity > degree {
            return Err(GuideError::KnotMultiplicity {
                guide: name,
                index: i,
                value: knots[i],
                multiplicity,
                degree,
            });
        }
        i += multiplicity;
    }
    Ok(())
}

/// The largest B-spline degree accepted, for guides and for the IGES surfaces
/// read as targets: a point costs about degree² operations (a guide of degree
/// 4000 and 500 samples took 20 s to validate), and no designer needs more
/// (Rhino stops at 11; guides are usually of degree 2 or 3).
pub const MAX_DEGREE: usize = 32;

/// Clamped uniform knots on `[0, 1]` for `count` control points of `degree`.
pub(crate) fn clamped_uniform_knots(count: usize, degree: usize) -> Vec<f64> {
    let spans = count - degree;
    let mut knots = vec![0.0; degree + 1];
    knots.extend((1..spans).map(|i| i as f64 / spans as f64));
    knots.extend(vec![1.0; degree + 1]);
    knots
}

/// The `bspline` kind: `samples` points at uniformly spaced parameters, or at
/// the given `parameters` (§4.8).
pub(super) fn sample_bspline(
    b: &BSplineSpec,
    parameters: Option<&[f64]>,
    name: GuideName,
) -> Result<Sampled, GuideError> {
    check_count(b.samples, "bspline.samples", name)?;
    let degree = b.degree;
    if degree == 0 {
        return Err(GuideError::ZeroDegree { guide: name });
    }
    if degree > MAX_DEGREE {
        return Err(GuideError::DegreeTooHigh {
            guide: name,
            degree,
            max: MAX_DEGREE,
        });
    }
    let count = b.control_points.len();
    if count <= degree {
        return Err(GuideError::TooFewControlPoints {
            guide: name,
            count,
            degree,
        });
    }
    for (i, p) in b.control_points.iter().enumerate() {
        check_finite(p, "bspline.control_points", Some(i), name)?;
    }
    let knots = match &b.knots {
        Some(k) => {
            check_knots(k, count, degree, name)?;
            k.clone()
        }
        None => clamped_uniform_knots(count, degree),
    };
    let weights = match &b.weights {
        Some(w) => {
            if w.len() != count {
                return Err(GuideError::WeightCount {
                    guide: name,
                    count: w.len(),
                    expected: count,
                });
            }
            if let Some(i) = w.iter().position(|x| !x.is_finite()) {
                return Err(GuideError::NonFinite {
                    guide: name,
                    field: "bspline.weights",
                    index: Some(i),
                });
            }
            if let Some(i) = w.iter().position(|&x| x <= 0.0) {
                return Err(GuideError::WeightNotPositive {
                    guide: name,
                    index: i,
                    value: w[i],
                });
            }
            w.clone()
        }
        None => vec![1.0; count],
    };
    // Relative to P0, so that round-off stays relative to the curve's size far
    // from the origin (and coordinates shared by all control points stay exact).
    let origin = v(&b.control_points[0]);
    let points: Vec<DVec3> = b.control_points.iter().map(|p| v(p) - origin).collect();
    let tangent = points[1] - points[0];
    let end = v(&b.control_points[count - 1]);
    let curve = Nurbs::new(degree, &points, &weights, &knots);
    let (lo, hi) = (knots[0], knots[knots.len() - 1]);
    if let Some(t) = parameters {
        check_parameters(t, b.samples, (lo, hi), name)?;
    }
    let last = (b.samples - 1) as f64;
    let samples = (0..b.samples)
        .map(|k| {
            let s = k as f64 / last;
            // Exactly `lo` at s = 0 and exactly `hi` at s = 1.
            let u = parameters.map_or((1.0 - s) * lo + s * hi, |t| t[k]);
            if u >= hi {
                end // the clamped end, exactly (P_n − P0 + P0 may round)
            } else {
                curve.point(u) + origin
            }
        })
        .collect();
    Ok((samples, Some((tangent, TangentSource::ControlPolygon))))
}

/// Checks `parameters` of a `bspline` guide (§4.8): one per sample, finite,
/// strictly increasing, within `[lo, hi]`.
pub(super) fn check_parameters(
    t: &[f64],
    samples: usize,
    (lo, hi): (f64, f64),
    name: GuideName,
) -> Result<(), GuideError> {
    if t.len() != samples {
        return Err(GuideError::ParameterCount {
            guide: name,
            count: t.len(),
            samples,
        });
    }
    if let Some(index) = t.iter().position(|x| !x.is_finite()) {
        return Err(GuideError::NonFinite {
            guide: name,
            field: "parameters",
            index: Some(index),
        });
    }
    if let Some(index) = t.iter().position(|&x| !(lo..=hi).contains(&x)) {
        return Err(GuideError::ParameterOutOfRange {
            guide: name,
            index,
            value: t[index],
            lo,
            hi,
        });
    }
    if let Some(k) = t.windows(2).position(|w| w[1] <= w[0]) {
        return Err(GuideError::ParametersNotIncreasing {
            guide: name,
            index: k + 1,
            previous: t[k],
            value: t[k + 1],
        });
    }
    Ok(())
}
