//! A mesh of polygons measured independently: a grid trimmed to a target's outline,
//! whose panels along the outline are cut (monge's extension of §4.7). A cut panel
//! keeps its face's plane but not its circle, so planarity is what such a mesh
//! guarantees, measured as a curvature line's is ([`polyline_planarity`]).

use glam::DVec3;
use serde::{Deserialize, Serialize};

use super::{polyline_planarity, Worst};

/// The planarity of a mesh of polygons (§2.2's face planarity, for any polygon).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct PolygonMeasurements {
    /// The bounding-box diagonal of the vertices the faces use, which lengths are
    /// relative to (1 when it is 0).
    pub scale: f64,
    /// The largest distance of a face's corner from the plane fitted to the face's
    /// corners (least squares), relative to `scale`; `at` is (face, corner in the face).
    pub planarity: Worst,
}

/// Measures the faces of a mesh of polygons, each a list of indices into `vertices`
/// (three corners or more; a triangle is planar). Indices out of range are the
/// caller's to refuse (a file reader's).
///
/// ```
/// use glam::DVec3;
/// use monge_core::measure::measure_polygons;
/// let vertices = [DVec3::ZERO, DVec3::X, DVec3::new(1.5, 1.0, 0.0), DVec3::Y, DVec3::new(0.5, 2.0, 0.0)];
/// let flat = measure_polygons(&vertices, &[vec![0, 1, 2, 4, 3]]);
/// assert_eq!(flat.planarity.value, 0.0);
/// // One corner lifted by 0.1: the fitted plane tilts towards it, the second face is
/// // off it by less than 0.1 (the triangle is planar).
/// let mut lifted = vertices;
/// lifted[4].z = 0.1;
/// let m = measure_polygons(&lifted, &[vec![0, 1, 2], vec![0, 1, 2, 4, 3]]);
/// assert_eq!(m.planarity.at.0, 1);
/// assert!(m.planarity.value * m.scale > 0.01 && m.planarity.value * m.scale < 0.1);
/// ```
pub fn measure_polygons(vertices: &[DVec3], faces: &[Vec<usize>]) -> PolygonMeasurements {
    let (lo, hi) = faces
        .iter()
        .flatten()
        .map(|k| vertices[*k])
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    let diagonal = (hi - lo).length();
    let scale = if diagonal > 0.0 { diagonal } else { 1.0 };
    let measured = crate::tasks::map(faces.len(), |f| {
        let corners: Vec<DVec3> = faces[f].iter().map(|k| vertices[*k]).collect();
        polyline_planarity(&corners)
    });
    let mut planarity = Worst::NONE;
    for (f, (d, k)) in measured.into_iter().enumerate() {
        planarity.update(d, (f, k));
    }
    PolygonMeasurements {
        scale,
        planarity: planarity.relative(scale),
    }
}
