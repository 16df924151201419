//! `monge generate`: design file → mesh file.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{bail, Context};
use glam::DVec3;
use monge_core::developable::{developable, DevelopableSpec};
use monge_core::multipatch::build;
use monge_core::{generate, BasePoint, GenerateOptions, Generated, MeshKind};
use monge_io::generated::{json_extras, layers, max_error, node_offset, Layer};
use monge_io::{
    check_output, is_stdio, read_any_design, write_mesh_at, write_output, write_trimmed_mesh_to,
    AnyDesign, MeshFormat, Outputs, Trimmable, TrimmedDesign,
};
use serde_json::{json, Map, Value};

use crate::shared::args::{parse_finite, MeshOutput};
use crate::shared::help::{EXIT, THETA};
use crate::shared::output::{eprint, far_from_origin_warning, inexact_warning, millis, num};
use crate::shared::warnings::{generation_warnings, range_text};
use crate::shared::Outcome;

/// Generate the mesh of a design and write it as OBJ, PLY or JSON.
#[derive(Debug, clap::Args)]
#[command(
    long_about = format!(
        "Generate the mesh of a design and write it as OBJ, PLY or JSON.\n\n\
         Reads DESIGN (`.json` or `.toml`), validates it (guides planar, starting at the same \
         point, meeting at 90°, θ admissible), builds the mesh exactly (§3) and writes it to OUT \
         in the format of OUT's extension (`.obj`, `.ply` or `.json`; `--format ply-binary` \
         or `ply-f32` for binary PLY with double or float coordinates), atomically: on any error \
         no file is created and an existing OUT is left untouched (with --offset, no file at \
         all). JSON output has `rows`, `cols`, `vertices`, `kind` and `offset`; a circular \
         mesh adds its node axes `normals`, a conical mesh its `face_normals` (§2.3), and \
         both `theta_deg`, `mode` and `report` (folded faces, first fold, smallest crossing \
         sine); a developable mesh (§3.3) adds `normals` and its slope `alpha_deg`. A one-paragraph summary (grid \
         size, mode, θ, admissible range, time taken, warnings about folds and pinches) goes \
         to stderr.\n\n\
         A trimmed design (`monge approximate --trim`'s: a design or a multi-patch design and \
         the target's outline) is written cut by its outline: its panels are polygons of 3 to 8 \
         corners in their faces' planes, as they are in OBJ and PLY, with the key `cut` (which \
         panels the outline cut) in JSON, as triangles in glTF (`.glb`).\n\n{THETA}"
    ),
    after_help = format!(
        "Examples:\n  \
         monge generate examples/fig13-freeform.json -o mesh.obj\n  \
         monge generate examples/fig14-family.toml -o - --format ply > mesh.ply\n\n{EXIT}"
    )
)]
pub struct GenerateArgs {
    /// The design file (`.json` or `.toml`).
    #[arg(value_name = "DESIGN")]
    pub design: PathBuf,
    #[command(flatten)]
    pub out: MeshOutput,
    /// Refuse grids of more than N vertices (rows × cols; of a developable design, rulings ×
    /// heights), before allocating anything.
    #[arg(long, value_name = "N", default_value_t = GenerateOptions::default().max_vertices)]
    pub max_vertices: usize,
    /// Also write the offset at distance D (repeatable): the node offset along the node axes
    /// of a circular mesh (§2.2), the face offset of a conical mesh (§2.3). Each is written
    /// next to OUT as `STEM.offset+D.EXT` (or `-D`), in OUT's format.
    #[arg(long = "offset", value_name = "D", allow_negative_numbers = true, value_parser = parse_finite)]
    pub offsets: Vec<f64>,
    /// Write coordinates relative to a base point: `start` (the guides' common start point) or
    /// X,Y,Z. Far from the origin (beyond about 1e3 times the design's size) this keeps the
    /// mesh exact to 1e-9 of its size, which absolute f64 coordinates cannot. The mesh is
    /// computed relative to the point, and the file records it: JSON `base_point`, OBJ
    /// `# base_point x y z`, PLY `comment base_point x y z` (add it to every vertex for the
    /// true coordinates), glTF the node's translation. Off by default.
    #[arg(long, value_name = "start|X,Y,Z", allow_hyphen_values = true)]
    pub base_point: Option<BasePoint>,
}

/// Runs `monge generate`.
pub fn run(args: &GenerateArgs) -> anyhow::Result<Outcome> {
    let out = args.out.output.as_path();
    // Everything about the output is checked before the (possibly long) generation.
    let format = args.out.checked_format(&[&args.design])?;
    if is_stdio(out) && !args.offsets.is_empty() {
        bail!("--offset writes one file per offset next to OUT: give a file for -o, not `-`");
    }
    // No offset's file may be the design.
    for d in &args.offsets {
        check_output(&offset_path(out, *d), &[&args.design])?;
    }

    let options = GenerateOptions {
        max_vertices: args.max_vertices,
    };
    let design = match read_any_design(&args.design)? {
        AnyDesign::Surface(design) => *design,
        AnyDesign::Developable(d) => {
            return run_developable(args, format, &d.developable, &options)
        }
        AnyDesign::Trimmed(t) => return run_trimmed(args, format, &t, &options),
    };
    let (design, base) = match &args.base_point {
        Some(b) => b.apply(design),
        None => (design, None),
    };
    let base = base.map(DVec3::from_array);
    let start = Instant::now();
    let generated =
        generate(&design, &options).with_context(|| args.design.display().to_string())?;
    let generation = start.elapsed().as_secs_f64();

    let start = Instant::now();
    let layers = layers(&generated, design.mesh, &args.offsets);
    write_layers(out, format, json_extras(&generated), &layers, base)?;
    let writing = start.elapsed().as_secs_f64();

    eprint(&summary(
        &args.design,
        out,
        format,
        &generated,
        (generation, writing),
    ));
    let report = layers[0].report.unwrap_or(generated.report);
    eprint(&generation_warnings(generated.info.theta_deg, &report));
    // What was written, measured as `monge check` measures it.
    let tolerance = design.tolerance.unwrap_or_default().planarity;
    for (k, layer) in layers.iter().enumerate() {
        let what = if k == 0 {
            format!("the mesh written to `{}`", out.display())
        } else {
            format!("the offset at {}", num(layer.offset))
        };
        let folds = layer.report.map_or(0, |r| r.folded_faces);
        eprint(&inexact_warning(
            &what,
            max_error(&layer.grid, design.mesh),
            tolerance,
            &layer.grid.vertices,
            folds,
            Some(generated.info.theta_deg),
        ));
    }
    eprint(&far_from_origin_warning(&layers[0].grid.vertices).unwrap_or_default());
    if let Some(b) = base {
        eprint(&format!(
            "coordinates written relative to the base point ({}, {}, {}), which the file \
             records ({}): add it to every vertex for the true coordinates.\n",
            num(b.x),
            num(b.y),
            num(b.z),
            base_record(format)
        ));
    }
    if design.mesh == MeshKind::Conical {
        let g = &layers[0].grid;
        eprint(&format!(
            "wrote the conical dual (§2.3): {} × {} vertices, {} faces, whose planes pass through \
             the circular mesh's vertices orthogonal to its node axes.\n",
            g.rows,
            g.cols,
            g.face_count()
        ));
    }
    Ok(Outcome::Success)
}

/// Where a file of `format` records the base point ([`monge_io::write_mesh_at`]).
fn base_record(format: MeshFormat) -> &'static str {
    match format {
        MeshFormat::Json => "key `base_point`",
        MeshFormat::Obj => "comment `# base_point x y z`",
        MeshFormat::Ply | MeshFormat::PlyBinary | MeshFormat::PlyF32 => {
            "header line `comment base_point x y z`"
        }
        MeshFormat::Glb => "the node's `translation`, so a viewer shows it in place",
    }
}

/// Writes the layers as one set of files ([`Outputs`]: after an error none has
/// changed): the first to OUT, each offset next to it, JSON with `extra` and each
/// layer's own keys; coordinates relative to `base`, if any, which every file records.
fn write_layers(
    out: &Path,
    format: MeshFormat,
    mut extra: Map<String, Value>,
    layers: &[Layer],
    base: Option<DVec3>,
) -> anyhow::Result<()> {
    let mut files = Outputs::new();
    let mut paths = Vec::with_capacity(layers.len());
    for (k, layer) in layers.iter().enumerate() {
        let path = if k == 0 {
            out.to_path_buf()
        } else {
            offset_path(out, layer.offset)
        };
        extra.extend(layer.extra.clone());
        files.write(&path, |w| {
            write_mesh_at(&layer.grid, format, base, &extra, w)
        })?;
        paths.push(path);
    }
    files.commit()?;
    for (layer, path) in layers.iter().zip(&paths).skip(1) {
        eprint(&format!(
            "wrote the offset at {}: `{}`.\n",
            num(layer.offset),
            path.display()
        ));
    }
    Ok(())
}

/// `monge generate` of a developable design (§3.3): the mesh and its node
/// offsets (the binormal node axes are torsion-free).
fn run_developable(
    args: &GenerateArgs,
    format: MeshFormat,
    spec: &DevelopableSpec,
    options: &GenerateOptions,
) -> anyhow::Result<Outcome> {
    if args.base_point.is_some() {
        bail!(
            "--base-point applies to designs with two guides; {} is a developable design \
             (§3.3), whose plan and heights are used as given: write them relative to a point \
             near the design instead",
            args.design.display()
        );
    }
    let start = Instant::now();
    let mesh = developable(spec, options).with_context(|| args.design.display().to_string())?;
    let generation = start.elapsed().as_secs_f64();
    let layers: Vec<Layer> = std::iter::once(0.0)
        .chain(args.offsets.iter().copied())
        .map(|d| Layer::new(d, node_offset(&mesh.grid, d), "developable", None))
        .collect();
    let mut extra = Map::new();
    extra.insert("alpha_deg".into(), json!(mesh.alpha_deg));
    let start = Instant::now();
    write_layers(&args.out.output, format, extra, &layers, None)?;
    let g = &mesh.grid;
    eprint(&format!(
        "{}: developable circular mesh (§3.3), slope α = {}°: {} rulings × {} cutting planes, \
         {} faces (isosceles trapezoids). Generated in {} ms; wrote {} `{}` in {} ms.\n",
        args.design.display(),
        num(mesh.alpha_deg),
        g.rows,
        g.cols,
        g.face_count(),
        millis(generation),
        format.extension().to_uppercase(),
        args.out.output.display(),
        millis(start.elapsed().as_secs_f64()),
    ));
    eprint(&far_from_origin_warning(&g.vertices).unwrap_or_default());
    Ok(Outcome::Success)
}

/// `monge generate` of a trimmed design: its design's mesh (one patch or several) cut
/// by its outline, as polygons (the cut panels keep their faces' planes) in any mesh
/// format ([`write_trimmed_mesh_to`]).
fn run_trimmed(
    args: &GenerateArgs,
    format: MeshFormat,
    design: &TrimmedDesign,
    options: &GenerateOptions,
) -> anyhow::Result<Outcome> {
    let file = args.design.display();
    if args.base_point.is_some() || !args.offsets.is_empty() {
        bail!(
            "--offset and --base-point work on a whole grid; {file} is a trimmed design: \
             generate the design before trimming (the file's `design`, as a file of its own)"
        );
    }
    let start = Instant::now();
    let (grid, mesh) = design.mesh(options).with_context(|| file.to_string())?;
    let generation = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let out = &args.out.output;
    write_output(out, |w| {
        write_trimmed_mesh_to(
            &mesh,
            format,
            &format!(
                "monge generate: {} faces of {file} trimmed to its outline",
                mesh.faces.len()
            ),
            w,
        )
    })?;
    // The exactness as `monge check` and `monge patches` measure it: of a multi-patch
    // design, each patch on its own grid (its lines are planar only piecewise).
    let (error, patches, tolerance) = match &design.design {
        Trimmable::Surface(d) => (max_error(&grid, d.mesh), "1 patch".to_owned(), d.tolerance),
        Trimmable::Patches(d) => (
            build(d, options)?.max_error(),
            format!("{} patches", d.patches.len()),
            d.tolerance,
        ),
    };
    eprint(&format!(
        "{file}: {patches} of {} × {} vertices trimmed to the design's outline: {} \
         faces, {} of them cut (their new corners in their faces' planes). Generated in {} ms; \
         wrote {} `{}` in {} ms.\n",
        grid.rows,
        grid.cols,
        mesh.faces.len(),
        mesh.cut.iter().filter(|c| **c).count(),
        millis(generation),
        format.extension().to_uppercase(),
        out.display(),
        millis(start.elapsed().as_secs_f64()),
    ));
    eprint(&inexact_warning(
        "the grid before trimming",
        error,
        tolerance.unwrap_or_default().planarity,
        &grid.vertices,
        0,
        None,
    ));
    eprint(&far_from_origin_warning(&mesh.vertices).unwrap_or_default());
    Ok(Outcome::Success)
}

/// `dir/stem.offset+D.ext` (or `-D`) for OUT = `dir/stem.ext`.
fn offset_path(out: &Path, d: f64) -> PathBuf {
    let stem = out.file_stem().unwrap_or_default().to_string_lossy();
    let name = match out.extension() {
        Some(ext) => format!("{stem}.offset{d:+}.{}", ext.to_string_lossy()),
        None => format!("{stem}.offset{d:+}"),
    };
    out.with_file_name(name)
}

/// The paragraph printed on stderr after a successful generation.
fn summary(
    design: &Path,
    out: &Path,
    format: MeshFormat,
    g: &Generated,
    (generation, writing): (f64, f64),
) -> String {
    let grid = &g.grid;
    let target = if is_stdio(out) {
        "standard output".to_owned()
    } else {
        format!("`{}`", out.display())
    };
    format!(
        "{}: {} × {} vertices, {} faces; mode {}; θ = {}°, admissible: {}. \
         Generated in {} ms; wrote {} to {} in {} ms.\n",
        design.display(),
        grid.rows,
        grid.cols,
        grid.face_count(),
        g.info.mode,
        num(g.info.theta_deg),
        range_text(g.info.mode, &g.info.theta_range),
        millis(generation),
        format.extension().to_uppercase(),
        target,
        millis(writing),
    )
}
