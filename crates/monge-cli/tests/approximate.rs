//! End-to-end tests of `monge approximate` (issue 14; monge's extension of the method).

use crate::common;

use std::fs;

use predicates::prelude::*;
use tempfile::TempDir;

use common::{examples, generate_and_check, monge, monge_to, refuses};

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
        "target, by its distance to the result",
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
    // The target's points, the initial guess and the result, on one scale.
    assert_eq!(scales.len(), 3);
    assert!(scales.iter().all(|s| *s == scales[0]), "{scales:?}");
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
fn approximate_fits_a_sphere_cap_umbilic_everywhere() {
    // Its principal directions are nowhere defined, but its boundary and its whole
    // quadric give starts: it is fitted, not refused.
    let dir = TempDir::new().unwrap();
    let target = dir.path().join("cap.obj");
    let mut text = String::new();
    for k in 0..400 {
        let (a, b) = ((k % 20) as f64 / 19.0 - 0.5, (k / 20) as f64 / 19.0 - 0.5);
        text.push_str(&format!("v {a} {b} {}\n", (4.0 - a * a - b * b).sqrt()));
    }
    fs::write(&target, text).unwrap();
    let design = dir.path().join("fit.json");
    monge()
        .arg("approximate")
        .arg(&target)
        .arg("-o")
        .arg(&design)
        .args(["--grid", "6x6", "--starts", "1", "--max-evaluations", "60"])
        .assert()
        .success()
        .stdout(predicate::str::contains("result: mesh → target max"));
    assert!(design.exists());
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

#[test]
fn approximate_reads_a_scans_points_and_an_stl_as_the_mesh_they_hold() {
    // The shipped paraboloid target (41 × 41 points, no faces) as a scan's text export and
    // as a binary STL of its grid's triangles, written here byte by byte.
    let dir = TempDir::new().unwrap();
    let obj = examples().join("targets/paraboloid.obj");
    let points = obj_points(&obj);
    let xyz = dir.path().join("roof.xyz");
    let text: String = points
        .iter()
        .map(|[x, y, z]| format!("{x},{y},{z},0.5\n"))
        .collect();
    fs::write(&xyz, format!("x,y,z,intensity\n{text}")).unwrap();
    let n: usize = 41;
    let mut stl = vec![b' '; 80];
    stl.extend(u32::try_from(2 * (n - 1) * (n - 1)).unwrap().to_le_bytes());
    let corner = |a: usize, b: usize| points[a * n + b];
    for i in 0..n - 1 {
        for j in 0..n - 1 {
            for t in [
                [corner(i, j), corner(i, j + 1), corner(i + 1, j + 1)],
                [corner(i, j), corner(i + 1, j + 1), corner(i + 1, j)],
            ] {
                stl.extend([0.0f32; 3].iter().flat_map(|c| c.to_le_bytes()));
                stl.extend(t.iter().flatten().flat_map(|c| (*c as f32).to_le_bytes()));
                stl.extend([0u8; 2]);
            }
        }
    }
    let stl_path = dir.path().join("roof.stl");
    fs::write(&stl_path, stl).unwrap();
    let fit = |target: &std::path::Path, name: &str| {
        let design = dir.path().join(name);
        monge()
            .arg("approximate")
            .arg(target)
            .arg("-o")
            .arg(&design)
            .args(["--grid", "6x6", "--starts", "1", "--max-evaluations", "60"])
            .assert()
            .success()
            .stdout(predicate::str::contains("target: 1681 points"));
        design
    };
    // The scan's points are the OBJ's: the same design, byte for byte.
    let from_obj = fit(&obj, "obj.json");
    let from_xyz = fit(&xyz, "xyz.json");
    assert_eq!(fs::read(&from_obj).unwrap(), fs::read(&from_xyz).unwrap());
    // The STL's distinct corners are the grid's points (in single precision).
    let from_stl = fit(&stl_path, "stl.json");
    generate_and_check(&from_stl, &dir.path().join("stl.obj"));
}

#[test]
fn approximate_sets_a_scans_stray_points_aside_and_names_them() {
    // 1 500 random points of a paraboloid roof, and the same with three stray points
    // among them: two above the roof (a bird, a crane), one far beyond its edge.
    let mut uniform = uniform_from(0x2545_f491_4f6c_dd1d_u64);
    let roof = |x: f64, y: f64| 0.04 * x * x + 0.1 * y * y;
    let mut lines: Vec<String> = (0..1500)
        .map(|_| {
            let (x, y) = (10.0 * uniform(), 10.0 * uniform());
            format!("{x} {y} {}", roof(x, y))
        })
        .collect();
    let dir = TempDir::new().unwrap();
    let clean = dir.path().join("clean.xyz");
    fs::write(&clean, lines.join("\n")).unwrap();
    for (at, point) in [
        (100, format!("5 5 {}", roof(5.0, 5.0) + 1.5)),
        (700, format!("2 8 {}", roof(2.0, 8.0) - 0.9)),
        (1200, format!("16 5 {}", roof(16.0, 5.0))),
    ] {
        lines.insert(at, point);
    }
    let scan = dir.path().join("scan.xyz");
    fs::write(&scan, lines.join("\n")).unwrap();
    let fit = |target: &std::path::Path, name: &str, extra: &[&std::ffi::OsStr]| {
        let design = dir.path().join(name);
        let out = monge()
            .arg("approximate")
            .arg(target)
            .arg("-o")
            .arg(&design)
            .args(["--grid", "6x6", "--starts", "1", "--max-evaluations", "60"])
            .args(extra)
            .output()
            .unwrap();
        assert!(out.status.success(), "{out:?}");
        (design, String::from_utf8(out.stdout).unwrap())
    };
    let (without, stdout) = fit(&clean, "clean.json", &[]);
    assert!(!stdout.contains("stray"), "{stdout}");
    let picture = dir.path().join("scan.svg");
    let (with, stdout) = fit(
        &scan,
        "scan.json",
        &["--picture".as_ref(), picture.as_os_str()],
    );
    assert!(
        stdout.contains(
            "set aside 3 stray points (isolated from the rest, or off the surface their nearest \
             others make; neither fitted nor measured): point 101 (5, 5, "
        ),
        "{stdout}"
    );
    assert!(stdout.contains(", point 701 (2, 8, "), "{stdout}");
    assert!(stdout.contains(", point 1201 (16, 5, "), "{stdout}");
    // Set aside, they change nothing: the scan's design without them, byte for byte.
    assert_eq!(fs::read(&without).unwrap(), fs::read(&with).unwrap());
    // The picture draws the 1 500 points kept, each coloured by its distance, and the
    // three set aside in blue (the colour no distance takes), each in a star of three
    // arms, and says so.
    let svg = fs::read_to_string(&picture).unwrap();
    let blue = |shape: &str| {
        svg.lines()
            .filter(|l| l.starts_with(shape) && l.contains("\"#1e64dc\""))
            .count()
    };
    assert_eq!(blue("<circle"), 3, "{svg}");
    assert_eq!(blue("<polyline"), 9, "{svg}");
    assert_eq!(
        svg.lines().filter(|l| l.starts_with("<circle")).count(),
        1503
    );
    assert!(svg.contains("3 stray points set aside, in blue"), "{svg}");
    // `render --deviation` measures the design as the fit did, and says so.
    monge()
        .arg("render")
        .arg(&with)
        .arg("--deviation")
        .arg(&scan)
        .arg("-o")
        .arg(dir.path().join("scan.png"))
        .assert()
        .success()
        .stderr(predicate::str::contains("; 3 stray points set aside)"));
}

/// Uniform random numbers in [0, 1) from `seed` (xorshift64), the same on every machine.
fn uniform_from(mut state: u64) -> impl FnMut() -> f64 {
    move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The points of an OBJ file's `v` lines, read by hand.
fn obj_points(path: &std::path::Path) -> Vec<[f64; 3]> {
    fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter_map(|l| l.strip_prefix("v "))
        .map(|l| {
            let x: Vec<f64> = l.split_whitespace().map(|w| w.parse().unwrap()).collect();
            [x[0], x[1], x[2]]
        })
        .collect()
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Distance from `p` to the segment `ab`.
fn to_segment(p: [f64; 3], a: [f64; 3], b: [f64; 3]) -> f64 {
    let (ab, ap) = (sub(b, a), sub(p, a));
    let t = (dot(ap, ab) / dot(ab, ab)).clamp(0.0, 1.0);
    let d = sub(ap, [ab[0] * t, ab[1] * t, ab[2] * t]);
    dot(d, d).sqrt()
}

/// Distance from `p` to the triangle `abc`: to its plane if the foot lies inside
/// (barycentric coordinates), else to its nearest edge.
fn to_triangle(p: [f64; 3], a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    let (u, v, w) = (sub(b, a), sub(c, a), sub(p, a));
    let (uu, uv, vv, wu, wv) = (dot(u, u), dot(u, v), dot(v, v), dot(w, u), dot(w, v));
    let det = uu * vv - uv * uv;
    let (s, t) = ((vv * wu - uv * wv) / det, (uu * wv - uv * wu) / det);
    if s >= 0.0 && t >= 0.0 && s + t <= 1.0 {
        let foot = [
            a[0] + s * u[0] + t * v[0],
            a[1] + s * u[1] + t * v[1],
            a[2] + s * u[2] + t * v[2],
        ];
        let d = sub(p, foot);
        return dot(d, d).sqrt();
    }
    to_segment(p, a, b)
        .min(to_segment(p, b, c))
        .min(to_segment(p, c, a))
}

/// The largest distances, by brute force, from the mesh vertices of `mesh` (an OBJ of
/// quads) to the shipped paraboloid z = 0.04 x² + 0.1 y² over [0, 10]² (sampled every
/// 0.02, nearest sample) and from the paraboloid's shipped points to the mesh's
/// triangles.
fn paraboloid_distances(mesh: &std::path::Path) -> (f64, f64) {
    let surface = |x: f64, y: f64| [x, y, 0.04 * x * x + 0.1 * y * y];
    let fine: Vec<[f64; 3]> = (0..=500)
        .flat_map(|i| (0..=500).map(move |j| surface(i as f64 / 50.0, j as f64 / 50.0)))
        .collect();
    let vertices = obj_points(mesh);
    let mesh_to_target = vertices
        .iter()
        .map(|v| {
            fine.iter()
                .map(|q| dot(sub(*v, *q), sub(*v, *q)))
                .fold(f64::INFINITY, f64::min)
                .sqrt()
        })
        .fold(0.0, f64::max);
    let faces = common::obj_faces(mesh);
    let target = obj_points(&examples().join("targets/paraboloid.obj"));
    let target_to_mesh = target
        .iter()
        .map(|p| {
            faces
                .iter()
                .flat_map(|f| (1..f.len() - 1).map(move |k| to_triangle(*p, f[0], f[k], f[k + 1])))
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max);
    (mesh_to_target, target_to_mesh)
}

/// The number after `label` in `text`.
fn number_after(text: &str, label: &str) -> f64 {
    let rest = &text[text
        .find(label)
        .unwrap_or_else(|| panic!("no `{label}` in {text}"))
        + label.len()..];
    let word = rest.split_whitespace().next().unwrap();
    word.trim_end_matches([';', ',']).parse().unwrap()
}

/// The standard output of an `approximate --tolerance` run that `out` is, checked to say
/// it is within the tolerance at one patch (exit status 0).
fn within_at_one_patch(out: std::process::Output) -> String {
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert_eq!(out.status.code(), Some(0), "{stdout}");
    assert!(
        stdout.contains("within the tolerance: largest distance"),
        "{stdout}"
    );
    assert!(stdout.contains("result: 1 patch\n"), "{stdout}");
    stdout
}

#[test]
fn approximate_to_a_tolerance_met_writes_a_design_within_it() {
    let dir = TempDir::new().unwrap();
    let design = dir.path().join("fit.json");
    let out = paraboloid(&design, 6, 60)
        .args(["--tolerance", "0.2"])
        .output()
        .unwrap();
    let stdout = within_at_one_patch(out);
    assert!(
        stdout.contains("panels 36, distinct node types"),
        "{stdout}"
    );
    assert!(stdout.contains("patch 1 (block 1 × 1): θ"), "{stdout}");
    // Measured independently: the mesh of the design written, both ways, by brute force.
    let mesh = dir.path().join("fit.obj");
    generate_and_check(&design, &mesh);
    let (m, t) = paraboloid_distances(&mesh);
    let size = number_after(&stdout, "size");
    assert!(m.max(t) <= 0.2 * size, "{m} {t} {size}");
    // The numbers printed are these distances (the target's own sampling, 0.25 apart,
    // and its boundary known to that spacing, account for the difference).
    let printed_m = number_after(&stdout, "largest distance mesh → target");
    let printed_t = number_after(&stdout, "target → mesh");
    assert!((printed_m - m).abs() < 0.3, "{printed_m} {m}");
    assert!((printed_t - t).abs() < 0.05 * t + 1e-9, "{printed_t} {t}");
}

/// A scan resampled from a mesh (the shipped roof scan: random vertices of a surface with
/// planar curvature lines, noised by 1e-4 of its size) has its edge where its outermost
/// points are: one patch counts as within 1e-3 of it, as it is, measured independently
/// against the roof it was sampled from (its design regenerated; each vertex of the
/// result's mesh to the roof's triangles, by brute force).
#[test]
fn approximate_to_a_tolerance_counts_a_scan_of_an_exact_surface_within_it() {
    let dir = TempDir::new().unwrap();
    let design = dir.path().join("fit.json");
    let out = monge()
        .arg("approximate")
        .arg(examples().join("targets/roof-pcl.obj"))
        .arg("-o")
        .arg(&design)
        .args(["--grid", "20x20", "--tolerance", "1e-3"])
        .output()
        .unwrap();
    let stdout = within_at_one_patch(out);
    let (mesh, roof) = (dir.path().join("fit.obj"), dir.path().join("roof.obj"));
    generate_and_check(&design, &mesh);
    generate_and_check(&examples().join("targets/roof.design.json"), &roof);
    let triangles: Vec<[[f64; 3]; 3]> = common::obj_faces(&roof)
        .iter()
        .flat_map(|f| (1..f.len() - 1).map(move |k| [f[0], f[k], f[k + 1]]))
        .collect();
    let farthest = obj_points(&mesh)
        .iter()
        .map(|v| {
            triangles
                .iter()
                .map(|[a, b, c]| to_triangle(*v, *a, *b, *c))
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max);
    let size = number_after(&stdout, "size");
    assert!(farthest <= 1e-3 * size, "{farthest} of {size}");
}

#[test]
fn approximate_to_a_tolerance_not_met_says_why_with_numbers_and_exits_1() {
    let dir = TempDir::new().unwrap();
    let design = dir.path().join("fit.json");
    let picture = dir.path().join("fit.svg");
    let out = paraboloid(&design, 8, 60)
        .args(["--tolerance", "1mm", "--max-patches", "2"])
        .arg("--picture")
        .arg(&picture)
        .output()
        .unwrap();
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert_eq!(out.status.code(), Some(1), "{stdout}");
    assert!(stdout.contains("tolerance 0.001 model units"), "{stdout}");
    assert!(stdout.contains("NOT within the tolerance"), "{stdout}");
    assert!(
        stdout.contains("2 patches tried (--max-patches 2)"),
        "{stdout}"
    );
    // Where the last layout (here the only one, two patches) came no nearer than a tenth
    // of the largest distance of fewer patches (the steps printed), it says so rather than
    // asking for more.
    let step = |line: &str| {
        let (_, rest) = line.split_once("largest distance ")?;
        rest.split_whitespace().next()?.parse::<f64>().ok()
    };
    let nearest = |several: bool| {
        stdout
            .lines()
            .filter(|l| l.starts_with("1 patch") != several && l.contains(": largest distance"))
            .filter_map(step)
            .fold(f64::INFINITY, f64::min)
    };
    let stalled = nearest(true) >= 0.9 * nearest(false);
    assert_eq!(
        stdout.contains("the last layout (2 patches) not 10% nearer than fewer patches"),
        stalled,
        "{stdout}"
    );
    assert_eq!(stdout.contains("allow more patches"), !stalled, "{stdout}");
    // Never farther than the one-patch fit; the design and the picture are written.
    let one = number_after(&stdout, "1 patch: largest distance");
    let best = number_after(&stdout, "the nearest design found is");
    assert!(best <= one, "{stdout}");
    assert!(best > 0.001);
    // The result: the design's mesh, or the trimmed mesh written beside it.
    let mesh = if stdout.contains(", trimmed to its outline\n") {
        assert!(stdout.contains("fit.trimmed.obj (the result: "), "{stdout}");
        dir.path().join("fit.trimmed.obj")
    } else {
        let command = if stdout.contains("result: 2 patches") {
            "patches"
        } else {
            "generate"
        };
        let mesh = dir.path().join("fit.obj");
        monge()
            .arg(command)
            .arg(&design)
            .arg("-o")
            .arg(&mesh)
            .assert()
            .success();
        mesh
    };
    let (m, t) = paraboloid_distances(&mesh);
    assert!((m.max(t) - best).abs() < 0.05 * best, "{m} {t} {best}");
    let svg = fs::read_to_string(&picture).unwrap();
    assert!(svg.contains("target, by its distance to the result"));
    // On the tolerance's scale.
    assert_eq!(
        svg.matches("dark red from 0.001 (the tolerance)").count(),
        1
    );
    // The result's panel of a trimmed result gives the trimmed mesh's figures.
    assert_eq!(
        svg.matches("dark red from 0.001<").count()
            + svg.matches("dark red from 0.001; figures trimmed<").count(),
        2
    );
    // One dot per target point.
    assert!(
        svg.matches("<circle").count() >= 41 * 41,
        "{}",
        svg.matches("<circle").count()
    );
}

#[test]
fn approximate_to_a_tolerance_says_when_patches_cannot_help() {
    let dir = TempDir::new().unwrap();
    let design = dir.path().join("fit.json");
    let out = paraboloid(&design, 6, 40)
        .args(["--kind", "conical", "--tolerance", "1e-4"])
        .output()
        .unwrap();
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert_eq!(out.status.code(), Some(1), "{stdout}");
    assert!(
        stdout.contains("2 patches cannot be fitted: patches (§4.7) continue circular meshes"),
        "{stdout}"
    );
    monge_to("generate", &design, dir.path().join("fit.obj"))
        .assert()
        .success();
}

#[test]
fn approximate_refuses_bad_tolerances_before_any_work() {
    let dir = TempDir::new().unwrap();
    let design = dir.path().join("fit.json");
    for (tolerance, expected) in [
        ("-1", "give a positive, finite number"),
        ("0", "give a positive, finite number"),
        ("0.05parsecs", "unknown unit `parsecs`"),
        ("5", "(e.g. 5m)"),
        ("abc", "is not a tolerance"),
        ("inf", "is not a tolerance"),
    ] {
        refuses(
            paraboloid(&design, 6, 40).arg(format!("--tolerance={tolerance}")),
            &["--tolerance", expected],
            &[&design],
        );
    }
    refuses(
        paraboloid(&design, 6, 40).args(["--tolerance", "-1"]),
        &["give a positive"],
        &[&design],
    );
    refuses(
        paraboloid(&design, 6, 40).args(["--tolerance", "5e-3", "--patches", "2"]),
        &["cannot be used with"],
        &[&design],
    );
    refuses(
        paraboloid(&design, 6, 40).args(["--max-patches", "3"]),
        &["--tolerance"],
        &[&design],
    );
    refuses(
        paraboloid(&design, 6, 40).args(["--tolerance", "5e-3", "--max-patches", "0"]),
        &["--max-patches"],
        &[&design],
    );
    // The node types are counted in the report of a tolerance fit, at a non-negative
    // angle (as `monge fabricate --angle-tol`).
    refuses(
        paraboloid(&design, 6, 40).args(["--angle-tol", "0.3"]),
        &["--tolerance"],
        &[&design],
    );
    refuses(
        paraboloid(&design, 6, 40).args(["--tolerance", "5e-3", "--angle-tol", "-1"]),
        &["--angle-tol", "not a finite, non-negative number"],
        &[&design],
    );
}

/// The polygons of the OBJ at `path`, read back by a third-party reader, each checked
/// planar (its corners' distances to the plane of its first three, measured here, within
/// 1e-9 of the shipped paraboloid's size): how many are cut (more or fewer than four
/// corners).
fn planar_polygons_cut(path: &std::path::Path) -> usize {
    let (models, _) = tobj::load_obj(path, &tobj::LoadOptions::default()).unwrap();
    let mesh = &models[0].mesh;
    let p = |k: u32| {
        let k = 3 * k as usize;
        [
            mesh.positions[k],
            mesh.positions[k + 1],
            mesh.positions[k + 2],
        ]
    };
    let mut start = 0;
    let mut cut = 0;
    for &arity in &mesh.face_arities {
        let corners: Vec<[f64; 3]> = mesh.indices[start..start + arity as usize]
            .iter()
            .map(|k| p(*k))
            .collect();
        start += arity as usize;
        cut += usize::from(arity != 4);
        let (u, v) = (sub(corners[1], corners[0]), sub(corners[2], corners[0]));
        let n = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        let length = dot(n, n).sqrt();
        for c in &corners[3..] {
            let off = dot(sub(*c, corners[0]), n).abs() / length;
            assert!(off < 1e-9 * 20.0, "a face off its plane by {off:e}");
        }
    }
    cut
}

#[test]
fn approximate_trim_writes_planar_panels_closer_to_a_target_whose_edges_are_not_curvature_lines() {
    let dir = TempDir::new().unwrap();
    let (fit, trimmed) = (dir.path().join("fit.json"), dir.path().join("trimmed.obj"));
    let picture = dir.path().join("fit.svg");
    let out = paraboloid(&fit, 8, 100)
        .arg("--trim")
        .arg(&trimmed)
        .arg("--picture")
        .arg(&picture)
        .output()
        .unwrap();
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert!(out.status.success(), "{stdout}");
    assert!(
        stdout.contains("faces trimmed to the target's outline"),
        "{stdout}"
    );
    // The picture draws the cut, the trimmed mesh's edges, in black on the result: one
    // closed loop (the edges of the trimmed mesh, each in one panel, form one).
    let svg = std::fs::read_to_string(&picture).unwrap();
    assert!(svg.contains("trimmed along the black line") && svg.contains("figures trimmed"));
    let cuts: Vec<&str> = svg
        .lines()
        .filter(|l| l.starts_with("<polyline") && l.contains("stroke=\"#000000\""))
        .collect();
    assert_eq!(cuts.len(), 1, "{cuts:?}");
    let ends: Vec<&str> = cuts[0]
        .split('"')
        .nth(1)
        .unwrap()
        .split_whitespace()
        .collect();
    assert!(ends.len() > 8 && ends.first() == ends.last(), "{ends:?}");
    assert!(planar_polygons_cut(&trimmed) > 0, "no face was cut");
    // The trimmed mesh is closer to the paraboloid, by brute force both ways, than the
    // untrimmed fit with the same settings (its boundary, a curvature line, cannot follow
    // the paraboloid's square edges), and monge reads its distances as measured here.
    let size = 19.8997;
    let (to_target, to_mesh) = paraboloid_distances(&trimmed);
    // DESIGN is a trimmed design: `monge generate` writes the same trimmed mesh (all
    // but the header comment), and its `design` is the design before trimming.
    let generated = dir.path().join("generated.obj");
    monge_to("generate", &fit, &generated).assert().success();
    assert_eq!(obj_body(&generated), obj_body(&trimmed));
    let untrimmed = dir.path().join("untrimmed.obj");
    monge_to("generate", design_before_trimming(&fit), &untrimmed)
        .assert()
        .success();
    let (a, b) = paraboloid_distances(&untrimmed);
    assert!(
        to_target.max(to_mesh) < 0.5 * a.max(b),
        "{to_target} {to_mesh} against {a} {b}"
    );
    let read = number_after(&stdout, "result: mesh → target max") * size;
    assert!(
        (read - to_target).abs() < 0.05 * to_target,
        "{read} {to_target}"
    );
}

#[test]
fn approximate_trim_with_patches_writes_the_patches_trimmed() {
    let dir = TempDir::new().unwrap();
    let (fit, trimmed) = (dir.path().join("fit.json"), dir.path().join("trimmed.obj"));
    let out = paraboloid(&fit, 8, 100)
        .arg("--trim")
        .arg(&trimmed)
        .args(["--patches", "2x2"])
        .output()
        .unwrap();
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert!(out.status.success(), "{stdout}");
    assert!(
        stdout.contains("they follow the target closer than one patch"),
        "{stdout}"
    );
    assert!(planar_polygons_cut(&trimmed) > 0, "no face was cut");
    // The trimmed mesh is cut from the patches' mesh: every vertex of it lies on a face
    // of the mesh `monge patches` builds from DESIGN (measured here, by brute force).
    let size = 19.8997;
    let generated = dir.path().join("generated.obj");
    monge_to("generate", &fit, &generated).assert().success();
    assert_eq!(obj_body(&generated), obj_body(&trimmed));
    let whole = dir.path().join("whole.obj");
    monge_to("patches", design_before_trimming(&fit), &whole)
        .assert()
        .success();
    let faces = common::obj_faces(&whole);
    for v in obj_points(&trimmed) {
        let off = faces
            .iter()
            .flat_map(|f| (1..f.len() - 1).map(move |k| to_triangle(v, f[0], f[k], f[k + 1])))
            .fold(f64::INFINITY, f64::min);
        assert!(
            off < 1e-9 * size,
            "a trimmed vertex {off:e} off the patches"
        );
    }
    // monge reads the patches' distances as measured here, both ways.
    let (to_target, to_mesh) = paraboloid_distances(&trimmed);
    let patches = &stdout[stdout.find("4 patches (§4.7):").unwrap()..];
    for (label, truth) in [
        ("mesh → target max", to_target),
        ("target → mesh max", to_mesh),
    ] {
        let read = number_after(patches, label) * size;
        assert!(
            (read - truth).abs() < 0.05 * truth,
            "{label}: {read} {truth}"
        );
    }
}

#[test]
fn approximate_trim_refuses_the_kept_boundary_and_a_target_with_a_hole() {
    let dir = TempDir::new().unwrap();
    let fit = dir.path().join("fit.json");
    paraboloid(&fit, 8, 100)
        .arg("--trim")
        .arg(dir.path().join("t.obj"))
        .arg("--keep-boundary")
        .assert()
        .failure()
        .stderr(predicate::str::contains("cannot be used with"));
    // A ring: its inner edge is not on the outline.
    let ring = dir.path().join("ring.obj");
    let text: String = (0..2000)
        .map(|k| {
            let (r, a) = (2.0 + 2.0 * (k as f64 + 0.5) / 2000.0, k as f64 * 2.399963);
            format!("v {} {} {}\n", r * a.cos(), r * a.sin(), 0.02 * r * r)
        })
        .collect();
    fs::write(&ring, text).unwrap();
    let trimmed = dir.path().join("t.obj");
    refuses(
        monge()
            .arg("approximate")
            .arg(&ring)
            .arg("-o")
            .arg(&fit)
            .arg("--trim")
            .arg(&trimmed),
        &["the target's outline cannot be traced", "ring-shaped"],
        &[&fit, &trimmed],
    );
}

#[test]
fn approximate_to_a_tolerance_on_a_scan_keeps_one_patch_where_only_its_edge_reads_above() {
    // 2 000 random points of a torus patch, a surface with planar curvature lines. One
    // patch comes 2.4e-3 of its size from the torus patch both ways (brute force against
    // the closed form), but its corners read 6.8e-3 beyond the scan's outermost points,
    // which leave the corners bare. Compared by that reading, two patches came nearer
    // (4.3e-3) and were kept, 4.5e-3 from the torus patch.
    let (big, small) = (10.0, 4.0);
    let torus = |u: f64, v: f64| {
        let rho = big + small * v.cos();
        [rho * u.cos(), rho * u.sin(), small * v.sin()]
    };
    let mut uniform = uniform_from(0x9e37_79b9_7f4a_7c15_u64);
    let dir = TempDir::new().unwrap();
    let scan = dir.path().join("torus-scan.obj");
    let points: String = (0..2000)
        .map(|_| {
            let (u, v) = (0.9 * uniform(), -0.6 + 1.5 * uniform());
            let [x, y, z] = torus(u, v);
            format!("v {x} {y} {z}\n")
        })
        .collect();
    fs::write(&scan, points).unwrap();
    // `monge approximate` of the scan into `design`, its exit status and standard output.
    let approximate = |design: &std::path::Path, args: &[&str]| {
        let out = monge()
            .arg("approximate")
            .arg(&scan)
            .arg("-o")
            .arg(design)
            .args(args)
            .output()
            .unwrap();
        (out.status.code(), String::from_utf8(out.stdout).unwrap())
    };
    let design = dir.path().join("fit.json");
    let (status, stdout) = approximate(&design, &["--tolerance", "5e-3"]);
    assert_eq!(status, Some(1), "{stdout}");
    assert!(stdout.contains("result: 1 patch\n"), "{stdout}");
    assert!(stdout.contains("NOT within the tolerance"), "{stdout}");
    assert!(stdout.contains("the target is a scan"), "{stdout}");
    // Each fit's largest distance as far as the scan's points tell its edge, below its
    // full reading.
    let line = stdout.lines().find(|l| l.starts_with("1 patch: ")).unwrap();
    let (read, edge) = line.split_once("edge").unwrap();
    let (read, resolved) = (number_after(read, "("), number_after(edge, "("));
    assert!(resolved < read && resolved <= 5e-3, "{line}");
    assert!(
        stdout.contains("2.5 mean spacings of its points"),
        "{stdout}"
    );
    // The mesh lies on the torus within the tolerance (its distance from the torus's
    // closed form, not monge's reading).
    let mesh = dir.path().join("fit.obj");
    generate_and_check(&design, &mesh);
    let size = number_after(&stdout, "size");
    let across = obj_points(&mesh)
        .iter()
        .map(|[x, y, z]| ((x.hypot(*y) - big).hypot(*z) - small).abs())
        .fold(0.0, f64::max);
    assert!(across <= 5e-3 * size, "{across} of {size}");
    // Four patches are compared with it the same way, and not kept (2.4e-3 of the size
    // from the torus patch both ways against their 4.0e-3, which read nearer). What is
    // tested is the comparison, not the search: a short one (a full one takes half a
    // minute of the suite's processor time).
    let (_, stdout) = approximate(
        &dir.path().join("patches.json"),
        &["--patches", "2x2", "--max-evaluations", "60"],
    );
    assert!(
        stdout.contains("they do not follow the target closer than one patch"),
        "{stdout}"
    );
}

/// An OBJ file's lines but its first (the header comment, which names the command).
fn obj_body(path: &std::path::Path) -> Vec<String> {
    let text = std::fs::read_to_string(path).unwrap();
    text.lines().skip(1).map(str::to_owned).collect()
}

/// The design before trimming of the trimmed design `path` (its key `design`), written
/// beside it as a file of its own.
fn design_before_trimming(path: &std::path::Path) -> std::path::PathBuf {
    let file: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    assert!(file.get("trim").is_some(), "not a trimmed design: {file}");
    let before = path.with_extension("before.json");
    std::fs::write(&before, serde_json::to_string(&file["design"]).unwrap()).unwrap();
    before
}
