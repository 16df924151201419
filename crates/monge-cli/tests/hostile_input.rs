//! Hostile and careless input files: a clear error and exit status 2, never a
//! panic (101) or an abort (134), and a cost bounded by what the file holds.
//! Each input here crashed or ran away before (found by a mutation fuzzer).

use crate::common;

use std::path::{Path, PathBuf};

use common::{example, monge, refuses};

/// `text` as `name` in `dir`.
fn file(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// A PLY whose `x` is declared as a list (of no items): `check` and `smooth
/// --mesh` indexed the empty list.
const LIST_X: &str = "ply\nformat ascii 1.0\nelement vertex 4\nproperty list uchar float x\n\
    property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\n\
    end_header\n0 0 0\n0 1 0\n0 0 1\n0 1 1\n4 0 2 3 1\n";

/// A point cloud declaring 1e15 vertices and holding one: `approximate` and
/// `render --deviation` reserved memory for them (capacity overflow; 1e11 aborted).
const HUGE_COUNT: &str = "ply\nformat ascii 1.0\nelement vertex 1000000000000000\n\
    property float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n";

#[test]
fn a_coordinate_declared_as_a_list_is_an_error_in_check_and_smooth() {
    let dir = tempfile::tempdir().unwrap();
    let ply = file(dir.path(), "list-x.ply", LIST_X);
    let said = "list-x.ply:4: the `vertex` property `x` is a list; coordinates and normals are \
                one number each: declare it as `property double x` (or float)";
    refuses(monge().arg("check").arg(&ply), &[said], &[]);
    let net = dir.path().join("net.json");
    refuses(
        monge()
            .args(["smooth", "--mesh"])
            .arg(&ply)
            .arg("-o")
            .arg(&net),
        &[said],
        &[&net],
    );
}

#[test]
fn a_count_the_file_cannot_hold_is_an_error_in_approximate_and_render() {
    let dir = tempfile::tempdir().unwrap();
    let ply = file(dir.path(), "huge.ply", HUGE_COUNT);
    let said = [
        "huge.ply:3: `element vertex 1000000000000000` does not fit in the file",
        "the count is wrong or the file is cut short",
    ];
    let design = dir.path().join("d.json");
    refuses(
        monge().arg("approximate").arg(&ply).arg("-o").arg(&design),
        &said,
        &[&design],
    );
    let picture = dir.path().join("d.png");
    refuses(
        monge()
            .arg("render")
            .arg(example("fig12-torus.json"))
            .arg("--deviation")
            .arg(&ply)
            .arg("-o")
            .arg(&picture),
        &said,
        &[&picture],
    );
}

/// `generate --format ply-binary` writes binary PLY; the target readers said
/// "invalid utf-8 sequence" of it.
#[test]
fn a_binary_ply_that_generate_writes_is_a_target() {
    let dir = tempfile::tempdir().unwrap();
    let ply = dir.path().join("torus.ply");
    monge()
        .arg("generate")
        .arg(example("fig12-torus.json"))
        .args(["--format", "ply-binary", "-o"])
        .arg(&ply)
        .assert()
        .success();
    assert!(std::fs::read(&ply)
        .unwrap()
        .starts_with(b"ply\nformat binary_little_endian"));
    // The torus against its own mesh: on it everywhere.
    monge()
        .arg("render")
        .arg(example("fig12-torus.json"))
        .arg("--deviation")
        .arg(&ply)
        .arg("-o")
        .arg(dir.path().join("d.png"))
        .assert()
        .success();
}

/// A B-spline guide of degree 4000 (a 120 kB design) took 20 s in `monge
/// info` (samples × degree²): refused at once, saying the limit and why.
#[test]
fn a_guide_of_too_high_a_degree_is_refused_with_the_limit() {
    let dir = tempfile::tempdir().unwrap();
    let n = 4000;
    let points: Vec<String> = (0..=n)
        .map(|k| {
            format!(
                "[{}, 0, {}]",
                k as f64 / n as f64,
                (k * k) as f64 / (n * n) as f64
            )
        })
        .collect();
    let design = format!(
        r#"{{"theta_deg": 30, "guide_u": {{"bspline": {{"degree": {n}, "control_points": [{}], "samples": 500}}}},
            "guide_v": {{"arc": {{"center": [0, 0, -1], "start": [0, 0, 0], "normal": [-1, 0, 0], "angle_deg": 60, "samples": 11}}}}}}"#,
        points.join(", ")
    );
    let path = file(dir.path(), "degree.json", &design);
    for command in ["info", "generate"] {
        let mut cmd = monge();
        cmd.arg(command).arg(&path);
        if command == "generate" {
            cmd.arg("-o").arg(dir.path().join("m.obj"));
        }
        refuses(
            &mut cmd,
            &["guide_u: `bspline.degree` is 4000, above the largest accepted, 32"],
            &[],
        );
    }
    // Degree 3 of the same control points is read.
    let cubic = design.replace(&format!("\"degree\": {n}"), "\"degree\": 3");
    let path = file(dir.path(), "cubic.json", &cubic);
    monge().arg("info").arg(&path).assert().success();
}

/// A design file used 25–45 times its size in memory (20 MB → 880 MB): a
/// design file over 16 MiB is refused by its length before it is read.
#[test]
fn a_design_file_over_16_mib_is_refused_before_it_is_read() {
    let dir = tempfile::tempdir().unwrap();
    let design = std::fs::read_to_string(example("fig12-torus.json")).unwrap();
    let path = dir.path().join("big.json");
    std::fs::write(&path, &design).unwrap();
    // 17 MiB: the design, then zeros (a sparse file: nothing written).
    let f = std::fs::OpenOptions::new().write(true).open(&path).unwrap();
    f.set_len(17 << 20).unwrap();
    for command in ["info", "generate", "patches", "align"] {
        let mut cmd = monge();
        cmd.arg(command).arg(&path);
        if command != "info" {
            cmd.arg("-o").arg(dir.path().join("out.json"));
        }
        refuses(
            &mut cmd,
            &[&format!(
                "{} has 17825792 bytes, more than a design file may have: 16777216 bytes (16 MiB)",
                path.display()
            )],
            &[],
        );
    }
}

/// A developable design of `points` helix points (a zigzag in plan, rising at
/// 45°) cut at `heights` planes below it.
fn developable_design(points: usize, heights: usize) -> String {
    let points: Vec<String> = (0..points).map(|k| format!("[{k},{},0]", k % 2)).collect();
    let heights: Vec<String> = (1..=heights).map(|k| format!("-{k}")).collect();
    format!(
        r#"{{"developable": {{"projection": {{"points": [{}], "alpha_deg": 45}}, "heights": [{}]}}}}"#,
        points.join(","),
        heights.join(",")
    )
}

/// A 1.6 MB developable design asked for 999 rulings × 200 000 cutting planes,
/// 2e8 vertices (a 16 MB one for 4e11, aborting on allocation), after a crossing
/// check quadratic in its points: refused at once by the vertex limit, the same
/// as a surface design's, or by its number of points; no output file.
#[test]
fn a_developable_design_over_the_vertex_limit_is_refused_before_it_is_built() {
    let dir = tempfile::tempdir().unwrap();
    let big = file(dir.path(), "big.json", &developable_design(1000, 200_000));
    let out = dir.path().join("m.obj");
    for command in ["info", "generate", "render"] {
        let mut cmd = monge();
        cmd.arg(command).arg(&big);
        if command != "info" {
            cmd.arg("-o").arg(if command == "render" {
                dir.path().join("m.png")
            } else {
                out.clone()
            });
        }
        refuses(
            &mut cmd,
            &[
                "the grid would have 999 × 200000 = 199800000 vertices, more than the limit of \
             25000000: lower the `samples` of the guides (of a developable design: its helix \
             points or `heights`), or raise the limit (`--max-vertices`",
            ],
            &[],
        );
    }
    assert!(!out.exists() && !dir.path().join("m.png").exists());
    // The same limit, lowered: 3 rulings × 3 planes.
    let small = file(dir.path(), "small.json", &developable_design(4, 3));
    for (limit, ok) in [("8", false), ("9", true)] {
        let mut run = monge();
        run.args(["generate", "--max-vertices", limit])
            .arg(&small)
            .arg("-o")
            .arg(&out);
        if ok {
            run.assert().success();
            assert!(out.exists());
        } else {
            refuses(
                &mut run,
                &["3 × 3 = 9 vertices, more than the limit of 8"],
                &[&out],
            );
        }
    }
    // More helix points than the crossing check accepts.
    let many = file(dir.path(), "many.json", &developable_design(1001, 2));
    refuses(
        monge().arg("info").arg(&many),
        &["the helix has 1001 points, more than the limit of 1000"],
        &[],
    );
}

/// A design near the largest size accepted (1e100): its coordinates beyond
/// ±3.4e38 do not fit the glTF's 32-bit floats.
const HUGE_DESIGN: &str = r#"{"theta_deg": -30,
  "guide_u": {"bspline": {"degree": 3, "samples": 5,
    "control_points": [[0, 0, 0], [4e98, 0, 0], [8e98, 0, 2.5e98], [12e98, 0, 1e98], [16e98, 0, 3.5e98]]}},
  "guide_v": {"bspline": {"degree": 3, "samples": 5,
    "control_points": [[0, 0, 0], [0, 3e98, 0], [0, 6e98, -1.5e98], [0, 10e98, 1e98]]}}}"#;

/// `fabricate` that cannot write one of its files leaves nothing behind, not
/// even the folder it created for them (it stayed, empty); the folders above
/// it must exist, as for every command.
#[test]
fn a_fabrication_that_cannot_be_written_leaves_no_folder() {
    let dir = tempfile::tempdir().unwrap();
    let design = file(dir.path(), "huge.json", HUGE_DESIGN);
    let out = dir.path().join("fab");
    refuses(
        monge().arg("fabricate").arg(&design).arg("-o").arg(&out),
        &["not finite in 32-bit floats"],
        &[&out],
    );
}

/// `scan` of a design near the largest size writes finite panel areas: the
/// squares of the faces' vector areas overflowed (areas `inf`, exit 0).
#[test]
fn panel_areas_of_a_huge_design_are_finite() {
    let dir = tempfile::tempdir().unwrap();
    let design = file(dir.path(), "huge.json", HUGE_DESIGN);
    let csv = dir.path().join("scan.csv");
    monge()
        .arg("scan")
        .arg(&design)
        .args(["--theta", "-30:-30:1", "-o"])
        .arg(&csv)
        .assert()
        .success();
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let row: Vec<&str> = lines.next().unwrap().split(',').collect();
    for name in ["area_min", "area_max", "area_spread", "area_mean"] {
        let k = header.iter().position(|h| *h == name).unwrap();
        let value: f64 = row[k].parse().unwrap();
        assert!(value.is_finite() && value > 0.0, "{name} = {}", row[k]);
    }
}
