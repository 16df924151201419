//! IGES entity 128: the writer's fixed format checked column by column, and a
//! cyclidic net written and read back.

use crate::common;

use std::io;
use std::path::Path;

use glam::DVec3;
use monge_core::cyclidic::{CyclidicNet, CyclidicOptions, NurbsSurface};
use monge_core::{generate, GenerateOptions};
use monge_io::{read_design, write_iges, NurbsColumn, NurbsColumns};

// ---------------------------------------------------------------------------
// Hand-written files

use common::iges::{entity, file, one, parameters, BILINEAR};

/// A degree-(2, 2) surface from `rows × cols` control points `f(a, b)`, weights `w(a, b)`.
fn surface(
    rows: usize,
    cols: usize,
    f: impl Fn(usize, usize) -> DVec3,
    w: impl Fn(usize, usize) -> f64,
) -> NurbsSurface {
    let knots = |n: usize| {
        let mut k = vec![0.0; 3];
        k.extend((1..n - 2).map(|s| s as f64));
        k.extend([(n - 2) as f64; 3]);
        k
    };
    let cells = || (0..rows).flat_map(move |a| (0..cols).map(move |b| (a, b)));
    NurbsSurface {
        rows,
        cols,
        control_points: cells().map(|(a, b)| f(a, b)).collect(),
        weights: cells().map(|(a, b)| w(a, b)).collect(),
        knots_u: knots(rows),
        knots_v: knots(cols),
    }
}

fn written(s: &NurbsSurface) -> String {
    let mut out = Vec::new();
    write_iges(s, &mut out).unwrap();
    String::from_utf8(out).unwrap()
}

/// The fixed-format check, independent of the reader: returns the entity's
/// parameters as text.
fn check_format(text: &str) -> Vec<String> {
    let lines: Vec<&str> = text.split_inclusive('\n').collect();
    assert!(text.ends_with('\n'));
    let mut count = [0usize; 5];
    let mut last_section = 0;
    for l in &lines {
        let l = l.strip_suffix('\n').unwrap();
        assert_eq!(l.len(), 80, "`{l}`");
        assert!(l.is_ascii());
        let section = "SGDPT".find(&l[72..73]).unwrap();
        assert!(section >= last_section);
        last_section = section;
        count[section] += 1;
        assert_eq!(
            l[73..].trim_start().parse::<usize>().unwrap(),
            count[section]
        );
        assert_eq!(l[73..].len(), 7);
    }
    assert_eq!(count[0], 1);
    assert_eq!(count[2], 2);
    assert_eq!(count[4], 1);
    let t = lines.last().unwrap();
    let expected_t = format!(
        "S{:>7}G{:>7}D{:>7}P{:>7}",
        count[0], count[1], count[2], count[3]
    );
    assert_eq!(&t[..32], expected_t);
    assert!(t[32..72].trim().is_empty());

    // Directory entry: type 128, parameter pointer 1, no transformation, status, line count.
    let d1 = lines[1 + count[1]];
    let d2 = lines[2 + count[1]];
    let field = |l: &str, k: usize| l[8 * k..8 * k + 8].trim().to_owned();
    assert_eq!(field(d1, 0), "128");
    assert_eq!(field(d1, 1), "1");
    assert_eq!(field(d1, 6), "0");
    assert_eq!(field(d1, 8), "00000000");
    assert_eq!(field(d2, 0), "128");
    assert_eq!(field(d2, 3), count[3].to_string());
    assert_eq!(field(d2, 4), "0");

    // Parameter data: back-pointers to DE 1, column 65 blank, a `;` at the end.
    let mut data = String::new();
    for l in &lines[3 + count[1]..3 + count[1] + count[3]] {
        assert_eq!(&l[64..65], " ");
        assert_eq!(l[65..72].trim(), "1");
        data += l[..64].trim_end();
    }
    let data = data.strip_suffix(';').expect("record delimiter");
    data.split(',').map(str::to_owned).collect()
}

#[test]
fn writer_output_is_fixed_format_with_right_pointers_and_parameters() {
    let s = surface(
        4,
        3,
        |a, b| DVec3::new(a as f64, b as f64 * 1.5, (a * b) as f64 / 7.0),
        |a, b| 1.0 + (a + 2 * b) as f64 / 10.0,
    );
    let text = written(&s);
    let p = check_format(&text);
    assert_eq!(
        &p[..10],
        ["128", "3", "2", "2", "2", "0", "0", "0", "0", "0"]
    );
    let numbers: Vec<f64> = p[10..].iter().map(|x| x.parse().unwrap()).collect();
    assert_eq!(numbers.len(), 7 + 6 + 12 + 36 + 4);
    assert_eq!(numbers[..7], s.knots_u[..]);
    assert_eq!(numbers[7..13], s.knots_v[..]);
    // Weights and points with the first index (along u) fastest.
    let iges_order: Vec<usize> = (0..3)
        .flat_map(|b| (0..4).map(move |a| a * 3 + b))
        .collect();
    for (k, &idx) in iges_order.iter().enumerate() {
        assert_eq!(numbers[13 + k], s.weights[idx]);
        assert_eq!(
            numbers[25 + 3 * k..28 + 3 * k],
            s.control_points[idx].to_array()
        );
    }
    assert_eq!(numbers[61..], [0.0, 2.0, 0.0, 1.0]);
    // Reals carry a decimal point and an E exponent.
    assert!(
        p[10..].iter().all(|x| x.contains('.') && x.contains('E')),
        "{p:?}"
    );

    let global: String = text
        .lines()
        .skip(1)
        .take_while(|l| &l[72..73] == "G")
        .map(|l| l[..72].trim_end())
        .collect();
    assert!(
        global.starts_with("1H,,1H;,5Hmonge,9Hmonge.igs,"),
        "{global}"
    );
    assert!(
        global.contains(",1.0E0,6,1HM,1,0.0E0,15H19700101.000000,"),
        "{global}"
    );
    assert!(global.contains(",11,0,15H19700101.000000;"), "{global}");
    // Resolution 1e-9 of the largest coordinate (3), then that coordinate.
    let (_, after_date) = global.split_once("15H19700101.000000,").unwrap();
    let fields: Vec<&str> = after_date.split(',').take(4).collect();
    assert_eq!(fields[0].parse::<f64>().unwrap(), 1e-9 * 3.0);
    assert_eq!(fields[1..], ["3.0E0", "", ""]);
}

#[test]
fn writer_sets_polynomial_and_closed_flags() {
    // A tube: first and last rows of control points equal, all weights equal.
    let ring = |a: usize, b: usize| {
        let t = (a % 4) as f64;
        DVec3::new(t.cos(), t.sin(), b as f64)
    };
    let p = check_format(&written(&surface(5, 3, ring, |_, _| 2.0)));
    assert_eq!(&p[5..10], ["1", "0", "1", "0", "0"]);
    let p = check_format(&written(&surface(
        3,
        5,
        |a, b| ring(b, a),
        |a, _| 1.0 + a as f64,
    )));
    assert_eq!(&p[5..10], ["0", "1", "0", "0", "0"]);
}

#[test]
fn writer_refuses_invalid_surfaces() {
    let good = surface(3, 3, |a, b| DVec3::new(a as f64, b as f64, 0.0), |_, _| 1.0);
    type Edit = fn(&mut NurbsSurface);
    let cases: [(&str, Edit); 6] = [
        ("at least 3 control points", |s| s.rows = 2),
        ("need 9 points and weights", |s| {
            s.weights.pop();
        }),
        ("control point is not finite", |s| {
            s.control_points[4].z = f64::NAN
        }),
        ("positive finite", |s| s.weights[0] = 0.0),
        ("knots along v are not", |s| s.knots_v.swap(2, 3)),
        ("domain along u is empty", |s| s.knots_u = vec![0.0; 6]),
    ];
    for (needle, edit) in cases {
        let mut s = good.clone();
        edit(&mut s);
        let mut out = Vec::new();
        let err = write_iges(&s, &mut out).unwrap_err();
        assert_eq!(err.kind(), io::ErrorKind::InvalidInput);
        assert!(err.to_string().contains(needle), "{err} lacks {needle}");
        assert!(out.is_empty());
    }
    assert!(!written(&good).is_empty());
}

#[test]
fn writer_refuses_a_surface_whose_columns_do_not_fit_its_size() {
    // A surface given column by column: `columns` columns of `rows` points.
    struct Columns {
        rows: usize,
        columns: usize,
    }
    impl NurbsColumns for Columns {
        fn size(&self) -> (usize, usize) {
            (3, 3)
        }
        fn knots(&self) -> (Vec<f64>, Vec<f64>) {
            let k = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
            (k.clone(), k)
        }
        fn columns(&self, column: &mut NurbsColumn<'_>) -> io::Result<()> {
            for b in 0..self.columns {
                let points: Vec<DVec3> = (0..self.rows)
                    .map(|a| DVec3::new(a as f64, b as f64, 0.0))
                    .collect();
                column(&points, &vec![1.0; self.rows])?;
            }
            Ok(())
        }
    }
    for (surface, needle) in [
        (
            Columns {
                rows: 2,
                columns: 3,
            },
            "need 3 points and weights a column, got 2 and 2 in column 0",
        ),
        (
            Columns {
                rows: 3,
                columns: 2,
            },
            "need 3 columns, got 2",
        ),
    ] {
        let mut out = Vec::new();
        let err = write_iges(&surface, &mut out).unwrap_err();
        assert_eq!(err.kind(), io::ErrorKind::InvalidInput);
        assert!(err.to_string().contains(needle), "{err} lacks {needle}");
        assert!(out.is_empty());
    }
    // The same surface with its columns right is written as when held.
    let right = Columns {
        rows: 3,
        columns: 3,
    };
    let held = surface(3, 3, |a, b| DVec3::new(a as f64, b as f64, 0.0), |_, _| 1.0);
    let mut out = Vec::new();
    write_iges(&right, &mut out).unwrap();
    assert_eq!(String::from_utf8(out).unwrap(), written(&held));
}

// ---------------------------------------------------------------------------
// A cyclidic net, written and read back

#[test]
fn cyclidic_net_round_trips_through_iges() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let design = read_design(&root.join("examples/fig12-dupin-theta30.json")).unwrap();
    let grid = generate(&design, &GenerateOptions::default()).unwrap().grid;
    let nurbs = CyclidicNet::from_normals(&grid, &CyclidicOptions::default())
        .unwrap()
        .nurbs();
    let text = written(&nurbs);
    check_format(&text);
    let s = one(&text);

    // Every number survives exactly.
    assert_eq!((s.degree_u, s.degree_v), (2, 2));
    assert_eq!((s.count_u, s.count_v), (nurbs.rows, nurbs.cols));
    assert_eq!(s.knots_u, nurbs.knots_u);
    assert_eq!(s.knots_v, nurbs.knots_v);
    assert_eq!(s.weights, nurbs.weights);
    assert_eq!(s.control_points, nurbs.control_points);
    let (mu, mv) = ((grid.rows - 1) as f64, (grid.cols - 1) as f64);
    assert_eq!(s.range_u, [0.0, mu]);
    assert_eq!(s.range_v, [0.0, mv]);

    // The surface read back is monge-core's, bit for bit, at knots and between
    // (one evaluator), and passes through the mesh's vertices.
    for (u, v) in parameters(60) {
        let (u, v) = (u * mu, v * mv);
        assert_eq!(s.point(u, v), nurbs.point(u, v), "({u}, {v})");
    }
    for i in 0..grid.rows {
        for j in 0..grid.cols {
            let p = s.point(i as f64, j as f64);
            assert_eq!(p, nurbs.point(i as f64, j as f64));
            assert!((p - grid.vertex(i, j)).length() < 1e-9);
        }
    }
}

// ---------------------------------------------------------------------------
// IGES surfaces as targets of `monge approximate`

#[test]
fn a_targets_points_are_sampled_on_its_iges_surfaces() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("hypar.IGS");
    std::fs::write(&path, file(&[entity(128, BILINEAR)])).unwrap();
    let points = monge_io::read_points(&path).unwrap();
    // One surface: a 64 × 64 grid (64² ≥ IGES_TARGET_POINTS = 4000).
    assert_eq!(points.len(), 64 * 64);
    assert!(points.len() >= monge_io::IGES_TARGET_POINTS);
    // Every point on the surface z = xy/6 over [0, 2] × [0, 3], corners included.
    for p in &points {
        assert!((p.z - p.x * p.y / 6.0).abs() < 1e-14, "{p}");
        assert!(
            p.x > -1e-14 && p.x < 2.0 + 1e-14 && p.y > -1e-14 && p.y < 3.0 + 1e-14,
            "{p}"
        );
    }
    assert!(points[0].length() < 1e-14);
    assert!(points[points.len() - 1].distance(DVec3::new(2.0, 3.0, 1.0)) < 1e-14);
    // A file without surfaces says so, with the file's name.
    let empty = dir.path().join("empty.iges");
    std::fs::write(&empty, file(&[])).unwrap();
    let e = monge_io::read_points(&empty).unwrap_err().to_string();
    assert!(
        e.contains("empty.iges") && e.contains("no rational B-spline surface"),
        "{e}"
    );
}
