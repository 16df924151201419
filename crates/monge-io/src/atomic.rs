//! Atomic file writes, and `-` for standard output.

use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::time::{Duration, SystemTime};

use crate::error::IoError;

/// Buffer size of the writers handed to the closures.
const BUFFER: usize = 1 << 16;

/// Age after which a `.NAME.XXXXXX.tmp` left beside `NAME` by a killed
/// [`write_atomic`] is removed by the next write to `NAME`: one hour.
pub const STALE: Duration = Duration::from_secs(3600);

/// Writes a file atomically: `f` writes into a temporary file in the same
/// directory, which is flushed, synced and then renamed to `path`.
///
/// If `f` (or anything else) fails, the temporary file is removed and nothing
/// exists at `path` that was not there before: a pre-existing file is left
/// untouched. The writer given to `f` is buffered. A new file gets the usual
/// permissions (`0o666` less the umask on Unix). Errors are
/// [`IoError::Write`] naming `path`, or [`IoError::Full`] when the file
/// system refuses more bytes (full disk, quota, `ulimit -f`). Several files
/// that must change together are written with [`Outputs`].
///
/// On Linux the temporary file is unnamed (`O_TMPFILE`): if the process is
/// killed (`kill -9`, power cut) while `f` writes, it vanishes with the
/// process and nothing is left behind. Once complete and synced, it is linked
/// under a hidden name `.NAME.XXXXXX.tmp` and renamed over `path` at once,
/// and the directory is synced: a process killed in the microseconds between
/// the link and the rename leaves that `.NAME.XXXXXX.tmp` behind. Where
/// `O_TMPFILE` is not supported (other file systems or systems), the
/// temporary file is named from the start, and a killed process leaves it
/// behind too. Either way, the next write to `path` removes such leftovers
/// once they are [`STALE`] old (a write in progress keeps its file's time fresh).
///
/// ```
/// # let dir = tempfile::tempdir().unwrap();
/// let path = dir.path().join("hello.txt");
/// monge_io::write_atomic(&path, |w| w.write_all(b"hello\n")).unwrap();
/// assert_eq!(std::fs::read_to_string(&path).unwrap(), "hello\n");
/// ```
pub fn write_atomic(
    path: &Path,
    f: impl FnOnce(&mut dyn Write) -> io::Result<()>,
) -> Result<(), IoError> {
    Outputs {
        files: vec![Pending::write(path, f)?],
    }
    .commit()
}

/// The files of one command, written as one: each is written and synced beside
/// its path as [`write_atomic`] does, and none replaces its path before every
/// one is complete ([`Outputs::commit`]). If one fails, or the set is dropped
/// without a commit, no file at any of the paths has changed. `-` is standard
/// output, written at once.
///
/// ```
/// # let dir = tempfile::tempdir().unwrap();
/// let (a, b) = (dir.path().join("a.txt"), dir.path().join("b.txt"));
/// std::fs::write(&a, "old").unwrap();
/// let mut out = monge_io::Outputs::new();
/// out.write(&a, |w| w.write_all(b"new")).unwrap();
/// // The second file fails: the first keeps its old content.
/// let e = out.write(&b, |_| Err(std::io::Error::other("no")));
/// assert!(e.is_err());
/// drop(out);
/// assert_eq!(std::fs::read_to_string(&a).unwrap(), "old");
/// assert!(!b.exists());
/// ```
#[derive(Default)]
pub struct Outputs {
    files: Vec<Pending>,
}

impl Outputs {
    /// No file yet.
    pub fn new() -> Self {
        Outputs::default()
    }

    /// Writes `path` beside it (or to standard output if `path` is `-`), to be
    /// put in place by [`Outputs::commit`]. A path given twice is
    /// [`IoError::SameOutput`].
    pub fn write(
        &mut self,
        path: &Path,
        f: impl FnOnce(&mut dyn Write) -> io::Result<()>,
    ) -> Result<(), IoError> {
        if is_stdio(path) {
            return write_stdout(f);
        }
        self.check_new(path)?;
        self.files.push(Pending::write(path, f)?);
        Ok(())
    }

    /// Writes `paths[k]` with `f(k, …)`, as many at once as the machine has
    /// cores (as [`Outputs::write`] each); the first error in the order of the
    /// paths is returned.
    pub fn write_each(
        &mut self,
        paths: &[PathBuf],
        f: impl Fn(usize, &mut dyn Write) -> io::Result<()> + Sync + Send,
    ) -> Result<(), IoError> {
        for path in paths {
            self.check_new(path)?;
        }
        let written =
            monge_core::tasks::map(paths.len(), |k| Pending::write(&paths[k], |w| f(k, w)));
        for file in written {
            self.files.push(file?);
        }
        Ok(())
    }

    /// Puts every file in place, then syncs their directories: first each is
    /// given its hidden name beside its path (where a name the file system
    /// refuses fails, with every path still as it was), then each is renamed
    /// over its path.
    pub fn commit(self) -> Result<(), IoError> {
        let named = self
            .files
            .into_iter()
            .map(|f| {
                let tmp = f
                    .staged
                    .named(&f.dir, &temp_builder(&f.prefix))
                    .map_err(|source| IoError::write(&f.path, source))?;
                Ok((f.path, f.dir, tmp))
            })
            .collect::<Result<Vec<_>, IoError>>()?;
        let mut dirs: Vec<PathBuf> = Vec::new();
        for (path, dir, tmp) in named {
            tmp.persist(&path)
                .map_err(|e| IoError::write(&path, e.error))?;
            if !dirs.contains(&dir) {
                dirs.push(dir);
            }
        }
        // Makes the renames durable across a power cut (elsewhere than Unix a
        // rename needs no more). The files are in place by now, so a directory
        // that refuses to be synced (some network file systems) is not an error.
        #[cfg(unix)]
        for dir in dirs {
            if let Ok(d) = File::open(&dir) {
                let _ = d.sync_all();
            }
        }
        Ok(())
    }

    fn check_new(&self, path: &Path) -> Result<(), IoError> {
        let key = canonical(path);
        if self
            .files
            .iter()
            .any(|f| f.path == path || (key.is_some() && f.canonical == key))
        {
            return Err(IoError::SameOutput {
                path: path.to_owned(),
            });
        }
        Ok(())
    }
}

/// A file of [`Outputs`] written and synced beside its path, not yet in place.
struct Pending {
    path: PathBuf,
    /// [`canonical`] of `path`, to tell the same file under two names.
    canonical: Option<PathBuf>,
    dir: PathBuf,
    prefix: String,
    staged: Staged,
}

impl Pending {
    /// Writes the temporary file of `path` with `f`, flushed and synced.
    fn write(
        path: &Path,
        f: impl FnOnce(&mut dyn Write) -> io::Result<()>,
    ) -> Result<Pending, IoError> {
        let err = |source| IoError::write(path, source);
        let dir = existing_directory(path)?;
        // A rename over a directory would fail only at the commit.
        if path.is_dir() {
            return Err(err(io::Error::new(
                io::ErrorKind::InvalidInput,
                "it is a directory: give a file name",
            )));
        }
        let prefix = match path.file_name() {
            Some(name) => format!(".{}.", name.to_string_lossy()),
            None => {
                return Err(err(io::Error::new(
                    io::ErrorKind::InvalidInput,
                    "not a file name",
                )))
            }
        };
        remove_stale(dir, &prefix);
        let staged = Staged::create(dir, &temp_builder(&prefix)).map_err(err)?;
        {
            let mut w = BufWriter::with_capacity(BUFFER, Writeback::new(staged.file()));
            f(&mut w).map_err(err)?;
            w.flush().map_err(err)?;
        }
        staged.file().sync_all().map_err(err)?;
        Ok(Pending {
            path: path.to_owned(),
            canonical: canonical(path),
            dir: dir.to_owned(),
            prefix,
            staged,
        })
    }
}

/// The builder of the temporary names `PREFIX` + 6 characters + `.tmp`.
fn temp_builder(prefix: &str) -> tempfile::Builder<'_, 'static> {
    let mut builder = tempfile::Builder::new();
    builder.prefix(prefix).suffix(".tmp");
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    builder
}

/// `path` with its directory canonicalised, if that directory exists.
fn canonical(path: &Path) -> Option<PathBuf> {
    existing_directory(path)
        .ok()
        .and_then(|dir| dir.canonicalize().ok())
        .zip(path.file_name())
        .map(|(dir, name)| dir.join(name))
}

/// Bytes written between two requests of [`Writeback`] to start writing
/// them to the disk: 8 MiB.
const WRITEBACK: u64 = 8 << 20;

/// The staged file as [`write_atomic`] fills it. On Linux, every
/// [`WRITEBACK`] bytes it asks the kernel to start writing the bytes so far
/// to the disk (`sync_file_range`, without waiting), so that the disk works
/// while the writer formats the rest and the final `sync_all` finds most of
/// the file written (65 MB here: `sync_all` 23 → 5–9 ms). Elsewhere it is the
/// file. The bytes are the same either way.
struct Writeback<'f> {
    file: &'f File,
    /// Bytes written so far.
    written: u64,
    /// Bytes already handed to the disk.
    started: u64,
}

impl<'f> Writeback<'f> {
    fn new(file: &'f File) -> Self {
        Writeback {
            file,
            written: 0,
            started: 0,
        }
    }

    /// Asks for the bytes from `started` to `written` to go to the disk
    /// (a hint: a file system that does not take it is written at `sync_all`).
    fn start(&mut self) {
        #[cfg(target_os = "linux")]
        {
            use std::os::fd::AsRawFd;
            // SAFETY: the descriptor is the open file's, borrowed for the call;
            // `sync_file_range` reads no memory of ours.
            unsafe {
                libc::sync_file_range(
                    self.file.as_raw_fd(),
                    self.started as libc::off64_t,
                    (self.written - self.started) as libc::off64_t,
                    libc::SYNC_FILE_RANGE_WRITE,
                );
            }
        }
        self.started = self.written;
    }
}

impl Write for Writeback<'_> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let n = self.file.write(buf)?;
        self.written += n as u64;
        if self.written - self.started >= WRITEBACK {
            self.start();
        }
        Ok(n)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.file.flush()
    }
}

/// Removes the temporary files `PREFIX` + 6 characters + `.tmp` in `dir` that
/// were last modified [`STALE`] ago or more: what killed writes left behind.
/// Best effort: a file that cannot be read or removed is left.
fn remove_stale(dir: &Path, prefix: &str) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let now = SystemTime::now();
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(random) = name
            .to_str()
            .and_then(|n| n.strip_prefix(prefix))
            .and_then(|n| n.strip_suffix(".tmp"))
        else {
            continue;
        };
        let old = entry
            .metadata()
            .and_then(|m| m.modified())
            .is_ok_and(|t| now.duration_since(t).is_ok_and(|age| age >= STALE));
        if random.len() == 6 && random.bytes().all(|b| b.is_ascii_alphanumeric()) && old {
            let _ = std::fs::remove_file(entry.path());
        }
    }
}

/// The temporary file of [`write_atomic`] while it is written.
enum Staged {
    /// An unnamed file (`O_TMPFILE`), linked into the directory when complete.
    #[cfg(target_os = "linux")]
    Unnamed(File),
    /// A named temporary file, removed if dropped.
    Named(tempfile::NamedTempFile),
}

impl Staged {
    /// An unnamed file in `dir` where the system supports it, else a named one.
    fn create(dir: &Path, builder: &tempfile::Builder) -> io::Result<Self> {
        #[cfg(target_os = "linux")]
        {
            use rustix::fs::{Mode, OFlags};
            let flags = OFlags::WRONLY | OFlags::TMPFILE | OFlags::CLOEXEC;
            if let Ok(fd) = rustix::fs::open(dir, flags, Mode::from(0o666)) {
                return Ok(Staged::Unnamed(File::from(fd)));
            }
        }
        builder.tempfile_in(dir).map(Staged::Named)
    }

    fn file(&self) -> &File {
        match self {
            #[cfg(target_os = "linux")]
            Staged::Unnamed(file) => file,
            Staged::Named(tmp) => tmp.as_file(),
        }
    }

    /// The complete file under its hidden name in `dir` (linked there if it
    /// was unnamed), ready to be renamed over its path; removed if dropped.
    /// (`dir` and `builder` serve the unnamed file, which only Linux makes.)
    #[cfg_attr(not(target_os = "linux"), allow(unused_variables))]
    fn named(self, dir: &Path, builder: &tempfile::Builder) -> io::Result<tempfile::TempPath> {
        match self {
            #[cfg(target_os = "linux")]
            Staged::Unnamed(file) => {
                use rustix::fs::{AtFlags, CWD};
                let proc = format!("/proc/self/fd/{}", std::os::fd::AsRawFd::as_raw_fd(&file));
                let linked = builder.make_in(dir, |tmp| {
                    rustix::fs::linkat(CWD, proc.as_str(), CWD, tmp, AtFlags::SYMLINK_FOLLOW)
                        .map_err(io::Error::from)
                })?;
                Ok(linked.into_temp_path())
            }
            Staged::Named(tmp) => Ok(tmp.into_temp_path()),
        }
    }
}

/// The directory of `path` (`.` for a bare file name), or
/// [`IoError::NoDirectory`] if it does not exist.
pub(crate) fn existing_directory(path: &Path) -> Result<&Path, IoError> {
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    if dir.is_dir() {
        Ok(dir)
    } else {
        Err(IoError::NoDirectory {
            path: path.to_owned(),
            dir: dir.to_owned(),
        })
    }
}

/// Checks an output path before a command does its work: its directory exists
/// ([`IoError::NoDirectory`]) and it is none of `inputs`
/// ([`IoError::OutputIsInput`], comparing canonical paths: the output's
/// directory canonicalised, plus its file name). `-` (standard output) passes.
///
/// ```
/// # let dir = tempfile::tempdir().unwrap();
/// let design = dir.path().join("d.json");
/// std::fs::write(&design, "{}").unwrap();
/// let same = dir.path().join(".").join("d.json");
/// assert!(monge_io::check_output(&same, &[&design]).is_err());
/// assert!(monge_io::check_output(&dir.path().join("d.obj"), &[&design]).is_ok());
/// ```
pub fn check_output(path: &Path, inputs: &[&Path]) -> Result<(), IoError> {
    if is_stdio(path) {
        return Ok(());
    }
    existing_directory(path)?;
    let canonical = canonical(path);
    let same = |input: &&Path| {
        !is_stdio(input) && canonical.is_some() && input.canonicalize().ok() == canonical
    };
    if inputs.iter().any(same) {
        return Err(IoError::OutputIsInput {
            path: path.to_owned(),
        });
    }
    Ok(())
}

/// Writes to `path` with [`write_atomic`], or to standard output if `path` is `-`.
///
/// Errors on standard output are [`IoError::Write`] with the path `<stdout>`.
pub fn write_output(
    path: &Path,
    f: impl FnOnce(&mut dyn Write) -> io::Result<()>,
) -> Result<(), IoError> {
    let mut out = Outputs::new();
    out.write(path, f)?;
    out.commit()
}

/// Writes to standard output, buffered; errors name `<stdout>`.
fn write_stdout(f: impl FnOnce(&mut dyn Write) -> io::Result<()>) -> Result<(), IoError> {
    let stdout = io::stdout();
    let mut w = BufWriter::with_capacity(BUFFER, stdout.lock());
    f(&mut w)
        .and_then(|()| w.flush())
        .map_err(|source| IoError::Write {
            path: PathBuf::from("<stdout>"),
            source,
        })
}

/// Whether `path` is `-`, standing for standard input or output.
pub fn is_stdio(path: &Path) -> bool {
    path.as_os_str() == "-"
}
