//! The lines of a buffered reader, one at a time into one buffer, and the
//! error of a failed read.

use std::io::{self, BufRead};
use std::path::PathBuf;

use crate::error::IoError;

/// [`IoError::Read`] of `file`.
pub(super) fn read_failed(file: &str, source: io::Error) -> IoError {
    IoError::Read {
        path: PathBuf::from(file),
        source,
    }
}

/// The lines of a buffered reader, read one at a time into one buffer.
pub(super) struct Lines<'f, R> {
    pub(super) reader: R,
    buf: Vec<u8>,
    /// Lines read so far.
    pub(super) number: usize,
    /// Bytes read so far.
    pub(super) bytes: usize,
    pub(super) file: &'f str,
}

impl<'f, R: BufRead> Lines<'f, R> {
    pub(super) fn new(reader: R, file: &'f str) -> Self {
        Lines {
            reader,
            buf: Vec::new(),
            number: 0,
            bytes: 0,
            file,
        }
    }

    /// The next line's 1-based number and bytes (without `\n` or `\r\n`), or
    /// `None` at the end of the input.
    pub(super) fn next_line(&mut self) -> Result<Option<(usize, &[u8])>, IoError> {
        self.buf.clear();
        let n = self
            .reader
            .read_until(b'\n', &mut self.buf)
            .map_err(|source| read_failed(self.file, source))?;
        if n == 0 {
            return Ok(None);
        }
        self.number += 1;
        self.bytes += n;
        if self.buf.last() == Some(&b'\n') {
            self.buf.pop();
            if self.buf.last() == Some(&b'\r') {
                self.buf.pop();
            }
        }
        Ok(Some((self.number, &self.buf)))
    }
}
