//! Wavefront OBJ: `v`, `vn` and `f` lines, and the shape comment.

use std::io::{self, BufRead};

use glam::DVec3;

use super::grid::{parse_shape, Keep, RawMesh};
use super::lines::{read_failed, Lines};
use crate::error::IoError;

/// A finite `f64`.
fn parse_f64(token: &str) -> Result<f64, String> {
    match token.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        Ok(_) => Err(format!("`{token}` is not a finite number")),
        Err(_) => Err(format!("expected a number, found `{token}`")),
    }
}

/// `x y z` from the first three of `tokens`.
fn parse_xyz<'a>(tokens: &mut impl Iterator<Item = &'a str>) -> Result<DVec3, String> {
    let mut p = [0.0; 3];
    for x in &mut p {
        *x = parse_f64(tokens.next().ok_or("expected three coordinates x y z")?)?;
    }
    Ok(DVec3::from_array(p))
}

pub(super) fn parse_obj(reader: impl BufRead, file: &str, keep: Keep) -> Result<RawMesh, IoError> {
    let mut raw = RawMesh::default();
    let mut lines = Lines::new(reader, file);
    while let Some((number, bytes)) = lines.next_line()? {
        let line = std::str::from_utf8(bytes).map_err(|e| {
            let message = format!("line {number} is not UTF-8 text: {e}");
            read_failed(file, io::Error::new(io::ErrorKind::InvalidData, message))
        })?;
        let syntax = |message: String| IoError::Syntax {
            file: file.to_owned(),
            line: number,
            message,
        };
        let line = line.trim_ascii();
        if let Some(comment) = line.strip_prefix('#') {
            if let Some(shape) = parse_shape(comment, &syntax)? {
                raw.shape = Some(shape);
            }
            continue;
        }
        let mut tokens = line.split_ascii_whitespace();
        match tokens.next() {
            Some("v") => raw.vertices.push(parse_xyz(&mut tokens).map_err(syntax)?),
            Some("vn") => raw.normals.push(parse_xyz(&mut tokens).map_err(syntax)?),
            Some("f") if keep == Keep::Grid => {
                let mut face = [0; 4];
                let mut corners = 0;
                for corner in tokens {
                    if let Some(slot) = face.get_mut(corners) {
                        *slot = obj_corner(corner, raw.vertices.len()).map_err(syntax)?;
                    }
                    corners += 1;
                }
                if corners != 4 {
                    return Err(syntax(format!(
                        "a face with {corners} corners; a quad grid has faces with 4"
                    )));
                }
                raw.faces.push(face);
            }
            Some("f") if keep == Keep::Polygons => {
                let face = tokens
                    .map(|corner| obj_corner(corner, raw.vertices.len()))
                    .collect::<Result<Vec<usize>, String>>()
                    .map_err(syntax)?;
                if face.len() < 3 || face.iter().any(|k| *k >= raw.vertices.len()) {
                    return Err(syntax(format!(
                        "a face with corners {:?} (0-based), not three or more of the {} vertices so far",
                        face,
                        raw.vertices.len()
                    )));
                }
                raw.polygons.push(face);
            }
            _ => {}
        }
    }
    Ok(raw)
}

/// The 0-based vertex of an OBJ face corner `v`, `v/t`, `v//n` or `v/t/n`
/// (negative `v` counts back from the last of `count` vertices so far).
/// A normal index must equal the vertex index: normals are read in vertex order.
fn obj_corner(corner: &str, count: usize) -> Result<usize, String> {
    let mut parts = corner.split('/');
    let index = |s: &str| -> Result<usize, String> {
        let bad = || format!("bad face corner `{corner}`");
        let k: i64 = s.parse().map_err(|_| bad())?;
        let k = if k < 0 { count as i64 + k } else { k - 1 };
        usize::try_from(k).map_err(|_| bad())
    };
    let v = index(parts.next().unwrap_or(""))?;
    if let Some(n) = parts.nth(1).filter(|s| !s.is_empty()) {
        let n = index(n)?;
        if n != v {
            return Err(format!(
                "face corner `{corner}` uses normal {} for vertex {}; normals must be in vertex order",
                n + 1,
                v + 1
            ));
        }
    }
    Ok(v)
}
