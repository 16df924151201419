//! `monge smooth`: the cyclidic net of a design (§4.4): a C¹ surface of Dupin
//! cyclide patches whose curvature lines are planar chains of circular arcs.

use std::io::{self, Write};
use std::time::Instant;

use anyhow::{bail, Context};
use glam::DVec3;
use monge_core::cyclidic::{CyclidicNet, CyclidicOptions, Family, Frame};
use monge_core::{generate, GenerateOptions, MeshKind};
use monge_io::{read_design, read_mesh, write_iges, write_mesh_to, write_output, MeshFormat};
use serde_json::{json, Value};

use crate::cli::SmoothArgs;
use crate::output::{eprint, millis};
use crate::Outcome;

/// Runs `monge smooth`.
pub fn run(args: &SmoothArgs) -> anyhow::Result<Outcome> {
    let out = args.output.as_path();
    let ext = out.extension().and_then(|e| e.to_str()).unwrap_or("");
    let output = if ext.eq_ignore_ascii_case("json") {
        SmoothOutput::Json
    } else if ext.eq_ignore_ascii_case("igs") || ext.eq_ignore_ascii_case("iges") {
        SmoothOutput::Iges
    } else {
        SmoothOutput::Mesh(MeshFormat::from_path(out).context(
            "monge smooth writes `.json` (patches and arcs), `.igs` (the exact NURBS surface), \
             or `.obj`/`.ply` (a dense mesh)",
        )?)
    };
    let start = Instant::now();
    let grid = if args.mesh {
        read_mesh(&args.design)?
    } else {
        let design = read_design(&args.design)?;
        if design.mesh == MeshKind::Conical {
            bail!(
                "{}: the design asks for a conical mesh (`\"mesh\": \"conical\"`), but the cyclidic \
                 net (§4.4) is built on circular meshes: each patch is a Dupin cyclide through the \
                 four corners of a circular face, and a conical mesh's faces are not circular. \
                 Remove `\"mesh\": \"conical\"` to get the net of the design's circular mesh \
                 (whose conical dual, §2.3, the design describes)",
                args.design.display()
            );
        }
        generate(&design, &GenerateOptions::default())
            .with_context(|| args.design.display().to_string())?
            .grid
    };
    let options = CyclidicOptions {
        allow_folded: args.allow_folded,
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
    let k = args.samples as usize;
    match output {
        SmoothOutput::Json => write_output(out, |w| write_net_json(&net, k, w))?,
        SmoothOutput::Iges => {
            let surface = net.nurbs();
            write_output(out, |w| write_iges(&surface, w))?;
        }
        SmoothOutput::Mesh(f) => {
            let dense = net.dense(k);
            write_output(out, |w| write_mesh_to(&dense, f, w))?;
        }
    }
    let lines = net.curvature_lines();
    let arcs: usize = lines.iter().map(|l| l.arcs.len()).sum();
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
        lines.len(),
        millis(elapsed),
        out.display()
    ));
    Ok(Outcome::Success)
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

/// The JSON contract of `monge smooth -o net.json`: `patches` (each sampled on
/// a K × K grid of its own (u, v), row-major) and `lines` (chains of arcs).
fn write_net_json(net: &CyclidicNet, k: usize, w: &mut dyn Write) -> io::Result<()> {
    let xyz = |p: DVec3| json!([p.x, p.y, p.z]);
    let patches: Vec<Value> = (0..net.rows() - 1)
        .flat_map(|i| (0..net.cols() - 1).map(move |j| (i, j)))
        .map(|(i, j)| {
            let points: Vec<Value> = net.sample_patch(i, j, k).into_iter().map(xyz).collect();
            json!({"i": i, "j": j, "rows": k, "cols": k, "points": points})
        })
        .collect();
    let lines: Vec<Value> = net
        .curvature_lines()
        .into_iter()
        .map(|l| {
            let arcs: Vec<Value> = l
                .arcs
                .iter()
                .map(|a| {
                    json!({
                        "center": xyz(a.center),
                        "radius": a.radius,
                        "normal": xyz(a.normal),
                        "start": xyz(a.start),
                        "end": xyz(a.end),
                        "sweep_deg": a.sweep().to_degrees(),
                    })
                })
                .collect();
            let family = match l.family {
                Family::U => "u",
                Family::V => "v",
            };
            json!({"family": family, "index": l.index, "arcs": arcs})
        })
        .collect();
    let doc = json!({
        "rows": net.rows(),
        "cols": net.cols(),
        "patches": patches,
        "lines": lines,
    });
    serde_json::to_writer(&mut *w, &doc)?;
    writeln!(w)
}
