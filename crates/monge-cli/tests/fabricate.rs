//! `monge fabricate` end to end (§6, Figure 25): files, summary, exit statuses.

use monge_io::FABRICATION_FILES;
use predicates::prelude::*;

use crate::common;
use common::{example, monge, refuses};

/// The summary line of one family of beams.
fn family_line<'a>(stdout: &'a str, family: &str) -> &'a str {
    stdout
        .lines()
        .find(|l| l.starts_with(family))
        .unwrap_or_else(|| panic!("no `{family}` line in:\n{stdout}"))
}

#[test]
fn biarc_design_has_biarc_rows_circular_columns_and_one_node_height() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("fab");
    let assert = monge()
        .args([
            "fabricate",
            example("fig25-biarc.json").to_str().unwrap(),
            "-o",
        ])
        .arg(&out)
        .args(["--layers", "0,-0.1,-0.2", "--section", "0.05,0.1"])
        .assert()
        .success();
    let stdout = String::from_utf8(assert.get_output().stdout.clone()).unwrap();
    assert!(
        stdout.contains("counts: 2016 panels, 162 beams, 725 nodes"),
        "{stdout}"
    );
    let rows = family_line(&stdout, "rows");
    assert!(
        rows.contains("2 segment(s) each, at most 2 radius(es) per beam"),
        "{rows}"
    );
    let cols = family_line(&stdout, "columns");
    assert!(
        cols.contains("1 segment(s) each, at most 1 radius(es) per beam"),
        "{cols}"
    );
    assert!(stdout.contains("node height: 0.2 to 0.2"), "{stdout}");
    assert!(stdout.contains(", panel circularity "), "{stdout}");
    for name in FABRICATION_FILES {
        assert!(out.join(name).is_file(), "{name} missing");
    }
    // The torsion residual in the summary is at most 1e-9.
    let torsion: f64 = stdout
        .rsplit("torsion ")
        .next()
        .unwrap()
        .trim()
        .parse()
        .unwrap();
    assert!(torsion <= 1e-9);
}

#[test]
fn conical_design_uses_face_offsets() {
    let dir = tempfile::tempdir().unwrap();
    monge()
        .args([
            "fabricate",
            example("fig13-conical.json").to_str().unwrap(),
            "-o",
        ])
        .arg(dir.path())
        .args(["--layers", "0,0.2"])
        .assert()
        .success()
        .stdout(predicate::str::contains(
            "conical mesh, face offsets (§2.3)",
        ))
        // Issue 10, item 5: a conical mesh's panels need not be circular, so
        // their circularity is no residual (the summary JSON has null).
        .stdout(predicate::str::contains("max residuals: offset "))
        .stdout(predicate::str::contains("circularity").not());
    let json = std::fs::read_to_string(dir.path().join("schedule.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(
        v["summary"]["max_panel_circularity"],
        serde_json::Value::Null
    );
    assert!(v["summary"]["max_panel_planarity"].as_f64().unwrap() <= 1e-9);
    // The schedules are the CSV files; --full-json repeats them in the JSON.
    assert!(v.get("panels").is_none() && v.get("nodes").is_none());
    monge()
        .args([
            "fabricate",
            example("fig13-conical.json").to_str().unwrap(),
            "--full-json",
            "-o",
        ])
        .arg(dir.path())
        .assert()
        .success();
    let json = std::fs::read_to_string(dir.path().join("schedule.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    let csv = std::fs::read_to_string(dir.path().join("panels.csv")).unwrap();
    assert_eq!(
        v["panels"].as_array().unwrap().len(),
        csv.lines().count() - 1
    );
    assert_eq!(
        v["panels"].as_array().unwrap().len(),
        v["summary"]["panels"]
    );
}

#[test]
fn bad_arguments_exit_with_status_2() {
    let dir = tempfile::tempdir().unwrap();
    let design = example("fig12-dupin-theta30.json");
    let out = dir.path().join("x");
    let run = |extra: &[&str], says: &str| {
        refuses(
            monge()
                .args(["fabricate", design.to_str().unwrap(), "-o"])
                .arg(&out)
                .args(extra),
            &[says],
            &[&out],
        )
    };
    run(&["--layers", "0,nan"], "not a finite number");
    run(&["--section", "0.1"], "WIDTH,DEPTH");
    run(&["--tol", "-1"], "non-negative");
    // A layer distance that collapses the mesh is a fabrication error.
    refuses(
        monge()
            .args(["fabricate", design.to_str().unwrap(), "-o"])
            .arg(dir.path().join("y"))
            .args(["--layers", "0,-3"]),
        &["no reliable direction"],
        &[],
    );
}

#[test]
fn an_output_above_max_output_is_refused_before_anything_is_written() {
    // fig13-freeform: 60 × 40 faces, 3 layers: about 19 MB of files (32 MB with --full-json).
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("fab");
    let run = |extra: &[&str], says: &[&str]| {
        refuses(
            monge()
                .args([
                    "fabricate",
                    example("fig13-freeform.json").to_str().unwrap(),
                    "-o",
                ])
                .arg(&out)
                .args(extra),
            says,
            &[&out],
        )
    };
    run(
        &["--layers", "0,0.1,0.2", "--max-output", "0.01"],
        &[
            "the fabrication files of 60 × 40 faces and 3 layer(s) would be about 19 MB",
            "fewer --layers",
            "--max-output GB",
        ],
    );
    run(
        &[
            "--layers",
            "0,0.1,0.2",
            "--max-output",
            "0.025",
            "--full-json",
        ],
        &["would be about 32 MB"],
    );
    run(&["--max-output", "0"], &["positive number of gigabytes"]);
}

/// A folded mesh is fabricated with the warning `monge generate` gives (it once
/// exited 0 without a word: its panels and beams cross each other).
#[test]
fn fabricate_warns_of_a_folded_mesh() {
    let dir = tempfile::TempDir::new().unwrap();
    let text = std::fs::read_to_string(common::example("fig14-family.toml")).unwrap();
    let folded = text.replace("theta_deg = 20.0", "theta_deg = 100.0");
    assert_ne!(folded, text);
    let design = dir.path().join("folded.toml");
    std::fs::write(&design, folded).unwrap();
    common::monge()
        .arg("fabricate")
        .arg(&design)
        .arg("-o")
        .arg(dir.path().join("F"))
        .assert()
        .success()
        .stderr(predicates::str::contains(
            "warning: the mesh folds over itself / pinches (§5.2) in 380 faces",
        ));
}

/// `-o -` is a directory named `-` no more (fabricate writes nine files).
#[test]
fn fabricate_refuses_standard_output() {
    refuses(
        monge()
            .arg("fabricate")
            .arg(example("fig25-biarc.json"))
            .args(["-o", "-"]),
        &["give a directory for -o"],
        &[],
    );
}

/// An OUT that is a file: said plainly (it once read only "File exists (os error 17)",
/// after all the work), the file untouched, nothing else written.
#[test]
fn fabricate_into_a_file_says_what_exists_and_what_to_do() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("fab");
    std::fs::write(&file, "mine").unwrap();
    let stderr = refuses(
        monge()
            .current_dir(dir.path())
            .arg("fabricate")
            .arg(example("fig25-biarc.json"))
            .args(["-o", "fab"]),
        &[],
        &[],
    );
    assert_eq!(
        stderr,
        "error: `fab` exists and is not a directory: the output is a directory of files; \
         give -o a new or existing directory (or remove `fab` first)\n"
    );
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "mine");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}
