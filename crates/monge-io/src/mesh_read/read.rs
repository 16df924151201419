//! Reading a mesh file or stream: its format from the extension (or given),
//! then the parser of that format.

use std::fs::File;
use std::io::{self, BufRead, BufReader, Read};
use std::path::{Path, PathBuf};

use glam::DVec3;
use monge_core::{MeshKind, QuadGrid};

use super::grid::Keep;
use super::json::{parse_json, parse_polygons_json};
use super::lines::read_failed;
use super::obj::parse_obj;
use super::ply::parse_ply;
use crate::error::IoError;
use crate::format::MeshFormat;
use crate::kind::unknown_extension;
use crate::read::{path_name, read_error};

/// Reads a quad grid from a `.json`, `.obj` or `.ply` file (by its extension).
///
/// * JSON: `rows`, `cols`, `vertices` and optional `normals`; other keys are ignored.
/// * OBJ: `v`, optional `vn` (one per vertex, in vertex order) and quad `f` lines.
/// * PLY (ASCII or `binary_little_endian`, any PLY scalar types): a `vertex`
///   element with `x y z` and optional `nx ny nz`, and a `face` element with
///   `vertex_indices` (or `vertex_index`).
///
/// For OBJ and PLY the grid shape comes from the comment `monge quad grid
/// rows=R cols=C` if present, else from the first face, which must be
/// `(0, C, C+1, 1)` (0-based) up to rotation and orientation. All faces are
/// then checked to be exactly the faces of the `R × C` grid, in any order.
///
/// `-` is refused with [`IoError::NeedFormat`]: use [`read_mesh_from`].
///
/// OBJ and PLY are parsed line by line (record by record) from a buffered
/// reader, so memory holds the mesh, not the file; JSON is read whole.
pub fn read_mesh(path: &Path) -> Result<QuadGrid, IoError> {
    read_mesh_and_kind(path).map(|(grid, _)| grid)
}

/// [`read_mesh`], and the kind of mesh the file says it is: a JSON mesh's `kind`
/// (`"circular"` or `"conical"`, as `monge generate` writes it); `None` for another
/// `kind` (`"developable"`), none, or an OBJ or PLY file, which do not say.
///
/// ```
/// use monge_core::MeshKind;
/// let dir = tempfile::tempdir().unwrap();
/// let path = dir.path().join("m.json");
/// std::fs::write(&path, r#"{"rows": 1, "cols": 1, "vertices": [[0, 0, 0]], "kind": "conical"}"#).unwrap();
/// let (grid, kind) = monge_io::read_mesh_and_kind(&path).unwrap();
/// assert_eq!((grid.rows, kind), (1, Some(MeshKind::Conical)));
/// ```
pub fn read_mesh_and_kind(path: &Path) -> Result<(QuadGrid, Option<MeshKind>), IoError> {
    let format = MeshFormat::from_path(path)?;
    if format == MeshFormat::Glb {
        return Err(not_readable(&path_name(path)));
    }
    let (reader, size) = open(path)?;
    parse_mesh(reader, format, size, &path_name(path))
}

/// The file `path`, buffered, and its length if it is a regular file.
fn open(path: &Path) -> Result<(BufReader<File>, Option<u64>), IoError> {
    let file = File::open(path).map_err(|source| read_error(path, source))?;
    let meta = file.metadata().map_err(|source| read_error(path, source))?;
    let size = meta.is_file().then_some(meta.len());
    Ok((BufReader::with_capacity(READ_BUFFER, file), size))
}

/// The vertices of an OBJ or PLY file (`format`), whatever its faces: the
/// points of a target of `monge approximate`.
pub(crate) fn read_vertices(path: &Path, format: MeshFormat) -> Result<Vec<DVec3>, IoError> {
    let (reader, size) = open(path)?;
    let file = path_name(path);
    let raw = match format {
        MeshFormat::Obj => parse_obj(reader, &file, Keep::Points)?,
        _ => parse_ply(reader, &file, size, Keep::Points)?,
    };
    Ok(raw.vertices)
}

/// The vertices and polygons of an OBJ, PLY or JSON file (by its extension; JSON with
/// `vertices` and `faces`) of faces of any number of corners (0-based corners), as
/// [`crate::write_trimmed_mesh_to`] writes a trimmed mesh; glTF is refused
/// ([`IoError::UnknownExtension`]).
///
/// ```
/// # use glam::DVec3;
/// let dir = std::env::temp_dir().join(format!("monge-polygons-{}", std::process::id()));
/// std::fs::create_dir_all(&dir).unwrap();
/// let path = dir.join("pentagon.obj");
/// let vertices = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(0.5, 1.5, 0.0), DVec3::ONE];
/// let faces = vec![vec![0, 1, 4, 3, 2]];
/// let mut text = Vec::new();
/// monge_io::write_polygons_obj(&vertices, &faces, "a pentagon", &mut text).unwrap();
/// std::fs::write(&path, text).unwrap();
/// assert_eq!(monge_io::read_polygons(&path).unwrap(), (vertices.to_vec(), faces));
/// # std::fs::remove_dir_all(&dir).unwrap();
/// ```
pub fn read_polygons(path: &Path) -> Result<(Vec<DVec3>, Vec<Vec<usize>>), IoError> {
    let format = MeshFormat::from_path(path)?;
    let (reader, size) = open(path)?;
    let file = path_name(path);
    let raw = match format {
        MeshFormat::Obj => parse_obj(reader, &file, Keep::Polygons)?,
        MeshFormat::Ply | MeshFormat::PlyBinary | MeshFormat::PlyF32 => {
            parse_ply(reader, &file, size, Keep::Polygons)?
        }
        MeshFormat::Json => {
            let mut text = String::new();
            let mut reader = reader;
            reader
                .read_to_string(&mut text)
                .map_err(|source| read_error(path, source))?;
            return parse_polygons_json(&text, &file);
        }
        MeshFormat::Glb => return Err(unknown_extension(path, "`.obj`, `.ply` or `.json`")),
    };
    Ok((raw.vertices, raw.polygons))
}

/// Reads a quad grid in `format` from a reader such as standard input (see [`read_mesh`]).
///
/// Errors name the input `<stdin>`.
///
/// ```
/// use monge_io::{read_mesh_from, MeshFormat};
/// let text = r#"{"rows": 1, "cols": 2, "vertices": [[0, 0, 0], [1, 0, 0]], "note": "ignored"}"#;
/// let grid = read_mesh_from(text.as_bytes(), MeshFormat::Json).unwrap();
/// assert_eq!((grid.rows, grid.cols), (1, 2));
/// ```
pub fn read_mesh_from(reader: impl Read, format: MeshFormat) -> Result<QuadGrid, IoError> {
    read_mesh_and_kind_from(reader, format).map(|(grid, _)| grid)
}

/// [`read_mesh_from`], and the kind of mesh the input says it is (see
/// [`read_mesh_and_kind`]).
pub fn read_mesh_and_kind_from(
    reader: impl Read,
    format: MeshFormat,
) -> Result<(QuadGrid, Option<MeshKind>), IoError> {
    parse_mesh(
        BufReader::with_capacity(READ_BUFFER, reader),
        format,
        None,
        "<stdin>",
    )
}

/// Bytes read from the input at a time.
const READ_BUFFER: usize = 1 << 16;

/// Reads a quad grid in `format` from `r` (`size` bytes long, when known),
/// and the kind a JSON mesh names.
fn parse_mesh(
    mut r: impl BufRead,
    format: MeshFormat,
    size: Option<u64>,
    file: &str,
) -> Result<(QuadGrid, Option<MeshKind>), IoError> {
    match format {
        MeshFormat::Json => {
            let mut bytes = Vec::new();
            r.read_to_end(&mut bytes)
                .map_err(|source| read_failed(file, source))?;
            let text = std::str::from_utf8(&bytes)
                .map_err(|e| read_failed(file, io::Error::new(io::ErrorKind::InvalidData, e)))?;
            parse_json(text, file)
        }
        MeshFormat::Obj => Ok((parse_obj(r, file, Keep::Grid)?.into_grid(file)?, None)),
        MeshFormat::Ply | MeshFormat::PlyBinary | MeshFormat::PlyF32 => {
            Ok((parse_ply(r, file, size, Keep::Grid)?.into_grid(file)?, None))
        }
        MeshFormat::Glb => Err(not_readable(file)),
    }
}

/// glTF is written for viewers (`f32`), never read back as a mesh to measure.
fn not_readable(file: &str) -> IoError {
    IoError::UnknownExtension {
        path: PathBuf::from(file),
        found:
            "glTF (`.glb`: monge writes it for viewers, with f32 coordinates, and does not read it)"
                .to_owned(),
        accepted: "`.obj`, `.ply` or `.json` (as written by monge)",
    }
}
