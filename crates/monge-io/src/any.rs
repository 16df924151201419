//! Any design file monge generates a mesh from: a design (§3), a developable design
//! (§3.3) or a trimmed design, told apart by their top-level keys.

use std::path::Path;

use monge_core::design::Design;
use monge_core::developable::DevelopableDesign;

use crate::design::{expect_design, parse_as, read_design_text, NO_FILE};
use crate::error::IoError;
use crate::format::{DesignFormat, FileKind};
use crate::read::path_name;
use crate::trimmed::{parse_trimmed, TrimmedDesign};

/// Any design file monge reads (§3, §3.3).
#[derive(Clone, Debug, PartialEq)]
pub enum AnyDesign {
    /// A surface from two guide curves and θ (§3): circular or conical.
    Surface(Box<Design>),
    /// A developable circular mesh from a discrete general helix (§3.3): a file
    /// whose only top-level key is `developable`.
    Developable(DevelopableDesign),
    /// A design or a multi-patch design whose mesh is cut by an outline: a file with
    /// the keys `design` and `trim` (`monge approximate`'s trimmed result).
    Trimmed(Box<TrimmedDesign>),
}

/// Reads a design file of any of these kinds, JSON or TOML by its extension: a
/// developable design if its top level has the key `developable`, a trimmed design
/// if it has the key `trim`, a surface design otherwise (with the errors of
/// [`read_design`](crate::read_design)).
///
/// ```
/// use monge_io::{read_any_design, AnyDesign};
/// let dir = std::env::temp_dir().join("monge-doc-any-design");
/// std::fs::create_dir_all(&dir).unwrap();
/// let path = dir.join("helix.json");
/// std::fs::write(&path, r#"{"developable": {"projection": {"points": [[0,0,0],[1,0,0],[2,1,0]],
///     "alpha_deg": 30}, "heights": [2, 3]}}"#).unwrap();
/// assert!(matches!(read_any_design(&path).unwrap(), AnyDesign::Developable(_)));
/// ```
pub fn read_any_design(path: &Path) -> Result<AnyDesign, IoError> {
    let format = DesignFormat::from_path(path)?;
    let text = read_design_text(path)?;
    parse_any_design_named(&text, format, &path_name(path))
}

/// Parses the text of a design file of any of these kinds (§3, §3.3), as
/// [`read_any_design`] does; errors name the file `<input>`.
///
/// ```
/// use monge_io::{parse_any_design, AnyDesign, DesignFormat};
/// let d = parse_any_design(r#"{"developable": {"projection": {"points": [[0,0,0],[1,0,0],[2,1,0]],
///     "alpha_deg": 30}, "heights": [2, 3]}}"#, DesignFormat::Json).unwrap();
/// assert!(matches!(d, AnyDesign::Developable(_)));
/// ```
pub fn parse_any_design(text: &str, format: DesignFormat) -> Result<AnyDesign, IoError> {
    parse_any_design_named(text, format, NO_FILE)
}

fn parse_any_design_named(
    text: &str,
    format: DesignFormat,
    file: &str,
) -> Result<AnyDesign, IoError> {
    let kinds = [FileKind::Design, FileKind::Developable, FileKind::Trimmed];
    match expect_design(text, format, file, &kinds)? {
        Some(FileKind::Developable) => parse_as(text, format, file).map(AnyDesign::Developable),
        Some(FileKind::Trimmed) => {
            parse_trimmed(text, format, file).map(|t| AnyDesign::Trimmed(Box::new(t)))
        }
        _ => parse_as(text, format, file).map(|d| AnyDesign::Surface(Box::new(d))),
    }
}
