//! The SVG back end: shapes as plain SVG 1.1 elements.

use std::fmt::Write;

use crate::compose::{Pen, Pt, Rgba, Shape};
use crate::RenderOptions;

/// `shapes` as an SVG document of the options' size.
pub fn document(shapes: &[Shape], o: &RenderOptions) -> String {
    let mut s = String::new();
    let bg = o.background;
    // `write!` to a String cannot fail.
    let _ = writeln!(
        s,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\">\n\
         <rect width=\"{w}\" height=\"{h}\" fill=\"#{:02x}{:02x}{:02x}\"/>\n\
         <g stroke-linejoin=\"round\" stroke-linecap=\"round\">",
        bg.r,
        bg.g,
        bg.b,
        w = o.width,
        h = o.height
    );
    for shape in shapes {
        element(&mut s, shape);
    }
    s.push_str("</g>\n</svg>\n");
    s
}

/// `#rrggbb`.
fn hex(c: Rgba) -> String {
    format!("#{:02x}{:02x}{:02x}", c.r, c.g, c.b)
}

/// A coordinate with at most two decimals, without trailing zeros.
fn num(x: f32) -> String {
    let s = format!("{x:.2}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".to_owned()
    } else {
        s.to_owned()
    }
}

/// `x,y x,y …`.
fn points(ps: &[Pt]) -> String {
    let list: Vec<String> = ps
        .iter()
        .map(|p| format!("{},{}", num(p[0]), num(p[1])))
        .collect();
    list.join(" ")
}

/// The `fill` attributes (`none` when absent).
fn fill(c: Option<Rgba>) -> String {
    match c {
        None => " fill=\"none\"".to_owned(),
        Some(c) if c.a == 255 => format!(" fill=\"{}\"", hex(c)),
        Some(c) => format!(
            " fill=\"{}\" fill-opacity=\"{}\"",
            hex(c),
            num(f32::from(c.a) / 255.0)
        ),
    }
}

/// The `stroke` attributes (none when absent).
fn stroke(pen: Option<Pen>) -> String {
    match pen {
        None => String::new(),
        Some(p) => {
            let mut s = format!(
                " stroke=\"{}\" stroke-width=\"{}\"",
                hex(p.color),
                num(p.width)
            );
            if p.color.a != 255 {
                let _ = write!(
                    s,
                    " stroke-opacity=\"{}\"",
                    num(f32::from(p.color.a) / 255.0)
                );
            }
            s
        }
    }
}

/// `text` with `&`, `<` and `>` escaped, and the control characters XML 1.0
/// forbids (all but tab, line feed and carriage return) replaced by U+FFFD.
fn escape(text: &str) -> String {
    text.chars()
        .map(|c| match c {
            '\t' | '\n' | '\r' => c,
            c if c.is_control() => '\u{FFFD}',
            c => c,
        })
        .collect::<String>()
        .replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// Appends one element.
fn element(s: &mut String, shape: &Shape) {
    let _ = match shape {
        Shape::Polygon {
            points: ps,
            fill: f,
            stroke: pen,
        } => writeln!(s, "<polygon points=\"{}\"{}{}/>", points(ps), fill(*f), stroke(*pen)),
        Shape::Polyline { points: ps, pen } => writeln!(
            s,
            "<polyline points=\"{}\" fill=\"none\"{}/>",
            points(ps),
            stroke(Some(*pen))
        ),
        Shape::Circle {
            center,
            radius,
            fill: f,
            stroke: pen,
        } => writeln!(
            s,
            "<circle cx=\"{}\" cy=\"{}\" r=\"{}\"{}{}/>",
            num(center[0]),
            num(center[1]),
            num(*radius),
            fill(*f),
            stroke(*pen)
        ),
        Shape::Text {
            center,
            size,
            color,
            text,
        } => writeln!(
            s,
            "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" font-family=\"Helvetica, Arial, sans-serif\" \
             font-size=\"{}\" fill=\"{}\">{}</text>",
            num(center[0]),
            num(center[1] + size / 2.0),
            num(size / 0.72),
            hex(*color),
            escape(text)
        ),
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_short() {
        assert_eq!(num(1.0), "1");
        assert_eq!(num(1.256), "1.26");
        assert_eq!(num(-0.001), "0");
        assert_eq!(num(-2.5), "-2.5");
    }

    #[test]
    fn text_is_escaped() {
        assert_eq!(escape("a<b & c>d"), "a&lt;b &amp; c&gt;d");
        // A file name with BEL and ESC once made the SVG invalid XML.
        assert_eq!(escape("ctl\u{7}\u{1b}.json"), "ctl\u{FFFD}\u{FFFD}.json");
    }
}
