//! A mesh of polygons, a grid trimmed to an outline ([`TrimmedMesh`]), in every mesh
//! format: OBJ and PLY with its polygons as they are, JSON with its polygons and
//! which of them the outline cut, glTF as triangles.

use std::io::{self, Write};

use glam::DVec3;
use monge_core::approximate::TrimmedMesh;

use crate::format::MeshFormat;
use crate::gltf::write_faces_glb;
use crate::mesh_write::Quads;
use crate::text::emit;

/// Most corners of a face: PLY counts a face's corners in a byte.
pub const MAX_CORNERS: usize = 255;

/// Writes `mesh` to `w` in `format`: OBJ ([`write_polygons_obj`]) and PLY (ASCII or
/// binary, `list uchar int vertex_indices` of each face's corners) with its polygons as
/// they are, `comment` in their header; JSON as `{"vertices": [[x, y, z], …], "faces":
/// [[a, b, c, …], …], "cut": [false, true, …]}` (0-based corners, and of each face
/// whether the outline cut it); glTF (`.glb`, `f32` positions, for looking at it) as
/// triangles: each face the outline did not cut split along a diagonal, each cut one
/// in its plane ([`TrimmedMesh::mesh_faces`]). Every coordinate but glTF's reads back
/// to the same `f64`.
///
/// Fails with [`io::ErrorKind::InvalidInput`] on a non-finite coordinate (of PLY
/// `float`, beyond ±3.4e38), a face of fewer than three or more than [`MAX_CORNERS`]
/// corners or a corner out of range, or a `cut` of another length than the faces,
/// before writing anything.
///
/// ```
/// use glam::DVec3;
/// use monge_core::approximate::TrimmedMesh;
/// use monge_io::{write_trimmed_mesh_to, MeshFormat};
/// let mesh = TrimmedMesh {
///     vertices: vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::new(0.5, 1.5, 0.0), DVec3::Y],
///     faces: vec![vec![0, 1, 2, 3, 4]],
///     from: vec![(0, 0)],
///     cut: vec![true],
/// };
/// let mut ply = Vec::new();
/// write_trimmed_mesh_to(&mesh, MeshFormat::Ply, "a pentagon", &mut ply).unwrap();
/// assert!(String::from_utf8(ply).unwrap().ends_with("end_header\n0.0 0.0 0.0\n1.0 0.0 0.0\n\
///     1.0 1.0 0.0\n0.5 1.5 0.0\n0.0 1.0 0.0\n5 0 1 2 3 4\n"));
/// let mut json = Vec::new();
/// write_trimmed_mesh_to(&mesh, MeshFormat::Json, "", &mut json).unwrap();
/// assert!(String::from_utf8(json).unwrap().ends_with("\"faces\":[[0,1,2,3,4]],\"cut\":[true]}\n"));
/// ```
pub fn write_trimmed_mesh_to<W: Write + ?Sized>(
    mesh: &TrimmedMesh,
    format: MeshFormat,
    comment: &str,
    w: &mut W,
) -> io::Result<()> {
    check_polygons(&mesh.vertices, &mesh.faces)?;
    if mesh.cut.len() != mesh.faces.len() {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!(
                "the mesh says whether the outline cut {} faces, but it has {}",
                mesh.cut.len(),
                mesh.faces.len()
            ),
        ));
    }
    let faces: &[Vec<usize>] = &mesh.faces;
    let quads = || Quads {
        vertices: &mesh.vertices,
        normals: &[],
        faces,
        comment: comment.to_owned(),
        base: None,
    };
    match format {
        MeshFormat::Obj => write_polygons_obj(&mesh.vertices, &mesh.faces, comment, w),
        MeshFormat::Ply => quads().ply(w),
        MeshFormat::PlyBinary => quads().ply_binary(false, w),
        MeshFormat::PlyF32 => {
            check_f32(&mesh.vertices)?;
            quads().ply_binary(true, w)
        }
        MeshFormat::Json => write_json(mesh, w),
        MeshFormat::Glb => write_faces_glb(&mesh.vertices, &mesh.mesh_faces(), w),
    }
}

/// Writes a mesh of polygons (a grid trimmed to a target's outline) as OBJ: the
/// header comment `# COMMENT`, `v x y z` per vertex and `f a b c …` per face, 1-based.
/// Fails as [`write_trimmed_mesh_to`] does, before writing anything.
///
/// ```
/// # use glam::DVec3;
/// let vertices = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(0.5, 1.5, 0.0), DVec3::ONE];
/// let mut out = Vec::new();
/// monge_io::write_polygons_obj(&vertices, &[vec![0, 1, 4, 3, 2]], "a pentagon", &mut out)
///     .unwrap();
/// assert!(String::from_utf8(out).unwrap().ends_with("v 1 1 1\nf 1 2 5 4 3\n"));
/// ```
pub fn write_polygons_obj<W: Write + ?Sized>(
    vertices: &[DVec3],
    faces: &[Vec<usize>],
    comment: &str,
    w: &mut W,
) -> io::Result<()> {
    check_polygons(vertices, faces)?;
    let mut text = format!("# {comment}\n");
    for v in vertices {
        text += &format!("v {} {} {}\n", v.x, v.y, v.z);
    }
    for f in faces {
        text.push('f');
        for c in f {
            text += &format!(" {}", c + 1);
        }
        text.push('\n');
    }
    w.write_all(text.as_bytes())
}

/// The JSON of [`write_trimmed_mesh_to`].
fn write_json<W: Write + ?Sized>(mesh: &TrimmedMesh, w: &mut W) -> io::Result<()> {
    w.write_all(b"{\"vertices\":[")?;
    emit(w, |out| {
        out.each(&mesh.vertices, |o, k, p| {
            o.str(if k == 0 { "\n[" } else { ",\n[" });
            o.xyz(*p, b',');
            o.push(b']');
        })?;
        out.str("\n],\"faces\":");
        Ok(())
    })?;
    serde_json::to_writer(&mut *w, &mesh.faces)?;
    w.write_all(b",\"cut\":")?;
    serde_json::to_writer(&mut *w, &mesh.cut)?;
    w.write_all(b"}\n")
}

/// Refuses a non-finite vertex, a face of fewer than three or more than
/// [`MAX_CORNERS`] corners, or a corner that is not one of the vertices.
fn check_polygons(vertices: &[DVec3], faces: &[Vec<usize>]) -> io::Result<()> {
    let invalid = |m: String| Err(io::Error::new(io::ErrorKind::InvalidInput, m));
    if let Some(k) = vertices.iter().position(|v| !v.is_finite()) {
        return invalid(format!("vertex {k} is not finite: {:?}", vertices[k]));
    }
    if let Some(k) = faces.iter().position(|f| {
        !(3..=MAX_CORNERS).contains(&f.len()) || f.iter().any(|c| *c >= vertices.len())
    }) {
        return invalid(format!(
            "face {k} has corners {:?}, not three to {MAX_CORNERS} of the {} vertices",
            faces[k],
            vertices.len()
        ));
    }
    Ok(())
}

/// Refuses a vertex beyond `f32`'s range (±3.4e38), which a `float` PLY would hold as
/// infinite.
fn check_f32(vertices: &[DVec3]) -> io::Result<()> {
    match vertices.iter().position(|p| !p.as_vec3().is_finite()) {
        Some(k) => Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!(
                "vertex {k} is {}, beyond the range of 32-bit floats (±3.4e38): rescale the \
                 model or write 64-bit coordinates (PLY `double`)",
                vertices[k]
            ),
        )),
        None => Ok(()),
    }
}
