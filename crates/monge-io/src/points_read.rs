//! Target readers for `monge approximate`: the points of any OBJ, PLY (ASCII or
//! binary little-endian) or JSON mesh or point cloud, whatever its faces
//! (triangles, quads, none).

use std::path::Path;

use glam::DVec3;
use serde::Deserialize;

use crate::design::parse_as;
use crate::error::IoError;
use crate::format::{DesignFormat, MeshFormat};
use crate::iges::read_iges_surfaces;
use crate::mesh_read::read_vertices;
use crate::read::{path_name, read_to_string};

/// Reads the points of a target: the vertices of an OBJ (`v` lines; faces, if any, are
/// ignored), of a PLY, ASCII or binary little-endian (`x`, `y`, `z` of the `vertex`
/// element, read by the mesh reader's PLY code), or of a JSON file
/// with `vertices` (a monge mesh) or `points`, each `[x, y, z]`; or points sampled on
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
    let extension = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    if matches!(extension.as_deref(), Some("igs" | "iges")) {
        return iges_points(&read_to_string(path)?, &file);
    }
    let format = MeshFormat::from_path(path)?;
    if format == MeshFormat::Glb {
        return Err(IoError::UnknownExtension {
            path: path.to_owned(),
            found: "glTF (`.glb`, f32 coordinates for viewers)".to_owned(),
            accepted: "`.obj`, `.ply` or `.json`",
        });
    }
    let points = match format {
        MeshFormat::Json => json_points(&read_to_string(path)?, &file)?,
        _ => read_vertices(path, format)?,
    };
    if points.is_empty() {
        return Err(IoError::Syntax {
            file,
            line: 1,
            message: "no points: a target needs vertices (`v x y z` lines in OBJ, a `vertex` \
                      element in PLY, `vertices` or `points` in JSON)"
                .to_owned(),
        });
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
