//! Developable circular meshes with planar curvature lines (§2.1.3, §3.3).
//!
//! Bonnet: the tangent developables of general helices are the only developable
//! surfaces of the third kind with planar curvature lines (§2.1.3, Figure 5).
//! Their discrete equivalent (§3.3, Figure 11) starts from a **discrete general
//! helix** — a polyline whose segments all make the same angle α with a reference
//! plane. The lines of its segments are the rulings (the first family of
//! curvature lines, straight); cutting them by planes parallel to the reference
//! plane gives the second family (planar). Two adjacent rulings meet at a helix
//! vertex `O` and have the same slope, so a face `ABCD` between two cutting planes
//! has `OA = OD` and `OB = OC`: it is an isosceles trapezoid, hence circular.
//!
//! # Node axes
//!
//! Write `N` for the unit reference normal, `u_i` for the unit horizontal
//! direction of helix segment `i` (its projection onto the reference plane), so
//! that ruling `i` has direction `cos α · u_i + sin α · N`. Every vertex on
//! ruling `i` gets the node axis
//!
//! `m_i = cos α · N − sin α · u_i`,
//!
//! the unit vector orthogonal to ruling `i` in the vertical plane through it:
//! the discrete binormal of the helix (the normal of the osculating plane of a
//! smooth general helix is exactly this vector). It is exactly torsion-free:
//! along a ruling the two axes are equal; across, the edge between rulings `i`
//! and `i + 1` at height `h` is `((h − z_O) / tan α) · (u_{i+1} − u_i)` (with `z_O`
//! the height of their common helix vertex) and `m_{i+1} − m_i = −sin α ·
//! (u_{i+1} − u_i)` is parallel to it, so the two axes and the edge are coplanar.
//! These axes are the ones every circular mesh carries (each is the mirror image
//! of its neighbour in the bisector plane of the edge between them), picked
//! orthogonal to the rulings; the vertex offset at distance `d` along them is
//! again such a mesh: the same construction on the helix translated by
//! `d / cos α` along `N`.
//!
//! # Limits
//!
//! The projection of the helix onto the reference plane must not cross itself
//! (checked pairwise, quadratic in the number of points, hence at most
//! [`MAX_HELIX_POINTS`] points: each point is a ruling, a row of panels; Figure 11
//! has 24); it may wind around several times without crossing, and a closed
//! projection (last point = first) is allowed. The mesh has as many vertices as
//! rulings (points − 1) times cutting planes, refused above
//! [`GenerateOptions::max_vertices`] before anything is built. Every
//! helix vertex where two rulings meet (all but the first and last) must lie
//! outside the range of the cutting heights, or some face would cross the helix.

use glam::{DVec2, DVec3};
use serde::{Deserialize, Serialize};

use crate::design::Xyz;
use crate::generate::{check_grid_size, GenerateError, GenerateOptions};
use crate::grid::{bbox_diagonal, QuadGrid};

/// Relative tolerance of every check (§3.3): lengths relative to the design size
/// (see [`DevelopableError`]), slopes relative to the mean slope, angles in radians.
pub const TOLERANCE: f64 = 1e-9;

/// Largest absolute coordinate or height accepted (§3.3).
pub const MAX_EXTENT: f64 = 1e100;

/// Smallest non-zero largest absolute coordinate or height accepted (§3.3).
pub const MIN_EXTENT: f64 = 1e-100;

/// Most helix points accepted (§3.3): the check that the helix does not cross
/// itself compares every pair of segments, about half a million pairs at this
/// count. Each point is a ruling, a row of panels: Figure 11 has 24.
pub const MAX_HELIX_POINTS: usize = 1000;

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
/// [`TOLERANCE`] relative in `sin α`), all rising or all falling.
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

/// Which input holds a bad number (§3.3).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Field {
    /// `helix.points[index]`.
    HelixPoint,
    /// `projection.points[index]`.
    ProjectionPoint,
    /// `projection.alpha_deg`.
    Alpha,
    /// `heights[index]`.
    Height,
    /// `reference_normal`.
    ReferenceNormal,
}

impl std::fmt::Display for Field {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Field::HelixPoint => "helix.points",
            Field::ProjectionPoint => "projection.points",
            Field::Alpha => "projection.alpha_deg",
            Field::Height => "heights",
            Field::ReferenceNormal => "reference_normal",
        })
    }
}

/// Everything that stops a developable mesh (§3.3). Lengths are compared with
/// [`TOLERANCE`] times the design size: the bounding-box diagonal of the helix
/// vertices together with the first helix vertex moved onto every cutting plane.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum DevelopableError {
    /// Neither or both of `helix` and `projection`.
    #[error(
        "the developable mesh needs exactly one of `helix` (the discrete helix's points) or \
         `projection` (a planar curve and `alpha_deg`), but {given} were given"
    )]
    CurveChoice {
        /// How many of the two were given (0 or 2).
        given: usize,
    },
    /// A NaN or infinite number.
    #[error("{field}[{index}] is not finite ({value}): give finite numbers")]
    NotFinite {
        /// The input holding it.
        field: Field,
        /// Index in that list (0 for a single value or vector).
        index: usize,
        /// The value.
        value: f64,
    },
    /// Coordinates too large or too small for the squared lengths of `f64`.
    #[error(
        "the design's largest coordinate or height is {extent:e}, outside [{MIN_EXTENT:e}, \
         {MAX_EXTENT:e}] where squared lengths overflow or underflow: rescale the design (change \
         its unit)"
    )]
    Scale {
        /// The largest absolute coordinate or height.
        extent: f64,
    },
    /// The reference normal is the zero vector.
    #[error(
        "reference_normal is [0, 0, 0]: give the normal of the reference plane, e.g. [0, 0, 1]"
    )]
    ZeroNormal,
    /// Fewer than 3 helix points.
    #[error(
        "the helix has {points} point(s), {segments} segment(s): give at least 3 points \
         (2 segments, so that two rulings meet)"
    )]
    TooFewSegments {
        /// Number of points.
        points: usize,
        /// Number of segments.
        segments: usize,
    },
    /// More than [`MAX_HELIX_POINTS`] helix points.
    #[error(
        "the helix has {points} points, more than the limit of {MAX_HELIX_POINTS} (every pair of \
         its segments is checked for crossings): give fewer points (each point is a ruling, \
         a row of panels; Figure 11 of the paper has 24)"
    )]
    TooManyPoints {
        /// Number of points.
        points: usize,
    },
    /// The mesh would have more vertices than [`GenerateOptions::max_vertices`]
    /// (always [`GenerateError::GridTooLarge`]: rows are the rulings, columns the
    /// cutting planes).
    #[error(transparent)]
    GridTooLarge(GenerateError),
    /// Fewer than 2 cutting planes.
    #[error("{heights} cutting plane height(s) given: give at least 2 in `heights`")]
    TooFewHeights {
        /// Number of heights.
        heights: usize,
    },
    /// The projection curve is not in a plane orthogonal to the reference normal.
    #[error(
        "projection.points[{index}] is {offset:.3e} off the plane of projection.points[0] along \
         the reference normal ({relative:.1e} of the design size; tolerance {TOLERANCE:.0e}): the \
         projection curve must lie in a plane parallel to the reference plane — give all points \
         the same height, or change reference_normal"
    )]
    ProjectionNotPlanar {
        /// Index of the farthest point.
        index: usize,
        /// Its signed offset along the reference normal.
        offset: f64,
        /// `|offset|` / design size.
        relative: f64,
    },
    /// Two consecutive helix points coincide.
    #[error(
        "helix points {index} and {next} coincide ({distance:.3e} apart, {relative:.1e} of the \
         design size; tolerance {TOLERANCE:.0e}): remove one of them",
        next = index + 1
    )]
    RepeatedPoint {
        /// Index of the first of the two points.
        index: usize,
        /// Their distance.
        distance: f64,
        /// Distance / design size.
        relative: f64,
    },
    /// The slope is 0°: rulings in the reference plane, parallel to the cutting planes.
    #[error(
        "the helix slope is α = {alpha_deg}°: its rulings lie parallel to the reference plane and \
         never cross the cutting planes; give a slope away from 0° (|α| > {TOLERANCE:.0e} rad)"
    )]
    Flat {
        /// The slope, in degrees.
        alpha_deg: f64,
    },
    /// The slope is 90°: rulings parallel to the reference normal (a cylinder).
    #[error(
        "the helix slope is α = {alpha_deg}°: its rulings are orthogonal to the reference plane \
         (a cylinder, whose rulings do not meet); give |α| < 90° (by more than {TOLERANCE:.0e} rad)"
    )]
    Vertical {
        /// The slope, in degrees.
        alpha_deg: f64,
    },
    /// |α| > 90°.
    #[error(
        "projection.alpha_deg = {alpha_deg}° is outside (−90°, 90°): give the angle of the helix \
         segments with the reference plane, negative for a descending helix"
    )]
    AlphaOutOfRange {
        /// The given slope, in degrees.
        alpha_deg: f64,
    },
    /// The segments do not all make the same angle with the reference plane.
    #[error(
        "the helix segments must all make the same angle with the reference plane, but segment \
         {segment} (points {segment}..{next}) makes {angle_deg:.9}° while the mean slope is \
         {alpha_deg:.9}° (sin α off by {deviation:.3e} relative; tolerance {TOLERANCE:.0e}). Move \
         the points, or give the projection curve and `alpha_deg` instead",
        next = segment + 1
    )]
    NonConstantSlope {
        /// The worst segment.
        segment: usize,
        /// Its angle with the reference plane, in degrees.
        angle_deg: f64,
        /// The mean slope `atan(Σ rise / Σ horizontal length)`, in degrees.
        alpha_deg: f64,
        /// `|sin angle − sin α|` / the length-weighted mean of `|sin angle|`.
        deviation: f64,
    },
    /// Two consecutive segments are collinear: their rulings coincide.
    #[error(
        "helix segments {before} and {vertex} are collinear (they turn by {turn_deg:.3e}° at \
         vertex {vertex}; tolerance {TOLERANCE:.0e} rad): their rulings coincide and the faces \
         between them are flat; remove vertex {vertex} or bend the curve there",
        before = vertex - 1
    )]
    Straight {
        /// The helix vertex between the two segments.
        vertex: usize,
        /// The turning angle of the projection there, in degrees.
        turn_deg: f64,
    },
    /// The projection of the helix onto the reference plane crosses (or touches) itself.
    #[error(
        "the projection curve crosses itself: segments {a} (points {a}..{a1}) and {b} (points \
         {b}..{b1}) come {distance:.3e} close ({relative:.1e} of the design size; tolerance \
         {TOLERANCE:.0e}); its projection must not cross itself — remove or move points",
        a1 = a + 1,
        b1 = b + 1
    )]
    SelfCrossing {
        /// The first segment.
        a: usize,
        /// The second segment.
        b: usize,
        /// Their distance in the reference plane.
        distance: f64,
        /// Distance / design size.
        relative: f64,
    },
    /// The heights are not strictly monotonic (or two consecutive are equal).
    #[error(
        "heights[{index}] = {height} does not continue the order of the heights (heights[{prev}] \
         = {previous}; gap tolerance {TOLERANCE:.0e} of the design size): give distinct heights \
         in increasing or decreasing order",
        prev = index - 1
    )]
    HeightsNotMonotonic {
        /// Index of the offending height.
        index: usize,
        /// `heights[index − 1]`.
        previous: f64,
        /// `heights[index]`.
        height: f64,
    },
    /// A cutting plane passes through a helix vertex where two rulings meet.
    #[error(
        "heights[{height_index}] = {height} is the height of helix vertex {vertex} ({vertex_height}; \
         {relative:.1e} of the design size apart, tolerance {TOLERANCE:.0e}), where rulings \
         {before} and {vertex} meet: the cut hits the helix and the faces between those rulings \
         degenerate to triangles. Move the plane off the helix",
        before = vertex - 1
    )]
    HeightAtHelixVertex {
        /// Index of the height.
        height_index: usize,
        /// The height.
        height: f64,
        /// The helix vertex (1 ..= segments − 1).
        vertex: usize,
        /// Its height.
        vertex_height: f64,
        /// `|height − vertex_height|` / design size.
        relative: f64,
    },
    /// Two consecutive cutting planes lie on both sides of a helix vertex.
    #[error(
        "helix vertex {vertex} (height {vertex_height}) lies between heights[{j}] = {below} and \
         heights[{j1}] = {above}: the face between rulings {before} and {vertex} would cross \
         itself at the helix (a folded quad). Keep every helix vertex where two rulings meet \
         (vertices 1 to segments − 1) outside the range of the heights",
        j1 = j + 1,
        before = vertex - 1
    )]
    FaceCrossesHelix {
        /// The helix vertex.
        vertex: usize,
        /// Its height.
        vertex_height: f64,
        /// Index of the first of the two heights.
        j: usize,
        /// `heights[j]`.
        below: f64,
        /// `heights[j + 1]`.
        above: f64,
    },
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

/// Any non-finite component of `v`, entry `index` of `field`.
fn finite(field: Field, index: usize, v: &[f64]) -> Result<(), DevelopableError> {
    match v.iter().find(|x| !x.is_finite()) {
        Some(&value) => Err(DevelopableError::NotFinite {
            field,
            index,
            value,
        }),
        None => Ok(()),
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

/// Consecutive helix vertices that coincide.
fn repeated(plan: &[DVec2], z: &[f64], size: f64) -> Result<(), DevelopableError> {
    for k in 0..plan.len() - 1 {
        let distance = (plan[k + 1] - plan[k]).length().hypot(z[k + 1] - z[k]);
        if distance.is_nan() || distance <= TOLERANCE * size {
            return Err(DevelopableError::RepeatedPoint {
                index: k,
                distance,
                relative: distance / size,
            });
        }
    }
    Ok(())
}

/// Refuse α (in degrees) of 0°, 90° or (with `range`) beyond ±90°, to
/// [`TOLERANCE`] radians.
fn check_alpha(alpha_deg: f64, range: bool) -> Result<(), DevelopableError> {
    let tol = TOLERANCE.to_degrees();
    if range && alpha_deg.abs() > 90.0 + tol {
        Err(DevelopableError::AlphaOutOfRange { alpha_deg })
    } else if alpha_deg.abs() <= tol {
        Err(DevelopableError::Flat { alpha_deg })
    } else if alpha_deg.abs() >= 90.0 - tol {
        Err(DevelopableError::Vertical { alpha_deg })
    } else {
        Ok(())
    }
}

/// The mean slope `(α, tan α)` of a helix given directly, after checking that
/// every segment has it.
fn helix_slope(z: &[f64], lengths: &[f64]) -> Result<(f64, f64), DevelopableError> {
    let rise: f64 = z[z.len() - 1] - z[0];
    let run: f64 = lengths.iter().sum();
    let alpha = rise.atan2(run);
    let angles: Vec<f64> = z
        .windows(2)
        .zip(lengths)
        .map(|(w, l)| (w[1] - w[0]).atan2(*l))
        .collect();
    let (abs_rise, total): (f64, f64) =
        z.windows(2)
            .zip(lengths)
            .fold((0.0, 0.0), |(a, t), (w, l)| {
                let dz = w[1] - w[0];
                (a + dz.abs(), t + dz.hypot(*l))
            });
    let mean_sin = abs_rise / total;
    if mean_sin > 0.0 {
        let (segment, deviation) = angles
            .iter()
            .map(|a| (a.sin() - alpha.sin()).abs() / mean_sin)
            .enumerate()
            .fold((0, 0.0), |w, (k, d)| if d > w.1 { (k, d) } else { w });
        if deviation > TOLERANCE {
            return Err(DevelopableError::NonConstantSlope {
                segment,
                angle_deg: angles[segment].to_degrees(),
                alpha_deg: alpha.to_degrees(),
                deviation,
            });
        }
    }
    check_alpha(alpha.to_degrees(), false)?;
    Ok((alpha, rise / run))
}

/// Consecutive collinear segments (same direction): coinciding rulings.
fn straight_vertices(directions: &[DVec2]) -> Result<(), DevelopableError> {
    for (k, w) in directions.windows(2).enumerate() {
        let turn = w[0].perp_dot(w[1]).atan2(w[0].dot(w[1]));
        if turn.abs() <= TOLERANCE {
            return Err(DevelopableError::Straight {
                vertex: k + 1,
                turn_deg: turn.to_degrees(),
            });
        }
    }
    Ok(())
}

/// Distance from `p` to the segment `ab`.
fn point_segment(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    let ab = b - a;
    let t = ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0);
    (p - (a + t * ab)).length()
}

/// Distance between the segments `ab` and `cd` (0 if they cross).
fn segment_segment(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> f64 {
    let side = |p: DVec2, q: DVec2, r: DVec2| (q - p).perp_dot(r - p);
    let (s1, s2) = (side(a, b, c), side(a, b, d));
    let (s3, s4) = (side(c, d, a), side(c, d, b));
    if s1 * s2 < 0.0 && s3 * s4 < 0.0 {
        return 0.0;
    }
    point_segment(a, c, d)
        .min(point_segment(b, c, d))
        .min(point_segment(c, a, b))
        .min(point_segment(d, a, b))
}

/// Segments of the projection that cross, touch or overlap, apart from the
/// common end of consecutive segments and the closing point of a closed curve.
fn self_crossing(plan: &[DVec2], size: f64) -> Result<(), DevelopableError> {
    let n = plan.len() - 1;
    let tol = TOLERANCE * size;
    let closed = (plan[n] - plan[0]).length() <= tol;
    let fail = |a: usize, b: usize, distance: f64| DevelopableError::SelfCrossing {
        a,
        b,
        distance,
        relative: distance / size,
    };
    for a in 0..n {
        // Consecutive segments share a point: they overlap only by folding back.
        if a + 1 < n {
            let d = point_segment(plan[a], plan[a + 1], plan[a + 2]).min(point_segment(
                plan[a + 2],
                plan[a],
                plan[a + 1],
            ));
            if d <= tol {
                return Err(fail(a, a + 1, d));
            }
        }
        for b in a + 2..n {
            let d = if closed && a == 0 && b == n - 1 {
                point_segment(plan[1], plan[n - 1], plan[n]).min(point_segment(
                    plan[n - 1],
                    plan[0],
                    plan[1],
                ))
            } else {
                segment_segment(plan[a], plan[a + 1], plan[b], plan[b + 1])
            };
            if d <= tol {
                return Err(fail(a, b, d));
            }
        }
    }
    Ok(())
}

/// Strictly monotonic heights, none through (or around) a helix vertex where two
/// rulings meet.
fn check_heights(heights: &[f64], z: &[f64], size: f64) -> Result<(), DevelopableError> {
    let tol = TOLERANCE * size;
    let up = heights[1] > heights[0];
    for (k, w) in heights.windows(2).enumerate() {
        let gap = if up { w[1] - w[0] } else { w[0] - w[1] };
        if gap <= tol {
            return Err(DevelopableError::HeightsNotMonotonic {
                index: k + 1,
                previous: w[0],
                height: w[1],
            });
        }
    }
    for (vertex, &zv) in z.iter().enumerate().take(z.len() - 1).skip(1) {
        for (height_index, &height) in heights.iter().enumerate() {
            if (height - zv).abs() <= tol {
                return Err(DevelopableError::HeightAtHelixVertex {
                    height_index,
                    height,
                    vertex,
                    vertex_height: zv,
                    relative: (height - zv).abs() / size,
                });
            }
        }
        for (j, w) in heights.windows(2).enumerate() {
            if (w[0] - zv) * (w[1] - zv) < 0.0 {
                return Err(DevelopableError::FaceCrossesHelix {
                    vertex,
                    vertex_height: zv,
                    j,
                    below: w[0],
                    above: w[1],
                });
            }
        }
    }
    Ok(())
}
