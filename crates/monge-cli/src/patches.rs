//! `monge patches` and `monge fit`: multi-patch meshes (§4.7), symmetric
//! assembly (§4.5) and fitting θ with BOBYQA (§4.7, HippoHaus).

use anyhow::Context;
use monge_core::measure::measure;
use monge_core::multipatch::{build, MultiPatch};
use monge_core::optimise::fit;
use monge_core::symmetry::{assemble, isometries};
use monge_core::GenerateOptions;
use monge_io::{
    check_output, read_multipatch, write_mesh, write_multipatch, write_output, write_quad_mesh,
    MeshFormat,
};
use serde_json::{json, Map, Value};

use crate::cli::{output_format, FitArgs, PatchesArgs};
use crate::output::{eprint, inexact_warning, num, print};
use crate::Outcome;

/// Runs `monge patches`.
pub fn run_patches(args: &PatchesArgs) -> anyhow::Result<Outcome> {
    let file = args.design.display().to_string();
    let format = output_format(args.format, &args.output)?;
    check_output(&args.output, &[&args.design])?;
    let design = read_multipatch(&args.design)?;
    let options = GenerateOptions {
        max_vertices: args.max_vertices,
    };
    let mp = build(&design, &options).with_context(|| file.clone())?;
    let mut summary = patch_summary(&mp);
    if design.symmetry.is_empty() {
        if format == MeshFormat::Json {
            let mut extra = Map::new();
            extra.insert("patches".into(), patch_json(&mp));
            extra.insert(
                "line_planes".into(),
                serde_json::to_value(mp.line_planes())?,
            );
            write_output(&args.output, |w| {
                monge_io::write_mesh_json(&mp.grid, &extra, w)
            })?;
        } else {
            write_mesh(&mp.grid, &args.output, Some(format))?;
        }
    } else {
        let copy = mp.grid.rows * mp.grid.cols;
        let isos = isometries(&design.symmetry, args.max_vertices / copy.max(1))
            .with_context(|| format!("{file} (--max-vertices {})", args.max_vertices))?;
        let a = assemble(std::slice::from_ref(&mp.grid), &isos);
        // Each patch of each copy: the copies' columns are only piecewise planar.
        let worst = isos
            .iter()
            .flat_map(|iso| (0..mp.patches.len()).map(|k| iso.apply(&mp.patch_grid(k))))
            .map(|g| measure(&g).max_error())
            .fold(0.0, f64::max);
        summary.push_str(&format!(
            "symmetry: {} copies merged into {} vertices and {} quads (merge distance {}, largest \
             merged gap {}, largest node-axis angle at merged vertices {} rad); worst measured \
             error over the patches of every copy {}\n",
            a.copies.len(),
            a.mesh.vertices.len(),
            a.mesh.quads.len(),
            num(a.merge_distance),
            num(a.max_merge_gap),
            num(a.max_axis_gap),
            num(worst)
        ));
        write_quad_mesh(&a.mesh, &args.output, Some(format))?;
    }
    eprint(&summary);
    eprint(&patch_warnings(&mp));
    Ok(Outcome::Success)
}

/// A warning for each patch whose measured error exceeds its design's
/// tolerance, with the likely cause ([`inexact_warning`]).
fn patch_warnings(mp: &MultiPatch) -> String {
    mp.patches
        .iter()
        .enumerate()
        .map(|(k, p)| {
            let grid = mp.patch_grid(k);
            inexact_warning(
                &format!("patch {k}"),
                measure(&grid).max_error(),
                p.design.tolerance.unwrap_or_default().planarity,
                &grid.vertices,
                p.folded_faces,
                Some(p.design.theta_deg),
            )
        })
        .collect()
}

/// One line per patch: where it lies, θ, mode, exactness and seam measures.
fn patch_summary(mp: &MultiPatch) -> String {
    let mut s = format!(
        "{} patches along {} in a {} × {} grid\n",
        mp.patches.len(),
        if mp.along_rows { "rows" } else { "columns" },
        mp.grid.rows,
        mp.grid.cols
    );
    for (k, p) in mp.patches.iter().enumerate() {
        s.push_str(&format!(
            "patch {k}: {} {}..={}{}, θ = {}°, {}, measured max error {}, seam gap {}, axis gap {}, \
             kink {}°{}\n",
            if mp.along_rows { "rows" } else { "columns" },
            p.range.0,
            p.range.1,
            if p.reversed { " (reversed)" } else { "" },
            num(p.design.theta_deg),
            p.mode,
            num(measure(&mp.patch_grid(k)).max_error()),
            num(p.seam_gap),
            num(p.axis_gap),
            num(p.kink_deg),
            if p.folded_faces > 0 {
                format!(", WARNING {} folded faces (§5.2)", p.folded_faces)
            } else {
                String::new()
            }
        ));
    }
    s
}

/// The patches as JSON (for the mesh file).
fn patch_json(mp: &MultiPatch) -> Value {
    Value::Array(
        mp.patches
            .iter()
            .enumerate()
            .map(|(k, p)| {
                json!({
                    "theta_deg": p.design.theta_deg,
                    "range": [p.range.0, p.range.1],
                    "reversed": p.reversed,
                    "size": [p.size.0, p.size.1],
                    "mode": p.mode.to_string(),
                    "theta_range_deg": [p.theta_range.min_deg, p.theta_range.max_deg],
                    "max_error": measure(&mp.patch_grid(k)).max_error(),
                    "seam_gap": p.seam_gap,
                    "axis_gap": p.axis_gap,
                    "kink_deg": p.kink_deg,
                    "folded_faces": p.folded_faces,
                })
            })
            .collect(),
    )
}

/// Runs `monge fit`.
pub fn run_fit(args: &FitArgs) -> anyhow::Result<Outcome> {
    let file = args.design.display().to_string();
    check_output(&args.output, &[&args.design])?;
    let design = read_multipatch(&args.design)?;
    let options = GenerateOptions {
        max_vertices: args.max_vertices,
    };
    let r = fit(&design, &options).with_context(|| file.clone())?;
    write_multipatch(&r.design, &args.output)?;
    let mut s = format!(
        "before: largest distance {} (rms {}, {} of the model size)\n\
         after:  largest distance {} (rms {}, {} of the model size)\n",
        num(r.before.max),
        num(r.before.rms),
        num(r.before.relative),
        num(r.after.max),
        num(r.after.rms),
        num(r.after.relative)
    );
    for (name, start, end, bounds) in &r.values {
        s.push_str(&format!(
            "{name}: {} -> {} (bounds [{}, {}])\n",
            num(*start),
            num(*end),
            num(bounds[0]),
            num(bounds[1])
        ));
    }
    s.push_str(&format!(
        "BOBYQA: {} meshes generated; {}\nwrote {}\n",
        r.evaluations,
        r.status,
        args.output.display()
    ));
    print(&s)?;
    // The fitted design's patches, measured as `monge patches` measures them.
    let fitted = build(&r.design, &options).with_context(|| file.clone())?;
    eprint(&patch_warnings(&fitted));
    Ok(Outcome::Success)
}
