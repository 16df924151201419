//! PLY, ASCII or binary little-endian, any scalar types: the header, its
//! counts checked against the file's size, then the records.

use std::io::{self, BufRead, Read};

use glam::DVec3;

use super::grid::{parse_shape, Keep, RawMesh};
use super::lines::{read_failed, Lines};
use crate::error::IoError;

/// A PLY scalar type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    /// The type named `name` (both the original and the sized names).
    fn from_name(name: &str) -> Option<Scalar> {
        Some(match name {
            "char" | "int8" => Scalar::I8,
            "uchar" | "uint8" => Scalar::U8,
            "short" | "int16" => Scalar::I16,
            "ushort" | "uint16" => Scalar::U16,
            "int" | "int32" => Scalar::I32,
            "uint" | "uint32" => Scalar::U32,
            "float" | "float32" => Scalar::F32,
            "double" | "float64" => Scalar::F64,
            _ => return None,
        })
    }

    fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    /// The little-endian value at the start of `b` (at least [`Scalar::size`] bytes), exactly.
    fn read_le(self, b: &[u8]) -> f64 {
        match self {
            Scalar::I8 => f64::from(b[0] as i8),
            Scalar::U8 => f64::from(b[0]),
            Scalar::I16 => f64::from(i16::from_le_bytes([b[0], b[1]])),
            Scalar::U16 => f64::from(u16::from_le_bytes([b[0], b[1]])),
            Scalar::I32 => f64::from(i32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            Scalar::U32 => f64::from(u32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            Scalar::F32 => f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            Scalar::F64 => f64::from_le_bytes(b[..8].try_into().expect("8 bytes")),
        }
    }
}

/// A PLY property: its name, and its type (a list's length type and item type).
struct Property {
    name: String,
    list: Option<Scalar>,
    scalar: Scalar,
    /// The 1-based header line declaring it.
    line: usize,
}

/// A PLY element declared in the header.
struct Element {
    name: String,
    count: usize,
    properties: Vec<Property>,
    /// The 1-based header line declaring it.
    line: usize,
}

impl Element {
    /// The fewest bytes one record of this element takes in `encoding`: in
    /// ASCII a value and a separator per property (a list at least its
    /// length), at least a line break; in binary the scalars' sizes (a
    /// list at least its length).
    fn min_record_bytes(&self, encoding: Encoding) -> u64 {
        match encoding {
            Encoding::Ascii => (2 * self.properties.len() as u64).max(1),
            Encoding::BinaryLittleEndian => self
                .properties
                .iter()
                .map(|p| p.list.unwrap_or(p.scalar).size() as u64)
                .sum(),
        }
    }
}

/// The body encodings of PLY that can be read.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Encoding {
    Ascii,
    BinaryLittleEndian,
}

/// A PLY header: the encoding, the elements, the grid shape from the comment,
/// the number of header lines and bytes.
struct PlyHeader {
    encoding: Encoding,
    elements: Vec<Element>,
    shape: Option<(usize, usize)>,
    lines: usize,
    bytes: usize,
}

fn parse_ply_header(lines: &mut Lines<'_, impl BufRead>, file: &str) -> Result<PlyHeader, IoError> {
    let syntax_at = |number: usize, message: String| IoError::Syntax {
        file: file.to_owned(),
        line: number + 1,
        message,
    };
    let mut header = PlyHeader {
        encoding: Encoding::Ascii,
        elements: Vec::new(),
        shape: None,
        lines: 0,
        bytes: 0,
    };
    loop {
        let Some((number, line)) = lines.next_line()? else {
            return Err(syntax_at(
                lines.number,
                "the header has no `end_header`".to_owned(),
            ));
        };
        let n = number - 1;
        let line = std::str::from_utf8(line)
            .map_err(|_| syntax_at(n, "the header is not text".to_owned()))?;
        let syntax = |message: String| syntax_at(n, message);
        if n == 0 {
            if line.trim() != "ply" {
                return Err(syntax("expected `ply` on the first line".to_owned()));
            }
            continue;
        }
        let mut tokens = line.split_whitespace();
        match tokens.next() {
            Some("format") => {
                header.encoding = match tokens.next().unwrap_or("") {
                    "ascii" => Encoding::Ascii,
                    "binary_little_endian" => Encoding::BinaryLittleEndian,
                    other => {
                        return Err(syntax(format!(
                            "only ASCII and binary_little_endian PLY can be read, this file is \
                             `{other}`; convert it with e.g. `plyfile` or MeshLab"
                        )))
                    }
                };
            }
            Some("comment") => {
                let comment = line.trim_start().strip_prefix("comment").unwrap_or("");
                if let Some(shape) = parse_shape(comment, &syntax)? {
                    header.shape = Some(shape);
                }
            }
            Some("element") => {
                let name = tokens.next().unwrap_or("").to_owned();
                let count = tokens
                    .next()
                    .and_then(|c| c.parse().ok())
                    .ok_or_else(|| syntax(format!("expected `element {name} COUNT`")))?;
                header.elements.push(Element {
                    name,
                    count,
                    properties: Vec::new(),
                    line: number,
                });
            }
            Some("property") => {
                let element = header
                    .elements
                    .last_mut()
                    .ok_or_else(|| syntax("a property before any element".to_owned()))?;
                let words: Vec<&str> = tokens.collect();
                let scalar = |t: &str| {
                    Scalar::from_name(t).ok_or_else(|| {
                        syntax(format!(
                            "unknown PLY type `{t}` in `{}`; the types are char, uchar, short, \
                             ushort, int, uint, float and double",
                            line.trim()
                        ))
                    })
                };
                let property = match words.as_slice() {
                    ["list", len, item, name] => Property {
                        name: (*name).to_owned(),
                        list: Some(match scalar(len)? {
                            Scalar::F32 | Scalar::F64 => {
                                return Err(syntax(format!(
                                    "a list's length is a whole number, not `{len}`, in `{}`: \
                                     declare it as e.g. `property list uchar {item} {name}`",
                                    line.trim()
                                )))
                            }
                            t => t,
                        }),
                        scalar: scalar(item)?,
                        line: number,
                    },
                    [t, name] => Property {
                        name: (*name).to_owned(),
                        list: None,
                        scalar: scalar(t)?,
                        line: number,
                    },
                    _ => return Err(syntax(format!("cannot read `{}`", line.trim()))),
                };
                element.properties.push(property);
            }
            Some("end_header") => {
                header.lines = number;
                header.bytes = lines.bytes;
                return Ok(header);
            }
            _ => {}
        }
    }
}

/// What a PLY element's records give: where their values are among its properties.
enum Slots {
    /// The `vertex` element: where `x y z` are, and `nx ny nz` if given.
    Vertex {
        xyz: [usize; 3],
        normal: Option<[usize; 3]>,
    },
    /// The `face` element of a mesh: where its corner list is, and whether its faces
    /// are polygons of any number of corners ([`Keep::Polygons`]) rather than quads.
    Face { indices: usize, polygons: bool },
    /// Any other element, or the faces of a point cloud: read past.
    Other,
}

impl Slots {
    /// Where `element`'s values are, checked before any record is read: a
    /// `vertex` element needs `x`, `y` and `z`, and they (and `nx ny nz`)
    /// must be single numbers; the `face` element of a mesh needs the list
    /// `vertex_indices` (or `vertex_index`).
    fn of(element: &Element, keep: Keep, file: &str) -> Result<Slots, IoError> {
        let syntax = |line: usize, message: String| IoError::Syntax {
            file: file.to_owned(),
            line,
            message,
        };
        let find = |name: &str| element.properties.iter().position(|p| p.name == name);
        let scalar = |k: usize| {
            let p = &element.properties[k];
            match p.list {
                None => Ok(k),
                Some(_) => Err(syntax(
                    p.line,
                    format!(
                        "the `{}` property `{}` is a list; coordinates and normals are one \
                         number each: declare it as `property double {}` (or float)",
                        element.name, p.name, p.name
                    ),
                )),
            }
        };
        let three = |names: [&str; 3]| -> Result<Option<[usize; 3]>, IoError> {
            match names.map(find) {
                [Some(a), Some(b), Some(c)] => Ok(Some([scalar(a)?, scalar(b)?, scalar(c)?])),
                _ => Ok(None),
            }
        };
        if element.count == 0 {
            return Ok(Slots::Other);
        }
        match element.name.as_str() {
            "vertex" => {
                let Some(xyz) = three(["x", "y", "z"])? else {
                    let missing = ["x", "y", "z"].into_iter().find(|n| find(n).is_none());
                    return Err(syntax(
                        element.line,
                        format!(
                            "the `vertex` element has no property `{}`; vertices need `x`, `y` and `z`",
                            missing.unwrap_or("x")
                        ),
                    ));
                };
                let normal = three(["nx", "ny", "nz"])?;
                Ok(Slots::Vertex { xyz, normal })
            }
            "face" if keep != Keep::Points => {
                let Some(k) = find("vertex_indices").or_else(|| find("vertex_index")) else {
                    return Err(syntax(
                        element.line,
                        "the `face` element has no property `vertex_indices`".to_owned(),
                    ));
                };
                let p = &element.properties[k];
                if p.list.is_none() {
                    return Err(syntax(
                        p.line,
                        format!(
                            "the `face` property `{}` is a single number; a face's corners are \
                             a list: `property list uchar int {}`",
                            p.name, p.name
                        ),
                    ));
                }
                Ok(Slots::Face {
                    indices: k,
                    polygons: keep == Keep::Polygons,
                })
            }
            _ => Ok(Slots::Other),
        }
    }

    /// Adds one record to `raw`: property `k`'s values (a list's items after
    /// its length) are `values[ranges[k].0..ranges[k].1]`.
    fn add(
        &self,
        values: &[f64],
        ranges: &[(usize, usize)],
        raw: &mut RawMesh,
    ) -> Result<(), String> {
        // Every slot is a single number (checked by `Slots::of`).
        let value = |k: usize| {
            let x = values[ranges[k].0];
            if x.is_finite() {
                Ok(x)
            } else {
                Err(format!("`{x}` is not a finite number"))
            }
        };
        let point = |[a, b, c]: [usize; 3]| -> Result<DVec3, String> {
            Ok(DVec3::new(value(a)?, value(b)?, value(c)?))
        };
        match *self {
            Slots::Vertex { xyz, normal } => {
                raw.vertices.push(point(xyz)?);
                if let Some(normal) = normal {
                    raw.normals.push(point(normal)?);
                }
            }
            Slots::Face { indices, polygons } => {
                let corners = &values[ranges[indices].0..ranges[indices].1];
                let corner = |c: f64| {
                    if c < 0.0 || c.fract() != 0.0 {
                        Err(format!("expected a vertex index, found `{c}`"))
                    } else {
                        Ok(c as usize)
                    }
                };
                if polygons {
                    let face = corners
                        .iter()
                        .map(|c| corner(*c))
                        .collect::<Result<Vec<_>, _>>()?;
                    if face.len() < 3 || face.iter().any(|k| *k >= raw.vertices.len()) {
                        return Err(format!(
                            "a face with corners {face:?} (0-based), not three or more of the {} vertices",
                            raw.vertices.len()
                        ));
                    }
                    raw.polygons.push(face);
                    return Ok(());
                }
                if corners.len() != 4 {
                    return Err(format!(
                        "a face with {} corners; a quad grid has faces with 4",
                        corners.len()
                    ));
                }
                let mut face = [0; 4];
                for (slot, &c) in face.iter_mut().zip(corners) {
                    *slot = corner(c)?;
                }
                raw.faces.push(face);
            }
            Slots::Other => {}
        }
        Ok(())
    }
}

/// Refuses a PLY header whose element counts need more bytes than the
/// `remaining` ones after it, before any record is read (so that no count
/// drives the work or the memory beyond what the file holds).
fn check_counts(header: &PlyHeader, remaining: u64, file: &str) -> Result<(), IoError> {
    // An ASCII file's last line may lack its line break.
    let slack = u128::from(header.encoding == Encoding::Ascii);
    let mut needed: u128 = 0;
    for (k, e) in header.elements.iter().enumerate() {
        let min = e.min_record_bytes(header.encoding);
        needed += e.count as u128 * u128::from(min);
        if needed > u128::from(remaining) + slack {
            let before = if k == 0 {
                ""
            } else {
                " with the records declared before them"
            };
            let encoding = match header.encoding {
                Encoding::Ascii => "in ASCII",
                Encoding::BinaryLittleEndian => "in binary",
            };
            return Err(IoError::Syntax {
                file: file.to_owned(),
                line: e.line,
                message: format!(
                    "`element {} {}` does not fit in the file: {} records of at least {min} bytes \
                     each ({encoding}){before} need more than the {remaining} bytes after the \
                     header; the count is wrong or the file is cut short",
                    e.name, e.count, e.count
                ),
            });
        }
    }
    Ok(())
}

/// Reads the PLY file from `reader` (`size` bytes long, when known).
pub(super) fn parse_ply(
    reader: impl BufRead,
    file: &str,
    size: Option<u64>,
    keep: Keep,
) -> Result<RawMesh, IoError> {
    let mut lines = Lines::new(reader, file);
    let header = parse_ply_header(&mut lines, file)?;
    if let Some(size) = size {
        check_counts(&header, size.saturating_sub(header.bytes as u64), file)?;
    }
    let slots = header
        .elements
        .iter()
        .map(|e| Slots::of(e, keep, file))
        .collect::<Result<Vec<_>, _>>()?;
    let mut raw = RawMesh {
        shape: header.shape,
        ..RawMesh::default()
    };
    match header.encoding {
        Encoding::Ascii => parse_ply_ascii(&mut lines, &header, &slots, file, &mut raw)?,
        Encoding::BinaryLittleEndian => {
            parse_ply_binary(&mut lines.reader, &header, &slots, file, &mut raw)?
        }
    }
    Ok(raw)
}

fn parse_ply_ascii(
    lines: &mut Lines<'_, impl BufRead>,
    header: &PlyHeader,
    slots: &[Slots],
    file: &str,
    raw: &mut RawMesh,
) -> Result<(), IoError> {
    let mut values: Vec<f64> = Vec::new();
    let mut ranges: Vec<(usize, usize)> = Vec::new();
    for (element, slots) in header.elements.iter().zip(slots) {
        for _ in 0..element.count {
            let last = lines.number;
            let syntax = |line: usize, message: String| IoError::Syntax {
                file: file.to_owned(),
                line,
                message,
            };
            let Some((n, line)) = lines.next_line()? else {
                return Err(syntax(
                    last + 1,
                    format!(
                        "the file ends before all {} `{}` lines",
                        element.count, element.name
                    ),
                ));
            };
            let line = std::str::from_utf8(line)
                .map_err(|e| syntax(n, format!("an ASCII PLY body that is not text: {e}")))?;
            ply_values(line, &element.properties, &mut values, &mut ranges)
                .map_err(|m| syntax(n, m))?;
            slots.add(&values, &ranges, raw).map_err(|m| syntax(n, m))?;
        }
    }
    Ok(())
}

/// The values of each property of one ASCII element line into `values`, and
/// into `ranges` where each property's values are (a list's items, after its length).
fn ply_values(
    line: &str,
    properties: &[Property],
    values: &mut Vec<f64>,
    ranges: &mut Vec<(usize, usize)>,
) -> Result<(), String> {
    values.clear();
    ranges.clear();
    let mut tokens = line.split_ascii_whitespace();
    let mut next = || {
        tokens
            .next()
            .ok_or_else(|| "too few values on the line".to_owned())
    };
    for property in properties {
        let first = next()?;
        let start = values.len();
        if property.list.is_some() {
            let len: usize = first
                .parse()
                .map_err(|_| format!("expected a list length, found `{first}`"))?;
            for _ in 0..len {
                values.push(parse_number(next()?)?);
            }
        } else {
            values.push(parse_number(first)?);
        }
        ranges.push((start, values.len()));
    }
    Ok(())
}

/// A number (not necessarily finite: the caller says which must be).
fn parse_number(token: &str) -> Result<f64, String> {
    token
        .parse::<f64>()
        .map_err(|_| format!("expected a number, found `{token}`"))
}

fn parse_ply_binary(
    body: &mut impl Read,
    header: &PlyHeader,
    slots: &[Slots],
    file: &str,
    raw: &mut RawMesh,
) -> Result<(), IoError> {
    let mut at = 0;
    let error = |offset: usize, message: String| IoError::Binary {
        file: file.to_owned(),
        offset: header.bytes + offset,
        message,
    };
    let mut values: Vec<f64> = Vec::new();
    let mut ranges: Vec<(usize, usize)> = Vec::new();
    let mut scratch = [0u8; 8];
    for (element, slots) in header.elements.iter().zip(slots) {
        if element.properties.is_empty() {
            continue; // records of no bytes: nothing to read, however many
        }
        for record in 0..element.count {
            let start = at;
            let mut read = |scalar: Scalar, at: &mut usize| -> Result<f64, IoError> {
                let b = &mut scratch[..scalar.size()];
                body.read_exact(b).map_err(|source| {
                    if source.kind() == io::ErrorKind::UnexpectedEof {
                        error(
                            *at,
                            format!(
                                "the file ends in `{}` record {record} of {}",
                                element.name, element.count
                            ),
                        )
                    } else {
                        read_failed(file, source)
                    }
                })?;
                *at += scalar.size();
                Ok(scalar.read_le(b))
            };
            values.clear();
            ranges.clear();
            for property in &element.properties {
                let first = values.len();
                match property.list {
                    Some(len_type) => {
                        let len = read(len_type, &mut at)?;
                        if len < 0.0 {
                            return Err(error(at, format!("a list of length {len}")));
                        }
                        for _ in 0..len as usize {
                            values.push(read(property.scalar, &mut at)?);
                        }
                    }
                    None => values.push(read(property.scalar, &mut at)?),
                }
                ranges.push((first, values.len()));
            }
            slots
                .add(&values, &ranges, raw)
                .map_err(|message| error(start, message))?;
        }
    }
    Ok(())
}
