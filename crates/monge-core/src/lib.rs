//! # monge-core
//!
//! Pure geometry of circular and conical quad meshes whose curvature lines are
//! planar, generated exactly from two planar guide curves and one angle θ. No
//! I/O, no printing.
//!
//! The method, and the § numbers cited throughout these docs, are those of
//! X. Tellier, C. Douthe, L. Hauswirth, O. Baverel, *Surfaces with planar
//! curvature lines: discretization, generation and application to the
//! rationalization of curved architectural envelopes*, Automation in
//! Construction 106 (2019) 102880, doi:10.1016/j.autcon.2019.102880.
//!
//! The source is laid out in folders, one part of the paper each:
//!
//! | folder | what | modules |
//! |---|---|---|
//! | `construction/` | the generation method (§2, §3) | [`design`], [`guide`], [`bspline`], [`projective`], [`gauss_map`], [`combescure`], [`grid`], [`generate`](mod@generate), [`conical`], [`offset`], [`developable`] |
//! | `measure/` | measuring any quad mesh, however it was made (§2.2, §2.3) | [`measure`] |
//! | `smooth/` | the smooth surface (§2.1.1, §4.4) | [`darboux`], [`cyclidic`] |
//! | `fabrication/` | the gridshell's parts (§6) | [`fabrication`] |
//! | `tools/` | the design tools (§4, §5) | [`scan`], [`panels`], [`boundary`], [`symmetry`], [`multipatch`], [`optimise`], [`approximate`] |
//!
//! Layers point one way: `construction` depends on no other folder; `measure`
//! on `construction`'s grid only; `smooth` and `fabrication` on those two;
//! `tools` on all of them. The modules are re-exported here, so a path is
//! `monge_core::guide`, whichever folder holds it.

mod construction;
pub mod fabrication;
pub mod measure;
mod smooth;
pub mod tasks;
mod tools;

pub(crate) use construction::coords;
pub use construction::{
    bspline, combescure, conical, design, developable, gauss_map, generate, grid, guide, offset,
    projective,
};
pub use smooth::{cyclidic, darboux};
pub use tools::{approximate, boundary, multipatch, optimise, panels, scan, symmetry};

pub use design::{BasePoint, Design, GuideSpec, MeshKind, Tolerances};
pub use generate::{
    generate, inspect, DesignInfo, GenerateError, GenerateOptions, Generated, Mode,
    MIN_NORMAL_TURN, SINGULAR_WINDOW_DEG,
};
pub use grid::QuadGrid;
