//! `monge render`: designs → a picture (PNG or SVG).

use std::path::{Path, PathBuf};

use anyhow::{bail, Context};
use glam::DVec3;
use monge_core::approximate::{TargetCloud, TrimmedMesh};
use monge_core::conical::conical_dual;
use monge_core::cyclidic::{CyclidicNet, CyclidicOptions};
use monge_core::developable::developable;
use monge_core::{generate, Design, GenerateError, GenerateOptions, Generated, MeshKind, QuadGrid};
use monge_io::{check_output, read_any_design, read_points, write_atomic, AnyDesign};
use monge_render::{
    gauss_net, guide_highlights, render_png, render_svg, Highlight, Panel, Projection,
    RenderOptions, Rgb, Scene, View, MAX_SIDE,
};

use crate::shared::args::parse_finite;
use crate::shared::help::{EXIT, THETA};
use crate::shared::output::{eprint, num};
use crate::shared::picture::{
    cut_highlights, distance_panel, sheet, trimmed_distance_panel, Picture,
};
use crate::shared::Outcome;

/// Draw designs as a shaded picture (PNG or SVG), or a sheet of θ values.
#[derive(Debug, clap::Args)]
#[command(
    long_about = format!(
        "Draw the mesh of a design as a picture: PNG or SVG by OUT's extension, written \
         atomically.\n\n\
         The mesh is seen from --view (z up) in a mild perspective (or --orthographic), \
         fitted to the picture. Its faces are shaded (light steel blue on the side facing \
         you, sand on the other, so folds show) and outlined; the guides are drawn on top: \
         guide_u (column 0) in red, guide_v (row 0) in blue. A design with \
         `\"mesh\": \"conical\"` is drawn as its conical dual (§2.3), with the guide samples \
         highlighted. With --gauss the Gauss map is drawn on the right: the node axes as a \
         quad net on the unit sphere (Figure 9), the normals along the guides in red and \
         blue.\n\n\
         Several DESIGNs make a contact sheet, one captioned cell each (any error stops \
         the command). --theta-sweep draws one DESIGN at several θ (the family of \
         Figure 14); a θ that cannot be built (the singular +90°, an inadmissible θ) \
         gets an empty crossed cell captioned with the reason. PNG captions use a \
         small pixel font in capitals.\n\n{THETA}"
    ),
    after_help = format!(
        "Examples:\n  \
         monge render examples/fig13-freeform.json -o freeform.png\n  \
         monge render examples/fig10-arbitrary.json -o gauss.svg --gauss --size 1500x700\n  \
         monge render examples/fig12-torus.json examples/fig12-dupin-theta30.json -o sheet.png\n  \
         monge render examples/fig14-family.toml --theta-sweep=-180,-90,0,45,90,150 -o family.png\n  \
         monge render examples/fig2-enneper.json -o top.png --view=-90,89 --orthographic\n\n{EXIT}"
    )
)]
pub struct RenderArgs {
    /// The design files (`.json` or `.toml`); several make a contact sheet.
    #[arg(value_name = "DESIGN", required = true)]
    pub designs: Vec<PathBuf>,
    /// The picture to write: `.png` or `.svg`.
    #[arg(short, long, value_name = "OUT")]
    pub output: PathBuf,
    /// Also draw the Gauss map (the node axes on the unit sphere) beside each mesh.
    #[arg(long)]
    pub gauss: bool,
    /// Size of the picture in pixels, WIDTHxHEIGHT (each from 1 to 16384).
    #[arg(long, value_name = "WxH", default_value = "1200x800", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Where the eye is, in degrees: azimuth around z from +x towards +y, and elevation
    /// above the xy plane (−89 to 89). Write `--view=-55,30` for a negative azimuth.
    #[arg(long, value_name = "AZ,EL", default_value = "-55,30", value_parser = parse_view, allow_hyphen_values = true)]
    pub view: (f64, f64),
    /// Parallel projection instead of the default mild perspective.
    #[arg(long)]
    pub orthographic: bool,
    /// Draw the one DESIGN at each of these θ (comma-separated degrees) as a contact sheet.
    #[arg(
        long,
        value_name = "θ,θ,…",
        value_delimiter = ',',
        allow_hyphen_values = true,
        value_parser = parse_finite
    )]
    pub theta_sweep: Option<Vec<f64>>,
    /// Cells per row of a contact sheet [default: cells closest to 3:2].
    #[arg(long, value_name = "N", default_value_t = 0, hide_default_value = true)]
    pub columns: usize,
    /// Draw the smooth surface instead: the cyclidic net (§4.4), K samples a patch side, with
    /// every curvature line through the mesh vertices drawn as its chain of circular arcs.
    #[arg(long, value_name = "K", value_parser = clap::value_parser!(u32).range(2..=64))]
    pub smooth: Option<u32>,
    /// Colour the mesh by its distance to TARGET (a mesh or point cloud: .obj, .ply,
    /// .json), as `monge approximate` measures it: white on the target, dark red at the
    /// 95th percentile (at least 1e-6 of the target's size) and beyond; the caption
    /// gives the scale and the deviation both ways. One DESIGN only. Of a trimmed design,
    /// the mesh before trimming is coloured with the cut drawn on it, and the deviation is
    /// the trimmed mesh's (as `monge approximate --picture` draws its result).
    #[arg(long, value_name = "TARGET")]
    pub deviation: Option<PathBuf>,
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
        let design = match read_any_design(path)? {
            AnyDesign::Surface(design) => design,
            AnyDesign::Developable(_) => bail!(
                "--theta-sweep varies the θ of a design with two guides; `{}` is a developable design (no θ)",
                path.display()
            ),
            AnyDesign::Trimmed(_) => bail!(
                "--theta-sweep varies the θ of one design; `{}` is a trimmed design: give the \
                 design before trimming (the file's `design`) as a file of its own",
                path.display()
            ),
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
        let (scene, _, trimmed) = load(path, args.gauss, args.smooth, &generate_options)?;
        let (panel, what) = deviation_panel(scene, target, trimmed.as_ref())?;
        let what = format!("`{}` coloured by {what}", path.display());
        (sheet(&[panel], 1, &options, format)?, what)
    } else if let [path] = args.designs.as_slice() {
        let (scene, _, _) = load(path, args.gauss, args.smooth, &generate_options)?;
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
                let (scene, what, _) = load(path, args.gauss, args.smooth, &generate_options)?;
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

/// The scene of the design at `path` (with its Gauss map if `gauss`), a few words on
/// it for a caption (`θ = 30°`, or `developable`), and of a trimmed design its mesh
/// trimmed (the scene draws the mesh before trimming, the cut on it).
///
/// A developable design (§3.3) is drawn with its helix in red and its first
/// curvature line in a cutting plane (column 0) in blue.
fn load(
    path: &Path,
    gauss: bool,
    smooth: Option<u32>,
    options: &GenerateOptions,
) -> anyhow::Result<(Scene, String, Option<TrimmedMesh>)> {
    let context = || path.display().to_string();
    match read_any_design(path)? {
        AnyDesign::Surface(design) => {
            let g = generate(&design, options).with_context(context)?;
            let what = format!("θ = {}°", num(g.info.theta_deg));
            Ok((scene(&g, design.mesh, gauss, smooth, path)?, what, None))
        }
        AnyDesign::Developable(d) => {
            let mesh = developable(&d.developable, options).with_context(context)?;
            let column: Vec<_> = mesh.grid.column(0).collect();
            let scene = Scene {
                highlights: guide_highlights(&mesh.helix, &column),
                gauss: if gauss { gauss_net(&mesh.grid) } else { None },
                mesh: mesh.grid,
                vertex_colors: None,
                dots: Vec::new(),
            };
            Ok((scene, "developable".to_owned(), None))
        }
        AnyDesign::Trimmed(t) => {
            if smooth.is_some() {
                bail!(
                    "{}: --smooth draws the cyclidic net of a whole grid; this is a trimmed design",
                    path.display()
                );
            }
            let (grid, trimmed) = t.mesh(options).with_context(context)?;
            let mut scene = Scene::new(grid);
            scene.highlights = cut_highlights(&trimmed);
            if gauss {
                scene.gauss = gauss_net(&scene.mesh);
            }
            let what = format!(
                "trimmed along the black line: {} panels, {} of them cut",
                trimmed.faces.len(),
                trimmed.cut.iter().filter(|c| **c).count()
            );
            Ok((scene, what, Some(trimmed)))
        }
    }
}

/// `scene` with its mesh coloured by the distance of each vertex to the target at
/// `path` ([`TargetCloud::distances`]), captioned with the colour scale and the
/// deviation both ways (of a trimmed design, its mesh `trimmed`'s,
/// [`trimmed_distance_panel`]); and a few words on it.
fn deviation_panel(
    scene: Scene,
    path: &Path,
    trimmed: Option<&TrimmedMesh>,
) -> anyhow::Result<(Panel, String)> {
    let points = read_points(path)?;
    let target =
        TargetCloud::new(&points).with_context(|| format!("target `{}`", path.display()))?;
    let name = path.file_name().unwrap_or_default().to_string_lossy();
    let title = format!("distance to {name}");
    let (panel, figures) = match trimmed {
        // Dark red from the trimmed mesh's largest distance: the overhang, cut away, is
        // farther, and a percentile of the whole grid's would leave what is built white.
        Some(mesh) => {
            let d = mesh.deviation(&target);
            let largest = d.mesh_to_target_max.max(d.target_to_mesh_max) * d.size;
            let scale = largest.max(1e-6 * d.size);
            let (panel, _) = trimmed_distance_panel(scene, &target, &title, Some(scale), &d);
            (panel, format!("trimmed, largest {}", num(largest)))
        }
        None => {
            let (panel, scale, d) = distance_panel(scene, &target, &title, None);
            let largest = d.mesh_to_target_max * d.size;
            (
                panel,
                format!("95th percentile {}, largest {}", num(scale), num(largest)),
            )
        }
    };
    // Measured without the target's stray points, as `approximate` measures it.
    let aside = match target.stray().len() {
        0 => String::new(),
        1 => "; 1 stray point set aside".to_owned(),
        n => format!("; {n} stray points set aside"),
    };
    let what = format!("its distance to `{}` ({figures}{aside})", path.display());
    Ok((panel, what))
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
                dots: Vec::new(),
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
        dots: Vec::new(),
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

/// `--size`: `WIDTHxHEIGHT`, each from 1 to [`MAX_SIDE`].
fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let bad = || {
        format!(
            "`{s}` is not a size: give WIDTHxHEIGHT in pixels, each from 1 to {MAX_SIDE}, e.g. \
             1200x800"
        )
    };
    let (w, h) = s.split_once(['x', 'X', '×']).ok_or_else(bad)?;
    let side = |t: &str| {
        let v = t.trim().parse::<u64>().map_err(|_| bad())?;
        match u32::try_from(v) {
            Ok(v @ 1..=MAX_SIDE) => Ok(v),
            _ => Err(format!(
                "`{s}`: a side of {v} pixels is outside 1 to {MAX_SIDE} (the largest picture monge \
                 draws is {MAX_SIDE} × {MAX_SIDE})"
            )),
        }
    };
    Ok((side(w)?, side(h)?))
}

/// `--view`: `AZ,EL` in degrees, the elevation from −89 to 89.
fn parse_view(s: &str) -> Result<(f64, f64), String> {
    let bad = || {
        format!(
            "`{s}` is not a view: give AZ,EL in degrees, e.g. -55,30 (elevation from -89 to 89)"
        )
    };
    let (a, e) = s.split_once(',').ok_or_else(bad)?;
    let az = parse_finite(a).map_err(|_| bad())?;
    let el = parse_finite(e).map_err(|_| bad())?;
    if !(-89.0..=89.0).contains(&el) {
        return Err(bad());
    }
    Ok((az, el))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reasons_are_short() {
        let e = GenerateError::ThetaSingular {
            theta_deg: 90.0,
            window: 1e-3,
        };
        assert_eq!(short_reason(&e), "singular");
    }

    #[test]
    fn sizes_and_views_parse() {
        assert_eq!(parse_size("900x600"), Ok((900, 600)));
        assert_eq!(parse_size("16384x1"), Ok((16384, 1)));
        for (size, side) in [("0x600", 0), ("20000x20000", 20000), ("900x16385", 16385)] {
            let err = parse_size(size).unwrap_err();
            assert!(
                err.contains(&format!("a side of {side} pixels is outside 1 to 16384")),
                "{err}"
            );
        }
        assert!(parse_size("900").is_err());
        assert_eq!(parse_view("-55,30"), Ok((-55.0, 30.0)));
        assert!(parse_view("0,90").is_err());
        assert!(parse_view("nan,0").is_err());
    }
}
