//! `monge generate` of bad designs and bad arguments: each refused with exit
//! status 2, a message that says what and where, and no output; and the help text.

use std::fs;

use predicates::prelude::*;
use tempfile::TempDir;

use crate::common;
use common::{example, fig10_with_theta, generate_and_check, monge, refuses, write};

/// Runs `generate` on `design` (written as `name`) into `out.obj` with `extra`
/// arguments, and asserts exit status 2, an `error:` message containing
/// `expected`, and no output file (nor a temporary one) left behind.
fn generate_fails(name: &str, design: &str, extra: &[&str], expected: &str) {
    let dir = TempDir::new().unwrap();
    let design = write(&dir, name, design);
    let out = dir.path().join("out.obj");
    refuses(
        monge()
            .arg("generate")
            .arg(&design)
            .arg("-o")
            .arg(&out)
            .args(extra),
        &[expected],
        &[],
    );
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
    refuses(
        monge()
            .arg("generate")
            .arg(example("fig13-freeform.json"))
            .arg("-o")
            .arg(&out)
            .args(["--max-vertices", "10"]),
        &["more than the limit of 10"],
        &[&out],
    );
}

#[test]
fn an_unknown_output_extension_and_a_missing_design_are_errors() {
    let dir = TempDir::new().unwrap();
    let out = dir.path().join("out.stl");
    refuses(
        monge()
            .arg("generate")
            .arg(example("contract.json"))
            .arg("-o")
            .arg(&out),
        &["unsupported extension `.stl`"],
        &[&out],
    );
    refuses(
        monge()
            .arg("generate")
            .arg(dir.path().join("nothere.json"))
            .arg("-o")
            .arg(dir.path().join("out.obj")),
        &["file not found"],
        &[],
    );
}

#[test]
fn a_failed_generation_leaves_an_existing_output_untouched() {
    let dir = TempDir::new().unwrap();
    let design = write(&dir, "theta20.json", &fig10_with_theta(20.0));
    let out = write(&dir, "out.obj", "keep me\n");
    refuses(
        monge().arg("generate").arg(&design).arg("-o").arg(&out),
        &[],
        &[],
    );
    assert_eq!(fs::read_to_string(&out).unwrap(), "keep me\n");
}

#[test]
fn bad_arguments_exit_2() {
    // Without a command clap prints the help, not an `error:`.
    monge().assert().code(2);
    refuses(monge().args(["generate", "x.json"]), &[], &[]);
    refuses(
        monge().args(["check", "x.obj", "--tol", "-1"]),
        &["not a finite, non-negative number"],
        &[],
    );
    refuses(monge().args(["bench", "--sizes", "0"]), &[], &[]);
    refuses(monge().args(["check", "-"]), &["needs --format"], &[]);
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
