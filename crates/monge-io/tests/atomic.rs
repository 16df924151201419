//! Atomic writes: a failure never leaves a half-written or empty file.

use std::io;
use std::path::Path;

use monge_io::{check_output, write_atomic, write_output, IoError};

fn entries(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn failing_closure_leaves_no_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("out.obj");
    let err = write_atomic(&path, |w| {
        w.write_all(&[b'x'; 100_000])?; // more than the buffer: reaches the temporary file
        Err(io::Error::other("generator failed"))
    })
    .unwrap_err();
    assert!(matches!(err, IoError::Write { .. }), "{err:?}");
    assert_eq!(
        err.to_string(),
        format!("cannot write `{}`: generator failed", path.display())
    );
    assert!(!path.exists());
    assert!(
        entries(dir.path()).is_empty(),
        "temporary file left: {:?}",
        entries(dir.path())
    );
}

#[test]
fn files_larger_than_the_writeback_step_come_out_whole() {
    // Over 8 MiB the staged file is handed to the disk as it grows (Linux):
    // pieces of every size, from one byte to 3 MiB, give the same bytes, and
    // a failure after that still leaves nothing behind.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("big.bin");
    let bytes: Vec<u8> = (0..20_000_003u32)
        .map(|k| (k.wrapping_mul(2_654_435_761) >> 24) as u8)
        .collect();
    let mut sizes = [1, 4096, 70_000, 3 << 20, 65_536, 7].into_iter().cycle();
    write_atomic(&path, |w| {
        let mut rest = &bytes[..];
        while !rest.is_empty() {
            let (piece, tail) = rest.split_at(sizes.next().unwrap().min(rest.len()));
            w.write_all(piece)?;
            rest = tail;
        }
        Ok(())
    })
    .unwrap();
    assert!(std::fs::read(&path).unwrap() == bytes, "the file differs");
    let failed = dir.path().join("failed.bin");
    write_atomic(&failed, |w| {
        w.write_all(&bytes)?;
        Err(io::Error::other("stopped after 20 MB"))
    })
    .unwrap_err();
    assert_eq!(entries(dir.path()), ["big.bin"]);
}

#[test]
fn failing_closure_leaves_an_existing_file_untouched() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("out.json");
    std::fs::write(&path, "previous").unwrap();
    let err = write_atomic(&path, |w| {
        w.write_all(b"partial")?;
        Err(io::Error::other("boom"))
    });
    assert!(err.is_err());
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "previous");
    assert_eq!(entries(dir.path()), ["out.json"]);

    write_atomic(&path, |w| w.write_all(b"new")).unwrap();
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "new");
    assert_eq!(entries(dir.path()), ["out.json"]);
}

#[test]
fn missing_directory_is_said_plainly() {
    let path = Path::new("/nonexistent-monge-dir/out.ply");
    let expected = "cannot write `/nonexistent-monge-dir/out.ply`: the directory \
                    `/nonexistent-monge-dir` does not exist (create it first, or choose another output path)";
    let err = write_atomic(path, |w| w.write_all(b"x")).unwrap_err();
    assert!(matches!(err, IoError::NoDirectory { .. }), "{err:?}");
    assert_eq!(err.to_string(), expected);
    let err = check_output(path, &[]).unwrap_err();
    assert_eq!(err.to_string(), expected);
}

#[test]
fn an_output_that_is_an_input_is_refused_however_it_is_spelled() {
    let dir = tempfile::tempdir().unwrap();
    let sub = dir.path().join("sub");
    std::fs::create_dir(&sub).unwrap();
    let input = dir.path().join("d.json");
    std::fs::write(&input, "{}").unwrap();
    for same in [
        input.clone(),
        dir.path().join(".").join("d.json"),
        sub.join("..").join("d.json"),
    ] {
        let err = check_output(&same, &[Path::new("-"), &input]).unwrap_err();
        assert!(matches!(err, IoError::OutputIsInput { .. }), "{err:?}");
        assert!(
            err.to_string().contains("choose another output path"),
            "{err}"
        );
    }
    #[cfg(unix)]
    {
        let link = dir.path().join("link.json");
        std::os::unix::fs::symlink(&input, &link).unwrap();
        assert!(check_output(&input, &[&link]).is_err());
    }
    // Other files, new files, standard output.
    std::fs::write(dir.path().join("other.json"), "{}").unwrap();
    for other in ["other.json", "new.obj", "d.json.obj"] {
        check_output(&dir.path().join(other), &[&input]).unwrap();
    }
    check_output(Path::new("-"), &[Path::new("-")]).unwrap();
    assert_eq!(std::fs::read_to_string(&input).unwrap(), "{}");
}

#[test]
fn relative_paths_without_a_directory_work() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("rel.txt");
    // write_output on a real path is write_atomic.
    write_output(&path, |w| w.write_all(b"ok")).unwrap();
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "ok");
    let err = write_atomic(Path::new(""), |w| w.write_all(b"x")).unwrap_err();
    assert!(matches!(err, IoError::Write { .. }), "{err:?}");
}

#[cfg(unix)]
#[test]
fn new_files_get_ordinary_permissions() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("perm.txt");
    write_atomic(&path, |w| w.write_all(b"x")).unwrap();
    let mode = |p: &Path| std::fs::metadata(p).unwrap().permissions().mode() & 0o777;
    // The same as `File::create` (0o666 less the umask), not tempfile's 0o600.
    let reference = dir.path().join("reference.txt");
    std::fs::write(&reference, "x").unwrap();
    assert_eq!(mode(&path), mode(&reference));
}

#[test]
fn the_next_write_removes_what_a_killed_write_left_an_hour_ago() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("out.obj");
    // Leftovers of a write killed between link and rename (or of a named
    // temporary file), one stale and one fresh, and files that only look alike.
    let names = [
        ".out.obj.Ab3dE9.tmp",
        ".out.obj.Zz9yX1.tmp",
        ".out.obj.toolong7.tmp",
        ".other.obj.Ab3dE9.tmp",
        "out.obj.Ab3dE9.tmp",
    ];
    let hours_ago = std::time::SystemTime::now() - monge_io::STALE * 2;
    for (k, name) in names.iter().enumerate() {
        let file = std::fs::File::create(dir.path().join(name)).unwrap();
        if k != 1 {
            file.set_modified(hours_ago).unwrap();
        }
    }
    write_atomic(&path, |w| w.write_all(b"new\n")).unwrap();
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "new\n");
    assert_eq!(
        entries(dir.path()),
        [
            ".other.obj.Ab3dE9.tmp",
            ".out.obj.Zz9yX1.tmp",
            ".out.obj.toolong7.tmp",
            "out.obj",
            "out.obj.Ab3dE9.tmp",
        ],
        "only the stale leftover of out.obj is removed"
    );
}

/// Files written as one: an error in any leaves every path as it was, and a
/// path given twice is refused (`scan -o k.csv --plot k.csv` once wrote the SVG
/// over the CSV).
#[test]
fn outputs_change_together_or_not_at_all() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("a.csv"), dir.path().join("b.svg"));
    std::fs::write(&a, "old a").unwrap();
    std::fs::write(&b, "old b").unwrap();
    let mut out = monge_io::Outputs::new();
    out.write(&a, |w| w.write_all(b"new a")).unwrap();
    let e = out
        .write(&dir.path().join(".").join("a.csv"), |w| {
            w.write_all(b"again")
        })
        .unwrap_err();
    assert!(matches!(e, IoError::SameOutput { .. }), "{e:?}");
    assert!(e.to_string().contains("written twice"), "{e}");
    std::fs::create_dir(dir.path().join("sub")).unwrap();
    let e = out
        .write(&dir.path().join("sub"), |w| w.write_all(b"x"))
        .unwrap_err();
    assert!(matches!(e, IoError::Write { .. }), "{e:?}");
    drop(out);
    assert_eq!(std::fs::read_to_string(&a).unwrap(), "old a");
    assert_eq!(entries(dir.path()), ["a.csv", "b.svg", "sub"]);
    let mut out = monge_io::Outputs::new();
    out.write(&a, |w| w.write_all(b"new a")).unwrap();
    out.write(&b, |w| w.write_all(b"new b")).unwrap();
    assert_eq!(std::fs::read_to_string(&a).unwrap(), "old a");
    out.commit().unwrap();
    assert_eq!(std::fs::read_to_string(&a).unwrap(), "new a");
    assert_eq!(std::fs::read_to_string(&b).unwrap(), "new b");
    assert_eq!(entries(dir.path()), ["a.csv", "b.svg", "sub"]);
}
