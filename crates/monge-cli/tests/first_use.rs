//! What a new user meets first: outputs into missing directories, outputs that
//! are inputs, files of the wrong kind, format mismatches, help footers.

use std::fs;
use std::path::{Path, PathBuf};

use predicates::prelude::*;
use tempfile::TempDir;

mod common;
use common::{example, monge};

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

/// `args` with `OUT.ext` replaced by `out` + `.ext`, run in `dir`.
fn run_with_output(dir: &Path, args: &[String], out: &str) -> assert_cmd::assert::Assert {
    let args: Vec<String> = args.iter().map(|a| a.replace("OUT", out)).collect();
    monge().current_dir(dir).args(&args).assert()
}

#[test]
fn every_command_refuses_a_missing_output_directory_plainly() {
    let dir = TempDir::new().unwrap();
    for (name, args) in writers() {
        let out = args.iter().find(|a| a.starts_with("OUT")).unwrap();
        let path = out.replace("OUT", "missing/x");
        let expected = format!(
            "error: cannot write `{path}`: the directory `missing` does not exist (create it \
             first, or choose another -o)\n"
        );
        run_with_output(dir.path(), &args, "missing/x")
            .code(2)
            .stderr(predicate::eq(expected.as_str()).name(name));
        assert!(!dir.path().join("missing").exists(), "{name}");
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
        monge()
            .current_dir(dir.path())
            .args(&args)
            .assert()
            .code(2)
            .stderr(
                predicate::eq(format!(
                    "error: `./input.{ext}` is an input of this command and cannot also be its \
                     output: choose another -o (monge never writes over its input)\n"
                ))
                .name(name),
            );
        assert_eq!(fs::read(&copy).unwrap(), before, "{name}: input untouched");
    }
}

/// `monge ARGS…` fails with exit status 2 and exactly `expected` on stderr.
fn fails_with(args: &[&str], file: &Path, expected: &str) {
    monge()
        .args(&args[..1])
        .arg(file)
        .args(&args[1..])
        .assert()
        .code(2)
        .stderr(predicate::eq(format!(
            "error: {} is {expected}\n",
            file.display()
        )));
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
    monge()
        .arg("generate")
        .arg(&design)
        .arg("-o")
        .arg(&mesh)
        .assert()
        .success();
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
