//! The IGES 5.3 fixed ASCII format: 80-column lines with a section letter and
//! a sequence number, fields packed without splitting, reals as the shortest
//! decimals that read back exactly, Hollerith strings.

use std::io::{self, Write};

use crate::text::Out;

/// Columns of data in a Start, Global or Directory Entry line.
pub(super) const DATA_COLUMNS: usize = 72;

/// Columns of data in a Parameter Data line (65–72 hold the back-pointer).
pub(super) const PARAMETER_COLUMNS: usize = 64;

/// The largest sequence number of a line: seven columns.
pub(super) const MAX_SEQUENCE: usize = 9_999_999;

/// Passes `values` to `field` in order as IGES reals, formatted in pieces on
/// every core (formatting is most of the writer's work).
pub(super) fn reals(
    values: &[f64],
    field: &mut dyn FnMut(&[u8]) -> io::Result<()>,
) -> io::Result<()> {
    let pieces = monge_core::tasks::ranges(values.len(), 1 << 10, |r| {
        let mut real = Real::default();
        let (mut text, mut ends) = (Vec::new(), Vec::with_capacity(r.len()));
        for &x in &values[r] {
            text.extend_from_slice(real.format(x));
            ends.push(text.len());
        }
        (text, ends)
    });
    for (text, ends) in pieces {
        let mut start = 0;
        for end in ends {
            field(&text[start..end])?;
            start = end;
        }
    }
    Ok(())
}

/// `text` as an IGES Hollerith string: `5Hmonge`.
pub(super) fn hollerith(text: &str) -> String {
    format!("{}H{text}", text.len())
}

/// The shortest decimal that parses back to `x`, in `E` notation with a decimal point.
pub(super) fn real(x: f64) -> String {
    String::from_utf8(Real::default().format(x).to_vec()).expect("ASCII")
}

/// Formats reals as IGES wants them: the shortest decimal that parses back to
/// the same `f64` (`zmij`), rewritten as `d.dddE±n` (`1.0E0`, `-2.5E-1`,
/// `0.0E0`): the text of `format!("{x:E}")` with `.0` added to a lone digit,
/// except where two shortest decimals are equally near `x`: then zmij takes the
/// even last digit (as Python's `repr`), the standard library the larger one.
#[derive(Default)]
pub(super) struct Real {
    shortest: zmij::Buffer,
    out: Vec<u8>,
}

impl Real {
    /// `x` (finite) in IGES `E` notation.
    pub(super) fn format(&mut self, x: f64) -> &[u8] {
        let text = self.shortest.format_finite(x).as_bytes();
        let (sign, text) = match text.split_first() {
            Some((b'-', rest)) => (true, rest),
            _ => (false, text),
        };
        let (mantissa, exponent) = match text.iter().position(|&c| c == b'e') {
            Some(e) => (
                &text[..e],
                std::str::from_utf8(&text[e + 1..])
                    .ok()
                    .and_then(|t| t.parse::<i32>().ok())
                    .expect("zmij writes an integer exponent"),
            ),
            None => (text, 0),
        };
        // The digits without the point, and the power of ten of the first one.
        let point = mantissa
            .iter()
            .position(|&c| c == b'.')
            .unwrap_or(mantissa.len());
        let digits = mantissa.iter().filter(|&&c| c != b'.');
        let leading = digits.clone().take_while(|&&c| c == b'0').count();
        self.out.clear();
        if sign {
            self.out.push(b'-');
        }
        // At most 17 significant digits, and zeros that pad them (`1e+16` is `1` alone).
        let mut significant = [0u8; 32];
        let mut n = 0;
        for &c in digits.skip(leading) {
            significant[n] = c;
            n += 1;
        }
        let significant = &significant[..n];
        let end = n - significant.iter().rev().take_while(|&&c| c == b'0').count();
        if end == 0 {
            self.out.extend_from_slice(b"0.0E0");
            return &self.out;
        }
        let power = exponent + point as i32 - leading as i32 - 1;
        self.out.push(significant[0]);
        self.out.push(b'.');
        if end > 1 {
            self.out.extend_from_slice(&significant[1..end]);
        } else {
            self.out.push(b'0');
        }
        self.out.push(b'E');
        self.out
            .extend_from_slice(itoa::Buffer::new().format(power).as_bytes());
        &self.out
    }
}

/// Delimited fields packed into lines of at most `width` columns, none split:
/// each field is followed by `,`, the last by `;`; `line` is called with each line.
pub(super) struct Packer<L: FnMut(&[u8]) -> io::Result<()>> {
    width: usize,
    /// The line being filled: fields, each with a `,` after it.
    pub(super) line: Vec<u8>,
    sink: L,
}

impl<L: FnMut(&[u8]) -> io::Result<()>> Packer<L> {
    pub(super) fn new(width: usize, sink: L) -> Self {
        Packer {
            width,
            line: Vec::with_capacity(width),
            sink,
        }
    }

    /// The next field, and its delimiter (`,` now; the last one's becomes `;`).
    pub(super) fn field(&mut self, field: &[u8]) -> io::Result<()> {
        if !self.line.is_empty() && self.line.len() + field.len() + 1 > self.width {
            (self.sink)(&self.line)?;
            self.line.clear();
        }
        self.line.extend_from_slice(field);
        self.line.push(b',');
        Ok(())
    }

    /// Ends the last field with `;` and writes the last line.
    pub(super) fn finish(mut self) -> io::Result<()> {
        if let Some(delimiter) = self.line.last_mut() {
            *delimiter = b';';
        }
        (self.sink)(&self.line)
    }
}

/// One 80-column line: `data` in columns 1–72, the section letter, the sequence number.
pub(super) fn put_line<W: Write + ?Sized>(
    o: &mut Out<'_, W>,
    data: &[u8],
    section: char,
    sequence: usize,
) -> io::Result<()> {
    debug_assert!(data.len() <= DATA_COLUMNS);
    let mut line = [b' '; 80];
    line[..data.len()].copy_from_slice(data);
    line[DATA_COLUMNS] = section as u8;
    let mut digits = itoa::Buffer::new();
    let digits = digits.format(sequence).as_bytes();
    debug_assert!(sequence <= MAX_SEQUENCE);
    line[80 - digits.len()..].copy_from_slice(digits);
    o.bytes(&line);
    o.end()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `{:E}` (the standard library's shortest digits) with `.0` added to a lone digit.
    fn std_real(x: f64) -> String {
        let s = format!("{x:E}");
        match s.find('.') {
            Some(_) => s,
            None => s.replacen('E', ".0E", 1),
        }
    }

    #[test]
    fn reals_are_the_standard_librarys_shortest_digits_in_e_notation() {
        let mut r = Real::default();
        let special = [
            0.0,
            -0.0,
            1.0,
            -2.5e-1,
            0.1,
            1e-7,
            1e15,
            1e16,
            1e17,
            123456789012345680.0,
            1234567890123456.7,
            0.000123,
            f64::MAX,
            f64::MIN_POSITIVE,
            5e-324,
            9007199254740993.0,
        ];
        // Random bit patterns (a fixed-seed sequence), every exponent, and
        // integers and short decimals, which zmij writes without an exponent.
        let mut rng = fastrand::Rng::with_seed(7);
        let mut next = || rng.u64(..);
        let mut values: Vec<f64> = special.to_vec();
        for _ in 0..200_000 {
            let x = f64::from_bits(next());
            if x.is_finite() {
                values.push(x);
            }
            values.push((next() % 100_000_000) as f64 / 1000.0);
            values.push((next() >> 11) as f64 * 10f64.powi((next() % 40) as i32 - 20));
        }
        for x in values {
            let (ours, std) = (std::str::from_utf8(r.format(x)).unwrap(), std_real(x));
            if ours != std {
                // Two shortest decimals equally near x: both read back to x,
                // have the same length, and ours ends in the even digit.
                assert_eq!(ours.len(), std.len(), "{x:?}");
                assert_eq!(ours.parse::<f64>().unwrap(), x, "{x:?}");
                assert_eq!(std.parse::<f64>().unwrap(), x, "{x:?}");
                let last = |s: &str| s.split('E').next().unwrap().bytes().last().unwrap();
                assert_eq!(last(ours) % 2, 0, "{x:?}: {ours} vs {std}");
            }
        }
    }
}
