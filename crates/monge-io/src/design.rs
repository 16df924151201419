//! Design files: a [`Design`] as JSON or TOML.

use std::io::{self, Write};
use std::path::Path;

use monge_core::design::{Design, GuideSpec, THIS_GUIDE};
use serde::de::DeserializeOwned;
use serde::Serialize;

use crate::atomic::Outputs;
use crate::error::IoError;
use crate::format::{DesignFormat, FileKind};
use crate::kind::expect_kind;
use crate::read::{path_name, read_error, read_unchanged, utf8};

/// File name used in error messages for text that did not come from a file.
pub(crate) const NO_FILE: &str = "<input>";

/// The largest design file read, of any kind (a design, a developable or
/// multi-patch design, a planes file), in bytes: 16 MiB. A design is a few kB;
/// reading one costs a few times its size in memory (up to about 20 times in
/// TOML), so that a larger file is refused before it is read.
pub const MAX_DESIGN_BYTES: u64 = 16 << 20;

/// [`IoError::DesignTooLarge`] if a design file of `size` bytes is over [`MAX_DESIGN_BYTES`].
fn check_design_size(size: u64, file: &str) -> Result<(), IoError> {
    if size > MAX_DESIGN_BYTES {
        return Err(IoError::DesignTooLarge {
            file: file.to_owned(),
            size,
            limit: MAX_DESIGN_BYTES,
        });
    }
    Ok(())
}

/// The text of the design file `path` (of any kind): one over
/// [`MAX_DESIGN_BYTES`] is refused by its length before it is read (a stream,
/// once more has been read).
pub(crate) fn read_design_text(path: &Path) -> Result<String, IoError> {
    let file = std::fs::File::open(path).map_err(|source| read_error(path, source))?;
    let opened = file.metadata().map_err(|source| read_error(path, source))?;
    check_design_size(opened.len(), &path_name(path))?;
    let bytes = read_unchanged(path, file, &opened, MAX_DESIGN_BYTES + 1)?;
    check_design_size(bytes.len() as u64, &path_name(path))?;
    utf8(path, bytes)
}

/// The kind of the design text `text` (of any kind) if recognisable, after
/// checking its size ([`MAX_DESIGN_BYTES`]) and that it is one of `expected`
/// (see [`expect_kind`]): what every design parser checks first.
pub(crate) fn expect_design(
    text: &str,
    format: DesignFormat,
    file: &str,
    expected: &[FileKind],
) -> Result<Option<FileKind>, IoError> {
    check_design_size(text.len() as u64, file)?;
    expect_kind(text, format, file, expected)
}

/// Reads a design file, JSON or TOML by its extension.
///
/// Errors: [`IoError::UnknownExtension`], [`IoError::NotFound`],
/// [`IoError::Read`], [`IoError::DesignTooLarge`], [`IoError::Parse`] (with line, column and what was
/// expected) and [`IoError::NonFinite`].
pub fn read_design(path: &Path) -> Result<Design, IoError> {
    let format = DesignFormat::from_path(path)?;
    let text = read_design_text(path)?;
    parse_design_named(&text, format, &path_name(path))
}

/// Parses the text of a design file.
///
/// Error messages name the file `<input>`.
///
/// ```
/// use monge_io::{parse_design, DesignFormat};
/// let d = parse_design(r#"
/// theta_deg = 30.0
/// guide_u.points = [[0, 0, 0], [1, 0, 0.2], [2, 0, 0.7]]
/// guide_v.arc = { center = [0, 0, -1], start = [0, 0, 0], normal = [-1, 0, 0], angle_deg = 60, samples = 5 }
/// "#, DesignFormat::Toml).unwrap();
/// assert_eq!(d.theta_deg, 30.0);
/// assert_eq!(d.guide_v.sample_count(), 5);
/// ```
pub fn parse_design(text: &str, format: DesignFormat) -> Result<Design, IoError> {
    parse_design_named(text, format, NO_FILE)
}

/// [`parse_design`] of the contents of `file` (named in the messages, e.g.
/// `design.json:3:7: …`).
pub fn parse_design_named(text: &str, format: DesignFormat, file: &str) -> Result<Design, IoError> {
    expect_design(text, format, file, &[FileKind::Design])?;
    parse_as(text, format, file)
}

/// `text` deserialised as a `T`, with [`IoError::Parse`] locating what is wrong,
/// or [`IoError::NonFinite`] naming the key of a TOML `nan` or `inf` (JSON has
/// neither).
pub(crate) fn parse_as<T: DeserializeOwned>(
    text: &str,
    format: DesignFormat,
    file: &str,
) -> Result<T, IoError> {
    match format {
        DesignFormat::Json => {
            let mut de = serde_json::Deserializer::from_str(text);
            let value = serde_path_to_error::deserialize(&mut de).map_err(|e| {
                let (inner, path) = (e.inner(), e.path().to_string());
                let message = plain_message(&json_message(inner), &path);
                IoError::parse_at_line(file, text, inner.line(), inner.column(), message)
            })?;
            de.end().map_err(|e| json_error(file, text, &e))?;
            Ok(value)
        }
        DesignFormat::Toml => {
            let toml_error = |e: &toml::de::Error, message: String| {
                let offset = e.span().map(|s| s.start);
                IoError::parse_at(file, text, offset, message)
            };
            let plain = |e: toml::de::Error| {
                let message = e.message().trim_end().to_owned();
                toml_error(&e, message)
            };
            // TOML's non-finite numbers are `nan` and `inf` (signed or not):
            // a text without them needs no tree of values to find them in.
            if text.contains("nan") || text.contains("inf") {
                let value: toml::Value = toml::from_str(text).map_err(plain)?;
                if let Some(key) = non_finite(&value, String::new()) {
                    return Err(IoError::NonFinite {
                        file: file.to_owned(),
                        key,
                    });
                }
            }
            let de = toml::Deserializer::parse(text).map_err(plain)?;
            serde_path_to_error::deserialize(de).map_err(|e| {
                let message = e.inner().message().trim_end();
                toml_error(e.inner(), plain_message(message, &e.path().to_string()))
            })
        }
    }
}

/// serde's `invalid type: string "20", expected f64` at `theta_deg` in words:
/// `theta_deg must be a number, got the string "20"`; a guide that is not one
/// curve named by its key (`guide_u has several curves …`,
/// [`monge_core::design::GuideSpecError`]); other messages as they are.
fn plain_message(message: &str, path: &str) -> String {
    if let Some(rest) = message.strip_prefix(THIS_GUIDE) {
        if !path.is_empty() && path != "." {
            return format!("{path}{rest}");
        }
    }
    let wrong = message
        .strip_prefix("invalid type: ")
        .or_else(|| message.strip_prefix("invalid value: "))
        .and_then(|rest| rest.split_once(", expected "));
    let Some((found, expected)) = wrong.filter(|_| !path.is_empty() && path != ".") else {
        return message.to_owned();
    };
    let expected = match expected {
        "f64" | "f32" => "a number",
        "usize" | "u64" | "u32" | "u16" | "u8" => "a whole number ≥ 0",
        "isize" | "i64" | "i32" | "i16" | "i8" => "a whole number",
        "a sequence" => "a list",
        "a boolean" => "true or false",
        e if e.starts_with("struct ") || e == "a map" => "a table ({…})",
        e => e,
    };
    let unquote = |s: &str| s.trim_matches('`').to_owned();
    let found = if let Some(s) = found.strip_prefix("string ") {
        format!("the string {s}")
    } else if let Some(n) = found.strip_prefix("integer ") {
        format!("the whole number {}", unquote(n))
    } else if let Some(x) = found.strip_prefix("floating point ") {
        format!("the number {}", unquote(x))
    } else if let Some(b) = found.strip_prefix("boolean ") {
        unquote(b)
    } else {
        match found {
            "sequence" => "a list".to_owned(),
            "map" => "a table".to_owned(),
            f => f.to_owned(),
        }
    };
    format!("{path} must be {expected}, got {found}")
}

/// The key path of the first non-finite float in a TOML value.
fn non_finite(value: &toml::Value, key: String) -> Option<String> {
    match value {
        toml::Value::Float(x) if !x.is_finite() => Some(key),
        toml::Value::Array(items) => items
            .iter()
            .enumerate()
            .find_map(|(k, v)| non_finite(v, format!("{key}[{k}]"))),
        toml::Value::Table(t) => t.iter().find_map(|(name, v)| {
            let key = if key.is_empty() {
                name.clone()
            } else {
                format!("{key}.{name}")
            };
            non_finite(v, key)
        }),
        _ => None,
    }
}

/// An [`IoError::Parse`] from a serde_json error on `text`.
pub(crate) fn json_error(file: &str, text: &str, e: &serde_json::Error) -> IoError {
    IoError::parse_at_line(file, text, e.line(), e.column(), json_message(e))
}

/// The message of a serde_json error without the " at line L column C" it appends.
fn json_message(e: &serde_json::Error) -> String {
    let full = e.to_string();
    let suffix = format!(" at line {} column {}", e.line(), e.column());
    full.strip_suffix(&suffix).unwrap_or(&full).to_owned()
}

/// Writes a design file, pretty JSON or TOML by the path's extension, atomically.
///
/// Refuses non-finite numbers ([`IoError::NonFinite`]), which neither format
/// could read back.
pub fn write_design(design: &Design, path: &Path) -> Result<(), IoError> {
    let mut out = Outputs::new();
    write_design_into(design, path, &mut out)?;
    out.commit()
}

/// [`write_design`] as one of several files of `out`, put in place by its commit.
pub fn write_design_into(design: &Design, path: &Path, out: &mut Outputs) -> Result<(), IoError> {
    let format = DesignFormat::from_path(path)?;
    check_finite(design, &path_name(path))?;
    out.write(path, |w| write_design_to(design, format, w))
}

/// Writes a design to `w` as pretty JSON or TOML (non-finite numbers are written
/// as JSON's `null` or TOML's `nan`/`inf`: check first if that matters).
pub fn write_design_to<W: Write + ?Sized>(
    design: &Design,
    format: DesignFormat,
    w: &mut W,
) -> io::Result<()> {
    write_pretty(design, format, w)
}

/// Writes any design file's value to `w` as pretty JSON or TOML.
pub(crate) fn write_pretty<T: Serialize, W: Write + ?Sized>(
    value: &T,
    format: DesignFormat,
    w: &mut W,
) -> io::Result<()> {
    match format {
        DesignFormat::Json => {
            serde_json::to_writer_pretty(&mut *w, value)?;
            w.write_all(b"\n")
        }
        DesignFormat::Toml => {
            let text = toml::to_string_pretty(value)
                .map_err(|e| io::Error::new(io::ErrorKind::InvalidData, e))?;
            w.write_all(text.as_bytes())
        }
    }
}

/// [`IoError::NonFinite`] naming the first non-finite number of `design`.
pub(crate) fn check_finite(design: &Design, file: &str) -> Result<(), IoError> {
    let mut bad = None;
    let mut check = |key: &dyn Fn() -> String, x: f64| {
        if bad.is_none() && !x.is_finite() {
            bad = Some(key());
        }
    };
    check(&|| "theta_deg".to_owned(), design.theta_deg);
    if let Some(t) = &design.tolerance {
        check(&|| "tolerance.planarity".to_owned(), t.planarity);
        check(&|| "tolerance.angle".to_owned(), t.angle);
        check(&|| "tolerance.start".to_owned(), t.start);
    }
    for (name, guide) in [("guide_u", &design.guide_u), ("guide_v", &design.guide_v)] {
        visit_guide(name, guide, &mut check);
    }
    match bad {
        Some(key) => Err(IoError::NonFinite {
            file: file.to_owned(),
            key,
        }),
        None => Ok(()),
    }
}

/// A callback receiving each number with a function that names its key path.
type Check<'a> = dyn FnMut(&dyn Fn() -> String, f64) + 'a;

/// Calls `check` on every number of a guide.
fn visit_guide(name: &str, g: &GuideSpec, check: &mut Check<'_>) {
    fn xyz(check: &mut Check<'_>, key: &dyn Fn() -> String, p: &[f64; 3]) {
        for (k, &x) in p.iter().enumerate() {
            check(&|| format!("{}[{k}]", key()), x);
        }
    }
    fn list(check: &mut Check<'_>, key: &dyn Fn() -> String, ps: &[[f64; 3]]) {
        for (n, p) in ps.iter().enumerate() {
            xyz(check, &|| format!("{}[{n}]", key()), p);
        }
    }
    match g {
        GuideSpec::Points { points, tangent } => {
            list(check, &|| format!("{name}.points"), points);
            if let Some(t) = tangent {
                xyz(check, &|| format!("{name}.tangent"), t);
            }
        }
        GuideSpec::BSpline { bspline: b, .. } => {
            list(
                check,
                &|| format!("{name}.bspline.control_points"),
                &b.control_points,
            );
            for (key, values) in [("knots", &b.knots), ("weights", &b.weights)] {
                for (n, &x) in values.iter().flatten().enumerate() {
                    check(&|| format!("{name}.bspline.{key}[{n}]"), x);
                }
            }
        }
        GuideSpec::Arc(a) => {
            xyz(check, &|| format!("{name}.arc.center"), &a.center);
            xyz(check, &|| format!("{name}.arc.start"), &a.start);
            xyz(check, &|| format!("{name}.arc.normal"), &a.normal);
            check(&|| format!("{name}.arc.angle_deg"), a.angle_deg);
        }
        GuideSpec::Parabola(p) => {
            xyz(check, &|| format!("{name}.parabola.start"), &p.start);
            xyz(check, &|| format!("{name}.parabola.tangent"), &p.tangent);
            xyz(
                check,
                &|| format!("{name}.parabola.quadratic"),
                &p.quadratic,
            );
        }
    }
}
