//! `monge patches`: multi-patch meshes (§4.7), optionally assembled by
//! symmetry (§4.5).

use std::path::PathBuf;

use anyhow::Context;
use monge_core::measure::measure;
use monge_core::multipatch::{build, MultiPatch};
use monge_core::symmetry::{assemble, isometries};
use monge_core::GenerateOptions;
use monge_io::{read_multipatch, write_mesh, write_output, write_quad_mesh, MeshFormat};
use serde_json::{json, Map, Value};

use crate::shared::args::MeshOutput;
use crate::shared::help::{EXIT, THETA};
use crate::shared::output::{eprint, num};
use crate::shared::warnings::patch_warnings;
use crate::shared::Outcome;

/// Build a multi-patch mesh (§4.7), optionally assembled by symmetry (§4.5).
#[derive(Debug, clap::Args)]
#[command(
    long_about = format!(
        "Build a mesh with piecewise planar curvature lines from a multi-patch design \
         (§4.7, Figures 20 and 21) and write it as OBJ, PLY or JSON.\n\n\
         A multi-patch design (`.json` or `.toml`) has `patches`: the first with `theta_deg`, \
         `guide_u` and `guide_v` like a design file; every later one with its own \
         `theta_deg`, `attach`: {{\"patch\": K, \"side\": S}} (S = `last_row`, `first_row`, \
         `last_column` or `first_column` of the earlier patch K, in K's own grid) and \
         `guide`: the continuation, which must start at the first vertex of that line. The \
         line becomes one guide of the new patch, the continuation the other (for a row \
         side it continues guide_u, for a column side guide_v; a `first_` side runs \
         backwards). Start tangents are forced so that the node axes continue across the \
         seam: draw the continuation in the plane of the guide it continues (one planar \
         bottom guide cut in pieces) and the beams are C¹ there. Patches in several rows \
         and columns (e.g. 2 × 2): a patch next to two earlier ones gives, instead of \
         `guide`, `guide_from`: {{\"patch\": L, \"side\": S}}, the other earlier patch's line \
         through the same corner (a row side when `attach` is a column side, and the other \
         way round). The patches must fill a rectangle of blocks, each sharing its lines \
         with its neighbours: the result is one grid, shared lines stored once.\n\n\
         Optional `symmetry`: a list of {{\"mirror\": {{\"point\", \"normal\"}}}} and \
         {{\"rotate\": {{\"point\", \"axis\", \"order\"}}}}, applied in order to all copies so \
         far (Figure 18: a mirror then order 5); the copies are merged where vertices \
         coincide (1e-9 of the size) into one quad mesh (OBJ/PLY/JSON with `quads`).\n\n\
         Without symmetry, JSON output has the grid plus `patches` (range, θ, mode, measured \
         max error, seam and axis gaps, kink; for a layout of several rows and columns also \
         block, rows, columns and flipped) and `line_planes` (for each row and column the \
         plane it lies in within each patch it crosses). A summary goes to stderr.\n\n{THETA}"
    ),
    after_help = format!(
        "Examples:\n  \
         monge patches examples/fig20-piecewise.patches.json -o dome.obj\n  \
         monge patches examples/fig21-hippohaus.patches.json -o - > hippo.json\n\n{EXIT}"
    )
)]
pub struct PatchesArgs {
    /// The multi-patch design file (`.json` or `.toml`).
    #[arg(value_name = "DESIGN")]
    pub design: PathBuf,
    #[command(flatten)]
    pub out: MeshOutput,
    /// Refuse patches of more than N grid vertices each.
    #[arg(long, value_name = "N", default_value_t = GenerateOptions::default().max_vertices)]
    pub max_vertices: usize,
}

/// Runs `monge patches`.
pub fn run(args: &PatchesArgs) -> anyhow::Result<Outcome> {
    let file = args.design.display().to_string();
    let format = args.out.checked_format(&[&args.design])?;
    let out = args.out.output.as_path();
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
            write_output(out, |w| monge_io::write_mesh_json(&mp.grid, &extra, w))?;
        } else {
            write_mesh(&mp.grid, out, Some(format))?;
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
        write_quad_mesh(&a.mesh, out, Some(format))?;
    }
    eprint(&summary);
    eprint(&patch_warnings(&mp));
    Ok(Outcome::Success)
}

/// One line per patch: where it lies, θ, mode, exactness and seam measures.
fn patch_summary(mp: &MultiPatch) -> String {
    let grid = is_grid(mp);
    let mut s = if grid {
        format!(
            "{} patches in a layout of {} × {} in a {} × {} grid\n",
            mp.patches.len(),
            mp.layout.0,
            mp.layout.1,
            mp.grid.rows,
            mp.grid.cols
        )
    } else {
        format!(
            "{} patches along {} in a {} × {} grid\n",
            mp.patches.len(),
            if mp.along_rows { "rows" } else { "columns" },
            mp.grid.rows,
            mp.grid.cols
        )
    };
    for (k, p) in mp.patches.iter().enumerate() {
        let place = if grid {
            format!(
                "rows {}..={}, columns {}..={}{}",
                p.rows.0,
                p.rows.1,
                p.cols.0,
                p.cols.1,
                match p.flipped {
                    (false, false) => "",
                    (true, false) => " (rows reversed)",
                    (false, true) => " (columns reversed)",
                    (true, true) => " (rows and columns reversed)",
                }
            )
        } else {
            format!(
                "{} {}..={}{}",
                if mp.along_rows { "rows" } else { "columns" },
                p.range.0,
                p.range.1,
                if p.reversed { " (reversed)" } else { "" },
            )
        };
        s.push_str(&format!(
            "patch {k}: {place}, θ = {}°, {}, measured max error {}, seam gap {}, axis gap {}, \
             kink {}°{}\n",
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

/// Whether the patches lie in several block rows and columns (else along one direction).
fn is_grid(mp: &MultiPatch) -> bool {
    mp.layout.0 > 1 && mp.layout.1 > 1
}

/// The patches as JSON (for the mesh file).
fn patch_json(mp: &MultiPatch) -> Value {
    Value::Array(
        mp.patches
            .iter()
            .enumerate()
            .map(|(k, p)| {
                let mut entry = json!({
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
                });
                if is_grid(mp) {
                    entry["block"] = json!([p.block.0, p.block.1]);
                    entry["rows"] = json!([p.rows.0, p.rows.1]);
                    entry["columns"] = json!([p.cols.0, p.cols.1]);
                    entry["flipped"] = json!([p.flipped.0, p.flipped.1]);
                }
                entry
            })
            .collect(),
    )
}
