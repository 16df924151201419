//! `monge generate`: every output format, the JSON contract, standard output,
//! offsets, developable designs, glTF, and the warnings of the summary.

use std::fs;
use std::path::Path;

use monge_core::{inspect, GenerateOptions};
use predicates::prelude::*;
use serde_json::Value;
use tempfile::TempDir;

use crate::common;
use common::{
    check_json, example, examples, generate_and_check, monge, monge_to, read_json, refuses, vertex,
    write,
};

/// Examples that must generate and pass `check`.
const REQUIRED: [&str; 5] = [
    "contract.json",
    "fig13-freeform.json",
    "fig2-enneper.json",
    "fig10-arbitrary.json",
    "fig14-family.toml",
];

#[test]
fn required_examples_generate_to_every_format_and_pass_check() {
    let dir = TempDir::new().unwrap();
    for name in REQUIRED {
        let stem = name.split('.').next().unwrap();
        for ext in ["obj", "ply", "json"] {
            generate_and_check(&example(name), &dir.path().join(format!("{stem}.{ext}")));
        }
    }
}

#[test]
fn binary_ply_generates_and_passes_check_and_a_wrong_extension_is_refused() {
    let dir = TempDir::new().unwrap();
    let design = example("fig13-freeform.json");
    let (ascii, binary) = (dir.path().join("a.ply"), dir.path().join("b.ply"));
    monge_to("generate", &design, &ascii).assert().success();
    monge_to("generate", &design, &binary)
        .args(["--format", "ply-binary"])
        .assert()
        .success();
    let bytes = fs::read(&binary).unwrap();
    assert!(bytes.starts_with(b"ply\nformat binary_little_endian 1.0\n"));
    assert!(bytes.len() < fs::metadata(&ascii).unwrap().len() as usize);
    monge()
        .arg("check")
        .arg(&binary)
        .assert()
        .success()
        .stdout(predicate::str::contains("PASS: every metric"));
    // From standard input as well.
    monge()
        .args(["check", "-", "--format", "ply"])
        .write_stdin(bytes)
        .assert()
        .success();
    // f32 to standard output.
    let out = monge()
        .arg("generate")
        .arg(&design)
        .args(["-o", "-", "--format", "ply-f32"])
        .output()
        .unwrap();
    assert!(out.status.success());
    assert!(out.stdout.windows(17).any(|w| w == b"property float x\n"));
    refuses(
        monge_to("generate", &design, dir.path().join("c.obj")).args(["--format", "ply-binary"]),
        &["--format ply-binary but OUT", "name it `.ply`"],
        &[],
    );
}

#[test]
fn every_other_example_either_passes_check_or_fails_cleanly() {
    let dir = TempDir::new().unwrap();
    for entry in fs::read_dir(examples()).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if REQUIRED.contains(&name.as_str()) {
            continue;
        }
        let out = dir.path().join(format!("{name}.obj"));
        let status = monge_to("generate", &path, &out).output().unwrap().status;
        match status.code() {
            Some(0) => {
                let conical = fs::read_to_string(&path).unwrap().contains("\"conical\"");
                let kind = if conical { "conical" } else { "circular" };
                monge()
                    .arg("check")
                    .arg(&out)
                    .args(["--kind", kind])
                    .assert()
                    .success();
            }
            Some(2) => assert!(!out.exists(), "{name}: failed but wrote output"),
            other => panic!("{name}: unexpected exit status {other:?}"),
        }
    }
}

#[test]
fn json_output_follows_the_contract() {
    let dir = TempDir::new().unwrap();
    let out = dir.path().join("contract.json");
    let design_path = example("contract.json");
    monge_to("generate", &design_path, &out).assert().success();
    let mesh = read_json(&out);
    assert_eq!(mesh["rows"], 3);
    assert_eq!(mesh["cols"], 41);
    assert_eq!(mesh["vertices"].as_array().unwrap().len(), 3 * 41);
    assert_eq!(mesh["normals"].as_array().unwrap().len(), 3 * 41);
    assert_eq!(mesh["theta_deg"], 30.0);
    assert!(mesh["mode"] == "characteristic" || mesh["mode"] == "arbitrary");
    assert_eq!(mesh["report"]["folded_faces"], 0);
    assert_eq!(mesh["report"]["first_fold"], Value::Null);
    assert!(mesh["report"]["min_crossing_sine"].as_f64().unwrap() > 1e-3);
    // guide_u is given point by point: column 0 is exactly those points.
    let design = read_json(&design_path);
    for (i, p) in design["guide_u"]["points"]
        .as_array()
        .unwrap()
        .iter()
        .enumerate()
    {
        let p = [0, 1, 2].map(|k| p[k].as_f64().unwrap());
        assert_eq!(vertex(&mesh, i, 0), p, "vertex ({i}, 0)");
    }
    // guide_v is a B-spline: row 0 is exactly its samples.
    let design = monge_io::read_design(&design_path).unwrap();
    let info = inspect(&design, &GenerateOptions::default()).unwrap();
    for (j, p) in info.guide_v.points.iter().enumerate() {
        assert_eq!(vertex(&mesh, 0, j), p.to_array(), "vertex (0, {j})");
    }
}

#[test]
fn json_output_starts_with_the_guides_for_a_characteristic_design() {
    let dir = TempDir::new().unwrap();
    let out = dir.path().join("fig13.json");
    let design_path = example("fig13-freeform.json");
    monge_to("generate", &design_path, &out)
        .assert()
        .success()
        .stderr(predicate::str::contains("characteristic"));
    let mesh = read_json(&out);
    assert_eq!(mesh["mode"], "characteristic");
    assert_eq!(mesh["theta_deg"], -30.0);
    let design = monge_io::read_design(&design_path).unwrap();
    let info = inspect(&design, &GenerateOptions::default()).unwrap();
    assert_eq!(mesh["rows"], info.guide_u.points.len());
    assert_eq!(mesh["cols"], info.guide_v.points.len());
    for (i, p) in info.guide_u.points.iter().enumerate() {
        assert_eq!(vertex(&mesh, i, 0), p.to_array(), "vertex ({i}, 0)");
    }
    for (j, p) in info.guide_v.points.iter().enumerate() {
        assert_eq!(vertex(&mesh, 0, j), p.to_array(), "vertex (0, {j})");
    }
}

#[test]
fn dash_writes_json_to_stdout_by_default_and_other_formats_on_request() {
    let dir = TempDir::new().unwrap();
    let out = monge()
        .current_dir(dir.path())
        .arg("generate")
        .arg(example("fig2-enneper.json"))
        .args(["-o", "-"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let mesh: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(
        (mesh["rows"].as_u64(), mesh["cols"].as_u64()),
        (Some(41), Some(41))
    );
    assert_eq!(mesh["theta_deg"], -90.0);
    // The summary goes to stderr, not into the mesh.
    assert!(String::from_utf8(out.stderr).unwrap().contains("41 × 41"));

    let obj = monge()
        .arg("generate")
        .arg(example("fig2-enneper.json"))
        .args(["-o", "-", "--format", "obj"])
        .output()
        .unwrap();
    assert!(obj.status.success());
    assert!(obj
        .stdout
        .starts_with(b"# monge quad grid rows=41 cols=41\n"));
    assert_eq!(
        fs::read_dir(dir.path()).unwrap().count(),
        0,
        "no file written"
    );

    // What went to stdout can be checked from stdin.
    monge()
        .args(["check", "-", "--format", "obj"])
        .write_stdin(obj.stdout)
        .assert()
        .success()
        .stdout(predicate::str::contains("<stdin>"));
}

#[test]
fn conical_meshes_and_offsets_are_written_and_pass_check() {
    let dir = TempDir::new().unwrap();
    let out = dir.path().join("c.json");
    monge_to("generate", example("fig13-conical.json"), &out)
        .args(["--offset", "0.25", "--offset", "-0.5"])
        .assert()
        .success()
        .stderr(predicate::str::contains("conical dual"));
    let mesh = read_json(&out);
    assert_eq!(mesh["kind"], "conical");
    // One vertex per face of the 61 × 41 circular mesh, one face normal per interior vertex.
    assert_eq!(
        (mesh["rows"].as_u64(), mesh["cols"].as_u64()),
        (Some(60), Some(40))
    );
    assert_eq!(mesh["face_normals"].as_array().unwrap().len(), 59 * 39);
    for (name, d) in [("c.offset+0.25.json", 0.25), ("c.offset-0.5.json", -0.5)] {
        let offset = dir.path().join(name);
        assert_eq!(read_json(&offset)["offset"], d);
        monge()
            .arg("check")
            .arg(&offset)
            .args(["--kind", "conical", "--offset-from"])
            .arg(&out)
            .assert()
            .success()
            .stdout(predicate::str::contains("offset distance"))
            .stdout(predicate::str::contains("conical vertices"));
    }
    // A circular mesh is not conical, and the conical check says so.
    let circular = dir.path().join("m.json");
    monge_to("generate", example("fig13-freeform.json"), &circular)
        .args(["--offset", "0.1"])
        .assert()
        .success();
    monge()
        .arg("check")
        .arg(dir.path().join("m.offset+0.1.json"))
        .arg("--offset-from")
        .arg(&circular)
        .assert()
        .success();
    monge()
        .arg("check")
        .arg(&circular)
        .args(["--kind", "conical"])
        .assert()
        .code(1);
    // Offsets of a mesh written to standard output have nowhere to go.
    refuses(
        monge()
            .arg("generate")
            .arg(example("fig13-freeform.json"))
            .args(["-o", "-", "--offset", "0.1"]),
        &["--offset writes one file per offset"],
        &[],
    );
    // An offset of another grid is refused.
    refuses(
        monge()
            .arg("check")
            .arg(&circular)
            .arg("--offset-from")
            .arg(&out),
        &["the grids differ"],
        &[],
    );
}

#[test]
fn developable_designs_generate_check_and_report() {
    let dir = TempDir::new().unwrap();
    let out = dir.path().join("d.json");
    monge_to("generate", example("fig11-helix.developable.json"), &out)
        .args(["--offset", "0.5"])
        .assert()
        .success()
        .stderr(predicate::str::contains("developable circular mesh (§3.3)"));
    let mesh = read_json(&out);
    assert_eq!(mesh["kind"], "developable");
    assert_eq!(mesh["alpha_deg"], 25.0);
    for path in [out.clone(), dir.path().join("d.offset+0.5.json")] {
        monge().arg("check").arg(&path).assert().success();
    }
    monge()
        .arg("info")
        .arg(example("fig11-helix.developable.json"))
        .assert()
        .success()
        .stdout(predicate::str::contains("slope α = 25°"));
    // A flat helix is refused with its reason, and nothing is written.
    let flat = write(
        &dir,
        "flat.json",
        r#"{"developable": {"projection": {"points": [[0,0,0],[1,0,0],[2,1,0]], "alpha_deg": 0},
            "heights": [1, 2]}}"#,
    );
    let bad = dir.path().join("flat.obj");
    refuses(&mut monge_to("generate", &flat, &bad), &["α"], &[&bad]);
}

#[test]
fn meshes_also_go_to_gltf_for_viewers_but_are_not_measured_from_it() {
    let dir = TempDir::new().unwrap();
    let glb = dir.path().join("m.glb");
    monge_to("generate", example("fig13-freeform.json"), &glb)
        .assert()
        .success();
    assert!(fs::read(&glb).unwrap().starts_with(b"glTF"));
    refuses(monge().arg("check").arg(&glb), &["glTF"], &[]);
}

/// A characteristic design of size about 4e-3 with its corner at `corner`.
fn small_design(corner: [f64; 3]) -> String {
    let p = |x: f64, y: f64, z: f64| {
        format!("[{}, {}, {}]", corner[0] + x, corner[1] + y, corner[2] + z)
    };
    format!(
        r#"{{ "theta_deg": 30,
  "guide_u": {{ "bspline": {{ "degree": 3, "samples": 11, "control_points": [{}, {}, {}, {}] }} }},
  "guide_v": {{ "bspline": {{ "degree": 3, "samples": 11, "control_points": [{}, {}, {}, {}] }} }} }}"#,
        p(0.0, 0.0, 0.0),
        p(0.001, 0.0, 0.0),
        p(0.002, 0.0, 0.0005),
        p(0.003, 0.0, 0.0015),
        p(0.0, 0.0, 0.0),
        p(0.0, 0.001, 0.0),
        p(0.0, 0.002, 0.0004),
        p(0.0, 0.003, 0.001),
    )
}

#[test]
fn designs_too_far_from_the_origin_for_f64_output_are_warned_about() {
    let dir = TempDir::new().unwrap();
    let warning = "times the design's size away from the origin";
    for (name, corner, warned) in [
        ("near", [0.0, 0.0, 0.0], false),
        // 4e-3 at 1: about 200 sizes away, coordinates round to 5e-14 of the
        // size, which faces amplify at most 4096 times: still below 1e-9.
        ("middle", [1.0, 0.0, 0.0], false),
        // 4e-3 at 20: about 4e3 sizes away, past 1.1e3, where errors can pass 1e-9.
        ("beyond", [20.0, 0.0, 0.0], true),
        // 4e-3 at 5e5: 2.5e-8 of the size, which no f64 file can hold to 1e-9.
        ("far", [5e5, 3e5, 1e3], true),
    ] {
        let design = write(&dir, &format!("{name}.json"), &small_design(corner));
        let mesh = dir.path().join(format!("{name}.obj"));
        let runs = [
            monge().arg("info").arg(&design).assert().success(),
            monge()
                .arg("generate")
                .arg(&design)
                .args(["-o", mesh.to_str().unwrap()])
                .assert()
                .success(),
            monge().arg("check").arg(&mesh).assert(),
        ];
        for run in runs {
            let stderr = String::from_utf8_lossy(&run.get_output().stderr).into_owned();
            assert_eq!(stderr.contains(warning), warned, "{name}: {stderr}");
            if warned {
                assert!(stderr.contains("`--base-point start`"), "{stderr}");
                assert!(
                    stderr.contains("model the design near the origin"),
                    "{stderr}"
                );
            }
        }
    }
}

/// An offset's JSON `report` counts the offset's own folds, as `monge check`
/// finds them (it once copied the generated mesh's 0).
#[test]
fn an_offsets_report_counts_its_own_folds() {
    let dir = TempDir::new().unwrap();
    let out = dir.path().join("d.json");
    monge_to("generate", example("fig12-dupin-theta30.json"), &out)
        .args(["--offset", "-5"])
        .assert()
        .success();
    let report = |path: &Path| -> Value { read_json(path)["report"].clone() };
    assert_eq!(report(&out)["folded_faces"], 0);
    let offset = dir.path().join("d.offset-5.json");
    let (code, checked) = check_json(&offset, &[]);
    assert_eq!(code, Some(1));
    let folds = &checked["metrics"]["folded_faces"];
    assert_eq!(report(&offset)["folded_faces"], folds["value"], "{checked}");
    assert_eq!(report(&offset)["folded_faces"], 288);
}

#[test]
fn a_measured_error_above_the_tolerance_is_never_silent() {
    let dir = TempDir::new().unwrap();
    // The conical mesh turned over (conical error 2.0, 4 folded faces): its error
    // measured by `check` on the written file.
    let turned = write(
        &dir,
        "turned.json",
        r#"{"theta_deg": -161.88466388622183, "mesh": "conical",
 "guide_u": {"bspline": {"degree": 3, "samples": 7, "control_points": [[0,0,0],[1,0,0],
   [2.2330790589699796,0,-0.5541680285794847],[2.8675485424895477,0,-2.155466699292466],[3.4849537934883603,0,1.7232772800102358]]}},
 "guide_v": {"bspline": {"degree": 3, "samples": 11, "control_points": [[0,0,0],[0,1,0],
   [-0.007441484123705624,1.9927520724723893,-0.0996294952040866],[6.193939782998956e-5,3.0061583164315824,0.0008292688442872063]]}}}"#,
    );
    let obj = dir.path().join("m.obj");
    monge_to("generate", &turned, &obj)
        .assert()
        .success()
        .stderr(predicate::str::contains(format!(
            "warning: the mesh written to `{}` measures an error of 2.0e0 of its size, above the \
             tolerance 1e-9: likely cause: its 4 folded faces",
            obj.display()
        )));
    let check = monge()
        .arg("check")
        .arg(&obj)
        .args(["--kind", "conical", "--json"])
        .output()
        .unwrap();
    let check: Value = serde_json::from_slice(&check.stdout).unwrap();
    assert!(
        (check["max_error"].as_f64().unwrap() - 2.0).abs() < 0.05,
        "{check}"
    );
    monge_to("fabricate", &turned, dir.path().join("fab"))
        .assert()
        .stderr(predicate::str::contains(
            "measures an error of 2.0e0 of its size, above the tolerance 1e-9: likely cause: its 4 \
             folded faces",
        ));
    // Far from the origin (1e10 away, 5.3e8 times the size): the cause and the option.
    let far = fs::read_to_string(example("fig12-dupin-theta30.json"))
        .unwrap()
        .replace("[0, 0, -10]", "[1e10, 0, -10]")
        .replace("[0, 0, -3]", "[1e10, 0, -3]")
        .replace("[0, 0, 0]", "[1e10, 0, 0]");
    let far = write(&dir, "far.json", &far);
    let out = monge_to("generate", &far, &obj).output().unwrap();
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(
        stderr.contains("likely cause: its coordinates, 5.3e8 times its size away from the origin"),
        "{stderr}"
    );
    assert!(stderr.contains("`--base-point start`"), "{stderr}");
    let check = monge()
        .arg("check")
        .arg(&obj)
        .arg("--json")
        .output()
        .unwrap();
    let check: Value = serde_json::from_slice(&check.stdout).unwrap();
    let measured = check["max_error"].as_f64().unwrap();
    assert!(measured > 1e-9, "{check}");
    assert!(
        stderr.contains(&format!("measures an error of {measured:.1e} of its size")),
        "{measured:e}: {stderr}"
    );
    // An exact mesh: no such warning.
    monge_to("generate", example("fig12-dupin-theta30.json"), &obj)
        .assert()
        .success()
        .stderr(predicate::str::contains("measures an error").not());
}
