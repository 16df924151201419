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

mod atomic;
mod design;
mod dxf;
mod error;
mod fabrication;
pub mod generated;
mod gltf;
mod iges;
mod kind;
mod mesh_read;
mod mesh_write;
mod multipatch;
mod net;
mod points_read;
mod schedule;
mod svg;
mod text;

use std::fs::{File, Metadata};
use std::io::{self, Read};
use std::path::Path;

pub use atomic::{check_output, is_stdio, write_atomic, write_output, Outputs, STALE};
pub use design::{
    parse_any_design, parse_design, parse_design_named, read_any_design, read_design, write_design,
    write_design_into, write_design_to, AnyDesign, DesignFormat, MAX_DESIGN_BYTES,
};
pub use dxf::{write_beams_dxf, write_panels_dxf};
pub use error::IoError;
pub use fabrication::{check_fabrication_output, write_fabrication, FABRICATION_FILES};
pub use gltf::{write_glb, write_grid_glb, write_quads_glb};
pub use iges::{read_iges_surfaces, write_iges, IgesSurface, NurbsColumn, NurbsColumns};
pub use kind::FileKind;
pub use mesh_read::{
    read_face_normals, read_mesh, read_mesh_and_kind, read_mesh_and_kind_from, read_mesh_from,
};
pub use mesh_write::{
    write_mesh, write_mesh_at, write_mesh_json, write_mesh_to, write_obj, write_ply,
    write_ply_binary, MeshFormat, BASE_POINT, MESH_JSON_KEYS,
};
pub use multipatch::{
    parse_multipatch, parse_planes, read_multipatch, read_planes, write_multipatch,
    write_multipatch_into, write_quad_mesh, write_quad_mesh_to,
};
pub use net::{conical_has_no_net, write_net_json};
pub use points_read::{read_points, IGES_TARGET_POINTS};
pub use schedule::{
    beam_label, panel_label, write_beams_csv, write_nodes_csv, write_panels_csv,
    write_schedule_json, write_segments_csv, ScheduleJson,
};
pub use svg::write_overview_svg;

/// The whole file as text (see [`read_file`]); invalid UTF-8 is [`IoError::Read`].
fn read_to_string(path: &Path) -> Result<String, IoError> {
    utf8(path, read_file(path)?)
}

/// `bytes` of the file `path` as text; invalid UTF-8 is [`IoError::Read`].
fn utf8(path: &Path, bytes: Vec<u8>) -> Result<String, IoError> {
    String::from_utf8(bytes).map_err(|e| IoError::Read {
        path: path.to_owned(),
        source: io::Error::new(io::ErrorKind::InvalidData, e.utf8_error()),
    })
}

/// The whole file; [`IoError::NotFound`], [`IoError::Read`] or
/// [`IoError::Changed`] naming it.
///
/// A regular file that is truncated, extended or rewritten while it is read
/// is [`IoError::Changed`], told by its length and modification time before
/// and after. A file removed or renamed over while it is read is still read
/// whole: the open file keeps its contents.
fn read_file(path: &Path) -> Result<Vec<u8>, IoError> {
    let file = File::open(path).map_err(|source| read_error(path, source))?;
    let opened = file.metadata().map_err(|source| read_error(path, source))?;
    read_unchanged(path, file, &opened, u64::MAX)
}

/// Reads `file` (the file `path` as it was `opened`) to its end, or its first
/// `limit` bytes, checking that it did not change meanwhile (see [`read_file`]).
fn read_unchanged(
    path: &Path,
    file: File,
    opened: &Metadata,
    limit: u64,
) -> Result<Vec<u8>, IoError> {
    let err = |source| read_error(path, source);
    let mut bytes = Vec::new();
    (&file).take(limit).read_to_end(&mut bytes).map_err(err)?;
    let now = file.metadata().map_err(err)?;
    let read = bytes.len() as u64;
    let same = read == opened.len()
        && now.len() == opened.len()
        && now.modified().ok() == opened.modified().ok();
    if opened.is_file() && !same {
        return Err(IoError::Changed {
            path: path.to_owned(),
            opened: opened.len(),
            read,
            now: now.len(),
        });
    }
    Ok(bytes)
}

/// [`IoError::NotFound`] or [`IoError::Read`] naming `path`.
fn read_error(path: &Path, source: io::Error) -> IoError {
    match source.kind() {
        io::ErrorKind::NotFound => IoError::NotFound {
            path: path.to_owned(),
        },
        _ => IoError::Read {
            path: path.to_owned(),
            source,
        },
    }
}

/// The path as shown in error messages.
fn path_name(path: &Path) -> String {
    path.display().to_string()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;
    use std::time::Duration;

    /// A file of 1000 bytes in a fresh directory, opened, with its metadata.
    fn opened(dir: &tempfile::TempDir) -> (std::path::PathBuf, File, Metadata) {
        let path = dir.path().join("d.json");
        std::fs::write(&path, [b' '; 1000]).unwrap();
        let file = File::open(&path).unwrap();
        let meta = file.metadata().unwrap();
        (path, file, meta)
    }

    fn changed(result: Result<Vec<u8>, IoError>) -> (u64, u64, u64, String) {
        match result {
            Err(
                e @ IoError::Changed {
                    opened, read, now, ..
                },
            ) => (opened, read, now, e.to_string()),
            other => panic!("expected Changed, got {other:?}"),
        }
    }

    #[test]
    fn a_file_truncated_while_read_is_changed() {
        let dir = tempfile::tempdir().unwrap();
        let (path, file, meta) = opened(&dir);
        let other = std::fs::OpenOptions::new().write(true).open(&path).unwrap();
        other.set_len(10).unwrap();
        let (opened, read, now, message) = changed(read_unchanged(&path, file, &meta, u64::MAX));
        assert_eq!((opened, read, now), (1000, 10, 10));
        assert!(
            message.contains("d.json` changed while it was being read"),
            "{message}"
        );
        assert!(
            message.contains("1000 bytes when opened, 10 were read"),
            "{message}"
        );
    }

    #[test]
    fn a_file_extended_while_read_is_changed() {
        let dir = tempfile::tempdir().unwrap();
        let (path, file, meta) = opened(&dir);
        let mut other = std::fs::OpenOptions::new()
            .append(true)
            .open(&path)
            .unwrap();
        other.write_all(&[b' '; 24]).unwrap();
        let (opened, read, now, _) = changed(read_unchanged(&path, file, &meta, u64::MAX));
        assert_eq!((opened, read, now), (1000, 1024, 1024));
    }

    #[test]
    fn a_file_rewritten_in_place_while_read_is_changed() {
        let dir = tempfile::tempdir().unwrap();
        let (path, file, meta) = opened(&dir);
        let mut other = std::fs::OpenOptions::new().write(true).open(&path).unwrap();
        other.write_all(&[b'x'; 1000]).unwrap();
        // The same length: only the modification time tells (set apart from
        // the clock's granularity).
        let later = meta.modified().unwrap() + Duration::from_secs(1);
        other.set_modified(later).unwrap();
        let (opened, read, now, _) = changed(read_unchanged(&path, file, &meta, u64::MAX));
        assert_eq!((opened, read, now), (1000, 1000, 1000));
    }

    #[test]
    fn a_file_removed_while_read_is_read_whole() {
        let dir = tempfile::tempdir().unwrap();
        let (path, file, meta) = opened(&dir);
        std::fs::remove_file(&path).unwrap();
        let bytes = read_unchanged(&path, file, &meta, u64::MAX).unwrap();
        assert_eq!(bytes, [b' '; 1000]);
    }
}
