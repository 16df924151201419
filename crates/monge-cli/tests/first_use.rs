//! What a new user meets first: outputs into missing directories, outputs that
//! are inputs, files of the wrong kind, format mismatches, help footers.

use std::fs;
use std::path::{Path, PathBuf};

use predicates::prelude::*;
use tempfile::TempDir;

use crate::common;
use common::{example, monge, monge_to, refuses, write};

/// Every command that writes a file, with its input file and `OUT` in place of
/// the output path.
fn writers() -> Vec<(&'static str, Vec<String>)> {
    let ex = |name: &str| example(name).display().to_string();
    let design = ex("fig13-freeform.json");
    let cmd = |args: &[&str]| args.iter().map(|a| (*a).to_owned()).collect::<Vec<_>>();
    vec![
        ("generate", cmd(&["generate", &design, "-o", "OUT.obj"])),
        ("smooth", cmd(&["smooth", &design, "-o", "OUT.json"])),
        ("render", cmd(&["render", &design, "-o", "OUT.png"])),
        (
            "patches",
            cmd(&[
                "patches",
                &ex("fig20-piecewise.patches.json"),
                "-o",
                "OUT.obj",
            ]),
        ),
        (
            "fit",
            cmd(&[
                "fit",
                &ex("fig21-hippohaus-fit.patches.json"),
                "-o",
                "OUT.json",
            ]),
        ),
        (
            "scan",
            cmd(&["scan", &design, "--theta", "0:10:10", "-o", "OUT.csv"]),
        ),
        (
            "scan --plot",
            cmd(&[
                "scan", &design, "--theta", "0:10:10", "-o", "x.csv", "--plot", "OUT.svg",
            ]),
        ),
        (
            "optimise-panels",
            cmd(&[
                "optimise-panels",
                &ex("fig22-panels.json"),
                "-o",
                "OUT.json",
            ]),
        ),
        (
            "align",
            cmd(&["align", &ex("fig17.planes.json"), "-o", "OUT.json"]),
        ),
    ]
}

/// `monge` in `dir` with `args`, `OUT.ext` in them replaced by `out` + `.ext`.
fn with_output(dir: &Path, args: &[String], out: &str) -> assert_cmd::Command {
    let args: Vec<String> = args.iter().map(|a| a.replace("OUT", out)).collect();
    let mut cmd = monge();
    cmd.current_dir(dir).args(&args);
    cmd
}

#[test]
fn every_command_refuses_a_missing_output_directory_plainly() {
    let dir = TempDir::new().unwrap();
    // fabricate's OUT is a directory: it makes that one, not the directories above it.
    let fabricate = [
        "fabricate",
        example("fig13-freeform.json").to_str().unwrap(),
        "-o",
        "OUT",
    ]
    .map(str::to_owned)
    .to_vec();
    for (name, args) in writers().into_iter().chain([("fabricate", fabricate)]) {
        let out = args.iter().find(|a| a.starts_with("OUT")).unwrap();
        let path = out.replace("OUT", "missing/x");
        let expected = format!(
            "error: cannot write `{path}`: the directory `missing` does not exist (create it \
             first, or choose another output path)\n"
        );
        let stderr = refuses(
            &mut with_output(dir.path(), &args, "missing/x"),
            &[],
            &[&dir.path().join("missing")],
        );
        assert_eq!(stderr, expected, "{name}");
    }
    assert_eq!(
        fs::read_dir(dir.path()).unwrap().count(),
        0,
        "nothing written"
    );
}

#[test]
fn every_command_refuses_to_write_over_its_input() {
    let dir = TempDir::new().unwrap();
    for (name, args) in writers() {
        // The input, copied into the directory and given again (differently spelled) as OUT.
        let input = PathBuf::from(&args[1]);
        let ext = input.extension().unwrap().to_str().unwrap();
        let copy = dir.path().join(format!("input.{ext}"));
        fs::copy(&input, &copy).unwrap();
        let before = fs::read(&copy).unwrap();
        let mut args = args.clone();
        args[1] = "input.".to_owned() + ext;
        let out = args.iter().position(|a| a.starts_with("OUT")).unwrap();
        args[out] = format!("./input.{ext}");
        let stderr = refuses(monge().current_dir(dir.path()).args(&args), &[], &[]);
        assert_eq!(
            stderr,
            format!(
                "error: `./input.{ext}` is an input of this command and cannot also be its \
                 output: choose another output path (monge never writes over its input)\n"
            ),
            "{name}"
        );
        assert_eq!(fs::read(&copy).unwrap(), before, "{name}: input untouched");
    }
}

/// `monge ARGS…` fails with exit status 2 and exactly `expected` on stderr.
fn fails_with(args: &[&str], file: &Path, expected: &str) {
    let stderr = refuses(
        monge().args(&args[..1]).arg(file).args(&args[1..]),
        &[],
        &[],
    );
    assert_eq!(stderr, format!("error: {} is {expected}\n", file.display()));
}

#[test]
fn a_file_of_the_wrong_kind_names_the_command_that_takes_it() {
    let dir = TempDir::new().unwrap();
    let patches = example("fig20-piecewise.patches.json");
    let planes = example("fig17.planes.json");
    let developable = example("fig11-helix.developable.json");
    let design = example("fig13-freeform.json");
    let design_toml = example("fig14-family.toml");
    let mesh = dir.path().join("mesh.json");
    monge_to("generate", &design, &mesh).assert().success();
    let out = dir.path().join("out.json").display().to_string();
    let png = dir.path().join("out.png").display().to_string();
    let to_patches = "a multi-patch design (§4.7), not a design (two guides and θ): use `monge \
                      patches` (or `monge fit` when it has a `fit` key)";
    let to_align = "a planes file (§4.5), not a design (two guides and θ): use `monge align`";
    let to_generate = "`monge generate` (or `info`, `smooth`, `render`, `fabricate`, `scan`, \
                       `optimise-panels`, `explore`)";
    let design_not =
        |what: &str| format!("a design (two guides and θ), not {what}: use {to_generate}");
    for command in [
        "info",
        "generate",
        "render",
        "smooth",
        "scan",
        "optimise-panels",
        "fabricate",
    ] {
        let args: Vec<&str> = match command {
            "info" => vec!["info"],
            "scan" => vec!["scan", "--theta", "0:1:1", "-o", &out],
            "render" => vec!["render", "-o", &png],
            _ => vec![command, "-o", &out],
        };
        fails_with(&args, &patches, to_patches);
        fails_with(&args, &planes, to_align);
    }
    fails_with(
        &["smooth", "-o", &out],
        &developable,
        "a developable design (§3.3), not a design (two guides and θ): use `monge generate` (or \
         `info`, `render`)",
    );
    fails_with(
        &["generate", "-o", &out],
        &mesh,
        "a mesh, not a design (two guides and θ): use `monge check` (or `monge smooth --mesh`)",
    );
    fails_with(&["check"], &design, &design_not("a mesh"));
    fails_with(
        &["patches", "-o", &out],
        &design,
        &design_not("a multi-patch design (§4.7)"),
    );
    fails_with(
        &["patches", "-o", &out],
        &design_toml,
        &design_not("a multi-patch design (§4.7)"),
    );
    fails_with(
        &["fit", "-o", &out],
        &design,
        &design_not("a multi-patch design (§4.7)"),
    );
    fails_with(
        &["align", "-o", &out],
        &design,
        &design_not("a planes file (§4.5)"),
    );
    fails_with(
        &["align", "-o", &out],
        &patches,
        "a multi-patch design (§4.7), not a planes file (§4.5): use `monge patches` (or `monge \
         fit` when it has a `fit` key)",
    );
    assert!(!Path::new(&out).exists());
}

/// The exit-status footer of every help text.
const EXIT: &str = "Exit status: 0 success; 1 `monge check` found a metric above --tol; 2 any \
error (unreadable, malformed or invalid design or mesh, unwritable output, bad arguments), \
reported on stderr as `error: <message>`.";

#[test]
fn every_help_ends_with_the_exit_status_footer_once() {
    let top = monge().arg("--help").output().unwrap();
    let top = String::from_utf8(top.stdout).unwrap();
    let commands: Vec<&str> = top
        .split("Commands:\n")
        .nth(1)
        .unwrap()
        .lines()
        .take_while(|l| l.starts_with("  "))
        .filter_map(|l| l.split_whitespace().next())
        .filter(|c| *c != "help")
        .collect();
    assert_eq!(commands.len(), 14, "{commands:?}");
    let helps = std::iter::once(top.clone()).chain(commands.iter().flat_map(|c| {
        ["--help", "-h"].map(|flag| {
            let out = monge().args([c, &flag]).output().unwrap();
            assert!(out.status.success(), "{c} {flag}");
            String::from_utf8(out.stdout).unwrap()
        })
    }));
    for (k, help) in helps.enumerate() {
        // clap wraps long lines: compare with the whitespace normalised.
        let flat = help.split_whitespace().collect::<Vec<_>>().join(" ");
        assert_eq!(flat.matches(EXIT).count(), 1, "help {k}:\n{help}");
        assert!(
            flat.ends_with(EXIT),
            "help {k} does not end with the footer:\n{help}"
        );
    }
}

#[test]
fn the_readme_smooth_usage_on_a_mesh_runs() {
    let readme =
        fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../README.md")).unwrap();
    let usage = readme
        .split('`')
        .find(|s| s.starts_with("monge smooth MESH"))
        .expect("README documents `monge smooth MESH …`");
    assert_eq!(
        usage,
        "monge smooth MESH --mesh -o OUT [--frame t1x,t1y,t1z,t2x,t2y,t2z]"
    );
    let dir = TempDir::new().unwrap();
    let mesh = dir.path().join("m.json");
    monge_to("generate", example("fig12-dupin-theta30.json"), &mesh)
        .assert()
        .success();
    let out = dir.path().join("net.obj");
    for frame in [None, Some("1,0,0,0,1,0")] {
        let args: Vec<String> = usage
            .split_whitespace()
            .skip(1)
            .filter_map(|word| match word {
                "MESH" => Some(mesh.display().to_string()),
                "OUT" => Some(out.display().to_string()),
                "[--frame" => frame.map(|_| "--frame".to_owned()),
                "t1x,t1y,t1z,t2x,t2y,t2z]" => frame.map(str::to_owned),
                w => Some(w.to_owned()),
            })
            .collect();
        monge().args(&args).assert().success();
        monge().arg("check").arg(&out).assert().success();
    }
}

#[test]
fn check_offers_only_the_formats_it_reads() {
    let help = monge().args(["check", "-h"]).output().unwrap();
    let help = String::from_utf8(help.stdout).unwrap();
    assert!(help.contains("[possible values: obj, ply, json]"), "{help}");
    let help = monge().args(["check", "--help"]).output().unwrap();
    let help = String::from_utf8(help.stdout).unwrap();
    assert!(!help.contains("glb") && help.contains("- json:"), "{help}");
    refuses(
        monge().args(["check", "-", "--format", "glb"]),
        &["[possible values: obj, ply, json]"],
        &[],
    );
}

#[test]
fn a_format_that_contradicts_the_extension_is_refused() {
    let dir = TempDir::new().unwrap();
    for (command, design) in [
        ("generate", "fig13-freeform.json"),
        ("patches", "fig20-piecewise.patches.json"),
    ] {
        let stderr = refuses(
            monge()
                .current_dir(dir.path())
                .arg(command)
                .arg(example(design))
                .args(["--format", "ply", "-o", "x.obj"]),
            &[],
            &[&dir.path().join("x.obj")],
        );
        assert_eq!(
            stderr,
            "error: --format ply but OUT `x.obj` ends in `.obj`: name it `.ply`, or leave \
             --format out\n"
        );
        // Agreeing, or an extension that names no format: written in --format.
        for out in ["x.ply", "x.mesh"] {
            monge()
                .current_dir(dir.path())
                .arg(command)
                .arg(example(design))
                .args(["--format", "ply", "-o", out])
                .assert()
                .success();
            let text = fs::read_to_string(dir.path().join(out)).unwrap();
            assert!(text.starts_with("ply\n"), "{command} {out}");
        }
    }
}

#[test]
fn small_messages_say_the_limit_and_one_list() {
    let dir = TempDir::new().unwrap();
    refuses(
        monge()
            .current_dir(dir.path())
            .arg("render")
            .arg(example("fig13-freeform.json"))
            .args(["--size", "20000x20000", "-o", "x.png"]),
        &["a side of 20000 pixels is outside 1 to 16384"],
        &[],
    );
    let stderr = refuses(
        monge()
            .current_dir(dir.path())
            .arg("smooth")
            .arg(example("fig13-freeform.json"))
            .args(["-o", "s.stl"]),
        &[],
        &[&dir.path().join("s.stl")],
    );
    assert_eq!(
        stderr,
        "error: cannot tell what to write to `s.stl`: monge smooth writes `.json` (patches \
         and arcs), `.igs` or `.iges` (the exact NURBS surface), or `.obj`, `.ply` or `.glb` \
         (a dense mesh)\n"
    );
    let text = fs::read_to_string(example("fig14-family.toml")).unwrap();
    let (line, _) = text
        .lines()
        .enumerate()
        .find(|(_, l)| l.starts_with("theta_deg"))
        .unwrap();
    let lines: Vec<&str> = text
        .lines()
        .enumerate()
        .map(|(k, l)| if k == line { "theta_deg = \"20\"" } else { l })
        .collect();
    let toml = write(&dir, "d.toml", &lines.join("\n"));
    refuses(
        monge().arg("info").arg(&toml),
        &[&format!(
            "{}:{}:13: theta_deg must be a number, got the string \"20\"\n",
            toml.display(),
            line + 1
        )],
        &[],
    );
    assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 1, "only d.toml");
}

#[test]
fn an_admissible_range_from_zero_is_one_interval() {
    // Arbitrary case (§3.2) with guide_v's plane orthogonal to t_u (c_v = 0) and
    // guide_u's plane tilted by 30° (c_u = sin 30°): |θ| ≤ 180° − 2·atan(1/2).
    let (s, c) = (0.5_f64, 3f64.sqrt() / 2.0);
    let u: Vec<[f64; 3]> = (0..9)
        .map(|k| {
            let t = f64::from(k) / 4.0;
            [t, -s * 0.3 * t * t, c * 0.3 * t * t]
        })
        .collect();
    let v: Vec<[f64; 3]> = (0..9)
        .map(|k| {
            let t = f64::from(k) / 4.0;
            [0.0, t, 0.2 * t * t]
        })
        .collect();
    let design = serde_json::json!({
        "theta_deg": 100,
        "guide_u": {"points": u, "tangent": [1, 0, 0]},
        "guide_v": {"points": v, "tangent": [0, 1, 0]},
    });
    let dir = TempDir::new().unwrap();
    let path = write(&dir, "zero.json", &design.to_string());
    let max = 180.0 - 2.0 * 0.5f64.atan().to_degrees();
    assert_eq!(format!("{max:.2}"), "126.87");
    monge()
        .arg("info")
        .arg(&path)
        .assert()
        .success()
        .stdout(predicate::str::contains(
            "admissible θ: |θ| ≤ 126.87°, i.e. θ in [−126.87°, 126.87°]\n",
        ));
}
