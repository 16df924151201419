//! `monge patches` and `monge fit` (§4.7, §4.5): outputs, summaries and exit statuses.

use std::fs;

use predicates::prelude::*;
use serde_json::Value;
use tempfile::TempDir;

use crate::common;
use common::{example, monge, refuses};

#[test]
fn patches_writes_one_grid_with_patches_and_line_planes() {
    let dir = TempDir::new().unwrap();
    let out = dir.path().join("h.json");
    monge()
        .arg("patches")
        .arg(example("fig21-hippohaus.patches.json"))
        .arg("-o")
        .arg(&out)
        .assert()
        .success()
        .stderr(predicate::str::contains(
            "5 patches along rows in a 31 × 11 grid",
        ));
    let v: Value = serde_json::from_str(&fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!(
        (v["rows"].as_u64(), v["cols"].as_u64()),
        (Some(31), Some(11))
    );
    let patches = v["patches"].as_array().unwrap();
    assert_eq!(patches.len(), 5);
    for p in patches {
        assert!(p["max_error"].as_f64().unwrap() <= 1e-9, "{p}");
    }
    // Columns cross the five patches: five planes each.
    let lines = v["line_planes"].as_array().unwrap();
    let column = lines.iter().find(|l| l["row"] == false).unwrap();
    assert_eq!(column["planes"].as_array().unwrap().len(), 5);
    // The mesh reads back and checks exact patch by patch through the library too.
    monge().args(["check"]).arg(&out).assert().code(1); // columns are only piecewise planar: the whole grid is not one patch
}

#[test]
fn patches_with_a_mirror_merges_the_seam() {
    let dir = TempDir::new().unwrap();
    let out = dir.path().join("dome.obj");
    monge()
        .arg("patches")
        .arg(example("fig20-piecewise.patches.json"))
        .arg("-o")
        .arg(&out)
        .assert()
        .success()
        .stderr(predicate::str::contains(
            "2 copies merged into 533 vertices and 480 quads",
        ));
    let text = fs::read_to_string(&out).unwrap();
    assert_eq!(text.lines().filter(|l| l.starts_with("v ")).count(), 533);
    assert_eq!(text.lines().filter(|l| l.starts_with("f ")).count(), 480);
}

#[test]
fn fit_recovers_the_hippohaus_thetas() {
    let dir = TempDir::new().unwrap();
    let out = dir.path().join("fitted.json");
    let assert = monge()
        .arg("fit")
        .arg(example("fig21-hippohaus-fit.patches.json"))
        .arg("-o")
        .arg(&out)
        .assert()
        .success()
        .stdout(predicate::str::contains("before: largest distance"));
    let stdout = String::from_utf8(assert.get_output().stdout.clone()).unwrap();
    assert!(stdout.contains("theta[1]: -40 -> -25"), "{stdout}");
    assert!(stdout.contains("theta[2]: 25 -> 40"), "{stdout}");
    let v: Value = serde_json::from_str(&fs::read_to_string(&out).unwrap()).unwrap();
    assert!((v["patches"][2]["theta_deg"].as_f64().unwrap() - 40.0).abs() < 1e-6);
    assert!(v["fit"].is_object(), "the fit section is kept");
}

/// Write `design` (the HippoHaus fit example, edited) and run `monge fit` on it.
fn fit_error(edit: impl FnOnce(&mut Value)) -> String {
    let dir = TempDir::new().unwrap();
    let mut d: Value = serde_json::from_str(
        &fs::read_to_string(example("fig21-hippohaus-fit.patches.json")).unwrap(),
    )
    .unwrap();
    edit(&mut d);
    let path = dir.path().join("d.json");
    fs::write(&path, d.to_string()).unwrap();
    let out = dir.path().join("out.json");
    refuses(
        monge().arg("fit").arg(&path).arg("-o").arg(&out),
        &[],
        &[&out],
    )
}

#[test]
fn fit_unreachable_target_exits_2() {
    let e = fit_error(|d| {
        d["fit"]["target"] = serde_json::json!({"polyline": [[90, 90, 90], [91, 90, 90]]});
        d["fit"]["max_evaluations"] = serde_json::json!(40);
    });
    assert!(
        e.contains("error: ") && e.contains("unreachable target"),
        "{e}"
    );
}

#[test]
fn fit_empty_bounds_exits_2() {
    let e = fit_error(|d| {
        d["fit"]["free"][0] = serde_json::json!({"theta": {"patch": 1, "bounds": [10, 20]}});
    });
    assert!(e.contains("empty bounds"), "{e}");
}

#[test]
fn patches_incompatible_boundaries_exit_2() {
    let dir = TempDir::new().unwrap();
    let mut d: Value =
        serde_json::from_str(&fs::read_to_string(example("fig21-hippohaus.patches.json")).unwrap())
            .unwrap();
    d["patches"][4]["attach"]["side"] = serde_json::json!("last_column");
    let path = dir.path().join("d.json");
    fs::write(&path, d.to_string()).unwrap();
    refuses(
        monge()
            .arg("patches")
            .arg(&path)
            .arg("-o")
            .arg(dir.path().join("m.obj")),
        &["incompatible boundaries"],
        &[],
    );
}

#[test]
fn patches_refuses_more_copies_than_the_vertex_limit() {
    // A rotation of order 10⁸: refused before any copy is made (it once ran for
    // minutes and many GB), and the message names the option.
    let dir = TempDir::new().unwrap();
    let mut d: Value =
        serde_json::from_str(&fs::read_to_string(example("fig20-piecewise.patches.json")).unwrap())
            .unwrap();
    d["symmetry"] = serde_json::json!([
        {"rotate": {"point": [0, 0, 0], "axis": [0, 0, 1], "order": 100_000_000}}
    ]);
    let path = dir.path().join("d.json");
    fs::write(&path, d.to_string()).unwrap();
    let out = dir.path().join("m.obj");
    refuses(
        monge().arg("patches").arg(&path).arg("-o").arg(&out),
        &["100000000 copies", "--max-vertices"],
        &[&out],
    );
}

#[test]
fn help_teaches_the_design_format() {
    monge()
        .args(["patches", "--help"])
        .assert()
        .success()
        .stdout(predicate::str::contains("`attach`").and(predicate::str::contains("symmetry")));
    monge()
        .args(["fit", "--help"])
        .assert()
        .success()
        .stdout(predicate::str::contains("BOBYQA").and(predicate::str::contains("max_distance")));
}
