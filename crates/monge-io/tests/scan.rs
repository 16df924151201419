//! Design-space scans (§4.3, Figure 14; §5.2) written as a CSV table and an SVG plot.

use monge_core::scan::{parse_range, scan, PanelStats, Scan, ScanRow, Status};
use std::path::Path;

use monge_core::Design;
use monge_io::{read_design, write_scan_csv, write_scan_svg, SCAN_CSV_HEADER};

fn csv(s: &Scan) -> String {
    let mut out = Vec::new();
    write_scan_csv(s, &mut out).unwrap();
    String::from_utf8(out).unwrap()
}

fn svg(s: &Scan) -> String {
    let mut out = Vec::new();
    write_scan_svg(s, &mut out).unwrap();
    String::from_utf8(out).unwrap()
}

/// The θ family of Figure 14 (`examples/fig14-family.toml`), read as a design
/// file is: it folds over itself between about 80° and 110°.
fn figure14() -> Design {
    read_design(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/fig14-family.toml"))
        .unwrap()
}

#[test]
fn the_plot_shades_the_folded_runs_and_the_table_has_a_line_per_value() {
    let v = parse_range("-180:180:2").unwrap();
    let s = scan(&figure14(), "theta", &v, &Default::default(), &|| {}).unwrap();
    let svg = svg(&s);
    let folded = s.intervals(Status::Folded);
    assert_eq!(folded.len(), 2, "{folded:?}");
    for (x, y) in folded {
        assert!(
            svg.contains(&format!(
                "class=\"folded\" data-from=\"{x}\" data-to=\"{y}\""
            )),
            "{svg}"
        );
    }
    assert!(svg.contains("class=\"inadmissible\" data-from=\"90\" data-to=\"90\""));
    assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
    let csv = csv(&s);
    assert_eq!(csv.lines().count(), 182);
    assert_eq!(csv.lines().next(), Some(SCAN_CSV_HEADER));
    assert!(csv
        .lines()
        .any(|l| l.starts_with("90,inadmissible,false,0,,")));
}

#[test]
fn a_row_without_a_mesh_has_empty_cells_and_its_message_quoted() {
    let panels = PanelStats {
        area_min: 0.0,
        area_max: 2.0,
        area_mean: 1.0,
        area_variance: 0.25,
        max_edge: 3.0,
    };
    let s = Scan {
        parameter: "theta_deg".into(),
        rows: vec![
            ScanRow {
                value: 1.5,
                status: Status::Fair,
                error: None,
                folded_faces: 0,
                min_crossing_sine: 0.5,
                panels: Some(panels),
                max_error: 1e-12,
            },
            ScanRow {
                value: 2.0,
                status: Status::Degenerate,
                error: Some("a \"pinch\", here".into()),
                folded_faces: 0,
                min_crossing_sine: f64::NAN,
                panels: None,
                max_error: f64::NAN,
            },
        ],
    };
    let text = csv(&s);
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(
        lines[1..],
        [
            "1.5,fair,true,0,5e-1,0e0,2e0,inf,1e0,2.5e-1,3e0,1e-12,",
            "2,degenerate,true,0,,,,,,,,,\"a \"\"pinch\"\", here\"",
        ]
    );
    assert!(text.ends_with('\n'));
}
