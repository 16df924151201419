//! Mesh formats and writers for a [`QuadGrid`]: OBJ, ASCII PLY and JSON.
//!
//! All three write every coordinate with the shortest decimal that parses
//! back to the same `f64` (`zmij`), vertex `(i, j)` as vertex number
//! `i * cols + j`, and face `(i, j)` as the quad
//! `(i, j), (i+1, j), (i+1, j+1), (i, j+1)`, reversed when the node axes point
//! the other way, so that every face turns counter-clockwise about its normals
//! ([`QuadGrid::oriented_faces`]).

use std::io::{self, Write};
use std::path::Path;

use glam::DVec3;
use monge_core::QuadGrid;
use serde_json::{Map, Value};

use crate::atomic::write_output;
use crate::error::IoError;
use crate::faces::{Faces, GridFaces};
use crate::format::MeshFormat;
use crate::gltf::write_grid_glb_at;
use crate::text::{emit, Out};

/// Keys of the mesh JSON format that extra keys may not use.
pub const MESH_JSON_KEYS: [&str; 4] = ["rows", "cols", "vertices", "normals"];

/// The key (JSON) and comment word (OBJ, PLY) that records the point a mesh's
/// coordinates are relative to ([`write_mesh_at`]).
pub const BASE_POINT: &str = "base_point";

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
    write_mesh_at(grid, format, None, &Map::new(), w)
}

/// Writes a grid to `w` in `format`, JSON with the keys of `extra`. With a
/// `base`, the grid's coordinates are relative to that point, which the file
/// records where the format allows: JSON `"base_point": [x, y, z]`, OBJ
/// `# base_point x y z`, PLY `comment base_point x y z` (the true coordinates
/// are the written ones plus it), glTF the node's `translation` (so that a
/// viewer places the mesh at its true place). Without one, the file is that of
/// [`write_mesh_to`] (JSON: [`write_mesh_json`]), byte for byte.
///
/// ```
/// # use glam::DVec3;
/// # use monge_core::QuadGrid;
/// let grid = QuadGrid::new(2, 2, vec![DVec3::ZERO, DVec3::Y, DVec3::X, DVec3::ONE], vec![]);
/// let base = Some(DVec3::new(1e6, 2e6, 0.5));
/// let mut out = Vec::new();
/// monge_io::write_mesh_at(&grid, monge_io::MeshFormat::Obj, base, &Default::default(), &mut out).unwrap();
/// let text = String::from_utf8(out).unwrap();
/// let head = "# monge quad grid rows=2 cols=2\n# base_point 1000000.0 2000000.0 0.5\nv 0.0 0.0 0.0\n";
/// assert!(text.starts_with(head), "{text}");
/// ```
pub fn write_mesh_at<W: Write + ?Sized>(
    grid: &QuadGrid,
    format: MeshFormat,
    base: Option<DVec3>,
    extra: &Map<String, Value>,
    w: &mut W,
) -> io::Result<()> {
    match format {
        MeshFormat::Obj => grid_quads(grid, base)?.obj(w),
        MeshFormat::Ply => grid_quads(grid, base)?.ply(w),
        MeshFormat::PlyBinary => grid_quads(grid, base)?.ply_binary(false, w),
        MeshFormat::PlyF32 => {
            let quads = grid_quads(grid, base)?;
            check_f32(grid)?;
            quads.ply_binary(true, w)
        }
        MeshFormat::Json => match base {
            Some(b) => {
                let mut extra = extra.clone();
                extra.insert(BASE_POINT.into(), serde_json::json!(b.to_array()));
                write_mesh_json(grid, &extra, w)
            }
            None => write_mesh_json(grid, extra, w),
        },
        MeshFormat::Glb => write_grid_glb_at(grid, base, w),
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
    grid_quads(grid, None)?.obj(w)
}

/// Writes a grid as ASCII PLY.
///
/// Vertices with `double` `x y z` (and `nx ny nz` if the grid has normals),
/// quad faces as `list uchar int vertex_indices` (0-based), and a header
/// comment `comment monge quad grid rows=R cols=C`. Fails like [`write_obj`].
pub fn write_ply<W: Write + ?Sized>(grid: &QuadGrid, w: &mut W) -> io::Result<()> {
    grid_quads(grid, None)?.ply(w)
}

/// Writes a grid as binary little-endian PLY, with `double` coordinates, or
/// `float` ones if `f32`.
///
/// The same elements, properties, comment and faces as [`write_ply`], in
/// `format binary_little_endian 1.0`; face indices are `int` (so at most
/// 2³¹ − 1 vertices). Fails like [`write_obj`].
///
/// ```
/// # use glam::DVec3;
/// # use monge_core::QuadGrid;
/// let grid = QuadGrid::new(2, 2, vec![DVec3::ZERO, DVec3::Y, DVec3::X, DVec3::ONE], vec![]);
/// let mut out = Vec::new();
/// monge_io::write_ply_binary(&grid, false, &mut out).unwrap();
/// let body = out.len() - 4 * 3 * 8 - (1 + 4 * 4);
/// assert!(out[..body].ends_with(b"end_header\n"));
/// assert_eq!(out[body + 4 * 8..body + 5 * 8], 1.0f64.to_le_bytes()); // vertex 1's y
/// ```
pub fn write_ply_binary<W: Write + ?Sized>(
    grid: &QuadGrid,
    f32: bool,
    w: &mut W,
) -> io::Result<()> {
    write_mesh_at(
        grid,
        if f32 {
            MeshFormat::PlyF32
        } else {
            MeshFormat::PlyBinary
        },
        None,
        &Map::new(),
        w,
    )
}

/// A quad mesh on its way to an OBJ or PLY file: vertices, normals (none,
/// or one per vertex), faces (0-based, already oriented), a header comment,
/// and the point the coordinates are relative to, if any (a second comment).
pub(crate) struct Quads<'a, F> {
    pub(crate) vertices: &'a [DVec3],
    pub(crate) normals: &'a [DVec3],
    pub(crate) faces: F,
    pub(crate) comment: String,
    pub(crate) base: Option<DVec3>,
}

/// A grid's vertices, normals and [`QuadGrid::oriented_faces`], with the
/// comment `monge quad grid rows=R cols=C`, after [`check_grid`].
fn grid_quads(grid: &QuadGrid, base: Option<DVec3>) -> io::Result<Quads<'_, GridFaces<'_>>> {
    check_grid(grid)?;
    Ok(Quads {
        vertices: &grid.vertices,
        normals: &grid.normals,
        faces: GridFaces::of(grid),
        comment: format!("monge quad grid rows={} cols={}", grid.rows, grid.cols),
        base,
    })
}

/// `base_point x y z`: the words of the comment that records a base point
/// (each coordinate the shortest decimal that reads back to the same f64).
fn base_comment(b: DVec3) -> String {
    format!("{BASE_POINT} {:?} {:?} {:?}", b.x, b.y, b.z)
}

impl<F: Faces> Quads<'_, F> {
    /// OBJ: `# comment`, `v`, `vn`, then `f a//a …` (`f a …` without normals), 1-based.
    pub(crate) fn obj<W: Write + ?Sized>(self, w: &mut W) -> io::Result<()> {
        writeln!(w, "# {}", self.comment)?;
        if let Some(b) = self.base {
            writeln!(w, "# {}", base_comment(b))?;
        }
        let with_normals = !self.normals.is_empty();
        emit(w, |out| {
            for (tag, points) in [("v ", self.vertices), ("vn ", self.normals)] {
                out.each(points, |o, _, p| {
                    o.str(tag);
                    o.xyz(*p, b' ');
                    o.push(b'\n');
                })?;
            }
            self.faces.each(out, |o, corners| {
                o.push(b'f');
                for &c in corners.as_ref() {
                    o.push(b' ');
                    o.int(c + 1);
                    if with_normals {
                        o.str("//");
                        o.int(c + 1);
                    }
                }
                o.push(b'\n');
            })
        })
    }

    /// ASCII PLY.
    pub(crate) fn ply<W: Write + ?Sized>(self, w: &mut W) -> io::Result<()> {
        self.ply_header("ascii", "double", w)?;
        emit(w, |out| {
            let normals = self.normals;
            out.each(self.vertices, |o, k, p| {
                o.xyz(*p, b' ');
                if let Some(n) = normals.get(k) {
                    o.push(b' ');
                    o.xyz(*n, b' ');
                }
                o.push(b'\n');
            })?;
            self.faces.each(out, |o, corners| {
                let corners = corners.as_ref();
                o.int(corners.len());
                for &c in corners {
                    o.push(b' ');
                    o.int(c);
                }
                o.push(b'\n');
            })
        })
    }

    /// Binary little-endian PLY, coordinates as `double` (or `float` if `f32`).
    pub(crate) fn ply_binary<W: Write + ?Sized>(self, f32: bool, w: &mut W) -> io::Result<()> {
        if i32::try_from(self.vertices.len()).is_err() {
            return Err(io::Error::new(
                io::ErrorKind::InvalidInput,
                format!(
                    "{} vertices do not fit PLY's `int` vertex indices (at most 2147483647)",
                    self.vertices.len()
                ),
            ));
        }
        self.ply_header(
            "binary_little_endian",
            if f32 { "float" } else { "double" },
            w,
        )?;
        emit(w, |out| {
            // One fixed-size record per vertex and per face, a number at a time.
            let put = |o: &mut Out<'_, Vec<u8>>, p: DVec3| {
                for x in p.to_array() {
                    if f32 {
                        o.bytes(&(x as f32).to_le_bytes());
                    } else {
                        o.bytes(&x.to_le_bytes());
                    }
                }
            };
            let normals = self.normals;
            out.each(self.vertices, |o, k, p| {
                put(o, *p);
                if let Some(n) = normals.get(k) {
                    put(o, *n);
                }
            })?;
            self.faces.each(out, |o, corners| {
                let corners = corners.as_ref();
                // At most 255 corners: checked by the writers of polygons.
                o.push(corners.len() as u8);
                for &c in corners {
                    // In range: checked above.
                    o.bytes(&(c as i32).to_le_bytes());
                }
            })
        })
    }

    /// The PLY header: `format FORMAT 1.0`, the comment, coordinates of type `scalar`.
    fn ply_header<W: Write + ?Sized>(
        &self,
        format: &str,
        scalar: &str,
        w: &mut W,
    ) -> io::Result<()> {
        write!(w, "ply\nformat {format} 1.0\ncomment {}\n", self.comment)?;
        if let Some(b) = self.base {
            writeln!(w, "comment {}", base_comment(b))?;
        }
        writeln!(w, "element vertex {}", self.vertices.len())?;
        let names: &[&str] = if self.normals.is_empty() {
            &["x", "y", "z"]
        } else {
            &["x", "y", "z", "nx", "ny", "nz"]
        };
        for name in names {
            writeln!(w, "property {scalar} {name}")?;
        }
        writeln!(
            w,
            "element face {}\nproperty list uchar int vertex_indices\nend_header",
            self.faces.count()
        )
    }
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
    emit(w, |out| {
        for (key, points) in [("vertices", &grid.vertices), ("normals", &grid.normals)] {
            if key == "normals" && points.is_empty() {
                continue;
            }
            out.str(",\"");
            out.str(key);
            out.str("\":[");
            out.each(points, |o, k, p| {
                o.str(if k == 0 { "\n[" } else { ",\n[" });
                o.xyz(*p, b',');
                o.push(b']');
            })?;
            out.str("\n]");
        }
        out.str("}\n");
        Ok(())
    })
}

/// Refuses a grid with a coordinate beyond `f32`'s range (±3.4e38), which a
/// `float` PLY would hold as infinite.
fn check_f32(grid: &QuadGrid) -> io::Result<()> {
    match first_where(&grid.vertices, |p| !p.as_vec3().is_finite()) {
        Some(k) => Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!(
                "vertex ({}, {}) is {}, beyond the range of 32-bit floats (±3.4e38): rescale \
                 the model or write 64-bit coordinates (PLY `double`)",
                k / grid.cols,
                k % grid.cols,
                grid.vertices[k]
            ),
        )),
        None => Ok(()),
    }
}

/// The first index of `points` where `bad` holds, blocks of points searched side by side.
fn first_where(points: &[DVec3], bad: impl Fn(&DVec3) -> bool + Sync) -> Option<usize> {
    monge_core::tasks::ranges(points.len(), monge_core::tasks::BLOCK, |r| {
        r.clone().find(|&k| bad(&points[k]))
    })
    .into_iter()
    .flatten()
    .next()
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
        if let Some(k) = first_where(points, |p| !p.is_finite()) {
            let (i, j) = (k / grid.cols, k % grid.cols);
            return invalid(format!("{what} ({i}, {j}) is not finite: {}", points[k]));
        }
    }
    Ok(())
}
