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

use crate::faces::{Faces, GridFaces};
use crate::text::{emit, Out};

/// Calls its argument with every item of a part, in order.
type Producer<'a, T> = Box<dyn Fn(&mut dyn FnMut(T)) + 'a>;

/// One triangle mesh of a `.glb`, produced on demand: the writer asks for it
/// twice, once for its size and bounds and once for its bytes, and never holds
/// its binary data.
struct Part<'a> {
    name: String,
    material: u32,
    shape: Shape<'a>,
}

/// The vertices and triangles of a [`Part`].
enum Shape<'a> {
    /// The vertices of a quad grid, and its faces, two triangles each, wound
    /// as [`QuadGrid::oriented_faces`].
    Grid(GridFaces<'a>),
    /// Vertices and triangles from producers.
    Produced {
        /// Calls its argument with every vertex, in order.
        positions: Producer<'a, DVec3>,
        /// Calls its argument with every triangle (indices into the vertices).
        triangles: Producer<'a, [u32; 3]>,
    },
}

impl Shape<'_> {
    /// The number of vertices, their bounds (`f32`) and the number of indices;
    /// an error if a vertex is not finite in `f32` (glTF's positions are `f32`).
    fn size(&self, part: &str) -> io::Result<(usize, [[f32; 3]; 2], usize)> {
        let widen = |bounds: &mut [[f32; 3]; 2], [lo, hi]: [[f32; 3]; 2]| {
            for k in 0..3 {
                bounds[0][k] = bounds[0][k].min(lo[k]);
                bounds[1][k] = bounds[1][k].max(hi[k]);
            }
        };
        // Widens `bounds` by `p`; whether `p` is finite in `f32`.
        let bound = |bounds: &mut [[f32; 3]; 2], p: DVec3| {
            let q = p.as_vec3();
            widen(bounds, [q.to_array(); 2]);
            q.is_finite()
        };
        let mut bounds = [[f32::INFINITY; 3], [f32::NEG_INFINITY; 3]];
        let mut finite = true;
        let (count, indices) = match self {
            Shape::Grid(faces) => {
                let vertices = &faces.grid.vertices;
                // Blocks of vertices side by side (min and max in any order).
                let blocks =
                    monge_core::tasks::ranges(vertices.len(), monge_core::tasks::BLOCK, |r| {
                        let mut block = [[f32::INFINITY; 3], [f32::NEG_INFINITY; 3]];
                        let finite = vertices[r]
                            .iter()
                            .fold(true, |ok, p| bound(&mut block, *p) & ok);
                        (block, finite)
                    });
                for (b, ok) in blocks {
                    widen(&mut bounds, b);
                    finite &= ok;
                }
                (vertices.len(), 6 * faces.count())
            }
            Shape::Produced {
                positions,
                triangles,
            } => {
                let mut count = 0;
                positions(&mut |p| {
                    finite &= bound(&mut bounds, p);
                    count += 1;
                });
                let mut indices = 0;
                triangles(&mut |_| indices += 3);
                (count, indices)
            }
        };
        if !finite {
            return Err(io::Error::new(
                io::ErrorKind::InvalidData,
                format!(
                    "the part `{part}` has a coordinate that is not finite in 32-bit floats (NaN, \
                     infinite, or beyond ±3.4e38), which glTF stores: rescale the model or \
                     write another format"
                ),
            ));
        }
        Ok((count, bounds, indices))
    }

    /// Appends the positions (`f32`), then the indices (`u32`).
    fn write<W: Write + ?Sized>(&self, o: &mut Out<'_, W>) -> io::Result<()> {
        match self {
            Shape::Grid(faces) => {
                o.each(&faces.grid.vertices, |o, _, p| put_position(o, *p))?;
                faces.each(o, |o, corners| {
                    let [a, b, c, d] = corners.map(|v| v as u32);
                    put_words(o, [a, b, c, a, c, d]);
                })
            }
            Shape::Produced {
                positions,
                triangles,
            } => {
                let mut result = Ok(());
                positions(&mut |p| {
                    if result.is_ok() {
                        put_position(o, p);
                        result = o.maybe_flush();
                    }
                });
                triangles(&mut |t| {
                    if result.is_ok() {
                        put_words(o, t);
                        result = o.maybe_flush();
                    }
                });
                result
            }
        }
    }
}

/// Appends a position as three little-endian `f32`.
fn put_position<W: Write + ?Sized>(o: &mut Out<'_, W>, p: DVec3) {
    put_words(o, p.as_vec3().to_array().map(f32::to_bits));
}

/// Appends `words` (at most six: a position, a triangle or a quad's two) as
/// little-endian `u32`, at once.
#[inline]
fn put_words<W: Write + ?Sized, const N: usize>(o: &mut Out<'_, W>, words: [u32; N]) {
    let mut bytes = [0u8; 24];
    for (b, w) in bytes.chunks_exact_mut(4).zip(words) {
        b.copy_from_slice(&w.to_le_bytes());
    }
    o.bytes(&bytes[..4 * N]);
}

/// A buffer view of `len` bytes at `offset` of the binary chunk.
fn view(
    root: &mut json::Root,
    offset: usize,
    len: usize,
    target: json::buffer::Target,
) -> json::Index<json::buffer::View> {
    root.push(json::buffer::View {
        buffer: json::Index::new(0),
        byte_length: USize64::from(len),
        byte_offset: Some(USize64::from(offset)),
        byte_stride: None,
        name: None,
        target: Some(Valid(target)),
        extensions: None,
        extras: Default::default(),
    })
}

/// An accessor of `count` elements of `type_` and `component` in `view`.
fn accessor(
    root: &mut json::Root,
    view: json::Index<json::buffer::View>,
    count: usize,
    component: json::accessor::ComponentType,
    type_: json::accessor::Type,
    bounds: Option<([f32; 3], [f32; 3])>,
) -> json::Index<json::Accessor> {
    root.push(json::Accessor {
        buffer_view: Some(view),
        byte_offset: None,
        count: USize64::from(count),
        component_type: Valid(json::accessor::GenericComponentType(component)),
        extensions: None,
        extras: Default::default(),
        type_: Valid(type_),
        min: bounds.map(|(lo, _)| json::Value::from(lo.to_vec())),
        max: bounds.map(|(_, hi)| json::Value::from(hi.to_vec())),
        name: None,
        normalized: false,
        sparse: None,
    })
}

/// Writes a binary glTF (`.glb`) made by `generator`: one scene `scene`, the
/// `materials`, and one mesh and node per non-empty part, streaming the binary
/// chunk (its length is known from a first pass over the parts). With a
/// `base`, every node's `translation` is that point, written as exact f64
/// numbers (glTF's JSON numbers; `gltf-json` would round them to f32).
fn write_parts<W: Write + ?Sized>(
    generator: &str,
    scene: &str,
    materials: Vec<json::Material>,
    parts: &[Part<'_>],
    base: Option<DVec3>,
    w: &mut W,
) -> io::Result<()> {
    let mut root = json::Root {
        asset: json::Asset {
            generator: Some(generator.into()),
            ..Default::default()
        },
        ..Default::default()
    };
    let scene = root.push(json::Scene {
        extensions: None,
        extras: Default::default(),
        name: Some(scene.into()),
        nodes: Vec::new(),
    });
    root.scene = Some(scene);
    for m in materials {
        root.push(m);
    }
    let mut offset = 0;
    let mut kept = Vec::new();
    for part in parts {
        let (count, [lo, hi], indices) = part.shape.size(&part.name)?;
        if indices == 0 {
            continue;
        }
        use json::accessor::{ComponentType, Type};
        let v = view(
            &mut root,
            offset,
            12 * count,
            json::buffer::Target::ArrayBuffer,
        );
        let positions = accessor(
            &mut root,
            v,
            count,
            ComponentType::F32,
            Type::Vec3,
            Some((lo, hi)),
        );
        offset += 12 * count;
        let v = view(
            &mut root,
            offset,
            4 * indices,
            json::buffer::Target::ElementArrayBuffer,
        );
        offset += 4 * indices;
        let indices = accessor(
            &mut root,
            v,
            indices,
            ComponentType::U32,
            Type::Scalar,
            None,
        );
        let primitive = json::mesh::Primitive {
            attributes: BTreeMap::from([(Valid(json::mesh::Semantic::Positions), positions)]),
            extensions: None,
            extras: Default::default(),
            indices: Some(indices),
            material: Some(json::Index::new(part.material)),
            mode: Valid(json::mesh::Mode::Triangles),
            targets: None,
        };
        let mesh = root.push(json::Mesh {
            extensions: None,
            extras: Default::default(),
            name: Some(part.name.clone()),
            primitives: vec![primitive],
            weights: None,
        });
        let node = root.push(json::Node {
            mesh: Some(mesh),
            name: Some(part.name.clone()),
            ..Default::default()
        });
        root.scenes[0].nodes.push(node);
        kept.push(part);
    }
    root.push(json::Buffer {
        byte_length: USize64::from(offset),
        name: None,
        uri: None,
        extensions: None,
        extras: Default::default(),
    });
    let mut text = match base {
        None => root.to_vec(),
        Some(b) => root.to_value().and_then(|mut doc| {
            for node in doc["nodes"].as_array_mut().into_iter().flatten() {
                node["translation"] = json::Value::from(b.to_array().to_vec());
            }
            serde_json::to_vec(&doc)
        }),
    }
    .map_err(io::Error::other)?;
    while text.len() % 4 != 0 {
        text.push(b' ');
    }
    let total = 12 + 8 + text.len() + 8 + offset;
    let too_large = |_| io::Error::other("glTF larger than 4 GiB");
    let total = u32::try_from(total).map_err(too_large)?;
    let bin = u32::try_from(offset).map_err(too_large)?;
    emit(w, |o| {
        o.str("glTF");
        o.bytes(&2u32.to_le_bytes());
        o.bytes(&total.to_le_bytes());
        o.bytes(&(text.len() as u32).to_le_bytes());
        o.str("JSON");
        o.bytes(&text);
        o.bytes(&bin.to_le_bytes());
        o.str("BIN\0");
        for part in kept {
            part.shape.write(o)?;
        }
        Ok(())
    })
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

/// The vertices of a rectangular tube of `width` (along the beam plane's
/// normal) by `depth` (in the plane) along a beam's nodes, mitred at every
/// node (§6): four per node.
fn sweep_positions(beam: &Beam, width: f64, depth: f64, f: &mut dyn FnMut(DVec3)) {
    let fr = &beam.frame;
    let points: Vec<DVec3> = beam.nodes.iter().map(|q| fr.to_space(*q)).collect();
    let n = points.len();
    let dir = |k: usize| (points[k + 1] - points[k]).normalize();
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
            f(*point + a * u + b * v);
        }
    }
}

/// The triangles of the tube of [`sweep_positions`] along `n` nodes whose
/// first vertex is `base`: four sides between consecutive nodes, and end caps.
fn sweep_triangles(base: u32, n: u32, f: &mut dyn FnMut([u32; 3])) {
    for k in 0..n - 1 {
        for c in 0..4 {
            let (a, b) = (base + 4 * k + c, base + 4 * k + (c + 1) % 4);
            f([a, b, b + 4]);
            f([a, b + 4, a + 4]);
        }
    }
    let last = base + 4 * (n - 1);
    f([base, base + 2, base + 1]);
    f([base, base + 3, base + 2]);
    f([last, last + 1, last + 2]);
    f([last, last + 2, last + 3]);
}

/// The whole assembly as binary glTF (§6): for each layer `k`, a mesh
/// `layer k panels` (its faces, two triangles each, translucent) and a mesh
/// `layer k beams` (every row and column swept with a `width × depth`
/// rectangular section: `width` along the beam plane's normal, `depth` in the plane).
/// With a `base`, the coordinates are relative to it and every node is
/// translated by it (as [`write_mesh_at`](crate::write_mesh_at) does).
pub fn write_glb(
    f: &Fabrication,
    width: f64,
    depth: f64,
    base: Option<DVec3>,
    w: &mut dyn Write,
) -> io::Result<()> {
    let mut parts = Vec::new();
    for (k, layer) in f.layers.iter().enumerate() {
        parts.push(grid_part(format!("layer {k} panels"), 0, &layer.grid));
        let positions = Box::new(move |emit: &mut dyn FnMut(DVec3)| {
            for beam in f.layer_beams(k) {
                sweep_positions(&beam, width, depth, emit);
            }
        });
        let triangles = Box::new(move |emit: &mut dyn FnMut([u32; 3])| {
            let mut base = 0;
            for n in f.layer_beam_nodes(k) {
                sweep_triangles(base, n as u32, emit);
                base += 4 * n as u32;
            }
        });
        parts.push(Part {
            name: format!("layer {k} beams"),
            material: 1,
            shape: Shape::Produced {
                positions,
                triangles,
            },
        });
    }
    let materials = vec![
        material("glass", [0.55, 0.75, 0.95, 0.4]),
        material("steel", [0.45, 0.45, 0.5, 1.0]),
    ];
    write_parts("monge fabricate", "gridshell", materials, &parts, base, w)
}

/// The faces of a quad grid, two triangles each, wound about its node axes.
fn grid_part(name: String, material: u32, g: &QuadGrid) -> Part<'_> {
    let shape = Shape::Grid(GridFaces::of(g));
    Part {
        name,
        material,
        shape,
    }
}

/// A part of `vertices` and the faces that `faces` yields (triangles, quads, or convex
/// polygons), each a fan of triangles from its first corner: two triangles a quad.
fn faces_part<'a, F: AsRef<[usize]>, I: IntoIterator<Item = F>>(
    name: String,
    material: u32,
    vertices: &'a [DVec3],
    faces: impl Fn() -> I + 'a,
) -> Part<'a> {
    let positions =
        Box::new(move |emit: &mut dyn FnMut(DVec3)| vertices.iter().for_each(|p| emit(*p)));
    let triangles = Box::new(move |emit: &mut dyn FnMut([u32; 3])| {
        for face in faces() {
            let f = face.as_ref();
            for k in 1..f.len().saturating_sub(1) {
                emit([f[0], f[k], f[k + 1]].map(|v| v as u32));
            }
        }
    });
    Part {
        name,
        material,
        shape: Shape::Produced {
            positions,
            triangles,
        },
    }
}

/// A quad mesh as binary glTF (`.glb`): one double-sided mesh, two triangles a
/// quad, positions in `f32` as glTF requires — for looking at a mesh in any
/// glTF viewer, not for its 1e-9 geometry (keep OBJ, PLY or JSON for that).
/// The quads are gone through twice (size, then bytes), hence `Clone`.
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
    quads: impl IntoIterator<Item = [usize; 4]> + Clone,
    w: &mut W,
) -> io::Result<()> {
    let part = faces_part("surface".to_owned(), 0, vertices, move || quads.clone());
    surface_glb(part, None, w)
}

/// A mesh of triangles and quads (a trimmed mesh's
/// [`TrimmedMesh::mesh_faces`](monge_core::approximate::TrimmedMesh::mesh_faces)) as
/// binary glTF, as [`write_quads_glb`] writes quads.
pub(crate) fn write_faces_glb<W: Write + ?Sized>(
    vertices: &[DVec3],
    faces: &[Vec<usize>],
    w: &mut W,
) -> io::Result<()> {
    let part = faces_part("surface".to_owned(), 0, vertices, move || faces.iter());
    surface_glb(part, None, w)
}

/// A quad grid as binary glTF (see [`write_quads_glb`]).
pub fn write_grid_glb<W: Write + ?Sized>(grid: &QuadGrid, w: &mut W) -> io::Result<()> {
    write_grid_glb_at(grid, None, w)
}

/// A quad grid as binary glTF, its coordinates relative to `base` (if any),
/// which becomes the node's `translation` (see [`crate::write_mesh_at`]).
pub(crate) fn write_grid_glb_at<W: Write + ?Sized>(
    grid: &QuadGrid,
    base: Option<DVec3>,
    w: &mut W,
) -> io::Result<()> {
    surface_glb(grid_part("surface".to_owned(), 0, grid), base, w)
}

/// One surface as binary glTF.
fn surface_glb<W: Write + ?Sized>(
    part: Part<'_>,
    base: Option<DVec3>,
    w: &mut W,
) -> io::Result<()> {
    let materials = vec![material("surface", [0.62, 0.72, 0.85, 1.0])];
    write_parts("monge", "mesh", materials, &[part], base, w)
}
