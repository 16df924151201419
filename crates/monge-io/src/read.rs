//! Reading whole files: text or bytes, refusing a file that changes while it
//! is read, with errors that name the file.

use std::fs::{File, Metadata};
use std::io::{self, Read};
use std::path::Path;

use crate::error::IoError;

/// The whole file as text (see [`read_file`]); invalid UTF-8 is [`IoError::Read`].
pub(crate) fn read_to_string(path: &Path) -> Result<String, IoError> {
    utf8(path, read_file(path)?)
}

/// `bytes` of the file `path` as text; invalid UTF-8 is [`IoError::Read`].
pub(crate) fn utf8(path: &Path, bytes: Vec<u8>) -> Result<String, IoError> {
    String::from_utf8(bytes).map_err(|e| IoError::Read {
        path: path.to_owned(),
        source: io::Error::new(io::ErrorKind::InvalidData, e.utf8_error()),
    })
}

/// The whole file; [`IoError::NotFound`], [`IoError::Read`] or
/// [`IoError::Changed`] naming it.
///
/// A regular file that is truncated, extended or rewritten while it is read
/// is [`IoError::Changed`], told by its length and modification time before
/// and after. A file removed or renamed over while it is read is still read
/// whole: the open file keeps its contents.
pub(crate) fn read_file(path: &Path) -> Result<Vec<u8>, IoError> {
    let file = File::open(path).map_err(|source| read_error(path, source))?;
    let opened = file.metadata().map_err(|source| read_error(path, source))?;
    read_unchanged(path, file, &opened, u64::MAX)
}

/// Reads `file` (the file `path` as it was `opened`) to its end, or its first
/// `limit` bytes, checking that it did not change meanwhile (see [`read_file`]).
pub(crate) fn read_unchanged(
    path: &Path,
    file: File,
    opened: &Metadata,
    limit: u64,
) -> Result<Vec<u8>, IoError> {
    let err = |source| read_error(path, source);
    let mut bytes = Vec::new();
    (&file).take(limit).read_to_end(&mut bytes).map_err(err)?;
    let now = file.metadata().map_err(err)?;
    let read = bytes.len() as u64;
    let same = read == opened.len()
        && now.len() == opened.len()
        && now.modified().ok() == opened.modified().ok();
    if opened.is_file() && !same {
        return Err(IoError::Changed {
            path: path.to_owned(),
            opened: opened.len(),
            read,
            now: now.len(),
        });
    }
    Ok(bytes)
}

/// [`IoError::NotFound`] or [`IoError::Read`] naming `path`.
pub(crate) fn read_error(path: &Path, source: io::Error) -> IoError {
    match source.kind() {
        io::ErrorKind::NotFound => IoError::NotFound {
            path: path.to_owned(),
        },
        _ => IoError::Read {
            path: path.to_owned(),
            source,
        },
    }
}

/// The path as shown in error messages.
pub(crate) fn path_name(path: &Path) -> String {
    path.display().to_string()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;
    use std::time::Duration;

    /// A file of 1000 bytes in a fresh directory, opened, with its metadata.
    fn opened(dir: &tempfile::TempDir) -> (std::path::PathBuf, File, Metadata) {
        let path = dir.path().join("d.json");
        std::fs::write(&path, [b' '; 1000]).unwrap();
        let file = File::open(&path).unwrap();
        let meta = file.metadata().unwrap();
        (path, file, meta)
    }

    fn changed(result: Result<Vec<u8>, IoError>) -> (u64, u64, u64, String) {
        match result {
            Err(
                e @ IoError::Changed {
                    opened, read, now, ..
                },
            ) => (opened, read, now, e.to_string()),
            other => panic!("expected Changed, got {other:?}"),
        }
    }

    #[test]
    fn a_file_truncated_while_read_is_changed() {
        let dir = tempfile::tempdir().unwrap();
        let (path, file, meta) = opened(&dir);
        let other = std::fs::OpenOptions::new().write(true).open(&path).unwrap();
        other.set_len(10).unwrap();
        let (opened, read, now, message) = changed(read_unchanged(&path, file, &meta, u64::MAX));
        assert_eq!((opened, read, now), (1000, 10, 10));
        assert!(
            message.contains("d.json` changed while it was being read"),
            "{message}"
        );
        assert!(
            message.contains("1000 bytes when opened, 10 were read"),
            "{message}"
        );
    }

    #[test]
    fn a_file_extended_while_read_is_changed() {
        let dir = tempfile::tempdir().unwrap();
        let (path, file, meta) = opened(&dir);
        let mut other = std::fs::OpenOptions::new()
            .append(true)
            .open(&path)
            .unwrap();
        other.write_all(&[b' '; 24]).unwrap();
        let (opened, read, now, _) = changed(read_unchanged(&path, file, &meta, u64::MAX));
        assert_eq!((opened, read, now), (1000, 1024, 1024));
    }

    #[test]
    fn a_file_rewritten_in_place_while_read_is_changed() {
        let dir = tempfile::tempdir().unwrap();
        let (path, file, meta) = opened(&dir);
        let mut other = std::fs::OpenOptions::new().write(true).open(&path).unwrap();
        other.write_all(&[b'x'; 1000]).unwrap();
        // The same length: only the modification time tells (set apart from
        // the clock's granularity).
        let later = meta.modified().unwrap() + Duration::from_secs(1);
        other.set_modified(later).unwrap();
        let (opened, read, now, _) = changed(read_unchanged(&path, file, &meta, u64::MAX));
        assert_eq!((opened, read, now), (1000, 1000, 1000));
    }

    #[test]
    fn a_file_removed_while_read_is_read_whole() {
        let dir = tempfile::tempdir().unwrap();
        let (path, file, meta) = opened(&dir);
        std::fs::remove_file(&path).unwrap();
        let bytes = read_unchanged(&path, file, &meta, u64::MAX).unwrap();
        assert_eq!(bytes, [b' '; 1000]);
    }
}
