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
//! [`GenerateOptions::max_vertices`](crate::generate::GenerateOptions::max_vertices)
//! before anything is built. Every helix vertex where two rulings meet (all but
//! the first and last) must lie outside the range of the cutting heights, or some
//! face would cross the helix.
//!
//! One file per idea: `spec` is the design file, `limits` the tolerance and size
//! limits, `checks` what the design must satisfy, `error` why it is refused, and
//! `mesh` builds the mesh.

mod checks;
mod error;
mod limits;
mod mesh;
mod spec;

pub use error::{DevelopableError, Field};
pub use limits::{MAX_EXTENT, MAX_HELIX_POINTS, MIN_EXTENT, TOLERANCE};
pub use mesh::{developable, DevelopableMesh};
pub use spec::{DevelopableDesign, DevelopableSpec, HelixSpec, ProjectionSpec};
