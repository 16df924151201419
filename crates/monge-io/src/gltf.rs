//! A binary glTF 2.0 (`.glb`) of the whole gridshell (§6, Figure 25): every
//! layer's panels and its beams as swept solids.
//!
//! Built with `gltf-json`; positions are `f32` as the glTF specification
//! requires, so the file is for looking at the assembly, not for the 1e-9
//! geometry (the schedules keep full `f64`).

use std::collections::BTreeMap;
use std::io::{self, Write};

use glam::DVec3;
use gltf_json as json;
use json::validation::{Checked::Valid, USize64};
use monge_core::fabrication::{Beam, Fabrication};
use monge_core::QuadGrid;

/// Binary data and the glTF objects that describe it, being built.
struct Builder {
    root: json::Root,
    bin: Vec<u8>,
}

impl Builder {
    /// An empty document made by `generator`, with one scene called `scene`.
    fn new(generator: &str, scene: &str) -> Builder {
        let mut b = Builder {
            root: json::Root {
                asset: json::Asset {
                    generator: Some(generator.into()),
                    ..Default::default()
                },
                ..Default::default()
            },
            bin: Vec::new(),
        };
        let scene = b.root.push(json::Scene {
            extensions: None,
            extras: Default::default(),
            name: Some(scene.into()),
            nodes: Vec::new(),
        });
        b.root.scene = Some(scene);
        b
    }

    /// Writes the document as binary glTF (`.glb`).
    fn finish(mut self, w: &mut (impl Write + ?Sized)) -> io::Result<()> {
        while self.bin.len() % 4 != 0 {
            self.bin.push(0);
        }
        self.root.push(json::Buffer {
            byte_length: USize64::from(self.bin.len()),
            name: None,
            uri: None,
            extensions: None,
            extras: Default::default(),
        });
        let mut text = self.root.to_vec().map_err(io::Error::other)?;
        while text.len() % 4 != 0 {
            text.push(b' ');
        }
        let total = 12 + 8 + text.len() + 8 + self.bin.len();
        let total = u32::try_from(total).map_err(|_| io::Error::other("glTF larger than 4 GiB"))?;
        w.write_all(b"glTF")?;
        w.write_all(&2u32.to_le_bytes())?;
        w.write_all(&total.to_le_bytes())?;
        w.write_all(&(text.len() as u32).to_le_bytes())?;
        w.write_all(b"JSON")?;
        w.write_all(&text)?;
        w.write_all(&(self.bin.len() as u32).to_le_bytes())?;
        w.write_all(b"BIN\0")?;
        w.write_all(&self.bin)
    }

    /// Appends `bytes` as a buffer view (4-byte aligned) and returns its index.
    fn view(
        &mut self,
        bytes: &[u8],
        target: json::buffer::Target,
    ) -> json::Index<json::buffer::View> {
        while self.bin.len() % 4 != 0 {
            self.bin.push(0);
        }
        let offset = self.bin.len();
        self.bin.extend_from_slice(bytes);
        self.root.push(json::buffer::View {
            buffer: json::Index::new(0),
            byte_length: USize64::from(bytes.len()),
            byte_offset: Some(USize64::from(offset)),
            byte_stride: None,
            name: None,
            target: Some(Valid(target)),
            extensions: None,
            extras: Default::default(),
        })
    }

    /// A triangle mesh named `name` with material `material`; `None` if empty.
    fn mesh(&mut self, name: String, positions: &[DVec3], triangles: &[u32], material: u32) {
        if triangles.is_empty() {
            return;
        }
        let p32: Vec<[f32; 3]> = positions.iter().map(|p| p.as_vec3().to_array()).collect();
        let (lo, hi) = p32.iter().fold(
            ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]),
            |(lo, hi), p| {
                (
                    [lo[0].min(p[0]), lo[1].min(p[1]), lo[2].min(p[2])],
                    [hi[0].max(p[0]), hi[1].max(p[1]), hi[2].max(p[2])],
                )
            },
        );
        let bytes: Vec<u8> = p32.iter().flatten().flat_map(|c| c.to_le_bytes()).collect();
        let view = self.view(&bytes, json::buffer::Target::ArrayBuffer);
        let positions = self.root.push(json::Accessor {
            buffer_view: Some(view),
            byte_offset: None,
            count: USize64::from(p32.len()),
            component_type: Valid(json::accessor::GenericComponentType(
                json::accessor::ComponentType::F32,
            )),
            extensions: None,
            extras: Default::default(),
            type_: Valid(json::accessor::Type::Vec3),
            min: Some(json::Value::from(lo.to_vec())),
            max: Some(json::Value::from(hi.to_vec())),
            name: None,
            normalized: false,
            sparse: None,
        });
        let bytes: Vec<u8> = triangles.iter().flat_map(|i| i.to_le_bytes()).collect();
        let view = self.view(&bytes, json::buffer::Target::ElementArrayBuffer);
        let indices = self.root.push(json::Accessor {
            buffer_view: Some(view),
            byte_offset: None,
            count: USize64::from(triangles.len()),
            component_type: Valid(json::accessor::GenericComponentType(
                json::accessor::ComponentType::U32,
            )),
            extensions: None,
            extras: Default::default(),
            type_: Valid(json::accessor::Type::Scalar),
            min: None,
            max: None,
            name: None,
            normalized: false,
            sparse: None,
        });
        let primitive = json::mesh::Primitive {
            attributes: BTreeMap::from([(Valid(json::mesh::Semantic::Positions), positions)]),
            extensions: None,
            extras: Default::default(),
            indices: Some(indices),
            material: Some(json::Index::new(material)),
            mode: Valid(json::mesh::Mode::Triangles),
            targets: None,
        };
        let mesh = self.root.push(json::Mesh {
            extensions: None,
            extras: Default::default(),
            name: Some(name.clone()),
            primitives: vec![primitive],
            weights: None,
        });
        let node = self.root.push(json::Node {
            mesh: Some(mesh),
            name: Some(name),
            ..Default::default()
        });
        self.root.scenes[0].nodes.push(node);
    }
}

/// A material of one colour (RGBA), double-sided.
fn material(name: &str, rgba: [f32; 4]) -> json::Material {
    json::Material {
        name: Some(name.to_owned()),
        pbr_metallic_roughness: json::material::PbrMetallicRoughness {
            base_color_factor: json::material::PbrBaseColorFactor(rgba),
            metallic_factor: json::material::StrengthFactor(if rgba[3] < 1.0 { 0.0 } else { 0.8 }),
            ..Default::default()
        },
        alpha_mode: Valid(if rgba[3] < 1.0 {
            json::material::AlphaMode::Blend
        } else {
            json::material::AlphaMode::Opaque
        }),
        double_sided: true,
        ..Default::default()
    }
}

/// A rectangular tube of `width` (along the beam plane's normal) by `depth`
/// (in the plane) along a beam's nodes, mitred at every node, with end caps (§6).
fn sweep(
    beam: &Beam,
    width: f64,
    depth: f64,
    positions: &mut Vec<DVec3>,
    triangles: &mut Vec<u32>,
) {
    let fr = &beam.frame;
    let points: Vec<DVec3> = beam.nodes.iter().map(|q| fr.to_space(*q)).collect();
    let n = points.len();
    let dir = |k: usize| (points[k + 1] - points[k]).normalize();
    let base = positions.len() as u32;
    for (k, point) in points.iter().enumerate() {
        let (tangent, along) = match k {
            0 => (dir(0), dir(0)),
            _ if k == n - 1 => (dir(k - 1), dir(k - 1)),
            _ => ((dir(k - 1) + dir(k)).normalize(), dir(k)),
        };
        // The in-plane section axis, lengthened so the mitre keeps the depth.
        let m = fr.normal.cross(tangent) / tangent.dot(along).max(0.2);
        let (u, v) = (0.5 * width * fr.normal, 0.5 * depth * m);
        for (a, b) in [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)] {
            positions.push(*point + a * u + b * v);
        }
    }
    for k in 0..n as u32 - 1 {
        for c in 0..4 {
            let (a, b) = (base + 4 * k + c, base + 4 * k + (c + 1) % 4);
            triangles.extend([a, b, b + 4, a, b + 4, a + 4]);
        }
    }
    let last = base + 4 * (n as u32 - 1);
    triangles.extend([base, base + 2, base + 1, base, base + 3, base + 2]);
    triangles.extend([last, last + 1, last + 2, last, last + 2, last + 3]);
}

/// The whole assembly as binary glTF (§6): for each layer `k`, a mesh
/// `layer k panels` (its faces, two triangles each, translucent) and a mesh
/// `layer k beams` (every row and column swept with a `width × depth`
/// rectangular section: `width` along the beam plane's normal, `depth` in the plane).
pub fn write_glb(f: &Fabrication, width: f64, depth: f64, w: &mut dyn Write) -> io::Result<()> {
    let mut b = Builder::new("monge fabricate", "gridshell");
    b.root.push(material("glass", [0.55, 0.75, 0.95, 0.4]));
    b.root.push(material("steel", [0.45, 0.45, 0.5, 1.0]));
    for (k, layer) in f.layers.iter().enumerate() {
        let g = &layer.grid;
        b.mesh(
            format!("layer {k} panels"),
            &g.vertices,
            &grid_triangles(g),
            0,
        );
        let (mut positions, mut triangles) = (Vec::new(), Vec::new());
        for beam in f.beams.iter().filter(|beam| beam.layer == k) {
            sweep(beam, width, depth, &mut positions, &mut triangles);
        }
        b.mesh(format!("layer {k} beams"), &positions, &triangles, 1);
    }
    b.finish(w)
}

/// Two triangles per face of a quad grid, wound about its node axes.
fn grid_triangles(g: &QuadGrid) -> Vec<u32> {
    quad_triangles(g.oriented_faces())
}

/// Two triangles per quad of vertex indices.
fn quad_triangles(quads: impl IntoIterator<Item = [usize; 4]>) -> Vec<u32> {
    quads
        .into_iter()
        .flat_map(|q| {
            let [a, b, c, d] = q.map(|v| v as u32);
            [a, b, c, a, c, d]
        })
        .collect()
}

/// A quad mesh as binary glTF (`.glb`): one double-sided mesh, two triangles a
/// quad, positions in `f32` as glTF requires — for looking at a mesh in any
/// glTF viewer, not for its 1e-9 geometry (keep OBJ, PLY or JSON for that).
///
/// ```
/// use glam::DVec3;
/// use monge_core::QuadGrid;
/// let g = QuadGrid::new(2, 2, vec![DVec3::ZERO, DVec3::Y, DVec3::X, DVec3::X + DVec3::Y], vec![]);
/// let mut glb = Vec::new();
/// monge_io::write_quads_glb(&g.vertices, [[0, 2, 3, 1]], &mut glb).unwrap();
/// assert_eq!(&glb[..4], b"glTF");
/// ```
pub fn write_quads_glb<W: Write + ?Sized>(
    vertices: &[DVec3],
    quads: impl IntoIterator<Item = [usize; 4]>,
    w: &mut W,
) -> io::Result<()> {
    surface_glb(vertices, &quad_triangles(quads), w)
}

/// A quad grid as binary glTF (see [`write_quads_glb`]).
pub fn write_grid_glb<W: Write + ?Sized>(grid: &QuadGrid, w: &mut W) -> io::Result<()> {
    surface_glb(&grid.vertices, &grid_triangles(grid), w)
}

/// One surface of triangles as binary glTF.
fn surface_glb<W: Write + ?Sized>(
    vertices: &[DVec3],
    triangles: &[u32],
    w: &mut W,
) -> io::Result<()> {
    let mut b = Builder::new("monge", "mesh");
    b.root.push(material("surface", [0.62, 0.72, 0.85, 1.0]));
    b.mesh("surface".to_owned(), vertices, triangles, 0);
    b.finish(w)
}
