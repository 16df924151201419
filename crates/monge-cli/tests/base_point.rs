//! `--base-point`: far from the origin, coordinates written relative to a base
//! point keep the mesh exact; every format records the point. The meshes are
//! measured here with closed forms of this file (not monge's measure module),
//! the files read by hand, by `tobj` and by `gltf`.

use crate::common;

use std::path::Path;

use common::monge;
use predicates::prelude::*;
use serde_json::{json, Value};

type P = [f64; 3];

fn sub(a: P, b: P) -> P {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: P, b: P) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: P, b: P) -> P {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn norm(a: P) -> f64 {
    dot(a, a).sqrt()
}

/// Figure 10's design (arbitrary mode, θ = 100°) of size about 1, its start at
/// `corner`; tolerances that admit the rounding of coordinates there.
fn far_design(dir: &Path, corner: P) -> std::path::PathBuf {
    let at = |p: P| -> Vec<f64> { (0..3).map(|k| corner[k] + p[k] / 9.0).collect() };
    let u: Vec<_> = [
        [0.0, 0.0, 0.0],
        [3.0, 0.0, 0.0],
        [6.0, 0.0, 1.5],
        [9.0, 0.0, 1.0],
    ]
    .map(at)
    .to_vec();
    let v: Vec<_> = [
        [0.0, 0.0, 0.0],
        [0.0, 3.0, 0.0],
        [0.6, 6.0, 0.8],
        [1.8, 9.0, 2.4],
    ]
    .map(at)
    .to_vec();
    let design = json!({
        "theta_deg": 100,
        "guide_u": {"bspline": {"degree": 3, "samples": 21, "control_points": u}},
        "guide_v": {"bspline": {"degree": 3, "samples": 17, "control_points": v}},
        "tolerance": {"planarity": 1e-8, "angle": 1e-8, "start": 1e-8},
    });
    let path = dir.join("far.json");
    std::fs::write(&path, design.to_string()).unwrap();
    path
}

/// The vertices of a JSON mesh, its `cols`, and its `base_point` if any.
fn read_json(path: &Path) -> (Vec<P>, usize, Option<P>) {
    let doc: Value = serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap();
    let point = |v: &Value| -> P {
        let a = v.as_array().unwrap();
        [0, 1, 2].map(|k| a[k].as_f64().unwrap())
    };
    let vertices = doc["vertices"]
        .as_array()
        .unwrap()
        .iter()
        .map(point)
        .collect();
    let base = doc.get("base_point").map(point);
    (vertices, doc["cols"].as_u64().unwrap() as usize, base)
}

/// Worst face planarity (distance of the fourth corner from the plane of the
/// other three) and circularity (distance of the fourth corner from the
/// circle through the other three, in 2D coordinates of their plane plus the
/// height above it), relative to the bounding-box diagonal; each face in
/// coordinates relative to its first corner.
fn worst_error(v: &[P], cols: usize) -> f64 {
    let rows = v.len() / cols;
    let (mut lo, mut hi) = (v[0], v[0]);
    for p in v {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let size = norm(sub(hi, lo));
    let mut worst = 0.0f64;
    for i in 0..rows - 1 {
        for j in 0..cols - 1 {
            let q = [
                v[i * cols + j],
                v[(i + 1) * cols + j],
                v[(i + 1) * cols + j + 1],
                v[i * cols + j + 1],
            ];
            let [b, c, d] = [sub(q[1], q[0]), sub(q[2], q[0]), sub(q[3], q[0])];
            let n = cross(b, c);
            let n = n.map(|x| x / norm(n));
            let height = dot(d, n);
            // In-plane axes: e1 along b, e2 = n × e1.
            let e1 = b.map(|x| x / norm(b));
            let e2 = cross(n, e1);
            let (bx, cx, cy) = (dot(b, e1), dot(c, e1), dot(c, e2));
            // Circle through (0, 0), (bx, 0), (cx, cy): centre (bx/2, y0).
            let y0 = (cx * cx + cy * cy - bx * cx) / (2.0 * cy);
            let (x0, r) = (bx / 2.0, (bx * bx / 4.0 + y0 * y0).sqrt());
            let (dx, dy) = (dot(d, e1) - x0, dot(d, e2) - y0);
            let off_circle = ((dx * dx + dy * dy).sqrt() - r).hypot(height);
            worst = worst.max(height.abs()).max(off_circle);
        }
    }
    worst / size
}

fn generate(design: &Path, out: &Path, base: Option<&str>) -> String {
    let mut cmd = monge();
    cmd.arg("generate").arg(design).arg("-o").arg(out);
    if let Some(b) = base {
        cmd.args(["--base-point", b]);
    }
    let output = cmd.output().unwrap();
    assert!(output.status.success(), "{output:?}");
    String::from_utf8(output.stderr).unwrap()
}

#[test]
fn relative_to_the_start_the_mesh_stays_exact_a_million_sizes_away() {
    let dir = tempfile::tempdir().unwrap();
    let corner = [0.6e6, -0.48e6, 0.64e6];
    let design = far_design(dir.path(), corner);
    let (far, near) = (dir.path().join("abs.json"), dir.path().join("rel.json"));
    let absolute = generate(&design, &far, None);
    let relative = generate(&design, &near, Some("start"));
    let (v_far, cols, none) = read_json(&far);
    let (v_near, _, base) = read_json(&near);
    assert_eq!(none, None);
    // The start point is guide_u's first control point, as written in the design.
    assert_eq!(base, Some(corner));
    let (before, after) = (worst_error(&v_far, cols), worst_error(&v_near, cols));
    println!("1e6 sizes from the origin: error {before:.2e} absolute, {after:.2e} relative");
    assert!(after <= 1e-9, "{after:e}");
    // The same mesh: moved back by the base point, it is the absolute one.
    for (a, b) in v_far.iter().zip(&v_near) {
        let moved = sub(*a, [b[0] + corner[0], b[1] + corner[1], b[2] + corner[2]]);
        assert!(norm(moved) < 1e-6, "{a:?} {b:?}");
    }
    // The absolute mesh is warned about, the relative one is not; it says where the point is.
    assert!(absolute.contains("--base-point start"), "{absolute}");
    assert!(!relative.contains("warning"), "{relative}");
    assert!(
        relative.contains("relative to the base point (600000, -480000, 640000)"),
        "{relative}"
    );
}

#[test]
fn every_mesh_format_records_the_base_point() {
    let dir = tempfile::tempdir().unwrap();
    let design = far_design(dir.path(), [1e6, 2e6, -3e6]);
    let base = "1000000.5,2e6,-3e6";
    let at = [1000000.5, 2e6, -3e6];

    let ply = dir.path().join("m.ply");
    generate(&design, &ply, Some(base));
    let text = std::fs::read_to_string(&ply).unwrap();
    let header = &text[..text.find("end_header").unwrap()];
    assert!(
        header.contains("\ncomment base_point 1000000.5 2000000.0 -3000000.0\n"),
        "{header}"
    );

    let obj = dir.path().join("m.obj");
    generate(&design, &obj, Some(base));
    let text = std::fs::read_to_string(&obj).unwrap();
    assert!(
        text.contains("\n# base_point 1000000.5 2000000.0 -3000000.0\n"),
        "{text:.200}"
    );
    // A third-party reader reads the file as before (the record is a comment)
    // and every coordinate is the small relative one.
    let (models, _) = tobj::load_obj(&obj, &tobj::LoadOptions::default()).unwrap();
    let positions = &models[0].mesh.positions;
    assert_eq!(positions.len(), 3 * 21 * 17);
    assert!(
        positions.iter().all(|x| x.abs() < 2.0),
        "{:?}",
        &positions[..6]
    );
    // `monge check` measures the relative mesh (and does not warn: it is near the origin).
    monge()
        .arg("check")
        .arg(&obj)
        .assert()
        .success()
        .stderr(predicate::str::contains("warning").not());

    let glb = dir.path().join("m.glb");
    generate(&design, &glb, Some(base));
    let bytes = std::fs::read(&glb).unwrap();
    let len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    let doc: Value = serde_json::from_slice(&bytes[20..20 + len]).unwrap();
    let t: Vec<f64> = doc["nodes"][0]["translation"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert_eq!(t, at, "the exact f64 base point");
    // A glTF reader places the node there.
    let gltf = gltf::Gltf::from_slice(&bytes).unwrap();
    let node = gltf.nodes().next().unwrap();
    let (translation, _, _) = node.transform().decomposed();
    assert_eq!(translation, at.map(|x| x as f32));
}

#[test]
fn fabrication_records_the_base_point() {
    let dir = tempfile::tempdir().unwrap();
    let corner = [3e5, 1e5, 2e5];
    let design = far_design(dir.path(), corner);
    let out = dir.path().join("fab");
    monge()
        .arg("fabricate")
        .arg(&design)
        .arg("-o")
        .arg(&out)
        .args(["--base-point", "start"])
        .assert()
        .success()
        .stderr(predicate::str::contains("relative to the base point"));
    let schedule: Value =
        serde_json::from_slice(&std::fs::read(out.join("schedule.json")).unwrap()).unwrap();
    assert_eq!(schedule["base_point"], json!(corner));
    let bytes = std::fs::read(out.join("gridshell.glb")).unwrap();
    let gltf = gltf::Gltf::from_slice(&bytes).unwrap();
    for node in gltf.nodes() {
        assert_eq!(node.transform().decomposed().0, corner.map(|x| x as f32));
    }
}

#[test]
fn a_base_point_is_start_or_three_numbers() {
    let dir = tempfile::tempdir().unwrap();
    let design = far_design(dir.path(), [0.0; 3]);
    for (bad, says) in [
        ("1,2", "has 2 number(s)"),
        ("1,2,nan", "three finite numbers"),
        ("origin", "give `start` or X,Y,Z"),
    ] {
        monge()
            .arg("generate")
            .arg(&design)
            .args(["-o", "-", "--base-point", bad])
            .assert()
            .failure()
            .stderr(predicate::str::contains(says));
    }
    // Developable designs have no guides' start: refused, saying so.
    monge()
        .arg("generate")
        .arg(common::example("fig11-helix.developable.json"))
        .args(["-o", "-", "--base-point", "start"])
        .assert()
        .failure()
        .stderr(predicate::str::contains("developable"));
}
