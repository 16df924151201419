//! Multi-patch design files (§4.7), planes files and assembled quad meshes (§4.5).

use std::io::{self, Write};
use std::path::Path;

use monge_core::boundary::BoundarySpec;
use monge_core::multipatch::MultiPatchDesign;
use monge_core::symmetry::QuadMesh;

use crate::atomic::{write_output, Outputs};
use crate::design::{expect_design, parse_as, read_design_text, write_pretty};
use crate::error::IoError;
use crate::format::{DesignFormat, FileKind, MeshFormat};
use crate::gltf::write_quads_glb;
use crate::mesh_write::Quads;
use crate::read::path_name;

/// Reads a multi-patch design file (§4.7), JSON or TOML by its extension.
///
/// The keys are those of [`MultiPatchDesign`]: `patches` (the first with
/// `theta_deg`, `guide_u`, `guide_v`; the others with `theta_deg`, `attach`
/// `{patch, side}` and `guide`), optional `tolerance`, `fit` and `symmetry`.
/// Errors as [`crate::read_design`]: unknown extension, missing file, parse
/// errors with line and column, non-finite numbers (TOML's `nan`, `inf`).
pub fn read_multipatch(path: &Path) -> Result<MultiPatchDesign, IoError> {
    let format = DesignFormat::from_path(path)?;
    let text = read_design_text(path)?;
    parse_multipatch_named(&text, format, &path_name(path))
}

/// Parses the text of a multi-patch design file (§4.7); errors name the file `<input>`.
///
/// ```
/// use monge_io::{parse_multipatch, DesignFormat};
/// let d = parse_multipatch(r#"{"patches": [
///   {"theta_deg": 30, "guide_u": {"points": [[0,0,0],[1,0,0.2],[2,0,0.7]]},
///                     "guide_v": {"points": [[0,0,0],[0,1,0.1],[0,2,0.5]]}},
///   {"theta_deg": -20, "attach": {"patch": 0, "side": "last_row"},
///    "guide": {"points": [[2,0,0.7],[3,0,1.5],[4,0,2.6]]}}]}"#, DesignFormat::Json).unwrap();
/// assert_eq!(d.patches.len(), 2);
/// ```
pub fn parse_multipatch(text: &str, format: DesignFormat) -> Result<MultiPatchDesign, IoError> {
    parse_multipatch_named(text, format, "<input>")
}

fn parse_multipatch_named(
    text: &str,
    format: DesignFormat,
    file: &str,
) -> Result<MultiPatchDesign, IoError> {
    expect_design(text, format, file, &[FileKind::MultiPatch])?;
    parse_as(text, format, file)
}

/// Reads a planes file (§4.5): the four boundary planes of `monge align`, JSON or
/// TOML by its extension, with the errors of [`read_multipatch`].
pub fn read_planes(path: &Path) -> Result<BoundarySpec, IoError> {
    let format = DesignFormat::from_path(path)?;
    let text = read_design_text(path)?;
    parse_planes_named(&text, format, &path_name(path))
}

/// Parses the text of a planes file (§4.5), as [`read_planes`] does; errors
/// name the file `<input>`.
pub fn parse_planes(text: &str, format: DesignFormat) -> Result<BoundarySpec, IoError> {
    parse_planes_named(text, format, "<input>")
}

fn parse_planes_named(
    text: &str,
    format: DesignFormat,
    file: &str,
) -> Result<BoundarySpec, IoError> {
    expect_design(text, format, file, &[FileKind::Planes])?;
    parse_as(text, format, file)
}

/// Writes a multi-patch design (§4.7), pretty JSON or TOML by the path's extension, atomically.
pub fn write_multipatch(design: &MultiPatchDesign, path: &Path) -> Result<(), IoError> {
    let mut out = Outputs::new();
    write_multipatch_into(design, path, &mut out)?;
    out.commit()
}

/// [`write_multipatch`] as one of several files of `out`, put in place by its commit.
pub fn write_multipatch_into(
    design: &MultiPatchDesign,
    path: &Path,
    out: &mut Outputs,
) -> Result<(), IoError> {
    let format = DesignFormat::from_path(path)?;
    out.write(path, |w| write_pretty(design, format, w))
}

/// Writes an assembled [`QuadMesh`] (§4.5) to `path` (atomically, `-` for standard
/// output with `format`): OBJ (`v`, `vn`, `f a//a …`), ASCII PLY (vertices with
/// `nx ny nz`, quads) or JSON (`{"vertices", "normals", "quads"}`, 0-based), every
/// coordinate written so that it reads back to the same `f64`.
///
/// ```
/// use glam::DVec3;
/// use monge_core::symmetry::QuadMesh;
/// # let dir = tempfile::tempdir().unwrap();
/// let mesh = QuadMesh { vertices: vec![DVec3::ZERO, DVec3::X, DVec3::ONE, DVec3::Y],
///                       normals: vec![DVec3::Z; 4], quads: vec![[0, 1, 2, 3]] };
/// let path = dir.path().join("m.obj");
/// monge_io::write_quad_mesh(&mesh, &path, None).unwrap();
/// assert!(std::fs::read_to_string(&path).unwrap().contains("f 1//1 2//2 3//3 4//4"));
/// ```
pub fn write_quad_mesh(
    mesh: &QuadMesh,
    path: &Path,
    format: Option<MeshFormat>,
) -> Result<(), IoError> {
    let format = match format {
        Some(f) => f,
        None => MeshFormat::from_path(path)?,
    };
    write_output(path, |w| write_quad_mesh_to(mesh, format, w))
}

/// Writes an assembled [`QuadMesh`] to `w` in `format` (§4.5); see [`write_quad_mesh`].
pub fn write_quad_mesh_to<W: Write + ?Sized>(
    mesh: &QuadMesh,
    format: MeshFormat,
    w: &mut W,
) -> io::Result<()> {
    if mesh
        .vertices
        .iter()
        .chain(&mesh.normals)
        .any(|p| !p.is_finite())
    {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            "the mesh has a non-finite coordinate",
        ));
    }
    let comment = format!(
        "monge quad mesh vertices={} quads={}",
        mesh.vertices.len(),
        mesh.quads.len()
    );
    let quads = Quads {
        vertices: &mesh.vertices,
        normals: &mesh.normals,
        faces: &mesh.quads[..],
        comment,
        base: None,
    };
    match format {
        MeshFormat::Obj => quads.obj(w),
        MeshFormat::Ply => quads.ply(w),
        MeshFormat::PlyBinary => quads.ply_binary(false, w),
        MeshFormat::PlyF32 => quads.ply_binary(true, w),
        MeshFormat::Json => {
            let arr =
                |v: &[glam::DVec3]| -> Vec<[f64; 3]> { v.iter().map(|p| p.to_array()).collect() };
            let value = serde_json::json!({
                "vertices": arr(&mesh.vertices),
                "normals": arr(&mesh.normals),
                "quads": mesh.quads,
            });
            serde_json::to_writer(&mut *w, &value)?;
            w.write_all(b"\n")
        }
        MeshFormat::Glb => write_quads_glb(&mesh.vertices, mesh.quads.iter().copied(), w),
    }
}
