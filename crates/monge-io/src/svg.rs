//! An SVG overview of a gridshell (§6): the plan (view from +Z) of every layer.

use std::io::{self, Write};

use glam::DVec3;
use monge_core::fabrication::{Fabrication, LineFamily};

use crate::text::{emit, Out};

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
    let xy = |o: &mut Out<'_, dyn Write>, p: DVec3| {
        milli(o, margin + (p.x - lo.x) * scale);
        o.push(b',');
        milli(o, margin + (hi.y - p.y) * scale);
    };
    emit(w, |o| {
        o.str(&format!(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{0:.0}" height="{1:.0}" viewBox="0 0 {0:.3} {1:.3}">"#,
            WIDTH + 2.0 * margin,
            height + 2.0 * margin + 30.0
        ));
        o.end()?;
        if let Some(top) = f.layers.last() {
            o.str(r##"<g id="panels" fill="#cfe8ff" stroke="#7aa7d8" stroke-width="0.5">"##);
            o.end()?;
            let g = &top.grid;
            for i in 0..g.rows - 1 {
                for j in 0..g.cols - 1 {
                    o.str(r#"<polygon points=""#);
                    for (k, p) in g.face(i, j).iter().enumerate() {
                        if k > 0 {
                            o.push(b' ');
                        }
                        xy(o, *p);
                    }
                    o.str(r#""/>"#);
                    o.end()?;
                }
            }
            o.str("</g>");
            o.end()?;
        }
        for (k, layer) in f.layers.iter().enumerate() {
            o.str(&format!(
                r#"<g id="layer-{k}" fill="none" stroke-width="1"><title>layer {k}, offset {}</title>"#,
                layer.distance
            ));
            o.end()?;
            for b in f.layer_beams(k) {
                o.str(match b.family {
                    LineFamily::Row => r##"<polyline stroke="#c0392b" points=""##,
                    LineFamily::Column => r##"<polyline stroke="#2c3e90" points=""##,
                });
                for (k, q) in b.nodes.iter().enumerate() {
                    if k > 0 {
                        o.push(b' ');
                    }
                    xy(o, b.frame.to_space(*q));
                    o.maybe_flush()?;
                }
                o.str(r#""/>"#);
                o.end()?;
            }
            o.str("</g>");
            o.end()?;
        }
        let s = &f.summary;
        o.str(&format!(
            r#"<text x="{margin}" y="{:.3}" font-family="sans-serif" font-size="14">{} panels, {} beams, {} nodes, {} radii, {} node types</text>"#,
            height + 2.0 * margin + 15.0,
            s.panels,
            s.beams,
            s.nodes,
            s.radii.len(),
            s.node_types
        ));
        o.str("\n</svg>");
        o.end()
    })
}

/// Appends `x` with three decimals (`12.345`, `-0.500`), as `{:.3}` does
/// (rounding `x × 1000` half away from zero, so a tie may differ in the last digit).
fn milli<W: Write + ?Sized>(o: &mut Out<'_, W>, x: f64) {
    let m = (x * 1000.0).round();
    if m < 0.0 {
        o.push(b'-');
    }
    let m = m.abs() as u64;
    o.int(m / 1000);
    o.push(b'.');
    let frac = m % 1000;
    if frac < 100 {
        o.push(b'0');
    }
    if frac < 10 {
        o.push(b'0');
    }
    o.int(frac);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn milli_agrees_with_fixed_formatting() {
        let mut v = Vec::new();
        let xs = [
            0.0,
            1.0,
            -1.0,
            12.3456,
            -0.0004,
            -0.5004,
            999.9996,
            0.05,
            1234567.0001,
        ];
        emit(&mut v, |o| {
            for x in xs {
                milli(o, x);
                o.push(b' ');
            }
            Ok(())
        })
        .unwrap();
        let expected: Vec<String> = xs
            .iter()
            .map(|x| format!("{x:.3}").replace("-0.000", "0.000"))
            .collect();
        assert_eq!(String::from_utf8(v).unwrap(), expected.join(" ") + " ");
    }
}
