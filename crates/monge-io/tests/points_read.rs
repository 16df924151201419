//! `read_points`: targets of `monge approximate` as OBJ, ASCII PLY and JSON points.

use monge_io::{read_points, IoError};

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
    let binary = read(
        "t.ply",
        "ply\nformat binary_little_endian 1.0\nend_header\n",
    )
    .unwrap_err();
    assert!(binary.to_string().contains("only ASCII PLY"), "{binary}");
    let no_z = read("t.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n1 2\n")
        .unwrap_err();
    assert!(no_z.to_string().contains("no property `z`"), "{no_z}");
    let short = read("t.ply", "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\nend_header\n1 2 3\n")
        .unwrap_err();
    assert!(short.to_string().contains("declares 2 vertices"), "{short}");
    let bad = read("t.obj", "v 0 0 0\nv 1 x 0\n").unwrap_err();
    assert!(matches!(bad, IoError::Syntax { line: 2, .. }), "{bad}");
    let empty = read("t.obj", "# nothing\n").unwrap_err();
    assert!(empty.to_string().contains("no points"), "{empty}");
}
