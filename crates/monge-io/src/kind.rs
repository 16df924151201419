//! The kinds of JSON/TOML file monge reads, told apart by their top-level keys,
//! so that a file given to the wrong command is named with the command that takes it.

use std::fmt;

use crate::design::DesignFormat;
use crate::error::IoError;

/// A kind of file monge reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FileKind {
    /// A design: two guides and θ (§3), keys `theta_deg`, `guide_u`, `guide_v`.
    Design,
    /// A developable design (§3.3): the key `developable`.
    Developable,
    /// A multi-patch design (§4.7): the key `patches`.
    MultiPatch,
    /// Four boundary planes (§4.5): `first_row`, `last_row`, `first_column`, `last_column`.
    Planes,
    /// A quad mesh: `rows`, `cols`, `vertices` (as `monge generate` writes it).
    Mesh,
}

impl FileKind {
    /// The kind whose top-level keys `keys` has, if any: `vertices` or `rows`
    /// makes a mesh (a multi-patch mesh also has `patches`), then `developable`,
    /// `patches`, any of the four planes, and any of a design's keys.
    pub fn from_keys(keys: &[&str]) -> Option<FileKind> {
        let has = |names: &[&str]| keys.iter().any(|k| names.contains(k));
        [
            (FileKind::Mesh, &["vertices", "rows"][..]),
            (FileKind::Developable, &["developable"]),
            (FileKind::MultiPatch, &["patches"]),
            (
                FileKind::Planes,
                &["first_row", "last_row", "first_column", "last_column"],
            ),
            (FileKind::Design, &["theta_deg", "guide_u", "guide_v"]),
        ]
        .into_iter()
        .find(|(_, names)| has(names))
        .map(|(kind, _)| kind)
    }

    /// The kind of a JSON or TOML text by its top-level keys; `None` if it does
    /// not parse as a table or has none of the keys of [`FileKind::from_keys`].
    ///
    /// ```
    /// use monge_io::{DesignFormat, FileKind};
    /// let kind = FileKind::of_text(r#"{"patches": []}"#, DesignFormat::Json);
    /// assert_eq!(kind, Some(FileKind::MultiPatch));
    /// assert_eq!(FileKind::of_text("theta_deg = 3", DesignFormat::Toml), Some(FileKind::Design));
    /// ```
    pub fn of_text(text: &str, format: DesignFormat) -> Option<FileKind> {
        // The keys only: the values are read past, not built (a design's
        // points as a tree of values took 16 times the file's size).
        type Keys = std::collections::BTreeMap<String, serde::de::IgnoredAny>;
        let keys: Keys = match format {
            DesignFormat::Json => serde_json::from_str(text).ok()?,
            DesignFormat::Toml => toml::from_str(text).ok()?,
        };
        let keys: Vec<&str> = keys.keys().map(String::as_str).collect();
        FileKind::from_keys(&keys)
    }

    /// The commands that read this kind of file, for error messages.
    pub fn commands(self) -> &'static str {
        match self {
            FileKind::Design => {
                "`monge generate` (or `info`, `smooth`, `render`, `fabricate`, `scan`, \
                 `optimise-panels`, `explore`)"
            }
            FileKind::Developable => "`monge generate` (or `info`, `render`)",
            FileKind::MultiPatch => "`monge patches` (or `monge fit` when it has a `fit` key)",
            FileKind::Planes => "`monge align`",
            FileKind::Mesh => "`monge check` (or `monge smooth --mesh`)",
        }
    }
}

impl fmt::Display for FileKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            FileKind::Design => "a design (two guides and θ)",
            FileKind::Developable => "a developable design (§3.3)",
            FileKind::MultiPatch => "a multi-patch design (§4.7)",
            FileKind::Planes => "a planes file (§4.5)",
            FileKind::Mesh => "a mesh",
        })
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
