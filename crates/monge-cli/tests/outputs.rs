//! A command's output files change together or not at all, and none is its input:
//! each once went wrong (an offset, a fabrication file, a plot or a picture that
//! failed after the files before it had replaced their paths).

use std::fs;
use std::path::Path;

use tempfile::TempDir;

use crate::common;
use common::{example, monge, refuses};

/// Every file of `dir` with its content, sorted by name (directories as `<dir>`).
fn snapshot(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut files: Vec<(String, Vec<u8>)> = fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            let name = e.file_name().to_string_lossy().into_owned();
            let content = if e.path().is_dir() {
                b"<dir>".to_vec()
            } else {
                fs::read(e.path()).unwrap()
            };
            (name, content)
        })
        .collect();
    files.sort();
    files
}

#[test]
fn generate_with_offsets_changes_no_file_when_one_offset_fails() {
    let dir = TempDir::new().unwrap();
    let d = dir.path();
    fs::write(d.join("m.obj"), "previous").unwrap();
    fs::create_dir(d.join("m.offset+1.obj")).unwrap();
    let generate = |offsets: [&str; 2], says: &str| {
        let before = snapshot(d);
        refuses(
            monge()
                .arg("generate")
                .arg(example("fig13-freeform.json"))
                .arg("-o")
                .arg(d.join("m.obj"))
                .args(["--offset", offsets[0], "--offset", offsets[1]]),
            &[says],
            &[],
        );
        assert_eq!(snapshot(d), before);
    };
    generate(["0.5", "1"], "is a directory");
    // A name the file system refuses (309 digits) fails before any file moves.
    fs::remove_dir(d.join("m.offset+1.obj")).unwrap();
    generate(["0.5", "1e308"], "too long");
}

#[test]
fn generate_never_writes_an_offset_over_its_design() {
    let dir = TempDir::new().unwrap();
    let design = dir.path().join("m.offset+1.json");
    fs::copy(example("fig13-freeform.json"), &design).unwrap();
    let before = snapshot(dir.path());
    refuses(
        monge()
            .arg("generate")
            .arg(&design)
            .arg("-o")
            .arg(dir.path().join("m.json"))
            .args(["--offset", "1"]),
        &["is an input of this command"],
        &[],
    );
    assert_eq!(snapshot(dir.path()), before);
}

#[test]
fn fabricate_changes_no_file_when_one_fails_and_never_writes_over_its_design() {
    let dir = TempDir::new().unwrap();
    let out = dir.path().join("F");
    fs::create_dir(&out).unwrap();
    fs::write(out.join("panels.csv"), "previous").unwrap();
    fs::create_dir(out.join("nodes.csv")).unwrap();
    let before = snapshot(&out);
    refuses(
        monge()
            .arg("fabricate")
            .arg(example("fig25-biarc.json"))
            .arg("-o")
            .arg(&out),
        &["nodes.csv", "directory"],
        &[],
    );
    assert_eq!(snapshot(&out), before);
    let design = out.join("schedule.json");
    fs::copy(example("fig25-biarc.json"), &design).unwrap();
    let before = snapshot(&out);
    refuses(
        monge().arg("fabricate").arg(&design).arg("-o").arg(&out),
        &["is an input of this command"],
        &[],
    );
    assert_eq!(snapshot(&out), before);
}

#[test]
fn scan_writes_its_table_and_plot_together() {
    let dir = TempDir::new().unwrap();
    let d = dir.path();
    fs::write(d.join("k.csv"), "previous").unwrap();
    fs::create_dir(d.join("plot.svg")).unwrap();
    let scan = |csv: &str, svg: &str| {
        let mut cmd = monge();
        cmd.arg("scan")
            .arg(example("fig14-family.toml"))
            .args(["--theta", "0:10:1", "-o"])
            .arg(d.join(csv))
            .arg("--plot")
            .arg(d.join(svg));
        cmd
    };
    let before = snapshot(d);
    refuses(&mut scan("k.csv", "plot.svg"), &["is a directory"], &[]);
    assert_eq!(snapshot(d), before);
    refuses(&mut scan("k.csv", "k.csv"), &["written twice"], &[]);
    assert_eq!(snapshot(d), before);
}

#[test]
fn approximate_never_writes_its_trimmed_mesh_over_its_target() {
    // The trimmed mesh is an output as -o is: the message names no option.
    let dir = TempDir::new().unwrap();
    let target = dir.path().join("roof.obj");
    fs::copy(example("targets/paraboloid.obj"), &target).unwrap();
    let before = snapshot(dir.path());
    let stderr = refuses(
        monge()
            .arg("approximate")
            .arg(&target)
            .arg("-o")
            .arg(dir.path().join("fit.json"))
            .arg("--trim")
            .arg(&target),
        &["is an input of this command", "choose another output path"],
        &[],
    );
    assert!(!stderr.contains("-o"), "{stderr}");
    assert_eq!(snapshot(dir.path()), before);
}
