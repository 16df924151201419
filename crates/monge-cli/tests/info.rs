//! `monge info`: what generation would use, and the designs it refuses.

use predicates::prelude::*;
use serde_json::Value;
use tempfile::TempDir;

use crate::common;
use common::{example, fig10_with_theta, monge, refuses, write};

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
        refuses(
            &mut cmd,
            &["the surface normal turns by only 5.2e-7 rad along guide_u"],
            &[],
        );
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
