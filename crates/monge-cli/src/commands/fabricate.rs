//! `monge fabricate`: a design → the gridshell's schedules, drawings and model (§6).

use std::path::PathBuf;
use std::time::Instant;

use anyhow::Context;
use glam::DVec3;
use monge_core::conical::{conical_dual, conical_folds};
use monge_core::fabrication::{fabricate, BaseMesh, FabricationOptions, Summary};
use monge_core::{generate, BasePoint, GenerateOptions, MeshKind};
use monge_io::generated::{max_error, with_folds};
use monge_io::{check_fabrication_output, read_design, write_fabrication, ScheduleJson};

use crate::shared::args::{parse_finite, parse_non_negative};
use crate::shared::help::EXIT;
use crate::shared::output::{
    check_output_size, eprint, inexact_warning, millis, num, parse_gigabytes, print, MAX_OUTPUT_GB,
};
use crate::shared::warnings::generation_warnings;
use crate::shared::Outcome;

/// Fabrication output of a gridshell: layers, panels, beams, nodes (§6).
#[derive(Debug, clap::Args)]
#[command(
    long_about = "Fabrication output of a gridshell built on the design's mesh (§6, Figure 25).\n\n\
         Generates the mesh (the conical dual for `\"mesh\": \"conical\"`), offsets it to every \
         --layers distance (node offsets along the node axes §2.2, face offsets §2.3), and writes \
         into DIR, all files or none (if one cannot be written, no file in DIR changes): panels.csv (every face flattened exactly in its plane: \
         outline, edges, angles, area, circumradius, residuals), beams.csv and segments.csv \
         (every row and column in its plane, split into circular arcs where the circle changes, \
         §4.6: radius, sweep, centre, split nodes, length along the arcs: the roller-bender list), nodes.csv (axis, \
         beam angles, height across the layers, torsion, node type), schedule.json (the \
         summary and the layers; with --full-json also every panel, beam and node), panels.dxf and beams.dxf (R12 drawings, labelled), overview.svg (plan) and \
         gridshell.glb (glTF of all layers, beams swept with a rectangular section). Prints a \
         summary: counts, segments per beam, distinct radii, node types, node heights, worst \
         residuals. Lengths and residuals in the files and the summary are in the model's \
         units; --tol is relative to the model's size (the summary prints it).",
    after_help = format!(
        "Examples:\n  \
         monge fabricate examples/fig12-dupin-theta30.json -o out --layers 0,0.1,0.2\n  \
         monge fabricate examples/fig25-biarc.json -o out --layers 0,-0.1,-0.2 --section 0.05,0.1\n\n{EXIT}"
    )
)]
pub struct FabricateArgs {
    /// The design file (`.json` or `.toml`); `"mesh": "conical"` fabricates the conical dual.
    #[arg(value_name = "DESIGN")]
    pub design: PathBuf,
    /// Output directory (created if missing, in a directory that exists); existing files of the
    /// same names are replaced.
    #[arg(short, long, value_name = "DIR")]
    pub output: PathBuf,
    /// Comma-separated layer distances along the node axes (node offsets §2.2; face offsets
    /// §2.3 for a conical design), in model units.
    #[arg(
        long,
        value_name = "D,D,…",
        value_delimiter = ',',
        default_value = "0",
        allow_negative_numbers = true,
        value_parser = parse_finite
    )]
    pub layers: Vec<f64>,
    /// Relative length tolerance (× model size) for a node to lie on a beam segment's circle.
    #[arg(long, value_name = "TOL", default_value = "1e-9", value_parser = parse_non_negative, allow_negative_numbers = true)]
    pub tol: f64,
    /// Relative tolerance (× model size) within which radii count as one [default: --tol].
    #[arg(long, value_name = "TOL", value_parser = parse_non_negative, allow_negative_numbers = true)]
    pub radius_tol: Option<f64>,
    /// Nodes whose beam angles agree within this many degrees are one node type.
    #[arg(long, value_name = "DEG", default_value = "1e-4", value_parser = parse_non_negative, allow_negative_numbers = true)]
    pub angle_tol: f64,
    /// Beam cross-section in the glTF: WIDTH,DEPTH (model units) [default: size/200 each].
    #[arg(long, value_name = "W,D", value_delimiter = ',', num_args = 1, value_parser = parse_non_negative, allow_negative_numbers = true)]
    pub section: Vec<f64>,
    /// Write every panel, beam and node into schedule.json too (by default it holds the summary
    /// and the layers, and the schedules are the CSV files): about 1.7 kB more a face and layer.
    #[arg(long)]
    pub full_json: bool,
    /// Refuse grids of more than N vertices (rows × cols).
    #[arg(long, value_name = "N", default_value_t = GenerateOptions::default().max_vertices)]
    pub max_vertices: usize,
    /// Refuse outputs estimated above this many gigabytes (10⁹ bytes), before computing
    /// them: the files take about 2.6 kB a face and layer (4.4 kB with --full-json), and
    /// memory about 1.1 kB.
    #[arg(long, value_name = "GB", default_value_t = MAX_OUTPUT_GB, value_parser = parse_gigabytes)]
    pub max_output: f64,
    /// Write coordinates relative to a base point: `start` (the guides' common start point) or
    /// X,Y,Z, to keep full precision far from the origin (as `monge generate --base-point`).
    /// schedule.json records it (`base_point`) and gridshell.glb's nodes are translated by it;
    /// the CSV coordinates are relative to it; the DXF drawings, laid out in each part's plane,
    /// do not depend on it.
    #[arg(long, value_name = "start|X,Y,Z", allow_hyphen_values = true)]
    pub base_point: Option<BasePoint>,
}

/// Bytes the fabrication files take per face and layer (measured with `monge bench`'s
/// design: 2622 at 400 × 400 faces, 2605 at 1000 × 1000).
const BYTES_PER_FACE: f64 = 2650.0;

/// Bytes `--full-json` adds to schedule.json per face and layer (measured: 1734 at
/// 400 × 400 faces).
const FULL_JSON_BYTES_PER_FACE: f64 = 1750.0;

/// Runs `monge fabricate`.
pub fn run(args: &FabricateArgs) -> anyhow::Result<Outcome> {
    if !args.section.is_empty() && args.section.len() != 2 {
        anyhow::bail!(
            "--section takes WIDTH,DEPTH (two numbers), got {} number(s)",
            args.section.len()
        );
    }
    if let [w, d] = args.section[..] {
        anyhow::ensure!(
            w > 0.0 && d > 0.0 && w.is_finite() && d.is_finite(),
            "--section {w},{d}: give a positive, finite width and depth"
        );
    }
    anyhow::ensure!(
        !monge_io::is_stdio(&args.output),
        "fabricate writes a directory of nine files: give a directory for -o, not `-`"
    );
    // The files go into OUT: none of them may be the design.
    check_fabrication_output(&args.output, &[&args.design])?;
    let (design, base_point) = match &args.base_point {
        Some(b) => b.apply(read_design(&args.design)?),
        None => (read_design(&args.design)?, None),
    };
    let base_point = base_point.map(DVec3::from_array);
    let start = Instant::now();
    let options = GenerateOptions {
        max_vertices: args.max_vertices,
    };
    let generated =
        generate(&design, &options).with_context(|| args.design.display().to_string())?;
    let grid = &generated.grid;
    let conical = (design.mesh == MeshKind::Conical).then(|| conical_dual(grid));
    // As `monge generate` warns: a folded or near-singular mesh makes panels and
    // beams that cross each other.
    let report = match &conical {
        Some(c) => with_folds(
            &generated.report,
            &conical_folds(&c.grid, Some(&c.face_normals)),
        ),
        None => generated.report,
    };
    eprint(&generation_warnings(generated.info.theta_deg, &report));
    let mesh = conical.as_ref().map_or(grid, |c| &c.grid);
    eprint(&inexact_warning(
        &format!("the mesh of `{}`", args.design.display()),
        max_error(mesh, design.mesh),
        design.tolerance.unwrap_or_default().planarity,
        &mesh.vertices,
        report.folded_faces,
        Some(generated.info.theta_deg),
    ));
    let faces = grid.rows.saturating_sub(1) * grid.cols.saturating_sub(1);
    let (json, per_face) = if args.full_json {
        (
            ScheduleJson::Full,
            BYTES_PER_FACE + FULL_JSON_BYTES_PER_FACE,
        )
    } else {
        (ScheduleJson::Summary, BYTES_PER_FACE)
    };
    check_output_size(
        per_face * (faces * args.layers.len()) as f64,
        args.max_output,
        &format!(
            "the fabrication files of {} × {} faces and {} layer(s)",
            grid.rows.saturating_sub(1),
            grid.cols.saturating_sub(1),
            args.layers.len()
        ),
        "use fewer guide samples or fewer --layers",
    )?;
    let base = match &conical {
        Some(c) => BaseMesh::Conical(c),
        None => BaseMesh::Circular(grid),
    };
    let fab_options = FabricationOptions {
        layers: args.layers.clone(),
        tol: args.tol,
        radius_tol: args.radius_tol.unwrap_or(args.tol),
        angle_tol: args.angle_tol.to_radians(),
    };
    let f = fabricate(base, &fab_options).with_context(|| args.design.display().to_string())?;
    let computed = start.elapsed().as_secs_f64();
    let section = match args.section[..] {
        [w, d] => (w, d),
        _ => (f.summary.size / 200.0, f.summary.size / 200.0),
    };
    let start = Instant::now();
    let paths = write_fabrication(&args.output, &f, section, json, base_point)?;
    eprint(&format!(
        "computed in {} ms, wrote {} files to `{}` in {} ms.\n",
        millis(computed),
        paths.len(),
        args.output.display(),
        millis(start.elapsed().as_secs_f64())
    ));
    if let Some(b) = base_point {
        eprint(&format!(
            "coordinates written relative to the base point ({}, {}, {}), recorded in \
             schedule.json (`base_point`) and as gridshell.glb's node translation.\n",
            num(b.x),
            num(b.y),
            num(b.z)
        ));
    }
    print(&summary(&f.summary, design.mesh))?;
    Ok(Outcome::Success)
}

/// The summary printed on standard output.
fn summary(s: &Summary, kind: MeshKind) -> String {
    let kind = match kind {
        MeshKind::Circular => "circular mesh, node offsets (§2.2)",
        MeshKind::Conical => "conical mesh, face offsets (§2.3)",
    };
    let layers: Vec<String> = s.layers.iter().map(|d| num(*d)).collect();
    let mut out = format!(
        "gridshell: {kind}; layers at {}; model size {}\n\
         counts: {} panels, {} beams, {} nodes\n",
        layers.join(", "),
        num(s.size),
        s.panels,
        s.beams,
        s.nodes
    );
    for fam in &s.families {
        let name = match fam.family {
            monge_core::fabrication::LineFamily::Row => "rows (along guide_v)",
            monge_core::fabrication::LineFamily::Column => "columns (along guide_u)",
        };
        let segments = if fam.min_segments == fam.max_segments {
            fam.min_segments.to_string()
        } else {
            format!("{}–{}", fam.min_segments, fam.max_segments)
        };
        out.push_str(&format!(
            "{name}: {} beams, {segments} segment(s) each, at most {} radius(es) per beam, \
             {} distinct radii, {} straight segments\n",
            fam.beams, fam.max_radii_per_beam, fam.distinct_radii, fam.straight_segments
        ));
    }
    let radii = match s.radii.as_slice() {
        [] => "none".to_owned(),
        [a] => num(*a),
        [a, .., b] => format!("{} to {}", num(*a), num(*b)),
    };
    out.push_str(&format!(
        "distinct radii: {} ({radii})\n\
         node types: {}\n\
         node height: {} to {}\n\
         max residuals: offset {}, panel planarity {}{}, beam plane {}, arc {}, torsion {}\n",
        s.radii.len(),
        s.node_types,
        num(s.node_height.0),
        num(s.node_height.1),
        sci(s.max_offset_deviation),
        sci(s.max_panel_planarity),
        s.max_panel_circularity
            .map_or(String::new(), |c| format!(", panel circularity {}", sci(c))),
        sci(s.max_beam_plane_residual),
        sci(s.max_arc_residual),
        sci(s.max_torsion)
    ));
    out
}

/// A residual in scientific notation, `0` for zero.
fn sci(x: f64) -> String {
    if x == 0.0 {
        "0".to_owned()
    } else {
        format!("{x:.1e}")
    }
}
