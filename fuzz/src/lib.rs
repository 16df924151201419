//! The properties the fuzz targets check (see `fuzz/README.md`).
//!
//! Every input either gives a typed error or an `Ok` whose every number is
//! finite (and whose measurement by [`measure`] is not NaN); a panic, an
//! abort, a NaN in an `Ok`, or an allocation beyond libFuzzer's
//! `-malloc_limit_mb` is a crash. Exactness (§2.2) is not asserted here: the
//! property tests of monge-core prove it on random designs.

use glam::DVec3;
use monge_core::conical::conical_dual;
use monge_core::developable::developable;
use monge_core::measure::measure;
use monge_core::multipatch::build;
use monge_core::symmetry::{assemble, isometries};
use monge_core::{generate, GenerateOptions, MeshKind, QuadGrid};
use monge_io::{
    parse_any_design, parse_multipatch, parse_planes, read_iges_surfaces, read_mesh_from,
    read_stl_points, read_text_points, write_trimmed_mesh_to, AnyDesign, DesignFormat, FileKind,
    MeshFormat,
};

/// The grid limit the targets generate with (the documented
/// [`GenerateOptions::max_vertices`] mechanism, lowered so that one execution
/// stays fast: 48 bytes a vertex, about 2 MB).
pub const MAX_VERTICES: usize = 40_000;

fn options() -> GenerateOptions {
    GenerateOptions {
        max_vertices: MAX_VERTICES,
    }
}

/// Every point finite.
fn assert_finite(what: &str, points: &[DVec3]) {
    if let Some(k) = points.iter().position(|p| !p.is_finite()) {
        panic!("{what}: point {k} is not finite: {:?}", points[k]);
    }
}

/// A generated grid: the right shape, finite, measurable.
fn assert_grid(what: &str, grid: &QuadGrid) {
    assert_eq!(grid.vertices.len(), grid.rows * grid.cols, "{what}: shape");
    assert_finite(what, &grid.vertices);
    assert_finite(what, &grid.normals);
    assert!(
        !measure(grid).max_error().is_nan(),
        "{what}: measured error is NaN"
    );
}

/// A design file of any kind in `format`: parsed, then generated as the command
/// that takes it would (`generate`, `patches`; planes files are parsed only).
pub fn design(data: &[u8], format: DesignFormat) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match FileKind::of_text(text, format) {
        Some(FileKind::MultiPatch) => {
            let Ok(d) = parse_multipatch(text, format) else {
                return;
            };
            let Ok(mp) = build(&d, &options()) else {
                return;
            };
            assert_grid("multi-patch", &mp.grid);
            // As `monge patches` does: no more copies than the vertex limit allows.
            let max_copies = MAX_VERTICES / mp.grid.vertices.len().max(1);
            if let Ok(isos) = isometries(&d.symmetry, max_copies) {
                assert!(isos.len() <= max_copies, "{} copies", isos.len());
                let a = assemble(std::slice::from_ref(&mp.grid), &isos);
                assert_finite("assembly", &a.mesh.vertices);
            }
        }
        // Parsed only: `monge align` scans θ with an optimiser (0.3–1 s an
        // input), too slow to fuzz; the designs it writes are surface designs,
        // fuzzed below.
        Some(FileKind::Planes) => {
            let _ = parse_planes(text, format);
        }
        _ => match parse_any_design(text, format) {
            Ok(AnyDesign::Surface(d)) => surface(&d),
            Ok(AnyDesign::Developable(d)) => {
                if let Ok(mesh) = developable(&d.developable, &options()) {
                    assert_grid("developable", &mesh.grid);
                }
            }
            Ok(AnyDesign::Trimmed(t)) => {
                if let Ok((grid, trimmed)) = t.mesh(&options()) {
                    assert_grid("trimmed design", &grid);
                    assert_finite("trimmed", &trimmed.vertices);
                    // Written in every mesh format `monge generate` writes it in (glTF
                    // may refuse coordinates beyond f32's range).
                    for format in [MeshFormat::Obj, MeshFormat::Ply, MeshFormat::Json] {
                        write_trimmed_mesh_to(&trimmed, format, "", &mut Vec::new())
                            .expect("a trimmed mesh is written");
                    }
                    let _ = write_trimmed_mesh_to(&trimmed, MeshFormat::Glb, "", &mut Vec::new());
                }
            }
            Err(_) => {}
        },
    }
}

/// A surface design generated, and its conical dual when asked for.
fn surface(d: &monge_core::Design) {
    let Ok(g) = generate(d, &options()) else {
        return;
    };
    assert_grid("generated", &g.grid);
    if d.mesh == MeshKind::Conical && g.grid.rows >= 3 && g.grid.cols >= 3 {
        let c = conical_dual(&g.grid);
        assert_finite("conical", &c.grid.vertices);
        assert_finite("conical face normals", &c.face_normals);
    }
}

/// A mesh file in `format`, read, then measured as `monge check` does.
pub fn mesh(data: &[u8], format: MeshFormat) {
    if let Ok(grid) = read_mesh_from(data, format) {
        assert_finite("mesh", &grid.vertices);
        assert_finite("mesh normals", &grid.normals);
        let _ = measure(&grid);
    }
}

/// An IGES file read: every surface's numbers finite.
pub fn iges(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok(surfaces) = read_iges_surfaces(text) {
        for s in &surfaces {
            assert_finite("IGES control points", &s.control_points);
            let numbers = s.knots_u.iter().chain(&s.knots_v).chain(&s.weights);
            assert!(
                numbers.copied().all(f64::is_finite),
                "IGES: non-finite knot or weight"
            );
        }
    }
}

/// A target's points read as an STL (ASCII or binary) and as a text file of points:
/// every point finite.
pub fn points(data: &[u8]) {
    if let Ok(points) = read_stl_points(data, "fuzz.stl") {
        assert_finite("STL points", &points);
    }
    if let Ok(text) = std::str::from_utf8(data) {
        if let Ok(points) = read_text_points(text, "fuzz.xyz") {
            assert_finite("text points", &points);
        }
    }
}
