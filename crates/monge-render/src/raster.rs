//! The PNG back end: shapes rasterised by tiny-skia, anti-aliased.

use tiny_skia::{
    Color, FillRule, LineCap, LineJoin, Paint, PathBuilder, Pixmap, Rect, Stroke, Transform,
};

use crate::compose::{Pen, Pt, Rgba, Shape};
use crate::font;
use crate::{RenderError, RenderOptions};

/// `shapes` drawn in order on the background, encoded as PNG.
pub fn png(shapes: &[Shape], o: &RenderOptions) -> Result<Vec<u8>, RenderError> {
    let mut pixmap = Pixmap::new(o.width, o.height).ok_or(RenderError::Size {
        width: o.width,
        height: o.height,
    })?;
    let bg = o.background;
    pixmap.fill(Color::from_rgba8(bg.r, bg.g, bg.b, 255));
    for shape in shapes {
        draw(&mut pixmap, shape);
    }
    encode(&pixmap).map_err(|e| RenderError::Encode(e.to_string()))
}

/// Colours of the palette of an encoded picture.
const PALETTE: usize = 256;

/// `pixmap` (opaque: the background is) as an indexed PNG, compressed hard: the
/// pictures are meant to be committed. The palette holds the 256 most frequent
/// colours (ties to the smaller colour); every other colour, in practice an
/// anti-aliased blend, becomes its nearest palette colour. Pictures of fewer
/// colours are exact.
fn encode(pixmap: &Pixmap) -> Result<Vec<u8>, png::EncodingError> {
    let pixels: Vec<u32> = pixmap
        .data()
        .chunks_exact(4)
        .map(|px| u32::from_be_bytes([0, px[0], px[1], px[2]]))
        .collect();
    // Distinct colours with their counts, sorted by colour.
    let mut sorted = pixels.clone();
    sorted.sort_unstable();
    let mut distinct: Vec<(u32, usize)> = Vec::new();
    for c in sorted {
        match distinct.last_mut() {
            Some((last, n)) if *last == c => *n += 1,
            _ => distinct.push((c, 1)),
        }
    }
    let mut by_count = distinct.clone();
    by_count.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
    let palette: Vec<u32> = by_count.iter().take(PALETTE).map(|d| d.0).collect();
    let rgb = |c: u32| c.to_be_bytes();
    let nearest = |c: u32| {
        let [_, r, g, b] = rgb(c);
        let dist = |p: u32| {
            let [_, pr, pg, pb] = rgb(p);
            let d = |x: u8, y: u8| (i32::from(x) - i32::from(y)).pow(2);
            d(r, pr) + d(g, pg) + d(b, pb)
        };
        (0..palette.len())
            .min_by_key(|&k| (dist(palette[k]), k))
            .unwrap_or(0) as u8
    };
    // Palette index of each distinct colour, in the order of `distinct`.
    let index: Vec<u8> = distinct.iter().map(|d| nearest(d.0)).collect();
    let indices: Vec<u8> = pixels
        .iter()
        .map(|c| index[distinct.partition_point(|d| d.0 < *c)])
        .collect();
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, pixmap.width(), pixmap.height());
    encoder.set_color(png::ColorType::Indexed);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_palette(
        palette
            .iter()
            .flat_map(|&c| {
                let [_, r, g, b] = rgb(c);
                [r, g, b]
            })
            .collect::<Vec<u8>>(),
    );
    encoder.set_compression(png::Compression::Best);
    encoder.set_adaptive_filter(png::AdaptiveFilterType::NonAdaptive);
    encoder.set_filter(png::FilterType::NoFilter);
    let mut writer = encoder.write_header()?;
    writer.write_image_data(&indices)?;
    writer.finish()?;
    Ok(bytes)
}

/// A solid, anti-aliased paint.
fn paint(c: Rgba) -> Paint<'static> {
    let mut p = Paint::default();
    p.set_color_rgba8(c.r, c.g, c.b, c.a);
    p.anti_alias = true;
    p
}

/// The path through `points`, closed if asked.
fn path(points: &[Pt], close: bool) -> Option<tiny_skia::Path> {
    let (first, rest) = points.split_first()?;
    let mut b = PathBuilder::new();
    b.move_to(first[0], first[1]);
    for p in rest {
        b.line_to(p[0], p[1]);
    }
    if close {
        b.close();
    }
    b.finish()
}

/// A round-joined stroke of `pen`.
fn stroke(pixmap: &mut Pixmap, path: &tiny_skia::Path, pen: Pen) {
    let s = Stroke {
        width: pen.width,
        line_cap: LineCap::Round,
        line_join: LineJoin::Round,
        ..Stroke::default()
    };
    pixmap.stroke_path(path, &paint(pen.color), &s, Transform::identity(), None);
}

/// Draws one shape (degenerate ones draw nothing).
fn draw(pixmap: &mut Pixmap, shape: &Shape) {
    match shape {
        Shape::Polygon {
            points,
            fill,
            stroke: pen,
        } => {
            let Some(p) = path(points, true) else { return };
            if let Some(c) = fill {
                pixmap.fill_path(
                    &p,
                    &paint(*c),
                    FillRule::Winding,
                    Transform::identity(),
                    None,
                );
            }
            if let Some(pen) = pen {
                stroke(pixmap, &p, *pen);
            }
        }
        Shape::Polyline { points, pen } => {
            if let Some(p) = path(points, false) {
                stroke(pixmap, &p, *pen);
            }
        }
        Shape::Circle {
            center,
            radius,
            fill,
            stroke: pen,
        } => {
            let Some(p) = PathBuilder::from_circle(center[0], center[1], *radius) else {
                return;
            };
            if let Some(c) = fill {
                pixmap.fill_path(
                    &p,
                    &paint(*c),
                    FillRule::Winding,
                    Transform::identity(),
                    None,
                );
            }
            if let Some(pen) = pen {
                stroke(pixmap, &p, *pen);
            }
        }
        Shape::Text {
            center,
            size,
            color,
            text,
        } => draw_text(pixmap, *center, *size, *color, text),
    }
}

/// `text` in the bitmap font, scaled by a whole factor to about `size` pixels,
/// centred on `center`, pixel-aligned.
fn draw_text(pixmap: &mut Pixmap, center: Pt, size: f32, color: Rgba, text: &str) {
    let s = (size / font::HEIGHT as f32).round().max(1.0);
    let n = text.chars().count() as f32;
    let width = (n * font::ADVANCE as f32 - 1.0) * s;
    let left = (center[0] - width / 2.0).round();
    let top = (center[1] - font::HEIGHT as f32 * s / 2.0).round();
    let mut p = paint(color);
    p.anti_alias = false;
    for (k, c) in text.chars().enumerate() {
        let x0 = left + (k as u32 * font::ADVANCE) as f32 * s;
        for (row, bits) in font::glyph(c).iter().enumerate() {
            let y = top + row as f32 * s;
            let mut col = 0;
            while col < 5 {
                if bits >> (4 - col) & 1 == 0 {
                    col += 1;
                    continue;
                }
                let start = col;
                while col < 5 && bits >> (4 - col) & 1 == 1 {
                    col += 1;
                }
                let x = x0 + start as f32 * s;
                if let Some(r) = Rect::from_xywh(x, y, (col - start) as f32 * s, s) {
                    pixmap.fill_rect(r, &p, Transform::identity(), None);
                }
            }
        }
    }
}
