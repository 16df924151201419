//! `monge smooth`: the cyclidic net of a design (§4.4): a C¹ surface of Dupin
//! cyclide patches whose curvature lines are planar chains of circular arcs.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{bail, Context};
use glam::DVec3;
use monge_core::cyclidic::{CyclidicNet, CyclidicOptions, Frame};
use monge_core::measure::measure;
use monge_core::{generate, GenerateOptions, MeshKind, Tolerances};
use monge_io::{
    check_output, conical_has_no_net, read_design, read_mesh, write_iges, write_mesh_to,
    write_net_json, write_output, MeshFormat,
};

use crate::shared::args::parse_tolerance;
use crate::shared::help::EXIT;
use crate::shared::output::{check_output_size, eprint, inexact_warning, millis};
use crate::shared::Outcome;

/// Build the smooth C¹ surface of a design: a cyclidic net of Dupin cyclide patches.
#[derive(Debug, clap::Args)]
#[command(
    long_about = format!(
        "Build the cyclidic net of a design (§4.4): one Dupin cyclide patch per face of its \
         circular mesh, with the frames of §4.4, so that patches share their boundary arcs and \
         tangent planes (C¹) and every curvature line is a planar chain of circular arcs: \
         one arc where the mesh line is inscribed in a circle, bi-arcs where it is inscribed \
         in two (§4.6).\n\n\
         OUT `.json`: `patches` (per face (i, j): the patch sampled on a K × K grid of its own \
         (u, v), row-major, (0, 0) at vertex (i, j), u towards (i+1, j), v towards (i, j+1)) and \
         `lines` (per mesh line: family `u` or `v`, index, and its arcs: center, radius, \
         normal, start, end). OUT `.igs`: the whole net as one exact NURBS surface (IGES \
         entity 128, rational, degree 2 × 2), which Rhino and other CAD tools open. OUT `.obj` \
         or `.ply`: the dense mesh of the whole net. A mesh \
         with folded faces (§5.2: crossed or non-convex, or turned over against the others; \
         the faces `monge check` counts) is refused unless --allow-folded, naming the first."
    ),
    after_help = format!(
        "Examples:\n  \
         monge smooth examples/fig12-dupin-theta30.json -o net.json --samples 9\n  \
         monge smooth examples/fig13-freeform.json -o smooth.obj\n\n{EXIT}"
    )
)]
pub struct SmoothArgs {
    /// The design file (`.json` or `.toml`).
    #[arg(value_name = "DESIGN")]
    pub design: PathBuf,
    /// Output: `.json` (patches and arcs), `.igs` (exact NURBS), `.obj`, `.ply` or `.glb` (dense
    /// mesh).
    #[arg(short, long, value_name = "OUT")]
    pub output: PathBuf,
    /// Samples per patch side, K ≥ 2 (K × K points a patch).
    #[arg(long, value_name = "K", default_value_t = 9, value_parser = clap::value_parser!(u32).range(2..=1000))]
    pub samples: u32,
    /// Refuse outputs estimated above this many gigabytes (10⁹ bytes), before computing
    /// them: about 60 bytes a sample point in `.json`, 190 a dense vertex in `.obj`.
    #[arg(long, value_name = "GB", default_value_t = crate::shared::output::MAX_OUTPUT_GB, value_parser = crate::shared::output::parse_gigabytes)]
    pub max_output: f64,
    /// Build the net over folded faces (those `monge check` counts) instead of refusing the mesh.
    #[arg(long)]
    pub allow_folded: bool,
    /// Largest accepted non-circularity of a face: |Im q| / |q| for the cross-ratio q of
    /// its corners (0 for a circle). Raise it for a mesh that is only nearly circular.
    #[arg(long, value_name = "TOL", default_value_t = CyclidicOptions::default().circularity_tolerance, value_parser = parse_tolerance)]
    pub circularity_tol: f64,
    /// DESIGN is a circular quad mesh (`.obj`, `.ply` or `.json`, row-major grid), not a design:
    /// the net is built on it (its lines need not be planar; then neither are the net's).
    #[arg(long)]
    pub mesh: bool,
    /// The frame at vertex (0, 0), carried over the whole mesh by reflections (§4.4), as
    /// `t1x,t1y,t1z,t2x,t2y,t2z` (orthonormal; t1 towards (1, 0), t2 towards (0, 1)).
    /// Default: the frames of §4.4 from the node axes, which make the curvature lines planar.
    #[arg(
        long,
        value_name = "T1,T2",
        value_delimiter = ',',
        allow_negative_numbers = true
    )]
    pub frame: Option<Vec<f64>>,
}

/// Runs `monge smooth`.
pub fn run(args: &SmoothArgs) -> anyhow::Result<Outcome> {
    let out = args.output.as_path();
    let ext = out.extension().and_then(|e| e.to_str()).unwrap_or("");
    let output = if ext.eq_ignore_ascii_case("json") {
        SmoothOutput::Json
    } else if ext.eq_ignore_ascii_case("igs") || ext.eq_ignore_ascii_case("iges") {
        SmoothOutput::Iges
    } else if let Some(format) = MeshFormat::from_extension(ext) {
        SmoothOutput::Mesh(format)
    } else {
        bail!(
            "cannot tell what to write to `{}`: monge smooth writes `.json` (patches and arcs), \
             `.igs` or `.iges` (the exact NURBS surface), or `.obj`, `.ply` or `.glb` (a dense mesh)",
            out.display()
        );
    };
    check_output(out, &[&args.design])?;
    let start = Instant::now();
    // The mesh, its tolerance and θ (none for a mesh file).
    let (grid, tolerance, theta) = if args.mesh {
        (
            read_mesh(&args.design)?,
            Tolerances::default().planarity,
            None,
        )
    } else {
        let design = read_design(&args.design)?;
        if design.mesh == MeshKind::Conical {
            bail!("{}", conical_has_no_net(&args.design.display().to_string()));
        }
        let g = generate(&design, &GenerateOptions::default())
            .with_context(|| args.design.display().to_string())?;
        let tolerance = design.tolerance.unwrap_or_default().planarity;
        (g.grid, tolerance, Some(g.info.theta_deg))
    };
    let k = args.samples as usize;
    let (what, bytes) = estimate(&output, grid.rows, grid.cols, k);
    check_output_size(
        bytes,
        args.max_output,
        &format!("`{}`, {what},", out.display()),
        "lower --samples or use fewer guide samples",
    )?;
    let options = CyclidicOptions {
        allow_folded: args.allow_folded,
        circularity_tolerance: args.circularity_tol,
        ..CyclidicOptions::default()
    };
    let net = match &args.frame {
        Some(f) => {
            if f.len() != 6 {
                bail!(
                    "--frame takes 6 numbers, t1x,t1y,t1z,t2x,t2y,t2z; got {}",
                    f.len()
                );
            }
            let frame = Frame::new(DVec3::new(f[0], f[1], f[2]), DVec3::new(f[3], f[4], f[5]));
            CyclidicNet::from_frame(&grid, frame, &options)
        }
        None => CyclidicNet::from_normals(&grid, &options),
    }
    .with_context(|| format!("{}: the cyclidic net", args.design.display()))?;
    let elapsed = start.elapsed().as_secs_f64();
    match output {
        SmoothOutput::Json => write_output(out, |w| write_net_json(&net, k, w))?,
        // The NURBS surface computed as it is written.
        SmoothOutput::Iges => write_output(out, |w| write_iges(&net, w))?,
        SmoothOutput::Mesh(f) => {
            let dense = net.dense(k);
            write_output(out, |w| write_mesh_to(&dense, f, w))?;
        }
    }
    let (lines, arcs) = net
        .curvature_lines_iter()
        .fold((0, 0), |(lines, arcs), l| (lines + 1, arcs + l.arcs.len()));
    eprint(&format!(
        "{}: cyclidic net (§4.4) of {} × {} Dupin cyclide patches, C¹, {}: \
         {} mesh lines made of {arcs} circular arcs. Built in {} ms; wrote `{}` ({k} × {k} samples \
         a patch).\n",
        args.design.display(),
        net.rows() - 1,
        net.cols() - 1,
        if args.frame.is_some() {
            "frames carried from the given one (curvature lines planar only if it is the §4.4 frame)"
        } else {
            "frames from the node axes: planar curvature lines"
        },
        lines,
        millis(elapsed),
        out.display()
    ));
    // The net is as exact as the mesh under it, measured as `monge check` does.
    eprint(&inexact_warning(
        &format!("the mesh under the net (of `{}`)", args.design.display()),
        measure(&grid).max_error(),
        tolerance,
        &grid.vertices,
        net.folded().len(),
        theta,
    ));
    Ok(Outcome::Success)
}

/// The output of a net on a `rows × cols` mesh with `k × k` samples a patch: what
/// it holds and about how many bytes it takes (measured on
/// examples/fig13-freeform.json made finer: 58 bytes a sample point and about 330
/// an arc in JSON, 181 (OBJ), 145 (PLY) and 36 (glTF) a dense vertex, 108 an
/// IGES control point).
fn estimate(output: &SmoothOutput, rows: usize, cols: usize, k: usize) -> (String, f64) {
    let (fr, fc) = (rows.saturating_sub(1), cols.saturating_sub(1));
    match output {
        SmoothOutput::Json => {
            let arcs = rows * fc + cols * fr;
            (
                format!("{fr} × {fc} patches of {k} × {k} points and {arcs} arcs"),
                60.0 * (fr * fc * k * k) as f64 + 330.0 * arcs as f64,
            )
        }
        SmoothOutput::Iges => {
            let points = (2 * rows).saturating_sub(1) * (2 * cols).saturating_sub(1);
            (format!("{points} control points"), 110.0 * points as f64)
        }
        SmoothOutput::Mesh(format) => {
            let (dr, dc) = (fr * (k - 1) + 1, fc * (k - 1) + 1);
            let per_vertex = match format {
                MeshFormat::Glb | MeshFormat::PlyF32 => 40.0,
                MeshFormat::PlyBinary => 70.0,
                MeshFormat::Ply => 150.0,
                MeshFormat::Obj | MeshFormat::Json => 190.0,
            };
            (
                format!("a dense mesh of {dr} × {dc} vertices"),
                per_vertex * (dr * dc) as f64,
            )
        }
    }
}

/// What `monge smooth` writes, by OUT's extension.
enum SmoothOutput {
    /// Patches and arcs.
    Json,
    /// The whole net as one exact rational B-spline surface (IGES entity 128).
    Iges,
    /// The dense mesh.
    Mesh(MeshFormat),
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The bytes each output of fig13-freeform's net actually takes, against the estimate.
    #[test]
    fn the_estimate_is_within_a_factor_of_two_of_the_bytes_written() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../examples/fig13-freeform.json"
        );
        let design = read_design(std::path::Path::new(path)).unwrap();
        let grid = generate(&design, &GenerateOptions::default()).unwrap().grid;
        let net = CyclidicNet::from_normals(&grid, &CyclidicOptions::default()).unwrap();
        let k = 4;
        let outputs = [
            SmoothOutput::Json,
            SmoothOutput::Iges,
            SmoothOutput::Mesh(MeshFormat::Obj),
            SmoothOutput::Mesh(MeshFormat::Ply),
            SmoothOutput::Mesh(MeshFormat::Glb),
        ];
        for output in outputs {
            let mut bytes = Vec::new();
            match &output {
                SmoothOutput::Json => write_net_json(&net, k, &mut bytes).unwrap(),
                SmoothOutput::Iges => write_iges(&net, &mut bytes).unwrap(),
                SmoothOutput::Mesh(f) => write_mesh_to(&net.dense(k), *f, &mut bytes).unwrap(),
            }
            let (what, estimate) = estimate(&output, grid.rows, grid.cols, k);
            let ratio = estimate / bytes.len() as f64;
            assert!(
                (0.5..2.0).contains(&ratio),
                "{what}: {estimate} estimated, {} written",
                bytes.len()
            );
        }
    }
}
