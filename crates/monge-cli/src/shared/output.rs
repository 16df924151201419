//! Printing without panicking, and number formats shared by the commands.

use std::io::{self, Write};

use anyhow::Context;
use glam::DVec3;
use monge_core::design::Xyz;
use monge_io::generated::far_from_origin;

/// Writes `text` to standard output and flushes it; a closed pipe is an error
/// (never a panic).
pub fn print(text: &str) -> anyhow::Result<()> {
    let mut out = io::stdout().lock();
    out.write_all(text.as_bytes())
        .and_then(|()| out.flush())
        .context("cannot write to standard output")
}

/// Writes `text` to standard error, ignoring failure (there is nowhere left to report it).
pub fn eprint(text: &str) {
    let _ = io::stderr().lock().write_all(text.as_bytes());
}

/// The warning of `generate` and `info` when the coordinates lie so far from the
/// origin, compared with the design's size, that f64 output cannot hold the mesh
/// to 1e-9 of its size (`None` otherwise).
pub fn far_from_origin_warning(points: &[DVec3]) -> Option<String> {
    far_from_origin(points).map(|m| format!("warning: {m}\n"))
}

/// The warning line of a mesh whose measured error exceeds the tolerance
/// ([`monge_io::generated::inexact`]: the error and its likely cause), or an
/// empty string.
pub fn inexact_warning(
    what: &str,
    max_error: f64,
    tolerance: f64,
    points: &[DVec3],
    folded_faces: usize,
    theta_deg: Option<f64>,
) -> String {
    monge_io::generated::inexact(what, max_error, tolerance, points, folded_faces, theta_deg)
        .map(|m| format!("warning: {m}\n"))
        .unwrap_or_default()
}

/// A point or vector as `(x, y, z)` with 6 significant digits.
pub fn xyz(p: Xyz) -> String {
    format!("({}, {}, {})", num(p[0]), num(p[1]), num(p[2]))
}

/// A number with up to 6 significant digits, without trailing zeros
/// (`0.707107`, `1`, `-2.5`, `1.2e-7`).
pub fn num(x: f64) -> String {
    if x == 0.0 {
        return "0".to_owned();
    }
    let magnitude = x.abs().log10().floor();
    if !(-4.0..6.0).contains(&magnitude) {
        let s = format!("{x:.5e}");
        return match s.split_once('e') {
            Some((mantissa, exponent)) => format!("{}e{exponent}", trim_zeros(mantissa)),
            None => s,
        };
    }
    let decimals = (5.0 - magnitude).max(0.0) as usize;
    trim_zeros(&format!("{x:.decimals$}")).to_owned()
}

/// `s` without the trailing zeros of its fraction (and without a bare `.`).
fn trim_zeros(s: &str) -> &str {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.')
    } else {
        s
    }
}

/// Milliseconds with 3 significant digits.
pub fn millis(seconds: f64) -> String {
    let ms = seconds * 1e3;
    if ms >= 100.0 {
        format!("{ms:.0}")
    } else if ms >= 10.0 {
        format!("{ms:.1}")
    } else {
        format!("{ms:.2}")
    }
}

/// Default of `--max-output`, in gigabytes (10⁹ bytes): the largest output a
/// command writes without being asked to (a few times what one `write_all` of the
/// 1000 × 1000-face mesh's coordinates takes).
pub const MAX_OUTPUT_GB: f64 = 8.0;

/// Refuses an output estimated at `bytes` above `max_gb` gigabytes, before
/// anything is computed or written: `what` names the output and how its size
/// comes about, `lower` says which option makes it smaller.
pub fn check_output_size(bytes: f64, max_gb: f64, what: &str, lower: &str) -> anyhow::Result<()> {
    if bytes > max_gb * 1e9 {
        anyhow::bail!(
            "{what} would be about {}, above the limit of {} GB: {lower}, or raise the limit \
             with --max-output GB",
            if bytes >= 1e9 {
                format!("{:.1} GB", bytes / 1e9)
            } else {
                format!("{:.0} MB", bytes / 1e6)
            },
            num(max_gb)
        );
    }
    Ok(())
}

/// `--max-output`: a finite, positive number of gigabytes.
pub fn parse_gigabytes(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(x) if x.is_finite() && x > 0.0 => Ok(x),
        _ => Err(format!(
            "`{s}` is not a finite, positive number of gigabytes"
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_short() {
        assert_eq!(num(0.0), "0");
        assert_eq!(num(1.0), "1");
        assert_eq!(num(-2.5), "-2.5");
        assert_eq!(num(std::f64::consts::FRAC_1_SQRT_2), "0.707107");
        assert_eq!(num(1.2e-7), "1.2e-7");
        assert_eq!(num(123456789.0), "1.23457e8");
        assert_eq!(num(61.927513), "61.9275");
        assert_eq!(xyz([1.0, 0.0, -0.5]), "(1, 0, -0.5)");
    }

    #[test]
    fn milliseconds_have_three_digits() {
        assert_eq!(millis(0.0012345), "1.23");
        assert_eq!(millis(0.012345), "12.3");
        assert_eq!(millis(0.12345), "123");
    }
}
