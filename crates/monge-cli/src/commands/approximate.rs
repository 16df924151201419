//! `monge approximate`: the design whose exact mesh is nearest to a target mesh or
//! point cloud (monge's extension of the method; related to the fitting of §4.7, §4.8).

use std::path::PathBuf;
use std::time::Duration;

use anyhow::Context;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use monge_core::approximate::{
    approximate, approximate_patches, deadline_after, ApproxOptions, Approximation, Deviation,
    PatchLayout, TargetCloud,
};
use monge_core::conical::conical_dual;
use monge_core::measure::{conical_error, measure};
use monge_core::multipatch::{build, MultiPatchDesign};
use monge_core::{generate, Design, GenerateOptions, MeshKind, QuadGrid};
use monge_io::{check_output, read_points, write_design_into, write_multipatch_into, Outputs};
use monge_render::{RenderOptions, Scene};

use crate::shared::args::{Named, KINDS};
use crate::shared::help::EXIT;
use crate::shared::output::{num, print};
use crate::shared::picture::{distance_panel, sheet, Picture};
use crate::shared::Outcome;

/// Find the design whose exact mesh is nearest to a target mesh or point cloud.
#[derive(Debug, clap::Args)]
#[command(
    long_about = "Find the design (corner, two planar guides, θ) whose exactly generated mesh is \
                  nearest to TARGET both ways (mesh → target and target → mesh), by least squares \
                  (BOBYQA where they stall away from the target) from the target's principal \
                  directions at its corners, its edges fitted to the envelope of the target's \
                  points (a scan's too); prints the deviation before \
                  and after, relative to the target's size, and the measured exactness.",
    after_help = format!("Example:\n  monge approximate examples/targets/roof-pcl.obj -o roof.json --grid 20x20\n\n{EXIT}")
)]
pub struct ApproximateArgs {
    /// The target: a mesh or point cloud (`.obj`, `.ply` ASCII or binary, or `.json` with `vertices` or
    /// `points`), or NURBS surfaces (`.igs`/`.iges`, entity 128, sampled at about 4000 points).
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
    /// Also draw the initial guess and the result side by side (`.png` or `.svg`), each
    /// mesh coloured by its distance to the target on the same scale (white 0, dark red
    /// from the initial guess's 95th percentile), as `monge render --deviation` does.
    #[arg(long, value_name = "PICTURE")]
    pub picture: Option<PathBuf>,
    /// Then fit UxV patches with piecewise planar curvature lines (§4.7), e.g. 2x3:
    /// guide_u cut into U pieces and guide_v into V (K alone: Kx1), every guide and θ
    /// free; DESIGN is then a multi-patch design (the input of `monge patches`),
    /// written only if it follows the target more closely.
    #[arg(long, value_name = "UxV")]
    pub patches: Option<PatchLayout>,
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

/// The picture of the initial guess and the result side by side, coloured by their
/// distance to the target on the initial guess's scale.
fn picture_bytes(
    r: &Approximation,
    result: &QuadGrid,
    target: &TargetCloud,
    format: Picture,
) -> anyhow::Result<Vec<u8>> {
    let mesh = |design: &Design| -> anyhow::Result<QuadGrid> {
        let g = generate(design, &GenerateOptions::default())?;
        Ok(match design.mesh {
            MeshKind::Circular => g.grid,
            MeshKind::Conical => conical_dual(&g.grid).grid,
        })
    };
    let (before, scale, _) = distance_panel(
        Scene::new(mesh(&r.initial).context("the initial guess")?),
        target,
        "initial guess",
        None,
    );
    let (after, _, _) = distance_panel(Scene::new(result.clone()), target, "result", Some(scale));
    let options = RenderOptions {
        width: 1600,
        height: 700,
        ..RenderOptions::default()
    };
    sheet(&[before, after], 2, &options, format)
}

/// The largest error of the patches of `design`, each measured on its own grid as by
/// `monge check` (a multi-patch mesh's lines are planar only piecewise).
fn patches_exactness(design: &MultiPatchDesign) -> anyhow::Result<f64> {
    let mp = build(design, &GenerateOptions::default())?;
    Ok((0..mp.patches.len())
        .map(|k| measure(&mp.patch_grid(k)).max_error())
        .fold(0.0, f64::max))
}

/// Runs `monge approximate`.
pub fn run(args: &ApproximateArgs) -> anyhow::Result<Outcome> {
    let file = args.target.display().to_string();
    check_output(&args.output, &[&args.target])?;
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
    let objective = |d: &Deviation| d.mesh_to_target_rms.powi(2) + d.beyond_mesh_rms.powi(2);
    let better = patched
        .as_ref()
        .filter(|p| objective(&p.after) < objective(&r.after));
    // The design and its picture change together or not at all.
    let mut out = Outputs::new();
    let (grid, after) = match better {
        Some(p) => {
            write_multipatch_into(&p.design, &args.output, &mut out)?;
            (&p.grid, p.after)
        }
        None => {
            write_design_into(&r.design, &args.output, &mut out)?;
            (&r.grid, r.after)
        }
    };
    if let Some((path, format)) = picture {
        let target = TargetCloud::new(&points).with_context(|| file.clone())?;
        let bytes = picture_bytes(&r, grid, &target, format)?;
        out.write(path, |w| w.write_all(&bytes))?;
    }
    out.commit()?;
    let m = measure(&r.grid);
    let exactness = match args.kind {
        MeshKind::Circular => m.max_error(),
        MeshKind::Conical => m.max_error_conical(conical_error(&r.grid)),
    };
    print(&format!(
        "target: {} points, size {}; corner curvatures {} and {}\n{}{}\
         exactness of the result (generated, measured): {}\n\
         θ {}°; {} starts, {} meshes generated{}\n",
        points.len(),
        num(r.after.size),
        num(r.corner_curvatures.0),
        num(r.corner_curvatures.1),
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
    print(&format!("wrote {}\n", args.output.display()))?;
    if let Some(path) = &args.picture {
        print(&format!(
            "wrote {} (the initial guess and the result, coloured by their distance to the target)\n",
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
                "a single surface with planar curvature lines cannot follow it closer: fit \
                 several patches with piecewise planar curvature lines (§4.7, e.g. --patches 3), \
                 or split the target and approximate each part"
            } else {
                "try more patches, or split the target and approximate each part"
            },
            args.output.display(),
            args.target.display()
        ))?;
    }
    Ok(Outcome::Success)
}
