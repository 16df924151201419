//! Helpers shared by the integration tests of the `monge` binary.

use std::ffi::OsStr;
use std::fs;
use std::path::{Path, PathBuf};

use assert_cmd::Command;
use predicates::prelude::*;
use serde_json::Value;
use tempfile::TempDir;

/// The bundled example designs.
pub fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

/// An example design by file name.
pub fn example(name: &str) -> PathBuf {
    examples().join(name)
}

/// The `monge` binary.
pub fn monge() -> Command {
    Command::new(env!("CARGO_BIN_EXE_monge"))
}

/// `monge COMMAND INPUT -o OUT`, to which a test adds its flags and assertions.
pub fn monge_to(command: &str, input: impl AsRef<OsStr>, out: impl AsRef<OsStr>) -> Command {
    let mut cmd = monge();
    cmd.arg(command).arg(input).arg("-o").arg(out);
    cmd
}

/// Runs `cmd` and asserts that `monge` refuses it: exit status 2, nothing on
/// standard output, standard error starting with `error: ` and containing each
/// of `expected`, and none of `absent` written. Returns standard error.
pub fn refuses(cmd: &mut Command, expected: &[&str], absent: &[&Path]) -> String {
    let output = cmd.assert().code(2).stdout("").get_output().clone();
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert!(stderr.starts_with("error: "), "not an error: {stderr}");
    for e in expected {
        assert!(stderr.contains(e), "stderr lacks `{e}`: {stderr}");
    }
    for path in absent {
        assert!(!path.exists(), "{} was written", path.display());
    }
    stderr
}

/// Generates `design` into `out` and checks the result, both with exit status 0.
pub fn generate_and_check(design: &Path, out: &Path) {
    monge_to("generate", design, out)
        .assert()
        .success()
        .stderr(predicate::str::contains("vertices"));
    assert!(out.is_file(), "{} was not written", out.display());
    monge()
        .arg("check")
        .arg(out)
        .assert()
        .success()
        .stdout(predicate::str::contains("PASS: every metric"));
}

/// The faces of an OBJ file as lists of corners, read by hand (`v` and `f`
/// lines only), independently of monge-io's reader.
pub fn obj_faces(path: &Path) -> Vec<Vec<[f64; 3]>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut vertices = Vec::new();
    let mut faces = Vec::new();
    for line in text.lines() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                let x: Vec<f64> = words.map(|w| w.parse().unwrap()).collect();
                vertices.push([x[0], x[1], x[2]]);
            }
            Some("f") => faces.push(
                words
                    .map(|w| w.split('/').next().unwrap().parse::<usize>().unwrap() - 1)
                    .collect::<Vec<_>>(),
            ),
            _ => {}
        }
    }
    faces
        .into_iter()
        .map(|f| f.into_iter().map(|k| vertices[k]).collect())
        .collect()
}

/// An ASCII PLY, parsed here: its header, each vertex's numbers (`x y z`, then any
/// others) and each face's corners (its count checked).
pub fn ply_ascii(path: &Path) -> (String, Vec<Vec<f64>>, Vec<Vec<usize>>) {
    let text = fs::read_to_string(path).unwrap();
    let (header, body) = text.split_once("end_header\n").unwrap();
    let count = |element: &str| -> usize {
        header
            .lines()
            .find_map(|l| l.strip_prefix(&format!("element {element} ")))
            .unwrap()
            .parse()
            .unwrap()
    };
    let (nv, nf) = (count("vertex"), count("face"));
    let lines: Vec<Vec<f64>> = body
        .lines()
        .map(|l| l.split_whitespace().map(|t| t.parse().unwrap()).collect())
        .collect();
    assert_eq!(lines.len(), nv + nf, "{}", path.display());
    let faces = lines[nv..]
        .iter()
        .map(|l| {
            assert_eq!(l[0] as usize, l.len() - 1);
            l[1..].iter().map(|&k| k as usize).collect()
        })
        .collect();
    (header.to_owned(), lines[..nv].to_vec(), faces)
}

/// Area of a planar polygon without crossings: half the length of its vector
/// area `½ Σ p_k × p_{k+1}` (the shoelace formula in 3D), relative to the first corner.
pub fn shoelace_area(polygon: &[[f64; 3]]) -> f64 {
    let o = polygon[0];
    let p: Vec<[f64; 3]> = polygon
        .iter()
        .map(|v| [v[0] - o[0], v[1] - o[1], v[2] - o[2]])
        .collect();
    let mut s = [0.0; 3];
    for k in 0..p.len() {
        let (a, b) = (p[k], p[(k + 1) % p.len()]);
        s[0] += a[1] * b[2] - a[2] * b[1];
        s[1] += a[2] * b[0] - a[0] * b[2];
        s[2] += a[0] * b[1] - a[1] * b[0];
    }
    0.5 * (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt()
}

/// Population variance and max/min of `values`.
pub fn variance_and_spread(values: &[f64]) -> (f64, f64) {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let variance = values.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / n;
    let min = values.iter().copied().fold(f64::INFINITY, f64::min);
    let max = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    (variance, max / min)
}

/// Parses a JSON file (a mesh, a design, a net).
pub fn read_json(path: &Path) -> Value {
    serde_json::from_str(&fs::read_to_string(path).unwrap()).unwrap()
}

/// Vertex `(i, j)` of a JSON mesh.
pub fn vertex(mesh: &Value, i: usize, j: usize) -> [f64; 3] {
    let cols = mesh["cols"].as_u64().unwrap() as usize;
    let v = &mesh["vertices"][i * cols + j];
    [0, 1, 2].map(|k| v[k].as_f64().unwrap())
}

/// fig10-arbitrary.json with another θ.
pub fn fig10_with_theta(theta: f64) -> String {
    let mut v: Value =
        serde_json::from_str(&fs::read_to_string(example("fig10-arbitrary.json")).unwrap())
            .unwrap();
    v["theta_deg"] = theta.into();
    v.to_string()
}

/// Writes `text` to `name` in `dir`.
pub fn write(dir: &TempDir, name: &str, text: &str) -> PathBuf {
    let path = dir.path().join(name);
    fs::write(&path, text).unwrap();
    path
}

/// `monge check --json` of `mesh` with `args`: its exit code and its JSON report.
pub fn check_json(mesh: &Path, args: &[&str]) -> (Option<i32>, Value) {
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
