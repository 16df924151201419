//! IGES 5.3 output of exact NURBS surfaces (entity 128, rational B-spline
//! surface) and a minimal reader of the same entity.
//!
//! The writer produces a fixed-format ASCII file of 80-column lines: one Start
//! line, the Global section, two Directory Entry lines and the Parameter Data of
//! one entity 128, and the Terminate line. Every real is written as the
//! shortest decimal that parses back to the same `f64`, in `E` notation with a
//! decimal point (`1.0E0`, `-2.5E-1`), so the surface is exact.
//!
//! The reader ([`read_iges_surfaces`]) accepts any IGES 5.3 fixed ASCII file and
//! returns every entity 128 in it, with its transformation matrix (entity 124)
//! applied to the control points.

//!
//! One idea per file: [`fields`] the fixed format (lines, fields, reals);
//! [`columns`] the surface as the writer goes through it, [`check`] what the
//! writer refuses, [`write`] the writer; [`params`] and [`read`] the reader,
//! [`surface`] the surfaces it returns and their evaluation.

mod check;
mod columns;
mod fields;
mod params;
mod read;
mod surface;
mod write;

pub use columns::{NurbsColumn, NurbsColumns};
pub use read::read_iges_surfaces;
pub use surface::IgesSurface;
pub use write::write_iges;
