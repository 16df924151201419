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
//! The pipeline, one module per concept of the paper:
//! [`guide`] (sampled, validated guide curves, §3) →
//! [`gauss_map`] (normals along the guides, pencil axes, the discrete Gauss map, §2.1.2, §2.2.1, §3.2) →
//! [`combescure`] (the discrete Combescure transform, §2.2.3) → a [`QuadGrid`].
//! [`measure`] measures any quad mesh independently of how it was made.

pub mod approximate;
pub mod boundary;
pub mod combescure;
pub mod conical;
mod coords;
pub mod cyclidic;
pub mod darboux;
pub mod design;
pub mod developable;
pub mod fabrication;
pub mod gauss_map;
pub mod generate;
pub mod grid;
pub mod guide;
pub mod measure;
pub mod multipatch;
pub mod offset;
pub mod optimise;
pub mod panels;
pub mod projective;
pub mod scan;
pub mod symmetry;
pub mod tasks;

pub use design::{BasePoint, Design, GuideSpec, MeshKind, Tolerances};
pub use generate::{
    generate, inspect, DesignInfo, GenerateError, GenerateOptions, Generated, Mode,
    MIN_NORMAL_TURN, SINGULAR_WINDOW_DEG,
};
pub use grid::QuadGrid;
