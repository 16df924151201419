//! `monge info`: validate a design and describe it, without generating.

use std::path::PathBuf;

use anyhow::Context;
use monge_core::developable::{developable, DevelopableSpec};
use monge_core::guide::Guide;
use monge_core::{inspect, DesignInfo, GenerateOptions, GuideSpec, Mode};
use monge_io::generated::{mode_name, near_singular, SINGULAR_DEG};
use monge_io::{read_any_design, AnyDesign, Trimmable};
use serde_json::{json, Value};

use crate::shared::help::{EXIT, THETA};
use crate::shared::output::{eprint, far_from_origin_warning, num, print, xyz};
use crate::shared::trimmed_design_refused;
use crate::shared::warnings::range_text;
use crate::shared::Outcome;

/// Validate a design and print what generation would use, without generating.
#[derive(Debug, clap::Args)]
#[command(
    long_about = format!(
        "Validate a design and print what generation would use, without building the mesh.\n\n\
         For each guide: its kind, number of samples, planarity deviation (absolute and \
         relative to the guide's size, against the design's tolerance), size (bounding-box \
         diagonal), unit start tangent and plane normal. Then the mode (characteristic §3.1: \
         every θ works; arbitrary §3.2: θ has an admissible range), the admissible θ in \
         degrees (both signs), whether the design's θ is admissible (an inadmissible θ is \
         reported, not an error), the singular θ = +90°, and the grid size.\n\n{THETA}"
    ),
    after_help = format!(
        "Examples:\n  \
         monge info examples/fig10-arbitrary.json\n  \
         monge info examples/fig14-family.toml --json\n\n{EXIT}"
    )
)]
pub struct InfoArgs {
    /// The design file (`.json` or `.toml`).
    #[arg(value_name = "DESIGN")]
    pub design: PathBuf,
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
    /// Refuse designs of more than N grid vertices (as `monge generate` would).
    #[arg(long, value_name = "N", default_value_t = GenerateOptions::default().max_vertices)]
    pub max_vertices: usize,
}

/// Runs `monge info`.
pub fn run(args: &InfoArgs) -> anyhow::Result<Outcome> {
    let options = GenerateOptions {
        max_vertices: args.max_vertices,
    };
    let (design, trimmed) = match read_any_design(&args.design)? {
        AnyDesign::Surface(design) => (*design, None),
        AnyDesign::Developable(d) => return developable_info(args, &d.developable, &options),
        AnyDesign::Trimmed(t) => match &t.design {
            // One patch: its information, and what the outline keeps of its mesh.
            Trimmable::Surface(d) => ((**d).clone(), Some(t)),
            Trimmable::Patches(_) => return Err(trimmed_design_refused(&args.design, "info")),
        },
    };
    let info = inspect(&design, &options).with_context(|| args.design.display().to_string())?;
    let report = Report {
        file: args.design.display().to_string(),
        info: &info,
        planarity_tol: design.tolerance.unwrap_or_default().planarity,
        guides: [
            ("guide_u", &design.guide_u, &info.guide_u),
            ("guide_v", &design.guide_v, &info.guide_v),
        ],
    };
    // A trimmed design: its outline, and the panels it keeps of the mesh.
    let trim = match &trimmed {
        Some(t) => {
            let (_, mesh) = t
                .mesh(&options)
                .with_context(|| args.design.display().to_string())?;
            Some(json!({
                "corners": t.trim.polygon().len(),
                "area": t.trim.area(),
                "panels": mesh.faces.len(),
                "cut": mesh.cut.iter().filter(|c| **c).count(),
            }))
        }
        None => None,
    };
    let text = match (args.json, &trim) {
        (true, None) => format!("{}\n", report.json()),
        (true, Some(trim)) => {
            let mut json = report.json();
            json["trim"] = trim.clone();
            format!("{json}\n")
        }
        (false, None) => report.text(),
        (false, Some(trim)) => format!(
            "{}trimmed to an outline of {} corners enclosing {} square model units: {} panels, \
             {} of them cut (`monge generate` writes them)\n",
            report.text(),
            trim["corners"],
            num(trim["area"].as_f64().unwrap_or(f64::NAN)),
            trim["panels"],
            trim["cut"]
        ),
    };
    print(&text)?;
    let guide_points = [info.guide_u.points.as_slice(), &info.guide_v.points].concat();
    eprint(&far_from_origin_warning(&guide_points).unwrap_or_default());
    Ok(Outcome::Success)
}

/// `monge info` of a developable design (§3.3): validated by building it (it is
/// cheap: one vertex per ruling and cutting plane, at most `options.max_vertices`).
fn developable_info(
    args: &InfoArgs,
    spec: &DevelopableSpec,
    options: &GenerateOptions,
) -> anyhow::Result<Outcome> {
    let mesh = developable(spec, options).with_context(|| args.design.display().to_string())?;
    let (rows, cols) = (mesh.grid.rows, mesh.grid.cols);
    let file = args.design.display().to_string();
    let text = if args.json {
        format!(
            "{}\n",
            json!({
                "file": file,
                "kind": "developable",
                "alpha_deg": mesh.alpha_deg,
                "helix_points": mesh.helix.len(),
                "rows": rows,
                "cols": cols,
                "faces": mesh.grid.face_count(),
            })
        )
    } else {
        format!(
            "{file}: valid developable design (§3.3)\n\
             discrete general helix of {} points, slope α = {}° to the reference plane\n\
             grid: {rows} rulings × {cols} cutting planes ({} vertices), {} faces, each an isosceles trapezoid\n",
            mesh.helix.len(),
            num(mesh.alpha_deg),
            rows * cols,
            mesh.grid.face_count()
        )
    };
    print(&text)?;
    eprint(&far_from_origin_warning(&mesh.grid.vertices).unwrap_or_default());
    Ok(Outcome::Success)
}

/// A guide's name, its spec and the validated guide.
type GuideRow<'a> = (&'static str, &'a GuideSpec, &'a Guide);

/// The kind of a guide spec, in words: its key, and whether a B-spline is rational.
fn kind(spec: &GuideSpec) -> &'static str {
    match spec {
        GuideSpec::BSpline { bspline, .. } if bspline.weights.is_some() => "bspline (NURBS)",
        GuideSpec::Points { .. }
        | GuideSpec::BSpline { .. }
        | GuideSpec::Arc(_)
        | GuideSpec::Parabola(_) => spec.kind(),
    }
}

/// What `monge info` reports of a valid design, as text or as JSON.
struct Report<'a> {
    /// The design file, as named on the command line.
    file: String,
    info: &'a DesignInfo,
    /// The design's planarity tolerance (its `tolerance.planarity`, or the default).
    planarity_tol: f64,
    guides: [GuideRow<'a>; 2],
}

impl Report<'_> {
    /// The human-readable report.
    fn text(&self) -> String {
        let Report {
            file,
            info,
            planarity_tol,
            guides,
        } = self;
        let mut s = format!("{file}: valid design\n");
        for (name, spec, g) in guides {
            s.push_str(&format!(
                "{name}: {}, {} samples, size {} (bounding-box diagonal)\n  \
             planarity deviation {:.3e} absolute, {:.3e} relative (tolerance {:.0e})\n  \
             start tangent {}, plane normal {}\n",
                kind(spec),
                g.points.len(),
                num(g.size),
                g.planarity,
                g.planarity / g.size,
                planarity_tol,
                xyz(g.tangent.to_array()),
                xyz(g.plane_normal.to_array()),
            ));
        }
        s.push_str(&format!(
            "start point {}\n",
            xyz(info.guide_u.points[0].to_array())
        ));
        s.push_str(&format!(
        "mode: {}\n",
        match info.mode {
            Mode::Characteristic =>
                "characteristic (§3.1): the guide planes are orthogonal and each start tangent is \
                 orthogonal to the other guide's plane",
            Mode::Arbitrary => "arbitrary (§3.2): θ is restricted to an admissible range",
        }
    ));
        s.push_str(&format!(
            "admissible θ: {}\n",
            range_text(info.mode, &info.theta_range)
        ));
        let admissible = info.theta_range.contains(info.theta_deg);
        s.push_str(&format!(
            "design θ = {}°: {}\n",
            num(info.theta_deg),
            if !admissible {
                "NOT admissible; `monge generate` will refuse it"
            } else if near_singular(info.theta_deg) {
                "admissible, but at or near the singular θ = +90°: expect a degenerate mesh"
            } else {
                "admissible"
            }
        ));
        s.push_str(
        "singular θ = +90°: every Gauss circle passes through the corner normal N_p and the corner \
         face collapses\n",
    );
        let (rows, cols) = info.grid_size();
        s.push_str(&format!(
            "grid: {rows} × {cols} vertices ({}), {} faces\n",
            rows * cols,
            (rows - 1) * (cols - 1)
        ));
        s
    }

    /// The JSON report (`file` is its last key).
    fn json(&self) -> Value {
        let Report {
            file,
            info,
            planarity_tol,
            guides,
        } = self;
        let mut v = json!({});
        for (name, spec, g) in guides {
            v[*name] = json!({
                "kind": kind(spec),
                "samples": g.points.len(),
                "planarity_abs": g.planarity,
                "planarity_rel": g.planarity / g.size,
                "planarity_tolerance": planarity_tol,
                "size": g.size,
                "start_tangent": g.tangent.to_array(),
                "plane_normal": g.plane_normal.to_array(),
            });
        }
        let (rows, cols) = info.grid_size();
        let r = info.theta_range;
        v["start_point"] = json!(info.guide_u.points[0].to_array());
        v["mode"] = json!(mode_name(info.mode));
        v["theta_deg"] = json!(info.theta_deg);
        v["theta_admissible"] = json!(info.theta_range.contains(info.theta_deg));
        v["admissible_theta_deg"] = json!({
            "abs_min": r.min_deg,
            "abs_max": r.max_deg,
            "intervals": [[-r.max_deg, -r.min_deg], [r.min_deg, r.max_deg]],
        });
        v["singular_theta_deg"] = json!(SINGULAR_DEG);
        v["theta_singular"] = json!(near_singular(info.theta_deg));
        v["rows"] = json!(rows);
        v["cols"] = json!(cols);
        v["vertices"] = json!(rows * cols);
        v["faces"] = json!((rows - 1) * (cols - 1));
        v["file"] = json!(file);
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use monge_core::design::{ArcSpec, BSplineSpec, ParabolaSpec};

    #[test]
    fn kinds_are_named() {
        let bspline = BSplineSpec {
            degree: 1,
            control_points: vec![[0.0; 3], [1.0, 0.0, 0.0]],
            knots: None,
            weights: None,
            samples: 2,
        };
        let nurbs = BSplineSpec {
            weights: Some(vec![1.0, 2.0]),
            ..bspline.clone()
        };
        let arc = ArcSpec {
            center: [0.0; 3],
            start: [1.0, 0.0, 0.0],
            normal: [0.0, 0.0, 1.0],
            angle_deg: 90.0,
            samples: 3,
        };
        let parabola = ParabolaSpec {
            start: [0.0; 3],
            tangent: [1.0, 0.0, 0.0],
            quadratic: [0.0, 1.0, 0.0],
            samples: 3,
        };
        let with = |b: BSplineSpec| GuideSpec::BSpline {
            bspline: b,
            parameters: None,
        };
        assert_eq!(kind(&GuideSpec::points(vec![[0.0; 3]])), "points");
        assert_eq!(kind(&with(bspline)), "bspline");
        assert_eq!(kind(&with(nurbs)), "bspline (NURBS)");
        let arc = GuideSpec::Arc(arc);
        assert_eq!(kind(&arc), "arc");
        let parabola = GuideSpec::Parabola(parabola);
        assert_eq!(kind(&parabola), "parabola");
    }
}
