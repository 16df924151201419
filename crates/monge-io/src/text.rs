//! A streaming text (and byte) output shared by the writers: numbers are
//! formatted without allocating, floats as the shortest decimal that parses
//! back to the same `f64` (`zmij`), and bytes are passed on in large chunks.

use std::io::{self, Write};
use std::ops::Range;
use std::sync::{Mutex, PoisonError};

use glam::DVec3;

/// Bytes collected before an [`Out`] passes them on.
const CHUNK: usize = 1 << 16;

/// Runs `body`, which formats into an [`Out`] writing to `w`, then flushes it.
pub(crate) fn emit<W: Write + ?Sized>(
    w: &mut W,
    body: impl FnOnce(&mut Out<'_, W>) -> io::Result<()>,
) -> io::Result<()> {
    let mut out = Out {
        buf: Vec::with_capacity(CHUNK + 1024),
        float: zmij::Buffer::new(),
        int: itoa::Buffer::new(),
        chunks: Vec::new(),
        ready: Vec::new(),
        w,
    };
    body(&mut out)?;
    out.flush()
}

/// An output buffer: append text and bytes, then [`Out::end`] a line (or call
/// [`Out::maybe_flush`]) so that full chunks go on to the writer.
pub(crate) struct Out<'w, W: Write + ?Sized> {
    buf: Vec<u8>,
    float: zmij::Buffer,
    int: itoa::Buffer,
    /// The chunks of [`Out::each`], kept from batch to batch and call to
    /// call: memory touched once (fresh pages cost more than formatting).
    chunks: Vec<Mutex<Vec<u8>>>,
    /// The batch of [`Out::each`] formatted last, written while the next
    /// one is formatted.
    ready: Vec<Vec<u8>>,
    w: &'w mut W,
}

/// Most items per chunk of [`Out::each_range`]: a bound on [`CHUNK_BYTES`]'s
/// estimate, should the first items be much shorter than the rest. Binary
/// items are short (a glTF position is 12 bytes, 21 845 to a chunk): with at
/// most 4096 of them, the 1000² glTF went in chunks of 48–98 kB and took
/// 36 ms; in 256 kB chunks, 30 ms (fewer hand-overs between the formatting
/// threads and the writer, and no chunk copied into the file's 64 kB buffer).
const ITEMS: usize = 1 << 16;

/// Items per chunk of the first batch of [`Out::each_range`], before the
/// size of an item is known.
const FIRST_ITEMS: usize = 1 << 8;

/// Bytes a chunk of [`Out::each_range`] aims at once the first batch tells
/// the size of an item: long lines (a panel's 570 bytes) come in fewer per
/// chunk, so that the chunks of two schedules written side by side take 8 MB,
/// not 75.
const CHUNK_BYTES: usize = 1 << 18;

/// Chunks formatted side by side before they are passed on: a few per core.
const BATCH: usize = 8;

impl<W: Write + ?Sized> Out<'_, W> {
    /// Appends one byte.
    pub(crate) fn push(&mut self, b: u8) {
        self.buf.push(b);
    }

    /// Appends bytes as they are.
    pub(crate) fn bytes(&mut self, b: &[u8]) {
        self.buf.extend_from_slice(b);
    }

    /// Appends a string.
    pub(crate) fn str(&mut self, s: &str) {
        self.buf.extend_from_slice(s.as_bytes());
    }

    /// Appends the shortest decimal that parses back to `x` (finite:
    /// callers check; a non-finite value would be written as a number).
    pub(crate) fn float(&mut self, x: f64) {
        self.buf
            .extend_from_slice(self.float.format_finite(x).as_bytes());
    }

    /// Appends a whole number.
    pub(crate) fn int(&mut self, n: impl itoa::Integer) {
        self.buf.extend_from_slice(self.int.format(n).as_bytes());
    }

    /// Appends `x y z` (floats separated by `sep`).
    pub(crate) fn xyz(&mut self, p: DVec3, sep: u8) {
        self.float(p.x);
        self.push(sep);
        self.float(p.y);
        self.push(sep);
        self.float(p.z);
    }

    /// Ends the line (passing the buffer on once it is full).
    pub(crate) fn end(&mut self) -> io::Result<()> {
        self.buf.push(b'\n');
        self.maybe_flush()
    }

    /// Passes the buffer on if it is full.
    pub(crate) fn maybe_flush(&mut self) -> io::Result<()> {
        if self.buf.len() >= CHUNK {
            self.flush()?;
        }
        Ok(())
    }

    /// Appends `line(k, item)` for every item, in order, formatted in chunks
    /// side by side (see [`Out::each_range`]).
    pub(crate) fn each<T: Sync>(
        &mut self,
        items: &[T],
        line: impl Fn(&mut Out<'_, Vec<u8>>, usize, &T) + Sync,
    ) -> io::Result<()> {
        self.each_range(items.len(), |o, range| {
            for k in range {
                line(o, k, &items[k]);
            }
        })
    }

    /// Appends `lines(range)` for consecutive ranges that cover `0..n`, in
    /// order, formatted side by side (one thread per core; one thread where
    /// there are no threads, as in WebAssembly), each batch of them written
    /// while the next is formatted: the bytes are the same whatever the number
    /// of threads. A range holds [`FIRST_ITEMS`] at first, then as many as
    /// make [`CHUNK_BYTES`] at the size of the items of the batch before, at
    /// most [`ITEMS`].
    pub(crate) fn each_range(
        &mut self,
        n: usize,
        lines: impl Fn(&mut Out<'_, Vec<u8>>, Range<usize>) + Sync,
    ) -> io::Result<()> {
        self.flush()?;
        let (mut first, mut items) = (0, FIRST_ITEMS);
        while first < n {
            let batch = first..n.min(first + items * BATCH);
            let bytes = self.batch(batch.clone(), items, &lines)?;
            items = (CHUNK_BYTES * batch.len() / bytes.max(1)).clamp(1, ITEMS);
            first = batch.end;
        }
        self.write_ready()
    }

    /// Formats `lines` of the chunks of `items` of `batch`, side by side,
    /// while the batch before is written; the new batch is then the one ready
    /// to be written. Returns its size in bytes.
    fn batch(
        &mut self,
        batch: Range<usize>,
        items: usize,
        lines: &(impl Fn(&mut Out<'_, Vec<u8>>, Range<usize>) + Sync),
    ) -> io::Result<usize> {
        let chunks = batch.len().div_ceil(items);
        self.chunks.resize_with(BATCH, Mutex::default);
        let (buffers, ready, w) = (&self.chunks, &self.ready, &mut *self.w);
        let (written, ()) = monge_core::tasks::beside(
            || ready.iter().try_for_each(|bytes| w.write_all(bytes)),
            || {
                monge_core::tasks::map(chunks, |c| {
                    let mut bytes = buffers[c].lock().unwrap_or_else(PoisonError::into_inner);
                    // Formatted straight into the chunk's buffer; whatever a
                    // line passes on (none does) goes first.
                    let mut passed = Vec::new();
                    let mut o = Out {
                        buf: std::mem::take(&mut *bytes),
                        float: zmij::Buffer::new(),
                        int: itoa::Buffer::new(),
                        chunks: Vec::new(),
                        ready: Vec::new(),
                        w: &mut passed,
                    };
                    o.buf.clear();
                    // Room for a whole chunk from the start: a buffer grown by
                    // doubling leaves a block of every smaller size behind, each
                    // on fresh pages (1000² OBJ peak 98 → 72 MB).
                    o.buf.reserve(CHUNK_BYTES + CHUNK_BYTES / 4);
                    let first = batch.start + c * items;
                    lines(&mut o, first..batch.end.min(first + items));
                    let formatted = std::mem::take(&mut o.buf);
                    *bytes = if passed.is_empty() {
                        formatted
                    } else {
                        passed.extend_from_slice(&formatted);
                        passed
                    };
                });
            },
        );
        written?;
        // The written buffers go back to be formatted into next time.
        self.ready.resize_with(chunks, Vec::new);
        for (ready, chunk) in self.ready.iter_mut().zip(&mut self.chunks) {
            std::mem::swap(
                ready,
                chunk.get_mut().unwrap_or_else(PoisonError::into_inner),
            );
        }
        Ok(self.ready.iter().map(Vec::len).sum())
    }

    /// Writes the batch formatted last (its buffers kept, emptied).
    fn write_ready(&mut self) -> io::Result<()> {
        for bytes in &mut self.ready {
            self.w.write_all(bytes)?;
            bytes.clear();
        }
        Ok(())
    }

    /// Passes on whatever is buffered.
    fn flush(&mut self) -> io::Result<()> {
        if !self.buf.is_empty() {
            self.w.write_all(&self.buf)?;
            self.buf.clear();
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn items_formatted_side_by_side_come_out_in_order() {
        // Several batches of BATCH chunks of ITEMS items, the last ones partial,
        // item by item and range by range.
        let items: Vec<f64> = (0..300_003).map(|k| k as f64 * 0.37 - 1e3).collect();
        let line = |o: &mut Out<'_, Vec<u8>>, k: usize, x: &f64| {
            o.int(k);
            o.push(b' ');
            o.float(*x);
            o.push(b'\n');
        };
        // A line may also pass its chunk's bytes on (`end`), in order.
        let ending = |o: &mut Out<'_, Vec<u8>>, k: usize, x: &f64| {
            o.int(k);
            o.push(b' ');
            o.float(*x);
            o.end().unwrap();
        };
        let mut side_by_side = Vec::new();
        emit(&mut side_by_side, |o| {
            o.str("head\n");
            o.each(&items, ending)?;
            o.each_range(items.len(), |o, range| {
                assert!(!range.is_empty() && range.len() <= ITEMS);
                for k in range {
                    line(o, k, &items[k]);
                }
            })?;
            o.end()
        })
        .unwrap();
        let mut alone = b"head\n".to_vec();
        for _ in 0..2 {
            for (k, x) in items.iter().enumerate() {
                alone.extend(format!("{k} {}\n", zmij::Buffer::new().format_finite(*x)).bytes());
            }
        }
        alone.push(b'\n');
        assert_eq!(
            String::from_utf8(side_by_side).unwrap(),
            String::from_utf8(alone).unwrap()
        );
    }

    #[test]
    fn long_lines_come_fewer_to_a_chunk() {
        // Lines of 10 kB: the first batch as FIRST_ITEMS a chunk, then about
        // CHUNK_BYTES of them.
        let sizes = Mutex::new(Vec::new());
        let mut v = Vec::new();
        emit(&mut v, |o| {
            o.each_range(10 * FIRST_ITEMS * BATCH, |o, range| {
                sizes.lock().unwrap().push((range.start, range.len()));
                for _ in range {
                    o.bytes(&[b'x'; 10_000]);
                }
            })
        })
        .unwrap();
        assert_eq!(v.len(), 10 * FIRST_ITEMS * BATCH * 10_000);
        let mut sizes = sizes.into_inner().unwrap();
        sizes.sort();
        assert!(sizes[..BATCH].iter().all(|s| s.1 == FIRST_ITEMS));
        assert!(sizes[BATCH..].iter().all(|s| s.1 <= CHUNK_BYTES / 10_000));
        assert!(sizes.windows(2).all(|w| w[0].0 + w[0].1 == w[1].0));
    }

    #[test]
    fn floats_are_shortest_and_conventional() {
        let mut v = Vec::new();
        emit(&mut v, |o| {
            for x in [0.1, -0.0, 1e-7, 1e16, 2.5, 1.0, 5e-324] {
                o.float(x);
                o.push(b' ');
            }
            o.int(42u32);
            o.end()
        })
        .unwrap();
        // Exponents as every float reader takes them (C's strtod, Python's
        // float(), JSON); zmij writes `e+` for positive exponents.
        assert_eq!(
            String::from_utf8(v).unwrap(),
            "0.1 -0.0 1e-7 1e+16 2.5 1.0 5e-324 42\n"
        );
    }
}
