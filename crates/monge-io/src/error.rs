//! The error type of this crate.

use std::io;
use std::path::{Path, PathBuf};

use crate::format::FileKind;

/// Everything that can go wrong reading or writing design and mesh files.
///
/// Messages are written for the person who wrote the file: they name the file,
/// give the line and column where known, and say what was expected.
#[derive(Debug, thiserror::Error)]
pub enum IoError {
    /// The file to read does not exist.
    #[error("file not found: `{}`", path.display())]
    NotFound {
        /// The missing file.
        path: PathBuf,
    },

    /// Reading a file (or standard input) failed for another reason.
    #[error("cannot read `{}`: {source}", path.display())]
    Read {
        /// The file being read (`<stdin>` for standard input).
        path: PathBuf,
        /// The underlying error.
        source: io::Error,
    },

    /// Writing a file (or standard output) failed; an existing file at the
    /// path is left as it was.
    #[error("cannot write `{}`: {source}", path.display())]
    Write {
        /// The file being written (`<stdout>` for standard output).
        path: PathBuf,
        /// The underlying error.
        source: io::Error,
    },

    /// The file system refused to write more bytes to a file: the disk is full
    /// (`ENOSPC`), a quota is reached (`EDQUOT`) or the file-size limit
    /// (`ulimit -f`, `EFBIG`); an existing file at the path is left as it was.
    #[error(
        "cannot write `{}`: the file system refused to write more: {source}; free some space \
         (or raise the quota or the file-size limit, `ulimit -f`) or choose another output path \
         (nothing was written: an existing `{}` is left as it was)",
        path.display(),
        path.display()
    )]
    Full {
        /// The file being written.
        path: PathBuf,
        /// The underlying error.
        source: io::Error,
    },

    /// A file changed (was truncated, extended or rewritten) while it was read.
    #[error(
        "`{}` changed while it was being read: it had {opened} bytes when opened, {read} were \
         read and it now has {now}; read it again once whatever writes it has finished",
        path.display()
    )]
    Changed {
        /// The file being read.
        path: PathBuf,
        /// Its length when opened.
        opened: u64,
        /// The number of bytes read.
        read: u64,
        /// Its length after the read.
        now: u64,
    },

    /// The directory of an output file does not exist.
    #[error(
        "cannot write `{}`: the directory `{}` does not exist (create it first, or choose another output path)",
        path.display(),
        dir.display()
    )]
    NoDirectory {
        /// The file to write.
        path: PathBuf,
        /// Its directory.
        dir: PathBuf,
    },

    /// An output directory's path is a file.
    #[error(
        "`{}` exists and is not a directory: the output is a directory of files; give -o a \
         new or existing directory (or remove `{}` first)",
        path.display(),
        path.display()
    )]
    NotADirectory {
        /// The output directory, as given.
        path: PathBuf,
    },

    /// An output path is one of the command's input files.
    #[error(
        "`{}` is an input of this command and cannot also be its output: choose another output path \
         (monge never writes over its input)",
        path.display()
    )]
    OutputIsInput {
        /// The output path, as given.
        path: PathBuf,
    },

    /// Two outputs of one command are the same file.
    #[error(
        "`{}` would be written twice by this command (two of its outputs name the same \
         file): give each output its own path",
        path.display()
    )]
    SameOutput {
        /// The path given the second time.
        path: PathBuf,
    },

    /// A file is of another kind than the command reads (a multi-patch design
    /// given to `monge generate`, a design given to `monge check`, …).
    #[error("{file} is {found}, not {expected}: use {}", found.commands())]
    WrongKind {
        /// The file name.
        file: String,
        /// What the file is, by its top-level keys.
        found: FileKind,
        /// What the command reads.
        expected: FileKind,
    },

    /// A design file (of any kind) is larger than [`MAX_DESIGN_BYTES`](crate::MAX_DESIGN_BYTES).
    #[error(
        "{file} has {size} bytes, more than a design file may have: {limit} bytes (16 MiB). A \
         design is a few kB (two guides and θ): give a long guide as a B-spline of a few \
         control points rather than as its points, or check that this is the design file meant"
    )]
    DesignTooLarge {
        /// The file name.
        file: String,
        /// Its size in bytes (read so far, for a stream).
        size: u64,
        /// [`MAX_DESIGN_BYTES`](crate::MAX_DESIGN_BYTES).
        limit: u64,
    },

    /// The file format cannot be told from the path's extension.
    #[error("`{}`: unsupported {found}; expected {accepted}", path.display())]
    UnknownExtension {
        /// The path.
        path: PathBuf,
        /// What was found, e.g. "extension `.stl`" or "file name without extension".
        found: String,
        /// The accepted extensions, e.g. "`.json` or `.toml`".
        accepted: &'static str,
    },

    /// `-` (standard input or output) was given without saying which format to use.
    #[error("`-` (standard input/output) needs an explicit format: {accepted}")]
    NeedFormat {
        /// The formats that could be given.
        accepted: &'static str,
    },

    /// A JSON or TOML file is not valid, or does not have the expected fields.
    #[error("{}", fmt_parse(file, *line, *column, message, snippet))]
    Parse {
        /// The file name (`<input>` for text without a file).
        file: String,
        /// 1-based line of the error; 0 when the parser gave no position.
        line: usize,
        /// 1-based column (in characters) of the error; 0 when unknown.
        column: usize,
        /// What is wrong, e.g. "unknown field `thetadeg`, expected one of …".
        message: String,
        /// The offending line with a caret under the column (empty when unknown).
        snippet: String,
    },

    /// A number in a design is NaN or infinite (TOML allows `nan` and `inf`).
    #[error("{file}: a number is not finite at `{key}`")]
    NonFinite {
        /// The file name (`<input>` for text without a file).
        file: String,
        /// Where the number is, e.g. `theta_deg` or `guide_u.points[2][1]`.
        key: String,
    },

    /// A line of an OBJ or PLY file cannot be understood.
    #[error("{file}:{line}: {message}")]
    Syntax {
        /// The file name.
        file: String,
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        message: String,
    },

    /// The binary body of a PLY file cannot be understood.
    #[error("{file}: byte {offset} (in the binary body): {message}")]
    Binary {
        /// The file name.
        file: String,
        /// 0-based byte offset in the file.
        offset: usize,
        /// What is wrong.
        message: String,
    },

    /// A count in a mesh file does not match the grid shape.
    #[error("{file}: {what}: expected {expected}, found {found}")]
    CountMismatch {
        /// The file name.
        file: String,
        /// What was counted, e.g. "vertices (rows × cols = 4 × 5)".
        what: String,
        /// The count the grid shape requires.
        expected: usize,
        /// The count in the file.
        found: usize,
    },

    /// The faces of a mesh file do not form a regular row-major quad grid.
    #[error("{file}: not a regular row-major quad grid: {message}")]
    NotAGrid {
        /// The file name.
        file: String,
        /// Which face is wrong and why.
        message: String,
    },
}

fn fmt_parse(file: &str, line: usize, column: usize, message: &str, snippet: &str) -> String {
    let mut s = if line == 0 {
        format!("{file}: {message}")
    } else {
        format!("{file}:{line}:{column}: {message}")
    };
    if !snippet.is_empty() {
        s.push('\n');
        s.push_str(snippet);
    }
    s
}

impl IoError {
    /// [`IoError::Full`] if `source` says the file system refused more bytes,
    /// else [`IoError::Write`], naming `path`.
    pub(crate) fn write(path: &Path, source: io::Error) -> Self {
        let path = path.to_owned();
        if refused_more(&source) {
            IoError::Full { path, source }
        } else {
            IoError::Write { path, source }
        }
    }

    /// A [`IoError::Parse`] at byte `offset` of `text` (line, column and snippet computed).
    pub(crate) fn parse_at(file: &str, text: &str, offset: Option<usize>, message: String) -> Self {
        let Some(offset) = offset else {
            return IoError::Parse {
                file: file.to_owned(),
                line: 0,
                column: 0,
                message,
                snippet: String::new(),
            };
        };
        let mut offset = offset.min(text.len());
        while !text.is_char_boundary(offset) {
            offset -= 1;
        }
        let line_start = text[..offset].rfind('\n').map_or(0, |p| p + 1);
        let line = text[..line_start].matches('\n').count() + 1;
        let column = text[line_start..offset].chars().count() + 1;
        IoError::Parse {
            file: file.to_owned(),
            line,
            column,
            message,
            snippet: snippet(text, line, column),
        }
    }

    /// A [`IoError::Parse`] at a 1-based line and column of `text`.
    pub(crate) fn parse_at_line(
        file: &str,
        text: &str,
        line: usize,
        column: usize,
        message: String,
    ) -> Self {
        IoError::Parse {
            file: file.to_owned(),
            line,
            column,
            message,
            snippet: snippet(text, line, column),
        }
    }
}

/// Whether `e` is a full disk, a reached quota or the file-size limit.
#[cfg(unix)]
fn refused_more(e: &io::Error) -> bool {
    use rustix::io::Errno;
    Errno::from_io_error(e).is_some_and(|e| [Errno::NOSPC, Errno::DQUOT, Errno::FBIG].contains(&e))
}

/// Outside Unix these errors are not told apart: they are [`IoError::Write`].
#[cfg(not(unix))]
fn refused_more(_: &io::Error) -> bool {
    false
}

/// Widest part of a line shown in a snippet (mesh JSON can be one long line).
const SNIPPET_WIDTH: usize = 72;

/// The 1-based `line` of `text`, cut to a window around `column`, with a caret
/// under the column. Empty if the line does not exist.
fn snippet(text: &str, line: usize, column: usize) -> String {
    let Some(src) = line.checked_sub(1).and_then(|l| text.lines().nth(l)) else {
        return String::new();
    };
    let len = src.chars().count();
    let col = column.max(1) - 1;
    let start = col.saturating_sub(SNIPPET_WIDTH / 2).min(len);
    let end = (start + SNIPPET_WIDTH).min(len);
    let prefix = if start > 0 { "…" } else { "" };
    let suffix = if end < len { "…" } else { "" };
    let shown: String = src.chars().skip(start).take(end - start).collect();
    let pad = " ".repeat(col - start + prefix.chars().count());
    format!("  | {prefix}{shown}{suffix}\n  | {pad}^")
}
