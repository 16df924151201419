//! Mesh readers: the JSON, OBJ and PLY (ASCII or binary little-endian) files
//! written by this crate, and OBJ/PLY quad grids from elsewhere whose vertices
//! are in row-major order.
//!
//! One idea per file: [`read`] opens the file or stream and picks the parser
//! by format; [`json`], [`obj`] and [`ply`] parse each format, through
//! [`lines`] for the line-based ones; [`grid`] turns what an OBJ or PLY file
//! says into a checked quad grid.

mod grid;
mod json;
mod lines;
mod obj;
mod ply;
mod read;

pub use json::read_face_normals;
pub(crate) use read::read_vertices;
pub use read::{
    read_mesh, read_mesh_and_kind, read_mesh_and_kind_from, read_mesh_from, read_polygons,
};
