//! The smooth surface (§2.1.1, §4.4): [`darboux`], Darboux's construction of a
//! smooth surface with planar curvature lines, and [`cyclidic`], the C¹ net of
//! Dupin cyclide patches on the faces of a circular mesh.

pub mod cyclidic;
pub mod darboux;
