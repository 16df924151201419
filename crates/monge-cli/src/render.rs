//! `monge render`: designs → a picture (PNG or SVG).

use std::path::{Path, PathBuf};

use anyhow::{bail, Context};
use glam::DVec3;
use monge_core::approximate::{Deviation, TargetCloud};
use monge_core::conical::conical_dual;
use monge_core::cyclidic::{CyclidicNet, CyclidicOptions};
use monge_core::developable::developable;
use monge_core::{generate, Design, GenerateError, GenerateOptions, Generated, MeshKind, QuadGrid};
use monge_io::{check_output, read_any_design, read_points, write_atomic, AnyDesign};
use monge_render::{
    gauss_net, guide_highlights, heat, render_png, render_svg, sheet_png, sheet_svg, Highlight,
    Panel, Projection, RenderOptions, Rgb, Scene, View,
};

use crate::cli::RenderArgs;
use crate::output::{eprint, num};
use crate::Outcome;

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

/// Runs `monge render`.
pub fn run(args: &RenderArgs) -> anyhow::Result<Outcome> {
    let out = args.output.as_path();
    let inputs: Vec<&Path> = args.designs.iter().map(PathBuf::as_path).collect();
    check_output(out, &inputs)?;
    let format = Picture::of(out)?;
    let (width, height) = args.size;
    let options = RenderOptions {
        width,
        height,
        view: View {
            azimuth_deg: args.view.0,
            elevation_deg: args.view.1,
        },
        projection: if args.orthographic {
            Projection::Orthographic
        } else {
            Projection::default()
        },
        ..RenderOptions::default()
    };
    let generate_options = GenerateOptions::default();

    if args.deviation.is_some() && (args.designs.len() != 1 || args.theta_sweep.is_some()) {
        bail!("--deviation colours one design by its distance to a target: give exactly one DESIGN, without --theta-sweep");
    }
    let (bytes, what) = if let Some(thetas) = &args.theta_sweep {
        let [path] = args.designs.as_slice() else {
            bail!("--theta-sweep renders one design at several θ: give exactly one DESIGN");
        };
        let AnyDesign::Surface(design) = read_any_design(path)? else {
            bail!(
                "--theta-sweep varies the θ of a design with two guides; `{}` is a developable design (no θ)",
                path.display()
            );
        };
        let panels: Vec<Panel> = thetas
            .iter()
            .map(|&theta| {
                let design = Design {
                    theta_deg: theta,
                    ..(*design).clone()
                };
                let caption = format!("θ = {}°", num(theta));
                match generate(&design, &generate_options) {
                    Ok(g) => Ok(Panel {
                        scene: Some(scene(&g, design.mesh, args.gauss, args.smooth, path)?),
                        caption,
                    }),
                    Err(e) => Ok(Panel {
                        scene: None,
                        caption: format!("{caption}\n{}", short_reason(&e)),
                    }),
                }
            })
            .collect::<anyhow::Result<_>>()?;
        let failed = panels.iter().filter(|p| p.scene.is_none()).count();
        let what = format!(
            "a sheet of {} θ ({failed} failed) of `{}`",
            panels.len(),
            path.display()
        );
        (sheet(&panels, args.columns, &options, format)?, what)
    } else if let (Some(target), [path]) = (&args.deviation, args.designs.as_slice()) {
        let (scene, _) = load(path, args.gauss, args.smooth, &generate_options)?;
        let (panel, what) = deviation_panel(scene, target)?;
        let what = format!("`{}` coloured by {what}", path.display());
        (sheet(&[panel], 1, &options, format)?, what)
    } else if let [path] = args.designs.as_slice() {
        let (scene, _) = load(path, args.gauss, args.smooth, &generate_options)?;
        let bytes = match format {
            Picture::Png => render_png(&scene, &options)?,
            Picture::Svg => render_svg(&scene, &options)?.into_bytes(),
        };
        (bytes, format!("`{}`", path.display()))
    } else {
        let panels: Vec<Panel> = args
            .designs
            .iter()
            .map(|path| {
                let (scene, what) = load(path, args.gauss, args.smooth, &generate_options)?;
                let stem = path.file_stem().unwrap_or_default().to_string_lossy();
                Ok(Panel {
                    scene: Some(scene),
                    caption: format!("{stem}: {what}"),
                })
            })
            .collect::<anyhow::Result<_>>()?;
        let what = format!("a sheet of {} designs", panels.len());
        (sheet(&panels, args.columns, &options, format)?, what)
    };
    write_atomic(out, |w| w.write_all(&bytes))?;
    eprint(&format!(
        "wrote `{}` ({width} × {height}, {} bytes): {what}.\n",
        out.display(),
        bytes.len()
    ));
    Ok(Outcome::Success)
}

/// The scene of the design at `path` (with its Gauss map if `gauss`), and a
/// few words on it for a caption (`θ = 30°`, or `developable`).
///
/// A developable design (§3.3) is drawn with its helix in red and its first
/// curvature line in a cutting plane (column 0) in blue.
fn load(
    path: &Path,
    gauss: bool,
    smooth: Option<u32>,
    options: &GenerateOptions,
) -> anyhow::Result<(Scene, String)> {
    let context = || path.display().to_string();
    match read_any_design(path)? {
        AnyDesign::Surface(design) => {
            let g = generate(&design, options).with_context(context)?;
            let what = format!("θ = {}°", num(g.info.theta_deg));
            Ok((scene(&g, design.mesh, gauss, smooth, path)?, what))
        }
        AnyDesign::Developable(d) => {
            let mesh = developable(&d.developable, options).with_context(context)?;
            let column: Vec<_> = mesh.grid.column(0).collect();
            let scene = Scene {
                highlights: guide_highlights(&mesh.helix, &column),
                gauss: if gauss { gauss_net(&mesh.grid) } else { None },
                mesh: mesh.grid,
                vertex_colors: None,
            };
            Ok((scene, "developable".to_owned()))
        }
    }
}

/// `scene` with its mesh coloured by the distance of each vertex to the target at
/// `path` ([`TargetCloud::distances`]), captioned with the colour scale and the
/// deviation both ways; and a few words on it.
fn deviation_panel(scene: Scene, path: &Path) -> anyhow::Result<(Panel, String)> {
    let points = read_points(path)?;
    let target =
        TargetCloud::new(&points).with_context(|| format!("target `{}`", path.display()))?;
    let name = path.file_name().unwrap_or_default().to_string_lossy();
    let (panel, scale, d) = distance_panel(scene, &target, &format!("distance to {name}"), None);
    let what = format!(
        "its distance to `{}` (95th percentile {}, largest {})",
        path.display(),
        num(scale),
        num(d.mesh_to_target_max * d.size)
    );
    Ok((panel, what))
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
    let size = target.size();
    // In the caption font's characters (capitals, digits, some punctuation).
    let caption = format!(
        "{title}\nwhite 0, dark red from {}{how}\n\
         mesh to target: max {}, RMS {}\ntarget to mesh: max {}, RMS {}",
        num(scale),
        num(d.mesh_to_target_max * size),
        num(d.mesh_to_target_rms * size),
        num(d.target_to_mesh_max * size),
        num(d.target_to_mesh_rms * size),
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

/// What to draw of a generated design: the circular mesh with its guides (row 0
/// and column 0), or the conical dual with the guide samples; and the Gauss map
/// (the circular mesh's node axes) if asked.
fn scene(
    g: &Generated,
    kind: MeshKind,
    gauss: bool,
    smooth: Option<u32>,
    path: &Path,
) -> anyhow::Result<Scene> {
    let mut scene = match (kind, smooth) {
        (MeshKind::Circular, Some(k)) => smooth_scene(&g.grid, k as usize, path)?,
        (MeshKind::Circular, None) => Scene::new(g.grid.clone()),
        (MeshKind::Conical, Some(_)) => bail!(
            "{}: --smooth draws the cyclidic net of a circular mesh, not of a conical one",
            path.display()
        ),
        (MeshKind::Conical, None) => {
            if g.grid.rows < 3 || g.grid.cols < 3 {
                bail!(
                    "{}: a conical mesh needs at least 3 samples on each guide (the grid is {} × {})",
                    path.display(),
                    g.grid.rows,
                    g.grid.cols
                );
            }
            Scene {
                mesh: conical_dual(&g.grid).grid,
                highlights: guide_highlights(&g.info.guide_u.points, &g.info.guide_v.points),
                gauss: None,
                vertex_colors: None,
            }
        }
    };
    if gauss {
        scene.gauss = gauss_net(&g.grid);
    }
    Ok(scene)
}

/// The cyclidic net of a circular mesh (§4.4) sampled `k` times a patch side,
/// with its mesh lines (chains of circular arcs) drawn on top in dark grey and
/// the guides in their colours.
fn smooth_scene(grid: &QuadGrid, k: usize, path: &Path) -> anyhow::Result<Scene> {
    let net = CyclidicNet::from_normals(grid, &CyclidicOptions::default())
        .with_context(|| format!("{}: the cyclidic net", path.display()))?;
    let dense = net.dense(k);
    let step = k - 1;
    let arc = |points: Vec<DVec3>| Highlight {
        points,
        color: ARC_COLOR,
    };
    let rows = (1..grid.rows).map(|i| arc(dense.row(i * step).collect()));
    let columns = (1..grid.cols).map(|j| arc(dense.column(j * step).collect()));
    let mut highlights: Vec<Highlight> = rows.chain(columns).collect();
    highlights.extend(guide_highlights(
        &dense.column(0).collect::<Vec<_>>(),
        &dense.row(0).collect::<Vec<_>>(),
    ));
    Ok(Scene {
        mesh: dense,
        highlights,
        gauss: None,
        vertex_colors: None,
    })
}

/// Colour of the curvature lines through the mesh vertices on a smooth net.
const ARC_COLOR: Rgb = Rgb::new(70, 70, 80);

/// Why a θ of a sweep failed, in a few words for a caption.
fn short_reason(e: &GenerateError) -> &'static str {
    match e {
        GenerateError::ThetaSingular { .. } => "singular",
        GenerateError::ThetaInadmissible { .. } => "not admissible",
        GenerateError::Degenerate { .. } | GenerateError::NormalStill { .. } => "degenerate",
        GenerateError::ThetaNotFinite(_) => "not finite",
        _ => "invalid design",
    }
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

    #[test]
    fn reasons_are_short() {
        let e = GenerateError::ThetaSingular {
            theta_deg: 90.0,
            window: 1e-3,
        };
        assert_eq!(short_reason(&e), "singular");
    }
}
