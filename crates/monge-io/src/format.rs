//! The formats and kinds of file monge reads and writes: plain names, told
//! apart by extension or by top-level keys, with nothing to read or write.
//! The lowest layer of this crate: every other module may use it, it uses none.

use std::fmt;

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
    /// A design or a multi-patch design whose mesh is cut by an outline: the keys
    /// `design` and `trim` (as `monge approximate` writes a trimmed result).
    Trimmed,
}

impl FileKind {
    /// The kind whose top-level keys `keys` has, if any: `vertices` or `rows`
    /// makes a mesh (a multi-patch mesh also has `patches`), then `developable`,
    /// `trim`, `patches`, any of the four planes, and any of a design's keys.
    pub fn from_keys(keys: &[&str]) -> Option<FileKind> {
        let has = |names: &[&str]| keys.iter().any(|k| names.contains(k));
        [
            (FileKind::Mesh, &["vertices", "rows"][..]),
            (FileKind::Developable, &["developable"]),
            (FileKind::Trimmed, &["trim"]),
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
            FileKind::Trimmed => {
                "`monge generate`, which writes its mesh trimmed (or `info`, `render`; its \
                 `design` is the design before trimming, for the other commands)"
            }
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
            FileKind::Trimmed => "a trimmed design (a design and the outline its mesh is cut by)",
        })
    }
}

/// The two design-file formats.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DesignFormat {
    /// JSON (`.json`).
    Json,
    /// TOML (`.toml`).
    Toml,
}

/// A mesh file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MeshFormat {
    /// Wavefront OBJ (`.obj`).
    Obj,
    /// ASCII PLY with `double` coordinates (`.ply`).
    Ply,
    /// Binary little-endian PLY with `double` coordinates (`.ply`; format
    /// name `ply-binary`): exact, a third of the size of ASCII.
    PlyBinary,
    /// Binary little-endian PLY with `float` (f32) coordinates (`.ply`;
    /// format name `ply-f32`): for viewers, about 1e-7 of the model size.
    PlyF32,
    /// `{"rows", "cols", "vertices", "normals"}` JSON (`.json`).
    Json,
    /// Binary glTF (`.glb`), for viewers: `f32` positions, so written but never
    /// read back (see [`crate::write_grid_glb`]).
    Glb,
}

impl MeshFormat {
    /// The format named by an extension or format name such as `obj`, `.PLY`,
    /// `json` or `ply-binary` (`.ply` alone is ASCII PLY).
    ///
    /// ```
    /// use monge_io::MeshFormat;
    /// assert_eq!(MeshFormat::from_extension(".PLY"), Some(MeshFormat::Ply));
    /// assert_eq!(MeshFormat::from_extension("ply-f32"), Some(MeshFormat::PlyF32));
    /// assert_eq!(MeshFormat::from_extension("stl"), None);
    /// ```
    pub fn from_extension(ext: &str) -> Option<MeshFormat> {
        let ext = ext.strip_prefix('.').unwrap_or(ext);
        [
            MeshFormat::Obj,
            MeshFormat::Ply,
            MeshFormat::PlyBinary,
            MeshFormat::PlyF32,
            MeshFormat::Json,
            MeshFormat::Glb,
        ]
        .into_iter()
        .find(|f| f.extension().eq_ignore_ascii_case(ext) || f.name().eq_ignore_ascii_case(ext))
    }

    /// The usual extension, without the dot: `obj`, `ply`, `json` or `glb`.
    pub fn extension(self) -> &'static str {
        match self {
            MeshFormat::Obj => "obj",
            MeshFormat::Ply | MeshFormat::PlyBinary | MeshFormat::PlyF32 => "ply",
            MeshFormat::Json => "json",
            MeshFormat::Glb => "glb",
        }
    }

    /// The format's name: its extension, or `ply-binary`, `ply-f32` for binary PLY.
    pub fn name(self) -> &'static str {
        match self {
            MeshFormat::PlyBinary => "ply-binary",
            MeshFormat::PlyF32 => "ply-f32",
            other => other.extension(),
        }
    }
}
