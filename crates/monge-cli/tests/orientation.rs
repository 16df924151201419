//! Every mesh writer winds every face counter-clockwise about the normals it
//! writes (right-hand rule): the face normal by Newell's method, from the file
//! as an independent reader sees it (tobj for OBJ, PLY and JSON parsed here, the
//! `gltf` crate for `.glb`), has a positive dot product with the normal of each
//! of its corners. `generate` (every example, circular, conical, developable),
//! `smooth`'s dense mesh, `patches` (merged and mirrored) and `fabricate`'s glTF.

use crate::common;

use std::fs;
use std::path::{Path, PathBuf};

use common::{example, examples, monge};
use serde_json::Value;
use tempfile::TempDir;

type V3 = [f64; 3];

/// The face normal of a polygon by Newell's method (twice its vector area).
fn newell(points: &[V3]) -> V3 {
    let mut n = [0.0; 3];
    for (k, p) in points.iter().enumerate() {
        let q = points[(k + 1) % points.len()];
        n[0] += (p[1] - q[1]) * (p[2] + q[2]);
        n[1] += (p[2] - q[2]) * (p[0] + q[0]);
        n[2] += (p[0] - q[0]) * (p[1] + q[1]);
    }
    n
}

fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Asserts that every face turns counter-clockwise about each of its corners'
/// normals (`normal_of(face, corner)`); returns the number of faces.
fn assert_oriented(
    what: &str,
    vertices: &[V3],
    faces: &[Vec<usize>],
    normal_of: impl Fn(usize, usize) -> V3,
) -> usize {
    assert!(!faces.is_empty(), "{what}: no faces");
    for (f, face) in faces.iter().enumerate() {
        let corners: Vec<V3> = face.iter().map(|&k| vertices[k]).collect();
        let n = newell(&corners);
        for (c, _) in face.iter().enumerate() {
            let d = dot(n, normal_of(f, c));
            assert!(
                d > 0.0,
                "{what}: face {f} {face:?} turns clockwise about the normal of its corner {c} \
                 (Newell normal {n:?} · normal = {d:e})"
            );
        }
    }
    faces.len()
}

/// `(positions, normals, faces)` of an OBJ, read by tobj.
fn check_obj(path: &Path) {
    let options = tobj::LoadOptions {
        single_index: false,
        triangulate: false,
        ..Default::default()
    };
    let (models, _) = tobj::load_obj(path, &options).unwrap();
    assert_eq!(models.len(), 1, "{}", path.display());
    let m = &models[0].mesh;
    let xyz = |v: &[f64], k: u32| -> V3 {
        let k = 3 * k as usize;
        [v[k], v[k + 1], v[k + 2]]
    };
    let positions: Vec<V3> = (0..m.positions.len() / 3)
        .map(|k| xyz(&m.positions, k as u32))
        .collect();
    let mut faces = Vec::new();
    let mut start = 0;
    for &arity in &m.face_arities {
        let a = arity as usize;
        faces.push((start..start + a).map(|k| m.indices[k] as usize).collect());
        start += a;
    }
    let what = path.display().to_string();
    if m.normals.is_empty() {
        return;
    }
    // Each corner's own `vn` (f a//a …), as the file gives it.
    let firsts: Vec<usize> = m
        .face_arities
        .iter()
        .scan(0usize, |s, &a| {
            let first = *s;
            *s += a as usize;
            Some(first)
        })
        .collect();
    assert_oriented(&what, &positions, &faces, |f, c| {
        xyz(&m.normals, m.normal_indices[firsts[f] + c])
    });
}

/// An ASCII PLY with `x y z nx ny nz` vertices and polygon faces, parsed here.
fn check_ply(path: &Path) {
    let (header, lines, faces) = common::ply_ascii(path);
    assert!(header.contains("property double nx"), "{}", path.display());
    let vertices: Vec<V3> = lines.iter().map(|l| [l[0], l[1], l[2]]).collect();
    let normals: Vec<V3> = lines.iter().map(|l| [l[3], l[4], l[5]]).collect();
    assert_oriented(&path.display().to_string(), &vertices, &faces, |f, c| {
        normals[faces[f][c]]
    });
}

fn triples(v: &Value) -> Vec<V3> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|p| {
            let p = p.as_array().unwrap();
            [0, 1, 2].map(|k| p[k].as_f64().unwrap())
        })
        .collect()
}

/// A mesh JSON, parsed here: a grid (`rows`, `cols`; faces as the README says:
/// `(i, j), (i+1, j), (i+1, j+1), (i, j+1)`, reversed if the normals point the
/// other way, so every face must then agree with its own corners' normals), a
/// conical grid (its `face_normals`), or an assembled mesh (`quads`).
fn check_json(path: &Path) {
    let v: Value = serde_json::from_str(&fs::read_to_string(path).unwrap()).unwrap();
    let what = path.display().to_string();
    let vertices = triples(&v["vertices"]);
    if let Some(quads) = v.get("quads") {
        let faces: Vec<Vec<usize>> = quads
            .as_array()
            .unwrap()
            .iter()
            .map(|q| {
                q.as_array()
                    .unwrap()
                    .iter()
                    .map(|k| k.as_u64().unwrap() as usize)
                    .collect()
            })
            .collect();
        let normals = triples(&v["normals"]);
        assert_oriented(&what, &vertices, &faces, |f, c| normals[faces[f][c]]);
        return;
    }
    let (rows, cols) = (
        v["rows"].as_u64().unwrap() as usize,
        v["cols"].as_u64().unwrap() as usize,
    );
    let mut faces: Vec<Vec<usize>> = Vec::new();
    for i in 0..rows - 1 {
        for j in 0..cols - 1 {
            let k = i * cols + j;
            faces.push(vec![k, k + cols, k + cols + 1, k + 1]);
        }
    }
    if let Some(face_normals) = v.get("face_normals") {
        let n = triples(face_normals);
        assert_oriented(&what, &vertices, &faces, |f, _| n[f]);
        return;
    }
    let normals = triples(&v["normals"]);
    let total: f64 = faces
        .iter()
        .map(|f| {
            let corners: Vec<V3> = f.iter().map(|&k| vertices[k]).collect();
            f.iter()
                .map(|&k| dot(newell(&corners), normals[k]))
                .sum::<f64>()
        })
        .sum();
    if total < 0.0 {
        for f in &mut faces {
            f.reverse();
        }
    }
    assert_oriented(&what, &vertices, &faces, |f, c| normals[faces[f][c]]);
}

/// Every triangle of every mesh named `panels` (or all meshes if `name` is
/// `None`) of a `.glb`, read by the `gltf` crate, turns counter-clockwise about
/// `normals` (the node axes of the same mesh, vertex for vertex).
fn check_glb(path: &Path, name: Option<&str>, normals: &[V3]) -> usize {
    let bytes = fs::read(path).unwrap();
    let gltf = gltf::Gltf::from_slice(&bytes).unwrap();
    let blob = gltf.blob.as_deref().unwrap();
    let mut checked = 0;
    for mesh in gltf.meshes() {
        if name.is_some_and(|n| !mesh.name().unwrap_or_default().contains(n)) {
            continue;
        }
        for prim in mesh.primitives() {
            let reader = prim.reader(|_| Some(blob));
            let positions: Vec<V3> = reader
                .read_positions()
                .unwrap()
                .map(|p| p.map(f64::from))
                .collect();
            assert_eq!(positions.len(), normals.len(), "{}", path.display());
            let indices: Vec<usize> = reader
                .read_indices()
                .unwrap()
                .into_u32()
                .map(|k| k as usize)
                .collect();
            let faces: Vec<Vec<usize>> = indices.chunks(3).map(|t| t.to_vec()).collect();
            checked += assert_oriented(&path.display().to_string(), &positions, &faces, |f, c| {
                normals[faces[f][c]]
            });
        }
    }
    checked
}

/// Vertex normals of an OBJ in vertex order (`vn` k belongs to `v` k in monge's OBJ).
fn obj_normals(path: &Path) -> Vec<V3> {
    fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter_map(|l| l.strip_prefix("vn "))
        .map(|l| {
            let v: Vec<f64> = l.split_whitespace().map(|t| t.parse().unwrap()).collect();
            [v[0], v[1], v[2]]
        })
        .collect()
}

fn run(args: &[&str], design: &Path, out: &Path) {
    monge()
        .arg(args[0])
        .arg(design)
        .args(&args[1..])
        .arg("-o")
        .arg(out)
        .assert()
        .success();
}

/// Every example design of one kind (`suffix`), skipping the other kinds.
fn designs(keep: impl Fn(&str) -> bool) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = fs::read_dir(examples())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| keep(&p.file_name().unwrap().to_string_lossy()))
        .collect();
    v.sort();
    v
}

fn is_surface_or_developable(name: &str) -> bool {
    (name.ends_with(".json") || name.ends_with(".toml"))
        && !name.ends_with(".patches.json")
        && !name.ends_with(".planes.json")
}

#[test]
fn generate_orients_every_example_in_every_format() {
    let dir = TempDir::new().unwrap();
    let all = designs(is_surface_or_developable);
    assert!(all.len() >= 14, "{all:?}");
    for design in &all {
        let stem = design
            .file_name()
            .unwrap()
            .to_string_lossy()
            .replace('.', "_");
        let out = |ext: &str| dir.path().join(format!("{stem}.{ext}"));
        for ext in ["obj", "ply", "json", "glb"] {
            run(&["generate"], design, &out(ext));
        }
        check_obj(&out("obj"));
        check_json(&out("json"));
        let normals = obj_normals(&out("obj"));
        if normals.is_empty() {
            // A conical mesh: its face normals are in the JSON only.
            assert!(fs::read_to_string(out("json"))
                .unwrap()
                .contains("face_normals"));
            continue;
        }
        check_ply(&out("ply"));
        assert!(check_glb(&out("glb"), None, &normals) > 0);
    }
}

#[test]
fn the_developable_example_is_wound_about_its_binormals() {
    // The example that was written inside-out: its faces, read back by tobj, turn
    // about the written normals, and the offset along them keeps the winding.
    let dir = TempDir::new().unwrap();
    let obj = dir.path().join("helix.obj");
    monge()
        .arg("generate")
        .arg(example("fig11-helix.developable.json"))
        .args(["-o", obj.to_str().unwrap(), "--offset", "0.5"])
        .assert()
        .success();
    check_obj(&obj);
    check_obj(&dir.path().join("helix.offset+0.5.obj"));
}

#[test]
fn smooth_dense_meshes_are_oriented() {
    let dir = TempDir::new().unwrap();
    for name in ["fig15-smooth.json", "fig2-enneper.json"] {
        let out = |ext: &str| dir.path().join(format!("{name}.{ext}"));
        for ext in ["obj", "ply", "glb"] {
            run(&["smooth", "--samples", "3"], &example(name), &out(ext));
        }
        check_obj(&out("obj"));
        check_ply(&out("ply"));
        assert!(check_glb(&out("glb"), None, &obj_normals(&out("obj"))) > 0);
    }
}

#[test]
fn patches_merged_and_mirrored_are_oriented() {
    let dir = TempDir::new().unwrap();
    let all = designs(|n| n.ends_with(".patches.json"));
    assert!(all.len() >= 3);
    for design in &all {
        let stem = design
            .file_name()
            .unwrap()
            .to_string_lossy()
            .replace('.', "_");
        let out = |ext: &str| dir.path().join(format!("{stem}.{ext}"));
        for ext in ["obj", "ply", "json", "glb"] {
            run(&["patches"], design, &out(ext));
        }
        check_obj(&out("obj"));
        check_ply(&out("ply"));
        check_json(&out("json"));
        assert!(check_glb(&out("glb"), None, &obj_normals(&out("obj"))) > 0);
    }
}

#[test]
fn fabrication_gltf_panels_are_oriented() {
    let dir = TempDir::new().unwrap();
    for name in ["fig25-biarc.json", "fig13-freeform.json"] {
        let design = example(name);
        let obj = dir.path().join(format!("{name}.obj"));
        run(&["generate"], &design, &obj);
        let fab = dir.path().join(name);
        run(&["fabricate", "--layers", "0,0.1"], &design, &fab);
        // Node offsets are parallel meshes: every layer has the mesh's node axes.
        let faces = check_glb(
            &fab.join("gridshell.glb"),
            Some("panels"),
            &obj_normals(&obj),
        );
        assert!(faces > 0);
    }
}
