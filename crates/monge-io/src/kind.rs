//! Telling a file's format by its path's extension and its kind by its
//! top-level keys, with the errors that name what was expected.

use std::path::Path;

use crate::atomic::is_stdio;
use crate::error::IoError;
use crate::format::{DesignFormat, FileKind, MeshFormat};

const DESIGN_ACCEPTED: &str = "`.json` or `.toml`";
const MESH_ACCEPTED: &str = "`.obj`, `.ply`, `.json` or `.glb` (glTF, written only)";

impl DesignFormat {
    /// The format named by the path's extension (`.json` or `.toml`, any case).
    ///
    /// ```
    /// use monge_io::DesignFormat;
    /// use std::path::Path;
    /// assert_eq!(DesignFormat::from_path(Path::new("a/b.TOML")).unwrap(), DesignFormat::Toml);
    /// assert!(DesignFormat::from_path(Path::new("b.yaml")).is_err());
    /// ```
    pub fn from_path(path: &Path) -> Result<DesignFormat, IoError> {
        match extension(path).as_deref() {
            Some("json") => Ok(DesignFormat::Json),
            Some("toml") => Ok(DesignFormat::Toml),
            _ => Err(unknown_extension(path, DESIGN_ACCEPTED)),
        }
    }
}

impl MeshFormat {
    /// The format named by the path's extension (any case).
    ///
    /// `-` (standard input/output) has none: [`IoError::NeedFormat`].
    ///
    /// ```
    /// use monge_io::MeshFormat;
    /// use std::path::Path;
    /// assert_eq!(MeshFormat::from_path(Path::new("out/mesh.obj")).unwrap(), MeshFormat::Obj);
    /// assert!(MeshFormat::from_path(Path::new("-")).is_err());
    /// ```
    pub fn from_path(path: &Path) -> Result<MeshFormat, IoError> {
        if is_stdio(path) {
            return Err(IoError::NeedFormat {
                accepted: "obj, ply or json",
            });
        }
        extension(path)
            .and_then(|e| MeshFormat::from_extension(&e))
            .ok_or_else(|| unknown_extension(path, MESH_ACCEPTED))
    }
}

/// The lower-case extension of `path`, if any.
pub(crate) fn extension(path: &Path) -> Option<String> {
    path.extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
}

/// The [`IoError::UnknownExtension`] for `path`.
pub(crate) fn unknown_extension(path: &Path, accepted: &'static str) -> IoError {
    let found = match path.extension() {
        Some(e) => format!("extension `.{}`", e.to_string_lossy()),
        None => "file name without extension".to_owned(),
    };
    IoError::UnknownExtension {
        path: path.to_owned(),
        found,
        accepted,
    }
}

/// [`IoError::WrongKind`] if `text` is recognisably a kind of file other than
/// `expected` (the first of which names what was expected); a text of no
/// recognisable kind is left to the parser, which says what is wrong with it.
/// Returns the kind found.
pub(crate) fn expect_kind(
    text: &str,
    format: DesignFormat,
    file: &str,
    expected: &[FileKind],
) -> Result<Option<FileKind>, IoError> {
    match FileKind::of_text(text, format) {
        Some(found) if !expected.contains(&found) => Err(IoError::WrongKind {
            file: file.to_owned(),
            found,
            expected: expected[0],
        }),
        found => Ok(found),
    }
}
