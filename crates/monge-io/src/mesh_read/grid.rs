//! What an OBJ or PLY file says, made a quad grid: the shape from the
//! `monge quad grid rows=R cols=C` comment or the first face, every face
//! checked to be one of the grid's.

use glam::DVec3;
use monge_core::QuadGrid;

use crate::error::IoError;

/// The grid after checking the counts.
pub(super) fn grid(
    file: &str,
    rows: usize,
    cols: usize,
    vertices: Vec<DVec3>,
    normals: Vec<DVec3>,
) -> Result<QuadGrid, IoError> {
    let mismatch = |what: String, expected, found| IoError::CountMismatch {
        file: file.to_owned(),
        what,
        expected,
        found,
    };
    if (rows == 0) != (cols == 0) {
        return Err(IoError::NotAGrid {
            file: file.to_owned(),
            message: format!(
                "the grid is empty (rows × cols = {rows} × {cols}): an empty grid is 0 × 0, any other has at least one row and one column"
            ),
        });
    }
    let n = rows.checked_mul(cols).ok_or_else(|| IoError::NotAGrid {
        file: file.to_owned(),
        message: format!("rows × cols = {rows} × {cols} is too large"),
    })?;
    if vertices.len() != n {
        let what = format!("vertices (rows × cols = {rows} × {cols})");
        return Err(mismatch(what, n, vertices.len()));
    }
    if !normals.is_empty() && normals.len() != n {
        return Err(mismatch(
            "normals (one per vertex)".to_owned(),
            n,
            normals.len(),
        ));
    }
    Ok(QuadGrid::new(rows, cols, vertices, normals))
}

/// What an OBJ or PLY file says, before the grid shape is known.
#[derive(Default)]
pub(super) struct RawMesh {
    /// From a `monge quad grid rows=R cols=C` comment.
    pub(super) shape: Option<(usize, usize)>,
    pub(super) vertices: Vec<DVec3>,
    pub(super) normals: Vec<DVec3>,
    /// 0-based corners.
    pub(super) faces: Vec<[usize; 4]>,
    /// 0-based corners of faces of any number of corners ([`Keep::Polygons`]).
    pub(super) polygons: Vec<Vec<usize>>,
}

impl RawMesh {
    pub(super) fn into_grid(self, file: &str) -> Result<QuadGrid, IoError> {
        let not_a_grid = |message: String| IoError::NotAGrid {
            file: file.to_owned(),
            message,
        };
        let n = self.vertices.len();
        let (rows, cols) = match (self.shape, self.faces.first()) {
            (Some(shape), _) => shape,
            (None, Some(first)) => {
                let cols = first_face_cols(first).ok_or_else(|| {
                    not_a_grid(format!(
                        "the first face is {} (0-based); the first face of a row-major grid \
                         with C columns is (0, C, C+1, 1), and there is no \
                         `monge quad grid rows=R cols=C` comment",
                        fmt_face(first)
                    ))
                })?;
                if n % cols != 0 {
                    return Err(not_a_grid(format!(
                        "the first face {} implies {cols} columns, but {n} vertices are not whole rows of {cols}",
                        fmt_face(first)
                    )));
                }
                (n / cols, cols)
            }
            (None, None) => {
                return Err(not_a_grid(
                    "no faces and no `monge quad grid rows=R cols=C` comment: the grid shape is unknown".to_owned(),
                ))
            }
        };
        let grid = grid(file, rows, cols, self.vertices, self.normals)?;
        if self.shape.is_none() || !self.faces.is_empty() {
            check_faces(&self.faces, rows, cols).map_err(not_a_grid)?;
        }
        Ok(grid)
    }
}

fn fmt_face(f: &[usize; 4]) -> String {
    format!("({}, {}, {}, {})", f[0], f[1], f[2], f[3])
}

/// The column count `C ≥ 2` if `f` is `(0, C, C+1, 1)` up to rotation and orientation.
fn first_face_cols(f: &[usize; 4]) -> Option<usize> {
    let p = f.iter().position(|&c| c == 0)?;
    let g = [f[p], f[(p + 1) % 4], f[(p + 2) % 4], f[(p + 3) % 4]];
    let cols = if g[3] == 1 { g[1] } else { g[3] };
    (cols >= 2 && face_matches(&g, 0, cols)).then_some(cols)
}

/// Whether `f` is the face with lowest corner `k` of a grid with `cols`
/// columns, up to rotation and orientation.
fn face_matches(f: &[usize; 4], k: usize, cols: usize) -> bool {
    let Some(p) = f.iter().position(|&c| c == k) else {
        return false;
    };
    let g = [f[p], f[(p + 1) % 4], f[(p + 2) % 4], f[(p + 3) % 4]];
    // Checked: a file's indices can be anything up to usize::MAX.
    let (Some(a), Some(b)) = (k.checked_add(cols), k.checked_add(1)) else {
        return false;
    };
    a.checked_add(1) == Some(g[2]) && ((g[1] == a && g[3] == b) || (g[1] == b && g[3] == a))
}

/// Checks that `faces` are exactly the faces of a `rows × cols` grid, each once.
fn check_faces(faces: &[[usize; 4]], rows: usize, cols: usize) -> Result<(), String> {
    let n = rows * cols;
    let expected = rows.saturating_sub(1) * cols.saturating_sub(1);
    let mut seen = vec![false; expected];
    for (number, f) in faces.iter().enumerate() {
        let face = || format!("face {} {}", number + 1, fmt_face(f));
        if let Some(&c) = f.iter().find(|&&c| c >= n) {
            return Err(format!(
                "{} refers to vertex {c}, but there are {n} vertices (0-based)",
                face()
            ));
        }
        let k = *f.iter().min().expect("four corners");
        let (i, j) = (k / cols, k % cols);
        if i + 1 >= rows || j + 1 >= cols || !face_matches(f, k, cols) {
            return Err(format!(
                "{} is not a quad (i, j), (i+1, j), (i+1, j+1), (i, j+1) of a {rows} × {cols} grid (0-based)",
                face()
            ));
        }
        let s = &mut seen[i * (cols - 1) + j];
        if *s {
            return Err(format!("{} repeats grid face ({i}, {j})", face()));
        }
        *s = true;
    }
    if faces.len() != expected {
        return Err(format!(
            "{} faces, but a {rows} × {cols} grid has {expected}",
            faces.len()
        ));
    }
    Ok(())
}

/// `Some(shape)` if `comment` is `monge quad grid rows=R cols=C`.
pub(super) fn parse_shape(
    comment: &str,
    syntax: &dyn Fn(String) -> IoError,
) -> Result<Option<(usize, usize)>, IoError> {
    let Some(rest) = comment.trim().strip_prefix("monge quad grid") else {
        return Ok(None);
    };
    let mut it = rest.split_whitespace();
    let rows = it
        .next()
        .and_then(|s| s.strip_prefix("rows="))
        .and_then(|s| s.parse().ok());
    let cols = it
        .next()
        .and_then(|s| s.strip_prefix("cols="))
        .and_then(|s| s.parse().ok());
    match (rows, cols) {
        (Some(r), Some(c)) => Ok(Some((r, c))),
        _ => Err(syntax(format!(
            "expected `monge quad grid rows=R cols=C` with whole numbers, found `{}`",
            comment.trim()
        ))),
    }
}

/// What a reader keeps of an OBJ or PLY file.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Keep {
    /// The quad grid: vertices, normals and faces (checked to be quads).
    Grid,
    /// The points only (`monge approximate`'s targets): faces of any shape are read past.
    Points,
    /// The vertices and faces of any number of corners (a trimmed mesh), OBJ or PLY.
    Polygons,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Found by the fuzzer (mesh_ply): a first face `(0, usize::MAX, …, 1)` made
    /// `k + cols + 1` overflow (a panic in debug builds).
    #[test]
    fn face_indices_near_usize_max_are_no_grid_not_a_panic() {
        assert_eq!(first_face_cols(&[0, usize::MAX, 5, 1]), None);
        assert!(!face_matches(&[usize::MAX, 0, 0, 0], usize::MAX, 3));
        assert_eq!(first_face_cols(&[0, 3, 4, 1]), Some(3));
        assert_eq!(first_face_cols(&[1, 4, 3, 0]), Some(3));
    }
}
