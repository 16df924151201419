//! Every fabrication output of a gridshell in one directory (§6).

use std::io;
use std::path::{Path, PathBuf};

use glam::DVec3;
use monge_core::fabrication::Fabrication;

use crate::atomic::{check_output, existing_directory, Outputs};
use crate::dxf::{write_beams_dxf, write_panels_dxf};
use crate::error::IoError;
use crate::gltf::write_glb;
use crate::schedule::{
    write_beams_csv, write_nodes_csv, write_panels_csv, write_schedule_json, write_segments_csv,
    ScheduleJson,
};
use crate::svg::write_overview_svg;

/// The files [`write_fabrication`] writes, in order (§6).
pub const FABRICATION_FILES: [&str; 9] = [
    "panels.csv",
    "beams.csv",
    "segments.csv",
    "nodes.csv",
    "schedule.json",
    "panels.dxf",
    "beams.dxf",
    "overview.svg",
    "gridshell.glb",
];

/// Checks the directory of [`write_fabrication`] before a command does its work, as
/// [`check_output`] checks a file: its own directory exists ([`IoError::NoDirectory`]:
/// one new directory is made, not a path of them), it is a directory if it exists
/// ([`IoError::NotADirectory`]), and none of its files is one of `inputs`.
///
/// ```
/// use monge_io::{check_fabrication_output, IoError};
/// let dir = tempfile::tempdir().unwrap();
/// assert!(check_fabrication_output(&dir.path().join("new"), &[]).is_ok());
/// let missing = dir.path().join("missing/new");
/// assert!(matches!(check_fabrication_output(&missing, &[]), Err(IoError::NoDirectory { .. })));
/// std::fs::write(dir.path().join("file"), "").unwrap();
/// let file = dir.path().join("file");
/// assert!(matches!(check_fabrication_output(&file, &[]), Err(IoError::NotADirectory { .. })));
/// ```
pub fn check_fabrication_output(dir: &Path, inputs: &[&Path]) -> Result<(), IoError> {
    existing_directory(dir)?;
    if dir.is_dir() {
        for name in FABRICATION_FILES {
            check_output(&dir.join(name), inputs)?;
        }
        Ok(())
    } else if dir.symlink_metadata().is_ok() {
        Err(IoError::NotADirectory {
            path: dir.to_owned(),
        })
    } else {
        Ok(())
    }
}

/// Writes the schedules, drawings and model of a gridshell into `dir` (§6),
/// creating it if needed (not its own directory: see [`check_fabrication_output`]),
/// the files as one ([`Outputs`]: after an error none has changed, and a directory
/// made for them is removed); returns the paths written, in the order of
/// [`FABRICATION_FILES`]. Beams in the glTF are swept with a
/// `section.0 × section.1` rectangle (width along the beam plane's normal,
/// depth in the plane); `schedule.json` holds `json`. With a `base`, the
/// fabrication's coordinates are relative to that point, which
/// `schedule.json` records (`base_point`) and the glTF's nodes are translated
/// by; the CSV schedules keep the relative coordinates, and the DXF drawings
/// lay each part out in its own plane, where no base point applies.
pub fn write_fabrication(
    dir: &Path,
    f: &Fabrication,
    section: (f64, f64),
    json: ScheduleJson,
    base: Option<DVec3>,
) -> Result<Vec<PathBuf>, IoError> {
    check_fabrication_output(dir, &[])?;
    let made = !dir.is_dir();
    if made {
        std::fs::create_dir(dir).map_err(|source| IoError::Write {
            path: dir.to_owned(),
            source,
        })?;
    }
    type Writer<'a> = Box<dyn Fn(&mut dyn io::Write) -> io::Result<()> + Send + Sync + 'a>;
    let writers: [Writer<'_>; 9] = [
        Box::new(|w| write_panels_csv(f, w)),
        Box::new(|w| write_beams_csv(f, w)),
        Box::new(|w| write_segments_csv(f, w)),
        Box::new(|w| write_nodes_csv(f, w)),
        Box::new(|w| write_schedule_json(f, json, base, w)),
        Box::new(|w| write_panels_dxf(f, w)),
        Box::new(|w| write_beams_dxf(f, w)),
        Box::new(|w| write_overview_svg(f, w)),
        Box::new(|w| write_glb(f, section.0, section.1, base, w)),
    ];
    let paths: Vec<PathBuf> = FABRICATION_FILES
        .iter()
        .map(|name| dir.join(name))
        .collect();
    // The files are independent: as many are formatted and written at once as
    // the machine has cores; none replaces its path before all are written, and
    // the first error in the order of the files is returned.
    let written = {
        let mut out = Outputs::new();
        out.write_each(&paths, |k, w| writers[k](w))
            .and_then(|()| out.commit())
    };
    if let Err(e) = written {
        if made {
            // Empty again once the staged files are dropped (none was put in place).
            let _ = std::fs::remove_dir(dir);
        }
        return Err(e);
    }
    Ok(paths)
}
