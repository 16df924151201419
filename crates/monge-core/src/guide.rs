//! Guide curves (§3): sampled, validated, planar.
use glam::DVec3;

/// Which guide (for messages).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GuideName {
    /// `guide_u`.
    U,
    /// `guide_v`.
    V,
}

/// A validated guide.
#[derive(Clone, Debug)]
pub struct Guide {
    /// Samples.
    pub points: Vec<DVec3>,
}

/// Invalid guide.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum GuideError {
    /// placeholder
    #[error("{0:?}")]
    Todo(GuideName),
}
