//! Reading IGES 5.3 fixed ASCII files: the sections, the Directory Entries,
//! each entity 128 with its transformation matrices (entity 124) applied.

use glam::DVec3;
use monge_core::guide::MAX_DEGREE;

use super::fields::PARAMETER_COLUMNS;
use super::params::{syntax, Parameter, Reader, NO_FILE};
use super::surface::IgesSurface;
use crate::error::IoError;

/// Deepest chain of transformation matrices followed by the reader.
const MAX_TRANSFORM_CHAIN: usize = 64;

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
    ) -> Result<impl Fn(DVec3) -> DVec3 + use<>, IoError> {
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
