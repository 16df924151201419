//! `monge generate`: design file → mesh file.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{bail, Context};
use glam::DVec3;
use monge_core::combescure::CombescureReport;
use monge_core::developable::{developable, DevelopableSpec};
use monge_core::gauss_map::ThetaRange;
use monge_core::{generate, GenerateOptions, Generated, MeshKind, Mode};
use monge_io::generated::{json_extras, layers, max_error, node_offset, Layer};
pub use monge_io::generated::{mode_name, near_singular, SINGULAR_DEG};
use monge_io::{
    check_output, is_stdio, read_any_design, write_mesh_at, AnyDesign, MeshFormat, Outputs,
};
use serde_json::{json, Map, Value};

use crate::cli::{output_format, GenerateArgs};
use crate::output::{eprint, far_from_origin_warning, inexact_warning, millis, num};
use crate::Outcome;

/// Below this smallest crossing sine the summary warns that the mesh nearly pinches (§5.2).
const LOW_CROSSING_SINE: f64 = 1e-3;

/// Runs `monge generate`.
pub fn run(args: &GenerateArgs) -> anyhow::Result<Outcome> {
    let out = args.output.as_path();
    // Everything about the output is checked before the (possibly long) generation.
    let format = output_format(args.format, out)?;
    check_output(out, &[&args.design])?;
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
    write_layers(&args.output, format, extra, &layers, None)?;
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
        args.output.display(),
        millis(start.elapsed().as_secs_f64()),
    ));
    eprint(&far_from_origin_warning(&g.vertices).unwrap_or_default());
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

/// What the summary says about folds and pinches (§5.2),
/// taken from a [`CombescureReport`].
#[derive(Clone, Copy, Debug, PartialEq)]
struct Pinching {
    /// Faces oriented against face (0, 0).
    folded_faces: usize,
    /// The first of them, row-major.
    first_fold: Option<(usize, usize)>,
    /// The smallest sine between the two lines that defined a vertex.
    min_sine: f64,
    /// The face where it occurred.
    min_face: (usize, usize),
}

impl From<&CombescureReport> for Pinching {
    fn from(r: &CombescureReport) -> Self {
        Pinching {
            folded_faces: r.folded_faces,
            first_fold: r.first_fold,
            min_sine: r.min_crossing.sine,
            min_face: r.min_crossing.face,
        }
    }
}

/// Below this |θ| in degrees, the lower end of an admissible range is 0 up to
/// round-off (c_v = 0 in §3.2 computes as about 1e-15°).
const ZERO_DEG: f64 = 1e-9;

/// The admissible θ in words, both signs (§3.2); a range from 0 (up to
/// round-off) is one interval, without `−0°`.
pub fn range_text(mode: Mode, r: &ThetaRange) -> String {
    match mode {
        Mode::Characteristic => "every θ in (−180°, 180°]".to_owned(),
        Mode::Arbitrary if r.min_deg.abs() < ZERO_DEG => format!(
            "|θ| ≤ {max}°, i.e. θ in [−{max}°, {max}°]",
            max = num(r.max_deg)
        ),
        Mode::Arbitrary => format!(
            "|θ| in [{min}°, {max}°], i.e. θ in [−{max}°, −{min}°] ∪ [{min}°, {max}°]",
            min = num(r.min_deg),
            max = num(r.max_deg)
        ),
    }
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

/// The warnings of a generation at `theta_deg` (near-singular θ, folds and
/// pinches, §5.2) whose mesh `report` describes (for a conical mesh, its own
/// folds), one line each, for every command that builds on a generated mesh.
pub fn generation_warnings(theta_deg: f64, report: &CombescureReport) -> String {
    warnings(theta_deg, &Pinching::from(report)).concat()
}

/// Warnings about the singular θ and about folds and pinches (§5.2), one line each.
fn warnings(theta_deg: f64, r: &Pinching) -> Vec<String> {
    let mut w = Vec::new();
    if near_singular(theta_deg) {
        w.push(format!(
            "warning: θ = {}° is at or near the singular θ = +90°, where every Gauss circle passes \
             through the corner normal: expect a degenerate mesh; run `monge check` on it.\n",
            num(theta_deg)
        ));
    }
    if let Some((i, j)) = r.first_fold {
        w.push(format!(
            "warning: the mesh folds over itself / pinches (§5.2) in {} faces, first at face ({i}, {j}).\n",
            r.folded_faces
        ));
    }
    if r.min_sine < LOW_CROSSING_SINE {
        let (i, j) = r.min_face;
        w.push(format!(
            "warning: low crossing sine {:.1e} at face ({i}, {j}): vertex ({}, {}) is defined by two \
             nearly parallel lines, the mesh nearly pinches there (§5.2); try another θ.\n",
            r.min_sine,
            i + 1,
            j + 1
        ));
    }
    w
}

#[cfg(test)]
mod tests {
    use super::*;

    fn report(folded_faces: usize, min_sine: f64) -> Pinching {
        Pinching {
            folded_faces,
            first_fold: (folded_faces > 0).then_some((5, 6)),
            min_sine,
            min_face: (3, 4),
        }
    }

    #[test]
    fn a_clean_mesh_has_no_warnings() {
        assert!(warnings(30.0, &report(0, 0.5)).is_empty());
    }

    #[test]
    fn folds_and_low_sines_are_reported_with_their_faces() {
        let w = warnings(-90.0, &report(7, 1e-4));
        assert_eq!(w.len(), 2);
        assert!(
            w[0].contains("in 7 faces, first at face (5, 6)"),
            "{}",
            w[0]
        );
        assert!(w[1].contains("1.0e-4 at face (3, 4)"), "{}", w[1]);
    }

    #[test]
    fn only_plus_ninety_is_singular() {
        assert!(near_singular(90.0));
        assert!(near_singular(89.5));
        assert!(!near_singular(-90.0));
        assert!(!near_singular(30.0));
        let w = warnings(90.0, &report(0, 0.5));
        assert_eq!(w.len(), 1);
        assert!(w[0].contains("singular θ = +90°"), "{}", w[0]);
    }

    #[test]
    fn ranges_have_both_signs() {
        let r = ThetaRange {
            min_deg: 61.9,
            max_deg: 170.0,
        };
        assert_eq!(
            range_text(Mode::Arbitrary, &r),
            "|θ| in [61.9°, 170°], i.e. θ in [−170°, −61.9°] ∪ [61.9°, 170°]"
        );
        for min_deg in [0.0, -0.0, 1.3e-15] {
            let r = ThetaRange {
                min_deg,
                max_deg: 170.0,
            };
            let text = range_text(Mode::Arbitrary, &r);
            assert_eq!(text, "|θ| ≤ 170°, i.e. θ in [−170°, 170°]");
        }
    }
}
