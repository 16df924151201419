//! DXF drawings (§6): flattened panels and beams in their planes, labelled.
//!
//! Written as minimal AutoCAD R12 (`AC1009`) ASCII DXF by hand: a `LAYER`
//! table and `LINE`, `ARC`, `CIRCLE` and `TEXT` entities, which every DXF reader
//! opens (the `dxf` crate would pull image, chrono and uuid for this). Units
//! are the model's; each drawing is laid out in the XY plane.

use std::io::{self, Write};

use glam::DVec2;
use monge_core::fabrication::{Fabrication, SegmentShape};

use crate::schedule::{beam_label, panel_label};

/// The DXF layers used, with their ACI colours.
const LAYERS: [(&str, u8); 6] = [
    ("PANEL", 5),
    ("EDGE", 8),
    ("ARC", 1),
    ("NODE", 3),
    ("SPLIT", 6),
    ("LABEL", 7),
];

/// An R12 DXF document being written.
struct Dxf<'a> {
    w: &'a mut dyn Write,
}

impl<'a> Dxf<'a> {
    fn begin(w: &'a mut dyn Write) -> io::Result<Self> {
        write!(
            w,
            "0\nSECTION\n2\nHEADER\n9\n$ACADVER\n1\nAC1009\n0\nENDSEC\n"
        )?;
        write!(
            w,
            "0\nSECTION\n2\nTABLES\n0\nTABLE\n2\nLAYER\n70\n{}\n",
            LAYERS.len()
        )?;
        for (name, colour) in LAYERS {
            write!(
                w,
                "0\nLAYER\n2\n{name}\n70\n0\n62\n{colour}\n6\nCONTINUOUS\n"
            )?;
        }
        write!(w, "0\nENDTAB\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n")?;
        Ok(Dxf { w })
    }

    fn end(self) -> io::Result<()> {
        write!(self.w, "0\nENDSEC\n0\nEOF\n")
    }

    fn line(&mut self, layer: &str, a: DVec2, b: DVec2) -> io::Result<()> {
        write!(
            self.w,
            "0\nLINE\n8\n{layer}\n10\n{}\n20\n{}\n30\n0\n11\n{}\n21\n{}\n31\n0\n",
            a.x, a.y, b.x, b.y
        )
    }

    fn circle(&mut self, layer: &str, c: DVec2, r: f64) -> io::Result<()> {
        write!(
            self.w,
            "0\nCIRCLE\n8\n{layer}\n10\n{}\n20\n{}\n30\n0\n40\n{r}\n",
            c.x, c.y
        )
    }

    /// A counter-clockwise arc from `start` to `end` degrees.
    fn arc(&mut self, layer: &str, c: DVec2, r: f64, start: f64, end: f64) -> io::Result<()> {
        write!(
            self.w,
            "0\nARC\n8\n{layer}\n10\n{}\n20\n{}\n30\n0\n40\n{r}\n50\n{start}\n51\n{end}\n",
            c.x, c.y
        )
    }

    fn text(&mut self, at: DVec2, height: f64, text: &str) -> io::Result<()> {
        write!(
            self.w,
            "0\nTEXT\n8\nLABEL\n10\n{}\n20\n{}\n30\n0\n40\n{height}\n1\n{text}\n",
            at.x, at.y
        )
    }
}

/// Bounding box of plane points: `(min, max)`.
fn bounds(points: &[DVec2]) -> (DVec2, DVec2) {
    points.iter().fold(
        (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    )
}

/// Flattened panels (§2.2, §6): each panel's exact outline in its own plane,
/// on DXF layer `PANEL`, labelled `L<layer>-P<i>.<j>` at its centroid (layer
/// `LABEL`). Panel `(i, j)` of layer `k` is placed in cell `(j, i)` of a grid
/// whose cells fit the largest panel; layers follow each other upwards.
pub fn write_panels_dxf(f: &Fabrication, w: &mut dyn Write) -> io::Result<()> {
    let mut dxf = Dxf::begin(w)?;
    let cell = f
        .panels
        .iter()
        .map(|p| {
            let (lo, hi) = bounds(&p.outline);
            (hi - lo).max_element()
        })
        .fold(0.0, f64::max)
        * 1.25;
    let mut y0 = 0.0;
    for layer in 0..f.layers.len() {
        let mut rows = 0;
        for p in f.panels.iter().filter(|p| p.layer == layer) {
            rows = rows.max(p.i + 1);
            let (lo, _) = bounds(&p.outline);
            let at = DVec2::new(p.j as f64 * cell, y0 + p.i as f64 * cell) - lo;
            let q = p.outline.map(|c| c + at);
            for k in 0..4 {
                dxf.line("PANEL", q[k], q[(k + 1) % 4])?;
            }
            let centroid = q.iter().copied().sum::<DVec2>() / 4.0;
            dxf.text(centroid, cell * 0.06, &panel_label(p))?;
        }
        y0 += (rows + 1) as f64 * cell;
    }
    dxf.end()
}

/// Beams in their planes (§4.6, §6): for each beam, its edges as straight
/// lines (layer `EDGE`), its circular segments as arcs (layer `ARC`), its nodes
/// as small circles (layer `NODE`, split nodes larger on layer `SPLIT`) and its
/// label with its radii (layer `LABEL`). Beams are stacked upwards, each with
/// its chord along X.
pub fn write_beams_dxf(f: &Fabrication, w: &mut dyn Write) -> io::Result<()> {
    let mut dxf = Dxf::begin(w)?;
    let size = f.summary.size;
    let (mark, gap) = (size * 0.002, size * 0.05);
    let mut y0 = 0.0;
    for b in &f.beams {
        let (lo, hi) = bounds(&b.nodes);
        let at = DVec2::new(0.0, y0) - lo;
        let q: Vec<DVec2> = b.nodes.iter().map(|p| *p + at).collect();
        for e in q.windows(2) {
            dxf.line("EDGE", e[0], e[1])?;
        }
        let mut split = vec![false; q.len()];
        for s in b.segments.iter().skip(1) {
            split[s.start] = true;
        }
        for (p, split) in q.iter().zip(split) {
            if split {
                dxf.circle("SPLIT", *p, 2.0 * mark)?;
            } else {
                dxf.circle("NODE", *p, mark)?;
            }
        }
        let mut radii = Vec::new();
        for s in &b.segments {
            if let SegmentShape::Arc {
                center,
                radius,
                sweep,
                ..
            } = s.shape
            {
                let c = center + at;
                let angle = |p: DVec2| (p - c).to_angle().to_degrees().rem_euclid(360.0);
                let (from, to) = (angle(q[s.start]), angle(q[s.end]));
                let (start, end) = if sweep >= 0.0 { (from, to) } else { (to, from) };
                dxf.arc("ARC", c, radius, start, end)?;
                radii.push(format!("R{radius:.6}"));
            }
        }
        let label = format!("{} {}", beam_label(b), radii.join(" "));
        dxf.text(DVec2::new(-gap * 4.0, y0), gap * 0.4, label.trim_end())?;
        y0 += (hi - lo).y + gap;
    }
    dxf.end()
}
