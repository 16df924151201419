//! Pictures that several commands draw: the format of a picture file, contact
//! sheets, and a mesh coloured by its distance to a target.

use std::path::Path;

use anyhow::bail;
use monge_core::approximate::{Deviation, TargetCloud, TrimmedMesh};
use monge_render::{heat, sheet_png, sheet_svg, Highlight, Panel, RenderOptions, Rgb, Scene};

use crate::shared::output::num;

/// The picture formats, by extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Picture {
    Png,
    Svg,
}

impl Picture {
    /// The format of `out`'s extension.
    pub fn of(out: &Path) -> anyhow::Result<Picture> {
        let ext = out
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase());
        match ext.as_deref() {
            Some("png") => Ok(Picture::Png),
            Some("svg") => Ok(Picture::Svg),
            _ => bail!(
                "cannot tell the picture format of `{}`: OUT must end in `.png` or `.svg`",
                out.display()
            ),
        }
    }
}

/// Colour of the edges of a mesh trimmed to an outline, drawn on the mesh before
/// trimming.
const TRIM_COLOR: Rgb = Rgb::new(0, 0, 0);

/// The edges of the trimmed mesh `trimmed` (the cut, where its panels meet the
/// outline), to draw on the mesh before trimming.
pub fn cut_highlights(trimmed: &TrimmedMesh) -> Vec<Highlight> {
    trimmed
        .edges()
        .into_iter()
        .map(|points| Highlight {
            points,
            color: TRIM_COLOR,
        })
        .collect()
}

/// `scene` with its mesh coloured by each vertex's distance to `target`
/// ([`TargetCloud::distances`]): white 0, dark red from `scale`, by default the 95th
/// percentile (so that a few vertices beyond the target's last points do not wash out
/// the rest; at least 1e-6 of the target's size, so that rounding on a mesh that is its
/// own target stays white). The caption starts with `title`, then gives the scale and
/// the deviation both ways. The panel, the scale, the deviation.
pub fn distance_panel(
    mut scene: Scene,
    target: &TargetCloud,
    title: &str,
    scale: Option<f64>,
) -> (Panel, f64, Deviation) {
    let (distances, d) = target.distances_and_deviation(&scene.mesh);
    let how = if scale.is_none() {
        " (95th percentile)"
    } else {
        ""
    };
    let scale = scale.unwrap_or_else(|| {
        let mut sorted = distances.clone();
        sorted.sort_by(f64::total_cmp);
        sorted[(sorted.len() - 1) * 95 / 100].max(1e-6 * target.size())
    });
    scene.vertex_colors = Some(distances.iter().map(|d| heat(d / scale)).collect());
    let caption = deviation_caption(
        &format!("{title}\nwhite 0, dark red from {}{how}", num(scale)),
        &d,
    );
    (
        Panel {
            scene: Some(scene),
            caption,
        },
        scale,
        d,
    )
}

/// [`distance_panel`] of a trimmed mesh: `scene`, the mesh before trimming with the cut
/// drawn on it ([`cut_highlights`]), coloured by its vertices' distances to `target`;
/// captioned `title, trimmed along the black line` with the figures of `trimmed`, the
/// deviation of the mesh trimmed (what is built).
pub fn trimmed_distance_panel(
    scene: Scene,
    target: &TargetCloud,
    title: &str,
    scale: Option<f64>,
    trimmed: &Deviation,
) -> (Panel, f64) {
    let title = format!("{title}, trimmed along the black line");
    let (mut panel, scale, _) = distance_panel(scene, target, &title, scale);
    panel.caption = deviation_caption(
        &format!(
            "{title}\nwhite 0, dark red from {}; figures trimmed",
            num(scale)
        ),
        trimmed,
    );
    (panel, scale)
}

/// A panel's caption: `head`, then the deviation `d` both ways in model units, in the
/// caption font's characters (capitals, digits, some punctuation).
pub fn deviation_caption(head: &str, d: &Deviation) -> String {
    let size = d.size;
    format!(
        "{head}\nmesh to target: max {}, RMS {}\ntarget to mesh: max {}, RMS {}",
        num(d.mesh_to_target_max * size),
        num(d.mesh_to_target_rms * size),
        num(d.target_to_mesh_max * size),
        num(d.target_to_mesh_rms * size),
    )
}

/// A contact sheet in `format`.
pub fn sheet(
    panels: &[Panel],
    columns: usize,
    options: &RenderOptions,
    format: Picture,
) -> anyhow::Result<Vec<u8>> {
    Ok(match format {
        Picture::Png => sheet_png(panels, columns, options)?,
        Picture::Svg => sheet_svg(panels, columns, options)?.into_bytes(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn format_follows_the_extension() {
        assert_eq!(Picture::of(Path::new("a/b.PNG")).unwrap(), Picture::Png);
        assert_eq!(Picture::of(Path::new("b.svg")).unwrap(), Picture::Svg);
        assert!(Picture::of(Path::new("b.jpg")).is_err());
        assert!(Picture::of(Path::new("-")).is_err());
    }
}
