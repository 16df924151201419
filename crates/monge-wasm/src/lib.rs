//! # monge-wasm
//!
//! Real-time exploration of the design space (§5.1) in the browser: monge-core
//! compiled to WebAssembly (`wasm32-unknown-unknown`, bound to JavaScript with
//! wasm-bindgen) for the explorer page, which then needs no server.
//!
//! The page parses design files with monge-io's parser (the CLI's messages),
//! generates the mesh (circular or conical, at an offset), asks for the
//! admissible θ, the metrics, and exports OBJ or JSON written by monge-io's
//! writers, so an exported file is the one `monge generate` writes, byte for
//! byte. Trigonometry in monge-core goes through the `libm` crate, so the
//! vertices are the same bits here as in the native build.
//!
//! Every function also compiles natively (the JavaScript types are only
//! touched when called), so the workspace's lints and tests cover the crate.

use glam::DVec3;
use js_sys::{Float32Array, Float64Array};
use monge_core::{generate as generate_mesh, inspect, Design, GenerateOptions, Generated};
use monge_core::{MeshKind, QuadGrid};
use monge_io::generated::{json_extras, kind_name, layers, metrics_json, mode_name, report_json};
use monge_io::{parse_design_named, write_mesh_json, write_mesh_to, DesignFormat, MeshFormat};
use serde_json::json;
use wasm_bindgen::prelude::*;

/// A design file's text (JSON, or TOML when `toml`) → the design re-encoded as
/// JSON text (§3), or the CLI's message naming the file `name`.
#[wasm_bindgen(js_name = parseDesign)]
pub fn parse_design(text: &str, name: &str, toml: bool) -> Result<String, JsError> {
    let design = parse(text, name, toml).map_err(|e| JsError::new(&e))?;
    Ok(design_json(&design))
}

/// The validated design's mode and admissible θ (§3.1, §3.2) as JSON text:
/// `{"mode", "theta_deg", "theta_range": {"min_deg", "max_deg"}, "rows", "cols"}`;
/// θ itself is not checked. `text` is a design as JSON.
#[wasm_bindgen]
pub fn info(text: &str, name: &str, max_vertices: usize) -> Result<String, JsError> {
    design_info(text, name, max_vertices).map_err(|e| JsError::new(&e))
}

/// Generates the design `text` (JSON, from the file `name`) and its mesh at
/// distance `offset` (§2.2 node offset, §2.3 face offset of a conical mesh),
/// refusing grids of more than `max_vertices` vertices; the CLI's message on
/// error.
#[wasm_bindgen]
pub fn generate(text: &str, name: &str, offset: f64, max_vertices: usize) -> Result<Mesh, JsError> {
    Mesh::new(text, name, offset, max_vertices).map_err(|e| JsError::new(&e))
}

/// A generated mesh (§3): the design's circular mesh, or its conical dual, at
/// an offset, with flat arrays ready to be viewed from JavaScript.
#[wasm_bindgen]
pub struct Mesh {
    generated: Generated,
    kind: MeshKind,
    offset: f64,
    /// The mesh shown and exported.
    grid: QuadGrid,
    /// Its JSON keys beyond `json_extras` (kind, offset, face normals).
    extra: serde_json::Map<String, serde_json::Value>,
    /// `grid`'s vertices, flat `x, y, z, x, …`.
    vertices: Vec<f64>,
    /// The same in f32, for drawing.
    positions: Vec<f32>,
    /// The circular mesh's node axes (its Gauss map), f32, flat.
    normals: Vec<f32>,
    /// The samples of guide_u and guide_v, f32, flat.
    guides: [Vec<f32>; 2],
}

/// Flat `x, y, z, x, …` of `points`.
fn flat(points: &[DVec3]) -> Vec<f64> {
    points.iter().flat_map(|p| p.to_array()).collect()
}

/// Flat f32 `x, y, z, x, …` of `points`, for drawing.
fn flat32(points: &[DVec3]) -> Vec<f32> {
    points
        .iter()
        .flat_map(|p| p.to_array())
        .map(|x| x as f32)
        .collect()
}

/// Parses a design file's text with the CLI's messages naming `name`.
fn parse(text: &str, name: &str, toml: bool) -> Result<Design, String> {
    let format = if toml {
        DesignFormat::Toml
    } else {
        DesignFormat::Json
    };
    parse_design_named(text, format, name).map_err(|e| e.to_string())
}

/// The design as JSON text.
fn design_json(design: &Design) -> String {
    serde_json::to_value(design)
        .map(|v| v.to_string())
        .unwrap_or_default()
}

/// [`info`] with the message as a `String`.
fn design_info(text: &str, name: &str, max_vertices: usize) -> Result<String, String> {
    let design = parse(text, name, false)?;
    let info =
        inspect(&design, &GenerateOptions { max_vertices }).map_err(|e| format!("{name}: {e}"))?;
    Ok(json!({
        "mode": mode_name(info.mode),
        "theta_deg": info.theta_deg,
        "theta_range": { "min_deg": info.theta_range.min_deg, "max_deg": info.theta_range.max_deg },
        "rows": info.guide_u.points.len(),
        "cols": info.guide_v.points.len(),
    })
    .to_string())
}

impl Mesh {
    /// [`generate`] with the message as a `String`.
    fn new(text: &str, name: &str, offset: f64, max_vertices: usize) -> Result<Mesh, String> {
        if !offset.is_finite() {
            return Err(format!("offset `{offset}` is not a finite number"));
        }
        let design = parse(text, name, false)?;
        let generated = generate_mesh(&design, &GenerateOptions { max_vertices })
            .map_err(|e| format!("{name}: {e}"))?;
        let layer = layers(&generated, design.mesh, &[offset])
            .pop()
            .ok_or("no mesh was generated")?;
        let info = &generated.info;
        Ok(Mesh {
            vertices: flat(&layer.grid.vertices),
            positions: flat32(&layer.grid.vertices),
            normals: flat32(&generated.grid.normals),
            guides: [flat32(&info.guide_u.points), flat32(&info.guide_v.points)],
            kind: design.mesh,
            offset,
            grid: layer.grid.into_owned(),
            extra: layer.extra,
            generated,
        })
    }

    /// The mesh file `monge generate` writes, `obj` or `json`.
    fn file(&self, format: &str) -> Result<Vec<u8>, String> {
        let mut out = Vec::new();
        let written = match format {
            "obj" => write_mesh_to(&self.grid, MeshFormat::Obj, &mut out),
            "json" => {
                let mut extra = json_extras(&self.generated);
                extra.extend(self.extra.clone());
                write_mesh_json(&self.grid, &extra, &mut out)
            }
            other => {
                return Err(format!(
                    "`{other}` is not an export format: give obj or json"
                ))
            }
        };
        written.map_err(|e| format!("cannot write the mesh: {e}"))?;
        Ok(out)
    }

    /// [`Mesh::header`] as a JSON value.
    fn header_value(&self) -> serde_json::Value {
        let g = &self.generated;
        let guide = |guide: &monge_core::guide::Guide| json!({ "tangent": guide.tangent.to_array(), "plane_normal": guide.plane_normal.to_array() });
        json!({
            "rows": self.grid.rows,
            "cols": self.grid.cols,
            "kind": kind_name(self.kind),
            "offset": self.offset,
            "gauss": { "rows": g.grid.rows, "cols": g.grid.cols },
            "guides": { "u": guide(&g.info.guide_u), "v": guide(&g.info.guide_v) },
            "theta_deg": g.info.theta_deg,
            "mode": mode_name(g.info.mode),
            "theta_range": { "min_deg": g.info.theta_range.min_deg, "max_deg": g.info.theta_range.max_deg },
            "report": report_json(&g.report),
        })
    }
}

#[wasm_bindgen]
impl Mesh {
    /// Everything but the arrays, as JSON text: `rows`, `cols`, `kind`,
    /// `offset`, `gauss` (`rows`, `cols`), `guides` (`u`, `v`: unit start
    /// `tangent`, `plane_normal`), `theta_deg`, `mode`, `theta_range`
    /// (`min_deg`, `max_deg`) and `report` (folds and pinches, §5.2).
    pub fn header(&self) -> String {
        self.header_value().to_string()
    }

    /// The vertices (f64, row-major, flat), a view into the module's memory:
    /// copy it before the next call into the module.
    pub fn vertices(&self) -> Float64Array {
        // SAFETY: a view of memory owned by `self`, valid until the module
        // allocates again; the page and the tests copy it at once.
        unsafe { Float64Array::view(&self.vertices) }
    }

    /// The vertices in f32, for drawing: a view, as [`Mesh::vertices`].
    pub fn positions(&self) -> Float32Array {
        // SAFETY: as in `vertices`.
        unsafe { Float32Array::view(&self.positions) }
    }

    /// The node axes of the circular mesh (its Gauss map, §2.2.1) in f32: a
    /// view, as [`Mesh::vertices`].
    pub fn normals(&self) -> Float32Array {
        // SAFETY: as in `vertices`.
        unsafe { Float32Array::view(&self.normals) }
    }

    /// The samples of guide_u (`u`) or guide_v in f32: a view, as [`Mesh::vertices`].
    #[wasm_bindgen(js_name = guidePoints)]
    pub fn guide_points(&self, u: bool) -> Float32Array {
        let points = &self.guides[usize::from(!u)];
        // SAFETY: as in `vertices`.
        unsafe { Float32Array::view(points) }
    }

    /// The centre of face (i, j) of the circular mesh (where folds and pinches
    /// are marked, §5.2), `[x, y, z]`.
    #[wasm_bindgen(js_name = faceCentre)]
    pub fn face_centre(&self, i: usize, j: usize) -> Vec<f64> {
        let grid = &self.generated.grid;
        if i + 1 >= grid.rows || j + 1 >= grid.cols {
            return vec![f64::NAN; 3];
        }
        let f = grid.face(i, j);
        ((f[0] + f[1] + f[2] + f[3]) / 4.0).to_array().to_vec()
    }

    /// The metrics as JSON text (§2.2, §2.3): planarity, circularity or the
    /// conical error, planar lines, torsion, `max_error`, `faces`, `panel_area`,
    /// `edge_length`.
    pub fn metrics(&self) -> String {
        metrics_json(&self.grid, self.kind).to_string()
    }

    /// The mesh file `monge generate` writes for this design and offset: `obj` or `json`.
    pub fn export(&self, format: &str) -> Result<Vec<u8>, JsError> {
        self.file(format).map_err(|e| JsError::new(&e))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Figure 13's design (a conical mesh).
    const CONICAL: &str = include_str!("../../../examples/fig13-conical.json");

    #[test]
    fn messages_name_the_file() {
        let e = parse("{ \"theta_deg\": 30,\n", "my.json", false).unwrap_err();
        assert!(e.starts_with("my.json:"), "{e}");
        let e = Mesh::new(CONICAL, "x.json", f64::NAN, 1000).err().unwrap();
        assert!(e.contains("not a finite number"), "{e}");
        let e = Mesh::new(CONICAL, "x.json", 0.0, 10).err().unwrap();
        assert!(e.starts_with("x.json: "), "{e}");
        let e = design_info(CONICAL, "x.json", 10).unwrap_err();
        assert!(e.starts_with("x.json: "), "{e}");
    }

    #[test]
    fn a_toml_design_parses_to_the_json_one() {
        let toml = include_str!("../../../examples/fig14-family.toml");
        let design = parse(toml, "f.toml", true).unwrap();
        let again = parse(&design_json(&design), "f.json", false).unwrap();
        assert_eq!(design, again);
    }

    #[test]
    fn the_header_and_arrays_describe_the_conical_mesh() {
        let mesh = Mesh::new(CONICAL, "c.json", 0.25, 1_000_000).unwrap();
        let h = mesh.header_value();
        let (rows, cols) = (mesh.grid.rows, mesh.grid.cols);
        assert_eq!(h["kind"], "conical");
        assert_eq!(
            h["gauss"]["rows"],
            rows + 1,
            "one conical vertex per circular face"
        );
        assert_eq!(mesh.vertices.len(), 3 * rows * cols);
        assert_eq!(mesh.positions.len(), mesh.vertices.len());
        assert_eq!(mesh.normals.len(), 3 * (rows + 1) * (cols + 1));
        assert!(mesh.face_centre(rows, 0)[0].is_nan());
        assert!(mesh.file("ply").is_err());
        let file = String::from_utf8(mesh.file("json").unwrap()).unwrap();
        let v: serde_json::Value = serde_json::from_str(&file).unwrap();
        assert_eq!(
            (v["kind"].clone(), v["offset"].clone()),
            (json!("conical"), json!(0.25))
        );
        let m: serde_json::Value = serde_json::from_str(&mesh.metrics()).unwrap();
        assert!(m["conical"]["value"].is_number(), "{m}");
    }
}
