//! End-to-end tests of the `monge` binary: every command, every exit status,
//! and the error messages for bad input.

use std::fs;
use std::path::{Path, PathBuf};

use monge_core::{inspect, GenerateOptions};
use predicates::prelude::*;
use serde_json::Value;
use tempfile::TempDir;

mod common;
use common::{example, examples, generate_and_check, monge};

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
    monge()
        .arg("generate")
        .arg(&design)
        .arg("-o")
        .arg(&ascii)
        .assert()
        .success();
    monge()
        .arg("generate")
        .arg(&design)
        .arg("-o")
        .arg(&binary)
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
    monge()
        .arg("generate")
        .arg(&design)
        .arg("-o")
        .arg(dir.path().join("c.obj"))
        .args(["--format", "ply-binary"])
        .assert()
        .code(2)
        .stderr(predicate::str::contains("--format ply-binary but OUT"))
        .stderr(predicate::str::contains("name it `.ply`"));
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
        let status = monge()
            .arg("generate")
            .arg(&path)
            .arg("-o")
            .arg(&out)
            .output()
            .unwrap()
            .status;
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

/// Parses the JSON mesh written by `monge generate`.
fn read_json(path: &Path) -> Value {
    serde_json::from_str(&fs::read_to_string(path).unwrap()).unwrap()
}

/// Vertex `(i, j)` of a JSON mesh.
fn vertex(mesh: &Value, i: usize, j: usize) -> [f64; 3] {
    let cols = mesh["cols"].as_u64().unwrap() as usize;
    let v = &mesh["vertices"][i * cols + j];
    [0, 1, 2].map(|k| v[k].as_f64().unwrap())
}

#[test]
fn json_output_follows_the_contract() {
    let dir = TempDir::new().unwrap();
    let out = dir.path().join("contract.json");
    let design_path = example("contract.json");
    monge()
        .arg("generate")
        .arg(&design_path)
        .arg("-o")
        .arg(&out)
        .assert()
        .success();
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
    let design: Value = serde_json::from_str(&fs::read_to_string(&design_path).unwrap()).unwrap();
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
    monge()
        .arg("generate")
        .arg(&design_path)
        .arg("-o")
        .arg(&out)
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
fn info_refuses_a_design_that_generate_refuses_for_its_guides() {
    // guide_v's plane 1.7e-5° from the tangent plane at the start: the normal
    // barely turns along guide_u, whatever θ. `info` says so, as `generate`.
    let dir = TempDir::new().unwrap();
    let design = write(
        &dir,
        "still.json",
        r#"{"theta_deg": 66,
            "guide_u": {"arc": {"center": [0, 0, -10], "start": [0, 0, 0], "normal": [0, 1, 0],
                                "angle_deg": 120, "samples": 41}},
            "guide_v": {"arc": {"center": [0, 10, -3e-6], "start": [0, 0, 0], "normal": [-1, 0, 0],
                                "angle_deg": 80, "samples": 33}}}"#,
    );
    for command in ["info", "generate"] {
        let mut cmd = monge();
        cmd.arg(command).arg(&design);
        if command == "generate" {
            cmd.arg("-o").arg(dir.path().join("m.obj"));
        }
        cmd.assert().code(2).stderr(predicate::str::contains(
            "the surface normal turns by only 5.2e-7 rad along guide_u",
        ));
    }
    assert!(!dir.path().join("m.obj").exists());
}

#[test]
fn info_prints_the_admissible_range_and_reports_an_inadmissible_theta() {
    monge()
        .arg("info")
        .arg(example("fig10-arbitrary.json"))
        .assert()
        .success()
        .stdout(
            predicate::str::contains("mode: arbitrary")
                .and(predicate::str::contains("|θ| in [61.9275°, 180°]"))
                .and(predicate::str::contains(
                    "[−180°, −61.9275°] ∪ [61.9275°, 180°]",
                ))
                .and(predicate::str::contains("design θ = 100°: admissible"))
                .and(predicate::str::contains("singular θ = +90°"))
                .and(predicate::str::contains(
                    "grid: 41 × 41 vertices (1681), 1600 faces",
                )),
        );
    monge()
        .arg("info")
        .arg(example("fig14-family.toml"))
        .assert()
        .success()
        .stdout(
            predicate::str::contains("mode: characteristic")
                .and(predicate::str::contains("every θ in (−180°, 180°]"))
                .and(predicate::str::contains("guide_u: bspline, 41 samples")),
        );

    let dir = TempDir::new().unwrap();
    let design = write(&dir, "theta20.json", &fig10_with_theta(20.0));
    monge()
        .arg("info")
        .arg(&design)
        .assert()
        .success()
        .stdout(predicate::str::contains("design θ = 20°: NOT admissible"));
    let out = monge()
        .arg("info")
        .arg(&design)
        .arg("--json")
        .output()
        .unwrap();
    assert!(out.status.success());
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["theta_admissible"], false);
    assert_eq!(v["mode"], "arbitrary");
    let min = v["admissible_theta_deg"]["abs_min"].as_f64().unwrap();
    assert!((min - 61.9275).abs() < 1e-3, "{min}");
    assert_eq!(v["guide_u"]["kind"], "bspline");
    assert_eq!(v["faces"], 1600);
}

/// fig10-arbitrary.json with another θ.
fn fig10_with_theta(theta: f64) -> String {
    let mut v: Value =
        serde_json::from_str(&fs::read_to_string(example("fig10-arbitrary.json")).unwrap())
            .unwrap();
    v["theta_deg"] = theta.into();
    v.to_string()
}

/// Writes `text` to `name` in `dir`.
fn write(dir: &TempDir, name: &str, text: &str) -> PathBuf {
    let path = dir.path().join(name);
    fs::write(&path, text).unwrap();
    path
}

/// Runs `generate` on `design` (written as `name`) into `out.obj` with `extra`
/// arguments, and asserts exit status 2, an `error:` message containing
/// `expected`, and no output file (nor a temporary one) left behind.
fn generate_fails(name: &str, design: &str, extra: &[&str], expected: &str) {
    let dir = TempDir::new().unwrap();
    let design = write(&dir, name, design);
    let out = dir.path().join("out.obj");
    monge()
        .arg("generate")
        .arg(&design)
        .arg("-o")
        .arg(&out)
        .args(extra)
        .assert()
        .code(2)
        .stdout("")
        .stderr(predicate::str::starts_with("error: ").and(predicate::str::contains(expected)));
    let left: Vec<_> = fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(
        left,
        [std::ffi::OsString::from(name)],
        "files left: {left:?}"
    );
}

/// Two polyline guides as JSON, θ = 30°, with the start tangents (1, 0, 0) for
/// guide_u and (0, 1, 0) for guide_v.
fn design(guide_u: &str, guide_v: &str) -> String {
    format!(
        r#"{{ "theta_deg": 30,
  "guide_u": {{ "points": {guide_u}, "tangent": [1, 0, 0] }},
  "guide_v": {{ "points": {guide_v}, "tangent": [0, 1, 0] }} }}"#
    )
}

/// guide_u in the plane y = 0, leaving along x.
const U: &str = "[[0,0,0],[1,0,0.2],[2,0,0.7]]";
/// guide_v in the plane x = 0, leaving along y.
const V: &str = "[[0,0,0],[0,1,0.1],[0,2,0.5]]";

#[test]
fn a_good_handwritten_design_generates() {
    let dir = TempDir::new().unwrap();
    let path = write(&dir, "good.json", &design(U, V));
    generate_and_check(&path, &dir.path().join("good.obj"));
}

#[test]
fn malformed_json_is_located() {
    generate_fails(
        "bad.json",
        "{ \"theta_deg\": 30,\n  \"guide_u\": { \"points\": [[0,0,0],[1,0,0.2]] ,\n}",
        &[],
        "bad.json:3:",
    );
}

#[test]
fn an_unknown_key_is_named() {
    let text = design(U, V).replacen("{ ", r#"{ "thetadeg": 1, "#, 1);
    generate_fails("unknown.json", &text, &[], "unknown field `thetadeg`");
}

#[test]
fn a_nan_in_toml_is_refused() {
    let text = format!(
        "theta_deg = nan\nguide_u.points = {U}\nguide_u.tangent = [1, 0, 0]\n\
         guide_v.points = {V}\nguide_v.tangent = [0, 1, 0]\n"
    );
    generate_fails("nan.toml", &text, &[], "not finite at `theta_deg`");
}

#[test]
fn guides_must_start_at_the_same_point() {
    let v = "[[0,0,0.1],[0,1,0.1],[0,2,0.5]]";
    generate_fails(
        "start.json",
        &design(U, v),
        &[],
        "the guides do not start at the same point",
    );
}

#[test]
fn guides_must_meet_at_right_angles() {
    // guide_v in the plane spanned by (0.3, 1, 0) and z, leaving along (0.3, 1, 0).
    let v = "[[0,0,0],[0.3,1,0.1],[0.6,2,0.5]]";
    let text = design(U, v).replace("[0, 1, 0]", "[0.3, 1, 0]");
    generate_fails("angle.json", &text, &[], "must meet at 90°");
}

#[test]
fn a_guide_must_be_planar() {
    let u = "[[0,0,0],[1,0,0.2],[2,0.3,0.7],[3,0,1]]";
    generate_fails("twisted.json", &design(u, V), &[], "guide_u is not planar");
}

#[test]
fn theta_outside_the_admissible_range_is_refused() {
    generate_fails(
        "theta20.json",
        &fig10_with_theta(20.0),
        &[],
        "theta_deg = 20° is not admissible",
    );
}

#[test]
fn a_grid_too_large_is_refused_before_generation() {
    generate_fails(
        "big.json",
        &design(U, V),
        &["--max-vertices", "8"],
        "more than the limit of 8",
    );
}

#[test]
fn max_vertices_10_refuses_an_example() {
    let dir = TempDir::new().unwrap();
    let out = dir.path().join("out.obj");
    monge()
        .arg("generate")
        .arg(example("fig13-freeform.json"))
        .arg("-o")
        .arg(&out)
        .args(["--max-vertices", "10"])
        .assert()
        .code(2)
        .stderr(predicate::str::contains("more than the limit of 10"));
    assert!(!out.exists());
}

#[test]
fn an_unknown_output_extension_and_a_missing_design_are_errors() {
    let dir = TempDir::new().unwrap();
    let out = dir.path().join("out.stl");
    monge()
        .arg("generate")
        .arg(example("contract.json"))
        .arg("-o")
        .arg(&out)
        .assert()
        .code(2)
        .stderr(predicate::str::contains("unsupported extension `.stl`"));
    assert!(!out.exists());
    monge()
        .arg("generate")
        .arg(dir.path().join("nothere.json"))
        .arg("-o")
        .arg(dir.path().join("out.obj"))
        .assert()
        .code(2)
        .stderr(predicate::str::contains("file not found"));
}

#[test]
fn a_failed_generation_leaves_an_existing_output_untouched() {
    let dir = TempDir::new().unwrap();
    let design = write(&dir, "theta20.json", &fig10_with_theta(20.0));
    let out = write(&dir, "out.obj", "keep me\n");
    monge()
        .arg("generate")
        .arg(&design)
        .arg("-o")
        .arg(&out)
        .assert()
        .code(2);
    assert_eq!(fs::read_to_string(&out).unwrap(), "keep me\n");
}

#[test]
fn bad_arguments_exit_2() {
    monge().assert().code(2);
    monge().args(["generate", "x.json"]).assert().code(2);
    monge()
        .args(["check", "x.obj", "--tol", "-1"])
        .assert()
        .code(2)
        .stderr(predicate::str::contains(
            "not a finite, non-negative number",
        ));
    monge().args(["bench", "--sizes", "0"]).assert().code(2);
    monge()
        .args(["check", "-"])
        .assert()
        .code(2)
        .stderr(predicate::str::contains("needs --format"));
}

/// A 3 × 3 JSON mesh of the unit grid in the plane z = 0, with vertex (1, 1) lifted by `lift`.
fn grid_json(lift: f64) -> String {
    let mut vertices = Vec::new();
    for i in 0..3 {
        for j in 0..3 {
            let z = if (i, j) == (1, 1) { lift } else { 0.0 };
            vertices.push(format!("[{i}, {j}, {z}]"));
        }
    }
    format!(
        r#"{{"rows": 3, "cols": 3, "vertices": [{}]}}"#,
        vertices.join(", ")
    )
}

#[test]
fn check_passes_a_good_mesh_and_fails_a_moved_vertex() {
    let dir = TempDir::new().unwrap();
    let good = write(&dir, "good.json", &grid_json(0.0));
    monge()
        .arg("check")
        .arg(&good)
        .assert()
        .code(0)
        .stdout(predicate::str::contains("face planarity").and(predicate::str::contains("PASS")));

    let bad = write(&dir, "bad.json", &grid_json(0.1));
    monge()
        .arg("check")
        .arg(&bad)
        .assert()
        .code(1)
        .stdout(predicate::str::contains("FAIL"));
    let out = monge()
        .arg("check")
        .arg(&bad)
        .arg("--json")
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["pass"], false);
    assert_eq!(v["metrics"]["face_planarity"]["pass"], false);
    assert!(v["metrics"]["face_planarity"]["value"].as_f64().unwrap() > 1e-3);
    assert_eq!(v["metrics"].get("torsion"), None, "no normals, no torsion");
    // A loose tolerance accepts it.
    monge()
        .arg("check")
        .arg(&bad)
        .args(["--tol", "0.1"])
        .assert()
        .code(0);
}

/// Issue 10, item 2: the unit 3 × 3 grid with vertices (2, 1) and (2, 2)
/// exchanged has face (1, 1) crossed (a symmetric bow-tie: its edges
/// (1, 1)–(2, 1) and (2, 2)–(1, 2) cross at (1.5, 1.5), its diagonals are
/// parallel), planar and circular: `check` fails it, whatever the tolerance.
#[test]
fn check_fails_a_crossed_face_with_its_index() {
    let dir = TempDir::new().unwrap();
    let mesh = write(
        &dir,
        "bow-tie.json",
        r#"{"rows": 3, "cols": 3, "vertices": [[0,0,0], [0,1,0], [0,2,0], [1,0,0], [1,1,0],
            [1,2,0], [2,0,0], [2,2,0], [2,1,0]]}"#,
    );
    monge()
        .arg("check")
        .arg(&mesh)
        .args(["--tol", "1"])
        .assert()
        .code(1)
        .stdout(predicate::str::contains(
            "folded faces               1  at first face (1, 1)",
        ));
    let (code, v) = check_json(&mesh, &[]);
    assert_eq!((code, &v["pass"]), (Some(1), &Value::Bool(false)));
    let folds = &v["metrics"]["folded_faces"];
    assert_eq!(folds["value"], 1);
    assert_eq!(folds["at"], serde_json::json!([1, 1]));
    assert_eq!(folds["pass"], false);
    // Exchanged back, the grid passes with no folded face.
    let fair = write(&dir, "fair.json", &grid_json(0.0));
    let (_, v) = check_json(&fair, &[]);
    assert_eq!(
        v["metrics"]["folded_faces"],
        serde_json::json!({"value": 0, "at": null, "pass": true})
    );
}

#[test]
fn check_reports_a_malformed_mesh_as_an_error() {
    let dir = TempDir::new().unwrap();
    let mesh = write(
        &dir,
        "short.json",
        r#"{"rows": 2, "cols": 2, "vertices": [[0,0,0]]}"#,
    );
    monge()
        .arg("check")
        .arg(&mesh)
        .assert()
        .code(2)
        .stderr(predicate::str::contains("expected 4, found 1"));
    // Meshes that cannot be measured: once PASSed with metrics 0, NaN or "at face
    // (0, 0)" of a grid without faces.
    for (name, text, says) in [
        (
            "empty.json",
            r#"{"rows": 0, "cols": 0, "vertices": []}"#,
            "0 × 0 vertices",
        ),
        (
            "line.json",
            r#"{"rows": 1, "cols": 3, "vertices": [[0,0,0],[1,0,0],[2,0,0]]}"#,
            "no face to measure",
        ),
        (
            "huge.json",
            r#"{"rows": 2, "cols": 2, "vertices": [[0,0,0],[0,1,0],[1e200,0,0],[1,1,0]]}"#,
            "outside [1e-100, 1e100]",
        ),
    ] {
        monge()
            .arg("check")
            .arg(write(&dir, name, text))
            .assert()
            .code(2)
            .stderr(predicate::str::contains(says));
    }
}

#[test]
fn bench_refuses_a_size_below_2() {
    // n = 1 was documented as valid, then failed on a straight guide.
    monge()
        .args(["bench", "--sizes", "1"])
        .assert()
        .code(2)
        .stderr(predicate::str::contains("--sizes"));
}

#[test]
fn bench_prints_one_json_line_per_size() {
    let out = monge()
        .args(["bench", "--sizes", "10,12", "--runs", "3"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 2, "{text}");
    assert!(
        lines[0].starts_with(r#"{"faces":"10x10","median_ms":"#),
        "{}",
        lines[0]
    );
    for (line, faces) in lines.iter().zip(["10x10", "12x12"]) {
        let v: Value = serde_json::from_str(line).unwrap();
        assert_eq!(v["faces"], faces);
        assert_eq!(v["runs"], 3);
        assert!(v["median_ms"].as_f64().unwrap() > 0.0);
    }
}

#[test]
fn bench_all_prints_one_json_line_per_command_and_size() {
    let out = monge()
        // Two runs each: the second removes the first's output (a file, or
        // fabricate's directory) before it writes anew.
        .args(["bench", "--all", "--sizes", "4,6", "--runs", "2"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<Value> = text
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 2 * 9, "{text}");
    assert!(
        text.contains("\"command\":\"generate .ply binary\""),
        "{text}"
    );
    for (k, v) in lines.iter().enumerate() {
        let n: u32 = if k < 9 { 4 } else { 6 };
        assert_eq!(v["faces"], format!("{n}x{n}"));
        assert_eq!(v["runs"], 2);
        let n = f64::from(n);
        let wall = v["wall_ms"].as_f64().unwrap();
        assert!(wall > 0.0, "{v}");
        // ms per million faces is the wall time scaled by the face count (both
        // printed to 0.1: the wall time's rounding is scaled too).
        let (per, mfaces) = (v["ms_per_mface"].as_f64().unwrap(), n * n / 1e6);
        assert!((per - wall / mfaces).abs() <= 0.05 + 0.05 / mfaces, "{v}");
        assert!(v["peak_rss_mb"].as_f64().unwrap() > 1.0, "{v}");
        let bytes = v["bytes"].as_u64().unwrap();
        if v["command"] == "check .obj" {
            assert_eq!(bytes, 0);
            assert!(v["ratio_to_raw"].is_null());
        } else {
            assert!(
                bytes > 0 && v["ratio_to_raw"].as_f64().unwrap() > 0.0,
                "{v}"
            );
        }
    }
}

#[test]
fn help_teaches_theta_examples_and_exit_statuses() {
    monge().arg("--help").assert().success().stdout(
        predicate::str::contains("θ = +90° is singular")
            .and(predicate::str::contains("Exit status: 0"))
            .and(predicate::str::contains("monge generate examples/")),
    );
    for (command, example) in [
        ("generate", "monge generate "),
        ("check", "monge check "),
        ("info", "monge info "),
        ("bench", "monge bench"),
    ] {
        monge()
            .args([command, "--help"])
            .assert()
            .success()
            .stdout(predicate::str::contains(example).and(predicate::str::contains("Exit status")));
    }
}

#[test]
fn conical_meshes_and_offsets_are_written_and_pass_check() {
    let dir = TempDir::new().unwrap();
    let out = dir.path().join("c.json");
    monge()
        .arg("generate")
        .arg(example("fig13-conical.json"))
        .arg("-o")
        .arg(&out)
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
    monge()
        .arg("generate")
        .arg(example("fig13-freeform.json"))
        .arg("-o")
        .arg(&circular)
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
    monge()
        .arg("generate")
        .arg(example("fig13-freeform.json"))
        .args(["-o", "-", "--offset", "0.1"])
        .assert()
        .code(2)
        .stderr(predicate::str::contains(
            "--offset writes one file per offset",
        ));
    // An offset of another grid is refused.
    monge()
        .arg("check")
        .arg(&circular)
        .arg("--offset-from")
        .arg(&out)
        .assert()
        .code(2)
        .stderr(predicate::str::contains("the grids differ"));
}

/// `monge check --json` of `mesh` with `args`: its exit code and its JSON report.
fn check_json(mesh: &Path, args: &[&str]) -> (Option<i32>, Value) {
    let out = monge()
        .arg("check")
        .arg(mesh)
        .arg("--json")
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code(),
        serde_json::from_slice(&out.stdout).unwrap(),
    )
}

/// Issue 10, item 3: the `max_error` of `check --kind conical` is the largest of
/// the metrics a conical mesh must meet, not its circularity (1.4e-5), which a
/// conical mesh need not meet.
#[test]
fn check_conical_max_error_is_the_largest_required_metric() {
    let dir = TempDir::new().unwrap();
    let out = dir.path().join("c.obj");
    monge()
        .arg("generate")
        .arg(example("fig13-conical.json"))
        .arg("-o")
        .arg(&out)
        .assert()
        .success();
    let (code, v) = check_json(&out, &["--kind", "conical"]);
    assert_eq!((code, &v["pass"]), (Some(0), &Value::Bool(true)), "{v}");
    let metrics = v["metrics"].as_object().unwrap();
    let keys: Vec<&str> = metrics.keys().map(String::as_str).collect();
    let expected = [
        "column_planarity",
        "conical",
        "face_planarity",
        "folded_faces",
        "row_planarity",
    ];
    assert_eq!(keys, expected);
    let largest = [
        "face_planarity",
        "conical",
        "row_planarity",
        "column_planarity",
    ]
    .iter()
    .map(|k| metrics[*k]["value"].as_f64().unwrap())
    .fold(0.0, f64::max);
    let max_error = v["max_error"].as_f64().unwrap();
    assert_eq!(max_error, largest);
    assert!(max_error <= 1e-9, "{v}");
    // The same mesh measured as circular: its circularity is what max_error was.
    let (code, circular) = check_json(&out, &[]);
    let circularity = circular["metrics"]["circularity"]["value"]
        .as_f64()
        .unwrap();
    assert_eq!(
        (code, circular["max_error"].as_f64()),
        (Some(1), Some(circularity))
    );
    println!("conical max_error {max_error:e}, circularity {circularity:e}");
    assert!(
        circularity > 1e-6 && circularity != max_error,
        "{circularity}"
    );
}

#[test]
fn developable_designs_generate_check_and_report() {
    let dir = TempDir::new().unwrap();
    let out = dir.path().join("d.json");
    monge()
        .arg("generate")
        .arg(example("fig11-helix.developable.json"))
        .arg("-o")
        .arg(&out)
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
    monge()
        .arg("generate")
        .arg(&flat)
        .arg("-o")
        .arg(&bad)
        .assert()
        .code(2)
        .stderr(predicate::str::contains("α"));
    assert!(!bad.exists());
}

#[test]
fn smooth_refuses_an_output_above_max_output() {
    let dir = TempDir::new().unwrap();
    let out = dir.path().join("net.json");
    monge()
        .arg("smooth")
        .arg(example("fig13-freeform.json"))
        .arg("-o")
        .arg(&out)
        .args(["--samples", "200", "--max-output", "1"])
        .assert()
        .code(2)
        .stderr(predicate::str::contains(
            "60 × 40 patches of 200 × 200 points and 4900 arcs, would be about 5.8 GB, above the \
             limit of 1 GB: lower --samples",
        ));
    assert!(!out.exists());
}

#[test]
fn smooth_writes_the_cyclidic_net_contract() {
    let dir = TempDir::new().unwrap();
    let design = example("fig12-dupin-theta30.json");
    let (net, mesh) = (dir.path().join("net.json"), dir.path().join("m.json"));
    monge()
        .arg("smooth")
        .arg(&design)
        .arg("-o")
        .arg(&net)
        .args(["--samples", "4"])
        .assert()
        .success()
        .stderr(predicate::str::contains("cyclidic net (§4.4)"));
    monge()
        .arg("generate")
        .arg(&design)
        .arg("-o")
        .arg(&mesh)
        .assert()
        .success();
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
    monge()
        .arg("smooth")
        .arg(example("fig13-freeform.json"))
        .arg("-o")
        .arg(&obj)
        .assert()
        .success();
    monge().arg("check").arg(&obj).assert().success();
    monge()
        .arg("smooth")
        .arg(&design)
        .args(["-o", "x.json", "--samples", "1"])
        .assert()
        .code(2);
    // The exact surface as IGES: read back independently, it passes through the mesh vertices.
    let igs = dir.path().join("net.igs");
    monge()
        .arg("smooth")
        .arg(&design)
        .arg("-o")
        .arg(&igs)
        .assert()
        .success();
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
    monge()
        .arg("smooth")
        .arg(&mesh_path)
        .args(["--mesh", "--frame=1,0,0", "-o", "x.json"])
        .assert()
        .code(2)
        .stderr(predicate::str::contains("--frame takes 6 numbers"));
}

#[test]
fn render_smooth_draws_the_net_and_refuses_conical_designs() {
    let dir = TempDir::new().unwrap();
    let png = dir.path().join("s.png");
    monge()
        .arg("render")
        .arg(example("fig15-smooth.json"))
        .args(["--smooth", "4", "--size", "300x200", "-o"])
        .arg(&png)
        .assert()
        .success();
    assert!(fs::read(&png).unwrap().starts_with(b"\x89PNG"));
    monge()
        .arg("render")
        .arg(example("fig13-conical.json"))
        .args(["--smooth", "4", "-o"])
        .arg(dir.path().join("c.png"))
        .assert()
        .code(2)
        .stderr(predicate::str::contains(
            "--smooth draws the cyclidic net of a circular mesh",
        ));
}

/// The fills of an SVG's polygons, as `(r, g, b)`.
fn svg_fills(svg: &str) -> Vec<(u8, u8, u8)> {
    svg.split("fill=\"#")
        .skip(1)
        .filter_map(|s| {
            let hex = s.get(..6)?;
            let c = |k: usize| u8::from_str_radix(&hex[k..k + 2], 16).ok();
            Some((c(0)?, c(2)?, c(4)?))
        })
        .collect()
}

/// Issue 14: `render --deviation TARGET` colours the mesh by its distance to a target.
#[test]
fn render_deviation_colours_the_mesh_by_its_distance_to_a_target() {
    let dir = TempDir::new().unwrap();
    let mesh = dir.path().join("mesh.obj");
    monge()
        .arg("generate")
        .arg(example("fig13-freeform.json"))
        .arg("-o")
        .arg(&mesh)
        .assert()
        .success();
    // Its own mesh as target: every face white (shaded grey), the scale at its floor.
    let svg = dir.path().join("self.svg");
    monge()
        .arg("render")
        .arg(example("fig13-freeform.json"))
        .arg("--deviation")
        .arg(&mesh)
        .arg("-o")
        .arg(&svg)
        .assert()
        .success()
        .stderr(predicate::str::contains("coloured by its distance to"));
    let text = fs::read_to_string(&svg).unwrap();
    let fills = svg_fills(&text);
    assert!(fills.len() > 100);
    // No warm colour of the scale (they have r well above b).
    let warm = |(r, _, b): &&(u8, u8, u8)| u16::from(*r) > u16::from(*b) + 20;
    assert_eq!(fills.iter().filter(warm).count(), 0);
    // The same target lifted by 0.5 along z: the faces turn red, the scale ends at
    // the distance, 0.5 along z (a little less to the tilted tangent planes).
    let lifted: String = fs::read_to_string(&mesh)
        .unwrap()
        .lines()
        .filter_map(|l| {
            let v: Vec<f64> = l
                .strip_prefix("v ")?
                .split_whitespace()
                .map(|x| x.parse().unwrap())
                .collect();
            Some(format!("v {} {} {}\n", v[0], v[1], v[2] + 0.5))
        })
        .collect();
    let target = dir.path().join("lifted.obj");
    fs::write(&target, lifted).unwrap();
    let svg = dir.path().join("lifted.svg");
    monge()
        .arg("render")
        .arg(example("fig13-freeform.json"))
        .arg("--deviation")
        .arg(&target)
        .arg("-o")
        .arg(&svg)
        .assert()
        .success()
        .stderr(predicate::str::contains("95th percentile 0.49"));
    let fills = svg_fills(&fs::read_to_string(&svg).unwrap());
    let red = fills
        .iter()
        .filter(|(r, g, b)| *r > 60 && u16::from(*g) + u16::from(*b) < 60)
        .count();
    assert!(red > 100, "{red} red faces");
    // One design only.
    monge()
        .arg("render")
        .arg(example("fig13-freeform.json"))
        .arg(example("fig14.json"))
        .arg("--deviation")
        .arg(&mesh)
        .arg("-o")
        .arg(dir.path().join("two.svg"))
        .assert()
        .code(2)
        .stderr(predicate::str::contains("--deviation colours one design"));
}

/// Issue 10, item 5: `smooth` refused a conical design by ignoring its
/// `"mesh": "conical"`; now it says why and how to proceed, exit 2, no output.
#[test]
fn smooth_refuses_a_conical_design() {
    let dir = TempDir::new().unwrap();
    for ext in ["json", "igs", "obj"] {
        let out = dir.path().join(format!("net.{ext}"));
        monge()
            .arg("smooth")
            .arg(example("fig13-conical.json"))
            .arg("-o")
            .arg(&out)
            .assert()
            .code(2)
            .stderr(predicate::str::contains("fig13-conical.json"))
            .stderr(predicate::str::contains("built on circular meshes"))
            .stderr(predicate::str::contains(r#"Remove `"mesh": "conical"`"#));
        assert!(!out.exists(), "{} was written", out.display());
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
    smooth(&[])
        .assert()
        .code(2)
        .stderr(predicate::str::contains("--circularity-tol"));
    smooth(&["--circularity-tol", "1e-7"]).assert().success();
    smooth(&["--circularity-tol", "-1"]).assert().code(2);
    monge()
        .arg("smooth")
        .arg(example("fig12-dupin-theta30.json"))
        .arg("-o")
        .arg(dir.path().join("nan.json"))
        .arg("--frame=nan,0,0,0,1,0")
        .assert()
        .code(2)
        .stderr(predicate::str::contains("not orthonormal"));
    assert!(!dir.path().join("nan.json").exists());
}

#[test]
fn meshes_also_go_to_gltf_for_viewers_but_are_not_measured_from_it() {
    let dir = TempDir::new().unwrap();
    let glb = dir.path().join("m.glb");
    monge()
        .arg("generate")
        .arg(example("fig13-freeform.json"))
        .arg("-o")
        .arg(&glb)
        .assert()
        .success();
    assert!(fs::read(&glb).unwrap().starts_with(b"glTF"));
    monge()
        .arg("check")
        .arg(&glb)
        .assert()
        .code(2)
        .stderr(predicate::str::contains("glTF"));
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
        let design = dir.path().join(format!("{name}.json"));
        fs::write(&design, small_design(corner)).unwrap();
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
    monge()
        .arg("generate")
        .arg(example("fig12-dupin-theta30.json"))
        .arg("-o")
        .arg(&out)
        .args(["--offset", "-5"])
        .assert()
        .success();
    let report = |path: &Path| -> Value {
        serde_json::from_str::<Value>(&fs::read_to_string(path).unwrap()).unwrap()["report"].clone()
    };
    assert_eq!(report(&out)["folded_faces"], 0);
    let offset = dir.path().join("d.offset-5.json");
    let (code, checked) = check_json(&offset, &[]);
    assert_eq!(code, Some(1));
    let folds = &checked["metrics"]["folded_faces"];
    assert_eq!(report(&offset)["folded_faces"], folds["value"], "{checked}");
    assert_eq!(report(&offset)["folded_faces"], 288);
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
    monge()
        .arg("generate")
        .arg(&design)
        .arg("-o")
        .arg(&mesh)
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
        cmd.assert()
            .code(2)
            .stderr(predicate::str::contains("face (0, 0) is folded"))
            .stderr(predicate::str::contains("--allow-folded"));
        assert!(!out.exists(), "{} was written", out.display());
        cmd.arg("--allow-folded").assert().success();
        assert!(out.is_file());
        fs::remove_file(&out).unwrap();
    }
}

/// Faces of an OBJ whose own normal (the cross product of its diagonals, from
/// the file's corners) points against the face normal the JSON of the same mesh
/// gives (the circular mesh's node axis, §2.3): faces turned over.
fn faces_turned_over(obj: &Path, json: &Value) -> usize {
    let normals = json["face_normals"].as_array().unwrap();
    let faces = common::obj_faces(obj);
    assert_eq!(faces.len(), normals.len());
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    faces
        .iter()
        .zip(normals)
        .filter(|(f, n)| {
            let (d1, d2) = (sub(f[2], f[0]), sub(f[3], f[1]));
            let own = [
                d1[1] * d2[2] - d1[2] * d2[1],
                d1[2] * d2[0] - d1[0] * d2[2],
                d1[0] * d2[1] - d1[1] * d2[0],
            ];
            (0..3).map(|c| own[c] * n[c].as_f64().unwrap()).sum::<f64>() < 0.0
        })
        .count()
}

#[test]
fn a_conical_mesh_turned_over_is_reported_folded_everywhere() {
    // Found by a sweep of random designs: the circular mesh is not folded, but
    // faces of its conical dual are turned over (the conical error is 2.0); the
    // report said 0 folded faces and generate said nothing.
    let dir = TempDir::new().unwrap();
    let design = write(
        &dir,
        "turned.json",
        r#"{"theta_deg": -161.88466388622183, "mesh": "conical",
 "guide_u": {"bspline": {"degree": 3, "samples": 7, "control_points": [[0,0,0],[1,0,0],
   [2.2330790589699796,0,-0.5541680285794847],[2.8675485424895477,0,-2.155466699292466],[3.4849537934883603,0,1.7232772800102358]]}},
 "guide_v": {"bspline": {"degree": 3, "samples": 11, "control_points": [[0,0,0],[0,1,0],
   [-0.007441484123705624,1.9927520724723893,-0.0996294952040866],[6.193939782998956e-5,3.0061583164315824,0.0008292688442872063]]}}}"#,
    );
    let circular = write(
        &dir,
        "circular.json",
        &fs::read_to_string(&design)
            .unwrap()
            .replace("\"conical\"", "\"circular\""),
    );
    for (input, kind, turned) in [
        (&design, "conical", true),
        (&example("fig13-conical.json"), "conical", false),
        (&circular, "circular", false),
    ] {
        let (obj, json) = (dir.path().join("m.obj"), dir.path().join("m.json"));
        for out in [&obj, &json] {
            monge()
                .arg("generate")
                .arg(input)
                .arg("-o")
                .arg(out)
                .assert()
                .success();
        }
        let mesh: Value = serde_json::from_str(&fs::read_to_string(&json).unwrap()).unwrap();
        let reported = mesh["report"]["folded_faces"].as_u64().unwrap() as usize;
        let check = monge()
            .arg("check")
            .arg(&obj)
            .args(["--kind", kind, "--json"])
            .output()
            .unwrap();
        let check: Value = serde_json::from_slice(&check.stdout).unwrap();
        let checked = check["metrics"]["folded_faces"]["value"].as_f64().unwrap() as usize;
        if kind == "conical" {
            let reversed = faces_turned_over(&obj, &mesh);
            assert_eq!(reversed > 0, turned, "{}", input.display());
            assert!(reported >= reversed, "{reported} < {reversed}");
        }
        if turned {
            assert_eq!((reported, checked), (4, 4));
            assert_eq!(mesh["report"]["first_fold"], serde_json::json!([3, 0]));
        } else if kind == "conical" {
            assert_eq!((reported, checked), (0, 0));
        } else {
            // The circular mesh itself is not folded.
            assert_eq!(reported, 0);
        }
    }
    monge()
        .arg("generate")
        .arg(&design)
        .arg("-o")
        .arg(dir.path().join("m.obj"))
        .assert()
        .stderr(predicate::str::contains("in 4 faces, first at face (3, 0)"));
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
    monge()
        .arg("generate")
        .arg(&turned)
        .arg("-o")
        .arg(&obj)
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
    monge()
        .arg("fabricate")
        .arg(&turned)
        .arg("-o")
        .arg(dir.path().join("fab"))
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
    let out = monge()
        .arg("generate")
        .arg(&far)
        .arg("-o")
        .arg(&obj)
        .output()
        .unwrap();
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
    monge()
        .arg("generate")
        .arg(example("fig12-dupin-theta30.json"))
        .arg("-o")
        .arg(&obj)
        .assert()
        .success()
        .stderr(predicate::str::contains("measures an error").not());
}

/// A conical mesh checked without --kind: a JSON mesh says its kind and is measured as
/// it says; an OBJ cannot say, and its failure as a circular mesh names the flag (that
/// it passes as conical when it does). The truth: the generator's conical dual.
#[test]
fn check_takes_a_json_mesh_s_kind_and_suggests_kind_conical_otherwise() {
    let dir = TempDir::new().unwrap();
    let (json, obj) = (dir.path().join("c.json"), dir.path().join("c.obj"));
    for out in [&json, &obj] {
        monge()
            .arg("generate")
            .arg(example("fig13-conical.json"))
            .arg("-o")
            .arg(out)
            .assert()
            .success();
    }
    assert_eq!(read_json(&json)["kind"], "conical");
    let (code, v) = check_json(&json, &[]);
    assert_eq!(code, Some(0), "{v}");
    assert_eq!(v["kind"], "conical");
    assert!(v["metrics"]["conical"]["pass"].as_bool().unwrap(), "{v}");
    assert!(v["metrics"].get("circularity").is_none(), "{v}");
    monge()
        .arg("check")
        .arg(&json)
        .assert()
        .success()
        .stdout(predicate::str::contains("measured as a conical mesh"))
        .stderr(predicate::str::is_empty());
    // Said on the command line, the kind is the user's: no note.
    monge()
        .arg("check")
        .arg(&json)
        .args(["--kind", "circular"])
        .assert()
        .code(1)
        .stderr(predicate::str::is_empty());
    // The OBJ: measured as circular, fails, and the note says what to do.
    monge()
        .arg("check")
        .arg(&obj)
        .assert()
        .code(1)
        .stdout(predicate::str::contains("measured as a circular mesh"))
        .stderr(predicate::eq(format!(
            "note: `{}` fails as a circular mesh but passes as a conical one (§2.3): check it \
             with --kind conical\n",
            obj.display()
        )));
    monge()
        .arg("check")
        .arg(&obj)
        .args(["--kind", "conical"])
        .assert()
        .success();
    // Neither circular nor conical (one vertex moved off its face's circle and plane):
    // the note only names the flag.
    let text = fs::read_to_string(&obj).unwrap();
    let first = text.find("\nv ").unwrap() + 1;
    let end = first + text[first..].find('\n').unwrap();
    let moved = format!("{}v 0.5 0.25 0.125{}", &text[..first], &text[end..]);
    let bent = dir.path().join("bent.obj");
    fs::write(&bent, moved).unwrap();
    monge()
        .arg("check")
        .arg(&bent)
        .assert()
        .code(1)
        .stderr(predicate::eq(format!(
            "note: `{}` was measured as a circular mesh (§2.2); a conical mesh (§2.3) is \
             checked with --kind conical\n",
            bent.display()
        )));
    monge()
        .arg("check")
        .arg(&bent)
        .args(["--kind", "conical"])
        .assert()
        .code(1);
}
