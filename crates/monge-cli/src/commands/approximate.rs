//! `monge approximate`: the design whose exact mesh is nearest to a target mesh or
//! point cloud (monge's extension of the method; related to the fitting of §4.7, §4.8).

use std::path::{Path, PathBuf};
use std::time::Duration;

use anyhow::{bail, Context};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use monge_core::approximate::{
    approximate, approximate_patches, approximate_to_tolerance, deadline_after, fit_report,
    ApproxOptions, Chosen, Deviation, FitDesign, Outline, PatchLayout, Stop, TargetCloud,
    Tolerance, ToleranceFit, ToleranceOptions, TrimmedMesh, PATCHES_GAIN,
};
use monge_core::fabrication::DESIGN_ANGLE_TOL_DEG;
use monge_core::measure::{conical_error, measure};
use monge_core::multipatch::{build, MultiPatchDesign};
use monge_core::{generate, GenerateOptions, MeshKind};
use monge_io::{
    check_output, is_stdio, read_points, write_design_into, write_multipatch_into,
    write_trimmed_into, write_trimmed_mesh_to, MeshFormat, Outputs, Trimmable, TrimmedDesign,
};

use crate::shared::args::{parse_non_negative, Named, KINDS};
use crate::shared::help::EXIT;
use crate::shared::output::{num, print};
use crate::shared::picture::Picture;
use crate::shared::Outcome;
use glam::DVec3;
use picture::{patch_boundaries, picture_bytes};

mod picture;

/// Find the design whose exact mesh is nearest to a target mesh or point cloud.
#[derive(Debug, clap::Args)]
#[command(
    long_about = "Find the design (corner, two planar guides, θ) whose exactly generated mesh is \
                  nearest to TARGET both ways (mesh → target and target → mesh), by least squares \
                  (again from θ moved to the best of a scan where they stall away from the \
                  target) from the target's principal \
                  directions at its corners, its edges fitted to the envelope of the target's \
                  points (a scan's too); prints the deviation before \
                  and after, relative to the target's size, and the measured exactness.",
    after_help = format!(
        "Examples:\n  monge approximate examples/targets/roof-pcl.obj -o roof.json --grid 20x20\n  \
         monge approximate examples/targets/paraboloid.obj -o roof.json --tolerance 0.05m\n\n\
         With --tolerance, the exit status is 1 also when the design found is not within the \
         tolerance (it is written all the same: the nearest found).\n\n{EXIT}"
    )
)]
pub struct ApproximateArgs {
    /// The target: a mesh or point cloud (`.obj`, `.ply` ASCII or binary, `.json` with `vertices` or
    /// `points`, `.stl` ASCII or binary), a scan's points one a line (`.xyz`, `.pts`, `.csv`,
    /// `.txt`: `x y z`, further columns ignored), or NURBS surfaces (`.igs`/`.iges`, entity 128,
    /// sampled at about 4000 points).
    #[arg(value_name = "TARGET")]
    pub target: PathBuf,
    /// Where to write the design found (`.json` or `.toml`).
    #[arg(short, long, value_name = "DESIGN")]
    pub output: PathBuf,
    /// Faces of the mesh, along guide_u × along guide_v.
    #[arg(long, value_name = "UxV", default_value = "40x40", value_parser = parse_grid)]
    pub grid: (usize, usize),
    /// Circular (default) or conical mesh (§2.3).
    #[arg(long, value_parser = KINDS, default_value = MeshKind::Circular.name())]
    pub kind: MeshKind,
    /// Number of starts, at least 1 (best θ at each corner of the target first).
    #[arg(
        long,
        value_name = "N",
        default_value_t = ApproxOptions::default().starts,
        value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(1..)
    )]
    pub starts: usize,
    /// Budget of mesh generations of each optimiser run (a smaller N is raised to the
    /// fewest its optimiser needs to start: 2n + 2 for its n parameters).
    #[arg(long, value_name = "N", default_value_t = ApproxOptions::default().max_evaluations)]
    pub max_evaluations: usize,
    /// Stop searching after this many seconds and keep the best design found.
    #[arg(long, value_name = "SECONDS")]
    pub time_limit: Option<f64>,
    /// Keep the target's boundary: the guides are two of its own boundary curves from a
    /// corner (traced through its points and fitted), and only θ is searched.
    #[arg(long)]
    pub keep_boundary: bool,
    /// Fit a mesh that covers the target, not one whose boundary follows its edges, and
    /// write it trimmed to the target's outline (seen along its normal) to TRIMMED, its
    /// faces polygons, in the format of its extension (`.obj`, `.ply`, `.json` with
    /// `vertices`, `faces` and `cut`, `.glb` as triangles): for a target whose edges are
    /// not curvature lines (a roof over a rectangle whose curvature lines run askew). The
    /// panels cut by the outline stay planar, no longer circular; the distances printed
    /// are the trimmed mesh's; --picture draws the mesh before trimming with the cut on
    /// it. DESIGN is a trimmed design: the design and the target's outline, which `monge
    /// generate` writes trimmed as TRIMMED is.
    /// With --patches, the patches cover the target too and are trimmed, where they
    /// follow it closer. With --tolerance, where that fit chooses a trimmed mesh (it
    /// tries one after one patch), it goes to TRIMMED (by default beside DESIGN:
    /// `x.trimmed.obj`).
    #[arg(long, value_name = "TRIMMED", conflicts_with = "keep_boundary")]
    pub trim: Option<PathBuf>,
    /// Also draw the target's points coloured by their distance to the result, and the
    /// initial guess and the result coloured by their distance to the target, side by
    /// side (`.png` or `.svg`), on one scale (white 0, dark red from the initial guess's
    /// 95th percentile, or from --tolerance), as `monge render --deviation` does; the
    /// boundaries between patches are drawn on the result in green.
    #[arg(long, value_name = "PICTURE")]
    pub picture: Option<PathBuf>,
    /// Then fit UxV patches with piecewise planar curvature lines (§4.7), e.g. 2x3:
    /// guide_u cut into U pieces and guide_v into V (K alone: Kx1), every guide and θ
    /// free; DESIGN is then a multi-patch design (the input of `monge patches`),
    /// written only if it follows the target more closely.
    #[arg(long, value_name = "UxV")]
    pub patches: Option<PatchLayout>,
    /// Fit one patch, then one patch that covers the target trimmed to its outline (as
    /// --trim, where the outline can be traced), then 2x1, 2x2, 3x2, … patches (as
    /// --patches) until the mesh is within TOL of the target both ways (the largest
    /// distances): a number is relative to the target's size (`5e-3`), a number and a
    /// unit a length (`0.05m`, `5cm`, `50mm`, the target's coordinates taken as metres).
    /// DESIGN is the nearest design found, within TOL or not (then exit status 1, and why:
    /// the patch budget, --time-limit, patches that cannot be fitted); a trimmed mesh
    /// found nearest goes to --trim's path, or beside DESIGN (`x.trimmed.obj`).
    #[arg(
        long,
        value_name = "TOL",
        value_parser = parse_tolerance,
        conflicts_with = "patches",
        allow_hyphen_values = true
    )]
    pub tolerance: Option<Tolerance>,
    /// With --tolerance: the most patches tried.
    #[arg(
        long,
        value_name = "N",
        requires = "tolerance",
        default_value_t = ToleranceOptions::default().max_patches,
        value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(1..)
    )]
    pub max_patches: usize,
    /// With --tolerance: the report counts nodes whose beam angles (and angles to the node
    /// axis) agree within DEG degrees as one node type, as `monge fabricate --angle-tol`
    /// groups them: a designer's fabrication tolerance (its 1e-4° default tells apart
    /// every node of a curved mesh).
    #[arg(
        long,
        value_name = "DEG",
        requires = "tolerance",
        default_value_t = DESIGN_ANGLE_TOL_DEG,
        value_parser = parse_non_negative,
        allow_negative_numbers = true
    )]
    pub angle_tol: f64,
}

/// `--tolerance`: [`Tolerance`]'s own parser and message.
fn parse_tolerance(text: &str) -> Result<Tolerance, String> {
    text.parse()
        .map_err(|e: monge_core::approximate::ToleranceError| e.to_string())
}

/// Above this RMS distance (either way, relative to the target's size) the result is
/// reported as a target one patch cannot follow.
const ONE_PATCH_RMS: f64 = 5e-3;

/// `UxV`, e.g. `40x40`.
fn parse_grid(text: &str) -> Result<(usize, usize), String> {
    let (u, v) = text
        .split_once(['x', 'X', '×'])
        .ok_or_else(|| format!("`{text}` is not UxV, e.g. 40x40"))?;
    let n = |s: &str| {
        s.trim()
            .parse::<usize>()
            .map_err(|_| format!("`{s}` in `{text}` is not a whole number of faces"))
    };
    Ok((n(u)?, n(v)?))
}

/// One line of distances, relative to the target's size and in model units.
fn line(name: &str, d: &Deviation) -> String {
    format!(
        "{name}: mesh → target max {} RMS {}, target → mesh max {} RMS {} (of the size {}; max {} model units)\n",
        num(d.mesh_to_target_max),
        num(d.mesh_to_target_rms),
        num(d.target_to_mesh_max),
        num(d.target_to_mesh_rms),
        num(d.size),
        num(d.max() * d.size)
    )
}

/// The largest error of the patches of `design`, each measured on its own grid as by
/// `monge check` (a multi-patch mesh's lines are planar only piecewise).
fn patches_exactness(design: &MultiPatchDesign) -> anyhow::Result<f64> {
    Ok(build(design, &GenerateOptions::default())?.max_error())
}

/// Runs `monge approximate`.
pub fn run(args: &ApproximateArgs) -> anyhow::Result<Outcome> {
    let file = args.target.display().to_string();
    check_output(&args.output, &[&args.target])?;
    trimmed_output(args)?;
    if let Some(path) = &args.trim {
        check_output(path, &[&args.target, &args.output])?;
    }
    let picture = match &args.picture {
        Some(path) => {
            check_output(path, &[&args.target, &args.output])?;
            Some((path, Picture::of(path)?))
        }
        None => None,
    };
    let deadline = match args.time_limit {
        Some(t) => deadline_after(t).context("--time-limit")?,
        None => None,
    };
    let points = read_points(&args.target)?;
    let options = ApproxOptions {
        faces: args.grid,
        kind: args.kind,
        starts: args.starts,
        max_evaluations: args.max_evaluations,
        deadline,
        keep_boundary: args.keep_boundary,
        // With --tolerance, --trim only says where a trimmed mesh goes: the fit tries one.
        trim: args.trim.is_some() && args.tolerance.is_none(),
    };
    // Drawn on stderr only when it is a terminal (indicatif hides it otherwise).
    let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
    bar.set_style(
        ProgressStyle::with_template("{spinner} {pos} meshes generated, {elapsed} elapsed: {msg}")
            .expect("a valid progress template"),
    );
    // The spinner and the elapsed time keep moving while the starts run in parallel
    // (their counts arrive when they end).
    bar.enable_steady_tick(Duration::from_millis(200));
    if let Some(tolerance) = args.tolerance {
        let options = ToleranceOptions {
            tolerance,
            max_patches: args.max_patches,
            approx: options,
        };
        let fit = approximate_to_tolerance(&points, &options, &mut |p| {
            bar.set_position(p.evaluations as u64);
            bar.set_message(format!(
                "{} patch{}: best RMS {:.2e} of the size{}",
                p.patches,
                if p.patches == 1 { "" } else { "es" },
                p.search.best_rms,
                if p.best_max.is_finite() {
                    format!(
                        "; nearest design so far: largest distance {:.2e}",
                        p.best_max
                    )
                } else {
                    String::new()
                }
            ));
        })
        .with_context(|| file.clone())?;
        bar.finish_and_clear();
        return finish_tolerance(args, &points, &fit, picture);
    }
    let r = approximate(&points, &options, &mut |p| {
        bar.set_position(p.evaluations as u64);
        bar.set_message(format!("best RMS {:.2e} of the size", p.best_rms));
    })
    .with_context(|| file.clone())?;
    // The second step: several patches (§4.7), kept if they follow the target closer.
    let patched = match args.patches {
        Some(k) => {
            let p = approximate_patches(&points, &r, k, &options, &mut |p| {
                bar.set_position(p.evaluations as u64);
                bar.set_message(format!(
                    "{k} patches: best RMS {:.2e} of the size",
                    p.best_rms
                ));
            })
            .with_context(|| file.clone())?;
            Some(p)
        }
        None => None,
    };
    bar.finish_and_clear();
    let better = patched.as_ref().filter(|p| p.closer_than(&r));
    // The design and its picture change together or not at all.
    let mut out = Outputs::new();
    // The result trimmed, where it is: the patches' where they are kept.
    let trimmed = match better {
        Some(p) => p.trimmed.as_ref().map(|t| (t, p.after)),
        None => r.trimmed.as_ref().map(|t| (t, r.after)),
    };
    let (grid, after, design) = match better {
        Some(p) => (&p.grid, p.after, Trimmable::Patches(p.design.clone())),
        None => (
            &r.grid,
            r.after,
            Trimmable::Surface(Box::new(r.design.clone())),
        ),
    };
    // The target indexed once, for the outline of a trimmed result and the picture.
    let target = (trimmed.is_some() || picture.is_some())
        .then(|| TargetCloud::new(&points))
        .transpose()
        .with_context(|| file.clone())?;
    let outline_of = trimmed.and(target.as_ref());
    write_result_into(args, design, outline_of, &mut out)?;
    if let (Some(_), Some((mesh, _))) = (&args.trim, trimmed) {
        let (path, format) = trimmed_output(args)?;
        write_trimmed_mesh_into(mesh, (&path, format), &file, &mut out)?;
    }
    if let (Some((path, format)), Some(target)) = (picture, &target) {
        let boundaries = match better {
            Some(p) => patch_boundaries(&build(&p.design, &GenerateOptions::default())?),
            None => Vec::new(),
        };
        let bytes = picture_bytes(&r, grid, boundaries, &points, target, None, format, trimmed)?;
        out.write(path, |w| w.write_all(&bytes))?;
    }
    out.commit()?;
    let m = measure(&r.grid);
    let exactness = match args.kind {
        MeshKind::Circular => m.max_error(),
        MeshKind::Conical => m.max_error_conical(conical_error(&r.grid)),
    };
    print(&format!(
        "target: {} points, size {}; corner curvatures {} and {}\n{}{}{}\
         exactness of the result (generated, measured): {}\n\
         θ {}°; {} starts, {} meshes generated{}\n",
        points.len(),
        num(r.after.size),
        num(r.corner_curvatures.0),
        num(r.corner_curvatures.1),
        stray_line(&points, &r.stray),
        line("initial guess", &r.before),
        line("result", &r.after),
        num(exactness),
        num(r.design.theta_deg),
        r.starts,
        r.evaluations,
        if r.timed_out {
            " (stopped by --time-limit)"
        } else {
            ""
        },
    ))?;
    if let Some(p) = &patched {
        let thetas: Vec<String> = p.design.patches.iter().map(|s| num(s.theta_deg)).collect();
        print(&format!(
            "{}exactness of the patches (generated, measured): {}\nθ of the patches: {}°; {} meshes generated; {}\n",
            line(&format!("{} patches (§4.7)", p.design.patches.len()), &p.after),
            num(patches_exactness(&p.design)?),
            thetas.join("°, "),
            p.evaluations,
            if better.is_some() {
                "they follow the target closer than one patch: DESIGN is a multi-patch design (`monge patches` reads it)"
            } else {
                "they do not follow the target closer than one patch: DESIGN is the single patch"
            }
        ))?;
    }
    print(&format!(
        "wrote {}{}\n",
        args.output.display(),
        if trimmed.is_some() {
            format!(" ({TRIMMED_DESIGN})")
        } else {
            String::new()
        }
    ))?;
    if let (Some(path), Some((mesh, _))) = (&args.trim, trimmed) {
        print(&format!(
            "wrote {} ({})\n",
            path.display(),
            trimmed_faces(mesh)
        ))?;
    }
    if let Some(path) = &args.picture {
        print(&format!(
            "wrote {} (the target coloured by its distance to the result; the initial guess and the result coloured by their distance to the target)\n",
            path.display()
        ))?;
    }
    let rms = after.mesh_to_target_rms.max(after.target_to_mesh_rms);
    if rms > ONE_PATCH_RMS {
        print(&format!(
            "{} follows this target only to an RMS distance of {} of its size (more than {}): \
             {}; `monge render {} --deviation {}` shows where it departs\n",
            if better.is_some() {
                "the multi-patch design"
            } else {
                "one patch"
            },
            num(rms),
            num(ONE_PATCH_RMS),
            if args.patches.is_none() {
                "a single surface with planar curvature lines cannot follow it closer: where the \
                 target's edges are not curvature lines, cover it and trim the mesh to its \
                 outline (--trim); else fit several patches with piecewise planar curvature \
                 lines (§4.7, e.g. --patches 3); --tolerance tries both"
            } else {
                "try more patches, or split the target and approximate each part"
            },
            args.output.display(),
            args.target.display()
        ))?;
    }
    Ok(Outcome::Success)
}

/// The line that names the target's stray points, set aside (empty without any): how
/// many, and the first few with their numbers in the file (from 1) and positions.
fn stray_line(points: &[DVec3], stray: &[usize]) -> String {
    const SHOWN: usize = 5;
    if stray.is_empty() {
        return String::new();
    }
    let named: Vec<String> = stray
        .iter()
        .take(SHOWN)
        .map(|&k| {
            let [x, y, z] = points[k].to_array().map(num);
            format!("point {} ({x}, {y}, {z})", k + 1)
        })
        .collect();
    format!(
        "set aside {} stray point{} (isolated from the rest, or off the surface their nearest \
         others make; neither fitted nor measured): {}{}\n",
        stray.len(),
        if stray.len() == 1 { "" } else { "s" },
        named.join(", "),
        if stray.len() > SHOWN {
            format!(" and {} more", stray.len() - SHOWN)
        } else {
            String::new()
        }
    )
}

/// What DESIGN is where the result is trimmed.
const TRIMMED_DESIGN: &str =
    "a trimmed design: the design and the target's outline; `monge generate` writes its mesh trimmed";

/// Queues DESIGN: the result's design, one patch or several, and where the result is
/// trimmed, the outline of the target `trimmed_to` with it (a trimmed design, whose
/// mesh `monge generate` cuts by it as the fit did: the same outline of the same points).
fn write_result_into(
    args: &ApproximateArgs,
    design: Trimmable,
    trimmed_to: Option<&TargetCloud>,
    out: &mut Outputs,
) -> anyhow::Result<()> {
    let path = &args.output;
    if let Some(target) = trimmed_to {
        let trim = Outline::of(target).with_context(|| args.target.display().to_string())?;
        write_trimmed_into(&TrimmedDesign { design, trim }, path, out)?;
    } else {
        match design {
            Trimmable::Surface(d) => write_design_into(&d, path, out)?,
            Trimmable::Patches(d) => write_multipatch_into(&d, path, out)?,
        }
    }
    Ok(())
}

/// Where the trimmed mesh goes: `--trim`'s path, or beside DESIGN (`x.json` →
/// `x.trimmed.obj`) when `--tolerance` chooses a trimmed mesh without it.
fn trimmed_path(args: &ApproximateArgs) -> PathBuf {
    args.trim
        .clone()
        .unwrap_or_else(|| args.output.with_extension("trimmed.obj"))
}

/// [`trimmed_path`] and the mesh format of its extension (an error naming `--trim`).
fn trimmed_output(args: &ApproximateArgs) -> anyhow::Result<(PathBuf, MeshFormat)> {
    let path = trimmed_path(args);
    if is_stdio(&path) {
        bail!(
            "--trim writes the trimmed mesh to a file (standard output carries the report): \
             give a path ending in `.obj`, `.ply`, `.json` or `.glb`"
        );
    }
    let format = MeshFormat::from_path(&path).context("--trim")?;
    Ok((path, format))
}

/// Queues the trimmed mesh `mesh` of the target `file` for `path`, in `format` (faces as
/// polygons: [`write_trimmed_mesh_to`]).
fn write_trimmed_mesh_into(
    mesh: &TrimmedMesh,
    (path, format): (&Path, MeshFormat),
    file: &str,
    out: &mut Outputs,
) -> anyhow::Result<()> {
    out.write(path, |w| {
        write_trimmed_mesh_to(
            mesh,
            format,
            &format!(
                "monge approximate: {} faces trimmed to the outline of {file}",
                mesh.faces.len()
            ),
            w,
        )
    })?;
    Ok(())
}

/// `N faces trimmed to the target's outline, M of them cut`.
fn trimmed_faces(mesh: &TrimmedMesh) -> String {
    format!(
        "{} faces trimmed to the target's outline, {} of them cut",
        mesh.faces.len(),
        mesh.cut.iter().filter(|c| **c).count()
    )
}

/// The exactness of `design` measured as by `monge check`: its mesh, or each patch on
/// its own grid.
fn exactness(design: &FitDesign) -> anyhow::Result<f64> {
    Ok(match design {
        FitDesign::Single(d) | FitDesign::Trimmed(d, _) => {
            let g = generate(d, &GenerateOptions::default())?.grid;
            let m = measure(&g);
            match d.mesh {
                MeshKind::Circular => m.max_error(),
                MeshKind::Conical => m.max_error_conical(conical_error(&g)),
            }
        }
        FitDesign::Patches(d) | FitDesign::TrimmedPatches(d, _) => patches_exactness(d)?,
    })
}

/// A distance relative to the target's size, in model units and relative.
fn both(relative: f64, size: f64) -> String {
    format!(
        "{} model units ({} of the size)",
        num(relative * size),
        num(relative)
    )
}

/// Writes the design of a `--tolerance` fit (and its picture), prints the report a
/// designer looks at, and says whether it is within the tolerance.
fn finish_tolerance(
    args: &ApproximateArgs,
    points: &[DVec3],
    fit: &ToleranceFit,
    picture: Option<(&PathBuf, Picture)>,
) -> anyhow::Result<Outcome> {
    let file = args.target.display().to_string();
    let target = TargetCloud::new(points).with_context(|| file.clone())?;
    let report = fit_report(&target, &fit.design, args.angle_tol.to_radians())
        .with_context(|| file.clone())?;
    let mut out = Outputs::new();
    let (trimmed_path, trimmed_format) = trimmed_output(args)?;
    let design = Trimmable::of_fit(&fit.design);
    let boundaries = match &design {
        Trimmable::Surface(_) => Vec::new(),
        Trimmable::Patches(d) => patch_boundaries(&build(d, &GenerateOptions::default())?),
    };
    let outline_of = fit.design.trimmed().and(Some(&target));
    write_result_into(args, design, outline_of, &mut out)?;
    if let Some(mesh) = fit.design.trimmed() {
        write_trimmed_mesh_into(mesh, (&trimmed_path, trimmed_format), &file, &mut out)?;
    }
    if let Some((path, format)) = picture {
        let tolerance = Some(fit.limit * fit.deviation.size);
        let bytes = picture_bytes(
            &fit.single,
            &fit.grid,
            boundaries,
            points,
            &target,
            tolerance,
            format,
            fit.design.trimmed().map(|t| (t, fit.deviation)),
        )?;
        out.write(path, |w| w.write_all(&bytes))?;
    }
    out.commit()?;
    let size = fit.deviation.size;
    let mut text = format!(
        "target: {} points, size {}; tolerance {} model units ({} of the size), both ways\n{}",
        points.len(),
        num(size),
        num(fit.limit * size),
        num(fit.limit),
        stray_line(points, &fit.single.stray)
    );
    for step in &fit.steps {
        let name = match (step.patches, step.trimmed) {
            (1, true) => "1 patch, trimmed to the target's outline".to_owned(),
            (1, false) => "1 patch".to_owned(),
            (k, true) => format!("{k} patches (§4.7), trimmed to the target's outline"),
            (k, false) => format!("{k} patches (§4.7)"),
        };
        match &step.outcome {
            Ok(d) if step.resolved < d.max() => text.push_str(&format!(
                "{name}: largest distance {}; as far as the scan's points tell its edge {}\n",
                both(d.max(), size),
                both(step.resolved, size)
            )),
            Ok(d) => text.push_str(&format!(
                "{name}: largest distance {}\n",
                both(d.max(), size)
            )),
            Err(e) => text.push_str(&format!("{name}: not fitted: {e}\n")),
        }
    }
    let d = &report.deviation;
    text.push_str(&format!(
        "result: {}\n\
         largest distance mesh → target {}, target → mesh {}; RMS {} and {} model units\n\
         panels {}, {}\n",
        match fit.chosen {
            Chosen::InitialGuess =>
                "the initial guess of one patch (nearer than every fit)".to_owned(),
            Chosen::OnePatch => "1 patch".to_owned(),
            Chosen::Trimmed => "1 patch covering the target, trimmed to its outline".to_owned(),
            Chosen::Patches(k) => format!("{k} patches (§4.7)"),
            Chosen::TrimmedPatches(k) =>
                format!("{k} patches (§4.7) covering the target, trimmed to its outline"),
        },
        both(d.mesh_to_target_max, size),
        both(d.target_to_mesh_max, size),
        num(d.mesh_to_target_rms * size),
        num(d.target_to_mesh_rms * size),
        report.panels,
        match &report.node_types {
            Ok(n) => format!(
                "distinct node types {n} (beam angles within {}°, as `monge fabricate \
                 --angle-tol` groups them)",
                num(report.node_angle_tol.to_degrees())
            ),
            Err(e) => format!("node types not counted: {e}"),
        },
    ));
    for (k, p) in report.per_patch.iter().enumerate() {
        text.push_str(&format!(
            "patch {} (block {} × {}): θ {}°, largest distance target → mesh {} model units (RMS {}, {} points)\n",
            k + 1,
            p.block.0 + 1,
            p.block.1 + 1,
            num(p.theta_deg),
            num(p.max * size),
            num(p.rms * size),
            p.target_points,
        ));
    }
    text.push_str(&format!(
        "exactness of the result (generated, measured): {}\n{} meshes generated\nwrote {}{}\n",
        num(exactness(&fit.design)?),
        fit.evaluations,
        args.output.display(),
        match fit.design {
            FitDesign::Single(_) => String::new(),
            FitDesign::Trimmed(_, ref mesh) => format!(
                " ({TRIMMED_DESIGN})\nwrote {} (the result: {})",
                trimmed_path.display(),
                trimmed_faces(mesh)
            ),
            FitDesign::Patches(_) => " (a multi-patch design: `monge patches` reads it)".to_owned(),
            FitDesign::TrimmedPatches(_, ref mesh) => format!(
                " ({TRIMMED_DESIGN}: several patches)\nwrote {} (the result: {})",
                trimmed_path.display(),
                trimmed_faces(mesh)
            ),
        }
    ));
    if let Some(path) = &args.picture {
        text.push_str(&format!(
            "wrote {} (the target coloured by its distance to the result; the initial guess and \
             the result coloured by their distance to the target)\n",
            path.display()
        ));
    }
    let largest = both(fit.deviation.max(), size);
    let resolved = if fit.resolved.max() < fit.deviation.max() {
        format!(
            "; {} as far as the scan's points tell its edge",
            both(fit.resolved.max(), size)
        )
    } else {
        String::new()
    };
    let tolerance = format!("{} model units", num(fit.limit * size));
    let why = match &fit.stop {
        Stop::Met => None,
        Stop::MaxPatches(n) if fit.patches_helped() == Some(false) => Some(format!(
            "up to {n} patches tried (--max-patches {n}), the last layout ({} patches) not {}% \
             nearer than fewer patches (the distances above): more patches are unlikely to \
             reach it; split the target into parts and approximate each, or give a larger \
             --tolerance",
            fit.last_layout().unwrap_or(*n),
            num(100.0 * PATCHES_GAIN)
        )),
        Stop::MaxPatches(n) => Some(format!(
            "{n} patch{} tried (--max-patches {n}); allow more patches, give a finer --grid or \
             a larger --tolerance",
            if *n == 1 { "" } else { "es" }
        )),
        Stop::TimeLimit => {
            Some("the time limit ended the search (--time-limit); give more time".to_owned())
        }
        Stop::Refused { patches, error } => {
            Some(format!("{patches} patches cannot be fitted: {error}"))
        }
        Stop::ScanEdge { .. } => fit.stop.scan_edge_reason(size),
    };
    text.push_str(&match why {
        None => format!("within the tolerance: largest distance {largest} ≤ {tolerance}\n"),
        Some(why) => format!(
            "NOT within the tolerance: the nearest design found is {largest} from the \
             target{resolved}, above {tolerance}: {why}\n"
        ),
    });
    print(&text)?;
    Ok(if fit.met() {
        Outcome::Success
    } else {
        Outcome::Failed
    })
}
