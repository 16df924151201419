//! The whole generation method of §3: guides → Gauss map → Combescure transform.

use crate::design::{Design, Tolerances};
use crate::grid::QuadGrid;
use crate::guide::{GuideError, GuideName};

/// Options of [`generate`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GenerateOptions {
    /// Largest number of grid vertices (`rows · cols`) accepted; larger grids are
    /// refused before anything is allocated. Default `25_000_000` (about 1.2 GB
    /// of vertices and normals).
    pub max_vertices: usize,
}

impl Default for GenerateOptions {
    fn default() -> Self {
        GenerateOptions {
            max_vertices: 25_000_000,
        }
    }
}

/// Everything wrong with a design that stops generation (§3, §5.2).
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum GenerateError {
    /// A guide curve is invalid.
    #[error(transparent)]
    Guide(#[from] GuideError),
    /// Placeholder while the generator is written.
    #[error("{0}")]
    Other(String),
}

/// What [`generate`] returns: the mesh and what was learnt on the way.
#[derive(Clone, Debug)]
pub struct Generated {
    /// The circular mesh with its node axes.
    pub grid: QuadGrid,
}

/// Generate the circular mesh with planar curvature lines of `design` (§3).
pub fn generate(design: &Design, options: &GenerateOptions) -> Result<Generated, GenerateError> {
    let _ = (design, options, Tolerances::default(), GuideName::U);
    Err(GenerateError::Other("not yet".into()))
}
