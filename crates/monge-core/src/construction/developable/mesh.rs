//! The developable mesh of a discrete general helix (§3.3, Figure 11): the helix
//! lifted or levelled to one slope, its rulings cut by the planes, the node axes.

use glam::{DVec2, DVec3};

use crate::design::Xyz;
use crate::generate::{check_grid_size, GenerateOptions};
use crate::grid::{bbox_diagonal, QuadGrid};

use super::checks::{
    check_alpha, check_heights, finite, helix_slope, repeated, self_crossing, straight_vertices,
};
use super::error::{DevelopableError, Field};
use super::limits::{MAX_EXTENT, MAX_HELIX_POINTS, MIN_EXTENT, TOLERANCE};
use super::spec::DevelopableSpec;

/// A generated developable mesh (§3.3, Figure 11).
#[derive(Clone, Debug, PartialEq)]
pub struct DevelopableMesh {
    /// Vertex `(i, j)` is ruling `i` (the line of helix segment `i`) cut by the
    /// plane at `heights[j]`: rows are rulings, columns lie in the cutting planes.
    /// Node axes: `cos α · N − sin α · u_i` on ruling `i` (see the module docs).
    pub grid: QuadGrid,
    /// The helix vertices used (for a helix given directly, its points with the
    /// heights recomputed from the mean slope).
    pub helix: Vec<DVec3>,
    /// The slope α of every helix segment, in degrees.
    pub alpha_deg: f64,
}

/// The developable circular mesh with planar curvature lines of a discrete
/// general helix (§3.3, Figure 11), refused before it is built if it would have
/// more than `options.max_vertices` vertices.
///
/// Rows are the rulings (one per helix segment), columns the cuts by the planes
/// at `heights`; every face is an isosceles trapezoid (circular), rows are
/// straight, columns lie in their cutting planes, and the node axes (see the
/// module docs) are unit and torsion-free.
///
/// ```
/// use monge_core::developable::{developable, DevelopableSpec};
/// use monge_core::GenerateOptions;
/// // Over a square, α = 45°: the helix rises by the length of each side.
/// let spec = DevelopableSpec::projection(
///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
///     45.0,
///     vec![-1.0, -2.0],
/// );
/// let mesh = developable(&spec, &GenerateOptions::default()).unwrap();
/// assert_eq!((mesh.grid.rows, mesh.grid.cols), (3, 2));
/// assert!((mesh.helix[3].z - 3.0).abs() < 1e-15);
/// // Ruling 0 runs along +x through the helix vertex (1, 0, 1): 2 below it at height −1.
/// assert!((mesh.grid.vertex(0, 0) - glam::DVec3::new(-1.0, 0.0, -1.0)).length() < 1e-15);
/// ```
pub fn developable(
    spec: &DevelopableSpec,
    options: &GenerateOptions,
) -> Result<DevelopableMesh, DevelopableError> {
    let (points, alpha_deg, field) = match (&spec.helix, &spec.projection) {
        (Some(h), None) => (&h.points, None, Field::HelixPoint),
        (None, Some(p)) => (&p.points, Some(p.alpha_deg), Field::ProjectionPoint),
        (h, p) => {
            return Err(DevelopableError::CurveChoice {
                given: usize::from(h.is_some()) + usize::from(p.is_some()),
            })
        }
    };
    finite(Field::ReferenceNormal, 0, &spec.reference_normal)?;
    for (index, p) in points.iter().enumerate() {
        finite(field, index, p)?;
    }
    if let Some(a) = alpha_deg {
        finite(Field::Alpha, 0, &[a])?;
    }
    for (index, h) in spec.heights.iter().enumerate() {
        finite(Field::Height, index, std::slice::from_ref(h))?;
    }
    let extent = points
        .iter()
        .flatten()
        .chain(&spec.heights)
        .fold(0.0f64, |m, x| m.max(x.abs()));
    if extent > MAX_EXTENT || (extent > 0.0 && extent < MIN_EXTENT) {
        return Err(DevelopableError::Scale { extent });
    }
    let normal = DVec3::from_array(spec.reference_normal);
    // Scale first, so that tiny or huge normals normalise without under/overflow.
    let normal = (normal / normal.abs().max_element()).normalize_or_zero();
    if normal == DVec3::ZERO {
        return Err(DevelopableError::ZeroNormal);
    }
    if points.len() < 3 {
        return Err(DevelopableError::TooFewSegments {
            points: points.len(),
            segments: points.len().saturating_sub(1),
        });
    }
    if spec.heights.len() < 2 {
        return Err(DevelopableError::TooFewHeights {
            heights: spec.heights.len(),
        });
    }
    if points.len() > MAX_HELIX_POINTS {
        return Err(DevelopableError::TooManyPoints {
            points: points.len(),
        });
    }
    check_grid_size(points.len() - 1, spec.heights.len(), options)
        .map_err(DevelopableError::GridTooLarge)?;

    let frame = Frame::new(normal);
    let plan: Vec<DVec2> = points.iter().map(|p| frame.plan(p)).collect();
    let given_z: Vec<f64> = points.iter().map(|p| frame.height(p)).collect();
    let lengths: Vec<f64> = plan.windows(2).map(|w| (w[1] - w[0]).length()).collect();

    let (alpha, slope, size) = match alpha_deg {
        None => {
            let size = frame.size(&plan, &given_z, &spec.heights);
            repeated(&plan, &given_z, size)?;
            let (alpha, slope) = helix_slope(&given_z, &lengths)?;
            (alpha, slope, size)
        }
        Some(deg) => {
            check_alpha(deg, true)?;
            let alpha = deg.to_radians();
            let slope = alpha.tan();
            let z = lift(given_z[0], slope, &lengths);
            let size = frame.size(&plan, &z, &spec.heights);
            let (index, offset) = given_z.iter().map(|z| z - given_z[0]).enumerate().fold(
                (0, 0.0f64),
                |w, (k, d)| {
                    if d.abs() > w.1.abs() {
                        (k, d)
                    } else {
                        w
                    }
                },
            );
            if offset.abs() > TOLERANCE * size {
                return Err(DevelopableError::ProjectionNotPlanar {
                    index,
                    offset,
                    relative: offset.abs() / size,
                });
            }
            repeated(&plan, &z, size)?;
            (alpha, slope, size)
        }
    };
    let z = lift(given_z[0], slope, &lengths);
    let directions: Vec<DVec2> = plan
        .windows(2)
        .zip(&lengths)
        .map(|(w, l)| (w[1] - w[0]) / *l)
        .collect();
    straight_vertices(&directions)?;
    self_crossing(&plan, size)?;
    check_heights(&spec.heights, &z, size)?;

    let (sin, cos) = alpha.sin_cos();
    let (rows, cols) = (directions.len(), spec.heights.len());
    let mut vertices = Vec::with_capacity(rows * cols);
    let mut normals = Vec::with_capacity(rows * cols);
    for (i, u) in directions.iter().enumerate() {
        // Ruling i through helix vertex i + 1, direction u + slope·N.
        let axis = frame.point(-sin * *u, cos);
        for &h in &spec.heights {
            let along = (h - z[i + 1]) / slope;
            vertices.push(frame.point(plan[i + 1] + along * *u, h));
            normals.push(axis);
        }
    }
    Ok(DevelopableMesh {
        grid: QuadGrid::new(rows, cols, vertices, normals),
        helix: plan
            .iter()
            .zip(&z)
            .map(|(p, &h)| frame.point(*p, h))
            .collect(),
        alpha_deg: alpha.to_degrees(),
    })
}

/// An orthonormal frame `(e1, e2, N)`: plan coordinates and heights.
struct Frame {
    e1: DVec3,
    e2: DVec3,
    n: DVec3,
}

impl Frame {
    fn new(n: DVec3) -> Self {
        let (e1, e2) = n.any_orthonormal_pair();
        Frame { e1, e2, n }
    }

    fn plan(&self, p: &Xyz) -> DVec2 {
        let p = DVec3::from_array(*p);
        DVec2::new(p.dot(self.e1), p.dot(self.e2))
    }

    fn height(&self, p: &Xyz) -> f64 {
        DVec3::from_array(*p).dot(self.n)
    }

    /// The point (or vector) with plan coordinates `plan` at `height`.
    fn point(&self, plan: DVec2, height: f64) -> DVec3 {
        plan.x * self.e1 + plan.y * self.e2 + height * self.n
    }

    /// The design size: bounding-box diagonal of the helix and of its first
    /// vertex moved onto every cutting plane (1 if that is 0).
    fn size(&self, plan: &[DVec2], z: &[f64], heights: &[f64]) -> f64 {
        let pts: Vec<DVec3> = plan
            .iter()
            .zip(z)
            .map(|(p, &h)| self.point(*p, h))
            .chain(heights.iter().map(|&h| self.point(plan[0], h)))
            .collect();
        let d = bbox_diagonal(&pts);
        if d > 0.0 {
            d
        } else {
            1.0
        }
    }
}

/// Heights of the helix vertices lifted from `z0` with `slope` per unit of
/// horizontal length.
fn lift(z0: f64, slope: f64, lengths: &[f64]) -> Vec<f64> {
    let mut along = 0.0;
    std::iter::once(z0)
        .chain(lengths.iter().map(|l| {
            along += l;
            z0 + slope * along
        }))
        .collect()
}
