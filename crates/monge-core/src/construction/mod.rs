//! The construction (§2, §3): from two planar guide curves and an angle θ to an
//! exact circular or conical quad mesh.
//!
//! The pipeline runs [`design`] (the input, §3) → [`guide`] (sampled, validated
//! guides, §3) → [`gauss_map`] (normals, pencil axes and the discrete Gauss map,
//! §2.1.2, §2.2.1, §3.2) → [`combescure`] (the discrete Combescure transform,
//! §2.2.3) → a [`grid::QuadGrid`]; [`generate`](mod@generate) runs it whole. [`conical`] is its
//! dual (§2.3), [`offset`] its offsets (§2.2, §2.3), [`developable`] the
//! developable family (§2.1.3, §3.3). [`projective`] holds the homogeneous points,
//! Plücker lines and planes that keep axes at infinity exact; [`bspline`] evaluates
//! B-spline and NURBS curves and basis functions.
//!
//! Nothing here depends on the other folders: measurement, the smooth surface,
//! fabrication and the design tools build on it.

pub mod bspline;
pub mod combescure;
pub mod conical;
pub(crate) mod coords;
pub mod design;
pub mod developable;
pub mod gauss_map;
pub mod generate;
pub mod grid;
pub mod guide;
pub mod offset;
pub mod projective;
