//! Design files: JSON and TOML, errors for architects, round trips.

use std::path::Path;

use monge_core::design::{ArcSpec, BSplineSpec, Design, GuideSpec, ParabolaSpec, Tolerances};
use monge_io::{
    parse_any_design, parse_design, read_any_design, read_design, read_mesh, read_multipatch,
    read_planes, write_design, DesignFormat, FileKind, IoError, MAX_DESIGN_BYTES,
};

const JSON: &str = r#"{ "theta_deg": 30.0, "guide_u": { "points": [[0,0,0],[1,0,0.2],[2,0,0.7]] }, "guide_v": { "bspline": { "degree": 3, "control_points": [[0,0,0],[0,1,0],[0,2,0.5],[0,3,1.5]], "samples": 41 } } }"#;

const TOML: &str = r#"theta_deg = 30.0

[guide_u]
points = [[0, 0, 0], [1, 0, 0.2], [2, 0, 0.7]]

[guide_v.bspline]
degree = 3
control_points = [[0, 0, 0], [0, 1, 0], [0, 2, 0.5], [0, 3, 1.5]]
samples = 41
"#;

fn expected() -> Design {
    Design {
        mesh: Default::default(),
        theta_deg: 30.0,
        guide_u: GuideSpec::points(vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.2], [2.0, 0.0, 0.7]]),
        guide_v: GuideSpec::BSpline {
            bspline: BSplineSpec {
                degree: 3,
                control_points: vec![
                    [0.0, 0.0, 0.0],
                    [0.0, 1.0, 0.0],
                    [0.0, 2.0, 0.5],
                    [0.0, 3.0, 1.5],
                ],
                knots: None,
                weights: None,
                samples: 41,
            },
            parameters: None,
        },
        tolerance: None,
    }
}

/// A design using every kind of guide and every optional field.
fn full() -> Design {
    Design {
        mesh: Default::default(),
        theta_deg: -12.5,
        guide_u: GuideSpec::Points {
            points: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.1]],
            tangent: Some([1.0, 0.0, 0.0]),
        },
        guide_v: GuideSpec::BSpline {
            bspline: BSplineSpec {
                degree: 2,
                control_points: vec![[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 2.0, 0.5]],
                knots: Some(vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0]),
                weights: Some(vec![1.0, 0.5, 1.0]),
                samples: 9,
            },
            parameters: None,
        },
        tolerance: Some(Tolerances {
            planarity: 1e-8,
            angle: 2e-9,
            start: 3e-10,
        }),
    }
}

fn others() -> [GuideSpec; 2] {
    [
        GuideSpec::Arc(ArcSpec {
            center: [0.0, 0.0, -1.0],
            start: [0.0, 0.0, 0.0],
            normal: [-1.0, 0.0, 0.0],
            angle_deg: 60.0,
            samples: 5,
        }),
        GuideSpec::Parabola(ParabolaSpec {
            start: [0.0, 0.0, 0.0],
            tangent: [1.0, 0.0, 0.0],
            quadratic: [0.0, 0.0, 0.3],
            samples: 7,
        }),
    ]
}

#[test]
fn json_and_toml_examples_parse() {
    assert_eq!(parse_design(JSON, DesignFormat::Json).unwrap(), expected());
    assert_eq!(parse_design(TOML, DesignFormat::Toml).unwrap(), expected());
}

#[test]
fn read_design_by_extension() {
    let dir = tempfile::tempdir().unwrap();
    for (name, text) in [("a.json", JSON), ("b.toml", TOML), ("C.JSON", JSON)] {
        let path = dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        assert_eq!(read_design(&path).unwrap(), expected(), "{name}");
    }
}

#[test]
fn write_design_round_trips_in_both_formats() {
    let dir = tempfile::tempdir().unwrap();
    let [arc, parabola] = others();
    let with_arc = Design {
        mesh: Default::default(),
        guide_u: arc,
        guide_v: parabola,
        ..full()
    };
    for design in [expected(), full(), with_arc] {
        for name in ["d.json", "d.toml"] {
            let path = dir.path().join(name);
            write_design(&design, &path).unwrap();
            assert_eq!(read_design(&path).unwrap(), design, "{name}");
        }
    }
    let text = std::fs::read_to_string(dir.path().join("d.json")).unwrap();
    assert!(text.contains("\n  \"theta_deg\""), "pretty JSON: {text}");
}

#[test]
fn unknown_field_in_json_names_file_line_column_and_expected_fields() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("typo.json");
    std::fs::write(&path, "{\n  \"thetadeg\": 30.0,\n  \"guide_u\": {}\n}\n").unwrap();
    let err = read_design(&path).unwrap_err();
    let IoError::Parse {
        file,
        line,
        column,
        message,
        snippet,
    } = &err
    else {
        panic!("{err:?}")
    };
    assert_eq!(file, &path.display().to_string());
    assert_eq!((*line, *column), (2, 12));
    assert!(
        message.starts_with("unknown field `thetadeg`, expected one of `theta_deg`"),
        "{message}"
    );
    assert!(snippet.contains("\"thetadeg\": 30.0"), "{snippet}");
    let shown = err.to_string();
    assert!(
        shown.starts_with(&format!("{}:2:12: unknown field", path.display())),
        "{shown}"
    );
}

#[test]
fn json_syntax_error_has_position() {
    let err = parse_design(
        "{\"theta_deg\": 30.0\n \"guide_u\": {}}",
        DesignFormat::Json,
    )
    .unwrap_err();
    let IoError::Parse {
        file,
        line,
        message,
        ..
    } = &err
    else {
        panic!("{err:?}")
    };
    assert_eq!(file, "<input>");
    assert_eq!(*line, 2);
    assert_eq!(message, "expected `,` or `}`");
}

#[test]
fn toml_unknown_field_shows_line_column_and_caret() {
    let text = "theta_deg = 30.0\n[guide_u]\npoint = [[0, 0, 0]]\n";
    let err = parse_design(text, DesignFormat::Toml).unwrap_err();
    let IoError::Parse {
        line,
        column,
        message,
        snippet,
        ..
    } = &err
    else {
        panic!("{err:?}")
    };
    assert_eq!((*line, *column), (3, 1));
    assert!(message.contains("unknown field `point`"), "{message}");
    assert!(message.contains("`points`"), "{message}");
    assert_eq!(snippet, "  | point = [[0, 0, 0]]\n  | ^");
}

#[test]
fn toml_missing_field_and_wrong_type() {
    let err = parse_design(
        "theta_deg = 30.0\n[guide_u]\npoints = []\n",
        DesignFormat::Toml,
    )
    .unwrap_err();
    assert!(err.to_string().contains("missing field `guide_v`"), "{err}");
    let err = parse_design("theta_deg = \"thirty\"\n", DesignFormat::Toml).unwrap_err();
    let IoError::Parse { line, message, .. } = &err else {
        panic!("{err:?}")
    };
    assert_eq!(*line, 1);
    assert_eq!(
        message,
        "theta_deg must be a number, got the string \"thirty\""
    );
}

#[test]
fn wrong_types_are_said_in_words_with_their_key() {
    let cases: [(&str, DesignFormat, &str); 4] = [
        (
            "theta_deg = \"20\"\n",
            DesignFormat::Toml,
            "theta_deg must be a number, got the string \"20\"",
        ),
        (
            r#"{"theta_deg": "20"}"#,
            DesignFormat::Json,
            "theta_deg must be a number, got the string \"20\"",
        ),
        (
            r#"{"theta_deg": 1, "guide_u": {"points": 3}}"#,
            DesignFormat::Json,
            "guide_u.points must be a list, got the whole number 3",
        ),
        (
            "theta_deg = 1\nguide_u.bspline = { degree = -1 }\n",
            DesignFormat::Toml,
            "guide_u.bspline.degree must be a whole number ≥ 0, got the whole number -1",
        ),
    ];
    for (text, format, expected) in cases {
        let err = parse_design(text, format).unwrap_err();
        let IoError::Parse { message, line, .. } = &err else {
            panic!("{err:?}")
        };
        assert_eq!(message, expected, "{text}");
        assert!(*line >= 1, "{text}: located");
    }
}

/// A guide that is not exactly one curve is refused as the file is read, named
/// by its key, in both formats.
#[test]
fn a_guide_that_is_not_one_curve_is_refused_with_its_name() {
    const KINDS: &str = "give exactly one of `points`, `bspline`, `arc` or `parabola`.";
    let points = "[[0, 0, 0], [1, 0, 0.2], [2, 0, 0.7]]";
    let arc = r#"{"center": [0, 0, -1], "start": [0, 0, 0], "normal": [0, 1, 0], "angle_deg": 30, "samples": 5}"#;
    let parabola =
        r#"{"start": [0, 0, 0], "tangent": [1, 0, 0], "quadratic": [0, 0, 1], "samples": 3}"#;
    let json = |u: String, v: String| {
        format!(r#"{{"theta_deg": 30, "guide_u": {{{u}}}, "guide_v": {{{v}}}}}"#)
    };
    let one = format!(r#""points": {points}"#);
    let cases = [
        (
            json(one.clone(), r#""tangent": [0, 1, 0]"#.to_owned()),
            format!("guide_v has no curve: {KINDS}"),
        ),
        (
            json(format!(r#""points": {points}, "arc": {arc}, "parabola": {parabola}"#), one.clone()),
            format!("guide_u has several curves (points, arc, parabola): {KINDS}"),
        ),
        (
            json(one.clone(), format!(r#""arc": {arc}, "tangent": [1, 0, 0]"#)),
            "guide_v: `tangent` is only allowed with `points`; this guide is a `arc`, whose start tangent is given by the curve itself. Remove `tangent`.".to_owned(),
        ),
        (
            json(format!(r#""parabola": {parabola}, "parameters": [0, 0.5, 1]"#), one.clone()),
            "guide_u: `parameters` (sample parameters, §4.8) is only allowed with `bspline`; this guide is a `parabola`. Remove `parameters`.".to_owned(),
        ),
    ];
    for (text, expected) in cases {
        let value: serde_json::Value = serde_json::from_str(&text).unwrap();
        let toml_text = toml::to_string(&value).unwrap();
        for (text, format) in [
            (text.clone(), DesignFormat::Json),
            (toml_text, DesignFormat::Toml),
        ] {
            let err = parse_design(&text, format).unwrap_err();
            let IoError::Parse { message, line, .. } = &err else {
                panic!("{err:?}")
            };
            assert_eq!(message, &expected, "{text}");
            assert!(*line >= 1, "{text}: located");
        }
    }
}

#[test]
fn a_file_of_another_kind_names_the_command_that_takes_it() {
    let dir = tempfile::tempdir().unwrap();
    let file = |name: &str, text: &str| {
        let path = dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        path
    };
    let patches = file("p.json", r#"{"patches": [{"theta_deg": 30}]}"#);
    let planes = file("q.toml", "[first_row]\npoint = [0, 0, 0]\n");
    let developable = file("d.json", r#"{"developable": {}}"#);
    let design = file("s.json", r#"{"theta_deg": 30, "guide_u": {}}"#);
    let mesh = file(
        "m.json",
        r#"{"rows": 1, "cols": 1, "vertices": [[0, 0, 0]]}"#,
    );
    let kind = |err: IoError| match err {
        IoError::WrongKind {
            found, expected, ..
        } => (found, expected),
        other => panic!("{other:?}"),
    };
    use FileKind::*;
    assert_eq!(
        kind(read_design(&patches).unwrap_err()),
        (MultiPatch, Design)
    );
    assert_eq!(
        kind(read_design(&developable).unwrap_err()),
        (Developable, Design)
    );
    assert_eq!(
        kind(read_any_design(&planes).unwrap_err()),
        (Planes, Design)
    );
    assert_eq!(kind(read_any_design(&mesh).unwrap_err()), (Mesh, Design));
    assert_eq!(
        kind(read_multipatch(&design).unwrap_err()),
        (Design, MultiPatch)
    );
    assert_eq!(kind(read_planes(&design).unwrap_err()), (Design, Planes));
    assert_eq!(kind(read_mesh(&design).unwrap_err()), (Design, Mesh));
    let message = read_any_design(&patches).unwrap_err().to_string();
    assert_eq!(
        message,
        format!(
            "{} is a multi-patch design (§4.7), not a design (two guides and θ): use `monge \
             patches` (or `monge fit` when it has a `fit` key)",
            patches.display()
        )
    );
    // A file of no known kind is left to the parser.
    let unknown = file("u.json", r#"{"thetadeg": 30}"#);
    assert!(matches!(read_design(&unknown), Err(IoError::Parse { .. })));
}

#[test]
fn toml_nan_and_inf_are_refused_with_key_path() {
    let err = parse_design(
        &TOML.replace("theta_deg = 30.0", "theta_deg = nan"),
        DesignFormat::Toml,
    )
    .unwrap_err();
    assert!(
        matches!(&err, IoError::NonFinite { key, .. } if key == "theta_deg"),
        "{err:?}"
    );
    assert_eq!(
        err.to_string(),
        "<input>: a number is not finite at `theta_deg`"
    );

    let text = TOML.replace("[2, 0, 0.7]", "[2, 0, -inf]");
    let err = parse_design(&text, DesignFormat::Toml).unwrap_err();
    assert!(
        matches!(&err, IoError::NonFinite { key, .. } if key == "guide_u.points[2][2]"),
        "{err:?}"
    );

    let text = TOML.replace("samples = 41", "samples = 41\nweights = [1, 1, +inf, 1]");
    let err = parse_design(&text, DesignFormat::Toml).unwrap_err();
    assert!(
        matches!(&err, IoError::NonFinite { key, .. } if key == "guide_v.bspline.weights[2]"),
        "{err:?}"
    );

    let text = format!("{TOML}\n[tolerance]\nangle = nan\n");
    let err = parse_design(&text, DesignFormat::Toml).unwrap_err();
    assert!(
        matches!(&err, IoError::NonFinite { key, .. } if key == "tolerance.angle"),
        "{err:?}"
    );
}

#[test]
fn writing_a_non_finite_design_is_refused_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("nan.json");
    let mut design = full();
    let GuideSpec::BSpline { bspline, .. } = &mut design.guide_v else {
        panic!("a B-spline guide_v");
    };
    bspline.control_points[1][0] = f64::NAN;
    let err = write_design(&design, &path).unwrap_err();
    assert!(
        matches!(&err, IoError::NonFinite { key, .. } if key == "guide_v.bspline.control_points[1][0]"),
        "{err:?}"
    );
    assert!(!path.exists());
}

#[test]
fn missing_file_is_said_plainly() {
    let err = read_design(Path::new("/nonexistent/dir/design.toml")).unwrap_err();
    assert!(matches!(err, IoError::NotFound { .. }), "{err:?}");
    assert_eq!(
        err.to_string(),
        "file not found: `/nonexistent/dir/design.toml`"
    );
}

#[test]
fn unreadable_file_is_a_read_error() {
    // A directory named like a design file cannot be read as one.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("dir.json");
    std::fs::create_dir(&path).unwrap();
    let err = read_design(&path).unwrap_err();
    assert!(matches!(err, IoError::Read { .. }), "{err:?}");
    assert!(
        err.to_string()
            .starts_with(&format!("cannot read `{}`", path.display())),
        "{err}"
    );
}

#[test]
fn wrong_extension_names_it_and_the_accepted_ones() {
    let err = read_design(Path::new("design.yaml")).unwrap_err();
    assert!(matches!(err, IoError::UnknownExtension { .. }), "{err:?}");
    assert_eq!(
        err.to_string(),
        "`design.yaml`: unsupported extension `.yaml`; expected `.json` or `.toml`"
    );
    let err = read_design(Path::new("design")).unwrap_err();
    assert_eq!(
        err.to_string(),
        "`design`: unsupported file name without extension; expected `.json` or `.toml`"
    );
    assert!(write_design(&expected(), Path::new("out.txt")).is_err());
}

/// A design file may have at most `MAX_DESIGN_BYTES` (16 MiB), of whatever
/// kind: one byte more is refused by its length, before it is read or parsed;
/// a text of that length given to a parser likewise.
#[test]
fn design_files_over_the_size_limit_are_refused_before_parsing() {
    let limit = MAX_DESIGN_BYTES as usize;
    assert_eq!(limit, 16 * 1024 * 1024);
    let design = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/fig12-torus.json"),
    )
    .unwrap();
    // The design padded with blanks to exactly the limit is read.
    let padded = |len: usize| format!("{design}{}", " ".repeat(len - design.len()));
    let dir = tempfile::tempdir().unwrap();
    let at_limit = dir.path().join("at-limit.json");
    std::fs::write(&at_limit, padded(limit)).unwrap();
    assert!(read_design(&at_limit).is_ok());
    let over = padded(limit + 1);
    for name in ["d.json", "d.patches.json", "d.planes.json"] {
        let path = dir.path().join(name);
        std::fs::write(&path, &over).unwrap();
        let errors = [
            read_design(&path).unwrap_err(),
            read_any_design(&path).unwrap_err(),
            read_multipatch(&path).unwrap_err(),
            read_planes(&path).unwrap_err(),
        ];
        for e in errors {
            assert!(
                matches!(e, IoError::DesignTooLarge { size, limit: l, .. }
                    if size == limit as u64 + 1 && l == MAX_DESIGN_BYTES),
                "{e:?}"
            );
            assert_eq!(
                e.to_string(),
                format!(
                    "{} has 16777217 bytes, more than a design file may have: 16777216 bytes \
                     (16 MiB). A design is a few kB (two guides and θ): give a long guide as a \
                     B-spline of a few control points rather than as its points, or check that \
                     this is the design file meant",
                    path.display()
                )
            );
        }
    }
    for format in [DesignFormat::Json, DesignFormat::Toml] {
        let e = parse_design(&over, format).unwrap_err();
        assert!(matches!(e, IoError::DesignTooLarge { .. }), "{e:?}");
        let e = parse_any_design(&over, format).unwrap_err();
        assert!(matches!(e, IoError::DesignTooLarge { .. }), "{e:?}");
    }
}
