//! IGES 5.3 output of exact NURBS surfaces (entity 128, rational B-spline
//! surface) and a minimal reader of the same entity.
//!
//! The writer produces a fixed-format ASCII file of 80-column lines: one Start
//! line, the Global section, two Directory Entry lines and the Parameter Data of
//! one entity 128, and the Terminate line. Every real is written as the
//! shortest decimal that parses back to the same `f64`, in `E` notation with a
//! decimal point (`1.0E0`, `-2.5E-1`), so the surface is exact.
//!
//! The reader ([`read_iges_surfaces`]) accepts any IGES 5.3 fixed ASCII file and
//! returns every entity 128 in it, with its transformation matrix (entity 124)
//! applied to the control points.

use std::cell::{Cell, RefCell};
use std::io::{self, Write};

use glam::DVec3;
use monge_core::cyclidic::{CyclidicNet, NurbsSurface, NURBS_DEGREE};
use monge_core::guide::MAX_DEGREE;

use crate::error::IoError;
use crate::text::{emit, Out};

/// File name in error messages of [`read_iges_surfaces`].
const NO_FILE: &str = "<input>";

/// The date written to the Global section (fields 18 and 25).
const DATE: &str = "19700101.000000";

/// Relative resolution written to the Global section and used for the closure flags.
const RELATIVE_RESOLUTION: f64 = 1e-9;

/// Columns of data in a Start, Global or Directory Entry line.
const DATA_COLUMNS: usize = 72;

/// Columns of data in a Parameter Data line (65–72 hold the back-pointer).
const PARAMETER_COLUMNS: usize = 64;

/// Deepest chain of transformation matrices followed by the reader.
const MAX_TRANSFORM_CHAIN: usize = 64;

/// Writes `surface` as an IGES 5.3 file holding one rational B-spline surface
/// (entity 128): a [`NurbsSurface`], or a [`CyclidicNet`], whose surface
/// ([`CyclidicNet::nurbs`]) is then computed a column at a time as it is
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

/// What [`NurbsColumns::columns`] calls with each column: its control points
/// and weights.
pub type NurbsColumn<'a> = dyn FnMut(&[DVec3], &[f64]) -> io::Result<()> + 'a;

/// A degree-2 NURBS surface as [`write_iges`] writes it (§5.3): its control
/// points and weights a column (index along `v`) at a time, so that a surface
/// computed as it is written ([`CyclidicNet::nurbs_columns`]) is never held.
pub trait NurbsColumns {
    /// The number of control points along `u` and along `v`.
    fn size(&self) -> (usize, usize);

    /// The knots along `u` and along `v`.
    fn knots(&self) -> (Vec<f64>, Vec<f64>);

    /// Calls `column` with the control points and weights of every column,
    /// in order, each along `u`; stops at its first error.
    fn columns(&self, column: &mut NurbsColumn<'_>) -> io::Result<()>;
}

/// The surface as it is held.
impl NurbsColumns for NurbsSurface {
    fn size(&self) -> (usize, usize) {
        (self.rows, self.cols)
    }

    fn knots(&self) -> (Vec<f64>, Vec<f64>) {
        (self.knots_u.clone(), self.knots_v.clone())
    }

    fn columns(&self, column: &mut NurbsColumn<'_>) -> io::Result<()> {
        let n = self.rows.checked_mul(self.cols);
        if n != Some(self.control_points.len()) || n != Some(self.weights.len()) {
            let n = n.map_or("more than usize::MAX".into(), |n| n.to_string());
            return Err(io::Error::new(
                io::ErrorKind::InvalidInput,
                format!(
                    "{} × {} control points need {n} points and weights, got {} and {}",
                    self.rows,
                    self.cols,
                    self.control_points.len(),
                    self.weights.len()
                ),
            ));
        }
        let (mut points, mut weights) = (Vec::new(), Vec::new());
        for b in 0..self.cols {
            let at = (0..self.rows).map(|a| a * self.cols + b);
            points.clear();
            weights.clear();
            points.extend(at.clone().map(|k| self.control_points[k]));
            weights.extend(at.map(|k| self.weights[k]));
            column(&points, &weights)?;
        }
        Ok(())
    }
}

/// The net's surface ([`CyclidicNet::nurbs`]), computed as it is written.
impl NurbsColumns for CyclidicNet {
    fn size(&self) -> (usize, usize) {
        (2 * self.rows() - 1, 2 * self.cols() - 1)
    }

    fn knots(&self) -> (Vec<f64>, Vec<f64>) {
        self.nurbs_knots()
    }

    fn columns(&self, column: &mut NurbsColumn<'_>) -> io::Result<()> {
        self.nurbs_columns()
            .try_for_each(|(points, weights)| column(&points, &weights))
    }
}

/// The largest sequence number of a line: seven columns.
const MAX_SEQUENCE: usize = 9_999_999;

/// Why `lines` Parameter Data lines of a surface of `rows × cols` control
/// points cannot be written, if they cannot.
fn check_lines(lines: usize, (rows, cols): (usize, usize)) -> Result<(), String> {
    if lines > MAX_SEQUENCE {
        return Err(format!(
            "the surface of {rows} × {cols} control points takes {lines} lines of parameter \
             data, more than the {MAX_SEQUENCE} that an IGES section can number: write fewer \
             patches (fewer guide samples), or another format"
        ));
    }
    Ok(())
}

/// Why `s` cannot be written, if its size or knots say so.
fn check_shape(s: &(impl NurbsColumns + ?Sized)) -> Result<(), String> {
    let p = NURBS_DEGREE;
    let (rows, cols) = s.size();
    if rows <= p || cols <= p {
        return Err(format!(
            "a degree-{p} surface needs at least {} control points in each direction, got {rows} × {cols}",
            p + 1,
        ));
    }
    let (knots_u, knots_v) = s.knots();
    for (name, knots, count) in [("u", &knots_u, rows), ("v", &knots_v, cols)] {
        if knots.len() != count + p + 1 {
            return Err(format!(
                "{count} control points of degree {p} need {} knots along {name}, got {}",
                count + p + 1,
                knots.len()
            ));
        }
        if !knots.iter().all(|k| k.is_finite()) || knots.windows(2).any(|k| k[0] > k[1]) {
            return Err(format!(
                "the knots along {name} are not finite and non-decreasing"
            ));
        }
        if knots[p] >= knots[count] {
            return Err(format!("the knot domain along {name} is empty"));
        }
    }
    Ok(())
}

/// A surface whose columns are checked ([`ColumnCheck`]) the first time
/// they are gone through, each before it is passed on.
struct Checking<'s, S: ?Sized> {
    surface: &'s S,
    check: RefCell<ColumnCheck>,
    /// Times the columns have been gone through.
    sweeps: Cell<usize>,
}

impl<S: NurbsColumns + ?Sized> NurbsColumns for Checking<'_, S> {
    fn size(&self) -> (usize, usize) {
        self.surface.size()
    }

    fn knots(&self) -> (Vec<f64>, Vec<f64>) {
        self.surface.knots()
    }

    fn columns(&self, column: &mut NurbsColumn<'_>) -> io::Result<()> {
        let first = self.sweeps.replace(self.sweeps.get() + 1) == 0;
        self.surface.columns(&mut |points, weights| {
            if first {
                let mut check = self.check.borrow_mut();
                check
                    .column(points, weights)
                    .map_err(|m| io::Error::new(io::ErrorKind::InvalidInput, m))?;
            }
            column(points, weights)
        })
    }
}

/// What the writer needs of the control points, found a column at a time.
struct ColumnCheck {
    rows: usize,
    cols: usize,
    /// Columns seen.
    columns: usize,
    /// The first column, to compare with the last.
    first: Vec<DVec3>,
    /// The first weight, to compare with every other.
    first_weight: Option<f64>,
    checked: Checked,
}

/// What [`ColumnCheck`] finds of a surface that can be written.
struct Checked {
    /// The largest absolute control point coordinate.
    max_coordinate: f64,
    /// The largest coordinate difference between the first and the last row
    /// of control points (closed along `u` within the resolution).
    closing_u: f64,
    /// The same between the first and the last column.
    closing_v: f64,
    /// All weights equal.
    polynomial: bool,
}

impl ColumnCheck {
    fn new((rows, cols): (usize, usize)) -> Self {
        ColumnCheck {
            rows,
            cols,
            columns: 0,
            first: Vec::new(),
            first_weight: None,
            checked: Checked {
                max_coordinate: 0.0,
                closing_u: 0.0,
                closing_v: 0.0,
                polynomial: true,
            },
        }
    }

    /// Takes the next column in, or says why the surface cannot be written.
    fn column(&mut self, points: &[DVec3], weights: &[f64]) -> Result<(), String> {
        let (rows, cols, k) = (self.rows, self.cols, self.columns);
        if points.len() != rows || weights.len() != rows {
            return Err(format!(
                "{rows} × {cols} control points need {rows} points and weights a column, \
                 got {} and {} in column {k}",
                points.len(),
                weights.len()
            ));
        }
        if !points.iter().all(|q| q.is_finite()) {
            return Err("a control point is not finite".into());
        }
        if !weights.iter().all(|&w| w.is_finite() && w > 0.0) {
            return Err("a weight is not a positive finite number".into());
        }
        let difference = |x: DVec3, y: DVec3| (x - y).abs().max_element();
        let c = &mut self.checked;
        for q in points {
            c.max_coordinate = c.max_coordinate.max(q.abs().max_element());
        }
        c.closing_u = c.closing_u.max(difference(points[0], points[rows - 1]));
        let w0 = *self.first_weight.get_or_insert(weights[0]);
        c.polynomial &= weights.iter().all(|&w| w == w0);
        if k == 0 {
            self.first = points.to_vec();
        }
        if k + 1 == cols {
            c.closing_v = (self.first.iter().zip(points))
                .map(|(x, y)| difference(*x, *y))
                .fold(0.0, f64::max);
        }
        self.columns += 1;
        Ok(())
    }

    /// What was found, once every column is in.
    fn finish(self) -> Result<Checked, String> {
        if self.columns != self.cols {
            return Err(format!(
                "{} × {} control points need {} columns, got {}",
                self.rows, self.cols, self.cols, self.columns
            ));
        }
        Ok(self.checked)
    }
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

/// Passes `values` to `field` in order as IGES reals, formatted in pieces on
/// every core (formatting is most of the writer's work).
fn reals(values: &[f64], field: &mut dyn FnMut(&[u8]) -> io::Result<()>) -> io::Result<()> {
    let pieces = monge_core::tasks::ranges(values.len(), 1 << 10, |r| {
        let mut real = Real::default();
        let (mut text, mut ends) = (Vec::new(), Vec::with_capacity(r.len()));
        for &x in &values[r] {
            text.extend_from_slice(real.format(x));
            ends.push(text.len());
        }
        (text, ends)
    });
    for (text, ends) in pieces {
        let mut start = 0;
        for end in ends {
            field(&text[start..end])?;
            start = end;
        }
    }
    Ok(())
}

/// `text` as an IGES Hollerith string: `5Hmonge`.
fn hollerith(text: &str) -> String {
    format!("{}H{text}", text.len())
}

/// The shortest decimal that parses back to `x`, in `E` notation with a decimal point.
fn real(x: f64) -> String {
    String::from_utf8(Real::default().format(x).to_vec()).expect("ASCII")
}

/// Formats reals as IGES wants them: the shortest decimal that parses back to
/// the same `f64` (`zmij`), rewritten as `d.dddE±n` (`1.0E0`, `-2.5E-1`,
/// `0.0E0`): the text of `format!("{x:E}")` with `.0` added to a lone digit,
/// except where two shortest decimals are equally near `x`: then zmij takes the
/// even last digit (as Python's `repr`), the standard library the larger one.
#[derive(Default)]
struct Real {
    shortest: zmij::Buffer,
    out: Vec<u8>,
}

impl Real {
    /// `x` (finite) in IGES `E` notation.
    fn format(&mut self, x: f64) -> &[u8] {
        let text = self.shortest.format_finite(x).as_bytes();
        let (sign, text) = match text.split_first() {
            Some((b'-', rest)) => (true, rest),
            _ => (false, text),
        };
        let (mantissa, exponent) = match text.iter().position(|&c| c == b'e') {
            Some(e) => (
                &text[..e],
                std::str::from_utf8(&text[e + 1..])
                    .ok()
                    .and_then(|t| t.parse::<i32>().ok())
                    .expect("zmij writes an integer exponent"),
            ),
            None => (text, 0),
        };
        // The digits without the point, and the power of ten of the first one.
        let point = mantissa
            .iter()
            .position(|&c| c == b'.')
            .unwrap_or(mantissa.len());
        let digits = mantissa.iter().filter(|&&c| c != b'.');
        let leading = digits.clone().take_while(|&&c| c == b'0').count();
        self.out.clear();
        if sign {
            self.out.push(b'-');
        }
        // At most 17 significant digits, and zeros that pad them (`1e+16` is `1` alone).
        let mut significant = [0u8; 32];
        let mut n = 0;
        for &c in digits.skip(leading) {
            significant[n] = c;
            n += 1;
        }
        let significant = &significant[..n];
        let end = n - significant.iter().rev().take_while(|&&c| c == b'0').count();
        if end == 0 {
            self.out.extend_from_slice(b"0.0E0");
            return &self.out;
        }
        let power = exponent + point as i32 - leading as i32 - 1;
        self.out.push(significant[0]);
        self.out.push(b'.');
        if end > 1 {
            self.out.extend_from_slice(&significant[1..end]);
        } else {
            self.out.push(b'0');
        }
        self.out.push(b'E');
        self.out
            .extend_from_slice(itoa::Buffer::new().format(power).as_bytes());
        &self.out
    }
}

/// Delimited fields packed into lines of at most `width` columns, none split:
/// each field is followed by `,`, the last by `;`; `line` is called with each line.
struct Packer<L: FnMut(&[u8]) -> io::Result<()>> {
    width: usize,
    /// The line being filled: fields, each with a `,` after it.
    line: Vec<u8>,
    sink: L,
}

impl<L: FnMut(&[u8]) -> io::Result<()>> Packer<L> {
    fn new(width: usize, sink: L) -> Self {
        Packer {
            width,
            line: Vec::with_capacity(width),
            sink,
        }
    }

    /// The next field, and its delimiter (`,` now; the last one's becomes `;`).
    fn field(&mut self, field: &[u8]) -> io::Result<()> {
        if !self.line.is_empty() && self.line.len() + field.len() + 1 > self.width {
            (self.sink)(&self.line)?;
            self.line.clear();
        }
        self.line.extend_from_slice(field);
        self.line.push(b',');
        Ok(())
    }

    /// Ends the last field with `;` and writes the last line.
    fn finish(mut self) -> io::Result<()> {
        if let Some(delimiter) = self.line.last_mut() {
            *delimiter = b';';
        }
        (self.sink)(&self.line)
    }
}

/// One 80-column line: `data` in columns 1–72, the section letter, the sequence number.
fn put_line<W: Write + ?Sized>(
    o: &mut Out<'_, W>,
    data: &[u8],
    section: char,
    sequence: usize,
) -> io::Result<()> {
    debug_assert!(data.len() <= DATA_COLUMNS);
    let mut line = [b' '; 80];
    line[..data.len()].copy_from_slice(data);
    line[DATA_COLUMNS] = section as u8;
    let mut digits = itoa::Buffer::new();
    let digits = digits.format(sequence).as_bytes();
    debug_assert!(sequence <= MAX_SEQUENCE);
    line[80 - digits.len()..].copy_from_slice(digits);
    o.bytes(&line);
    o.end()
}

/// A rational B-spline surface (IGES entity 128) read by [`read_iges_surfaces`].
///
/// Control point `(a, b)`, `a` along `u` (the IGES `S` direction), is
/// `control_points[a * count_v + b]`, as in
/// [`NurbsSurface`]; its weight is `weights[a * count_v + b]`.
#[derive(Clone, Debug, PartialEq)]
pub struct IgesSurface {
    /// Degree along `u` (IGES `M1`).
    pub degree_u: usize,
    /// Degree along `v` (IGES `M2`).
    pub degree_v: usize,
    /// Control points along `u` (IGES `K1 + 1`).
    pub count_u: usize,
    /// Control points along `v` (IGES `K2 + 1`).
    pub count_v: usize,
    /// Knots along `u`: `count_u + degree_u + 1`, non-decreasing.
    pub knots_u: Vec<f64>,
    /// Knots along `v`: `count_v + degree_v + 1`, non-decreasing.
    pub knots_v: Vec<f64>,
    /// Positive weights, `count_u · count_v`.
    pub weights: Vec<f64>,
    /// Control points, `count_u · count_v`, with the entity's transformation applied.
    pub control_points: Vec<DVec3>,
    /// The parameter range along `u` given in the file (`U0`, `U1`).
    pub range_u: [f64; 2],
    /// The parameter range along `v` given in the file (`V0`, `V1`).
    pub range_v: [f64; 2],
}

impl IgesSurface {
    /// The point at `(u, v)`: the rational tensor-product B-spline, its basis
    /// functions by the Cox–de Boor recursion.
    ///
    /// Parameters outside the knot domain `[knots[degree], knots[count]]` are
    /// clamped to it; NaN gives NaN.
    ///
    /// # Panics
    ///
    /// If the fields are inconsistent (lengths as documented), which never
    /// happens for a surface returned by [`read_iges_surfaces`].
    pub fn point(&self, u: f64, v: f64) -> DVec3 {
        let (first_u, nu) = basis(&self.knots_u, self.degree_u, self.count_u, u);
        let (first_v, nv) = basis(&self.knots_v, self.degree_v, self.count_v, v);
        let (mut sum, mut weight) = (DVec3::ZERO, 0.0);
        for (a, &na) in nu.iter().enumerate().filter(|(_, &n)| n != 0.0) {
            for (b, &nb) in nv.iter().enumerate().filter(|(_, &n)| n != 0.0) {
                let k = (first_u + a) * self.count_v + first_v + b;
                let w = self.weights[k] * na * nb;
                sum += self.control_points[k] * w;
                weight += w;
            }
        }
        sum / weight
    }
}

/// The `degree + 1` B-spline basis functions of `degree` on `knots` (for
/// `count` control points) that can be non-zero at `t` (clamped to the
/// domain), and the index of the first: from the degree-0 indicator of the
/// span holding `t` (the last non-empty span at the end of the domain) raised
/// one degree at a time, in `degree²` operations whatever the number of knots.
fn basis(knots: &[f64], degree: usize, count: usize, t: f64) -> (usize, Vec<f64>) {
    let t = t.clamp(knots[degree], knots[count]);
    let span = if t.is_nan() {
        degree
    } else if t < knots[count] {
        knots.partition_point(|&k| k <= t) - 1
    } else {
        knots.partition_point(|&k| k < t) - 1
    };
    let first = span - degree;
    let ratio = |num: f64, den: f64| if den == 0.0 { 0.0 } else { num / den };
    // n[i - first] is basis function i; one more, always 0, past the span.
    let mut n = vec![0.0; degree + 2];
    n[degree] = if t.is_nan() { f64::NAN } else { 1.0 };
    for p in 1..=degree {
        for i in first..=span {
            let j = i - first;
            n[j] = ratio(t - knots[i], knots[i + p] - knots[i]) * n[j]
                + ratio(knots[i + p + 1] - t, knots[i + p + 1] - knots[i + 1]) * n[j + 1];
        }
    }
    n.truncate(degree + 1);
    (first, n)
}

/// Every rational B-spline surface (entity 128) of an IGES 5.3 fixed-format
/// ASCII file, in Directory Entry order.
///
/// Lines may end in `\n` or `\r\n` and may lack trailing blanks, but must have
/// the section letter in column 73 and at most 80 columns. Sections must come
/// in the order Start, Global, Directory Entry, Parameter Data, Terminate, with
/// consecutive sequence numbers from 1, and the Terminate line's counts must
/// match. The delimiters are taken from the Global section; reals may use
/// `E` or `D` exponents. Parameter data may wrap over any number of lines.
/// Surfaces subordinate to others (e.g. of a trimmed surface) are returned as
/// well, and a transformation matrix (entity 124, chains included) is applied
/// to the control points. Other entities are skipped.
///
/// # Errors
///
/// [`IoError::Syntax`] (file `<input>`, the line at fault) for a malformed
/// line, section or number, a wrong pointer, or an entity 128 whose knots,
/// weights or degrees are invalid; [`IoError::CountMismatch`] when an entity's
/// parameter data is shorter than its counts require.
pub fn read_iges_surfaces(text: &str) -> Result<Vec<IgesSurface>, IoError> {
    let file = Sections::split(text)?;
    let (pdelim, rdelim) = file.delimiters()?;
    let mut surfaces = Vec::new();
    for k in (0..file.directory.len()).step_by(2) {
        let de = k + 1;
        if file.entry(de)?.entity_type == 128 {
            surfaces.push(file.surface(de, pdelim, rdelim)?);
        }
    }
    Ok(surfaces)
}

/// A line of an IGES file: its 1-based number in the text and its columns 1–72.
#[derive(Clone, Copy)]
struct Line<'a> {
    number: usize,
    data: &'a str,
}

/// The sections of an IGES file, lines checked.
struct Sections<'a> {
    global: Vec<Line<'a>>,
    directory: Vec<Line<'a>>,
    parameters: Vec<Line<'a>>,
    /// Line number of the last line, for errors about a missing part.
    last_line: usize,
}

/// The fields of a Directory Entry that the reader uses.
struct Entry {
    entity_type: i64,
    parameter_pointer: i64,
    transform_pointer: i64,
    parameter_lines: i64,
}

/// A parameter of an entity: its text (trimmed) and its line.
struct Parameter {
    text: String,
    line: usize,
}

fn syntax(line: usize, message: impl Into<String>) -> IoError {
    IoError::Syntax {
        file: NO_FILE.into(),
        line,
        message: message.into(),
    }
}

impl<'a> Sections<'a> {
    fn split(text: &'a str) -> Result<Sections<'a>, IoError> {
        const ORDER: &str = "SGDPT";
        let mut sections = Sections {
            global: Vec::new(),
            directory: Vec::new(),
            parameters: Vec::new(),
            last_line: 0,
        };
        let mut counts = [0usize; 5];
        let mut current = 0;
        let mut terminate = None;
        for (k, raw) in text.lines().enumerate() {
            let number = k + 1;
            sections.last_line = number;
            let line = raw.strip_suffix('\r').unwrap_or(raw);
            if !line.is_ascii() {
                return Err(syntax(number, "not an ASCII line (IGES files are ASCII)"));
            }
            if line.len() > 80 || line.len() < 73 {
                return Err(syntax(
                    number,
                    format!(
                        "{} columns; IGES lines have 80, the section letter in column 73",
                        line.len()
                    ),
                ));
            }
            let letter = char::from(line.as_bytes()[72]);
            let Some(section) = ORDER.find(letter) else {
                return Err(syntax(
                    number,
                    format!(
                        "unknown section letter `{letter}` in column 73 \
                         (only the fixed ASCII form of IGES is read, not the compressed or binary form)"
                    ),
                ));
            };
            if section < current {
                return Err(syntax(
                    number,
                    format!(
                        "section `{letter}` after section `{}`; the order is S, G, D, P, T",
                        &ORDER[current..=current]
                    ),
                ));
            }
            if terminate.is_some() {
                return Err(syntax(number, "line after the Terminate line"));
            }
            current = section;
            counts[section] += 1;
            let sequence = line[73..].trim();
            if sequence.parse::<usize>().ok() != Some(counts[section]) {
                return Err(syntax(
                    number,
                    format!(
                        "sequence number `{sequence}` in columns 74–80; expected {}",
                        counts[section]
                    ),
                ));
            }
            let line = Line {
                number,
                data: &line[..72],
            };
            match letter {
                'G' => sections.global.push(line),
                'D' => sections.directory.push(line),
                'P' => sections.parameters.push(line),
                'T' => terminate = Some(line),
                _ => {}
            }
        }
        if sections.directory.len() % 2 == 1 {
            let last = sections.directory.last().expect("an odd count is not zero");
            return Err(syntax(
                last.number,
                "odd number of Directory Entry lines; each entity has two",
            ));
        }
        let Some(t) = terminate else {
            return Err(syntax(
                sections.last_line.max(1),
                "no Terminate line (section `T`); the file is incomplete",
            ));
        };
        for (k, letter) in "SGDP".chars().enumerate() {
            let field = &t.data[8 * k..8 * k + 8];
            let count = field
                .strip_prefix(letter)
                .and_then(|n| n.trim().parse::<usize>().ok());
            if count != Some(counts[k]) {
                return Err(syntax(
                    t.number,
                    format!(
                        "Terminate field `{}` in columns {}–{}; expected `{letter}` and {}, the count of `{letter}` lines",
                        field.trim_end(),
                        8 * k + 1,
                        8 * k + 8,
                        counts[k]
                    ),
                ));
            }
        }
        Ok(sections)
    }

    /// The parameter and record delimiters of the Global section (defaults `,` and `;`).
    fn delimiters(&self) -> Result<(char, char), IoError> {
        let text: String = self.global.iter().map(|l| l.data).collect();
        let line = self.global.first().map_or(self.last_line, |l| l.number);
        let mut rest = text.as_str();
        let pdelim = match hollerith_char(rest, line)? {
            Some(c) => {
                rest = &rest[3..];
                c
            }
            None => ',',
        };
        // The first field ends with the parameter delimiter (unless the section is empty).
        if let Some(after) = rest.strip_prefix(pdelim) {
            rest = after;
        } else if !rest.trim().is_empty() {
            return Err(syntax(
                line,
                format!("the Global section's first field does not end with `{pdelim}`"),
            ));
        }
        let rdelim = hollerith_char(rest, line)?.unwrap_or(';');
        if pdelim == rdelim {
            return Err(syntax(line, "parameter and record delimiters are the same"));
        }
        Ok((pdelim, rdelim))
    }

    /// The Directory Entry numbered `de` (its first line's sequence number).
    fn entry(&self, de: usize) -> Result<Entry, IoError> {
        let (l1, l2) = (self.directory[de - 1], self.directory[de]);
        let field = |line: Line, k: usize| -> Result<i64, IoError> {
            let text = line.data[8 * k..8 * k + 8].trim();
            if text.is_empty() {
                return Ok(0);
            }
            text.parse().map_err(|_| {
                syntax(
                    line.number,
                    format!(
                        "`{text}` in columns {}–{} is not an integer",
                        8 * k + 1,
                        8 * k + 8
                    ),
                )
            })
        };
        let entry = Entry {
            entity_type: field(l1, 0)?,
            parameter_pointer: field(l1, 1)?,
            transform_pointer: field(l1, 6)?,
            parameter_lines: field(l2, 3)?,
        };
        let second_type = field(l2, 0)?;
        if second_type != entry.entity_type {
            return Err(syntax(
                l2.number,
                format!(
                    "entity type {second_type} on the second Directory Entry line; the first says {}",
                    entry.entity_type
                ),
            ));
        }
        Ok(entry)
    }

    /// The parameters of the entity at Directory Entry `de`, the entity type first.
    fn parameters(
        &self,
        de: usize,
        entry: &Entry,
        pdelim: char,
        rdelim: char,
    ) -> Result<Vec<Parameter>, IoError> {
        let de_line = self.directory[de - 1].number;
        let first = usize::try_from(entry.parameter_pointer).unwrap_or(0);
        let count = usize::try_from(entry.parameter_lines).unwrap_or(0);
        // The last line's number, when the pointer and the count are positive
        // and the lines end inside the section.
        let last = (first > 0 && count > 0)
            .then(|| first.checked_add(count - 1))
            .flatten()
            .filter(|&l| l <= self.parameters.len());
        let Some(last) = last else {
            return Err(syntax(
                de_line,
                format!(
                    "entity at DE {de}: parameter data pointer {} with {} lines is outside the {} Parameter Data lines",
                    entry.parameter_pointer,
                    entry.parameter_lines,
                    self.parameters.len()
                ),
            ));
        };
        let mut parameters = Vec::new();
        let mut text = String::new();
        let mut start = 0;
        for line in &self.parameters[first - 1..last] {
            let back = line.data[65..72].trim();
            if back.parse::<usize>().ok() != Some(de) {
                return Err(syntax(
                    line.number,
                    format!(
                        "back-pointer `{back}` in columns 66–72; expected the entity's DE {de}"
                    ),
                ));
            }
            for c in line.data[..PARAMETER_COLUMNS].chars() {
                if text.is_empty() && !c.is_ascii_whitespace() {
                    start = line.number;
                }
                if c == pdelim || c == rdelim {
                    parameters.push(Parameter {
                        text: text.trim().to_owned(),
                        line: if text.trim().is_empty() {
                            line.number
                        } else {
                            start
                        },
                    });
                    text.clear();
                    if c == rdelim {
                        return Ok(parameters);
                    }
                } else if !(text.is_empty() && c.is_ascii_whitespace()) {
                    text.push(c);
                }
            }
        }
        Err(syntax(
            self.parameters[last - 1].number,
            format!("entity at DE {de}: parameter data does not end with `{rdelim}`"),
        ))
    }

    /// The entity 128 at Directory Entry `de`, transformed.
    fn surface(&self, de: usize, pdelim: char, rdelim: char) -> Result<IgesSurface, IoError> {
        let entry = self.entry(de)?;
        let params = self.parameters(de, &entry, pdelim, rdelim)?;
        let mut reader = Reader {
            params: &params,
            next: 0,
            de,
        };
        reader.entity_type(128)?;
        let k1 = reader.integer("K1")?;
        let k2 = reader.integer("K2")?;
        let m1 = reader.integer("M1")?;
        let m2 = reader.integer("M2")?;
        for name in ["PROP1", "PROP2", "PROP3", "PROP4", "PROP5"] {
            reader.integer(name)?;
        }
        let header_line = params[0].line;
        for (k, m, name) in [(k1, m1, "first"), (k2, m2, "second")] {
            if m > MAX_DEGREE {
                return Err(syntax(
                    header_line,
                    format!(
                        "entity 128 at DE {de}: degree {m} in the {name} direction, above the \
                         largest read, {MAX_DEGREE} (a point costs about degree² operations; CAD \
                         systems stop far below): rebuild the surface at a lower degree"
                    ),
                ));
            }
            if m == 0 || k < m {
                return Err(syntax(
                    header_line,
                    format!(
                        "entity 128 at DE {de}: degree {m} with {} control points in the {name} direction; \
                         the degree must be at least 1 and below the control point count",
                        k.saturating_add(1)
                    ),
                ));
            }
        }
        let (count_u, count_v) = (k1.saturating_add(1), k2.saturating_add(1));
        let needed = [
            count_u.saturating_add(m1).saturating_add(1),
            count_v.saturating_add(m2).saturating_add(1),
            count_u.saturating_mul(count_v).saturating_mul(4),
            13,
        ]
        .into_iter()
        .fold(0usize, usize::saturating_add);
        let found = params.len() - 1;
        if found < needed {
            return Err(IoError::CountMismatch {
                file: NO_FILE.into(),
                what: format!(
                    "parameters of entity 128 at DE {de} (line {}) for {count_u} × {count_v} control points of degree ({m1}, {m2})",
                    header_line
                ),
                expected: needed,
                found,
            });
        }
        let knots_u = reader.knots(count_u + m1 + 1, "S")?;
        let knots_v = reader.knots(count_v + m2 + 1, "T")?;
        for (knots, m, count, name) in [(&knots_u, m1, count_u, "S"), (&knots_v, m2, count_v, "T")]
        {
            if knots[m] >= knots[count] {
                return Err(syntax(
                    header_line,
                    format!(
                        "entity 128 at DE {de}: the {name} knots leave an empty domain [{}, {}]",
                        knots[m], knots[count]
                    ),
                ));
            }
        }
        let n = count_u * count_v;
        // IGES order (first index fastest) to row-major (a * count_v + b).
        let row_major = |k: usize| (k % count_u) * count_v + k / count_u;
        let mut weights = vec![0.0; n];
        for k in 0..n {
            let line = reader.line();
            let w = reader.real("weight")?;
            if w <= 0.0 {
                return Err(syntax(
                    line,
                    format!("entity 128 at DE {de}: weight {w} is not positive"),
                ));
            }
            weights[row_major(k)] = w;
        }
        let mut control_points = vec![DVec3::ZERO; n];
        for k in 0..n {
            control_points[row_major(k)] = reader.point("control point")?;
        }
        let range_u = [reader.real("U0")?, reader.real("U1")?];
        let range_v = [reader.real("V0")?, reader.real("V1")?];
        let transform = self.transform(de, &entry, pdelim, rdelim)?;
        for p in &mut control_points {
            *p = transform(*p);
        }
        Ok(IgesSurface {
            degree_u: m1,
            degree_v: m2,
            count_u,
            count_v,
            knots_u,
            knots_v,
            weights,
            control_points,
            range_u,
            range_v,
        })
    }

    /// The map of the transformation matrices (entity 124) from the entity at
    /// `de` outwards: its matrix, then that matrix's matrix, and so on.
    fn transform(
        &self,
        de: usize,
        entry: &Entry,
        pdelim: char,
        rdelim: char,
    ) -> Result<impl Fn(DVec3) -> DVec3, IoError> {
        let mut matrices: Vec<[DVec3; 4]> = Vec::new();
        let (mut from, mut pointer) = (de, entry.transform_pointer);
        while pointer != 0 {
            let from_line = self.directory[from - 1].number;
            if matrices.len() == MAX_TRANSFORM_CHAIN {
                return Err(syntax(
                    from_line,
                    format!("more than {MAX_TRANSFORM_CHAIN} chained transformation matrices (a cycle?)"),
                ));
            }
            let target = usize::try_from(pointer)
                .ok()
                .filter(|&t| t % 2 == 1 && t < self.directory.len());
            let Some(target) = target else {
                return Err(syntax(
                    from_line,
                    format!("entity at DE {from}: transformation matrix pointer {pointer} is not a Directory Entry"),
                ));
            };
            let matrix_entry = self.entry(target)?;
            if matrix_entry.entity_type != 124 {
                return Err(syntax(
                    from_line,
                    format!(
                        "entity at DE {from}: transformation matrix pointer {pointer} names an entity {}, not 124",
                        matrix_entry.entity_type
                    ),
                ));
            }
            let params = self.parameters(target, &matrix_entry, pdelim, rdelim)?;
            let mut reader = Reader {
                params: &params,
                next: 0,
                de: target,
            };
            reader.entity_type(124)?;
            // Rows (R_i1, R_i2, R_i3, T_i) for i = 1, 2, 3.
            let rows = [reader.row()?, reader.row()?, reader.row()?];
            matrices.push([
                DVec3::new(rows[0][0], rows[1][0], rows[2][0]),
                DVec3::new(rows[0][1], rows[1][1], rows[2][1]),
                DVec3::new(rows[0][2], rows[1][2], rows[2][2]),
                DVec3::new(rows[0][3], rows[1][3], rows[2][3]),
            ]);
            (from, pointer) = (target, matrix_entry.transform_pointer);
        }
        Ok(move |p: DVec3| {
            matrices.iter().fold(p, |p, [c1, c2, c3, t]| {
                *c1 * p.x + *c2 * p.y + *c3 * p.z + *t
            })
        })
    }
}

/// The Hollerith string of one character at the start of `text` (`1H,`), if any.
fn hollerith_char(text: &str, line: usize) -> Result<Option<char>, IoError> {
    if !text.starts_with("1H") && !text.starts_with("1h") {
        return Ok(None);
    }
    text[2..]
        .chars()
        .next()
        .map(Some)
        .ok_or_else(|| syntax(line, "the Global section ends inside a delimiter `1H`"))
}

/// Reads an entity's parameters in order.
struct Reader<'p> {
    params: &'p [Parameter],
    next: usize,
    de: usize,
}

impl Reader<'_> {
    /// The line of the next parameter (of the last one if none is left).
    fn line(&self) -> usize {
        self.params[self.next.min(self.params.len() - 1)].line
    }

    /// The next parameter, or a [`IoError::CountMismatch`].
    fn take(&mut self, what: &str) -> Result<&Parameter, IoError> {
        let found = self.params.len() - 1;
        let p = self
            .params
            .get(self.next)
            .ok_or_else(|| IoError::CountMismatch {
                file: NO_FILE.into(),
                what: format!(
                    "parameters of the entity at DE {} (line {}), up to its {what}",
                    self.de, self.params[0].line
                ),
                expected: self.next,
                found,
            })?;
        self.next += 1;
        Ok(p)
    }

    fn entity_type(&mut self, expected: i64) -> Result<(), IoError> {
        let de = self.de;
        let p = self.take("entity type")?;
        if p.text.parse::<i64>().ok() != Some(expected) {
            return Err(syntax(
                p.line,
                format!(
                    "parameter data of DE {de} starts with `{}`; expected its entity type {expected}",
                    p.text
                ),
            ));
        }
        Ok(())
    }

    fn integer(&mut self, name: &str) -> Result<usize, IoError> {
        let de = self.de;
        let p = self.take(name)?;
        p.text.parse().map_err(|_| {
            syntax(
                p.line,
                format!(
                    "{name} of the entity at DE {de} is `{}`, not a non-negative integer",
                    p.text
                ),
            )
        })
    }

    fn real(&mut self, name: &str) -> Result<f64, IoError> {
        let de = self.de;
        let p = self.take(name)?;
        parse_real(&p.text).ok_or_else(|| {
            syntax(
                p.line,
                format!(
                    "{name} of the entity at DE {de} is `{}`, not a finite real number",
                    p.text
                ),
            )
        })
    }

    fn point(&mut self, name: &str) -> Result<DVec3, IoError> {
        Ok(DVec3::new(
            self.real(name)?,
            self.real(name)?,
            self.real(name)?,
        ))
    }

    fn row(&mut self) -> Result<[f64; 4], IoError> {
        let name = "transformation matrix entry";
        Ok([
            self.real(name)?,
            self.real(name)?,
            self.real(name)?,
            self.real(name)?,
        ])
    }

    /// `count` non-decreasing knots.
    fn knots(&mut self, count: usize, name: &str) -> Result<Vec<f64>, IoError> {
        let mut knots: Vec<f64> = Vec::with_capacity(count);
        for _ in 0..count {
            let line = self.line();
            let k = self.real(&format!("{name} knot"))?;
            if knots.last().is_some_and(|&last| k < last) {
                return Err(syntax(
                    line,
                    format!(
                        "entity 128 at DE {}: {name} knot {k} is below the one before it",
                        self.de
                    ),
                ));
            }
            knots.push(k);
        }
        Ok(knots)
    }
}

/// An IGES real (`1.5`, `-2.`, `.5`, `1.5E3`, `1.5D-3`, `7`), if it is one and finite.
fn parse_real(text: &str) -> Option<f64> {
    let valid = !text.is_empty()
        && text.bytes().all(|b| {
            b.is_ascii_digit() || matches!(b, b'+' | b'-' | b'.' | b'E' | b'e' | b'D' | b'd')
        });
    if !valid {
        return None;
    }
    let x: f64 = text.replace(['D', 'd'], "E").parse().ok()?;
    x.is_finite().then_some(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn more_lines_than_a_section_can_number_are_refused() {
        // 1415 × 1415 faces of cyclidic patches: 2831 × 2831 control points,
        // about 10.7 million lines (what the first pass counts).
        assert!(check_lines(MAX_SEQUENCE, (2831, 2831)).is_ok());
        let e = check_lines(10_700_000, (2831, 2831)).unwrap_err();
        assert!(
            e.contains("2831 × 2831 control points takes 10700000 lines")
                && e.contains("more than the 9999999")
                && e.contains("fewer guide samples"),
            "{e}"
        );
    }

    /// `{:E}` (the standard library's shortest digits) with `.0` added to a lone digit.
    fn std_real(x: f64) -> String {
        let s = format!("{x:E}");
        match s.find('.') {
            Some(_) => s,
            None => s.replacen('E', ".0E", 1),
        }
    }

    #[test]
    fn reals_are_the_standard_librarys_shortest_digits_in_e_notation() {
        let mut r = Real::default();
        let special = [
            0.0,
            -0.0,
            1.0,
            -2.5e-1,
            0.1,
            1e-7,
            1e15,
            1e16,
            1e17,
            123456789012345680.0,
            1234567890123456.7,
            0.000123,
            f64::MAX,
            f64::MIN_POSITIVE,
            5e-324,
            9007199254740993.0,
        ];
        // Random bit patterns (a fixed xorshift sequence), every exponent, and
        // integers and short decimals, which zmij writes without an exponent.
        let mut state = 0x9e3779b97f4a7c15u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        let mut values: Vec<f64> = special.to_vec();
        for _ in 0..200_000 {
            let x = f64::from_bits(next());
            if x.is_finite() {
                values.push(x);
            }
            values.push((next() % 100_000_000) as f64 / 1000.0);
            values.push((next() >> 11) as f64 * 10f64.powi((next() % 40) as i32 - 20));
        }
        for x in values {
            let (ours, std) = (std::str::from_utf8(r.format(x)).unwrap(), std_real(x));
            if ours != std {
                // Two shortest decimals equally near x: both read back to x,
                // have the same length, and ours ends in the even digit.
                assert_eq!(ours.len(), std.len(), "{x:?}");
                assert_eq!(ours.parse::<f64>().unwrap(), x, "{x:?}");
                assert_eq!(std.parse::<f64>().unwrap(), x, "{x:?}");
                let last = |s: &str| s.split('E').next().unwrap().bytes().last().unwrap();
                assert_eq!(last(ours) % 2, 0, "{x:?}: {ours} vs {std}");
            }
        }
    }
}
