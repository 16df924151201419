//! Parsers and kinds of command-line values that several commands take.

use std::ffi::OsStr;
use std::path::Path;

use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use clap::error::ErrorKind;
use clap::ValueEnum;
use monge_core::MeshKind;
use monge_io::{is_stdio, MeshFormat};

/// A `--format` value: one of a list of [`MeshFormat`]s, each named by
/// [`MeshFormat::name`] and described in the help by its text.
#[derive(Clone, Copy, Debug)]
pub struct MeshFormats(&'static [(MeshFormat, &'static str)]);

/// The mesh formats a command writes.
pub const WRITTEN_FORMATS: MeshFormats = MeshFormats(&[
    (MeshFormat::Obj, "Wavefront OBJ"),
    (MeshFormat::Ply, "ASCII PLY"),
    (
        MeshFormat::PlyBinary,
        "Binary little-endian PLY, `double` coordinates (exact; `.ply`)",
    ),
    (
        MeshFormat::PlyF32,
        "Binary little-endian PLY, `float` coordinates (f32, for viewers; `.ply`)",
    ),
    (MeshFormat::Json, JSON_HELP),
    (
        MeshFormat::Glb,
        "Binary glTF, for viewers (f32 coordinates; not read back by `check`)",
    ),
]);

/// The mesh formats that are read back (glTF is written for viewers only, in f32;
/// `ply` reads binary PLY too).
pub const READ_FORMATS: MeshFormats = MeshFormats(&[
    (MeshFormat::Obj, "Wavefront OBJ"),
    (MeshFormat::Ply, "PLY, ASCII or binary little-endian"),
    (MeshFormat::Json, JSON_HELP),
]);

/// The help of the JSON mesh format.
const JSON_HELP: &str = "JSON (`rows`, `cols`, `vertices`, `normals`)";

impl MeshFormats {
    /// The names and help texts, as clap lists them.
    fn values(self) -> impl Iterator<Item = PossibleValue> {
        self.0
            .iter()
            .map(|&(format, help)| PossibleValue::new(format.name()).help(help))
    }
}

impl TypedValueParser for MeshFormats {
    type Value = MeshFormat;

    /// clap checks the name (and words the error of a wrong one); the format is
    /// then the one of that name.
    fn parse_ref(
        &self,
        cmd: &clap::Command,
        arg: Option<&clap::Arg>,
        value: &OsStr,
    ) -> Result<MeshFormat, clap::Error> {
        let name = PossibleValuesParser::new(self.values()).parse_ref(cmd, arg, value)?;
        self.0
            .iter()
            .map(|&(format, _)| format)
            .find(|format| format.name().eq_ignore_ascii_case(&name))
            .ok_or_else(|| clap::Error::new(ErrorKind::InvalidValue).with_cmd(cmd))
    }

    fn possible_values(&self) -> Option<Box<dyn Iterator<Item = PossibleValue> + '_>> {
        Some(Box::new(self.values()))
    }
}

/// The format of a mesh output OUT: `--format`, else OUT's extension (JSON for
/// `-`); a `--format` that contradicts OUT's extension is refused.
pub fn output_format(format: Option<MeshFormat>, out: &Path) -> anyhow::Result<MeshFormat> {
    if is_stdio(out) {
        return Ok(format.unwrap_or(MeshFormat::Json));
    }
    let Some(format) = format else {
        return Ok(MeshFormat::from_path(out)?);
    };
    match MeshFormat::from_path(out) {
        Ok(by_extension) if by_extension.extension() != format.extension() => anyhow::bail!(
            "--format {} but OUT `{}` ends in `.{}`: name it `.{f}`, or leave --format out",
            format.name(),
            out.display(),
            by_extension.extension(),
            f = format.extension()
        ),
        _ => Ok(format),
    }
}

/// What kind of mesh a command measures or makes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum KindArg {
    /// A circular mesh: planar circular faces, planar lines, torsion-free node axes (§2.2).
    Circular,
    /// A conical mesh: planar faces tangent to a cone at each vertex, planar lines (§2.3).
    Conical,
}

impl From<MeshKind> for KindArg {
    fn from(kind: MeshKind) -> Self {
        match kind {
            MeshKind::Circular => KindArg::Circular,
            MeshKind::Conical => KindArg::Conical,
        }
    }
}

impl From<KindArg> for MeshKind {
    fn from(kind: KindArg) -> Self {
        match kind {
            KindArg::Circular => MeshKind::Circular,
            KindArg::Conical => MeshKind::Conical,
        }
    }
}

/// A finite number (`--offset`, `--theta-sweep`, `--layers`).
pub fn parse_finite(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(format!("`{s}` is not a finite number")),
    }
}

/// A finite, non-negative number (tolerances and sizes).
pub fn parse_non_negative(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(x) if x.is_finite() && x >= 0.0 => Ok(x),
        _ => Err(format!("`{s}` is not a finite, non-negative number")),
    }
}

/// `--tol`: a finite, non-negative number; text that is no number at all is
/// called so.
pub fn parse_tolerance(s: &str) -> Result<f64, String> {
    s.trim()
        .parse::<f64>()
        .map_err(|_| format!("`{s}` is not a number"))?;
    parse_non_negative(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tolerance_must_be_finite_and_non_negative() {
        assert_eq!(parse_tolerance("1e-6"), Ok(1e-6));
        assert_eq!(
            parse_tolerance("-1"),
            Err("`-1` is not a finite, non-negative number".to_owned())
        );
        assert_eq!(
            parse_tolerance("nan"),
            Err("`nan` is not a finite, non-negative number".to_owned())
        );
        assert_eq!(parse_tolerance("x"), Err("`x` is not a number".to_owned()));
    }

    #[test]
    fn formats_are_named_as_monge_io_names_them() {
        let cmd = clap::Command::new("t");
        for (formats, names) in [
            (WRITTEN_FORMATS, "obj ply ply-binary ply-f32 json glb"),
            (READ_FORMATS, "obj ply json"),
        ] {
            let listed: Vec<String> = formats.values().map(|v| v.get_name().to_owned()).collect();
            assert_eq!(listed.join(" "), names);
            for name in listed {
                let format = formats.parse_ref(&cmd, None, OsStr::new(&name)).unwrap();
                assert_eq!(MeshFormat::from_extension(&name), Some(format));
            }
        }
        assert!(READ_FORMATS
            .parse_ref(&cmd, None, OsStr::new("glb"))
            .is_err());
    }
}
