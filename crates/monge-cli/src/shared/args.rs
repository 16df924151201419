//! Parsers and kinds of command-line values that several commands take.

use std::ffi::OsStr;
use std::path::{Path, PathBuf};

use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use clap::error::ErrorKind;
use monge_core::MeshKind;
use monge_io::generated::kind_name;
use monge_io::{check_output, is_stdio, MeshFormat};

/// A value named on the command line by one word.
pub trait Named: Copy + Send + Sync + 'static {
    /// The word.
    fn name(self) -> &'static str;
}

impl Named for MeshFormat {
    /// [`MeshFormat::name`].
    fn name(self) -> &'static str {
        MeshFormat::name(self)
    }
}

impl Named for MeshKind {
    /// The name a JSON mesh gives its kind ([`kind_name`]).
    fn name(self) -> &'static str {
        kind_name(self)
    }
}

/// A command-line value that is one of a list of values, each named by
/// [`Named::name`] and described in the help by its text.
#[derive(Clone, Copy, Debug)]
pub struct Choices<T: 'static>(&'static [(T, &'static str)]);

/// The mesh formats a command writes.
pub const WRITTEN_FORMATS: Choices<MeshFormat> = Choices(&[
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
pub const READ_FORMATS: Choices<MeshFormat> = Choices(&[
    (MeshFormat::Obj, "Wavefront OBJ"),
    (MeshFormat::Ply, "PLY, ASCII or binary little-endian"),
    (MeshFormat::Json, JSON_HELP),
]);

/// The help of the JSON mesh format.
const JSON_HELP: &str = "JSON (`rows`, `cols`, `vertices`, `normals`)";

/// The kinds of mesh a command measures or makes (`--kind`).
pub const KINDS: Choices<MeshKind> = Choices(&[
    (
        MeshKind::Circular,
        "A circular mesh: planar circular faces, planar lines, torsion-free node axes (§2.2)",
    ),
    (
        MeshKind::Conical,
        "A conical mesh: planar faces tangent to a cone at each vertex, planar lines (§2.3)",
    ),
]);

impl<T: Named> Choices<T> {
    /// The names and help texts, as clap lists them.
    fn values(self) -> impl Iterator<Item = PossibleValue> {
        self.0
            .iter()
            .map(|&(value, help)| PossibleValue::new(value.name()).help(help))
    }
}

impl<T: Named> TypedValueParser for Choices<T> {
    type Value = T;

    /// clap checks the name (and words the error of a wrong one); the value is
    /// then the one of that name.
    fn parse_ref(
        &self,
        cmd: &clap::Command,
        arg: Option<&clap::Arg>,
        value: &OsStr,
    ) -> Result<T, clap::Error> {
        let name = PossibleValuesParser::new(self.values()).parse_ref(cmd, arg, value)?;
        self.0
            .iter()
            .map(|&(value, _)| value)
            .find(|value| value.name().eq_ignore_ascii_case(&name))
            .ok_or_else(|| clap::Error::new(ErrorKind::InvalidValue).with_cmd(cmd))
    }

    fn possible_values(&self) -> Option<Box<dyn Iterator<Item = PossibleValue> + '_>> {
        Some(Box::new(self.values()))
    }
}

/// The mesh file a command writes (`monge generate`, `monge patches`): OUT and
/// its `--format`.
#[derive(Debug, clap::Args)]
pub struct MeshOutput {
    /// Output file (`.obj`, `.ply` or `.json`), or `-` for standard output.
    #[arg(short, long, value_name = "OUT")]
    pub output: PathBuf,
    /// Output format, for `-o -` (default json) or an OUT whose extension names none; it must
    /// agree with OUT's extension.
    #[arg(long, value_parser = WRITTEN_FORMATS)]
    pub format: Option<MeshFormat>,
}

impl MeshOutput {
    /// The format OUT is written in, once OUT is known to be writable without
    /// overwriting any of `inputs` ([`check_output`]): all checked before the work.
    pub fn checked_format(&self, inputs: &[&Path]) -> anyhow::Result<MeshFormat> {
        let format = output_format(self.format, &self.output)?;
        check_output(&self.output, inputs)?;
        Ok(format)
    }
}

/// The format of a mesh output OUT: `--format`, else OUT's extension (JSON for
/// `-`); a `--format` that contradicts OUT's extension is refused.
fn output_format(format: Option<MeshFormat>, out: &Path) -> anyhow::Result<MeshFormat> {
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

    /// `--kind` names every kind as a JSON mesh and a design file name it: the
    /// names monge-io writes, read back by the design's own (serde) reader.
    #[test]
    fn kinds_are_named_as_monge_io_names_them() {
        let cmd = clap::Command::new("t");
        let every = [MeshKind::Circular, MeshKind::Conical];
        // Until a kind added to monge-core is listed here, this does not compile.
        for kind in every {
            match kind {
                MeshKind::Circular | MeshKind::Conical => {}
            }
        }
        let io_names: Vec<&str> = every.iter().map(|&k| kind_name(k)).collect();
        let listed: Vec<String> = KINDS.values().map(|v| v.get_name().to_owned()).collect();
        assert_eq!(listed, io_names);
        assert_eq!(listed.join(" "), "circular conical");
        for (name, kind) in listed.iter().zip(every) {
            assert_eq!(KINDS.parse_ref(&cmd, None, OsStr::new(name)).unwrap(), kind);
            let read: MeshKind = serde_json::from_value(serde_json::json!(name)).unwrap();
            assert_eq!(read, kind);
        }
        assert!(KINDS.parse_ref(&cmd, None, OsStr::new("bogus")).is_err());
    }
}
