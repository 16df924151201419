//! Design-space scans (§4.3, Figure 14; §5.2) as files: a CSV table, one row
//! per value, and an SVG plot of the panel-area spread and folded faces
//! against the value, bad intervals shaded.

use std::fmt::Write as _;
use std::io::{self, Write};

use monge_core::scan::{PanelStats, Scan, Status};

/// The header of [`write_scan_csv`].
pub const SCAN_CSV_HEADER: &str =
    "value,status,admissible,folded_faces,min_crossing_sine,area_min,\
area_max,area_spread,area_mean,area_variance,max_edge,max_error,error";

/// Writes a scan as CSV (§4.3): [`SCAN_CSV_HEADER`], then one row per value; empty cells
/// where there is no mesh, `inf` for the spread of a mesh with a zero-area face;
/// the error message quoted (double quotes doubled).
pub fn write_scan_csv<W: Write + ?Sized>(scan: &Scan, w: &mut W) -> io::Result<()> {
    let mut s = String::from(SCAN_CSV_HEADER);
    s.push('\n');
    let num = |x: f64| {
        if x.is_nan() {
            String::new()
        } else {
            format!("{x:e}")
        }
    };
    for r in &scan.rows {
        let p = r.panels;
        let field = |f: fn(&PanelStats) -> f64| p.as_ref().map(f).map(num).unwrap_or_default();
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{},{},{},{},{}",
            r.value,
            r.status.name(),
            r.admissible(),
            r.folded_faces,
            num(r.min_crossing_sine),
            field(|p| p.area_min),
            field(|p| p.area_max),
            field(PanelStats::spread),
            field(|p| p.area_mean),
            field(|p| p.area_variance),
            field(|p| p.max_edge),
            num(r.max_error),
            r.error
                .as_deref()
                .map(|e| format!("\"{}\"", e.replace('"', "\"\"")))
                .unwrap_or_default()
        );
    }
    w.write_all(s.as_bytes())
}

/// Plot size in SVG user units.
const WIDTH: f64 = 900.0;
const HEIGHT: f64 = 420.0;
const LEFT: f64 = 70.0;
const RIGHT: f64 = 70.0;
const TOP: f64 = 40.0;
const BOTTOM: f64 = 60.0;

/// Colours of the shaded intervals, by status.
fn shade(status: Status) -> Option<&'static str> {
    match status {
        Status::Fair => None,
        Status::Folded => Some("#f4a6a6"),
        Status::Inadmissible => Some("#c8c8c8"),
        Status::Degenerate => Some("#f6d28b"),
        Status::Invalid => Some("#b9c9e8"),
    }
}

/// Writes a scan as an SVG plot a designer can read (§4.3, Figure 14): the parameter
/// on x; the panel-area spread `max/min` (log scale, blue line, left axis) and
/// the number of folded faces (red line, right axis) on y; intervals where the
/// mesh folds over itself (§5.2) shaded red, inadmissible values grey,
/// degenerate ones orange, invalid ones blue, each shaded rectangle carrying
/// `class="<status>"` and `data-from`/`data-to` (the first and last value of the
/// interval) so that tools can read them back.
pub fn write_scan_svg<W: Write + ?Sized>(scan: &Scan, w: &mut W) -> io::Result<()> {
    let rows = &scan.rows;
    let (x0, x1) = match (rows.first(), rows.last()) {
        (Some(a), Some(b)) if b.value > a.value => (a.value, b.value),
        (Some(a), _) => (a.value - 1.0, a.value + 1.0),
        _ => (0.0, 1.0),
    };
    let half = if rows.len() > 1 {
        0.5 * (x1 - x0) / (rows.len() - 1) as f64
    } else {
        0.5
    };
    let (lo, hi) = (x0 - half, x1 + half);
    let px = |x: f64| LEFT + (x - lo) / (hi - lo) * (WIDTH - LEFT - RIGHT);
    let spreads: Vec<f64> = rows
        .iter()
        .filter_map(|r| r.panels.map(|p| p.spread()))
        .filter(|s| s.is_finite() && *s >= 1.0)
        .collect();
    let top_spread = spreads.iter().copied().fold(10.0, f64::max).log10().ceil();
    let max_folds = rows
        .iter()
        .map(|r| r.folded_faces)
        .max()
        .unwrap_or(0)
        .max(1) as f64;
    let plot_h = HEIGHT - TOP - BOTTOM;
    let py_spread = |s: f64| TOP + plot_h * (1.0 - s.max(1.0).log10().min(top_spread) / top_spread);
    let py_folds = |f: f64| TOP + plot_h * (1.0 - f / max_folds);
    let mut s = String::new();
    let _ = writeln!(
        s,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{WIDTH}\" height=\"{HEIGHT}\" \
         viewBox=\"0 0 {WIDTH} {HEIGHT}\" font-family=\"sans-serif\" font-size=\"12\">"
    );
    let _ = writeln!(
        s,
        "<rect x=\"0\" y=\"0\" width=\"{WIDTH}\" height=\"{HEIGHT}\" fill=\"white\"/>"
    );
    // Shaded intervals, one rectangle per run of equal non-fair status.
    for status in [
        Status::Folded,
        Status::Inadmissible,
        Status::Degenerate,
        Status::Invalid,
    ] {
        let colour = shade(status).unwrap_or("none");
        for (a, b) in scan.intervals(status) {
            let (xa, xb) = (px(a - half), px(b + half));
            let _ = writeln!(
                s,
                "<rect class=\"{}\" data-from=\"{a}\" data-to=\"{b}\" x=\"{xa:.2}\" y=\"{TOP}\" \
                 width=\"{:.2}\" height=\"{plot_h}\" fill=\"{colour}\"/>",
                status.name(),
                xb - xa
            );
        }
    }
    // Axes and ticks.
    let (bx, by) = (WIDTH - RIGHT, TOP + plot_h);
    let _ = writeln!(
        s,
        "<path d=\"M{LEFT} {TOP}V{by}H{bx}V{TOP}\" fill=\"none\" stroke=\"black\"/>"
    );
    for k in 0..=6 {
        let x = x0 + (x1 - x0) * k as f64 / 6.0;
        let _ = writeln!(
            s,
            "<text x=\"{:.2}\" y=\"{}\" text-anchor=\"middle\">{}</text>",
            px(x),
            by + 18.0,
            round(x)
        );
    }
    for k in 0..=top_spread as usize {
        let _ = writeln!(
            s,
            "<text x=\"{}\" y=\"{:.2}\" text-anchor=\"end\" fill=\"#1f5fbf\">1e{k}</text>",
            LEFT - 6.0,
            py_spread(10f64.powi(k as i32)) + 4.0
        );
    }
    for f in [0.0, max_folds] {
        let _ = writeln!(
            s,
            "<text x=\"{}\" y=\"{:.2}\" fill=\"#c0392b\">{f}</text>",
            bx + 6.0,
            py_folds(f) + 4.0
        );
    }
    let _ = writeln!(
        s,
        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>",
        0.5 * (LEFT + bx),
        HEIGHT - 12.0,
        scan.parameter
    );
    let _ = writeln!(
        s,
        "<text x=\"{LEFT}\" y=\"24\"><tspan fill=\"#1f5fbf\">panel area spread max/min (log)</tspan> \
         <tspan fill=\"#c0392b\">folded faces</tspan> · shaded: <tspan fill=\"#d05050\">folded</tspan> \
         <tspan fill=\"#909090\">inadmissible</tspan> <tspan fill=\"#c08020\">degenerate</tspan> \
         <tspan fill=\"#5070b0\">invalid</tspan></text>"
    );
    // The two curves, broken where there is no mesh.
    let curve = |points: Vec<Option<(f64, f64)>>, class: &str, colour: &str| {
        let mut d = String::new();
        let mut pen = false;
        for p in points {
            match p {
                Some((x, y)) => {
                    let _ = write!(d, "{}{x:.2} {y:.2}", if pen { "L" } else { "M" });
                    pen = true;
                }
                None => pen = false,
            }
        }
        format!(
            "<path class=\"{class}\" d=\"{d}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"1.5\"/>\n"
        )
    };
    s.push_str(&curve(
        rows.iter()
            .map(|r| {
                r.panels
                    .map(|p| (px(r.value), py_spread(p.spread().min(1e300))))
            })
            .collect(),
        "spread",
        "#1f5fbf",
    ));
    s.push_str(&curve(
        rows.iter()
            .map(|r| {
                r.panels
                    .map(|_| (px(r.value), py_folds(r.folded_faces as f64)))
            })
            .collect(),
        "folds",
        "#c0392b",
    ));
    s.push_str("</svg>\n");
    w.write_all(s.as_bytes())
}

/// `x` rounded to 4 significant decimals for tick labels.
fn round(x: f64) -> f64 {
    (x * 1e4).round() / 1e4
}
