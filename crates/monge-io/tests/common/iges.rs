//! Hand-written IGES files for the reader and writer tests.

use monge_io::{read_iges_surfaces, IgesSurface};

/// One 80-column line.
pub fn line(data: &str, section: char, sequence: usize) -> String {
    assert!(data.len() <= 72, "test data too long: {data}");
    format!("{data:<72}{section}{sequence:>7}\n")
}

/// An entity for [`file`]: type, transformation matrix pointer, parameter lines.
pub struct Entity<'a> {
    pub kind: i64,
    pub transform: usize,
    pub lines: &'a [&'a str],
}

pub fn entity<'a>(kind: i64, lines: &'a [&'a str]) -> Entity<'a> {
    Entity {
        kind,
        transform: 0,
        lines,
    }
}

/// A complete file: one Start line, `global` as the Global section (one line),
/// the entities' Directory Entries (DE 1, 3, 5, …) and Parameter Data, Terminate.
pub fn file_with_global(global: &str, entities: &[Entity]) -> String {
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

pub fn file(entities: &[Entity]) -> String {
    file_with_global(GLOBAL, entities)
}

pub fn parameters(n: usize) -> impl Iterator<Item = (f64, f64)> {
    (0..=n).flat_map(move |a| (0..=n).map(move |b| (a as f64 / n as f64, b as f64 / n as f64)))
}

pub fn one(text: &str) -> IgesSurface {
    let mut surfaces = read_iges_surfaces(text).unwrap();
    assert_eq!(surfaces.len(), 1);
    surfaces.pop().unwrap()
}

/// The hyperbolic paraboloid `(u, 3v, uv/2)`, `u ∈ [0, 2]`, `v ∈ [0, 1]`, as a
/// degree-(1, 1) NURBS: corners (0,0,0), (2,0,0), (0,3,0), (2,3,1) in IGES order,
/// wrapped over several lines, `D` and `E` exponents, blanks around numbers.
pub const BILINEAR: &[&str] = &[
    "128,1,1,1,1,0,0,1,0,0,",
    "0.0, 0.0 ,2.0D0,2.,0,0,1.0E0,1,",
    "1.D0,1.0,1.0,1.0,",
    "0.,0.,0.,2.0D+00,0.0,0.0,0.0,3.0,0.0,",
    "2.0,3.0,1.0,0.0,2.0,0.0,1.0;",
];
