//! Writing a NURBS surface as an IGES 5.3 file (entity 128, §5.3): the
//! Start, Global, Directory Entry, Parameter Data and Terminate sections.

use std::cell::{Cell, RefCell};
use std::io::{self, Write};

use monge_core::cyclidic::NURBS_DEGREE;

use super::check::{check_lines, check_shape, Checking, ColumnCheck};
use super::columns::NurbsColumns;
use super::fields::{
    hollerith, put_line, real, reals, Packer, Real, DATA_COLUMNS, PARAMETER_COLUMNS,
};
use crate::text::emit;

/// The date written to the Global section (fields 18 and 25).
const DATE: &str = "19700101.000000";

/// Relative resolution written to the Global section and used for the closure flags.
const RELATIVE_RESOLUTION: f64 = 1e-9;

/// Writes `surface` as an IGES 5.3 file holding one rational B-spline surface
/// (entity 128): a [`NurbsSurface`](monge_core::cyclidic::NurbsSurface), or a [`CyclidicNet`](monge_core::cyclidic::CyclidicNet), whose surface
/// ([`CyclidicNet::nurbs`](monge_core::cyclidic::CyclidicNet::nurbs)) is then computed a column at a time as it is
/// written, never held ([`NurbsColumns`]).
///
/// IGES numbers the control points `W(i, j)` with `i` along the first
/// parameter; they are written with `i` running fastest. `u` of `surface` is
/// the IGES `S` direction and control point `(a, b)` is `W(a, b)`. The flags are
/// computed: closed in a direction when the first and last rows (columns) of
/// control points agree to the written resolution, polynomial when all weights
/// are equal, never periodic. The parameter range is the whole knot domain.
/// Reals are the shortest decimals that parse back to the same `f64`, in `E`
/// notation with a decimal point (`1.0E0`, `-2.5E-1`), so nothing is rounded.
///
/// The Global section says:
///
/// * units flag 6 (metres, unit name `M`): monge has no units, so the model
///   units are the design's units and a receiver may need to rescale;
/// * model space scale 1.0;
/// * maximum coordinate: the largest absolute control point coordinate (the
///   surface lies in the convex hull of its control points);
/// * minimum resolution: `1e-9` times that maximum (`1e-9` for a surface at the origin);
/// * file name `monge.igs`, sending system `monge-io <version>`, IGES 5.3
///   (version flag 11), and the fixed generation and modification date
///   `19700101.000000`, so that the output depends on the surface alone. It is
///   not the time the file was written.
///
/// # Errors
///
/// [`io::ErrorKind::InvalidInput`] when `surface` is not a valid degree-2 NURBS
/// surface (array lengths, non-finite numbers, weights not positive, knots
/// decreasing or with an empty domain) or needs more than 9 999 999 lines,
/// before anything is written; otherwise the errors of `w`.
///
/// ```
/// use monge_core::cyclidic::{CyclidicNet, CyclidicOptions, Frame};
/// use monge_core::QuadGrid;
/// use glam::DVec3;
/// let g = QuadGrid::new(2, 2, vec![DVec3::ZERO, DVec3::Y, DVec3::X, DVec3::X + DVec3::Y], vec![]);
/// let net = CyclidicNet::from_frame(&g, Frame::new(DVec3::X, DVec3::Y), &CyclidicOptions::default()).unwrap();
/// let mut out = Vec::new();
/// monge_io::write_iges(&net, &mut out).unwrap();
/// // The same file as from the surface held whole.
/// let mut whole = Vec::new();
/// monge_io::write_iges(&net.nurbs(), &mut whole).unwrap();
/// assert_eq!(out, whole);
/// let text = String::from_utf8(out).unwrap();
/// assert!(text.lines().all(|l| l.len() == 80));
/// let surfaces = monge_io::read_iges_surfaces(&text).unwrap();
/// assert!((surfaces[0].point(0.5, 0.5) - DVec3::new(0.5, 0.5, 0.0)).length() < 1e-15);
/// ```
pub fn write_iges<W: Write + ?Sized>(
    surface: &(impl NurbsColumns + ?Sized),
    w: &mut W,
) -> io::Result<()> {
    let invalid = |m: String| io::Error::new(io::ErrorKind::InvalidInput, m);
    check_shape(surface).map_err(invalid)?;
    // The Directory Entry gives the number of Parameter Data lines, which
    // come after it: a first pass counts them (the flags, one digit each,
    // unknown yet) and checks the control points, the second writes them.
    let mut parameter_lines = 0;
    let mut counter = Packer::new(PARAMETER_COLUMNS, |_: &[u8]| {
        parameter_lines += 1;
        Ok(())
    });
    let checking = Checking {
        surface,
        check: RefCell::new(ColumnCheck::new(surface.size())),
        sweeps: Cell::new(0),
    };
    surface_parameters(&checking, [false; 3], &mut |f| counter.field(f))?;
    counter.finish()?;
    let checked = checking.check.into_inner().finish().map_err(invalid)?;
    check_lines(parameter_lines, surface.size()).map_err(invalid)?;
    let max_coordinate = checked.max_coordinate;
    let resolution = if max_coordinate > 0.0 {
        RELATIVE_RESOLUTION * max_coordinate
    } else {
        RELATIVE_RESOLUTION
    };
    let flags = [
        checked.closing_u <= resolution,
        checked.closing_v <= resolution,
        checked.polynomial,
    ];

    let global = global_parameters(max_coordinate, resolution);
    emit(w, |o| {
        let start = "monge: exact NURBS surface (rational B-spline surface, IGES entity 128)";
        put_line(o, start.as_bytes(), 'S', 1)?;
        let mut global_lines = 0;
        let mut packer = Packer::new(DATA_COLUMNS, |line: &[u8]| {
            global_lines += 1;
            put_line(o, line, 'G', global_lines)
        });
        for field in &global {
            packer.field(field.as_bytes())?;
        }
        packer.finish()?;

        let de = 1;
        let entry1 = format!(
            "{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}",
            128, 1, 0, 0, 0, 0, 0, 0, "00000000"
        );
        let entry2 = format!(
            "{:>8}{:>8}{:>8}{:>8}{:>8}{:8}{:8}{:8}{:>8}",
            128, 0, 0, parameter_lines, 0, "", "", "", 0
        );
        put_line(o, entry1.as_bytes(), 'D', de)?;
        put_line(o, entry2.as_bytes(), 'D', de + 1)?;
        let mut sequence = 0;
        let back_pointer = format!(" {de:>7}");
        let mut packer = Packer::new(PARAMETER_COLUMNS, |line: &[u8]| {
            sequence += 1;
            let mut data = [b' '; DATA_COLUMNS];
            data[..line.len()].copy_from_slice(line);
            data[PARAMETER_COLUMNS..].copy_from_slice(back_pointer.as_bytes());
            put_line(o, &data, 'P', sequence)
        });
        surface_parameters(surface, flags, &mut |f| packer.field(f))?;
        packer.finish()?;
        debug_assert_eq!(sequence, parameter_lines);

        let counts = format!(
            "S{:>7}G{:>7}D{:>7}P{:>7}",
            1, global_lines, 2, parameter_lines
        );
        put_line(o, counts.as_bytes(), 'T', 1)
    })
}

/// The Global section's parameters (without delimiters).
fn global_parameters(max_coordinate: f64, resolution: f64) -> [String; 25] {
    let system = concat!("monge-io ", env!("CARGO_PKG_VERSION"));
    [
        hollerith(","),         // 1 parameter delimiter
        hollerith(";"),         // 2 record delimiter
        hollerith("monge"),     // 3 product identification from sender
        hollerith("monge.igs"), // 4 file name
        hollerith(system),      // 5 native system ID
        hollerith(system),      // 6 preprocessor version
        "32".into(),            // 7 bits of an integer
        "38".into(),            // 8 single precision: largest power of ten
        "6".into(),             // 9 single precision: significant digits
        "308".into(),           // 10 double precision: largest power of ten
        "15".into(),            // 11 double precision: significant digits
        hollerith("monge"),     // 12 product identification for receiver
        real(1.0),              // 13 model space scale
        "6".into(),             // 14 units flag: metres
        hollerith("M"),         // 15 units name
        "1".into(),             // 16 line weight gradations
        real(0.0),              // 17 width of the thickest line (none drawn)
        hollerith(DATE),        // 18 date and time of generation
        real(resolution),       // 19 minimum user-intended resolution
        real(max_coordinate),   // 20 approximate maximum coordinate
        String::new(),          // 21 author (defaulted)
        String::new(),          // 22 organisation (defaulted)
        "11".into(),            // 23 IGES version: 5.3
        "0".into(),             // 24 drafting standard: none
        hollerith(DATE),        // 25 date and time of last modification
    ]
}

/// Entity 128's parameters (without delimiters), each passed to `field` in order.
fn surface_parameters(
    s: &(impl NurbsColumns + ?Sized),
    [closed_u, closed_v, polynomial]: [bool; 3],
    field: &mut dyn FnMut(&[u8]) -> io::Result<()>,
) -> io::Result<()> {
    let p = NURBS_DEGREE;
    let (rows, cols) = s.size();
    let (knots_u, knots_v) = s.knots();
    let mut int = itoa::Buffer::new();
    for n in [128, rows - 1, cols - 1, p, p] {
        field(int.format(n).as_bytes())?;
    }
    for flag in [closed_u, closed_v, polynomial, false, false] {
        field(int.format(u8::from(flag)).as_bytes())?;
    }
    let mut real = Real::default();
    for &k in knots_u.iter().chain(&knots_v) {
        field(real.format(k))?;
    }
    // IGES order: first index (along u) fastest, so column by column.
    s.columns(&mut |_, weights| reals(weights, field))?;
    let mut coordinates = Vec::new();
    s.columns(&mut |points, _| {
        coordinates.clear();
        coordinates.extend(points.iter().flat_map(|q| q.to_array()));
        reals(&coordinates, field)
    })?;
    for x in [knots_u[p], knots_u[rows], knots_v[p], knots_v[cols]] {
        field(real.format(x))?;
    }
    Ok(())
}
