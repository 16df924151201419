//! Target readers for `monge approximate`: the points of any OBJ, PLY (ASCII or
//! binary little-endian), JSON or STL mesh or point cloud, whatever its faces
//! (triangles, quads, none), of a text file of points, or sampled on IGES surfaces.

use std::path::Path;

use glam::DVec3;
use serde::Deserialize;

use crate::design::parse_as;
use crate::error::IoError;
use crate::format::{DesignFormat, MeshFormat};
use crate::iges::read_iges_surfaces;
use crate::kind::{extension, unknown_extension};
use crate::mesh_read::read_vertices;
use crate::read::{path_name, read_file, read_to_string};
use crate::stl::read_stl_points;

/// Reads the points of a target: the vertices of an OBJ (`v` lines; faces, if any, are
/// ignored), of a PLY, ASCII or binary little-endian (`x`, `y`, `z` of the `vertex`
/// element, read by the mesh reader's PLY code), or of a JSON file
/// with `vertices` (a monge mesh) or `points`, each `[x, y, z]`, or the distinct
/// corners of an STL's triangles (ASCII or binary: single precision); the points of a
/// text file of one point a line (`.xyz`, `.pts`, `.csv`, `.txt`: `x y z` and perhaps
/// more columns, which are ignored); or points sampled on
/// the rational B-spline surfaces of an IGES file (`.igs`, `.iges`: every entity 128, on
/// a grid of its parameter range, [`IGES_TARGET_POINTS`] points in all; trimming curves
/// are ignored).
///
/// ```
/// let dir = tempfile::tempdir().unwrap();
/// let path = dir.path().join("cloud.obj");
/// std::fs::write(&path, "# a point cloud\nv 0 0 0\nv 1 0 0.5\n").unwrap();
/// let points = monge_io::read_points(&path).unwrap();
/// assert_eq!(points.len(), 2);
/// assert_eq!(points[1].z, 0.5);
/// ```
pub fn read_points(path: &Path) -> Result<Vec<DVec3>, IoError> {
    let file = path_name(path);
    let points = match extension(path).as_deref() {
        Some("igs" | "iges") => return iges_points(&read_to_string(path)?, &file),
        Some("stl") => read_stl_points(&read_file(path)?, &file)?,
        Some("xyz" | "pts" | "csv" | "txt") => read_text_points(&read_to_string(path)?, &file)?,
        _ => match MeshFormat::from_path(path) {
            Ok(MeshFormat::Json) => json_points(&read_to_string(path)?, &file)?,
            Ok(MeshFormat::Glb) => {
                return Err(IoError::UnknownExtension {
                    path: path.to_owned(),
                    found: "glTF (`.glb`, f32 coordinates for viewers)".to_owned(),
                    accepted: TARGET_ACCEPTED,
                })
            }
            Ok(format) => read_vertices(path, format)?,
            Err(IoError::UnknownExtension { .. }) => {
                return Err(unknown_extension(path, TARGET_ACCEPTED))
            }
            Err(e) => return Err(e),
        },
    };
    if points.is_empty() {
        return Err(IoError::Syntax {
            file,
            line: 1,
            message: "no points: a target needs vertices (`v x y z` lines in OBJ, a `vertex` \
                      element in PLY, `vertices` or `points` in JSON, triangles in STL, a line \
                      `x y z` a point in a text file of points)"
                .to_owned(),
        });
    }
    Ok(points)
}

/// The extensions [`read_points`] reads.
const TARGET_ACCEPTED: &str = "a mesh (`.obj`, `.ply`, `.json`, `.stl`), points one per line \
     (`.xyz`, `.pts`, `.csv`, `.txt`) or surfaces (`.igs`, `.iges`)";

/// The points of a text file of one point a line, as scanners and spreadsheets write
/// them (`.xyz`, `.pts`, `.csv`, `.txt`), named `file` (for messages): on each line `x y z` and
/// perhaps more columns (intensity, colour, normal: ignored), separated by spaces,
/// tabs or commas, or by semicolons (then a decimal comma counts as a decimal point). Blank
/// lines, lines beginning with `#` or `//`, a line of one whole number (the count a
/// `.pts` file begins with) and, before the first point, one header line (`x,y,z`)
/// are skipped.
///
/// ```
/// let scan = "x,y,z,intensity\n1,2,3,0.5\n4,5,6.5,0.7\n";
/// let points = monge_io::read_text_points(scan, "scan.csv").unwrap();
/// assert_eq!(points[1].to_array(), [4.0, 5.0, 6.5]);
/// ```
pub fn read_text_points(text: &str, file: &str) -> Result<Vec<DVec3>, IoError> {
    let mut points = Vec::new();
    let mut header = false;
    for (k, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') || line.starts_with("//") {
            continue;
        }
        let tokens: Vec<String> = if line.contains(';') {
            line.split(|c: char| c == ';' || c.is_whitespace())
                .filter(|t| !t.is_empty())
                .map(|t| t.replace(',', "."))
                .collect()
        } else {
            line.split(|c: char| c == ',' || c.is_whitespace())
                .filter(|t| !t.is_empty())
                .map(str::to_owned)
                .collect()
        };
        if tokens.len() == 1 && tokens[0].parse::<u64>().is_ok() {
            continue;
        }
        let numbers: Vec<Result<f64, _>> =
            tokens.iter().take(3).map(|t| t.parse::<f64>()).collect();
        if points.is_empty() && !header && numbers.iter().any(Result::is_err) {
            header = true;
            continue;
        }
        let bad = |message: String| syntax(file, k + 1, message);
        if tokens.len() < 3 {
            return Err(bad(format!(
                "`{line}` has {} number{}: a point is `x y z` (more columns are ignored)",
                tokens.len(),
                if tokens.len() == 1 { "" } else { "s" }
            )));
        }
        let mut p = [0.0; 3];
        for ((x, n), t) in p.iter_mut().zip(numbers).zip(&tokens) {
            *x = n.map_err(|_| bad(format!("`{t}` is not a number (in `{line}`)")))?;
            if !x.is_finite() {
                return Err(bad(format!("`{t}` is not a finite number (in `{line}`)")));
            }
        }
        points.push(DVec3::from_array(p));
    }
    Ok(points)
}

/// About how many points [`read_points`] samples on the surfaces of an IGES target.
pub const IGES_TARGET_POINTS: usize = 4000;

/// The parameters `(u, v)` at which a target's surface is sampled when `surfaces`
/// surfaces make the target: a square grid of `range_u` × `range_v`, ends included, `u`
/// slowest, about [`IGES_TARGET_POINTS`] points in all (at least 5 × 5 a surface). The
/// rule of [`read_points`] for IGES surfaces, and of the Python package for Rhino ones.
///
/// ```
/// let grid: Vec<(f64, f64)> = monge_io::surface_parameters(1000, [0.0, 1.0], [2.0, 4.0]).collect();
/// assert_eq!(grid.len(), 25);
/// assert_eq!((grid[1], grid[24]), ((0.0, 2.5), (1.0, 4.0)));
/// ```
pub fn surface_parameters(
    surfaces: usize,
    range_u: [f64; 2],
    range_v: [f64; 2],
) -> impl Iterator<Item = (f64, f64)> {
    let side = ((IGES_TARGET_POINTS / surfaces.max(1)) as f64)
        .sqrt()
        .ceil() as usize;
    let side = side.max(5);
    let at = move |range: [f64; 2], k: usize| {
        range[0] + (range[1] - range[0]) * k as f64 / (side - 1) as f64
    };
    (0..side * side).map(move |k| (at(range_u, k / side), at(range_v, k % side)))
}

/// Points on every rational B-spline surface of an IGES file, on a square grid of each
/// one's parameter range ([`surface_parameters`]).
fn iges_points(text: &str, file: &str) -> Result<Vec<DVec3>, IoError> {
    let surfaces = read_iges_surfaces(text).map_err(|e| match e {
        IoError::Syntax { line, message, .. } => syntax(file, line, message),
        e => e,
    })?;
    if surfaces.is_empty() {
        return Err(syntax(
            file,
            1,
            "no rational B-spline surface (IGES entity 128): a target needs surfaces, or give \
             its mesh or points as OBJ, PLY or JSON"
                .to_owned(),
        ));
    }
    let n = surfaces.len();
    Ok(surfaces
        .iter()
        .flat_map(|s| surface_parameters(n, s.range_u, s.range_v).map(|(u, v)| s.point(u, v)))
        .collect())
}

fn syntax(file: &str, line: usize, message: String) -> IoError {
    IoError::Syntax {
        file: file.to_owned(),
        line,
        message,
    }
}

#[derive(Deserialize)]
struct PointsJson {
    #[serde(default)]
    vertices: Vec<[f64; 3]>,
    #[serde(default)]
    points: Vec<[f64; 3]>,
}

fn json_points(text: &str, file: &str) -> Result<Vec<DVec3>, IoError> {
    let j: PointsJson = parse_as(text, DesignFormat::Json, file)?;
    Ok(j.vertices
        .into_iter()
        .chain(j.points)
        .map(DVec3::from_array)
        .collect())
}
