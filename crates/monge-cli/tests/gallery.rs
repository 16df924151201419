//! The gallery (docs/gallery/) is up to date: every picture listed in
//! docs/gallery/gallery.txt, rendered again by this build of `monge`, has the
//! bytes of the committed file. Rendering is deterministic on one kind of machine.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The repository root.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// `(output, arguments)` of each line of gallery.txt.
fn gallery() -> Vec<(String, Vec<String>)> {
    let list = std::fs::read_to_string(root().join("docs/gallery/gallery.txt"))
        .expect("docs/gallery/gallery.txt is readable");
    list.lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with('#'))
        .map(|l| {
            let mut words = l.split_whitespace().map(str::to_owned);
            let out = words.next().expect("a non-empty line has a first word");
            (out, words.collect())
        })
        .collect()
}

#[test]
fn gallery_pictures_are_up_to_date() {
    let pictures = gallery();
    assert!(
        pictures.len() >= 6,
        "gallery.txt lists {} pictures",
        pictures.len()
    );
    let dir = tempfile::tempdir().unwrap();
    // One process per picture, run side by side (each is single-threaded and deterministic).
    let stale: Vec<String> = std::thread::scope(|s| {
        let jobs: Vec<_> = pictures
            .iter()
            .map(|(out, args)| {
                let fresh = dir.path().join(out);
                s.spawn(move || {
                    let run = Command::new(env!("CARGO_BIN_EXE_monge"))
                        .current_dir(root())
                        .arg("render")
                        .args(args)
                        .arg("-o")
                        .arg(&fresh)
                        .output()
                        .unwrap();
                    assert!(
                        run.status.success(),
                        "monge render {} failed: {}",
                        args.join(" "),
                        String::from_utf8_lossy(&run.stderr)
                    );
                    let committed = std::fs::read(root().join("docs/gallery").join(out)).ok();
                    (committed != Some(std::fs::read(&fresh).unwrap())).then(|| out.clone())
                })
            })
            .collect();
        jobs.into_iter().filter_map(|j| j.join().unwrap()).collect()
    });
    assert!(
        stale.is_empty(),
        "docs/gallery/ is out of date ({}): run `docs/gallery/make.sh` to refresh it and commit the pictures",
        stale.join(", ")
    );
}

/// `monge render ARGS` from the repository root.
fn render(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_monge"))
        .current_dir(root())
        .arg("render")
        .args(args)
        .output()
        .unwrap()
}

#[test]
fn render_writes_svg_and_refuses_bad_requests_with_status_2() {
    let dir = tempfile::tempdir().unwrap();
    let svg = dir.path().join("view.svg");
    let ok = render(&[
        "examples/fig12-torus.json",
        "--gauss",
        "--size",
        "300x200",
        "-o",
        svg.to_str().unwrap(),
    ]);
    assert!(
        ok.status.success(),
        "{}",
        String::from_utf8_lossy(&ok.stderr)
    );
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.starts_with("<svg") && text.contains(">Gauss map</text>"));

    let jpg = dir.path().join("view.jpg");
    let two = ["examples/fig12-torus.json", "examples/fig2-enneper.json"];
    for (args, needle) in [
        (
            vec![two[0], "-o", jpg.to_str().unwrap()],
            "`.png` or `.svg`",
        ),
        (
            vec![
                two[0],
                two[1],
                "--theta-sweep=0,30",
                "-o",
                svg.to_str().unwrap(),
            ],
            "exactly one DESIGN",
        ),
        (
            vec![
                "examples/fig11-helix.developable.json",
                "--theta-sweep=0",
                "-o",
                svg.to_str().unwrap(),
            ],
            "developable",
        ),
    ] {
        let out = render(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(
            stderr.starts_with("error: ") && stderr.contains(needle),
            "{stderr}"
        );
    }
    assert!(!jpg.exists());
}
