//! STL targets (a triangle mesh, ASCII or binary, in single precision), read with
//! `stl_io`: the points of `monge approximate`'s targets.

use std::io::Cursor;

use glam::DVec3;

use crate::error::IoError;

/// Bytes of a binary STL's header (80) and triangle count (4).
const HEADER: usize = 84;
/// Bytes of one triangle in a binary STL: its normal and corners (12 `f32`) and a
/// 2-byte attribute.
const TRIANGLE: usize = 50;

/// The distinct corners of the triangles of an STL file `bytes` named `file` (for
/// messages), in the order they first appear (each shared corner once): the points of
/// an STL target ([`read_points`](crate::read_points)). A file is binary when its
/// length is that of the triangles its header counts (84 + 50 per triangle), whatever
/// its header says (some exporters begin it with `solid`), else ASCII (`solid …`).
///
/// ```
/// let ascii = "solid\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n\
///              vertex 0 1 0.5\nendloop\nendfacet\nendsolid\n";
/// let points = monge_io::read_stl_points(ascii.as_bytes(), "roof.stl").unwrap();
/// assert_eq!(points.len(), 3);
/// assert_eq!(points[2].z, 0.5);
/// ```
pub fn read_stl_points(bytes: &[u8], file: &str) -> Result<Vec<DVec3>, IoError> {
    let error = |message: String| IoError::Syntax {
        file: file.to_owned(),
        line: 1,
        message,
    };
    let counted = bytes
        .get(80..HEADER)
        .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]) as usize);
    let binary = counted.is_some_and(|n| {
        n.checked_mul(TRIANGLE).and_then(|b| b.checked_add(HEADER)) == Some(bytes.len())
    });
    let mut data = bytes.to_vec();
    if binary {
        // stl_io reads a file that begins with `solid ` as ASCII: the header is
        // free text, blank it.
        data[..80].fill(b' ');
    } else {
        let start = bytes
            .iter()
            .position(|b| !b.is_ascii_whitespace())
            .unwrap_or(bytes.len());
        if !bytes[start..].starts_with(b"solid") {
            return Err(error(format!(
                "neither an ASCII STL (which begins with `solid`) nor a binary one (84 bytes \
                 of header and count, then 50 bytes a triangle: this file has {} bytes{})",
                bytes.len(),
                counted.map_or(String::new(), |n| format!(
                    " where its header counts {n} triangles"
                ))
            )));
        }
        // stl_io wants `solid ` and a name on the first line.
        let end = data[start..]
            .iter()
            .position(|b| *b == b'\n')
            .map_or(data.len(), |k| start + k);
        data.splice(start..end, b"solid monge".iter().copied());
    }
    let mesh = stl_io::read_stl(&mut Cursor::new(data)).map_err(|e| {
        error(format!(
            "not a valid {} STL: {e}",
            if binary { "binary" } else { "ASCII" }
        ))
    })?;
    let points: Vec<DVec3> = mesh
        .vertices
        .iter()
        .map(|v| DVec3::new(f64::from(v[0]), f64::from(v[1]), f64::from(v[2])))
        .collect();
    if let Some(k) = points.iter().position(|p| !p.is_finite()) {
        let triangle = mesh
            .faces
            .iter()
            .position(|t| t.vertices.contains(&k))
            .unwrap_or(0);
        return Err(error(format!(
            "triangle {} has a corner that is not a finite number: {}",
            triangle + 1,
            points[k]
        )));
    }
    Ok(points)
}
