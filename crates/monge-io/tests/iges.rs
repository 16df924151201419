//! IGES entity 128: the reader on hand-written files, the writer's fixed
//! format checked column by column, and a cyclidic net written and read back.

use std::f64::consts::FRAC_1_SQRT_2;
use std::io;
use std::path::Path;

use glam::DVec3;
use monge_core::cyclidic::{CyclidicNet, CyclidicOptions, NurbsSurface};
use monge_core::{generate, GenerateOptions};
use monge_io::{
    read_design, read_iges_surfaces, write_iges, IgesSurface, IoError, NurbsColumn, NurbsColumns,
};

// ---------------------------------------------------------------------------
// Hand-written files

/// One 80-column line.
fn line(data: &str, section: char, sequence: usize) -> String {
    assert!(data.len() <= 72, "test data too long: {data}");
    format!("{data:<72}{section}{sequence:>7}\n")
}

/// An entity for [`file`]: type, transformation matrix pointer, parameter lines.
struct Entity<'a> {
    kind: i64,
    transform: usize,
    lines: &'a [&'a str],
}

fn entity<'a>(kind: i64, lines: &'a [&'a str]) -> Entity<'a> {
    Entity {
        kind,
        transform: 0,
        lines,
    }
}

/// A complete file: one Start line, `global` as the Global section (one line),
/// the entities' Directory Entries (DE 1, 3, 5, …) and Parameter Data, Terminate.
fn file_with_global(global: &str, entities: &[Entity]) -> String {
    let mut d = String::new();
    let mut p = String::new();
    let mut p_seq = 1;
    for (k, e) in entities.iter().enumerate() {
        let de = 2 * k + 1;
        let first = format!(
            "{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}",
            e.kind, p_seq, 0, 0, 0, 0, e.transform, 0, "00000000"
        );
        let second = format!("{:>8}{:>8}{:>8}{:>8}{:>8}", e.kind, 0, 0, e.lines.len(), 0);
        d += &line(&first, 'D', de);
        d += &line(&second, 'D', de + 1);
        for l in e.lines {
            p += &line(&format!("{l:<64} {de:>7}"), 'P', p_seq);
            p_seq += 1;
        }
    }
    let counts = format!(
        "S{:>7}G{:>7}D{:>7}P{:>7}",
        1,
        1,
        2 * entities.len(),
        p_seq - 1
    );
    line("hand-written test file", 'S', 1)
        + &line(global, 'G', 1)
        + &d
        + &p
        + &line(&counts, 'T', 1)
}

const GLOBAL: &str = "1H,,1H;,4Htest,8Htest.igs,,,32,38,6,308,15,,1.0,6,1HM,,,,1.0E-9;";

fn file(entities: &[Entity]) -> String {
    file_with_global(GLOBAL, entities)
}

/// The hyperbolic paraboloid `(u, 3v, uv/2)`, `u ∈ [0, 2]`, `v ∈ [0, 1]`, as a
/// degree-(1, 1) NURBS: corners (0,0,0), (2,0,0), (0,3,0), (2,3,1) in IGES order,
/// wrapped over several lines, `D` and `E` exponents, blanks around numbers.
const BILINEAR: &[&str] = &[
    "128,1,1,1,1,0,0,1,0,0,",
    "0.0, 0.0 ,2.0D0,2.,0,0,1.0E0,1,",
    "1.D0,1.0,1.0,1.0,",
    "0.,0.,0.,2.0D+00,0.0,0.0,0.0,3.0,0.0,",
    "2.0,3.0,1.0,0.0,2.0,0.0,1.0;",
];

fn bilinear_exact(u: f64, v: f64) -> DVec3 {
    DVec3::new(u, 3.0 * v, u * v / 2.0)
}

/// A quarter of the unit cylinder about `z`, `z ∈ [0, 2]`: degree 2 around, 1 along.
const CYLINDER: &[&str] = &[
    "128,2,1,2,1,0,0,0,0,0,",
    "0.0,0.0,0.0,1.0,1.0,1.0,",
    "0.0,0.0,1.0,1.0,",
    "1.0,7.071067811865476D-1,1.0,1.0,7.0710678118654757E-01,1.0,",
    "1.0,0.0,0.0, 1.0,1.0,0.0, 0.0,1.0,0.0,",
    "1.0,0.0,2.0, 1.0,1.0,2.0, 0.0,1.0,2.0,",
    "0.0,1.0,0.0,1.0;",
];

fn parameters(n: usize) -> impl Iterator<Item = (f64, f64)> {
    (0..=n).flat_map(move |a| (0..=n).map(move |b| (a as f64 / n as f64, b as f64 / n as f64)))
}

fn one(text: &str) -> IgesSurface {
    let mut surfaces = read_iges_surfaces(text).unwrap();
    assert_eq!(surfaces.len(), 1);
    surfaces.pop().unwrap()
}

#[test]
fn reader_evaluates_a_bilinear_patch() {
    let s = one(&file(&[entity(128, BILINEAR)]));
    assert_eq!((s.degree_u, s.degree_v, s.count_u, s.count_v), (1, 1, 2, 2));
    assert_eq!(s.knots_u, [0.0, 0.0, 2.0, 2.0]);
    assert_eq!(s.knots_v, [0.0, 0.0, 1.0, 1.0]);
    assert_eq!(s.range_u, [0.0, 2.0]);
    assert_eq!(s.range_v, [0.0, 1.0]);
    // Row-major: (a, b) at a * count_v + b, a along u.
    assert_eq!(s.control_points[1], DVec3::new(0.0, 3.0, 0.0));
    assert_eq!(s.control_points[2], DVec3::new(2.0, 0.0, 0.0));
    for (u, v) in parameters(10) {
        let (u, v) = (2.0 * u, v);
        assert!(
            (s.point(u, v) - bilinear_exact(u, v)).length() < 1e-15,
            "({u}, {v})"
        );
    }
    // Outside the domain: clamped.
    assert_eq!(s.point(-1.0, 2.0), bilinear_exact(0.0, 1.0));
    assert!(s.point(f64::NAN, 0.5).is_nan());
}

#[test]
fn reader_evaluates_a_quarter_cylinder_exactly() {
    let s = one(&file(&[entity(128, CYLINDER)]));
    assert_eq!((s.degree_u, s.degree_v, s.count_u, s.count_v), (2, 1, 3, 2));
    assert_eq!(s.weights[2], FRAC_1_SQRT_2); // (1, 0): both spellings parse to the same f64
    assert_eq!(s.weights[3], FRAC_1_SQRT_2);
    let mut last_angle = -1.0;
    for (u, v) in parameters(40) {
        let p = s.point(u, v);
        assert!((p.x.hypot(p.y) - 1.0).abs() < 1e-14, "({u}, {v}): {p}");
        assert!((p.z - 2.0 * v).abs() < 1e-15);
        assert!(p.x >= -1e-15 && p.y >= -1e-15);
        if v == 0.0 {
            let angle = p.y.atan2(p.x);
            assert!(angle > last_angle);
            last_angle = angle;
        }
    }
    let mid = s.point(0.5, 0.0);
    assert!((mid - DVec3::new(FRAC_1_SQRT_2, FRAC_1_SQRT_2, 0.0)).length() < 1e-15);
    assert!((s.point(1.0, 1.0) - DVec3::new(0.0, 1.0, 2.0)).length() < 1e-15);
}

#[test]
fn reader_skips_other_entities_and_applies_transformation_chains() {
    // DE 1: a line (110); DE 3: the cylinder under DE 5; DE 5: a quarter turn about z
    // under DE 7; DE 7: a translation by (10, 20, 30).
    let line110: &[&str] = &["110,0.0,0.0,0.0,1.0,1.0,1.0;"];
    let turn: &[&str] = &["124,0.0,-1.0,0.0,0.0,", "1.0,0.0,0.0,0.0,0.0,0.0,1.0,0.0;"];
    let shift: &[&str] = &["124,1.0,0.0,0.0,10.0,0.0,1.0,0.0,20.0,0.0,0.0,1.0,30.0;"];
    let text = file(&[
        entity(110, line110),
        Entity {
            transform: 5,
            ..entity(128, CYLINDER)
        },
        Entity {
            transform: 7,
            ..entity(124, turn)
        },
        entity(124, shift),
    ]);
    let moved = one(&text);
    let plain = one(&file(&[entity(128, CYLINDER)]));
    let map = |p: DVec3| DVec3::new(-p.y, p.x, p.z) + DVec3::new(10.0, 20.0, 30.0);
    for (u, v) in parameters(12) {
        assert!((moved.point(u, v) - map(plain.point(u, v))).length() < 1e-13);
    }
}

#[test]
fn reader_takes_the_delimiters_from_the_global_section() {
    let global = "1H//1H$/4Htest/8Htest.igs//////////////1.0E-9$";
    let lines: Vec<String> = BILINEAR
        .iter()
        .map(|l| l.replace(',', "/").replace(';', "$"))
        .collect();
    let lines: Vec<&str> = lines.iter().map(String::as_str).collect();
    let s = one(&file_with_global(global, &[entity(128, &lines)]));
    assert_eq!(s.point(1.0, 0.5), bilinear_exact(1.0, 0.5));
    // Defaulted delimiters (the Global section starts with two commas).
    let s = one(&file_with_global(",,4Htest;", &[entity(128, BILINEAR)]));
    assert_eq!(s.point(1.0, 0.5), bilinear_exact(1.0, 0.5));
}

#[test]
fn reader_accepts_crlf_and_files_without_entities() {
    let text = file(&[entity(128, BILINEAR)]).replace('\n', "\r\n");
    assert_eq!(one(&text).count_u, 2);
    assert!(read_iges_surfaces(&file(&[])).unwrap().is_empty());
}

// ---------------------------------------------------------------------------
// Reader errors

#[track_caller]
fn syntax_error(text: &str, line: usize, needle: &str) {
    match read_iges_surfaces(text) {
        Err(IoError::Syntax {
            file,
            line: l,
            message,
        }) => {
            assert_eq!(file, "<input>");
            assert_eq!(l, line, "{message}");
            assert!(message.contains(needle), "`{message}` lacks `{needle}`");
        }
        other => panic!("expected a syntax error, got {other:?}"),
    }
}

/// The bilinear file with line `n` (1-based) replaced by `f` of it.
fn edit_line(n: usize, f: impl Fn(&str) -> String) -> String {
    let text = file(&[entity(128, BILINEAR)]);
    text.lines()
        .enumerate()
        .map(|(k, l)| if k + 1 == n { f(l) } else { l.to_owned() } + "\n")
        .collect()
}

/// The bilinear file with its parameter lines replaced.
fn bilinear_with(lines: &[&str]) -> String {
    file(&[entity(128, lines)])
}

// Lines of the bilinear file: 1 S, 2 G, 3–4 D, 5–9 P, 10 T.

#[test]
fn error_line_length() {
    syntax_error(&edit_line(5, |l| format!("{l} ")), 5, "81 columns");
    syntax_error(&edit_line(5, |l| l[..60].to_owned()), 5, "60 columns");
    syntax_error("\n", 1, "0 columns");
}

#[test]
fn error_not_ascii() {
    syntax_error(&edit_line(1, |l| l.replacen("hand", "händ", 1)), 1, "ASCII");
}

#[test]
fn error_unknown_section_letter() {
    syntax_error(
        &edit_line(1, |l| format!("{}C{}", &l[..72], &l[73..])),
        1,
        "compressed",
    );
}

#[test]
fn error_sections_out_of_order() {
    let text = file(&[entity(128, BILINEAR)]);
    let mut lines: Vec<&str> = text.lines().collect();
    lines.swap(1, 2);
    syntax_error(&(lines.join("\n") + "\n"), 3, "order is S, G, D, P, T");
}

#[test]
fn error_sequence_number() {
    syntax_error(
        &edit_line(6, |l| format!("{}      9", &l[..73])),
        6,
        "expected 2",
    );
}

#[test]
fn error_missing_or_wrong_terminate() {
    let text = file(&[entity(128, BILINEAR)]);
    let truncated: String = text.lines().take(8).map(|l| format!("{l}\n")).collect();
    syntax_error(&truncated, 8, "no Terminate line");
    syntax_error("", 1, "no Terminate line");
    syntax_error(
        &edit_line(10, |l| l.replacen("P      5", "P      4", 1)),
        10,
        "count of `P` lines",
    );
    syntax_error(
        &(text.clone() + &line("", 'T', 2)),
        11,
        "after the Terminate line",
    );
}

#[test]
fn error_odd_directory() {
    let text = file(&[entity(128, BILINEAR)]);
    let lines: Vec<&str> = text.lines().collect();
    let mut odd = lines[..3].join("\n") + "\n";
    odd += &line("S      1G      1D      1P      0", 'T', 1);
    syntax_error(&odd, 3, "odd number of Directory Entry lines");
}

#[test]
fn error_directory_fields() {
    syntax_error(
        &edit_line(3, |l| l.replacen("       1", "      x1", 1)),
        3,
        "not an integer",
    );
    syntax_error(
        &edit_line(4, |l| l.replacen("     128", "     126", 1)),
        4,
        "entity type 126",
    );
}

#[test]
fn error_parameter_pointer_out_of_range() {
    syntax_error(
        &edit_line(4, |l| l.replacen("       5", "       6", 1)),
        3,
        "outside the 5",
    );
    syntax_error(
        &edit_line(3, |l| l.replacen("       1", "       0", 1)),
        3,
        "pointer 0",
    );
    // Both zero: the last line would be line −1 (found by the fuzzer).
    syntax_error(
        &edit_line(4, |l| l.replacen("       5", "       0", 1)).replacen(
            "     128       1",
            "     128       0",
            1,
        ),
        3,
        "pointer 0 with 0 lines",
    );
}

#[test]
fn error_back_pointer() {
    syntax_error(
        &edit_line(7, |l| format!("{}      3P      3", &l[..65])),
        7,
        "expected the entity's DE 1",
    );
}

#[test]
fn error_no_record_delimiter() {
    let mut lines = BILINEAR.to_vec();
    lines[4] = "2.0,3.0,1.0,0.0,2.0,0.0,1.0,";
    syntax_error(&bilinear_with(&lines), 9, "does not end with `;`");
}

#[test]
fn error_entity_type_in_parameter_data() {
    let mut lines = BILINEAR.to_vec();
    lines[0] = "126,1,1,1,1,0,0,1,0,0,";
    syntax_error(&bilinear_with(&lines), 5, "expected its entity type 128");
}

#[test]
fn error_bad_numbers() {
    let mut lines = BILINEAR.to_vec();
    lines[3] = "0.,0.,0.,2.0Q+00,0.0,0.0,0.0,3.0,0.0,";
    syntax_error(&bilinear_with(&lines), 8, "`2.0Q+00`, not a finite real");
    lines[3] = "0.,0.,0.,1D999,0.0,0.0,0.0,3.0,0.0,";
    syntax_error(&bilinear_with(&lines), 8, "`1D999`, not a finite real");
    lines[3] = "0.,0.,0.,,0.0,0.0,0.0,3.0,0.0,";
    syntax_error(&bilinear_with(&lines), 8, "``, not a finite real");
    let mut lines = BILINEAR.to_vec();
    lines[0] = "128,1,1,1.5,1,0,0,1,0,0,";
    syntax_error(
        &bilinear_with(&lines),
        5,
        "M1 of the entity at DE 1 is `1.5`",
    );
}

#[test]
fn error_degrees() {
    let mut lines = BILINEAR.to_vec();
    lines[0] = "128,1,1,0,1,0,0,1,0,0,";
    syntax_error(
        &bilinear_with(&lines),
        5,
        "degree 0 with 2 control points in the first",
    );
    lines[0] = "128,1,1,1,2,0,0,1,0,0,";
    syntax_error(
        &bilinear_with(&lines),
        5,
        "degree 2 with 2 control points in the second",
    );
    // A degree above monge_core's MAX_DEGREE is refused before anything is
    // evaluated (a point costs about degree² operations).
    lines[0] = "128,40,1,33,1,0,0,1,0,0,";
    syntax_error(
        &bilinear_with(&lines),
        5,
        "degree 33 in the first direction, above the largest read, 32",
    );
}

#[test]
fn error_knots() {
    let mut lines = BILINEAR.to_vec();
    lines[1] = "0.0, 0.0 ,2.0D0,1.,0,0,1.0E0,1,";
    syntax_error(&bilinear_with(&lines), 6, "S knot 1 is below");
    lines[1] = "0.0, 0.0 ,0.0D0,2.,0,0,1.0E0,1,";
    syntax_error(
        &bilinear_with(&lines),
        5,
        "S knots leave an empty domain [0, 0]",
    );
}

#[test]
fn error_weights() {
    let mut lines = BILINEAR.to_vec();
    lines[2] = "1.D0,1.0,-1.0,1.0,";
    syntax_error(&bilinear_with(&lines), 7, "weight -1 is not positive");
}

#[test]
fn error_too_few_parameters() {
    let mut lines = BILINEAR.to_vec();
    lines[4] = "2.0,3.0,1.0,0.0,2.0,0.0;";
    match read_iges_surfaces(&bilinear_with(&lines)) {
        Err(IoError::CountMismatch {
            file,
            what,
            expected,
            found,
        }) => {
            assert_eq!(file, "<input>");
            assert!(what.contains("entity 128 at DE 1 (line 5)"), "{what}");
            assert_eq!((expected, found), (37, 36));
        }
        other => panic!("expected a count mismatch, got {other:?}"),
    }
    // So short that even the header is incomplete.
    match read_iges_surfaces(&bilinear_with(&["128,1,1;"])) {
        Err(IoError::CountMismatch { what, found, .. }) => {
            assert!(what.contains("up to its M1"), "{what}");
            assert_eq!(found, 2);
        }
        other => panic!("expected a count mismatch, got {other:?}"),
    }
}

#[test]
fn error_transformation_pointers() {
    let line110: &[&str] = &["110,0.0,0.0,0.0,1.0,1.0,1.0;"];
    let to_line = file(&[
        Entity {
            transform: 3,
            ..entity(128, BILINEAR)
        },
        entity(110, line110),
    ]);
    syntax_error(&to_line, 3, "names an entity 110, not 124");
    let even = file(&[Entity {
        transform: 2,
        ..entity(128, BILINEAR)
    }]);
    syntax_error(&even, 3, "pointer 2 is not a Directory Entry");
    let identity: &[&str] = &["124,1.0,0.0,0.0,0.0,0.0,1.0,0.0,0.0,0.0,0.0,1.0,0.0;"];
    let cycle = file(&[
        Entity {
            transform: 3,
            ..entity(128, BILINEAR)
        },
        Entity {
            transform: 3,
            ..entity(124, identity)
        },
    ]);
    syntax_error(&cycle, 5, "chained transformation matrices");
}

// ---------------------------------------------------------------------------
// Writer

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

    // The independent evaluator agrees with monge-core's, at knots and between.
    let mut worst: f64 = 0.0;
    for (u, v) in parameters(60) {
        let (u, v) = (u * mu, v * mv);
        worst = worst.max((s.point(u, v) - nurbs.point(u, v)).length());
    }
    for i in 0..grid.rows {
        for j in 0..grid.cols {
            let p = s.point(i as f64, j as f64);
            worst = worst.max((p - nurbs.point(i as f64, j as f64)).length());
            assert!((p - grid.vertex(i, j)).length() < 1e-9);
        }
    }
    assert!(worst <= 1e-12, "largest difference {worst:e}");
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
