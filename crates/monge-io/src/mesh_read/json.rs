//! The mesh JSON format (`rows`, `cols`, `vertices`, optional `normals`, and
//! a conical mesh's `face_normals`).

use std::path::Path;

use glam::DVec3;
use monge_core::{MeshKind, QuadGrid};
use serde::Deserialize;

use super::grid::grid;
use crate::design::parse_as;
use crate::error::IoError;
use crate::format::{DesignFormat, FileKind, MeshFormat};
use crate::kind::expect_kind;
use crate::read::{path_name, read_error};

#[derive(Deserialize)]
struct MeshJson {
    rows: usize,
    cols: usize,
    vertices: Vec<[f64; 3]>,
    #[serde(default)]
    normals: Vec<[f64; 3]>,
    /// Any value: only a mesh kind's name is taken.
    #[serde(default)]
    kind: serde_json::Value,
}

pub(super) fn parse_json(text: &str, file: &str) -> Result<(QuadGrid, Option<MeshKind>), IoError> {
    expect_kind(text, DesignFormat::Json, file, &[FileKind::Mesh])?;
    let m: MeshJson = parse_as(text, DesignFormat::Json, file)?;
    let kind = serde_json::from_value(m.kind).ok();
    let vertices = m.vertices.into_iter().map(DVec3::from_array).collect();
    let normals = m.normals.into_iter().map(DVec3::from_array).collect();
    Ok((grid(file, m.rows, m.cols, vertices, normals)?, kind))
}

/// A mesh of polygons as JSON (`vertices`, `faces` of 0-based corners, as
/// [`write_trimmed_mesh_to`](crate::write_trimmed_mesh_to) writes a trimmed mesh; other
/// keys are read past): each face of three or more of the vertices.
pub(super) fn parse_polygons_json(
    text: &str,
    file: &str,
) -> Result<(Vec<DVec3>, Vec<Vec<usize>>), IoError> {
    #[derive(Deserialize)]
    struct PolygonsJson {
        vertices: Vec<[f64; 3]>,
        faces: Vec<Vec<usize>>,
    }
    let m: PolygonsJson = parse_as(text, DesignFormat::Json, file)?;
    let n = m.vertices.len();
    if let Some(k) = m
        .faces
        .iter()
        .position(|f| f.len() < 3 || f.iter().any(|c| *c >= n))
    {
        return Err(IoError::Parse {
            file: file.to_owned(),
            line: 0,
            column: 0,
            message: format!(
                "faces[{k}] has corners {:?} (0-based), not three or more of the {n} vertices",
                m.faces[k]
            ),
            snippet: String::new(),
        });
    }
    Ok((
        m.vertices.into_iter().map(DVec3::from_array).collect(),
        m.faces,
    ))
}

/// The `face_normals` of a conical mesh's JSON file (§2.3, as `monge generate`
/// writes them), one per face of `grid` (the mesh read from it); `None` for a
/// file of another format or without the key.
///
/// # Errors
/// Those of [`read_mesh`](crate::read_mesh) for the file, and [`IoError::CountMismatch`] if the
/// normals are not one per face.
pub fn read_face_normals(path: &Path, grid: &QuadGrid) -> Result<Option<Vec<DVec3>>, IoError> {
    if MeshFormat::from_path(path)? != MeshFormat::Json {
        return Ok(None);
    }
    #[derive(Deserialize)]
    struct FaceNormals {
        #[serde(default)]
        face_normals: Option<Vec<[f64; 3]>>,
    }
    let file = path_name(path);
    let text = std::fs::read_to_string(path).map_err(|source| read_error(path, source))?;
    let n: FaceNormals = parse_as(&text, DesignFormat::Json, &file)?;
    let Some(normals) = n.face_normals else {
        return Ok(None);
    };
    if normals.len() != grid.face_count() {
        return Err(IoError::CountMismatch {
            file,
            what: format!(
                "face_normals (one per face of the {} × {} grid)",
                grid.rows, grid.cols
            ),
            expected: grid.face_count(),
            found: normals.len(),
        });
    }
    Ok(Some(normals.into_iter().map(DVec3::from_array).collect()))
}
