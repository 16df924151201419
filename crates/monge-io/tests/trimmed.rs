//! Trimmed design files: a design or a multi-patch design and the outline its mesh is
//! cut by, written and read back to the bit, their kind told, their errors.

use glam::DVec3;
use monge_core::approximate::{Outline, TargetCloud};
use monge_core::multipatch::build;
use monge_core::{generate, GenerateOptions, QuadGrid};
use monge_io::{
    parse_design, parse_multipatch, read_any_design, read_design, write_trimmed, AnyDesign,
    DesignFormat, IoError, Trimmable, TrimmedDesign,
};

/// The outline of 400 points over a flat disc round the centre of `grid`'s plan, of a
/// quarter of its extent.
fn disc_outline(grid: &QuadGrid) -> Outline {
    let (lo, hi) = grid
        .vertices
        .iter()
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(*v), hi.max(*v))
        });
    let (centre, radius) = ((lo + hi) / 2.0, 0.25 * (hi - lo).truncate().min_element());
    let disc: Vec<DVec3> = (0..400)
        .map(|k| {
            let (r, a) = (
                radius * ((k as f64 + 0.5) / 400.0).sqrt(),
                k as f64 * 2.399963,
            );
            centre + DVec3::new(r * a.cos(), r * a.sin(), 0.0)
        })
        .collect();
    Outline::of(&TargetCloud::new(&disc).unwrap()).unwrap()
}

/// Two arcs at right angles, θ 30°.
fn surface() -> Trimmable {
    let design = parse_design(
        r#"{"theta_deg": 30,
            "guide_u": {"arc": {"center": [0,0,-4], "start": [0,0,0], "normal": [0,-1,0], "angle_deg": 40, "samples": 9}},
            "guide_v": {"arc": {"center": [0,0,-3], "start": [0,0,0], "normal": [1,0,0], "angle_deg": 50, "samples": 9}}}"#,
        DesignFormat::Json,
    )
    .unwrap();
    Trimmable::Surface(Box::new(design))
}

/// Two patches: the first [`surface`]'s, the second attached along its last row.
fn patches() -> Trimmable {
    let (s, c) = (40f64.to_radians().sin(), 40f64.to_radians().cos());
    let design = parse_multipatch(
        &format!(
            r#"{{"patches": [
              {{"theta_deg": 30,
                "guide_u": {{"arc": {{"center": [0,0,-4], "start": [0,0,0], "normal": [0,-1,0], "angle_deg": 40, "samples": 9}}}},
                "guide_v": {{"arc": {{"center": [0,0,-3], "start": [0,0,0], "normal": [1,0,0], "angle_deg": 50, "samples": 9}}}}}},
              {{"theta_deg": 40, "attach": {{"patch": 0, "side": "last_row"}},
                "guide": {{"arc": {{"center": [0,0,-4], "start": [{}, 0, {}], "normal": [0,-1,0], "angle_deg": 30, "samples": 7}}}}}}]}}"#,
            -4.0 * s,
            4.0 * c - 4.0
        ),
        DesignFormat::Json,
    )
    .unwrap();
    Trimmable::Patches(design)
}

/// `design` trimmed to a disc in its middle.
fn trimmed(design: Trimmable) -> TrimmedDesign {
    let options = GenerateOptions::default();
    let grid = match &design {
        Trimmable::Surface(d) => generate(d, &options).unwrap().grid,
        Trimmable::Patches(d) => build(d, &options).unwrap().grid,
    };
    TrimmedDesign {
        trim: disc_outline(&grid),
        design,
    }
}

#[test]
fn trimmed_designs_read_back_to_the_bit_in_both_formats() {
    let dir = tempfile::tempdir().unwrap();
    for (k, design) in [surface(), patches()].into_iter().enumerate() {
        for ext in ["json", "toml"] {
            let trimmed = trimmed(design.clone());
            let path = dir.path().join(format!("t{k}.{ext}"));
            write_trimmed(&trimmed, &path).unwrap();
            let text = std::fs::read_to_string(&path).unwrap();
            assert!(text.contains("polygon"), "{text}");
            assert_eq!(
                read_any_design(&path).unwrap(),
                AnyDesign::Trimmed(Box::new(trimmed)),
                "{ext}"
            );
        }
    }
}

#[test]
fn a_trimmed_design_given_where_a_design_is_read_says_which_command_reads_it() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.json");
    write_trimmed(&trimmed(surface()), &path).unwrap();
    let e = read_design(&path).unwrap_err();
    assert!(matches!(e, IoError::WrongKind { .. }), "{e}");
    let text = e.to_string();
    assert!(
        text.contains("is a trimmed design") && text.contains("`monge generate`"),
        "{text}"
    );
}

#[test]
fn a_trimmed_design_whose_outline_is_not_one_says_why_and_where() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.json");
    write_trimmed(&trimmed(surface()), &path).unwrap();
    // The outline's corners reversed: clockwise.
    let mut value: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    value["trim"]["polygon"].as_array_mut().unwrap().reverse();
    std::fs::write(&path, serde_json::to_string_pretty(&value).unwrap()).unwrap();
    let e = read_any_design(&path).unwrap_err().to_string();
    assert!(
        e.contains("t.json:") && e.contains("counter-clockwise") && e.contains("reverse"),
        "{e}"
    );
    // A key the file does not have.
    value["trim"]["polygon"].as_array_mut().unwrap().reverse();
    value["trimmed"] = true.into();
    std::fs::write(&path, serde_json::to_string_pretty(&value).unwrap()).unwrap();
    let e = read_any_design(&path).unwrap_err().to_string();
    assert!(e.contains("unknown field `trimmed`"), "{e}");
}

#[test]
fn a_trimmed_design_is_cut_by_its_outline_or_says_why_its_design_cannot_be_built() {
    use monge_io::TrimmedMeshError;
    let options = GenerateOptions::default();
    for design in [surface(), patches()] {
        let trimmed = trimmed(design);
        let (grid, mesh) = trimmed.mesh(&options).unwrap();
        // Fewer faces than the grid's, every vertex within the disc (seen along its
        // axis) or on its edge (a cut's corner).
        assert!(mesh.faces.len() < grid.face_count() && !mesh.faces.is_empty());
        for v in &mesh.vertices {
            assert!(
                trimmed.trim.contains(*v) || on_outline(&trimmed.trim, *v),
                "{v}"
            );
        }
    }
    // A design whose guides do not meet at 90°.
    let mut surface = surface();
    if let Trimmable::Surface(d) = &mut surface {
        d.guide_v = monge_core::design::GuideSpec::points(vec![
            [0.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [2.0, 2.0, 0.5],
        ]);
    }
    let e = TrimmedDesign {
        design: surface,
        trim: trimmed(self::surface()).trim,
    }
    .mesh(&options)
    .unwrap_err();
    assert!(matches!(e, TrimmedMeshError::Surface(_)), "{e}");
    // A patch attached to one that is not there.
    let mut patches = patches();
    if let Trimmable::Patches(d) = &mut patches {
        d.patches[1].attach.as_mut().unwrap().patch = 5;
    }
    let e = TrimmedDesign {
        design: patches,
        trim: trimmed(self::patches()).trim,
    }
    .mesh(&options)
    .unwrap_err();
    assert!(matches!(e, TrimmedMeshError::Patches(_)), "{e}");
}

/// Whether `v` lies on the outline's polygon (a cut's corner), within round-off: its
/// corners in space, seen along its direction.
fn on_outline(outline: &Outline, v: DVec3) -> bool {
    let corners = outline.polygon();
    let n = corners.len();
    (0..n).any(|k| {
        let (a, b) = (corners[k], corners[(k + 1) % n]);
        // Distance in plan (the outline's direction is near z here) to the side a-b.
        let (a, b, p) = (a.truncate(), b.truncate(), v.truncate());
        let t = ((p - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 1.0);
        p.distance(a + t * (b - a)) < 1e-6
    })
}

/// The area of a planar polygon (Newell's normal's length, halved).
fn polygon_area(corners: &[DVec3]) -> f64 {
    let n = corners.len();
    (0..n)
        .map(|k| corners[k].cross(corners[(k + 1) % n]))
        .sum::<DVec3>()
        .length()
        / 2.0
}

#[test]
fn a_trimmed_mesh_reads_back_in_every_format_with_other_readers() {
    use monge_io::{write_trimmed_mesh_to, MeshFormat};
    use ply_rs_bw::{parser::Parser, ply::DefaultElement, ply::Property};
    let (_, mesh) = trimmed(patches())
        .mesh(&GenerateOptions::default())
        .unwrap();
    let cut = mesh.cut.iter().filter(|c| **c).count();
    assert!(cut > 0 && cut < mesh.faces.len());
    assert!(mesh.faces.iter().any(|f| f.len() != 4));
    let write = |format| {
        let mut bytes = Vec::new();
        write_trimmed_mesh_to(&mesh, format, "a trimmed mesh", &mut bytes).unwrap();
        bytes
    };
    let as_faces = |faces: Vec<Vec<i64>>| -> Vec<Vec<usize>> {
        faces
            .into_iter()
            .map(|f| f.into_iter().map(|c| c as usize).collect())
            .collect()
    };
    // PLY, ASCII and binary: every coordinate to the bit, every polygon as it is.
    for format in [MeshFormat::Ply, MeshFormat::PlyBinary] {
        let ply = Parser::<DefaultElement>::new()
            .read_ply(&mut write(format).as_slice())
            .unwrap();
        assert_eq!(ply.header.comments, ["a trimmed mesh"]);
        let double = |p: &Property| match p {
            Property::Double(x) => *x,
            other => panic!("not a double: {other:?}"),
        };
        let vertices: Vec<DVec3> = ply.payload["vertex"]
            .iter()
            .map(|e| DVec3::new(double(&e["x"]), double(&e["y"]), double(&e["z"])))
            .collect();
        assert_eq!(vertices, mesh.vertices, "{format:?}");
        let faces: Vec<Vec<i64>> = ply.payload["face"]
            .iter()
            .map(|e| match &e["vertex_indices"] {
                Property::ListInt(c) => c.iter().map(|c| i64::from(*c)).collect(),
                other => panic!("not a list: {other:?}"),
            })
            .collect();
        assert_eq!(as_faces(faces), mesh.faces, "{format:?}");
    }
    // OBJ, read by tobj without triangulating.
    let options = tobj::LoadOptions {
        triangulate: false,
        ..Default::default()
    };
    let (models, _) = tobj::load_obj_buf(&mut write(MeshFormat::Obj).as_slice(), &options, |_| {
        unreachable!("no materials")
    })
    .unwrap();
    let m = &models[0].mesh;
    let mut at = 0;
    for (face, count) in mesh.faces.iter().zip(&m.face_arities) {
        let corners: Vec<usize> = m.indices[at..at + *count as usize]
            .iter()
            .map(|c| *c as usize)
            .collect();
        assert_eq!(&corners, face);
        at += *count as usize;
    }
    let positions: Vec<DVec3> = m
        .positions
        .chunks(3)
        .map(|p| DVec3::new(p[0], p[1], p[2]))
        .collect();
    assert_eq!(positions, mesh.vertices);
    // JSON, read by serde_json: vertices to the bit, faces, which were cut.
    let json: serde_json::Value = serde_json::from_slice(&write(MeshFormat::Json)).unwrap();
    let vertices: Vec<[f64; 3]> = serde_json::from_value(json["vertices"].clone()).unwrap();
    assert_eq!(
        vertices,
        mesh.vertices
            .iter()
            .map(|v| v.to_array())
            .collect::<Vec<_>>()
    );
    let faces: Vec<Vec<usize>> = serde_json::from_value(json["faces"].clone()).unwrap();
    assert_eq!(faces, mesh.faces);
    let read_cut: Vec<bool> = serde_json::from_value(json["cut"].clone()).unwrap();
    assert_eq!(read_cut, mesh.cut);
    // glTF, read by the gltf crate: triangles over the polygons, their area the
    // polygons' (f32 positions).
    let bytes = write(MeshFormat::Glb);
    let gltf = gltf::Gltf::from_slice(&bytes).unwrap();
    let blob = gltf.blob.as_deref().unwrap();
    let prim = gltf.meshes().next().unwrap().primitives().next().unwrap();
    let reader = prim.reader(|_| Some(blob));
    let positions: Vec<DVec3> = reader
        .read_positions()
        .unwrap()
        .map(|p| glam::Vec3::from_array(p).as_dvec3())
        .collect();
    let indices: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
    let triangles: f64 = indices
        .chunks(3)
        .map(|t| polygon_area(&[0, 1, 2].map(|k| positions[t[k] as usize])))
        .sum();
    let polygons: f64 = mesh
        .faces
        .iter()
        .map(|f| polygon_area(&f.iter().map(|c| mesh.vertices[*c]).collect::<Vec<_>>()))
        .sum();
    assert!(
        (triangles - polygons).abs() <= 1e-6 * polygons,
        "{triangles} {polygons}"
    );
}

#[test]
fn a_trimmed_mesh_that_is_not_one_is_refused_before_anything_is_written() {
    use monge_io::{write_trimmed_mesh_to, MeshFormat, MAX_CORNERS};
    let (_, mesh) = trimmed(surface())
        .mesh(&GenerateOptions::default())
        .unwrap();
    let refused = |mesh: &monge_core::approximate::TrimmedMesh, format| {
        let mut bytes = Vec::new();
        let e = write_trimmed_mesh_to(mesh, format, "", &mut bytes).unwrap_err();
        assert!(bytes.is_empty(), "{format:?}");
        e.to_string()
    };
    for format in [
        MeshFormat::Obj,
        MeshFormat::Ply,
        MeshFormat::Json,
        MeshFormat::Glb,
    ] {
        let mut bad = mesh.clone();
        bad.vertices[0].x = f64::NAN;
        assert!(refused(&bad, format).contains("vertex 0 is not finite"));
        let mut bad = mesh.clone();
        bad.faces[1] = vec![0, 1];
        assert!(refused(&bad, format).contains("face 1 has corners [0, 1]"));
        let mut bad = mesh.clone();
        bad.faces[2] = (0..=MAX_CORNERS).map(|k| k % 3).collect();
        assert!(refused(&bad, format).contains("face 2 has corners"));
        let mut bad = mesh.clone();
        bad.faces[0][0] = mesh.vertices.len();
        assert!(refused(&bad, format).contains("face 0 has corners"));
        let mut bad = mesh.clone();
        bad.cut.pop();
        assert!(refused(&bad, format).contains("whether the outline cut"));
    }
    let mut far = mesh.clone();
    far.vertices[3].z = 1e39;
    assert!(refused(&far, MeshFormat::PlyF32).contains("vertex 3 is"));
}

#[test]
fn polygons_are_read_from_obj_ply_and_json_and_bad_ones_are_refused_where_they_are() {
    use monge_io::{read_polygons, write_trimmed_mesh_to, MeshFormat};
    let (_, mesh) = trimmed(surface())
        .mesh(&GenerateOptions::default())
        .unwrap();
    let dir = tempfile::tempdir().unwrap();
    for (name, format) in [
        ("m.obj", MeshFormat::Obj),
        ("m.ply", MeshFormat::Ply),
        ("b.ply", MeshFormat::PlyBinary),
        ("m.json", MeshFormat::Json),
    ] {
        let path = dir.path().join(name);
        let mut bytes = Vec::new();
        write_trimmed_mesh_to(&mesh, format, "m", &mut bytes).unwrap();
        std::fs::write(&path, bytes).unwrap();
        assert_eq!(
            read_polygons(&path).unwrap(),
            (mesh.vertices.clone(), mesh.faces.clone()),
            "{name}"
        );
    }
    // A face of two corners, at its line.
    let path = dir.path().join("two.ply");
    std::fs::write(
        &path,
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n\
         property double z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n\
         0 0 0\n1 0 0\n0 1 0\n2 0 1\n",
    )
    .unwrap();
    let e = read_polygons(&path).unwrap_err().to_string();
    assert!(e.contains("two.ply:13: a face with corners [0, 1]"), "{e}");
    // A JSON face of two corners, by its index; glTF is not read.
    let path = dir.path().join("two.json");
    std::fs::write(
        &path,
        r#"{"vertices": [[0,0,0],[1,0,0],[0,1,0]], "faces": [[0,1,2],[2,0]]}"#,
    )
    .unwrap();
    let e = read_polygons(&path).unwrap_err().to_string();
    assert!(e.contains("two.json: faces[1] has corners [2, 0]"), "{e}");
    let path = dir.path().join("m.glb");
    std::fs::write(&path, "glTF").unwrap();
    let e = read_polygons(&path).unwrap_err().to_string();
    assert!(e.contains("`.obj`, `.ply` or `.json`"), "{e}");
}
