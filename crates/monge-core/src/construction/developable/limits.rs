//! The tolerance and the size limits of a developable design (§3.3).

/// Relative tolerance of every check (§3.3): lengths relative to the design size
/// (see [`DevelopableError`](super::DevelopableError)), slopes relative to the
/// mean slope, angles in radians.
pub const TOLERANCE: f64 = 1e-9;

/// Largest absolute coordinate or height accepted (§3.3).
pub const MAX_EXTENT: f64 = 1e100;

/// Smallest non-zero largest absolute coordinate or height accepted (§3.3).
pub const MIN_EXTENT: f64 = 1e-100;

/// Most helix points accepted (§3.3): the check that the helix does not cross
/// itself compares every pair of segments, about half a million pairs at this
/// count. Each point is a ruling, a row of panels: Figure 11 has 24.
pub const MAX_HELIX_POINTS: usize = 1000;
