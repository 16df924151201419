//! The design tools (§4, §5): what a designer does with the construction.
//!
//! [`scan`] sweeps the design space (§4.3, §5.2), [`panels`] evens out panel
//! sizes (§4.8), [`boundary`] aligns a mesh with boundary planes (§4.5),
//! [`symmetry`] mirrors and assembles (§4.5, §4.7), [`multipatch`] joins patches
//! with piecewise planar curvature lines (§4.7), [`optimise`] fits a multi-patch
//! design to a target (§4.7), and [`approximate`] finds the design nearest a
//! target shape.
//!
//! They build on the construction and on measurement; nothing below depends on
//! them.

pub mod approximate;
pub mod boundary;
pub mod multipatch;
pub mod optimise;
pub mod panels;
pub mod scan;
pub mod symmetry;
