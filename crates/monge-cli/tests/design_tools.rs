//! The design tools of §4.3 and §4.8 on the command line: `monge scan` and
//! `monge optimise-panels` (outputs, summaries, exit statuses).

use std::fs;

use predicates::prelude::*;
use tempfile::TempDir;

mod common;
use common::{example, monge};

#[test]
fn scan_writes_csv_and_plot_with_the_folded_interval() {
    let dir = TempDir::new().unwrap();
    let (csv, svg) = (dir.path().join("scan.csv"), dir.path().join("scan.svg"));
    monge()
        .args(["scan"])
        .arg(example("fig14-family.toml"))
        .args(["--theta", "60:130:5", "-o"])
        .arg(&csv)
        .arg("--plot")
        .arg(&svg)
        .assert()
        .success()
        .stderr(predicate::str::contains("folded: 75..85, 95..115"))
        .stderr(predicate::str::contains("inadmissible: 90"));
    let table = fs::read_to_string(&csv).unwrap();
    let statuses: Vec<(f64, String)> = table
        .lines()
        .skip(1)
        .map(|l| {
            let mut f = l.split(',');
            (
                f.next().unwrap().parse().unwrap(),
                f.next().unwrap().to_owned(),
            )
        })
        .collect();
    assert_eq!(statuses.len(), 15);
    for (theta, status) in statuses {
        let expected = if theta == 90.0 {
            "inadmissible"
        } else if (75.0..=115.0).contains(&theta) {
            "folded"
        } else {
            "fair"
        };
        assert_eq!(status, expected, "θ = {theta}");
    }
    let plot = fs::read_to_string(&svg).unwrap();
    assert!(plot.contains("class=\"folded\" data-from=\"95\" data-to=\"115\""));
}

#[test]
fn scan_of_another_parameter_and_bad_arguments() {
    let dir = TempDir::new().unwrap();
    let csv = dir.path().join("scan.csv");
    monge()
        .args(["scan"])
        .arg(example("fig14-family.toml"))
        .args([
            "--param",
            "guide_v.bspline.control_points[2][2]",
            "--range",
            "1:3:1",
            "-o",
        ])
        .arg(&csv)
        .assert()
        .success()
        .stderr(predicate::str::contains("fair: 1..3"));
    assert_eq!(fs::read_to_string(&csv).unwrap().lines().count(), 4);
    monge()
        .args(["scan"])
        .arg(example("fig14-family.toml"))
        .args(["--theta", "0:10:-1", "-o"])
        .arg(&csv)
        .assert()
        .code(2)
        .stderr(predicate::str::contains("never reaches its end"));
    monge()
        .args(["scan"])
        .arg(example("fig14-family.toml"))
        .args(["--param", "guide_w.points[0][0]", "--range", "0:1:1", "-o"])
        .arg(&csv)
        .assert()
        .code(2)
        .stderr(predicate::str::contains("no key `guide_w`"));
}

#[test]
fn optimise_panels_writes_a_design_with_parameters_that_generates_exactly() {
    let dir = TempDir::new().unwrap();
    let (out, mesh) = (dir.path().join("even.json"), dir.path().join("even.obj"));
    monge()
        .arg("optimise-panels")
        .arg(example("fig22-panels.json"))
        .arg("-o")
        .arg(&out)
        .assert()
        .success()
        .stdout(predicate::str::contains("before: area variance 1.73454e-5"))
        .stdout(predicate::str::contains("folded faces 0"));
    let text = fs::read_to_string(&out).unwrap();
    assert_eq!(text.matches("\"parameters\"").count(), 2, "{text}");
    monge()
        .arg("generate")
        .arg(&out)
        .arg("-o")
        .arg(&mesh)
        .assert()
        .success();
    monge().arg("check").arg(&mesh).assert().success();
    // A design without B-spline guides: exit 2 with the reason.
    monge()
        .arg("optimise-panels")
        .arg(example("fig12-dupin-theta30.json"))
        .arg("-o")
        .arg(dir.path().join("x.json"))
        .assert()
        .code(2)
        .stderr(predicate::str::contains("bspline"));
}
