//! Mesh readers: grid shape, checks, and clear errors.

use crate::common;

use std::io::{self, Read};
use std::path::Path;

use common::{assert_bits_eq, random_grid};
use glam::DVec3;
use monge_io::{read_mesh, read_mesh_from, IoError, MeshFormat};

fn obj(text: &str) -> Result<monge_core::QuadGrid, IoError> {
    read_mesh_from(text.as_bytes(), MeshFormat::Obj)
}

fn ply(text: &str) -> Result<monge_core::QuadGrid, IoError> {
    read_mesh_from(text.as_bytes(), MeshFormat::Ply)
}

/// OBJ `v` lines for `n` vertices `(k, 0, 0)`.
fn v_lines(n: usize) -> String {
    (0..n).map(|k| format!("v {k} 0 0\n")).collect()
}

/// The faces of a `rows × cols` grid, 1-based, each transformed by `f`.
fn f_lines(rows: usize, cols: usize, f: impl Fn([usize; 4]) -> [usize; 4]) -> String {
    let mut s = String::new();
    for i in 0..rows - 1 {
        for j in 0..cols - 1 {
            let k = i * cols + j + 1;
            let [a, b, c, d] = f([k, k + cols, k + cols + 1, k + 1]);
            s += &format!("f {a} {b} {c} {d}\n");
        }
    }
    s
}

#[test]
fn obj_shape_is_inferred_from_faces_without_the_comment() {
    let rotate = |[a, b, c, d]: [usize; 4]| [c, d, a, b];
    let reverse = |[a, b, c, d]: [usize; 4]| [a, d, c, b];
    for f in [
        &(|x| x) as &dyn Fn([usize; 4]) -> [usize; 4],
        &rotate,
        &reverse,
    ] {
        let text = format!("o thing\n{}vt 0 0\n{}", v_lines(12), f_lines(3, 4, f));
        let grid = obj(&text).unwrap();
        assert_eq!((grid.rows, grid.cols), (3, 4));
        assert_eq!(grid.vertex(2, 1), DVec3::new(9.0, 0.0, 0.0));
        assert!(grid.normals.is_empty());
    }
}

#[test]
fn obj_faces_may_come_in_any_order_with_any_index_style() {
    let mut faces: Vec<String> = f_lines(3, 3, |x| x).lines().map(String::from).collect();
    faces.swap(1, 3);
    faces[2] = "f 4/1 5/1 -2/2 -3/3".to_owned(); // face (1, 0), reversed, with texture and relative indices
    let text = format!(
        "# monge quad grid rows=3 cols=3\n{}{}\n",
        v_lines(9),
        faces.join("\r\n")
    );
    let grid = obj(&text).unwrap();
    assert_eq!((grid.rows, grid.cols), (3, 3));
}

#[test]
fn obj_with_comment_needs_no_faces() {
    let grid = obj(&format!("# monge quad grid rows=2 cols=3\n{}", v_lines(6))).unwrap();
    assert_eq!((grid.rows, grid.cols), (2, 3));
}

#[test]
fn obj_normals_are_read_in_vertex_order() {
    let grid = random_grid(3, 2, true, 8);
    let mut out = Vec::new();
    monge_io::write_obj(&grid, &mut out).unwrap();
    let text = String::from_utf8(out).unwrap();
    assert_bits_eq(&obj(&text).unwrap(), &grid);

    let swapped = text.replacen("f 1//1 ", "f 1//2 ", 1);
    let err = obj(&swapped).unwrap_err();
    assert!(matches!(err, IoError::Syntax { .. }), "{err:?}");
    assert_eq!(
        err.to_string(),
        format!(
            "<stdin>:{}: face corner `1//2` uses normal 2 for vertex 1; normals must be in vertex order",
            text.lines().position(|l| l.starts_with("f ")).unwrap() + 1
        )
    );
}

#[test]
fn obj_not_a_grid() {
    // First face is not the corner face of a row-major grid.
    let err = obj(&format!("{}f 2 6 7 3\n", v_lines(8))).unwrap_err();
    assert!(matches!(err, IoError::NotAGrid { .. }), "{err:?}");
    assert!(
        err.to_string().starts_with(
            "<stdin>: not a regular row-major quad grid: the first face is (1, 5, 6, 2)"
        ),
        "{err}"
    );

    // A face that is not a grid quad.
    let text = format!("{}{}f 2 6 8 3\n", v_lines(8), f_lines(2, 4, |x| x));
    let err = obj(&text).unwrap_err();
    assert_eq!(
        err.to_string(),
        "<stdin>: not a regular row-major quad grid: face 4 (1, 5, 7, 2) is not a quad \
         (i, j), (i+1, j), (i+1, j+1), (i, j+1) of a 2 × 4 grid (0-based)"
    );

    // A repeated face, a missing face, a vertex out of range.
    let faces = f_lines(3, 3, |x| x);
    let first = faces.lines().next().unwrap();
    let err = obj(&format!("{}{faces}{first}\n", v_lines(9))).unwrap_err();
    assert!(
        err.to_string()
            .ends_with("face 5 (0, 3, 4, 1) repeats grid face (0, 0)"),
        "{err}"
    );
    let three: String = faces.lines().take(3).map(|l| format!("{l}\n")).collect();
    let err = obj(&format!("{}{three}", v_lines(9))).unwrap_err();
    assert!(
        err.to_string().ends_with("3 faces, but a 3 × 3 grid has 4"),
        "{err}"
    );
    let err = obj(&format!(
        "# monge quad grid rows=2 cols=2\n{}f 1 3 4 9\n",
        v_lines(4)
    ))
    .unwrap_err();
    assert!(
        err.to_string().ends_with(
            "face 1 (0, 2, 3, 8) refers to vertex 8, but there are 4 vertices (0-based)"
        ),
        "{err}"
    );

    // Vertex count not a whole number of rows.
    let err = obj(&format!("{}{}", v_lines(9), f_lines(2, 4, |x| x))).unwrap_err();
    assert!(
        err.to_string().ends_with(
            "the first face (0, 4, 5, 1) implies 4 columns, but 9 vertices are not whole rows of 4"
        ),
        "{err}"
    );

    // No shape at all.
    let err = obj(&v_lines(4)).unwrap_err();
    assert!(
        err.to_string().contains("the grid shape is unknown"),
        "{err}"
    );
}

/// Found by the `mesh_obj` fuzz target: an empty grid with a huge column count
/// was read, and measuring it asked for a vector of `cols` points (capacity
/// overflow). An empty grid is refused.
#[test]
fn an_empty_grid_is_refused() {
    for text in [
        "# monge quad grid rows=0 cols=3333333333333333333 ",
        "# monge quad grid rows=3 cols=0\n",
    ] {
        let err = obj(text).unwrap_err();
        assert!(matches!(err, IoError::NotAGrid { .. }), "{err:?}");
        assert!(err.to_string().contains("the grid is empty"), "{err}");
    }
    let err = read_mesh_from(
        b"{\"rows\": 0, \"cols\": 4, \"vertices\": []}".as_slice(),
        MeshFormat::Json,
    )
    .unwrap_err();
    assert!(err.to_string().contains("the grid is empty"), "{err}");
}

#[test]
fn obj_count_mismatch_with_comment() {
    let err = obj(&format!("# monge quad grid rows=3 cols=4\n{}", v_lines(11))).unwrap_err();
    assert!(
        matches!(
            err,
            IoError::CountMismatch {
                expected: 12,
                found: 11,
                ..
            }
        ),
        "{err:?}"
    );
    assert_eq!(
        err.to_string(),
        "<stdin>: vertices (rows × cols = 3 × 4): expected 12, found 11"
    );
    let err = obj(&format!(
        "# monge quad grid rows=1 cols=2\n{}vn 0 0 1\n",
        v_lines(2)
    ))
    .unwrap_err();
    assert_eq!(
        err.to_string(),
        "<stdin>: normals (one per vertex): expected 2, found 1"
    );
}

#[test]
fn obj_syntax_errors_name_the_line() {
    let err = obj("v 0 0 0\nv 1 x 0\n").unwrap_err();
    assert!(matches!(err, IoError::Syntax { line: 2, .. }), "{err:?}");
    assert_eq!(err.to_string(), "<stdin>:2: expected a number, found `x`");
    assert_eq!(
        obj("v 1 2\n").unwrap_err().to_string(),
        "<stdin>:1: expected three coordinates x y z"
    );
    assert_eq!(
        obj("v 1 2 nan\n").unwrap_err().to_string(),
        "<stdin>:1: `nan` is not a finite number"
    );
    let err = obj(&format!("{}f 1 2 3\n", v_lines(3))).unwrap_err();
    assert_eq!(
        err.to_string(),
        "<stdin>:4: a face with 3 corners; a quad grid has faces with 4"
    );
    let err = obj(&format!("{}f 1 2 3 0\n", v_lines(4))).unwrap_err();
    assert_eq!(err.to_string(), "<stdin>:5: bad face corner `0`");
    let err = obj("# monge quad grid rows=2\n").unwrap_err();
    assert_eq!(
        err.to_string(),
        "<stdin>:1: expected `monge quad grid rows=R cols=C` with whole numbers, found `monge quad grid rows=2`"
    );
}

#[test]
fn json_counts_are_checked_and_extra_keys_ignored() {
    let json = |s: &str| read_mesh_from(s.as_bytes(), MeshFormat::Json);
    let grid = json(r#"{"rows": 1, "cols": 2, "vertices": [[0,0,0],[1,0,0]], "normals": [[0,0,1],[0,0,1]], "x": {"y": 1}}"#).unwrap();
    assert_eq!(grid.normals, vec![DVec3::Z; 2]);
    let err = json(r#"{"rows": 2, "cols": 2, "vertices": [[0,0,0],[1,0,0]]}"#).unwrap_err();
    assert!(
        matches!(
            err,
            IoError::CountMismatch {
                expected: 4,
                found: 2,
                ..
            }
        ),
        "{err:?}"
    );
    let err =
        json(r#"{"rows": 1, "cols": 2, "vertices": [[0,0,0],[1,0,0]], "normals": [[0,0,1]]}"#)
            .unwrap_err();
    assert_eq!(
        err.to_string(),
        "<stdin>: normals (one per vertex): expected 2, found 1"
    );
    let err = json(r#"{"rows": 1, "cols": 2, "vertices": [[0,0,0],[1,0]]}"#).unwrap_err();
    assert!(matches!(err, IoError::Parse { line: 1, .. }), "{err:?}");
    assert!(
        err.to_string()
            .contains("invalid length 2, expected an array of length 3"),
        "{err}"
    );
    let err = json(r#"{"rows": 1, "cols": 2}"#).unwrap_err();
    assert!(
        err.to_string().contains("missing field `vertices`"),
        "{err}"
    );
    let err = json(r#"{"rows": 4294967296, "cols": 4294967296, "vertices": []}"#).unwrap_err();
    assert!(matches!(err, IoError::NotAGrid { .. }), "{err:?}");
}

#[test]
fn json_errors_in_long_lines_show_a_short_snippet() {
    let vertices = vec!["[0.125,0.25,0.5]"; 1000].join(",");
    let text = format!(r#"{{"rows": 1, "cols": 1000, "vertices": [{vertices},oops]}}"#);
    let err = read_mesh_from(text.as_bytes(), MeshFormat::Json).unwrap_err();
    let IoError::Parse {
        snippet, column, ..
    } = &err
    else {
        panic!("{err:?}")
    };
    assert!(*column > 17_000);
    assert!(snippet.len() < 200, "{snippet}");
    assert!(snippet.contains(",oops]"), "{snippet}");
    let caret = snippet.lines().nth(1).unwrap();
    let line = snippet.lines().next().unwrap();
    let o = line.chars().position(|c| c == 'o').unwrap();
    assert_eq!(
        caret.chars().position(|c| c == '^').unwrap(),
        o,
        "{snippet}"
    );
}

#[test]
fn ply_from_elsewhere_with_extra_properties() {
    let text = "ply\nformat ascii 1.0\ncomment made by hand\nelement vertex 4\n\
        property float x\nproperty float y\nproperty float z\nproperty uchar red\n\
        element face 1\nproperty list uchar uint vertex_index\nproperty int flags\n\
        element edge 1\nproperty int a\nproperty int b\nend_header\n\
        0 0 0 255\n0 1 0 255\n1 0 0 255\n1 1 0.5 255\n4 2 3 1 0 7\n0 1\n";
    let grid = ply(text).unwrap();
    assert_eq!((grid.rows, grid.cols), (2, 2));
    assert_eq!(grid.vertex(1, 1), DVec3::new(1.0, 1.0, 0.5));
}

#[test]
fn ply_errors() {
    let header = "ply\nformat ascii 1.0\nelement vertex 2\nproperty double x\nproperty double y\nproperty double z\n";
    let err = ply("ply\nformat binary_big_endian 1.0\nend_header\n").unwrap_err();
    assert_eq!(
        err.to_string(),
        "<stdin>:2: only ASCII and binary_little_endian PLY can be read, this file is \
         `binary_big_endian`; convert it with e.g. `plyfile` or MeshLab"
    );
    let err = ply(&format!("{header}property quad w\nend_header\n")).unwrap_err();
    assert!(
        err.to_string()
            .starts_with("<stdin>:7: unknown PLY type `quad` in `property quad w`"),
        "{err}"
    );
    assert_eq!(
        ply("solid x\n").unwrap_err().to_string(),
        "<stdin>:1: expected `ply` on the first line"
    );
    let err = ply(header).unwrap_err();
    assert_eq!(err.to_string(), "<stdin>:7: the header has no `end_header`");
    let err = ply(&format!("{header}end_header\n0 0 0\n")).unwrap_err();
    assert_eq!(
        err.to_string(),
        "<stdin>:9: the file ends before all 2 `vertex` lines"
    );
    let err = ply(&format!("{header}end_header\n0 0 0\n0 0\n")).unwrap_err();
    assert_eq!(err.to_string(), "<stdin>:9: too few values on the line");
    let err = ply(&format!(
        "{header}comment monge quad grid rows=1 cols=2\nend_header\n0 0 0\n0 0 inf\n"
    ))
    .unwrap_err();
    assert_eq!(err.to_string(), "<stdin>:10: `inf` is not a finite number");
    let grid = ply(&format!(
        "{header}comment monge quad grid rows=1 cols=2\nend_header\n0 0 0\n0 0 1\n"
    ))
    .unwrap();
    assert_eq!((grid.rows, grid.cols), (1, 2));
    let err = ply(&format!(
        "{header}comment monge quad grid rows=2 cols=2\nend_header\n0 0 0\n0 0 1\n"
    ))
    .unwrap_err();
    assert!(
        matches!(
            err,
            IoError::CountMismatch {
                expected: 4,
                found: 2,
                ..
            }
        ),
        "{err:?}"
    );
}

#[test]
fn read_mesh_by_extension_and_its_errors() {
    let err = read_mesh(Path::new("-")).unwrap_err();
    assert!(matches!(err, IoError::NeedFormat { .. }), "{err:?}");
    let err = read_mesh(Path::new("mesh.stl")).unwrap_err();
    assert!(matches!(err, IoError::UnknownExtension { .. }), "{err:?}");
    let err = read_mesh(Path::new("/nonexistent/mesh.obj")).unwrap_err();
    assert!(matches!(err, IoError::NotFound { .. }), "{err:?}");

    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.obj");
    std::fs::write(&path, "v 0 0\n").unwrap();
    let err = read_mesh(&path).unwrap_err();
    assert_eq!(
        err.to_string(),
        format!("{}:1: expected three coordinates x y z", path.display())
    );
}

#[test]
fn a_failing_reader_is_a_read_error() {
    struct Failing;
    impl Read for Failing {
        fn read(&mut self, _: &mut [u8]) -> io::Result<usize> {
            Err(io::Error::other("pipe closed"))
        }
    }
    let err = read_mesh_from(Failing, MeshFormat::Obj).unwrap_err();
    assert!(matches!(err, IoError::Read { .. }), "{err:?}");
    assert_eq!(err.to_string(), "cannot read `<stdin>`: pipe closed");
    let err = read_mesh_from(&[0xff, 0xfe][..], MeshFormat::Obj).unwrap_err();
    assert!(matches!(err, IoError::Read { .. }), "{err:?}");
}

/// A binary little-endian PLY: the header, then the body's bytes.
fn binary_ply(header: &str, body: &[u8]) -> Result<monge_core::QuadGrid, IoError> {
    let mut bytes =
        format!("ply\nformat binary_little_endian 1.0\n{header}end_header\n").into_bytes();
    bytes.extend_from_slice(body);
    read_mesh_from(bytes.as_slice(), MeshFormat::Ply)
}

#[test]
fn binary_ply_of_any_scalar_types_and_its_errors() {
    // float x, short y, double z, and a uchar-counted list of uint.
    let header = "comment monge quad grid rows=2 cols=2\nelement vertex 4\nproperty float x\n\
                  property short y\nproperty double z\nelement face 1\n\
                  property list uchar uint vertex_indices\n";
    let mut body = Vec::new();
    for (x, y, z) in [
        (0.5f32, -1i16, 1e-300f64),
        (1.5, 2, 0.0),
        (2.5, 3, -0.0),
        (3.5, 4, 7.0),
    ] {
        body.extend(x.to_le_bytes());
        body.extend(y.to_le_bytes());
        body.extend(z.to_le_bytes());
    }
    body.push(4);
    for c in [0u32, 2, 3, 1] {
        body.extend(c.to_le_bytes());
    }
    let grid = binary_ply(header, &body).unwrap();
    assert_eq!((grid.rows, grid.cols), (2, 2));
    assert_eq!(grid.vertices[0].to_array(), [0.5, -1.0, 1e-300]);
    assert_eq!(grid.vertices[2].z.to_bits(), (-0.0f64).to_bits());

    let header_len =
        "ply\nformat binary_little_endian 1.0\n".len() + header.len() + "end_header\n".len();
    let err = binary_ply(header, &body[..body.len() - 2]).unwrap_err();
    assert!(matches!(err, IoError::Binary { .. }), "{err:?}");
    // The fourth corner of the face (4 bytes from the end) is cut short.
    assert_eq!(
        err.to_string(),
        format!(
            "<stdin>: byte {} (in the binary body): the file ends in `face` record 0 of 1",
            header_len + body.len() - 4
        )
    );
    let mut nan = body.clone();
    nan[6..14].copy_from_slice(&f64::NAN.to_le_bytes());
    let err = binary_ply(header, &nan).unwrap_err();
    assert_eq!(
        err.to_string(),
        format!("<stdin>: byte {header_len} (in the binary body): `NaN` is not a finite number")
    );
}

/// A reader that hands out `chunk` bytes at a time, so that lines and binary
/// records straddle the reader's buffer boundaries.
struct Trickle<'a> {
    bytes: &'a [u8],
    chunk: usize,
}

impl Read for Trickle<'_> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        let n = self.chunk.min(buf.len()).min(self.bytes.len());
        buf[..n].copy_from_slice(&self.bytes[..n]);
        self.bytes = &self.bytes[n..];
        Ok(n)
    }
}

#[test]
fn streamed_input_in_small_pieces_reads_the_same_bits() {
    let grid = random_grid(7, 5, true, 11);
    for format in [
        MeshFormat::Obj,
        MeshFormat::Ply,
        MeshFormat::PlyBinary,
        MeshFormat::Json,
    ] {
        let mut bytes = Vec::new();
        monge_io::write_mesh_to(&grid, format, &mut bytes).unwrap();
        for chunk in [1, 3, 4096] {
            let read = read_mesh_from(
                Trickle {
                    bytes: &bytes,
                    chunk,
                },
                format,
            )
            .unwrap();
            assert_bits_eq(&read, &grid);
        }
    }
}

#[test]
fn crlf_lines_read_and_bad_text_names_its_line() {
    let text = format!("{}{}", v_lines(4), f_lines(2, 2, |x| x)).replace('\n', "\r\n");
    let grid = obj(&text).unwrap();
    assert_eq!((grid.rows, grid.cols), (2, 2));
    let mut bytes = v_lines(4).into_bytes();
    bytes.extend_from_slice(b"v 0 0 \xff\n");
    let err = read_mesh_from(bytes.as_slice(), MeshFormat::Obj).unwrap_err();
    assert!(matches!(err, IoError::Read { .. }), "{err:?}");
    assert!(
        err.to_string().contains("line 5 is not UTF-8 text"),
        "{err}"
    );
    let header = "ply\nformat ascii 1.0\nelement vertex 1\nproperty double x\nproperty double y\n\
                  property double z\nend_header\n";
    let mut bytes = header.as_bytes().to_vec();
    bytes.extend_from_slice(b"0 \xff 0\n");
    let err = read_mesh_from(bytes.as_slice(), MeshFormat::Ply).unwrap_err();
    assert!(
        err.to_string()
            .starts_with("<stdin>:8: an ASCII PLY body that is not text"),
        "{err}"
    );
}

/// `path` in a fresh directory holding `bytes`, read as a mesh (its size known).
fn read_file(name: &str, bytes: &[u8]) -> Result<monge_core::QuadGrid, IoError> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name);
    std::fs::write(&path, bytes).unwrap();
    read_mesh(&path)
}

/// Found by a mutation fuzzer: `x` declared as a list (of none, of one, of
/// two) indexed an empty list (a panic), or quietly took its first item.
#[test]
fn a_coordinate_declared_as_a_list_is_refused_at_its_line() {
    let header = |body: &str| {
        format!(
            "ply\nformat ascii 1.0\nelement vertex 4\nproperty list uchar float x\n\
             property float y\nproperty float z\nelement face 1\n\
             property list uchar int vertex_indices\nend_header\n{body}"
        )
    };
    for items in ["0", "1 0", "2 0 0"] {
        let body: String =
            (0..4).map(|_| format!("{items} 0 0\n")).collect::<String>() + "4 0 2 3 1\n";
        let err = ply(&header(&body)).unwrap_err();
        assert_eq!(
            err.to_string(),
            "<stdin>:4: the `vertex` property `x` is a list; coordinates and normals are one \
             number each: declare it as `property double x` (or float)"
        );
    }
    // Binary alike, and a normal as a list.
    let err = binary_ply(
        "element vertex 1\nproperty float x\nproperty float y\nproperty float z\n\
         property list uchar float nx\nproperty float ny\nproperty float nz\n",
        &[0; 21],
    )
    .unwrap_err();
    assert!(
        err.to_string()
            .starts_with("<stdin>:7: the `vertex` property `nx` is a list"),
        "{err}"
    );
    // Face corners as one number, a list counted by a float.
    let err =
        ply("ply\nformat ascii 1.0\nelement face 1\nproperty int vertex_indices\nend_header\n0\n")
            .unwrap_err();
    assert!(
        err.to_string()
            .starts_with("<stdin>:4: the `face` property `vertex_indices` is a single number"),
        "{err}"
    );
    let err = ply("ply\nformat ascii 1.0\nelement face 1\nproperty list float int vertex_indices\nend_header\n")
        .unwrap_err();
    assert!(
        err.to_string()
            .starts_with("<stdin>:4: a list's length is a whole number, not `float`"),
        "{err}"
    );
}

/// Found by a mutation fuzzer (in the points reader): a huge `element vertex`
/// count reserved memory for it (capacity overflow, or an abort at 1e11).
/// Every count is now weighed against the bytes after the header before
/// anything is read or reserved.
#[test]
fn counts_that_cannot_fit_in_the_file_are_refused_before_any_record() {
    let ascii = |count: &str, body: &str| {
        format!(
            "ply\nformat ascii 1.0\nelement vertex {count}\nproperty float x\nproperty float y\n\
             property float z\nend_header\n{body}"
        )
    };
    for count in ["100000000000", "1000000000000000", &usize::MAX.to_string()] {
        let err = read_file("c.ply", ascii(count, "0 0 0\n").as_bytes()).unwrap_err();
        assert_eq!(
            err.to_string().split(": ").nth(1).unwrap(),
            format!("`element vertex {count}` does not fit in the file")
        );
        assert!(
            err.to_string().ends_with(&format!(
                "{count} records of at least 6 bytes each (in ASCII) need more than the 6 bytes \
                 after the header; the count is wrong or the file is cut short"
            )),
            "{err}"
        );
        // From a stream of unknown length: the records run out, nothing is reserved.
        let err = ply(&ascii(count, "0 0 0\n")).unwrap_err();
        assert!(
            err.to_string().contains("the file ends before all"),
            "{err}"
        );
    }
    // The smallest records fit: "0 0 0" three times, the last line without its break.
    let fits = ascii("3", "0 0 0\n0 0 0\n0 0 0");
    let err = read_file("c.ply", fits.as_bytes()).unwrap_err();
    assert!(matches!(err, IoError::NotAGrid { .. }), "{err}");
    // Binary: 12 bytes a vertex, and records of no bytes however many.
    let mut bytes = b"ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty float x\n\
        property float y\nproperty float z\nelement nothing 18446744073709551615\nend_header\n"
        .to_vec();
    bytes.extend([0; 23]);
    let err = read_file("b.ply", &bytes).unwrap_err();
    assert!(
        err.to_string().contains(
            "`element vertex 2` does not fit in the file: 2 records of at least 12 bytes each \
             (in binary) need more than the 23 bytes after the header"
        ),
        "{err}"
    );
    bytes.push(0);
    let err = read_file("b.ply", &bytes).unwrap_err();
    assert!(matches!(err, IoError::NotAGrid { .. }), "{err}");
    let err = read_mesh_from(bytes.as_slice(), MeshFormat::Ply).unwrap_err();
    assert!(matches!(err, IoError::NotAGrid { .. }), "{err}");
}
