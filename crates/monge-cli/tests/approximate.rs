//! End-to-end tests of `monge approximate` (issue 14; monge's extension of the method).

use crate::common;

use std::fs;

use predicates::prelude::*;
use tempfile::TempDir;

use common::{examples, generate_and_check, monge, refuses};

/// `monge approximate` of the shipped paraboloid into `design`, quick: a grid of `n` × `n`
/// faces, one start, `evaluations` meshes per search.
fn paraboloid(design: &std::path::Path, n: usize, evaluations: usize) -> assert_cmd::Command {
    let mut command = monge();
    command
        .arg("approximate")
        .arg(examples().join("targets/paraboloid.obj"))
        .arg("-o")
        .arg(design)
        .args(["--grid", &format!("{n}x{n}"), "--starts", "1"])
        .args(["--max-evaluations", &evaluations.to_string()]);
    command
}

#[test]
fn approximate_writes_a_design_whose_mesh_is_exact() {
    let dir = TempDir::new().unwrap();
    let design = dir.path().join("fit.json");
    paraboloid(&design, 6, 60)
        .assert()
        .success()
        .stdout(predicate::str::contains("result: mesh → target max"))
        .stdout(predicate::str::contains("exactness of the result"))
        // A paraboloid has no planar curvature lines: one patch does not follow it.
        .stdout(predicate::str::contains(
            "one patch follows this target only",
        ));
    // The design is an ordinary design: generate it and measure it independently.
    let mesh = dir.path().join("fit.obj");
    generate_and_check(&design, &mesh);
}

#[test]
fn approximate_draws_the_initial_guess_and_the_result() {
    let dir = TempDir::new().unwrap();
    let design = dir.path().join("fit.json");
    let picture = dir.path().join("fit.svg");
    paraboloid(&design, 6, 60)
        .arg("--picture")
        .arg(&picture)
        .assert()
        .success()
        .stdout(predicate::str::contains(
            "coloured by their distance to the target",
        ));
    let svg = fs::read_to_string(&picture).unwrap();
    for caption in [
        "initial guess",
        "result",
        "white 0, dark red from",
        "target to mesh: max",
    ] {
        assert!(svg.contains(caption), "{caption}");
    }
    // Both panels on the initial guess's scale: the result's caption gives the same number.
    let scales: Vec<&str> = svg
        .split("dark red from ")
        .skip(1)
        .map(|s| s.split([' ', '<']).next().unwrap())
        .collect();
    assert_eq!(scales.len(), 2);
    assert_eq!(scales[0], scales[1]);
    // A picture of another format is refused before any work, and nothing is written.
    let design = dir.path().join("other.json");
    refuses(
        monge()
            .arg("approximate")
            .arg(examples().join("targets/paraboloid.obj"))
            .arg("-o")
            .arg(&design)
            .args(["--picture", "fit.gif"]),
        &["`.png` or `.svg`"],
        &[&design],
    );
}

#[test]
fn approximate_refuses_a_sphere_cap_with_status_2_and_no_output() {
    let dir = TempDir::new().unwrap();
    let target = dir.path().join("cap.obj");
    let mut text = String::new();
    for k in 0..400 {
        let (a, b) = ((k % 20) as f64 / 19.0 - 0.5, (k / 20) as f64 / 19.0 - 0.5);
        text.push_str(&format!("v {a} {b} {}\n", (4.0 - a * a - b * b).sqrt()));
    }
    fs::write(&target, text).unwrap();
    let design = dir.path().join("fit.json");
    refuses(
        monge()
            .arg("approximate")
            .arg(&target)
            .arg("-o")
            .arg(&design),
        &["umbilic", "cannot follow"],
        &[&design],
    );
}

#[test]
fn approximate_refuses_a_malformed_grid_and_time_limit() {
    let target = examples().join("targets/paraboloid.obj");
    refuses(
        monge()
            .args(["approximate"])
            .arg(&target)
            .args(["-o", "x.json", "--grid", "40"]),
        &["not UxV"],
        &[],
    );
    refuses(
        monge()
            .args(["approximate"])
            .arg(&target)
            .args(["-o", "x.json", "--time-limit=0"]),
        &["positive number of seconds"],
        &[],
    );
    // Once quietly taken as 1.
    refuses(
        monge()
            .args(["approximate"])
            .arg(&target)
            .args(["-o", "x.json", "--starts", "0"]),
        &["--starts"],
        &[],
    );
    // Beyond what the clock holds (it once panicked: "overflow when adding duration
    // to instant", "cannot convert float seconds to Duration"): no limit.
    let dir = TempDir::new().unwrap();
    for limit in ["1e19", "1e20", "inf"] {
        monge()
            .args(["approximate"])
            .arg(&target)
            .arg("-o")
            .arg(dir.path().join("x.json"))
            .args(["--grid", "8x8", "--starts", "1", "--max-evaluations", "10"])
            .arg(format!("--time-limit={limit}"))
            .assert()
            .success();
    }
}

#[test]
fn approximate_patches_writes_a_multi_patch_design_when_it_follows_closer() {
    let dir = TempDir::new().unwrap();
    let design = dir.path().join("fit.patches.json");
    let out = paraboloid(&design, 8, 80)
        .args(["--patches", "2"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8(out.stdout).unwrap();
    // Two patches, or the single patch when they do not come closer (never worse).
    assert!(
        stdout.contains("2 patches (§4.7): mesh → target max")
            || stdout.contains("1 patches (§4.7): mesh → target max"),
        "{stdout}"
    );
    assert!(stdout.contains("exactness of the patches (generated, measured)"));
    // Whichever was written, the command that reads it builds it.
    let command = if stdout.contains("DESIGN is a multi-patch design") {
        "patches"
    } else {
        assert!(stdout.contains("DESIGN is the single patch"), "{stdout}");
        "generate"
    };
    monge()
        .arg(command)
        .arg(&design)
        .arg("-o")
        .arg(dir.path().join("fit.obj"))
        .assert()
        .success();
    // One patch is not several.
    let other = dir.path().join("other.json");
    refuses(
        paraboloid(&other, 8, 40).args(["--patches", "1"]),
        &["at least 2"],
        &[&other],
    );
}

#[test]
fn approximate_reads_an_iges_surface_as_target() {
    // The smooth surface of the shipped roof (a cyclidic net, one NURBS surface in IGES).
    let dir = TempDir::new().unwrap();
    let iges = dir.path().join("roof.igs");
    monge()
        .arg("smooth")
        .arg(examples().join("targets/roof.design.json"))
        .arg("-o")
        .arg(&iges)
        .assert()
        .success();
    let design = dir.path().join("fit.json");
    monge()
        .arg("approximate")
        .arg(&iges)
        .arg("-o")
        .arg(&design)
        .args(["--grid", "6x6", "--starts", "1", "--max-evaluations", "60"])
        .assert()
        .success()
        .stdout(predicate::str::contains("target: 4096 points"));
    generate_and_check(&design, &dir.path().join("fit.obj"));
}
