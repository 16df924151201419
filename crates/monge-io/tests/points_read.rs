//! `read_points`: targets of `monge approximate` as OBJ, PLY and JSON points.

use crate::common;

use monge_io::{read_points, write_mesh, IoError, MeshFormat};

fn read(name: &str, text: &str) -> Result<Vec<glam::DVec3>, IoError> {
    read_bytes(name, text.as_bytes())
}

#[test]
fn points_come_from_every_format_whatever_the_faces() {
    let obj = read("t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 2\nf 1 2 3\n").unwrap();
    assert_eq!(obj[2].to_array(), [0.0, 1.0, 2.0]);
    let ply = "ply\nformat ascii 1.0\nelement vertex 2\nproperty float z\nproperty float x\nproperty float y\n\
               element face 0\nproperty list uchar int vertex_indices\nend_header\n3 1 2\n6 4 5\n";
    let ply = read("t.ply", ply).unwrap();
    assert_eq!(ply[1].to_array(), [4.0, 5.0, 6.0]);
    let json = read("t.json", r#"{"points": [[1, 2, 3]]}"#).unwrap();
    assert_eq!(json[0].to_array(), [1.0, 2.0, 3.0]);
}

#[test]
fn malformed_targets_are_refused_with_their_line() {
    let big_endian = read("t.ply", "ply\nformat binary_big_endian 1.0\nend_header\n").unwrap_err();
    assert!(
        big_endian
            .to_string()
            .contains("only ASCII and binary_little_endian PLY"),
        "{big_endian}"
    );
    let no_z = read("t.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n1 2\n")
        .unwrap_err();
    assert!(no_z.to_string().contains("no property `z`"), "{no_z}");
    let short = read("t.ply", "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\nend_header\n1 2 3\n")
        .unwrap_err();
    assert!(
        short
            .to_string()
            .contains("`element vertex 2` does not fit in the file"),
        "{short}"
    );
    let bad = read("t.obj", "v 0 0 0\nv 1 x 0\n").unwrap_err();
    assert!(matches!(bad, IoError::Syntax { line: 2, .. }), "{bad}");
    let empty = read("t.obj", "# nothing\n").unwrap_err();
    assert!(empty.to_string().contains("no points"), "{empty}");
}

/// `monge approximate` of the binary PLY that `monge generate --format
/// ply-binary` writes said "invalid utf-8 sequence": PLY targets are read by
/// the mesh reader's PLY code, ASCII or binary, and give the same points.
#[test]
fn binary_ply_targets_are_read_as_ascii_ones() {
    let grid = common::random_grid(5, 4, false, 7);
    let dir = tempfile::tempdir().unwrap();
    let (ascii, binary) = (dir.path().join("a.ply"), dir.path().join("b.ply"));
    write_mesh(&grid, &ascii, Some(MeshFormat::Ply)).unwrap();
    write_mesh(&grid, &binary, Some(MeshFormat::PlyBinary)).unwrap();
    for path in [ascii, binary] {
        let points = read_points(&path).unwrap();
        assert_eq!(points.len(), grid.vertices.len());
        for (p, v) in points.iter().zip(&grid.vertices) {
            assert_eq!(
                p.to_array().map(f64::to_bits),
                v.to_array().map(f64::to_bits)
            );
        }
    }
}

/// Found by a mutation fuzzer: a point cloud whose `element vertex` count is
/// huge made `approximate` and `render --deviation` panic (capacity overflow)
/// or abort (1e11); a coordinate declared as a list panicked in `check`.
#[test]
fn huge_counts_and_list_coordinates_are_refused_not_a_crash() {
    for count in ["100000000000", "1000000000000000", "18446744073709551615"] {
        let text = format!(
            "ply\nformat ascii 1.0\nelement vertex {count}\nproperty float x\nproperty float y\n\
             property float z\nend_header\n0 0 0\n"
        );
        let err = read("t.ply", &text).unwrap_err();
        assert!(
            matches!(err, IoError::Syntax { line: 3, .. })
                && err.to_string().contains("does not fit in the file"),
            "{err}"
        );
    }
    let text = "ply\nformat ascii 1.0\nelement vertex 1\nproperty list uchar float x\n\
                property float y\nproperty float z\nend_header\n0 0 0\n";
    let err = read("t.ply", text).unwrap_err();
    assert!(
        matches!(err, IoError::Syntax { line: 4, .. }) && err.to_string().contains("is a list"),
        "{err}"
    );
    // Faces of any shape are read past in a point cloud.
    let text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
                property float z\nelement face 1\nproperty list uchar int vertex_indices\n\
                end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    assert_eq!(read("t.ply", text).unwrap().len(), 3);
}

/// A binary STL of `triangles` written byte by byte as the format lays it out (80
/// bytes of header, the count, then per triangle its normal, its corners and two bytes).
fn binary_stl(header: &str, triangles: &[[[f32; 3]; 3]]) -> Vec<u8> {
    let mut bytes = vec![b' '; 80];
    bytes[..header.len()].copy_from_slice(header.as_bytes());
    bytes.extend((triangles.len() as u32).to_le_bytes());
    for t in triangles {
        bytes.extend([0.0f32, 0.0, 1.0].iter().flat_map(|c| c.to_le_bytes()));
        bytes.extend(t.iter().flatten().flat_map(|c| c.to_le_bytes()));
        bytes.extend([0u8, 0]);
    }
    bytes
}

fn read_bytes(name: &str, bytes: &[u8]) -> Result<Vec<glam::DVec3>, IoError> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name);
    std::fs::write(&path, bytes).unwrap();
    read_points(&path)
}

#[test]
fn stl_targets_are_the_distinct_corners_of_their_triangles() {
    // Two triangles sharing an edge: four distinct corners, in the order they appear,
    // each coordinate the f32 written. The header begins with `solid`, as some
    // exporters write it; the file is binary by its length.
    let (a, b, c, d) = (
        [0.1f32, 0.0, 0.0],
        [1.0, 0.0, 0.3],
        [1.0, 1.0, 0.7],
        [0.0, 1.0, 1e-7],
    );
    let bytes = binary_stl("solid exported", &[[a, b, c], [a, c, d]]);
    let points = read_bytes("roof.STL", &bytes).unwrap();
    let expected: Vec<[f64; 3]> = [a, b, c, d].iter().map(|p| p.map(f64::from)).collect();
    assert_eq!(
        points.iter().map(|p| p.to_array()).collect::<Vec<_>>(),
        expected
    );
    // ASCII, its first line `solid` without a name, as many exporters write it.
    let ascii = "solid\n facet normal 0 0 1\n  outer loop\n   vertex 0.1 0 0\n   vertex 1 0 0.3\n   \
                 vertex 1 1 0.7\n  endloop\n endfacet\n facet normal 0 0 1\n  outer loop\n   \
                 vertex 0.1 0 0\n   vertex 1 1 0.7\n   vertex 0 1 1e-7\n  endloop\n endfacet\nendsolid\n";
    let points = read_bytes("roof.stl", ascii.as_bytes()).unwrap();
    assert_eq!(
        points.iter().map(|p| p.to_array()).collect::<Vec<_>>(),
        expected
    );
}

#[test]
fn malformed_stl_targets_are_refused_saying_why() {
    let one = binary_stl("", &[[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]]);
    // Cut short: its length is not that of the triangle its header counts.
    let short = read_bytes("t.stl", &one[..one.len() - 10]).unwrap_err();
    assert!(
        short
            .to_string()
            .contains("this file has 124 bytes where its header counts 1 triangles"),
        "{short}"
    );
    let nan = binary_stl(
        "",
        &[[[0.0, 0.0, 0.0], [f32::NAN, 0.0, 0.0], [0.0, 1.0, 0.0]]],
    );
    let nan = read_bytes("t.stl", &nan).unwrap_err();
    assert!(
        nan.to_string()
            .contains("triangle 1 has a corner that is not a finite number"),
        "{nan}"
    );
    let ascii = "solid x\n facet normal 0 0 1\n  outer loop\n   vertex 0 0\n";
    let ascii = read_bytes("t.stl", ascii.as_bytes()).unwrap_err();
    assert!(
        ascii.to_string().contains("not a valid ASCII STL"),
        "{ascii}"
    );
    let empty = read_bytes("t.stl", b"solid x\nendsolid x\n").unwrap_err();
    assert!(empty.to_string().contains("no points"), "{empty}");
}

#[test]
fn text_targets_are_one_point_a_line_whatever_the_separators() {
    let expect = |name: &str, text: &str, points: &[[f64; 3]]| {
        let read = read(name, text).unwrap();
        assert_eq!(
            read.iter().map(|p| p.to_array()).collect::<Vec<_>>(),
            points,
            "{name}"
        );
    };
    let two = [[1.0, 2.0, 3.5], [-4.0, 5e-3, 6.0]];
    expect("s.xyz", "# scan\n1 2 3.5\n\n-4\t5e-3   6\n", &two);
    // A header, more columns (intensity, colour).
    expect(
        "s.csv",
        "x,y,z,intensity\n1,2,3.5,0.7\n-4, 5e-3, 6, 0.2\n",
        &two,
    );
    // A .pts file: the count first, then x y z intensity r g b.
    expect(
        "s.pts",
        "2\n1 2 3.5 -120 255 0 0\n-4 0.005 6 -80 0 255 0\n",
        &two,
    );
    // Semicolons, decimal commas.
    expect("s.txt", "1;2;3,5\n-4;0,005;6\n", &two);
}

#[test]
fn malformed_text_targets_are_refused_with_their_line() {
    let refused = |text: &str, line: usize, says: &str| {
        let e = read("s.xyz", text).unwrap_err();
        assert!(
            matches!(e, IoError::Syntax { line: l, .. } if l == line),
            "{e}"
        );
        assert!(e.to_string().contains(says), "{e}");
    };
    refused("1 2 3\n4 5\n", 2, "`4 5` has 2 numbers: a point is `x y z`");
    refused("1 2 3\n4 five 6\n", 2, "`five` is not a number");
    refused("1 2 3\n\n4 5 NaN\n", 3, "`NaN` is not a finite number");
    // A header is read as one only before the first point.
    refused("x y z\nX Y Z\n1 2 3\n", 2, "`X` is not a number");
    refused("x y z\n", 1, "no points");
}

#[test]
fn a_text_target_is_the_mesh_it_lists() {
    // The shipped paraboloid target's vertices (its `v` lines, split here), written one
    // a line: the same points to the bit, in the same order.
    let obj = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/targets/paraboloid.obj");
    let positions: Vec<f64> = std::fs::read_to_string(&obj)
        .unwrap()
        .lines()
        .filter_map(|l| l.strip_prefix("v "))
        .flat_map(|l| l.split_whitespace().map(|t| t.parse::<f64>().unwrap()))
        .collect();
    let text: String = positions
        .chunks(3)
        .map(|p| format!("{} {} {}\n", p[0], p[1], p[2]))
        .collect();
    let read = read("paraboloid.xyz", &text).unwrap();
    assert_eq!(read.len() * 3, positions.len());
    for (p, q) in read.iter().zip(positions.chunks(3)) {
        assert_eq!(p.to_array(), [q[0], q[1], q[2]]);
    }
    assert_eq!(read, read_points(&obj).unwrap());
}

#[test]
fn an_unknown_extension_names_every_target_format() {
    let e = read("t.dwg", "").unwrap_err();
    for format in [".obj", ".stl", ".xyz", ".pts", ".csv", ".igs"] {
        assert!(e.to_string().contains(format), "{e}");
    }
    let e = read("t.glb", "").unwrap_err();
    assert!(e.to_string().contains(".stl"), "{e}");
}
