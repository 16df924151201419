//! Trimmed designs (a design and the outline its mesh is cut by): `monge generate`
//! writes the mesh cut by the outline, measured here by hand; the commands that work on
//! a whole grid refuse one and say what to do.

use std::f64::consts::PI;
use std::path::{Path, PathBuf};

use serde_json::{json, Value};
use tempfile::TempDir;

use crate::common::{example, monge, monge_to, obj_faces, ply_ascii, refuses};

/// The hexagon of the trimmed design, in plan: centre (8, 5), radius 3.
const CENTRE: [f64; 2] = [8.0, 5.0];
const RADIUS: f64 = 3.0;

/// `examples/fig13-freeform.json` (16 × 10 in plan) trimmed to a hexagon in its middle,
/// seen from above, written as `name` in `dir`.
fn trimmed_design(dir: &TempDir, name: &str) -> PathBuf {
    let design: Value =
        serde_json::from_str(&std::fs::read_to_string(example("fig13-freeform.json")).unwrap())
            .unwrap();
    let polygon: Vec<[f64; 2]> = (0..6)
        .map(|k| {
            let a = k as f64 * PI / 3.0;
            [RADIUS * a.cos(), RADIUS * a.sin()]
        })
        .collect();
    let file = json!({
        "design": design,
        "trim": {
            "origin": [CENTRE[0], CENTRE[1], 0.0],
            "axes": [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            "up": [0.0, 0.0, 1.0],
            "polygon": polygon,
        }
    });
    let path = dir.path().join(name);
    std::fs::write(&path, serde_json::to_string_pretty(&file).unwrap()).unwrap();
    path
}

/// Whether the plan point `p` lies inside the hexagon or on it (within `eps`).
fn in_hexagon(p: [f64; 2], eps: f64) -> bool {
    let (x, y) = (p[0] - CENTRE[0], p[1] - CENTRE[1]);
    // Inside each side's half-plane: the side's normal at angle 30° + 60° k, the
    // apothem R cos 30°.
    (0..6).all(|k| {
        let a = PI / 6.0 + k as f64 * PI / 3.0;
        x * a.cos() + y * a.sin() <= RADIUS * (PI / 6.0).cos() + eps
    })
}

#[test]
fn generate_cuts_a_trimmed_designs_mesh_by_its_outline_into_planar_panels() {
    let dir = TempDir::new().unwrap();
    let design = trimmed_design(&dir, "trimmed.json");
    let (whole, cut) = (dir.path().join("whole.obj"), dir.path().join("cut.obj"));
    monge_to("generate", example("fig13-freeform.json"), &whole)
        .assert()
        .success();
    let stderr = monge_to("generate", &design, &cut)
        .assert()
        .success()
        .get_output()
        .stderr
        .clone();
    let stderr = String::from_utf8(stderr).unwrap();
    assert!(
        stderr.contains("trimmed to the design's outline"),
        "{stderr}"
    );
    let (whole, faces) = (obj_faces(&whole), obj_faces(&cut));
    assert!(
        faces.len() < whole.len() / 2 && faces.len() > 10,
        "{}",
        faces.len()
    );
    let mut corners = 0;
    for face in &faces {
        // Every corner inside the hexagon, in plan (its cuts on it).
        for p in face {
            assert!(in_hexagon([p[0], p[1]], 1e-9), "{p:?} outside");
        }
        // Planar: every corner in the plane of its first three, within round-off
        // (measured here, not by monge).
        let [a, b, c] = [face[0], face[1], face[2]];
        let sub = |p: [f64; 3], q: [f64; 3]| [p[0] - q[0], p[1] - q[1], p[2] - q[2]];
        let (u, v) = (sub(b, a), sub(c, a));
        let n = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        let length = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        for p in &face[3..] {
            let d = sub(*p, a);
            let off = (d[0] * n[0] + d[1] * n[1] + d[2] * n[2]).abs() / length;
            assert!(off < 1e-9 * 16.0, "a panel {off:e} off its plane");
        }
        corners = corners.max(face.len());
    }
    // Some panels are cut into polygons of more than four corners.
    assert!(corners > 4, "{corners}");
    // The hexagon's area, covered: the panels' areas in plan add up to it (the grid
    // covers it whole).
    let area: f64 = faces
        .iter()
        .map(|f| {
            let n = f.len();
            0.5 * (0..n)
                .map(|k| f[k][0] * f[(k + 1) % n][1] - f[(k + 1) % n][0] * f[k][1])
                .sum::<f64>()
                .abs()
        })
        .sum();
    let hexagon = 1.5 * 3f64.sqrt() * RADIUS * RADIUS;
    assert!((area - hexagon).abs() < 1e-9 * hexagon, "{area} {hexagon}");
}

/// The faces of the JSON mesh of polygons at `path` (`vertices`, `faces`), each its
/// corners' coordinates.
fn json_faces(path: &Path) -> Vec<Vec<[f64; 3]>> {
    let json: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let vertices: Vec<[f64; 3]> = serde_json::from_value(json["vertices"].clone()).unwrap();
    let faces: Vec<Vec<usize>> = serde_json::from_value(json["faces"].clone()).unwrap();
    faces
        .into_iter()
        .map(|f| f.into_iter().map(|k| vertices[k]).collect())
        .collect()
}

/// The faces of the ASCII PLY mesh at `path`, each its corners' coordinates.
fn ply_faces(path: &Path) -> Vec<Vec<[f64; 3]>> {
    let (_, vertices, faces) = ply_ascii(path);
    faces
        .into_iter()
        .map(|f| {
            f.into_iter()
                .map(|k| [0, 1, 2].map(|c| vertices[k][c]))
                .collect()
        })
        .collect()
}

#[test]
fn a_trimmed_designs_mesh_is_written_in_every_mesh_format_with_the_same_panels() {
    let dir = TempDir::new().unwrap();
    let design = trimmed_design(&dir, "trimmed.json");
    let path = |name: &str| dir.path().join(name);
    for name in ["cut.obj", "cut.ply", "cut.json", "cut.glb"] {
        let stderr = monge_to("generate", &design, path(name))
            .assert()
            .success()
            .get_output()
            .stderr
            .clone();
        let format = name.rsplit('.').next().unwrap().to_uppercase();
        assert!(
            String::from_utf8(stderr)
                .unwrap()
                .contains(&format!("wrote {format} `")),
            "{name}"
        );
    }
    // The same panels, corner for corner, to the bit.
    let obj = obj_faces(&path("cut.obj"));
    assert!(obj.iter().any(|f| f.len() > 4));
    assert_eq!(ply_faces(&path("cut.ply")), obj);
    assert_eq!(json_faces(&path("cut.json")), obj);
    let glb = std::fs::read(path("cut.glb")).unwrap();
    assert_eq!(&glb[..4], b"glTF");
    // check measures the PLY meshes, ASCII and binary, and the JSON one as the OBJ.
    monge_to("generate", &design, path("binary.ply"))
        .args(["--format", "ply-binary"])
        .assert()
        .success();
    for name in ["cut.ply", "binary.ply", "cut.json"] {
        let out = monge()
            .arg("check")
            .arg(path(name))
            .arg("--json")
            .output()
            .unwrap();
        assert!(out.status.success(), "{name}: {out:?}");
        let report: Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(report["polygons"], obj.len(), "{name}");
        assert!(report["max_error"].as_f64().unwrap() < 1e-12, "{report}");
    }
}

#[test]
fn approximate_writes_a_trimmed_mesh_in_the_format_of_its_extension() {
    let dir = TempDir::new().unwrap();
    let path = |name: &str| dir.path().join(name);
    let target = example("targets/paraboloid.obj");
    let fit = |trimmed: &Path| {
        let mut cmd = monge();
        cmd.arg("approximate")
            .arg(&target)
            .arg("-o")
            .arg(path("fit.json"))
            .arg("--trim")
            .arg(trimmed)
            .args([
                "--grid",
                "12x12",
                "--starts",
                "1",
                "--max-evaluations",
                "60",
            ]);
        cmd
    };
    let stdout = fit(&path("fit.ply"))
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let stdout = String::from_utf8(stdout).unwrap();
    // The largest distance of the trimmed result, in model units, as the fit prints it
    // and `monge render --deviation` draws it.
    let largest = stdout
        .lines()
        .find(|l| l.starts_with("result:"))
        .and_then(|l| l.split("; max ").nth(1))
        .and_then(|l| l.split(' ').next())
        .unwrap()
        .to_owned();
    let png = path("deviation.png");
    let out = monge_to("render", path("fit.json"), &png)
        .arg("--deviation")
        .arg(&target)
        .assert()
        .success()
        .get_output()
        .stderr
        .clone();
    let out = String::from_utf8(out).unwrap();
    assert!(
        out.contains(&format!("(trimmed, largest {largest})")),
        "{out} {stdout}"
    );
    assert!(png.exists());
    // As `monge generate` writes the trimmed design, but for its header's comment.
    monge_to("generate", path("fit.json"), path("again.ply"))
        .assert()
        .success();
    let body = |name: &str| {
        let text = std::fs::read_to_string(path(name)).unwrap();
        text.lines()
            .filter(|l| !l.starts_with("comment"))
            .collect::<Vec<_>>()
            .join("\n")
    };
    assert_eq!(body("fit.ply"), body("again.ply"));
    // Standard output, which carries the report, and an extension that is not a mesh
    // format's are refused before the fit, nothing written.
    std::fs::remove_file(path("fit.json")).unwrap();
    refuses(
        &mut fit(Path::new("-")),
        &["--trim writes the trimmed mesh to a file"],
        &[&path("fit.json")],
    );
    refuses(
        &mut fit(&path("fit.stl")),
        &["--trim", "`.stl`", "`.obj`, `.ply`, `.json` or `.glb`"],
        &[&path("fit.stl"), &path("fit.json")],
    );
}

#[test]
fn a_trimmed_design_is_refused_by_whole_grid_commands() {
    let dir = TempDir::new().unwrap();
    let design = trimmed_design(&dir, "trimmed.json");
    let obj = dir.path().join("cut.obj");
    refuses(
        monge_to("generate", &design, &obj).args(["--offset", "0.1"]),
        &["--offset and --base-point work on a whole grid"],
        &[&obj],
    );
    // info tells what the outline keeps.
    let out = monge().arg("info").arg(&design).output().unwrap();
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert!(out.status.success(), "{stdout}");
    let panels = obj_faces(&{
        let cut = dir.path().join("for-info.obj");
        monge_to("generate", &design, &cut).assert().success();
        cut
    })
    .len();
    assert!(
        stdout.contains(&format!("trimmed to an outline of 6 corners enclosing 23.3827 square model units: {panels} panels")),
        "{stdout}"
    );
    let out = monge()
        .args(["info", "--json"])
        .arg(&design)
        .output()
        .unwrap();
    let json: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(json["trim"]["panels"], panels);
    let png = dir.path().join("x.png");
    refuses(
        monge_to("render", &design, &png).args(["--theta-sweep", "10,20"]),
        &["is a trimmed design", "the file's `design`"],
        &[&png],
    );
    let out: &Path = &dir.path().join("fab");
    refuses(
        monge().arg("fabricate").arg(&design).arg("-o").arg(out),
        &["is a trimmed design", "not a design", "`monge generate`"],
        &[out],
    );
}

#[test]
fn check_measures_a_trimmed_mesh_for_the_planarity_of_its_panels() {
    let dir = TempDir::new().unwrap();
    let design = trimmed_design(&dir, "trimmed.json");
    let cut = dir.path().join("cut.obj");
    monge_to("generate", &design, &cut).assert().success();
    let out = monge()
        .arg("check")
        .arg(&cut)
        .arg("--json")
        .output()
        .unwrap();
    assert!(out.status.success(), "{out:?}");
    let report: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(report["pass"], true);
    assert!(report["max_error"].as_f64().unwrap() < 1e-12, "{report}");
    assert_eq!(report["polygons"], obj_faces(&cut).len());
    // One corner of a five-cornered panel moved off its plane by 1e-3: it fails there.
    let text = std::fs::read_to_string(&cut).unwrap();
    let faces: Vec<Vec<usize>> = text
        .lines()
        .filter_map(|l| l.strip_prefix("f "))
        .map(|l| l.split_whitespace().map(|k| k.parse().unwrap()).collect())
        .collect();
    let (f, face) = faces
        .iter()
        .enumerate()
        .find(|(_, f)| f.len() >= 5)
        .unwrap();
    let moved = face[2];
    let mut v = 0;
    let bent: String = text
        .lines()
        .map(|l| {
            if let Some(rest) = l.strip_prefix("v ") {
                v += 1;
                if v == moved {
                    let c: Vec<f64> = rest
                        .split_whitespace()
                        .map(|x| x.parse().unwrap())
                        .collect();
                    return format!("v {} {} {}\n", c[0], c[1], c[2] + 1e-3);
                }
            }
            format!("{l}\n")
        })
        .collect();
    let bent_path = dir.path().join("bent.obj");
    std::fs::write(&bent_path, bent).unwrap();
    let out = monge().arg("check").arg(&bent_path).output().unwrap();
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert_eq!(out.status.code(), Some(1), "{stdout}");
    assert!(
        stdout.contains("not a quad grid") && stdout.contains(&format!("at face {f},")),
        "{stdout}"
    );
    assert!(stdout.contains("FAIL: a face's corner"), "{stdout}");
    refuses(
        monge().arg("check").arg(&cut).args(["--kind", "conical"]),
        &[
            "is a mesh of polygons",
            "--kind and --offset-from need a quad grid",
        ],
        &[],
    );
}

#[test]
fn render_draws_a_trimmed_design_with_its_cut() {
    let dir = TempDir::new().unwrap();
    let design = trimmed_design(&dir, "trimmed.json");
    let svg = dir.path().join("trimmed.svg");
    let out = monge_to("render", &design, &svg).output().unwrap();
    assert!(out.status.success(), "{out:?}");
    let text = std::fs::read_to_string(&svg).unwrap();
    // The cut, in black: one closed polyline round the hexagon.
    let cuts: Vec<&str> = text
        .lines()
        .filter(|l| l.starts_with("<polyline") && l.contains("stroke=\"#000000\""))
        .collect();
    assert_eq!(cuts.len(), 1, "{cuts:?}");
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(stderr.contains("wrote"), "{stderr}");
}
