//! `monge smooth`: the cyclidic net's contract and the meshes it refuses.

use std::fs;

use predicates::prelude::*;
use tempfile::TempDir;

use crate::common;
use common::{example, monge, monge_to, read_json, refuses, vertex, write};

#[test]
fn smooth_refuses_an_output_above_max_output() {
    let dir = TempDir::new().unwrap();
    let out = dir.path().join("net.json");
    refuses(
        monge_to("smooth", example("fig13-freeform.json"), &out).args([
            "--samples",
            "200",
            "--max-output",
            "1",
        ]),
        &[
            "60 × 40 patches of 200 × 200 points and 4900 arcs, would be about 5.8 GB, above the \
             limit of 1 GB: lower --samples",
        ],
        &[&out],
    );
}

#[test]
fn smooth_writes_the_cyclidic_net_contract() {
    let dir = TempDir::new().unwrap();
    let design = example("fig12-dupin-theta30.json");
    let (net, mesh) = (dir.path().join("net.json"), dir.path().join("m.json"));
    monge_to("smooth", &design, &net)
        .args(["--samples", "4"])
        .assert()
        .success()
        .stderr(predicate::str::contains("cyclidic net (§4.4)"));
    monge_to("generate", &design, &mesh).assert().success();
    let (net, mesh) = (read_json(&net), read_json(&mesh));
    let (rows, cols) = (
        mesh["rows"].as_u64().unwrap() as usize,
        mesh["cols"].as_u64().unwrap() as usize,
    );
    let patches = net["patches"].as_array().unwrap();
    assert_eq!(patches.len(), (rows - 1) * (cols - 1));
    let size = 20.0;
    for p in patches {
        let (i, j) = (
            p["i"].as_u64().unwrap() as usize,
            p["j"].as_u64().unwrap() as usize,
        );
        assert_eq!((p["rows"].as_u64(), p["cols"].as_u64()), (Some(4), Some(4)));
        let pts = p["points"].as_array().unwrap();
        assert_eq!(pts.len(), 16);
        // (u, v) = (0, 0) at vertex (i, j), (1, 0) at (i+1, j), (0, 1) at (i, j+1), (1, 1) at (i+1, j+1).
        for (k, (a, b)) in [
            (0, (i, j)),
            (12, (i + 1, j)),
            (3, (i, j + 1)),
            (15, (i + 1, j + 1)),
        ] {
            let p: Vec<f64> = pts[k]
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect();
            let v = vertex(&mesh, a, b);
            let d = (0..3).map(|c| (p[c] - v[c]).powi(2)).sum::<f64>().sqrt();
            assert!(d < 1e-12 * size, "patch ({i}, {j}) corner {k}: {d}");
        }
    }
    // One line per mesh row and column; on a Dupin cyclide each is a single arc (§4.6).
    let lines = net["lines"].as_array().unwrap();
    assert_eq!(lines.len(), rows + cols);
    assert!(lines
        .iter()
        .all(|l| l["arcs"].as_array().unwrap().len() == 1));
    // The dense mesh opens as a mesh and is itself circular with planar lines.
    let obj = dir.path().join("smooth.obj");
    monge_to("smooth", example("fig13-freeform.json"), &obj)
        .assert()
        .success();
    monge().arg("check").arg(&obj).assert().success();
    refuses(
        monge()
            .arg("smooth")
            .arg(&design)
            .args(["-o", "x.json", "--samples", "1"]),
        &[],
        &[],
    );
    // The exact surface as IGES: read back independently, it passes through the mesh vertices.
    let igs = dir.path().join("net.igs");
    monge_to("smooth", &design, &igs).assert().success();
    let surfaces = monge_io::read_iges_surfaces(&fs::read_to_string(&igs).unwrap()).unwrap();
    assert_eq!(surfaces.len(), 1);
    for (i, j) in [
        (0, 0),
        (rows - 1, 0),
        (0, cols - 1),
        (rows / 2, cols / 3),
        (rows - 1, cols - 1),
    ] {
        let p = surfaces[0].point(i as f64, j as f64);
        let v = vertex(&mesh, i, j);
        let d = (0..3).map(|c| (p[c] - v[c]).powi(2)).sum::<f64>().sqrt();
        assert!(d < 1e-12 * size, "IGES at vertex ({i}, {j}): {d}");
    }
    // On a mesh read from a file: from its node axes, or from one given frame.
    let mesh_path = dir.path().join("m.json");
    let frame_out = dir.path().join("f.obj");
    monge()
        .arg("smooth")
        .arg(&mesh_path)
        .arg("--mesh")
        .args(["--frame=1,0,0,0,1,0", "--samples", "3", "-o"])
        .arg(&frame_out)
        .assert()
        .success()
        .stderr(predicate::str::contains(
            "frames carried from the given one",
        ));
    monge().arg("check").arg(&frame_out).assert().success();
    refuses(
        monge()
            .arg("smooth")
            .arg(&mesh_path)
            .args(["--mesh", "--frame=1,0,0", "-o", "x.json"]),
        &["--frame takes 6 numbers"],
        &[],
    );
}

/// Issue 10, item 5: `smooth` refused a conical design by ignoring its
/// `"mesh": "conical"`; now it says why and how to proceed, exit 2, no output.
#[test]
fn smooth_refuses_a_conical_design() {
    let dir = TempDir::new().unwrap();
    for ext in ["json", "igs", "obj"] {
        let out = dir.path().join(format!("net.{ext}"));
        refuses(
            &mut monge_to("smooth", example("fig13-conical.json"), &out),
            &[
                "fig13-conical.json",
                "built on circular meshes",
                r#"Remove `"mesh": "conical"`"#,
            ],
            &[&out],
        );
    }
}

#[test]
fn smooth_takes_a_circularity_tolerance_and_refuses_a_nan_frame() {
    let dir = TempDir::new().unwrap();
    let text = fs::read_to_string(example("fig14-family.toml")).unwrap();
    let design = write(
        &dir,
        "folded.toml",
        &text.replace("theta_deg = 20.0", "theta_deg = 100.0"),
    );
    let out = dir.path().join("net.json");
    let smooth = |extra: &[&str]| {
        let mut cmd = monge();
        cmd.arg("smooth")
            .arg(&design)
            .arg("-o")
            .arg(&out)
            .arg("--allow-folded")
            .args(extra);
        cmd
    };
    // Face (36, 33) of this folded mesh is circular to 1.8e-8 only: the message
    // names the option that accepts it (it once named a Rust field).
    refuses(&mut smooth(&[]), &["--circularity-tol"], &[]);
    smooth(&["--circularity-tol", "1e-7"]).assert().success();
    refuses(&mut smooth(&["--circularity-tol", "-1"]), &[], &[]);
    refuses(
        monge_to(
            "smooth",
            example("fig12-dupin-theta30.json"),
            dir.path().join("nan.json"),
        )
        .arg("--frame=nan,0,0,0,1,0"),
        &["not orthonormal"],
        &[],
    );
    assert!(!dir.path().join("nan.json").exists());
}

/// A design of the Dupin family whose guides are polylines sampled from two
/// circular arcs (radius 1, 120° and 300°), θ = 30°, 25 × 21 vertices: folded
/// (§5.2) in 144 faces, 48 of them bow-ties.
fn sampled_dupin_design() -> String {
    let arc = |n: usize, angle_deg: f64, v: bool| -> Vec<[f64; 3]> {
        (0..n)
            .map(|k| {
                let t = (angle_deg * k as f64 / (n - 1) as f64).to_radians();
                let (s, c) = (t.sin(), t.cos() - 1.0);
                if v {
                    [0.0, s, c]
                } else {
                    [s, 0.0, c]
                }
            })
            .collect()
    };
    serde_json::json!({
        "theta_deg": 30,
        "guide_u": { "points": arc(25, 120.0, false) },
        "guide_v": { "points": arc(21, 300.0, true) },
    })
    .to_string()
}

#[test]
fn smooth_refuses_the_folded_mesh_that_check_finds_folded() {
    let dir = TempDir::new().unwrap();
    let design = write(&dir, "dupin.json", &sampled_dupin_design());
    let mesh = dir.path().join("m.obj");
    monge_to("generate", &design, &mesh)
        .assert()
        .success()
        .stderr(predicate::str::contains(
            "in 144 faces, first at face (0, 0)",
        ));
    // Measured on the file, as any mesh.
    monge()
        .arg("check")
        .arg(&mesh)
        .assert()
        .code(1)
        .stdout(predicate::str::is_match(r"folded faces +144 +at first face \(0, 0\)").unwrap());
    for (input, mesh_flag) in [(&design, false), (&mesh, true)] {
        let out = dir.path().join("net.json");
        let mut cmd = monge();
        cmd.arg("smooth").arg(input).arg("-o").arg(&out);
        if mesh_flag {
            cmd.arg("--mesh");
        }
        refuses(
            &mut cmd,
            &["face (0, 0) is folded", "--allow-folded"],
            &[&out],
        );
        cmd.arg("--allow-folded").assert().success();
        assert!(out.is_file());
        fs::remove_file(&out).unwrap();
    }
}
