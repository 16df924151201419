//! DXF drawings (§6): flattened panels and beams in their planes, labelled.
//!
//! Written as minimal AutoCAD R12 (`AC1009`) ASCII DXF by hand: a `LAYER`
//! table and `LINE`, `ARC`, `CIRCLE` and `TEXT` entities, which every DXF reader
//! opens (the `dxf` crate would pull image, chrono and uuid for this). Units
//! are the model's; each drawing is laid out in the XY plane.

use std::io::{self, Write};

use glam::DVec2;
use monge_core::fabrication::{Fabrication, Panel, SegmentShape};
use monge_core::tasks;

use crate::schedule::{put_beam_label, put_panel_label};
use crate::text::{emit, Out};

/// The DXF layers used, with their ACI colours.
const LAYERS: [(&str, u8); 6] = [
    ("PANEL", 5),
    ("EDGE", 8),
    ("ARC", 1),
    ("NODE", 3),
    ("SPLIT", 6),
    ("LABEL", 7),
];

/// Starts an R12 DXF document: header, layer table, and the entities section.
fn begin<W: Write + ?Sized>(o: &mut Out<'_, W>) -> io::Result<()> {
    o.str("0\nSECTION\n2\nHEADER\n9\n$ACADVER\n1\nAC1009\n0\nENDSEC\n");
    o.str("0\nSECTION\n2\nTABLES\n0\nTABLE\n2\nLAYER\n70\n");
    o.int(LAYERS.len());
    o.push(b'\n');
    for (name, colour) in LAYERS {
        o.str("0\nLAYER\n2\n");
        o.str(name);
        o.str("\n70\n0\n62\n");
        o.int(colour);
        o.str("\n6\nCONTINUOUS\n");
    }
    o.str("0\nENDTAB\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n");
    o.maybe_flush()
}

/// Ends the entities section and the document.
fn end<W: Write + ?Sized>(o: &mut Out<'_, W>) -> io::Result<()> {
    o.str("0\nENDSEC\n0\nEOF\n");
    o.maybe_flush()
}

/// `0 KIND 8 LAYER`: the start of an entity.
fn entity<W: Write + ?Sized>(o: &mut Out<'_, W>, kind: &str, layer: &str) {
    o.str("0\n");
    o.str(kind);
    o.str("\n8\n");
    o.str(layer);
    o.push(b'\n');
}

/// A point in the XY plane with group codes `10 + k`, `20 + k`, `30 + k`.
fn point<W: Write + ?Sized>(o: &mut Out<'_, W>, k: u8, p: DVec2) {
    o.int(10 + k);
    o.push(b'\n');
    o.float(p.x);
    o.push(b'\n');
    o.int(20 + k);
    o.push(b'\n');
    o.float(p.y);
    o.push(b'\n');
    o.int(30 + k);
    o.str("\n0\n");
}

/// A real value with its group code.
fn real<W: Write + ?Sized>(o: &mut Out<'_, W>, code: u8, x: f64) {
    o.int(code);
    o.push(b'\n');
    o.float(x);
    o.push(b'\n');
}

// The entities are appended, not passed on: a caller writing to a file calls
// `maybe_flush` after each.

fn line<W: Write + ?Sized>(o: &mut Out<'_, W>, layer: &str, a: DVec2, b: DVec2) {
    entity(o, "LINE", layer);
    point(o, 0, a);
    point(o, 1, b);
}

fn circle<W: Write + ?Sized>(o: &mut Out<'_, W>, layer: &str, c: DVec2, r: f64) {
    entity(o, "CIRCLE", layer);
    point(o, 0, c);
    real(o, 40, r);
}

/// A counter-clockwise arc from `start` to `end` degrees.
fn arc<W: Write + ?Sized>(o: &mut Out<'_, W>, layer: &str, c: DVec2, r: f64, start: f64, end: f64) {
    entity(o, "ARC", layer);
    point(o, 0, c);
    real(o, 40, r);
    real(o, 50, start);
    real(o, 51, end);
}

/// A text on layer `LABEL` whose string `put` writes.
fn text<W: Write + ?Sized>(
    o: &mut Out<'_, W>,
    at: DVec2,
    height: f64,
    put: impl FnOnce(&mut Out<'_, W>),
) {
    entity(o, "TEXT", "LABEL");
    point(o, 0, at);
    real(o, 40, height);
    o.str("1\n");
    put(o);
    o.push(b'\n');
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
    emit(w, |o| panels_dxf(f, o))
}

fn panels_dxf<W: Write + ?Sized>(f: &Fabrication, o: &mut Out<'_, W>) -> io::Result<()> {
    begin(o)?;
    let size = |p: Panel| {
        let (lo, hi) = bounds(&p.outline);
        (hi - lo).max_element()
    };
    let cell = tasks::ranges(f.panels().len(), tasks::BLOCK, |r| {
        f.panels_in(r).map(size).fold(0.0, f64::max)
    })
    .into_iter()
    .fold(0.0, f64::max)
        * 1.25;
    // Layer by layer, each `rows + 1` cells above the one before.
    let rows = f.layers[0].grid.rows - 1;
    let y0: Vec<f64> = (f.layers.iter())
        .scan(0.0, |y, _| {
            let at = *y;
            *y += (rows + 1) as f64 * cell;
            Some(at)
        })
        .collect();
    // Panels computed and formatted in chunks side by side.
    o.each_range(f.panels().len(), |o, range| {
        for p in f.panels_in(range) {
            let (lo, _) = bounds(&p.outline);
            let at = DVec2::new(p.j as f64 * cell, y0[p.layer] + p.i as f64 * cell) - lo;
            let q = p.outline.map(|c| c + at);
            for k in 0..4 {
                line(o, "PANEL", q[k], q[(k + 1) % 4]);
            }
            let centroid = q.iter().copied().sum::<DVec2>() / 4.0;
            text(o, centroid, cell * 0.06, |o| put_panel_label(o, &p));
        }
    })?;
    end(o)
}

/// Beams in their planes (§4.6, §6): for each beam, its edges as straight
/// lines (layer `EDGE`), its circular segments as arcs (layer `ARC`), its nodes
/// as small circles (layer `NODE`, split nodes larger on layer `SPLIT`) and its
/// label with its radii (layer `LABEL`). Beams are stacked upwards, each with
/// its chord along X.
pub fn write_beams_dxf(f: &Fabrication, w: &mut dyn Write) -> io::Result<()> {
    emit(w, |o| beams_dxf(f, o))
}

fn beams_dxf<W: Write + ?Sized>(f: &Fabrication, o: &mut Out<'_, W>) -> io::Result<()> {
    begin(o)?;
    let size = f.summary.size;
    let (mark, gap) = (size * 0.002, size * 0.05);
    let mut y0 = 0.0;
    for b in f.beams() {
        let (lo, hi) = bounds(&b.nodes);
        let at = DVec2::new(0.0, y0) - lo;
        let q: Vec<DVec2> = b.nodes.iter().map(|p| *p + at).collect();
        for e in q.windows(2) {
            line(o, "EDGE", e[0], e[1]);
            o.maybe_flush()?;
        }
        let mut split = vec![false; q.len()];
        for s in b.segments.iter().skip(1) {
            split[s.start] = true;
        }
        for (p, split) in q.iter().zip(split) {
            if split {
                circle(o, "SPLIT", *p, 2.0 * mark);
            } else {
                circle(o, "NODE", *p, mark);
            }
            o.maybe_flush()?;
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
                arc(o, "ARC", c, radius, start, end);
                o.maybe_flush()?;
                radii.push(format!("R{radius:.6}"));
            }
        }
        text(o, DVec2::new(-gap * 4.0, y0), gap * 0.4, |o| {
            put_beam_label(o, &b);
            for r in &radii {
                o.push(b' ');
                o.str(r);
            }
        });
        o.maybe_flush()?;
        y0 += (hi - lo).y + gap;
    }
    end(o)
}
