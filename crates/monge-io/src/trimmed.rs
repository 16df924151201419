//! Trimmed design files: a design, or a multi-patch design (§4.7), and the outline its
//! mesh is cut by (`monge approximate`'s result where it covers the target and is
//! trimmed to its outline).

use std::collections::BTreeMap;
use std::path::Path;

use monge_core::approximate::{trim, FitDesign, Outline, TrimmedMesh};
use monge_core::design::Design;
use monge_core::multipatch::{build, MultiPatchDesign, MultiPatchError};
use monge_core::{generate, GenerateError, GenerateOptions, QuadGrid};
use serde::de::IgnoredAny;
use serde::{Deserialize, Serialize};

use crate::atomic::Outputs;
use crate::design::{check_finite, parse_as, write_pretty};
use crate::error::IoError;
use crate::format::DesignFormat;
use crate::read::path_name;

/// A design whose mesh is cut by an outline: the file's keys `design` (the design
/// before trimming: a design or a multi-patch design) and `trim` (the [`Outline`]:
/// `origin`, `axes`, `up` and `polygon`, the polygon's corners in the plane through
/// `origin` spanned by `axes`, seen along `up`).
#[derive(Clone, Debug, PartialEq)]
pub struct TrimmedDesign {
    /// The design before trimming.
    pub design: Trimmable,
    /// The outline its mesh is cut by ([`monge_core::approximate::trim`]).
    pub trim: Outline,
}

/// What keeps a trimmed design from its mesh: its design's own error.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum TrimmedMeshError {
    /// The design of one patch cannot be generated.
    #[error(transparent)]
    Surface(#[from] GenerateError),
    /// The multi-patch design cannot be built.
    #[error(transparent)]
    Patches(#[from] MultiPatchError),
}

impl TrimmedDesign {
    /// Its mesh before trimming (the design generated, §3, or the patches built, §4.7)
    /// and that mesh cut by its outline ([`trim`]): what `monge generate` writes.
    pub fn mesh(
        &self,
        options: &GenerateOptions,
    ) -> Result<(QuadGrid, TrimmedMesh), TrimmedMeshError> {
        let grid = match &self.design {
            Trimmable::Surface(design) => generate(design, options)?.grid,
            Trimmable::Patches(design) => build(design, options)?.grid,
        };
        let trimmed = trim(&grid, &self.trim);
        Ok((grid, trimmed))
    }
}

/// The design a trimmed design cuts.
#[derive(Clone, Debug, PartialEq)]
pub enum Trimmable {
    /// One patch (§3).
    Surface(Box<Design>),
    /// Several patches (§4.7): a design file's `design` with the key `patches`.
    Patches(MultiPatchDesign),
}

impl Trimmable {
    /// The design of a fit's result before any trimming: what a trimmed design file holds
    /// as its `design` (one patch, or several, §4.7).
    ///
    /// ```
    /// use monge_core::approximate::FitDesign;
    /// use monge_core::multipatch::MultiPatchDesign;
    /// use monge_io::Trimmable;
    /// let patches = MultiPatchDesign { patches: vec![], tolerance: None, fit: None, symmetry: vec![] };
    /// let fit = FitDesign::TrimmedPatches(patches.clone(), Default::default());
    /// assert_eq!(Trimmable::of_fit(&fit), Trimmable::Patches(patches));
    /// ```
    pub fn of_fit(fit: &FitDesign) -> Trimmable {
        match fit {
            FitDesign::Single(d) | FitDesign::Trimmed(d, _) => {
                Trimmable::Surface(Box::new(d.clone()))
            }
            FitDesign::Patches(d) | FitDesign::TrimmedPatches(d, _) => {
                Trimmable::Patches(d.clone())
            }
        }
    }

    /// The fit's result this design is, its mesh trimmed being `mesh`
    /// ([`TrimmedDesign::mesh`]): the inverse of [`Trimmable::of_fit`] for a trimmed fit.
    pub fn into_fit(self, mesh: TrimmedMesh) -> FitDesign {
        match self {
            Trimmable::Surface(d) => FitDesign::Trimmed(*d, mesh),
            Trimmable::Patches(d) => FitDesign::TrimmedPatches(d, mesh),
        }
    }
}

/// A trimmed design as its file has it (read with `O` an [`Outline`], written with
/// a reference to one).
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct TrimmedFile<T, O = Outline> {
    design: T,
    trim: O,
}

/// The keys of a trimmed design file's `design`, to tell its kind.
#[derive(Deserialize)]
struct Probe {
    design: BTreeMap<String, IgnoredAny>,
}

/// The text of a trimmed design file (its kind already checked) as a
/// [`TrimmedDesign`]: a multi-patch design if its `design` has the key `patches`.
pub(crate) fn parse_trimmed(
    text: &str,
    format: DesignFormat,
    file: &str,
) -> Result<TrimmedDesign, IoError> {
    let probe: Option<Probe> = match format {
        DesignFormat::Json => serde_json::from_str(text).ok(),
        DesignFormat::Toml => toml::from_str(text).ok(),
    };
    if probe.is_some_and(|p| p.design.contains_key("patches")) {
        let f: TrimmedFile<MultiPatchDesign> = parse_as(text, format, file)?;
        Ok(TrimmedDesign {
            design: Trimmable::Patches(f.design),
            trim: f.trim,
        })
    } else {
        let f: TrimmedFile<Design> = parse_as(text, format, file)?;
        Ok(TrimmedDesign {
            design: Trimmable::Surface(Box::new(f.design)),
            trim: f.trim,
        })
    }
}

/// Writes a trimmed design file, pretty JSON or TOML by the path's extension, atomically
/// ([`write_trimmed_into`] alone).
pub fn write_trimmed(trimmed: &TrimmedDesign, path: &Path) -> Result<(), IoError> {
    let mut out = Outputs::new();
    write_trimmed_into(trimmed, path, &mut out)?;
    out.commit()
}

/// Writes a trimmed design to `path` (pretty JSON or TOML by its extension) as one of
/// several files of `out`, put in place by its commit. Refuses a design's non-finite
/// numbers ([`IoError::NonFinite`]), as [`crate::write_design`] does.
///
/// ```
/// use glam::DVec3;
/// use monge_core::approximate::{Outline, TargetCloud};
/// use monge_core::design::{Design, GuideSpec};
/// use monge_io::{read_any_design, write_trimmed_into, AnyDesign, Outputs, Trimmable, TrimmedDesign};
/// # let dir = tempfile::tempdir().unwrap();
/// let design = Design {
///     mesh: Default::default(),
///     theta_deg: 30.0,
///     guide_u: GuideSpec::points(vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.2], [2.0, 0.0, 0.7]]),
///     guide_v: GuideSpec::points(vec![[0.0, 0.0, 0.0], [0.0, 1.0, 0.1], [0.0, 2.0, 0.5]]),
///     tolerance: None,
/// };
/// // The outline of a disc's points.
/// let disc: Vec<DVec3> = (0..400)
///     .map(|k| {
///         let (r, a) = (1.5 * ((k as f64 + 0.5) / 400.0).sqrt(), k as f64 * 2.399963);
///         DVec3::new(1.0 + r * a.cos(), 1.0 + r * a.sin(), 0.0)
///     })
///     .collect();
/// let trimmed = TrimmedDesign {
///     design: Trimmable::Surface(Box::new(design)),
///     trim: Outline::of(&TargetCloud::new(&disc).unwrap()).unwrap(),
/// };
/// let path = dir.path().join("trimmed.json");
/// let mut out = Outputs::new();
/// write_trimmed_into(&trimmed, &path, &mut out).unwrap();
/// out.commit().unwrap();
/// assert_eq!(read_any_design(&path).unwrap(), AnyDesign::Trimmed(Box::new(trimmed)));
/// ```
pub fn write_trimmed_into(
    trimmed: &TrimmedDesign,
    path: &Path,
    out: &mut Outputs,
) -> Result<(), IoError> {
    let format = DesignFormat::from_path(path)?;
    let trim = &trimmed.trim;
    match &trimmed.design {
        Trimmable::Surface(design) => {
            check_finite(design, &path_name(path))?;
            out.write(path, |w| {
                write_pretty(&TrimmedFile { design, trim }, format, w)
            })
        }
        Trimmable::Patches(design) => out.write(path, |w| {
            write_pretty(&TrimmedFile { design, trim }, format, w)
        }),
    }
}
