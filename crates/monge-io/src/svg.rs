//! An SVG overview of a gridshell (§6): the plan (view from +Z) of every layer.

use std::io::{self, Write};

use glam::DVec3;
use monge_core::fabrication::{Fabrication, LineFamily};

/// Width of the drawing in SVG user units.
const WIDTH: f64 = 1000.0;

/// The plan of every layer (§6): the panels of the last layer filled light
/// blue, then the beams of every layer, rows in red and columns in blue, each
/// layer a group `<g id="layer-k">`, and a caption with the summary counts.
pub fn write_overview_svg(f: &Fabrication, w: &mut dyn Write) -> io::Result<()> {
    let all = f.layers.iter().flat_map(|l| &l.grid.vertices);
    let (lo, hi) = all.fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    let span = (hi - lo).truncate().max_element().max(f64::MIN_POSITIVE);
    let scale = WIDTH / span;
    let margin = 20.0;
    let height = (hi.y - lo.y) * scale;
    let xy = |p: DVec3| {
        format!(
            "{:.3},{:.3}",
            margin + (p.x - lo.x) * scale,
            margin + (hi.y - p.y) * scale
        )
    };
    writeln!(
        w,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{0:.0}" height="{1:.0}" viewBox="0 0 {0:.3} {1:.3}">"#,
        WIDTH + 2.0 * margin,
        height + 2.0 * margin + 30.0
    )?;
    if let Some(top) = f.layers.last() {
        writeln!(
            w,
            r##"<g id="panels" fill="#cfe8ff" stroke="#7aa7d8" stroke-width="0.5">"##
        )?;
        let g = &top.grid;
        for i in 0..g.rows - 1 {
            for j in 0..g.cols - 1 {
                let pts: Vec<String> = g.face(i, j).iter().map(|p| xy(*p)).collect();
                writeln!(w, r#"<polygon points="{}"/>"#, pts.join(" "))?;
            }
        }
        writeln!(w, "</g>")?;
    }
    for (k, layer) in f.layers.iter().enumerate() {
        writeln!(
            w,
            r#"<g id="layer-{k}" fill="none" stroke-width="1"><title>layer {k}, offset {}</title>"#,
            layer.distance
        )?;
        for b in f.beams.iter().filter(|b| b.layer == k) {
            let colour = match b.family {
                LineFamily::Row => "#c0392b",
                LineFamily::Column => "#2c3e90",
            };
            let pts: Vec<String> = b.nodes.iter().map(|q| xy(b.frame.to_space(*q))).collect();
            writeln!(
                w,
                r#"<polyline stroke="{colour}" points="{}"/>"#,
                pts.join(" ")
            )?;
        }
        writeln!(w, "</g>")?;
    }
    let s = &f.summary;
    writeln!(
        w,
        r#"<text x="{margin}" y="{:.3}" font-family="sans-serif" font-size="14">{} panels, {} beams, {} nodes, {} radii, {} node types</text>"#,
        height + 2.0 * margin + 15.0,
        s.panels,
        s.beams,
        s.nodes,
        s.radii.len(),
        s.node_types
    )?;
    writeln!(w, "</svg>")
}
