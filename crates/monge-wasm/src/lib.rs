//! # monge-wasm
//!
//! Real-time exploration of the design space (§5.1) in the browser: monge-core
//! compiled to WebAssembly (`wasm32-unknown-unknown`, bound to JavaScript with
//! wasm-bindgen) for the explorer page, which then needs no server.
//!
//! The page parses design files with monge-io's parser (the CLI's messages),
//! generates the mesh (circular or conical, at an offset), asks for the
//! admissible θ, the metrics, and exports OBJ, JSON or binary glTF written by
//! monge-io's writers, so an exported file is the one `monge generate` writes,
//! byte for byte. Trigonometry in monge-core goes through the `libm` crate, so the
//! vertices are the same bits here as in the native build.
//!
//! Every function also compiles natively (the JavaScript types are only
//! touched when called), so the workspace's lints and tests cover the crate.

use glam::DVec3;
use js_sys::{Float32Array, Float64Array};
use monge_core::combescure::CombescureReport;
use monge_core::cyclidic::{CyclidicNet, CyclidicOptions};
use monge_core::projective::Line;
use monge_core::{generate as generate_mesh, inspect, Design, GenerateOptions, Generated};
use monge_core::{MeshKind, QuadGrid};
use monge_io::generated::{json_extras, kind_name, layers, metrics_json, mode_name, report_json};
use monge_io::{
    conical_has_no_net, parse_design_named, write_mesh_json, write_mesh_to, write_net_json,
    DesignFormat, MeshFormat,
};
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
    /// The design file's name, for messages.
    name: String,
    generated: Generated,
    kind: MeshKind,
    offset: f64,
    /// The mesh shown and exported.
    grid: QuadGrid,
    /// Its JSON keys beyond `json_extras` (kind, offset, face normals).
    extra: serde_json::Map<String, serde_json::Value>,
    /// Its report (§5.2): its own folds, as `monge generate` writes it.
    report: CombescureReport,
    /// Which of its faces are folded, row-major.
    folded: Vec<bool>,
    /// `grid`'s vertices, flat `x, y, z, x, …`.
    vertices: Vec<f64>,
    /// The same in f32, for drawing.
    positions: Vec<f32>,
    /// The circular mesh's node axes (its Gauss map), f32, flat.
    normals: Vec<f32>,
    /// The samples of guide_u and guide_v, flat.
    guides: [Vec<f64>; 2],
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
            report: layer.report.unwrap_or(generated.report),
            folded: layer.folded_faces(),
            vertices: flat(&layer.grid.vertices),
            positions: flat32(&layer.grid.vertices),
            normals: flat32(&generated.grid.normals),
            guides: [flat(&info.guide_u.points), flat(&info.guide_v.points)],
            kind: design.mesh,
            name: name.to_owned(),
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
            "glb" => write_mesh_to(&self.grid, MeshFormat::Glb, &mut out),
            "json" => {
                let mut extra = json_extras(&self.generated);
                extra.extend(self.extra.clone());
                write_mesh_json(&self.grid, &extra, &mut out)
            }
            other => {
                return Err(format!(
                    "`{other}` is not an export format: give obj, json or glb"
                ))
            }
        };
        written.map_err(|e| format!("cannot write the mesh: {e}"))?;
        Ok(out)
    }

    /// [`Mesh::smooth`] with the message as a `String`.
    fn net(&self, per_arc: usize) -> Result<Net, String> {
        if self.kind == MeshKind::Conical {
            return Err(conical_has_no_net(&self.name));
        }
        let net = CyclidicNet::from_normals(&self.grid, &CyclidicOptions::default())
            .map_err(|e| format!("{}: the cyclidic net: {e}", self.name))?;
        let per_arc = per_arc.max(1);
        let (mut lines, mut arcs, mut segments) = (0, 0, Vec::new());
        for line in net.curvature_lines_iter() {
            lines += 1;
            for arc in &line.arcs {
                arcs += 1;
                let mut from = arc.start;
                for k in 1..=per_arc {
                    let to = arc.point(k as f64 / per_arc as f64);
                    segments.extend(
                        [from, to]
                            .iter()
                            .flat_map(|p| p.to_array())
                            .map(|x| x as f32),
                    );
                    from = to;
                }
            }
        }
        Ok(Net {
            net,
            lines,
            arcs,
            segments,
        })
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
            "report": report_json(&self.report),
            "axes": { "l1": axis_json(&g.axes.l1), "l2": axis_json(&g.axes.l2) },
        })
    }
}

/// A pencil axis of the Gauss map (§2.1.2) as JSON: `{"point", "dir"}`, its
/// point nearest the sphere's centre and its unit direction, or `null` for an
/// axis at infinity (the pencil of parallel planes of great circles' polars).
fn axis_json(line: &Line) -> serde_json::Value {
    // Infinite (or NaN, 0/0) when the direction is zero: the line is at infinity.
    if !line.distance_to_origin().is_finite() {
        return serde_json::Value::Null;
    }
    let d2 = line.dir.length_squared();
    json!({
        "point": (line.dir.cross(line.moment) / d2).to_array(),
        "dir": line.dir.normalize().to_array(),
    })
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

    /// The samples of guide_u (`u`) or guide_v (f64, flat; drawn, and
    /// exported to Rhino as they are): a view, as [`Mesh::vertices`].
    #[wasm_bindgen(js_name = guidePoints)]
    pub fn guide_points(&self, u: bool) -> Float64Array {
        let points = &self.guides[usize::from(!u)];
        // SAFETY: as in `vertices`.
        unsafe { Float64Array::view(points) }
    }

    /// The quads of the mesh shown, four vertex indices each (0-based, flat),
    /// wound as the exported files wind them. A copy.
    pub fn faces(&self) -> Vec<u32> {
        self.grid
            .oriented_faces()
            .flatten()
            .map(|k| k as u32)
            .collect()
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

    /// The area of each face of the mesh shown (§4.8), row-major: face (i, j)
    /// at `i·(cols − 1) + j`. A copy.
    #[wasm_bindgen(js_name = faceAreas)]
    pub fn face_areas(&self) -> Vec<f64> {
        self.grid.face_areas()
    }

    /// Whether each face of the mesh shown is folded (§5.2), 1 or 0, in the
    /// order of [`Mesh::face_areas`]. A copy.
    #[wasm_bindgen(js_name = foldedFaces)]
    pub fn folded_faces(&self) -> Vec<u8> {
        self.folded.iter().map(|&f| u8::from(f)).collect()
    }

    /// The metrics as JSON text (§2.2, §2.3): planarity, circularity or the
    /// conical error, planar lines, torsion, `max_error`, `faces`, `panel_area`,
    /// `edge_length`.
    pub fn metrics(&self) -> String {
        metrics_json(&self.grid, self.kind).to_string()
    }

    /// The mesh file `monge generate` writes for this design and offset: `obj`,
    /// `json` or `glb`.
    pub fn export(&self, format: &str) -> Result<Vec<u8>, JsError> {
        self.file(format).map_err(|e| JsError::new(&e))
    }

    /// The cyclidic net of the mesh shown (§4.4): a C¹ surface of Dupin cyclide
    /// patches whose curvature lines are planar chains of circular arcs, each arc
    /// drawn as `per_arc` chords (at least 1). Circular meshes only: a conical
    /// design gets `monge smooth`'s message, a folded face the net's.
    pub fn smooth(&self, per_arc: usize) -> Result<Net, JsError> {
        self.net(per_arc).map_err(|e| JsError::new(&e))
    }
}

/// The cyclidic net of a mesh (§4.4), ready to draw and to export.
#[wasm_bindgen]
pub struct Net {
    net: CyclidicNet,
    /// Curvature lines (both families).
    lines: usize,
    /// Circular arcs on them, consecutive arcs on one circle merged (§4.6).
    arcs: usize,
    /// The arcs' chords, f32, flat pairs of points `x, y, z, x, y, z, …`.
    segments: Vec<f32>,
}

#[wasm_bindgen]
impl Net {
    /// The number of curvature lines (§4.4).
    pub fn lines(&self) -> usize {
        self.lines
    }

    /// The number of circular arcs on them (§4.6).
    pub fn arcs(&self) -> usize {
        self.arcs
    }

    /// The arcs' chords, for `THREE.LineSegments`: a view, as [`Mesh::vertices`].
    pub fn segments(&self) -> Float32Array {
        // SAFETY: as in `Mesh::vertices`.
        unsafe { Float32Array::view(&self.segments) }
    }

    /// The JSON `monge smooth -o net.json --samples K` writes (§4.4), with
    /// `samples` × `samples` points a patch.
    pub fn export(&self, samples: usize) -> Result<Vec<u8>, JsError> {
        let mut out = Vec::new();
        write_net_json(&self.net, samples, &mut out)
            .map_err(|e| JsError::new(&format!("cannot write the net: {e}")))?;
        Ok(out)
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

    #[test]
    fn face_areas_are_the_two_triangles_and_the_metrics_extremes() {
        for offset in [0.0, 0.25] {
            let mesh = Mesh::new(CONICAL, "c.json", offset, 1_000_000).unwrap();
            let areas = mesh.face_areas();
            let g = &mesh.grid;
            assert_eq!(areas.len(), (g.rows - 1) * (g.cols - 1));
            let max = areas.iter().copied().fold(0.0, f64::max);
            // The faces are planar: two triangles' areas, a different formula.
            for (k, area) in areas.iter().enumerate() {
                let [a, b, c, d] = g.face(k / (g.cols - 1), k % (g.cols - 1));
                let triangles =
                    0.5 * ((b - a).cross(c - a).length() + (c - a).cross(d - a).length());
                assert!(
                    (area - triangles).abs() <= 1e-9 * max,
                    "face {k}: {area} vs {triangles}"
                );
            }
            let m: serde_json::Value = serde_json::from_str(&mesh.metrics()).unwrap();
            let min = areas.iter().copied().fold(f64::INFINITY, f64::min);
            assert_eq!(
                (json!(min), json!(max)),
                (
                    m["panel_area"]["min"].clone(),
                    m["panel_area"]["max"].clone()
                )
            );
        }
    }

    #[test]
    fn folded_faces_are_those_the_generator_reports() {
        // Figure 14's family: unfolded at θ = 20°, folded in hundreds of faces at θ = 84°.
        let toml = include_str!("../../../examples/fig14-family.toml");
        let mut d = serde_json::to_value(parse(toml, "f.toml", true).unwrap()).unwrap();
        let mut folded = Vec::new();
        for theta in [20.0, 84.0] {
            d["theta_deg"] = json!(theta);
            let mesh = Mesh::new(&d.to_string(), "f.json", 0.0, 1_000_000).unwrap();
            let flags = mesh.folded_faces();
            let report = &mesh.generated.report;
            assert_eq!(flags.len(), mesh.grid.face_count());
            assert!(flags.iter().all(|&f| f <= 1));
            let count = flags.iter().filter(|&&f| f == 1).count();
            assert_eq!(count, report.folded_faces, "θ = {theta}");
            let cols = mesh.grid.cols - 1;
            let first = flags.iter().position(|&f| f == 1);
            assert_eq!(first.map(|k| (k / cols, k % cols)), report.first_fold);
            folded.push(count);
        }
        assert!(folded[0] == 0 && folded[1] > 100, "{folded:?}");
    }

    #[test]
    fn the_net_draws_its_arcs_on_their_circles() {
        let circular = CONICAL.replace("\"conical\"", "\"circular\"");
        assert_ne!(circular, CONICAL);
        let e = Mesh::new(CONICAL, "c.json", 0.0, 1_000_000)
            .unwrap()
            .net(4)
            .err()
            .unwrap();
        assert!(
            e.starts_with("c.json: the design asks for a conical mesh"),
            "{e}"
        );
        let mesh = Mesh::new(&circular, "c.json", 0.0, 1_000_000).unwrap();
        let net = mesh.net(4).unwrap();
        let (rows, cols) = (mesh.grid.rows, mesh.grid.cols);
        assert_eq!(net.lines, rows + cols);
        assert!(net.arcs >= net.lines && net.arcs <= rows * (cols - 1) + cols * (rows - 1));
        assert_eq!(net.segments.len(), net.arcs * 4 * 6);
        // Every chord end is on its arc's circle (centre and radius as the net
        // gives them, not from `Arc::point`), in its plane, and the chords join
        // the arc's start to its end.
        let p =
            |k: usize| DVec3::from_array(std::array::from_fn(|c| net.segments[3 * k + c] as f64));
        let size = mesh.vertices.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let arcs = net.net.curvature_lines_iter().flat_map(|l| l.arcs);
        for (a, arc) in arcs.enumerate() {
            let ends: Vec<DVec3> = (0..8).map(|k| p(8 * a + k)).collect();
            for q in &ends {
                let r = *q - arc.center;
                assert!((r.length() - arc.radius).abs() < 1e-6 * size, "arc {a}");
                assert!(arc.normal.dot(r).abs() < 1e-6 * size, "arc {a}");
            }
            assert!((ends[0] - arc.start).length() < 1e-6 * size, "arc {a}");
            assert!((ends[7] - arc.end).length() < 1e-6 * size, "arc {a}");
            for k in [1, 3, 5] {
                assert_eq!(ends[k], ends[k + 1], "arc {a}: chords join");
            }
        }
        let json: serde_json::Value = serde_json::from_slice(&net.export(3).unwrap()).unwrap();
        assert_eq!(
            json["patches"].as_array().unwrap().len(),
            (rows - 1) * (cols - 1)
        );
        assert_eq!(json["lines"].as_array().unwrap().len(), net.lines);
    }

    #[test]
    fn an_axis_at_infinity_is_null() {
        let at_infinity = Line {
            dir: DVec3::ZERO,
            moment: DVec3::X,
        };
        assert!(axis_json(&at_infinity).is_null());
        // θ = 180°: the u-lines are great circles, whose planes meet in L2, through
        // the centre; L1 is then at infinity up to cos 90° ≈ 6e-17 (1.6e16 away).
        let toml = include_str!("../../../examples/fig14-family.toml");
        let mut d = serde_json::to_value(parse(toml, "f.toml", true).unwrap()).unwrap();
        d["theta_deg"] = json!(180.0);
        let mesh = Mesh::new(&d.to_string(), "f.json", 0.0, 1_000_000).unwrap();
        let axes = &mesh.header_value()["axes"];
        let distance = |a: &serde_json::Value| {
            let p: [f64; 3] = serde_json::from_value(a["point"].clone()).unwrap();
            DVec3::from_array(p).length()
        };
        assert!(distance(&axes["l1"]) > 1e15, "{axes}");
        assert!(distance(&axes["l2"]) < 1e-15, "{axes}");
    }

    #[test]
    fn the_pencil_axes_hold_the_planes_of_the_gauss_circles() {
        let mesh = Mesh::new(CONICAL, "c.json", 0.0, 1_000_000).unwrap();
        let h = mesh.header_value();
        let axis = |name: &str| {
            let a = &h["axes"][name];
            let v = |key: &str| DVec3::from_array(serde_json::from_value(a[key].clone()).unwrap());
            (v("point"), v("dir"))
        };
        let ((p1, d1), (p2, d2)) = (axis("l1"), axis("l2"));
        // Polar reciprocal lines (§2.1.2): orthogonal, at distances a and 1/a.
        assert!(d1.dot(d2).abs() < 1e-12 && (p1.length() * p2.length() - 1.0).abs() < 1e-12);
        // Each v-line of the Gauss map (fixed i) lies in a plane through L1, each u-line through L2.
        let g = &mesh.generated.grid;
        for (i, j) in [(0, 0), (g.rows / 2, g.cols / 3), (g.rows - 1, g.cols - 1)] {
            let n = |i, j| g.normals[g.index(i, j)];
            let row_plane = d1.cross(n(i, 0) - p1).normalize();
            let col_plane = d2.cross(n(0, j) - p2).normalize();
            for k in 0..g.cols {
                assert!(
                    row_plane.dot(n(i, k) - p1).abs() < 1e-9,
                    "row {i}, column {k}"
                );
            }
            for k in 0..g.rows {
                assert!(
                    col_plane.dot(n(k, j) - p2).abs() < 1e-9,
                    "column {j}, row {k}"
                );
            }
        }
    }
}
