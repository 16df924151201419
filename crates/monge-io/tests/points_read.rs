//! `read_points`: targets of `monge approximate` as OBJ, PLY and JSON points.

use crate::common;

use monge_io::{read_points, write_mesh, IoError, MeshFormat};

fn read(name: &str, text: &str) -> Result<Vec<glam::DVec3>, IoError> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name);
    std::fs::write(&path, text).unwrap();
    read_points(&path)
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
