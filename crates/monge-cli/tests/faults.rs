//! Faults survived (Linux): `kill -9` while writing, a file-size limit
//! (`RLIMIT_FSIZE`) and a full disk (a tiny tmpfs) while writing, a design
//! that ends early while read.
#![cfg(target_os = "linux")]

use crate::common;

use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Duration;

/// The torus of Figure 12 with 400 × 400 samples: a 28 MB OBJ, written in
/// about a second and a half by the debug binary.
fn big_design(dir: &Path) -> PathBuf {
    let text = std::fs::read_to_string(common::example("fig12-torus.json")).unwrap();
    let big = text.replace("\"samples\": 41", "\"samples\": 400");
    let big = big.replace("\"samples\": 33", "\"samples\": 400");
    assert_ne!(big, text);
    let path = dir.join("big.json");
    std::fs::write(&path, big).unwrap();
    path
}

/// The names in `dir`, sorted.
fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// `monge generate DESIGN -o OUT` as a plain process (to kill or limit it).
fn generate(design: &Path, out: &Path) -> Command {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_monge"));
    cmd.arg("generate").arg(design).arg("-o").arg(out);
    cmd
}

/// How many bytes process `pid` has written to a file open in `dir` (its
/// position in it, from /proc), if it has one open for writing.
fn written_in(pid: u32, dir: &Path) -> Option<u64> {
    let fds = std::fs::read_dir(format!("/proc/{pid}/fd")).ok()?;
    fds.filter_map(|fd| {
        let fd = fd.ok()?;
        let target = std::fs::read_link(fd.path()).ok()?;
        if !target.starts_with(dir) {
            return None;
        }
        let info = std::fs::read_to_string(format!(
            "/proc/{pid}/fdinfo/{}",
            fd.file_name().to_string_lossy()
        ))
        .ok()?;
        let flags = info.lines().find_map(|l| l.strip_prefix("flags:"))?;
        let flags = u32::from_str_radix(flags.trim(), 8).ok()?;
        let writing = flags & 0o3 != 0; // O_WRONLY or O_RDWR
        let pos = info.lines().find_map(|l| l.strip_prefix("pos:"))?;
        writing.then(|| pos.trim().parse().ok())?
    })
    .max()
}

#[test]
fn kill_9_while_writing_leaves_the_previous_file_and_nothing_else() {
    let dir = tempfile::tempdir().unwrap();
    let dir_path = dir.path().canonicalize().unwrap();
    let design = big_design(&dir_path);
    let out = dir_path.join("big.obj");
    let previous = b"# the previous file\n".repeat(1000);
    std::fs::write(&out, &previous).unwrap();
    let before = listing(&dir_path);
    // Killed at the first bytes, after 1 MB and after 10 MB of the 28 MB.
    for at in [1, 1 << 20, 10 << 20] {
        let mut child = generate(&design, &out)
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        let mut written = None;
        while child.try_wait().unwrap().is_none() {
            written = written_in(child.id(), &dir_path).filter(|&n| n >= at);
            if written.is_some() {
                break;
            }
            std::thread::sleep(Duration::from_millis(1));
        }
        child.kill().unwrap(); // SIGKILL
        let status = child.wait().unwrap();
        assert!(
            written.is_some(),
            "monge ended ({status}) before writing {at} bytes: make the design bigger"
        );
        assert_eq!(
            std::os::unix::process::ExitStatusExt::signal(&status),
            Some(libc::SIGKILL)
        );
        assert_eq!(listing(&dir_path), before, "killed after {written:?} bytes");
        assert!(
            std::fs::read(&out).unwrap() == previous,
            "killed after {written:?} bytes"
        );
    }
}

/// Runs `cmd` with a file-size limit of `bytes` and SIGXFSZ ignored, so that
/// a write beyond it fails with `EFBIG` instead of killing the process.
fn with_file_size_limit(cmd: &mut Command, bytes: u64) -> &mut Command {
    // SAFETY: between fork and exec the closure calls only `signal` and
    // `setrlimit`, both async-signal-safe, and allocates nothing.
    unsafe {
        cmd.pre_exec(move || {
            libc::signal(libc::SIGXFSZ, libc::SIG_IGN);
            let limit = libc::rlimit {
                rlim_cur: bytes,
                rlim_max: bytes,
            };
            if libc::setrlimit(libc::RLIMIT_FSIZE, &limit) == 0 {
                Ok(())
            } else {
                Err(std::io::Error::last_os_error())
            }
        })
    }
}

#[test]
fn a_file_size_limit_is_a_clear_error_and_leaves_no_file() {
    let dir = tempfile::tempdir().unwrap();
    let design = big_design(dir.path());
    let out = dir.path().join("big.obj");
    let output = with_file_size_limit(&mut generate(&design, &out), 1 << 20)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    let expected = format!(
        "cannot write `{}`: the file system refused to write more: File too large (os error 27); \
         free some space (or raise the quota or the file-size limit, `ulimit -f`) or choose another output path",
        out.display()
    );
    assert!(stderr.contains(&expected), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(listing(dir.path()), ["big.json"]);
}

#[test]
fn a_file_size_limit_leaves_the_previous_file() {
    let dir = tempfile::tempdir().unwrap();
    let design = big_design(dir.path());
    let out = dir.path().join("big.obj");
    std::fs::write(&out, "previous\n").unwrap();
    let output = with_file_size_limit(&mut generate(&design, &out), 1 << 20)
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(2));
    assert_eq!(listing(dir.path()), ["big.json", "big.obj"]);
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "previous\n");
}

#[test]
fn a_design_that_ends_early_is_a_clear_error() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("design.json");
    let made = Command::new("mkfifo").arg(&fifo).status().unwrap();
    assert!(made.success());
    let text = std::fs::read_to_string(common::example("fig12-torus.json")).unwrap();
    let half = text[..text.len() / 2].to_owned();
    let writer_path = fifo.clone();
    // The writer sends half of the design and closes the pipe: the reader
    // sees the end of the file in the middle of it.
    let writer = std::thread::spawn(move || std::fs::write(writer_path, half).unwrap());
    let out = dir.path().join("out.obj");
    let output = generate(&fifo, &out).output().unwrap();
    writer.join().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains(&format!("{}:", fifo.display())), "{stderr}");
    assert!(stderr.contains("EOF while parsing"), "{stderr}");
    assert!(!out.exists());
}

/// What `sh -c SCRIPT` with `args` printed in a private mount namespace
/// (`unshare -m`), or `None` if mounting is not permitted here (the script
/// exits with status 99 when its `mount` fails).
fn in_mount_namespace(script: &str, args: &[&Path]) -> Option<std::process::Output> {
    let output = Command::new("unshare")
        .args(["-m", "sh", "-c", script, "sh"])
        .args(args)
        .output()
        .ok()?;
    (output.status.code() != Some(99)).then_some(output)
}

#[test]
fn a_full_disk_is_a_clear_error_and_leaves_the_previous_file() {
    let designs = tempfile::tempdir().unwrap();
    let design = big_design(designs.path());
    let disk = tempfile::tempdir().unwrap();
    // A 1 MB tmpfs holding a previous file, then a 28 MB mesh written over it.
    let script = r#"mount -t tmpfs -o size=1m tmpfs "$1" || exit 99
printf 'previous\n' > "$1/big.obj"
"$2" generate "$3" -o "$1/big.obj"
echo "status $?"
ls -A "$1"
cat "$1/big.obj""#;
    let monge = Path::new(env!("CARGO_BIN_EXE_monge"));
    let Some(output) = in_mount_namespace(script, &[disk.path(), monge, &design]) else {
        eprintln!("skipped: cannot mount a tmpfs here (needs unshare -m and mount)");
        return;
    };
    let stdout = String::from_utf8_lossy(&output.stdout);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(stdout, "status 2\nbig.obj\nprevious\n", "{stderr}");
    let out = disk.path().join("big.obj");
    let expected = format!(
        "cannot write `{}`: the file system refused to write more: No space left on device \
         (os error 28); free some space",
        out.display()
    );
    assert!(stderr.contains(&expected), "{stderr}");
}

#[test]
fn standard_output_full_or_closed_is_a_clear_error() {
    let design = common::example("fig13-freeform.json");
    // A full device as standard output.
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_monge"))
        .args([
            "generate".as_ref(),
            design.as_os_str(),
            "-o".as_ref(),
            "-".as_ref(),
        ])
        .stdout(full)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.starts_with("error: cannot write `<stdout>`: No space left on device"),
        "{err}"
    );
    // A reader that closes its end after 10 bytes (`monge … -o - | head -c 10`).
    let mut child = Command::new(env!("CARGO_BIN_EXE_monge"))
        .args([
            "generate".as_ref(),
            design.as_os_str(),
            "-o".as_ref(),
            "-".as_ref(),
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut head = [0u8; 10];
    std::io::Read::read_exact(child.stdout.as_mut().unwrap(), &mut head).unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.starts_with("error: cannot write `<stdout>`: Broken pipe"),
        "{err}"
    );
    assert!(!err.contains("panicked"), "{err}");
}

/// A directory that `monge fabricate` made for its files is removed when they cannot be
/// written: nothing is left.
#[test]
fn a_file_size_limit_leaves_no_fabrication_directory() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("fab");
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_monge"));
    cmd.arg("fabricate")
        .arg(common::example("fig25-biarc.json"))
        .arg("-o")
        .arg(&out);
    let output = with_file_size_limit(&mut cmd, 1024).output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("refused to write more"), "{stderr}");
    assert!(!out.exists(), "the directory made for the files is left");
    assert!(listing(dir.path()).is_empty());
}
