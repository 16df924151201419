//! Trimmed design files: a design or a multi-patch design and the outline its mesh is
//! cut by, written and read back to the bit, their kind told, their errors.

use glam::DVec3;
use monge_core::approximate::{Outline, TargetCloud};
use monge_core::multipatch::build;
use monge_core::{generate, GenerateOptions, QuadGrid};
use monge_io::{
    parse_design, parse_multipatch, read_any_design, read_design, write_trimmed, AnyDesign,
    DesignFormat, IoError, Trimmable, TrimmedDesign,
};

/// The outline of 400 points over a flat disc round the centre of `grid`'s plan, of a
/// quarter of its extent.
fn disc_outline(grid: &QuadGrid) -> Outline {
    let (lo, hi) = grid
        .vertices
        .iter()
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(*v), hi.max(*v))
        });
    let (centre, radius) = ((lo + hi) / 2.0, 0.25 * (hi - lo).truncate().min_element());
    let disc: Vec<DVec3> = (0..400)
        .map(|k| {
            let (r, a) = (
                radius * ((k as f64 + 0.5) / 400.0).sqrt(),
                k as f64 * 2.399963,
            );
            centre + DVec3::new(r * a.cos(), r * a.sin(), 0.0)
        })
        .collect();
    Outline::of(&TargetCloud::new(&disc).unwrap()).unwrap()
}

/// Two arcs at right angles, θ 30°.
fn surface() -> Trimmable {
    let design = parse_design(
        r#"{"theta_deg": 30,
            "guide_u": {"arc": {"center": [0,0,-4], "start": [0,0,0], "normal": [0,-1,0], "angle_deg": 40, "samples": 9}},
            "guide_v": {"arc": {"center": [0,0,-3], "start": [0,0,0], "normal": [1,0,0], "angle_deg": 50, "samples": 9}}}"#,
        DesignFormat::Json,
    )
    .unwrap();
    Trimmable::Surface(Box::new(design))
}

/// Two patches: the first [`surface`]'s, the second attached along its last row.
fn patches() -> Trimmable {
    let (s, c) = (40f64.to_radians().sin(), 40f64.to_radians().cos());
    let design = parse_multipatch(
        &format!(
            r#"{{"patches": [
              {{"theta_deg": 30,
                "guide_u": {{"arc": {{"center": [0,0,-4], "start": [0,0,0], "normal": [0,-1,0], "angle_deg": 40, "samples": 9}}}},
                "guide_v": {{"arc": {{"center": [0,0,-3], "start": [0,0,0], "normal": [1,0,0], "angle_deg": 50, "samples": 9}}}}}},
              {{"theta_deg": 40, "attach": {{"patch": 0, "side": "last_row"}},
                "guide": {{"arc": {{"center": [0,0,-4], "start": [{}, 0, {}], "normal": [0,-1,0], "angle_deg": 30, "samples": 7}}}}}}]}}"#,
            -4.0 * s,
            4.0 * c - 4.0
        ),
        DesignFormat::Json,
    )
    .unwrap();
    Trimmable::Patches(design)
}

/// `design` trimmed to a disc in its middle.
fn trimmed(design: Trimmable) -> TrimmedDesign {
    let options = GenerateOptions::default();
    let grid = match &design {
        Trimmable::Surface(d) => generate(d, &options).unwrap().grid,
        Trimmable::Patches(d) => build(d, &options).unwrap().grid,
    };
    TrimmedDesign {
        trim: disc_outline(&grid),
        design,
    }
}

#[test]
fn trimmed_designs_read_back_to_the_bit_in_both_formats() {
    let dir = tempfile::tempdir().unwrap();
    for (k, design) in [surface(), patches()].into_iter().enumerate() {
        for ext in ["json", "toml"] {
            let trimmed = trimmed(design.clone());
            let path = dir.path().join(format!("t{k}.{ext}"));
            write_trimmed(&trimmed, &path).unwrap();
            let text = std::fs::read_to_string(&path).unwrap();
            assert!(text.contains("polygon"), "{text}");
            assert_eq!(
                read_any_design(&path).unwrap(),
                AnyDesign::Trimmed(Box::new(trimmed)),
                "{ext}"
            );
        }
    }
}

#[test]
fn a_trimmed_design_given_where_a_design_is_read_says_which_command_reads_it() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.json");
    write_trimmed(&trimmed(surface()), &path).unwrap();
    let e = read_design(&path).unwrap_err();
    assert!(matches!(e, IoError::WrongKind { .. }), "{e}");
    let text = e.to_string();
    assert!(
        text.contains("is a trimmed design") && text.contains("`monge generate`"),
        "{text}"
    );
}

#[test]
fn a_trimmed_design_whose_outline_is_not_one_says_why_and_where() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.json");
    write_trimmed(&trimmed(surface()), &path).unwrap();
    // The outline's corners reversed: clockwise.
    let mut value: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    value["trim"]["polygon"].as_array_mut().unwrap().reverse();
    std::fs::write(&path, serde_json::to_string_pretty(&value).unwrap()).unwrap();
    let e = read_any_design(&path).unwrap_err().to_string();
    assert!(
        e.contains("t.json:") && e.contains("counter-clockwise") && e.contains("reverse"),
        "{e}"
    );
    // A key the file does not have.
    value["trim"]["polygon"].as_array_mut().unwrap().reverse();
    value["trimmed"] = true.into();
    std::fs::write(&path, serde_json::to_string_pretty(&value).unwrap()).unwrap();
    let e = read_any_design(&path).unwrap_err().to_string();
    assert!(e.contains("unknown field `trimmed`"), "{e}");
}

#[test]
fn a_trimmed_design_is_cut_by_its_outline_or_says_why_its_design_cannot_be_built() {
    use monge_io::TrimmedMeshError;
    let options = GenerateOptions::default();
    for design in [surface(), patches()] {
        let trimmed = trimmed(design);
        let (grid, mesh) = trimmed.mesh(&options).unwrap();
        // Fewer faces than the grid's, every vertex within the disc (seen along its
        // axis) or on its edge (a cut's corner).
        assert!(mesh.faces.len() < grid.face_count() && !mesh.faces.is_empty());
        for v in &mesh.vertices {
            assert!(
                trimmed.trim.contains(*v) || on_outline(&trimmed.trim, *v),
                "{v}"
            );
        }
    }
    // A design whose guides do not meet at 90°.
    let mut surface = surface();
    if let Trimmable::Surface(d) = &mut surface {
        d.guide_v = monge_core::design::GuideSpec::points(vec![
            [0.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [2.0, 2.0, 0.5],
        ]);
    }
    let e = TrimmedDesign {
        design: surface,
        trim: trimmed(self::surface()).trim,
    }
    .mesh(&options)
    .unwrap_err();
    assert!(matches!(e, TrimmedMeshError::Surface(_)), "{e}");
    // A patch attached to one that is not there.
    let mut patches = patches();
    if let Trimmable::Patches(d) = &mut patches {
        d.patches[1].attach.as_mut().unwrap().patch = 5;
    }
    let e = TrimmedDesign {
        design: patches,
        trim: trimmed(self::patches()).trim,
    }
    .mesh(&options)
    .unwrap_err();
    assert!(matches!(e, TrimmedMeshError::Patches(_)), "{e}");
}

/// Whether `v` lies on the outline's polygon (a cut's corner), within round-off: its
/// corners in space, seen along its direction.
fn on_outline(outline: &Outline, v: DVec3) -> bool {
    let corners = outline.polygon();
    let n = corners.len();
    (0..n).any(|k| {
        let (a, b) = (corners[k], corners[(k + 1) % n]);
        // Distance in plan (the outline's direction is near z here) to the side a-b.
        let (a, b, p) = (a.truncate(), b.truncate(), v.truncate());
        let t = ((p - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 1.0);
        p.distance(a + t * (b - a)) < 1e-6
    })
}
