//! `monge check`: measure a mesh against a tolerance.

use std::io;
use std::path::PathBuf;

use anyhow::{bail, Context};
use glam::DVec3;
use monge_core::conical::conical_folds;
use monge_core::measure::{
    conical_error, largest, measurable, measure, measure_polygons, Measurements, Worst,
};
use monge_core::{MeshKind, QuadGrid};
use monge_io::generated::kind_name;
use monge_io::{
    is_stdio, read_face_normals, read_mesh, read_mesh_and_kind, read_mesh_and_kind_from,
    read_polygons, MeshFormat,
};
use serde_json::{json, Map, Value};

use crate::shared::args::{parse_tolerance, KINDS, READ_FORMATS};
use crate::shared::help::EXIT;
use crate::shared::output::{eprint, far_from_origin_warning, num, print};
use crate::shared::Outcome;

/// Measure a quad mesh: planarity, circularity, planar lines, node axes.
#[derive(Debug, clap::Args)]
#[command(
    long_about = format!(
        "Measure a quad mesh (from `monge generate` or any row-major quad grid) independently \
         of how it was made.\n\n\
         Reads MESH (`.obj`, `.ply` or `.json` by extension, or `-` for standard input with \
         --format) and prints, for each metric, its worst value and where it occurs, and PASS \
         or FAIL against --tol: face planarity (distance between the diagonals' lines), \
         circularity (distance of a corner from the circle through the other three), row and \
         column planarity (distance of a vertex from the best-fit plane of its curvature \
         line), all relative to the bounding-box diagonal; and, when the mesh has normals, \
         torsion (|det(edge, n_p, n_q)| over edges, also relative to the diagonal: 0 when the \
         node axes at both ends of every edge are coplanar) and normal length (| |n| − 1 |). \
         A conical mesh (--kind conical; by default the `kind` a JSON mesh names) has the \
         conical condition at every vertex instead of circularity, torsion and normal length. An \
         OBJ, PLY or JSON (`vertices`, `faces`) of polygons that is not a quad grid (a mesh trimmed to an outline, as `monge \
         generate` writes a trimmed design) is measured for the planarity of its faces only \
         (the distance of a corner from the plane fitted to its face's corners)."
    ),
    after_help = format!(
        "Examples:\n  \
         monge check mesh.obj\n  \
         monge generate examples/fig2-enneper.json -o - | monge check - --format json --json\n\n{EXIT}"
    )
)]
pub struct CheckArgs {
    /// The mesh file (`.obj`, `.ply` or `.json`), or `-` for standard input (needs --format).
    #[arg(value_name = "MESH")]
    pub mesh: PathBuf,
    /// Largest accepted value of each metric (a non-negative number).
    #[arg(
        long,
        value_name = "TOL",
        default_value = "1e-9",
        value_parser = parse_tolerance,
        allow_negative_numbers = true
    )]
    pub tol: f64,
    /// Format of standard input when MESH is `-` (files are read by their extension).
    #[arg(long, value_parser = READ_FORMATS)]
    pub format: Option<MeshFormat>,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    pub json: bool,
    /// What MESH is: which properties to measure (default: the `kind` a JSON mesh
    /// written by monge names, else circular).
    #[arg(long, value_parser = KINDS)]
    pub kind: Option<MeshKind>,
    /// MESH is an offset of BASE (same grid): also measure how far the offset distance varies
    /// (vertex distances for a circular mesh, face-plane distances for a conical one).
    #[arg(long, value_name = "BASE")]
    pub offset_from: Option<PathBuf>,
}

/// Runs `monge check`.
pub fn run(args: &CheckArgs) -> anyhow::Result<Outcome> {
    let path = args.mesh.as_path();
    let (grid, named_kind) = match (is_stdio(path), args.format) {
        (true, Some(f)) => read_mesh_and_kind_from(io::stdin().lock(), f)?,
        (true, None) => bail!("`-` (standard input) needs --format obj, ply or json"),
        (false, None) => match read_mesh_and_kind(path) {
            Ok(read) => read,
            // Not a quad grid, but perhaps a mesh of polygons (a trimmed mesh).
            Err(e) => match MeshFormat::from_path(path) {
                Ok(MeshFormat::Obj | MeshFormat::Ply | MeshFormat::Json) => match read_polygons(path) {
                    Ok((vertices, faces)) => return run_polygons(args, &e, &vertices, &faces),
                    Err(_) => return Err(e.into()),
                },
                _ => return Err(e.into()),
            },
        },
        (false, Some(_)) => bail!(
            "--format is only for `-` (standard input); `{}` is read in the format of its extension",
            path.display()
        ),
    };
    let name = if is_stdio(path) {
        "<stdin>".to_owned()
    } else {
        path.display().to_string()
    };
    measurable(&grid).with_context(|| name.clone())?;
    let m = measure(&grid);
    // Said on the command line, else by the file, else circular.
    let kind = args.kind.or(named_kind).unwrap_or(MeshKind::Circular);
    // A conical mesh's faces are turned over against their normals when the
    // file gives them, else against the vertex cones.
    let face_normals = if is_stdio(path) {
        None
    } else {
        read_face_normals(path, &grid)?
    };
    let mut metrics = metrics_of(&grid, &m, kind, face_normals.as_deref());
    if let Some(base) = &args.offset_from {
        let base = read_mesh(base)?;
        if (base.rows, base.cols) != (grid.rows, grid.cols) {
            bail!(
                "`{name}` ({} × {}) cannot be an offset of `{}` ({} × {}): the grids differ",
                grid.rows,
                grid.cols,
                args.offset_from.as_deref().unwrap_or(path).display(),
                base.rows,
                base.cols
            );
        }
        // Before the folded faces.
        metrics.insert(
            metrics.len() - 1,
            offset_metric(&base, &grid, kind, m.scale),
        );
    }
    let report = Report {
        name: &name,
        grid: &grid,
        scale: m.scale,
        kind,
        metrics,
        tol: args.tol,
    };
    print(&if args.json {
        format!("{}\n", report.json())
    } else {
        report.text()
    })?;
    eprint(&far_from_origin_warning(&grid.vertices).unwrap_or_default());
    // Failed as circular for want of saying what it is: perhaps a conical mesh.
    let circularity_failed = report
        .metrics
        .iter()
        .any(|r| r.key == "circularity" && !r.passes(args.tol));
    if circularity_failed && args.kind.is_none() && named_kind.is_none() {
        let as_conical = metrics_of(&grid, &m, MeshKind::Conical, face_normals.as_deref());
        eprint(&if as_conical.iter().all(|r| r.passes(args.tol)) {
            format!(
                "note: `{name}` fails as a circular mesh but passes as a conical one (§2.3): \
                 check it with --kind conical\n"
            )
        } else {
            format!(
                "note: `{name}` was measured as a circular mesh (§2.2); a conical mesh (§2.3) \
                 is checked with --kind conical\n"
            )
        });
    }
    Ok(if report.passes() {
        Outcome::Success
    } else {
        Outcome::Failed
    })
}

/// `monge check` of an OBJ, PLY or JSON mesh of polygons that is not a quad grid (`not_grid` says
/// why), such as a grid trimmed to an outline: the planarity of its faces, which is what
/// trimming keeps (a cut panel is no longer circular).
fn run_polygons(
    args: &CheckArgs,
    not_grid: &monge_io::IoError,
    vertices: &[DVec3],
    faces: &[Vec<usize>],
) -> anyhow::Result<Outcome> {
    let name = args.mesh.display();
    if args.kind.is_some() || args.offset_from.is_some() {
        bail!(
            "`{name}` is a mesh of polygons, not a quad grid ({not_grid}): it is measured for \
             the planarity of its faces only; --kind and --offset-from need a quad grid"
        );
    }
    let m = measure_polygons(vertices, faces);
    let pass = passes(m.planarity.value, args.tol);
    let (face, corner) = m.planarity.at;
    let corners = |n: usize| faces.iter().filter(|f| f.len() == n).count();
    if args.json {
        let planarity = json!({"value": m.planarity.value, "at": [face, corner], "pass": pass});
        print(&format!(
            "{}\n",
            json!({
                "file": name.to_string(),
                "polygons": faces.len(),
                "vertices": vertices.len(),
                "scale": m.scale,
                "tol": args.tol,
                "max_error": m.planarity.value,
                "pass": pass,
                "metrics": { "face_planarity": planarity },
            })
        ))?;
    } else {
        let at = format!("at face {face}, corner {corner}");
        let verdict_line = if pass {
            format!("PASS: every face planar within {:e}", args.tol)
        } else {
            format!(
                "FAIL: a face's corner {:e} off its plane (must be ≤ {:e})",
                m.planarity.value, args.tol
            )
        };
        print(&format!(
            "{name}: not a quad grid ({not_grid}): measured as a mesh of polygons, each face's \
             planarity only (a panel cut by an outline keeps its plane, not its circle)\n\
             {} vertices, {} faces ({} triangles, {} quads, {} of five corners or more); lengths \
             relative to the bounding-box diagonal {}\n\
             {:<17} {:>10}  {at:<23} {}\n{verdict_line}\n",
            vertices.len(),
            faces.len(),
            corners(3),
            corners(4),
            faces.len() - corners(3) - corners(4),
            num(m.scale),
            "face planarity",
            format!("{:.3e}", m.planarity.value),
            verdict(pass),
        ))?;
    }
    eprint(&far_from_origin_warning(vertices).unwrap_or_default());
    Ok(if pass {
        Outcome::Success
    } else {
        Outcome::Failed
    })
}

/// One measured metric (§2.2).
struct Metric {
    /// Key in the JSON output.
    key: &'static str,
    /// Name in the table.
    label: &'static str,
    /// What `worst.at` indexes, for the table.
    element: &'static str,
    /// The worst value and where.
    worst: Worst,
    /// A count that must be 0 (folded faces), not an error compared with the tolerance.
    count: bool,
}

impl Metric {
    /// Whether the metric passes: a count is 0, an error is ≤ `tol` (NaN fails).
    fn passes(&self, tol: f64) -> bool {
        passes(self.worst.value, if self.count { 0.0 } else { tol })
    }
}

/// Every metric of `grid` (measured as `m`) as a mesh of `kind` but an offset's:
/// [`metrics`], then the folded faces (§5.2): a conical mesh's about its
/// `face_normals` if given, else about its vertex cones ([`conical_folds`]).
fn metrics_of(
    grid: &QuadGrid,
    m: &Measurements,
    kind: MeshKind,
    face_normals: Option<&[DVec3]>,
) -> Vec<Metric> {
    let mut v = metrics(grid, m, kind);
    let (folded, first) = match kind {
        MeshKind::Circular => (m.folded_faces, m.first_fold),
        MeshKind::Conical => {
            let folds = conical_folds(grid, face_normals);
            (folds.count(), folds.first())
        }
    };
    v.push(Metric {
        key: "folded_faces",
        label: "folded faces",
        element: "first face",
        worst: Worst {
            value: folded as f64,
            at: first.unwrap_or((0, 0)),
        },
        count: true,
    });
    v
}

/// The metrics of `grid` (measured as `m`) for a mesh of `kind`, in print order: for
/// a circular mesh torsion and normal length only with normals (§2.2); for a conical
/// mesh the conical condition instead of circularity (§2.3).
fn metrics(grid: &QuadGrid, m: &Measurements, kind: MeshKind) -> Vec<Metric> {
    let metric = |key, label, element, worst| Metric {
        key,
        label,
        element,
        worst,
        count: false,
    };
    let mut v = vec![metric(
        "face_planarity",
        "face planarity",
        "face",
        m.face_planarity,
    )];
    match kind {
        MeshKind::Circular => v.push(metric("circularity", "circularity", "face", m.circularity)),
        MeshKind::Conical => {
            if let Some(c) = conical_error(grid) {
                v.push(metric("conical", "conical vertices", "vertex", c));
            }
        }
    }
    v.push(metric(
        "row_planarity",
        "row planarity",
        "vertex",
        m.row_planarity,
    ));
    v.push(metric(
        "column_planarity",
        "column planarity",
        "vertex",
        m.column_planarity,
    ));
    if kind == MeshKind::Circular {
        if let Some(t) = m.torsion {
            v.push(metric("torsion", "torsion", "edge from", t));
        }
        if let Some(n) = m.normal_length {
            v.push(metric("normal_length", "normal length", "vertex", n));
        }
    }
    v
}

/// How far the distance from `base` to its offset `grid` varies, relative to the
/// scale (§2.2, §2.3): for circular meshes the distance between corresponding
/// vertices, for conical meshes the signed distance of each offset face's corners
/// from the plane of the base face (its normal from the base face's diagonals).
fn offset_metric(base: &QuadGrid, grid: &QuadGrid, kind: MeshKind, scale: f64) -> Metric {
    let mut distances: Vec<(f64, (usize, usize))> = Vec::new();
    match kind {
        MeshKind::Circular => {
            for i in 0..grid.rows {
                for j in 0..grid.cols {
                    distances.push((grid.vertex(i, j).distance(base.vertex(i, j)), (i, j)));
                }
            }
        }
        MeshKind::Conical => {
            for i in 0..grid.rows.saturating_sub(1) {
                for j in 0..grid.cols.saturating_sub(1) {
                    let [a, b, c, d] = base.face(i, j);
                    let n = (c - a).cross(d - b).normalize();
                    let h = n.dot(a + b + c + d) / 4.0;
                    for v in grid.face(i, j) {
                        distances.push((n.dot(v) - h, (i, j)));
                    }
                }
            }
        }
    }
    let mean = distances.iter().map(|d| d.0).sum::<f64>() / distances.len().max(1) as f64;
    let worst = distances
        .iter()
        .map(|&(d, at)| Worst {
            value: (d - mean).abs() / scale,
            at,
        })
        .fold(
            Worst {
                value: 0.0,
                at: (0, 0),
            },
            |w, x| {
                if x.value > w.value || x.value.is_nan() {
                    x
                } else {
                    w
                }
            },
        );
    Metric {
        count: false,
        key: "offset_distance",
        label: "offset distance",
        element: if kind == MeshKind::Circular {
            "vertex"
        } else {
            "face"
        },
        worst,
    }
}

/// `value ≤ tol`; NaN fails.
fn passes(value: f64, tol: f64) -> bool {
    value <= tol
}

/// `PASS` or `FAIL`.
fn verdict(pass: bool) -> &'static str {
    if pass {
        "PASS"
    } else {
        "FAIL"
    }
}

/// What `monge check` found, as the table and the JSON object both tell it.
struct Report<'a> {
    /// The mesh's file name, `<stdin>` for standard input.
    name: &'a str,
    /// The mesh.
    grid: &'a QuadGrid,
    /// The bounding-box diagonal the lengths are relative to.
    scale: f64,
    /// What the mesh was measured as.
    kind: MeshKind,
    /// The metrics, in print order.
    metrics: Vec<Metric>,
    /// Largest accepted error (`--tol`).
    tol: f64,
}

impl Report<'_> {
    /// Whether every metric passes.
    fn passes(&self) -> bool {
        self.metrics.iter().all(|r| r.passes(self.tol))
    }

    /// The table.
    fn text(&self) -> String {
        let (grid, tol) = (self.grid, self.tol);
        let mut s = format!(
            "{}: {} × {} vertices, {} faces, {}, measured as a {} mesh\n\
             lengths and torsion relative to the bounding-box diagonal {}; normal length is dimensionless\n",
            self.name,
            grid.rows,
            grid.cols,
            grid.face_count(),
            if grid.normals.is_empty() {
                "no normals"
            } else {
                "with normals"
            },
            kind_name(self.kind),
            num(self.scale)
        );
        for r in &self.metrics {
            let (i, j) = r.worst.at;
            let at = format!("at {} ({i}, {j})", r.element);
            let (value, at) = match (r.count, r.worst.value) {
                (true, 0.0) => ("0".to_owned(), String::new()),
                (true, n) => (n.to_string(), at),
                (false, e) => (format!("{e:.3e}"), at),
            };
            s.push_str(&format!(
                "{:<17} {value:>10}  {at:<23} {}\n",
                r.label,
                verdict(r.passes(tol))
            ));
        }
        let failed = self.metrics.iter().filter(|r| !r.passes(tol)).count();
        if self.passes() {
            s.push_str(&format!("PASS: every metric ≤ {tol:e}, no folded face\n"));
        } else {
            s.push_str(&format!(
                "FAIL: {failed} of {} metrics fail (errors must be ≤ {tol:e}, folded faces 0)\n",
                self.metrics.len()
            ));
        }
        s
    }

    /// The JSON object.
    fn json(&self) -> Value {
        let (grid, tol) = (self.grid, self.tol);
        let mut all = Map::new();
        for r in &self.metrics {
            all.insert(
                r.key.to_owned(),
                if r.count {
                    let at = (r.worst.value > 0.0).then_some([r.worst.at.0, r.worst.at.1]);
                    json!({ "value": r.worst.value as usize, "at": at, "pass": r.passes(tol) })
                } else {
                    json!({
                        "value": r.worst.value,
                        "at": [r.worst.at.0, r.worst.at.1],
                        "pass": r.passes(tol),
                    })
                },
            );
        }
        json!({
            "file": self.name,
            "rows": grid.rows,
            "cols": grid.cols,
            "faces": grid.face_count(),
            "normals": !grid.normals.is_empty(),
            "kind": kind_name(self.kind),
            "scale": self.scale,
            "tol": tol,
            "max_error": largest(self.metrics.iter().filter(|r| !r.count).map(|r| r.worst.value)),
            "pass": self.passes(),
            "metrics": all,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nan_fails() {
        assert!(passes(1e-12, 1e-9));
        assert!(passes(1e-9, 1e-9));
        assert!(!passes(2e-9, 1e-9));
        assert!(!passes(f64::NAN, 1e-9));
    }
}
