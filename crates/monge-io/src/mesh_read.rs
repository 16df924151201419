//! Mesh readers: the JSON, OBJ and PLY (ASCII or binary little-endian) files
//! written by this crate, and OBJ/PLY quad grids from elsewhere whose vertices
//! are in row-major order.

use std::fs::File;
use std::io::{self, BufRead, BufReader, Read};
use std::path::{Path, PathBuf};

use glam::DVec3;
use monge_core::{MeshKind, QuadGrid};
use serde::Deserialize;

use crate::design::parse_as;
use crate::error::IoError;
use crate::format::{DesignFormat, FileKind, MeshFormat};
use crate::kind::expect_kind;
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

/// [`IoError::Read`] of `file`.
fn read_failed(file: &str, source: io::Error) -> IoError {
    IoError::Read {
        path: PathBuf::from(file),
        source,
    }
}

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

/// The lines of a buffered reader, read one at a time into one buffer.
struct Lines<'f, R> {
    reader: R,
    buf: Vec<u8>,
    /// Lines read so far.
    number: usize,
    /// Bytes read so far.
    bytes: usize,
    file: &'f str,
}

impl<'f, R: BufRead> Lines<'f, R> {
    fn new(reader: R, file: &'f str) -> Self {
        Lines {
            reader,
            buf: Vec::new(),
            number: 0,
            bytes: 0,
            file,
        }
    }

    /// The next line's 1-based number and bytes (without `\n` or `\r\n`), or
    /// `None` at the end of the input.
    fn next_line(&mut self) -> Result<Option<(usize, &[u8])>, IoError> {
        self.buf.clear();
        let n = self
            .reader
            .read_until(b'\n', &mut self.buf)
            .map_err(|source| read_failed(self.file, source))?;
        if n == 0 {
            return Ok(None);
        }
        self.number += 1;
        self.bytes += n;
        if self.buf.last() == Some(&b'\n') {
            self.buf.pop();
            if self.buf.last() == Some(&b'\r') {
                self.buf.pop();
            }
        }
        Ok(Some((self.number, &self.buf)))
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

fn parse_json(text: &str, file: &str) -> Result<(QuadGrid, Option<MeshKind>), IoError> {
    expect_kind(text, DesignFormat::Json, file, &[FileKind::Mesh])?;
    let m: MeshJson = parse_as(text, DesignFormat::Json, file)?;
    let kind = serde_json::from_value(m.kind).ok();
    let vertices = m.vertices.into_iter().map(DVec3::from_array).collect();
    let normals = m.normals.into_iter().map(DVec3::from_array).collect();
    Ok((grid(file, m.rows, m.cols, vertices, normals)?, kind))
}

/// The `face_normals` of a conical mesh's JSON file (§2.3, as `monge generate`
/// writes them), one per face of `grid` (the mesh read from it); `None` for a
/// file of another format or without the key.
///
/// # Errors
/// Those of [`read_mesh`] for the file, and [`IoError::CountMismatch`] if the
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

/// The grid after checking the counts.
fn grid(
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
struct RawMesh {
    /// From a `monge quad grid rows=R cols=C` comment.
    shape: Option<(usize, usize)>,
    vertices: Vec<DVec3>,
    normals: Vec<DVec3>,
    /// 0-based corners.
    faces: Vec<[usize; 4]>,
}

impl RawMesh {
    fn into_grid(self, file: &str) -> Result<QuadGrid, IoError> {
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
fn parse_shape(
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

fn parse_obj(reader: impl BufRead, file: &str, keep: Keep) -> Result<RawMesh, IoError> {
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

/// A PLY scalar type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    /// The type named `name` (both the original and the sized names).
    fn from_name(name: &str) -> Option<Scalar> {
        Some(match name {
            "char" | "int8" => Scalar::I8,
            "uchar" | "uint8" => Scalar::U8,
            "short" | "int16" => Scalar::I16,
            "ushort" | "uint16" => Scalar::U16,
            "int" | "int32" => Scalar::I32,
            "uint" | "uint32" => Scalar::U32,
            "float" | "float32" => Scalar::F32,
            "double" | "float64" => Scalar::F64,
            _ => return None,
        })
    }

    fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    /// The little-endian value at the start of `b` (at least [`Scalar::size`] bytes), exactly.
    fn read_le(self, b: &[u8]) -> f64 {
        match self {
            Scalar::I8 => f64::from(b[0] as i8),
            Scalar::U8 => f64::from(b[0]),
            Scalar::I16 => f64::from(i16::from_le_bytes([b[0], b[1]])),
            Scalar::U16 => f64::from(u16::from_le_bytes([b[0], b[1]])),
            Scalar::I32 => f64::from(i32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            Scalar::U32 => f64::from(u32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            Scalar::F32 => f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            Scalar::F64 => f64::from_le_bytes(b[..8].try_into().expect("8 bytes")),
        }
    }
}

/// A PLY property: its name, and its type (a list's length type and item type).
struct Property {
    name: String,
    list: Option<Scalar>,
    scalar: Scalar,
    /// The 1-based header line declaring it.
    line: usize,
}

/// A PLY element declared in the header.
struct Element {
    name: String,
    count: usize,
    properties: Vec<Property>,
    /// The 1-based header line declaring it.
    line: usize,
}

impl Element {
    /// The fewest bytes one record of this element takes in `encoding`: in
    /// ASCII a value and a separator per property (a list at least its
    /// length), at least a line break; in binary the scalars' sizes (a
    /// list at least its length).
    fn min_record_bytes(&self, encoding: Encoding) -> u64 {
        match encoding {
            Encoding::Ascii => (2 * self.properties.len() as u64).max(1),
            Encoding::BinaryLittleEndian => self
                .properties
                .iter()
                .map(|p| p.list.unwrap_or(p.scalar).size() as u64)
                .sum(),
        }
    }
}

/// The body encodings of PLY that can be read.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Encoding {
    Ascii,
    BinaryLittleEndian,
}

/// A PLY header: the encoding, the elements, the grid shape from the comment,
/// the number of header lines and bytes.
struct PlyHeader {
    encoding: Encoding,
    elements: Vec<Element>,
    shape: Option<(usize, usize)>,
    lines: usize,
    bytes: usize,
}

fn parse_ply_header(lines: &mut Lines<'_, impl BufRead>, file: &str) -> Result<PlyHeader, IoError> {
    let syntax_at = |number: usize, message: String| IoError::Syntax {
        file: file.to_owned(),
        line: number + 1,
        message,
    };
    let mut header = PlyHeader {
        encoding: Encoding::Ascii,
        elements: Vec::new(),
        shape: None,
        lines: 0,
        bytes: 0,
    };
    loop {
        let Some((number, line)) = lines.next_line()? else {
            return Err(syntax_at(
                lines.number,
                "the header has no `end_header`".to_owned(),
            ));
        };
        let n = number - 1;
        let line = std::str::from_utf8(line)
            .map_err(|_| syntax_at(n, "the header is not text".to_owned()))?;
        let syntax = |message: String| syntax_at(n, message);
        if n == 0 {
            if line.trim() != "ply" {
                return Err(syntax("expected `ply` on the first line".to_owned()));
            }
            continue;
        }
        let mut tokens = line.split_whitespace();
        match tokens.next() {
            Some("format") => {
                header.encoding = match tokens.next().unwrap_or("") {
                    "ascii" => Encoding::Ascii,
                    "binary_little_endian" => Encoding::BinaryLittleEndian,
                    other => {
                        return Err(syntax(format!(
                            "only ASCII and binary_little_endian PLY can be read, this file is \
                             `{other}`; convert it with e.g. `plyfile` or MeshLab"
                        )))
                    }
                };
            }
            Some("comment") => {
                let comment = line.trim_start().strip_prefix("comment").unwrap_or("");
                if let Some(shape) = parse_shape(comment, &syntax)? {
                    header.shape = Some(shape);
                }
            }
            Some("element") => {
                let name = tokens.next().unwrap_or("").to_owned();
                let count = tokens
                    .next()
                    .and_then(|c| c.parse().ok())
                    .ok_or_else(|| syntax(format!("expected `element {name} COUNT`")))?;
                header.elements.push(Element {
                    name,
                    count,
                    properties: Vec::new(),
                    line: number,
                });
            }
            Some("property") => {
                let element = header
                    .elements
                    .last_mut()
                    .ok_or_else(|| syntax("a property before any element".to_owned()))?;
                let words: Vec<&str> = tokens.collect();
                let scalar = |t: &str| {
                    Scalar::from_name(t).ok_or_else(|| {
                        syntax(format!(
                            "unknown PLY type `{t}` in `{}`; the types are char, uchar, short, \
                             ushort, int, uint, float and double",
                            line.trim()
                        ))
                    })
                };
                let property = match words.as_slice() {
                    ["list", len, item, name] => Property {
                        name: (*name).to_owned(),
                        list: Some(match scalar(len)? {
                            Scalar::F32 | Scalar::F64 => {
                                return Err(syntax(format!(
                                    "a list's length is a whole number, not `{len}`, in `{}`: \
                                     declare it as e.g. `property list uchar {item} {name}`",
                                    line.trim()
                                )))
                            }
                            t => t,
                        }),
                        scalar: scalar(item)?,
                        line: number,
                    },
                    [t, name] => Property {
                        name: (*name).to_owned(),
                        list: None,
                        scalar: scalar(t)?,
                        line: number,
                    },
                    _ => return Err(syntax(format!("cannot read `{}`", line.trim()))),
                };
                element.properties.push(property);
            }
            Some("end_header") => {
                header.lines = number;
                header.bytes = lines.bytes;
                return Ok(header);
            }
            _ => {}
        }
    }
}

/// What a PLY element's records give: where their values are among its properties.
enum Slots {
    /// The `vertex` element: where `x y z` are, and `nx ny nz` if given.
    Vertex {
        xyz: [usize; 3],
        normal: Option<[usize; 3]>,
    },
    /// The `face` element of a mesh: where its corner list is.
    Face { indices: usize },
    /// Any other element, or the faces of a point cloud: read past.
    Other,
}

impl Slots {
    /// Where `element`'s values are, checked before any record is read: a
    /// `vertex` element needs `x`, `y` and `z`, and they (and `nx ny nz`)
    /// must be single numbers; the `face` element of a mesh needs the list
    /// `vertex_indices` (or `vertex_index`).
    fn of(element: &Element, keep: Keep, file: &str) -> Result<Slots, IoError> {
        let syntax = |line: usize, message: String| IoError::Syntax {
            file: file.to_owned(),
            line,
            message,
        };
        let find = |name: &str| element.properties.iter().position(|p| p.name == name);
        let scalar = |k: usize| {
            let p = &element.properties[k];
            match p.list {
                None => Ok(k),
                Some(_) => Err(syntax(
                    p.line,
                    format!(
                        "the `{}` property `{}` is a list; coordinates and normals are one \
                         number each: declare it as `property double {}` (or float)",
                        element.name, p.name, p.name
                    ),
                )),
            }
        };
        let three = |names: [&str; 3]| -> Result<Option<[usize; 3]>, IoError> {
            match names.map(find) {
                [Some(a), Some(b), Some(c)] => Ok(Some([scalar(a)?, scalar(b)?, scalar(c)?])),
                _ => Ok(None),
            }
        };
        if element.count == 0 {
            return Ok(Slots::Other);
        }
        match element.name.as_str() {
            "vertex" => {
                let Some(xyz) = three(["x", "y", "z"])? else {
                    let missing = ["x", "y", "z"].into_iter().find(|n| find(n).is_none());
                    return Err(syntax(
                        element.line,
                        format!(
                            "the `vertex` element has no property `{}`; vertices need `x`, `y` and `z`",
                            missing.unwrap_or("x")
                        ),
                    ));
                };
                let normal = three(["nx", "ny", "nz"])?;
                Ok(Slots::Vertex { xyz, normal })
            }
            "face" if keep == Keep::Grid => {
                let Some(k) = find("vertex_indices").or_else(|| find("vertex_index")) else {
                    return Err(syntax(
                        element.line,
                        "the `face` element has no property `vertex_indices`".to_owned(),
                    ));
                };
                let p = &element.properties[k];
                if p.list.is_none() {
                    return Err(syntax(
                        p.line,
                        format!(
                            "the `face` property `{}` is a single number; a face's corners are \
                             a list: `property list uchar int {}`",
                            p.name, p.name
                        ),
                    ));
                }
                Ok(Slots::Face { indices: k })
            }
            _ => Ok(Slots::Other),
        }
    }

    /// Adds one record to `raw`: property `k`'s values (a list's items after
    /// its length) are `values[ranges[k].0..ranges[k].1]`.
    fn add(
        &self,
        values: &[f64],
        ranges: &[(usize, usize)],
        raw: &mut RawMesh,
    ) -> Result<(), String> {
        // Every slot is a single number (checked by `Slots::of`).
        let value = |k: usize| {
            let x = values[ranges[k].0];
            if x.is_finite() {
                Ok(x)
            } else {
                Err(format!("`{x}` is not a finite number"))
            }
        };
        let point = |[a, b, c]: [usize; 3]| -> Result<DVec3, String> {
            Ok(DVec3::new(value(a)?, value(b)?, value(c)?))
        };
        match *self {
            Slots::Vertex { xyz, normal } => {
                raw.vertices.push(point(xyz)?);
                if let Some(normal) = normal {
                    raw.normals.push(point(normal)?);
                }
            }
            Slots::Face { indices } => {
                let corners = &values[ranges[indices].0..ranges[indices].1];
                if corners.len() != 4 {
                    return Err(format!(
                        "a face with {} corners; a quad grid has faces with 4",
                        corners.len()
                    ));
                }
                let mut face = [0; 4];
                for (slot, &c) in face.iter_mut().zip(corners) {
                    if c < 0.0 || c.fract() != 0.0 {
                        return Err(format!("expected a vertex index, found `{c}`"));
                    }
                    *slot = c as usize;
                }
                raw.faces.push(face);
            }
            Slots::Other => {}
        }
        Ok(())
    }
}

/// What a reader keeps of an OBJ or PLY file.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Keep {
    /// The quad grid: vertices, normals and faces (checked to be quads).
    Grid,
    /// The points only (`monge approximate`'s targets): faces of any shape are read past.
    Points,
}

/// Refuses a PLY header whose element counts need more bytes than the
/// `remaining` ones after it, before any record is read (so that no count
/// drives the work or the memory beyond what the file holds).
fn check_counts(header: &PlyHeader, remaining: u64, file: &str) -> Result<(), IoError> {
    // An ASCII file's last line may lack its line break.
    let slack = u128::from(header.encoding == Encoding::Ascii);
    let mut needed: u128 = 0;
    for (k, e) in header.elements.iter().enumerate() {
        let min = e.min_record_bytes(header.encoding);
        needed += e.count as u128 * u128::from(min);
        if needed > u128::from(remaining) + slack {
            let before = if k == 0 {
                ""
            } else {
                " with the records declared before them"
            };
            let encoding = match header.encoding {
                Encoding::Ascii => "in ASCII",
                Encoding::BinaryLittleEndian => "in binary",
            };
            return Err(IoError::Syntax {
                file: file.to_owned(),
                line: e.line,
                message: format!(
                    "`element {} {}` does not fit in the file: {} records of at least {min} bytes \
                     each ({encoding}){before} need more than the {remaining} bytes after the \
                     header; the count is wrong or the file is cut short",
                    e.name, e.count, e.count
                ),
            });
        }
    }
    Ok(())
}

/// Reads the PLY file from `reader` (`size` bytes long, when known).
fn parse_ply(
    reader: impl BufRead,
    file: &str,
    size: Option<u64>,
    keep: Keep,
) -> Result<RawMesh, IoError> {
    let mut lines = Lines::new(reader, file);
    let header = parse_ply_header(&mut lines, file)?;
    if let Some(size) = size {
        check_counts(&header, size.saturating_sub(header.bytes as u64), file)?;
    }
    let slots = header
        .elements
        .iter()
        .map(|e| Slots::of(e, keep, file))
        .collect::<Result<Vec<_>, _>>()?;
    let mut raw = RawMesh {
        shape: header.shape,
        ..RawMesh::default()
    };
    match header.encoding {
        Encoding::Ascii => parse_ply_ascii(&mut lines, &header, &slots, file, &mut raw)?,
        Encoding::BinaryLittleEndian => {
            parse_ply_binary(&mut lines.reader, &header, &slots, file, &mut raw)?
        }
    }
    Ok(raw)
}

fn parse_ply_ascii(
    lines: &mut Lines<'_, impl BufRead>,
    header: &PlyHeader,
    slots: &[Slots],
    file: &str,
    raw: &mut RawMesh,
) -> Result<(), IoError> {
    let mut values: Vec<f64> = Vec::new();
    let mut ranges: Vec<(usize, usize)> = Vec::new();
    for (element, slots) in header.elements.iter().zip(slots) {
        for _ in 0..element.count {
            let last = lines.number;
            let syntax = |line: usize, message: String| IoError::Syntax {
                file: file.to_owned(),
                line,
                message,
            };
            let Some((n, line)) = lines.next_line()? else {
                return Err(syntax(
                    last + 1,
                    format!(
                        "the file ends before all {} `{}` lines",
                        element.count, element.name
                    ),
                ));
            };
            let line = std::str::from_utf8(line)
                .map_err(|e| syntax(n, format!("an ASCII PLY body that is not text: {e}")))?;
            ply_values(line, &element.properties, &mut values, &mut ranges)
                .map_err(|m| syntax(n, m))?;
            slots.add(&values, &ranges, raw).map_err(|m| syntax(n, m))?;
        }
    }
    Ok(())
}

/// The values of each property of one ASCII element line into `values`, and
/// into `ranges` where each property's values are (a list's items, after its length).
fn ply_values(
    line: &str,
    properties: &[Property],
    values: &mut Vec<f64>,
    ranges: &mut Vec<(usize, usize)>,
) -> Result<(), String> {
    values.clear();
    ranges.clear();
    let mut tokens = line.split_ascii_whitespace();
    let mut next = || {
        tokens
            .next()
            .ok_or_else(|| "too few values on the line".to_owned())
    };
    for property in properties {
        let first = next()?;
        let start = values.len();
        if property.list.is_some() {
            let len: usize = first
                .parse()
                .map_err(|_| format!("expected a list length, found `{first}`"))?;
            for _ in 0..len {
                values.push(parse_number(next()?)?);
            }
        } else {
            values.push(parse_number(first)?);
        }
        ranges.push((start, values.len()));
    }
    Ok(())
}

/// A number (not necessarily finite: the caller says which must be).
fn parse_number(token: &str) -> Result<f64, String> {
    token
        .parse::<f64>()
        .map_err(|_| format!("expected a number, found `{token}`"))
}

fn parse_ply_binary(
    body: &mut impl Read,
    header: &PlyHeader,
    slots: &[Slots],
    file: &str,
    raw: &mut RawMesh,
) -> Result<(), IoError> {
    let mut at = 0;
    let error = |offset: usize, message: String| IoError::Binary {
        file: file.to_owned(),
        offset: header.bytes + offset,
        message,
    };
    let mut values: Vec<f64> = Vec::new();
    let mut ranges: Vec<(usize, usize)> = Vec::new();
    let mut scratch = [0u8; 8];
    for (element, slots) in header.elements.iter().zip(slots) {
        if element.properties.is_empty() {
            continue; // records of no bytes: nothing to read, however many
        }
        for record in 0..element.count {
            let start = at;
            let mut read = |scalar: Scalar, at: &mut usize| -> Result<f64, IoError> {
                let b = &mut scratch[..scalar.size()];
                body.read_exact(b).map_err(|source| {
                    if source.kind() == io::ErrorKind::UnexpectedEof {
                        error(
                            *at,
                            format!(
                                "the file ends in `{}` record {record} of {}",
                                element.name, element.count
                            ),
                        )
                    } else {
                        read_failed(file, source)
                    }
                })?;
                *at += scalar.size();
                Ok(scalar.read_le(b))
            };
            values.clear();
            ranges.clear();
            for property in &element.properties {
                let first = values.len();
                match property.list {
                    Some(len_type) => {
                        let len = read(len_type, &mut at)?;
                        if len < 0.0 {
                            return Err(error(at, format!("a list of length {len}")));
                        }
                        for _ in 0..len as usize {
                            values.push(read(property.scalar, &mut at)?);
                        }
                    }
                    None => values.push(read(property.scalar, &mut at)?),
                }
                ranges.push((first, values.len()));
            }
            slots
                .add(&values, &ranges, raw)
                .map_err(|message| error(start, message))?;
        }
    }
    Ok(())
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
