//! Mesh formats and writers for a [`QuadGrid`]: OBJ, ASCII PLY and JSON.
//!
//! All three write every coordinate with the shortest decimal that parses
//! back to the same `f64` (`ryu`), vertex `(i, j)` as vertex number
//! `i * cols + j`, and face `(i, j)` as the quad
//! `(i, j), (i+1, j), (i+1, j+1), (i, j+1)`, reversed when the node axes point
//! the other way, so that every face turns counter-clockwise about its normals
//! ([`QuadGrid::oriented_faces`]).

use std::io::{self, Write};
use std::path::Path;

use glam::DVec3;
use monge_core::QuadGrid;
use serde_json::{Map, Value};

use crate::atomic::{is_stdio, write_output};
use crate::design::{extension, unknown_extension};
use crate::error::IoError;

const ACCEPTED: &str = "`.obj`, `.ply`, `.json` or `.glb` (glTF, written only)";

/// Keys of the mesh JSON format that extra keys may not use.
pub const MESH_JSON_KEYS: [&str; 4] = ["rows", "cols", "vertices", "normals"];

/// A mesh file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MeshFormat {
    /// Wavefront OBJ (`.obj`).
    Obj,
    /// ASCII PLY with `double` coordinates (`.ply`).
    Ply,
    /// `{"rows", "cols", "vertices", "normals"}` JSON (`.json`).
    Json,
    /// Binary glTF (`.glb`), for viewers: `f32` positions, so written but never
    /// read back (see [`crate::write_grid_glb`]).
    Glb,
}

impl MeshFormat {
    /// The format named by the path's extension (any case).
    ///
    /// `-` (standard input/output) has none: [`IoError::NeedFormat`].
    ///
    /// ```
    /// use monge_io::MeshFormat;
    /// use std::path::Path;
    /// assert_eq!(MeshFormat::from_path(Path::new("out/mesh.obj")).unwrap(), MeshFormat::Obj);
    /// assert!(MeshFormat::from_path(Path::new("-")).is_err());
    /// ```
    pub fn from_path(path: &Path) -> Result<MeshFormat, IoError> {
        if is_stdio(path) {
            return Err(IoError::NeedFormat {
                accepted: "obj, ply or json",
            });
        }
        extension(path)
            .and_then(|e| MeshFormat::from_extension(&e))
            .ok_or_else(|| unknown_extension(path, ACCEPTED))
    }

    /// The format named by an extension or format name such as `obj`, `.PLY` or `json`.
    ///
    /// ```
    /// use monge_io::MeshFormat;
    /// assert_eq!(MeshFormat::from_extension(".PLY"), Some(MeshFormat::Ply));
    /// assert_eq!(MeshFormat::from_extension("stl"), None);
    /// ```
    pub fn from_extension(ext: &str) -> Option<MeshFormat> {
        let ext = ext.strip_prefix('.').unwrap_or(ext);
        [
            MeshFormat::Obj,
            MeshFormat::Ply,
            MeshFormat::Json,
            MeshFormat::Glb,
        ]
        .into_iter()
        .find(|f| f.extension().eq_ignore_ascii_case(ext))
    }

    /// The usual extension, without the dot: `obj`, `ply`, `json` or `glb`.
    pub fn extension(self) -> &'static str {
        match self {
            MeshFormat::Obj => "obj",
            MeshFormat::Ply => "ply",
            MeshFormat::Json => "json",
            MeshFormat::Glb => "glb",
        }
    }
}

/// Writes a grid to `path` (atomically) or to standard output if `path` is `-`.
///
/// `format` overrides the path's extension; it is required for `-`
/// ([`IoError::NeedFormat`]).
///
/// ```
/// # use glam::DVec3;
/// # use monge_core::QuadGrid;
/// # let dir = tempfile::tempdir().unwrap();
/// let grid = QuadGrid::new(2, 2, vec![DVec3::ZERO, DVec3::Y, DVec3::X, DVec3::ONE], vec![]);
/// let path = dir.path().join("mesh.obj");
/// monge_io::write_mesh(&grid, &path, None).unwrap();
/// assert_eq!(monge_io::read_mesh(&path).unwrap(), grid);
/// ```
pub fn write_mesh(grid: &QuadGrid, path: &Path, format: Option<MeshFormat>) -> Result<(), IoError> {
    let format = match format {
        Some(f) => f,
        None => MeshFormat::from_path(path)?,
    };
    write_output(path, |w| write_mesh_to(grid, format, w))
}

/// Writes a grid to `w` in `format` (JSON without extra keys).
pub fn write_mesh_to<W: Write + ?Sized>(
    grid: &QuadGrid,
    format: MeshFormat,
    w: &mut W,
) -> io::Result<()> {
    match format {
        MeshFormat::Obj => write_obj(grid, w),
        MeshFormat::Ply => write_ply(grid, w),
        MeshFormat::Json => write_mesh_json(grid, &Map::new(), w),
        MeshFormat::Glb => crate::write_grid_glb(grid, w),
    }
}

/// Writes a grid as Wavefront OBJ.
///
/// A header comment `# monge quad grid rows=R cols=C`, then `v x y z` per
/// vertex, `vn x y z` per normal (if any), and `f a//a b//b c//c d//d` per face
/// (`f a b c d` without normals), 1-based. Fails with
/// [`io::ErrorKind::InvalidInput`] on an inconsistent grid or a non-finite
/// coordinate, before writing anything.
///
/// ```
/// # use glam::DVec3;
/// # use monge_core::QuadGrid;
/// let grid = QuadGrid::new(2, 2, vec![DVec3::ZERO, DVec3::Y, DVec3::X, DVec3::ONE], vec![]);
/// let mut out = Vec::new();
/// monge_io::write_obj(&grid, &mut out).unwrap();
/// assert_eq!(String::from_utf8(out).unwrap(), "# monge quad grid rows=2 cols=2\n\
///     v 0.0 0.0 0.0\nv 0.0 1.0 0.0\nv 1.0 0.0 0.0\nv 1.0 1.0 1.0\nf 1 3 4 2\n");
/// ```
pub fn write_obj<W: Write + ?Sized>(grid: &QuadGrid, w: &mut W) -> io::Result<()> {
    check_grid(grid)?;
    writeln!(w, "# monge quad grid rows={} cols={}", grid.rows, grid.cols)?;
    emit(w, |line| {
        for (tag, points) in [("v", &grid.vertices), ("vn", &grid.normals)] {
            for p in points {
                line.push_str(tag);
                line.push(b' ');
                line.xyz(*p);
                line.end()?;
            }
        }
        let with_normals = !grid.normals.is_empty();
        for corners in grid.oriented_faces() {
            line.push_str("f");
            for c in corners {
                line.push(b' ');
                line.int(c + 1);
                if with_normals {
                    line.push_str("//");
                    line.int(c + 1);
                }
            }
            line.end()?;
        }
        Ok(())
    })
}

/// Writes a grid as ASCII PLY.
///
/// Vertices with `double` `x y z` (and `nx ny nz` if the grid has normals),
/// quad faces as `list uchar int vertex_indices` (0-based), and a header
/// comment `comment monge quad grid rows=R cols=C`. Fails like [`write_obj`].
pub fn write_ply<W: Write + ?Sized>(grid: &QuadGrid, w: &mut W) -> io::Result<()> {
    check_grid(grid)?;
    let with_normals = !grid.normals.is_empty();
    write!(
        w,
        "ply\nformat ascii 1.0\ncomment monge quad grid rows={} cols={}\n\
         element vertex {}\nproperty double x\nproperty double y\nproperty double z\n",
        grid.rows,
        grid.cols,
        grid.vertices.len()
    )?;
    if with_normals {
        w.write_all(b"property double nx\nproperty double ny\nproperty double nz\n")?;
    }
    writeln!(
        w,
        "element face {}\nproperty list uchar int vertex_indices\nend_header",
        grid.face_count()
    )?;
    emit(w, |line| {
        for (k, p) in grid.vertices.iter().enumerate() {
            line.xyz(*p);
            if with_normals {
                line.push(b' ');
                line.xyz(grid.normals[k]);
            }
            line.end()?;
        }
        for corners in grid.oriented_faces() {
            line.push(b'4');
            for c in corners {
                line.push(b' ');
                line.int(c);
            }
            line.end()?;
        }
        Ok(())
    })
}

/// Writes a grid as JSON: `{"rows": R, "cols": C, …extra, "vertices": [[x, y, z], …], "normals": [[x, y, z], …]}`.
///
/// Vertex `(i, j)` is entry `i * cols + j`; `normals` is omitted when the grid
/// has none. The keys of `extra` are written at the top level (readers ignore
/// them); one of [`MESH_JSON_KEYS`] among them is an
/// [`io::ErrorKind::InvalidInput`] error, as is an inconsistent grid or a
/// non-finite coordinate (checked before anything is written).
///
/// Numbers are exact for a correctly rounding reader (Python, JavaScript,
/// Rust's `str::parse`); serde_json rounds correctly only with its
/// `float_roundtrip` feature, which this crate enables.
///
/// ```
/// # use glam::DVec3;
/// # use monge_core::QuadGrid;
/// let grid = QuadGrid::new(1, 2, vec![DVec3::ZERO, DVec3::new(0.1, 2.0, -3e-7)], vec![]);
/// let mut extra = serde_json::Map::new();
/// extra.insert("theta_deg".into(), 30.0.into());
/// let mut out = Vec::new();
/// monge_io::write_mesh_json(&grid, &extra, &mut out).unwrap();
/// assert_eq!(String::from_utf8(out).unwrap(), "{\"rows\":1,\"cols\":2,\"theta_deg\":30.0,\"vertices\":[\n\
///     [0.0,0.0,0.0],\n[0.1,2.0,-3e-7]\n]}\n");
/// ```
pub fn write_mesh_json<W: Write + ?Sized>(
    grid: &QuadGrid,
    extra: &Map<String, Value>,
    w: &mut W,
) -> io::Result<()> {
    check_grid(grid)?;
    if let Some(key) = MESH_JSON_KEYS.iter().find(|k| extra.contains_key(**k)) {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("extra key `{key}` would replace the mesh's own `{key}`"),
        ));
    }
    write!(w, "{{\"rows\":{},\"cols\":{}", grid.rows, grid.cols)?;
    for (key, value) in extra {
        w.write_all(b",")?;
        serde_json::to_writer(&mut *w, key)?;
        w.write_all(b":")?;
        serde_json::to_writer(&mut *w, value)?;
    }
    emit(w, |line| {
        for (key, points) in [("vertices", &grid.vertices), ("normals", &grid.normals)] {
            if key == "normals" && points.is_empty() {
                continue;
            }
            line.push_str(",\"");
            line.push_str(key);
            line.push_str("\":[");
            for (k, p) in points.iter().enumerate() {
                line.push_str(if k == 0 { "\n[" } else { ",\n[" });
                line.float(p.x);
                line.push(b',');
                line.float(p.y);
                line.push(b',');
                line.float(p.z);
                line.push(b']');
                line.maybe_flush()?;
            }
            line.push_str("\n]");
        }
        line.push_str("}\n");
        Ok(())
    })
}

/// Refuses a grid whose counts disagree or that has a non-finite coordinate
/// (which no format could read back).
fn check_grid(grid: &QuadGrid) -> io::Result<()> {
    let invalid = |msg: String| Err(io::Error::new(io::ErrorKind::InvalidInput, msg));
    let n = grid.rows.checked_mul(grid.cols);
    if n != Some(grid.vertices.len()) {
        return invalid(format!(
            "the grid has {} vertices but rows × cols = {} × {}",
            grid.vertices.len(),
            grid.rows,
            grid.cols
        ));
    }
    if !grid.normals.is_empty() && grid.normals.len() != grid.vertices.len() {
        return invalid(format!(
            "the grid has {} normals for {} vertices",
            grid.normals.len(),
            grid.vertices.len()
        ));
    }
    for (what, points) in [("vertex", &grid.vertices), ("normal", &grid.normals)] {
        if let Some(k) = points.iter().position(|p| !p.is_finite()) {
            let (i, j) = (k / grid.cols, k % grid.cols);
            return invalid(format!("{what} ({i}, {j}) is not finite: {}", points[k]));
        }
    }
    Ok(())
}

/// Bytes collected before a [`Line`] passes them on.
const CHUNK: usize = 1 << 16;

/// Runs `body`, which formats the grid into a [`Line`] writing to `w`.
fn emit<W: Write + ?Sized>(
    w: &mut W,
    body: impl FnOnce(&mut Line<'_>) -> io::Result<()>,
) -> io::Result<()> {
    let mut out = |buf: &mut Vec<u8>| {
        w.write_all(buf)?;
        buf.clear();
        Ok(())
    };
    let mut line = Line::new(&mut out);
    body(&mut line)?;
    line.flush()
}

/// Where a [`Line`] passes its full buffer (which it leaves empty).
type Out<'a> = dyn FnMut(&mut Vec<u8>) -> io::Result<()> + 'a;

/// An output buffer for lines: numbers are formatted without allocating, and
/// the bytes are passed on in chunks. Call [`Line::flush`] at the end.
struct Line<'a> {
    buf: Vec<u8>,
    float: ryu::Buffer,
    int: itoa::Buffer,
    out: &'a mut Out<'a>,
}

impl<'a> Line<'a> {
    fn new(out: &'a mut Out<'a>) -> Self {
        Line {
            buf: Vec::with_capacity(CHUNK + 256),
            float: ryu::Buffer::new(),
            int: itoa::Buffer::new(),
            out,
        }
    }

    fn push(&mut self, b: u8) {
        self.buf.push(b);
    }

    fn push_str(&mut self, s: &str) {
        self.buf.extend_from_slice(s.as_bytes());
    }

    fn float(&mut self, x: f64) {
        self.buf
            .extend_from_slice(self.float.format_finite(x).as_bytes());
    }

    fn int(&mut self, n: usize) {
        self.buf.extend_from_slice(self.int.format(n).as_bytes());
    }

    /// Appends `x y z`.
    fn xyz(&mut self, p: DVec3) {
        self.float(p.x);
        self.push(b' ');
        self.float(p.y);
        self.push(b' ');
        self.float(p.z);
    }

    /// Ends the line (passing the buffer on once it is full).
    fn end(&mut self) -> io::Result<()> {
        self.buf.push(b'\n');
        self.maybe_flush()
    }

    /// Passes the buffer on if it is full.
    fn maybe_flush(&mut self) -> io::Result<()> {
        if self.buf.len() >= CHUNK {
            self.flush()?;
        }
        Ok(())
    }

    /// Passes on whatever is buffered.
    fn flush(&mut self) -> io::Result<()> {
        if self.buf.is_empty() {
            return Ok(());
        }
        (self.out)(&mut self.buf)
    }
}
