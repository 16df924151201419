//! File input and output for monge: design files, mesh exporters and readers.
//!
//! * Design files ([`read_design`], [`parse_design`], [`write_design`]): a
//!   [`Design`](monge_core::Design) as JSON or TOML, chosen by extension. Errors
//!   name the file, the line and column, and what was expected; NaN and
//!   infinities (which TOML allows) are refused.
//! * Mesh writers ([`write_mesh`], [`write_obj`], [`write_ply`],
//!   [`write_mesh_json`]): a [`QuadGrid`](monge_core::QuadGrid) as OBJ, ASCII
//!   PLY or JSON, every coordinate written so that it parses back to the same
//!   `f64`. Files are written atomically ([`write_atomic`]); `-` is standard output.
//! * Mesh readers ([`read_mesh`], [`read_mesh_from`]) for the same three formats,
//!   checking that the file really is a row-major quad grid.
//!
//! Every fallible function returns an [`IoError`].
//!
//! ```
//! use monge_io::{parse_design, DesignFormat};
//! let design = parse_design(r#"{
//!     "theta_deg": 30.0,
//!     "guide_u": { "points": [[0, 0, 0], [1, 0, 0.2], [2, 0, 0.7]] },
//!     "guide_v": { "bspline": { "degree": 3, "control_points": [[0, 0, 0], [0, 1, 0], [0, 2, 0.5], [0, 3, 1.5]], "samples": 41 } }
//! }"#, DesignFormat::Json).unwrap();
//! assert_eq!(design.guide_v.sample_count(), 41);
//! ```

#![warn(missing_docs)]

mod any;
mod atomic;
mod design;
mod dxf;
mod error;
mod fabrication;
mod faces;
mod format;
pub mod generated;
mod gltf;
mod iges;
mod kind;
mod mesh_read;
mod mesh_write;
mod multipatch;
mod net;
mod points_read;
mod polygons;
mod read;
mod scan;
mod schedule;
mod stl;
mod svg;
mod text;
mod trimmed;

pub use any::{parse_any_design, read_any_design, AnyDesign};
pub use atomic::{check_output, is_stdio, write_atomic, write_output, Outputs, STALE};
pub use design::{
    parse_design, parse_design_named, read_design, write_design, write_design_into,
    write_design_to, MAX_DESIGN_BYTES,
};
pub use dxf::{write_beams_dxf, write_panels_dxf};
pub use error::IoError;
pub use fabrication::{check_fabrication_output, write_fabrication, FABRICATION_FILES};
pub use format::{DesignFormat, FileKind, MeshFormat};
pub use gltf::{write_glb, write_grid_glb, write_quads_glb};
pub use iges::{read_iges_surfaces, write_iges, IgesSurface, NurbsColumn, NurbsColumns};
pub use mesh_read::{
    read_face_normals, read_mesh, read_mesh_and_kind, read_mesh_and_kind_from, read_mesh_from,
    read_polygons,
};
pub use mesh_write::{
    write_mesh, write_mesh_at, write_mesh_json, write_mesh_to, write_obj, write_ply,
    write_ply_binary, BASE_POINT, MESH_JSON_KEYS,
};
pub use multipatch::{
    parse_multipatch, parse_planes, read_multipatch, read_planes, write_multipatch,
    write_multipatch_into, write_quad_mesh, write_quad_mesh_to,
};
pub use net::{conical_has_no_net, write_net_json};
pub use points_read::{read_points, read_text_points, surface_parameters, IGES_TARGET_POINTS};
pub use polygons::{write_polygons_obj, write_trimmed_mesh_to, MAX_CORNERS};
pub use scan::{write_scan_csv, write_scan_svg, SCAN_CSV_HEADER};
pub use schedule::{
    beam_label, panel_label, write_beams_csv, write_nodes_csv, write_panels_csv,
    write_schedule_json, write_segments_csv, ScheduleJson,
};
pub use stl::read_stl_points;
pub use svg::write_overview_svg;
pub use trimmed::{write_trimmed, write_trimmed_into, Trimmable, TrimmedDesign, TrimmedMeshError};
