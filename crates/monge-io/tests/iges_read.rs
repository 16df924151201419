//! IGES entity 128: the reader on hand-written files, and the errors that
//! name the line at fault.

use crate::common;

use std::f64::consts::FRAC_1_SQRT_2;

use fastrand::Rng;
use glam::DVec3;
use monge_core::bspline::surface_point;
use monge_io::{read_iges_surfaces, IgesSurface, IoError};

use common::iges::{entity, file, file_with_global, line, one, parameters, Entity, BILINEAR};

// ---------------------------------------------------------------------------
// Hand-written files

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

// ---------------------------------------------------------------------------
// Evaluation: monge-core's B-spline evaluator

/// A surface from its degrees, knots and seed-drawn weights and control points.
fn surface(degrees: [usize; 2], knots: [Vec<f64>; 2], rng: &mut Rng) -> IgesSurface {
    let count = |d: usize| knots[d].len() - degrees[d] - 1;
    let (count_u, count_v) = (count(0), count(1));
    let n = count_u * count_v;
    let range = |d: usize| [knots[d][degrees[d]], knots[d][count(d)]];
    let (range_u, range_v) = (range(0), range(1));
    let [knots_u, knots_v] = knots;
    IgesSurface {
        degree_u: degrees[0],
        degree_v: degrees[1],
        count_u,
        count_v,
        knots_u,
        knots_v,
        weights: (0..n).map(|_| 0.2 + 3.0 * rng.f64()).collect(),
        control_points: (0..n)
            .map(|_| DVec3::new(rng.f64(), rng.f64(), rng.f64()) * 20.0 - 10.0)
            .collect(),
        range_u,
        range_v,
    }
}

#[test]
fn surfaces_are_evaluated_by_monge_core_bit_for_bit() {
    // Random degrees, knots (distinct or repeated, clamped or not), weights and
    // parameters (at knots, between, outside the domain): the reader's point is
    // monge-core's at the parameter clamped to the domain, to the last bit.
    let mut rng = Rng::with_seed(7);
    let mut evaluations = 0;
    while evaluations < 20_000 {
        let draw_knots = |rng: &mut Rng| {
            let degree = 1 + rng.usize(..5);
            let count = degree + 1 + rng.usize(..5);
            let coarse = rng.usize(..2) == 0;
            let mut knots: Vec<f64> = (0..count + degree + 1)
                .map(|_| {
                    if coarse {
                        rng.usize(..5) as f64
                    } else {
                        rng.f64() * 10.0 - 3.0
                    }
                })
                .collect();
            knots.sort_by(f64::total_cmp);
            if rng.usize(..2) == 0 {
                let (start, end, last) = (knots[degree], knots[count], knots.len() - 1);
                knots[..degree].fill(start);
                knots[last - degree..].fill(end);
            }
            (degree, knots)
        };
        let ((du, ku), (dv, kv)) = (draw_knots(&mut rng), draw_knots(&mut rng));
        if ku[du] >= ku[ku.len() - du - 1] || kv[dv] >= kv[kv.len() - dv - 1] {
            continue; // an empty domain, which the reader refuses
        }
        let s = surface([du, dv], [ku, kv], &mut rng);
        let param = |rng: &mut Rng, knots: &[f64], range: [f64; 2]| match rng.usize(..4) {
            0 => knots[rng.usize(..knots.len())],
            1 => range[0] + (range[1] - range[0]) * (3.0 * rng.f64() - 1.0),
            _ => range[0] + (range[1] - range[0]) * rng.f64(),
        };
        for _ in 0..10 {
            let u = param(&mut rng, &s.knots_u, s.range_u);
            let v = param(&mut rng, &s.knots_v, s.range_v);
            let p = s.point(u, v);
            let expected = surface_point(
                [s.degree_u, s.degree_v],
                [&s.knots_u, &s.knots_v],
                &s.control_points,
                &s.weights,
                u.clamp(s.range_u[0], s.range_u[1]),
                v.clamp(s.range_v[0], s.range_v[1]),
            );
            let at = format!(
                "degrees ({}, {}), knots {:?} and {:?}, at ({u}, {v})",
                s.degree_u, s.degree_v, s.knots_u, s.knots_v
            );
            assert!(p.is_finite(), "{at}: {p}");
            assert_eq!(
                p.to_array().map(f64::to_bits),
                expected.to_array().map(f64::to_bits),
                "{at}"
            );
            evaluations += 1;
        }
    }
}

#[test]
fn the_end_of_a_domain_closed_by_a_double_knot_is_its_control_point() {
    // Degree 1 along u on unclamped knots [0, 0, 1, 1, 2]: the domain [0, 1]
    // ends at a double knot, where the surface passes through control row 1.
    let mut rng = Rng::with_seed(11);
    let s = surface(
        [1, 1],
        [vec![0.0, 0.0, 1.0, 1.0, 2.0], vec![0.0, 0.0, 1.0, 1.0]],
        &mut rng,
    );
    assert_eq!(s.range_u, [0.0, 1.0]);
    // One term, `w P / w`: the control point to round-off.
    for (u, v, k) in [(1.0, 0.0, 2), (1.0, 1.0, 3), (5.0, 1.0, 3), (0.0, 0.0, 0)] {
        let gap = (s.point(u, v) - s.control_points[k]).length();
        assert!(gap < 1e-14, "({u}, {v}): {gap:e} from control point {k}");
    }
}
