//! Mesh writers: exact round trips through independent readers.

use crate::common;

use std::io::Write;

use common::{assert_bits_eq, random_grid};
use glam::DVec3;
use monge_core::QuadGrid;
use monge_io::{
    read_mesh, read_mesh_from, write_mesh, write_mesh_json, write_mesh_to, write_obj, write_ply,
    IoError, MeshFormat,
};
use serde_json::{Map, Value};

const FORMATS: [MeshFormat; 3] = [MeshFormat::Obj, MeshFormat::Ply, MeshFormat::Json];

fn to_string(grid: &QuadGrid, format: MeshFormat) -> String {
    let mut out = Vec::new();
    write_mesh_to(grid, format, &mut out).unwrap();
    String::from_utf8(out).unwrap()
}

#[test]
fn json_matches_the_contract_and_round_trips_f64_exactly() {
    for normals in [false, true] {
        let grid = random_grid(7, 5, normals, 0x9e37_79b9_7f4a_7c15);
        let mut extra = Map::new();
        extra.insert("theta_deg".into(), 30.0.into());
        extra.insert("design".into(), serde_json::json!({"nested": [1, 2]}));
        let mut out = Vec::new();
        write_mesh_json(&grid, &extra, &mut out).unwrap();

        // Read it with serde_json alone, as another tool would.
        let v: Value = serde_json::from_slice(&out).unwrap();
        assert_eq!(v["rows"], 7);
        assert_eq!(v["cols"], 5);
        assert_eq!(v["theta_deg"], 30.0);
        assert_eq!(v["design"]["nested"][1], 2);
        let read = |key: &str| -> Vec<DVec3> {
            v[key]
                .as_array()
                .map(|a| {
                    a.iter()
                        .map(|p| DVec3::from_array(std::array::from_fn(|k| p[k].as_f64().unwrap())))
                        .collect()
                })
                .unwrap_or_default()
        };
        assert_eq!(v.get("normals").is_some(), normals);
        let independent = QuadGrid::new(7, 5, read("vertices"), read("normals"));
        assert_bits_eq(&independent, &grid);

        // And with our own reader (extra keys ignored).
        assert_bits_eq(
            &read_mesh_from(out.as_slice(), MeshFormat::Json).unwrap(),
            &grid,
        );
    }
}

#[test]
fn special_values_round_trip_in_every_format() {
    let vertices = vec![
        DVec3::new(-0.0, 0.0, f64::MIN_POSITIVE),
        DVec3::new(5e-324, -5e-324, f64::MAX),
        DVec3::new(f64::MIN, 0.1 + 0.2, 1e-7),
        DVec3::new(123_456_789.012_345_67, -1e300, 2.0f64.sqrt()),
    ];
    let grid = QuadGrid::new(2, 2, vertices, vec![DVec3::Z; 4]);
    for format in FORMATS {
        let text = to_string(&grid, format);
        assert_bits_eq(&read_mesh_from(text.as_bytes(), format).unwrap(), &grid);
    }
}

#[test]
fn obj_reads_back_identically_with_tobj() {
    for normals in [false, true] {
        let grid = random_grid(6, 9, normals, 42);
        let text = to_string(&grid, MeshFormat::Obj);
        assert!(text.starts_with("# monge quad grid rows=6 cols=9\n"));
        let (models, _) =
            tobj::load_obj_buf(&mut text.as_bytes(), &tobj::LoadOptions::default(), |_| {
                unreachable!("no materials")
            })
            .unwrap();
        assert_eq!(models.len(), 1);
        let mesh = &models[0].mesh;
        // tobj renumbers vertices in order of first use by a face: compare
        // corner by corner.
        assert_eq!(mesh.face_arities, vec![4; grid.face_count()]);
        assert_eq!(mesh.positions.len(), 3 * grid.vertices.len());
        let mut expected = Vec::new();
        for i in 0..grid.rows - 1 {
            for j in 0..grid.cols - 1 {
                let k = i * grid.cols + j;
                let c = grid.cols;
                expected.extend([k, k + c, k + c + 1, k + 1]);
            }
        }
        let at = |values: &[f64], k: u32| -> [u64; 3] {
            let k = 3 * k as usize;
            [
                values[k].to_bits(),
                values[k + 1].to_bits(),
                values[k + 2].to_bits(),
            ]
        };
        for (n, &v) in expected.iter().enumerate() {
            let bits = grid.vertices[v].to_array().map(f64::to_bits);
            assert_eq!(at(&mesh.positions, mesh.indices[n]), bits, "corner {n}");
            if normals {
                let bits = grid.normals[v].to_array().map(f64::to_bits);
                assert_eq!(
                    at(&mesh.normals, mesh.normal_indices[n]),
                    bits,
                    "normal {n}"
                );
            }
        }
        if normals {
            assert!(text.contains("\nf 1//1 10//10 11//11 2//2\n"), "{text}");
        } else {
            assert!(text.contains("\nf 1 10 11 2\n"), "{text}");
        }
    }
}

#[test]
fn ply_reads_back_identically_with_ply_rs() {
    use ply_rs_bw::{parser::Parser, ply::DefaultElement, ply::Property};
    for normals in [false, true] {
        let grid = random_grid(4, 3, normals, 7);
        let text = to_string(&grid, MeshFormat::Ply);
        let ply = Parser::<DefaultElement>::new()
            .read_ply(&mut text.as_bytes())
            .unwrap();
        assert!(ply
            .header
            .comments
            .iter()
            .any(|c| c == "monge quad grid rows=4 cols=3"));
        let double = |p: &Property| match p {
            Property::Double(x) => *x,
            other => panic!("not a double: {other:?}"),
        };
        let vertices = &ply.payload["vertex"];
        assert_eq!(vertices.len(), 12);
        for (k, e) in vertices.iter().enumerate() {
            let p = DVec3::new(double(&e["x"]), double(&e["y"]), double(&e["z"]));
            assert_eq!(
                p.to_array().map(f64::to_bits),
                grid.vertices[k].to_array().map(f64::to_bits)
            );
            assert_eq!(e.contains_key("nx"), normals);
            if normals {
                let n = DVec3::new(double(&e["nx"]), double(&e["ny"]), double(&e["nz"]));
                assert_eq!(n, grid.normals[k]);
            }
        }
        let faces = &ply.payload["face"];
        assert_eq!(faces.len(), 6);
        // The grid's quads, all turned around if the random normals point the
        // other way (tests/orientation.rs of monge-cli checks which).
        let reversed = faces[0]["vertex_indices"] == Property::ListInt(vec![0, 1, 4, 3]);
        assert!(normals || !reversed);
        let quad = |q: [i32; 4]| {
            Property::ListInt(if reversed {
                vec![q[0], q[3], q[2], q[1]]
            } else {
                q.to_vec()
            })
        };
        assert_eq!(faces[0]["vertex_indices"], quad([0, 3, 4, 1]));
        assert_eq!(faces[5]["vertex_indices"], quad([7, 10, 11, 8]));
    }
}

#[test]
fn files_by_extension_and_explicit_format() {
    let dir = tempfile::tempdir().unwrap();
    let grid = random_grid(3, 4, true, 5);
    for format in FORMATS {
        let path = dir
            .path()
            .join(format!("mesh.{}", format.extension().to_uppercase()));
        write_mesh(&grid, &path, None).unwrap();
        assert_bits_eq(&read_mesh(&path).unwrap(), &grid);
        assert_eq!(
            std::fs::read_to_string(&path).unwrap(),
            to_string(&grid, format)
        );
    }
    // An explicit format wins over the extension.
    let path = dir.path().join("mesh.txt");
    write_mesh(&grid, &path, Some(MeshFormat::Ply)).unwrap();
    assert!(std::fs::read_to_string(&path).unwrap().starts_with("ply\n"));
    let err = write_mesh(&grid, &path, None).unwrap_err();
    assert_eq!(
        err.to_string(),
        format!(
            "`{}`: unsupported extension `.txt`; expected `.obj`, `.ply`, `.json` or `.glb` (glTF, written only)",
            path.display()
        )
    );
}

#[test]
fn stdout_needs_a_format() {
    let grid = random_grid(2, 2, false, 1);
    let err = write_mesh(&grid, std::path::Path::new("-"), None).unwrap_err();
    assert!(matches!(err, IoError::NeedFormat { .. }), "{err:?}");
    assert_eq!(
        err.to_string(),
        "`-` (standard input/output) needs an explicit format: obj, ply or json"
    );
}

#[test]
fn degenerate_grids_round_trip() {
    for (rows, cols) in [(0, 0), (1, 1), (1, 5), (5, 1), (2, 2)] {
        let grid = random_grid(rows, cols, true, 11);
        for format in [MeshFormat::Json, MeshFormat::Obj, MeshFormat::Ply] {
            let text = to_string(&grid, format);
            assert_bits_eq(&read_mesh_from(text.as_bytes(), format).unwrap(), &grid);
        }
    }
}

#[test]
fn non_finite_or_inconsistent_grids_are_refused_before_writing() {
    let dir = tempfile::tempdir().unwrap();
    let mut grid = random_grid(3, 3, true, 3);
    grid.vertices[5].y = f64::NAN;
    for format in FORMATS {
        let mut out = Vec::new();
        let err = write_mesh_to(&grid, format, &mut out).unwrap_err();
        assert_eq!(err.kind(), std::io::ErrorKind::InvalidInput);
        let message = err.to_string();
        assert!(
            message.starts_with("vertex (1, 2) is not finite: [") && message.contains("NaN"),
            "{message}"
        );
        assert!(out.is_empty());
        let path = dir.path().join(format!("bad.{}", format.extension()));
        let err = write_mesh(&grid, &path, None).unwrap_err();
        assert!(matches!(err, IoError::Write { .. }), "{err:?}");
        assert!(err.to_string().contains("is not finite"), "{err}");
        assert!(!path.exists());
    }
    // Large grids are searched in blocks side by side: still the first bad
    // point of the first bad kind is named (vertex 70 000, not 80 000 in a
    // later block nor the normal before it).
    let mut grid = random_grid(300, 300, true, 3);
    grid.vertices[80_000].x = f64::INFINITY;
    grid.vertices[70_000].z = f64::NAN;
    grid.normals[10].x = f64::NAN;
    let err = write_ply(&grid, &mut std::io::sink()).unwrap_err();
    assert!(
        err.to_string()
            .starts_with("vertex (233, 100) is not finite"),
        "{err}"
    );
    let mut grid = random_grid(3, 3, true, 3);
    grid.normals.pop();
    let err = write_obj(&grid, &mut std::io::sink()).unwrap_err();
    assert_eq!(err.to_string(), "the grid has 8 normals for 9 vertices");
    grid.vertices.pop();
    let err = write_ply(&grid, &mut std::io::sink()).unwrap_err();
    assert_eq!(
        err.to_string(),
        "the grid has 8 vertices but rows × cols = 3 × 3"
    );
}

#[test]
fn extra_json_keys_may_not_replace_mesh_keys() {
    let grid = random_grid(2, 2, false, 1);
    let mut extra = Map::new();
    extra.insert("rows".into(), 3.into());
    let err = write_mesh_json(&grid, &extra, &mut Vec::new()).unwrap_err();
    assert_eq!(
        err.to_string(),
        "extra key `rows` would replace the mesh's own `rows`"
    );
}

#[test]
fn large_grids_written_in_many_chunks_round_trip() {
    // Several megabytes: many buffer flushes.
    let grid = random_grid(129, 131, true, 77);
    for format in FORMATS {
        let text = to_string(&grid, format);
        assert_bits_eq(&read_mesh_from(text.as_bytes(), format).unwrap(), &grid);
    }
}

#[test]
fn a_failing_writer_stops_a_large_write() {
    /// Accepts `budget` bytes, then fails.
    struct Failing {
        budget: usize,
    }
    impl Write for Failing {
        fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
            if self.budget < buf.len() {
                return Err(std::io::Error::other("disk full"));
            }
            self.budget -= buf.len();
            Ok(buf.len())
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }
    let grid = random_grid(200, 200, true, 78);
    for format in FORMATS {
        for budget in [0, 10, 100_000] {
            let err = write_mesh_to(&grid, format, &mut Failing { budget }).unwrap_err();
            assert_eq!(err.to_string(), "disk full");
        }
    }
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("big.obj");
    std::fs::write(&path, "old").unwrap();
    // A failure after megabytes of output keeps the old file.
    let err = monge_io::write_atomic(&path, |w| {
        write_obj(&grid, w)?;
        Err(std::io::Error::other("disk full"))
    })
    .unwrap_err();
    assert!(err.to_string().ends_with("disk full"), "{err}");
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "old");
}

/// The time to write a 1001 × 1001 grid in every format (well under a second in a
/// release build), reported, not asserted: a test never depends on the machine's speed.
/// Run with `cargo test --release -p monge-io -- --ignored --nocapture`.
#[test]
#[ignore]
fn reports_the_time_to_write_a_1001_by_1001_grid() {
    // A smooth surface of architectural size, with normals.
    let n = 1001;
    let (mut vertices, mut normals) = (Vec::new(), Vec::new());
    for i in 0..n {
        for j in 0..n {
            let (u, v) = (i as f64 / 50.0, j as f64 / 50.0);
            vertices.push(DVec3::new(u, v, 0.3 * (u * 0.7).sin() * (v * 1.3).cos()));
            normals.push(DVec3::new(-(u * 0.7).cos(), (v * 1.3).sin(), 1.0).normalize());
        }
    }
    let grid = QuadGrid::new(n, n, vertices, normals);
    let dir = tempfile::tempdir().unwrap();
    for format in FORMATS {
        let path = dir.path().join(format!("big.{}", format.extension()));
        let start = std::time::Instant::now();
        write_mesh_to(&grid, format, &mut std::io::sink()).unwrap();
        writeln!(
            std::io::stderr(),
            "{format:?} to sink: {:?}",
            start.elapsed()
        )
        .unwrap();
        let start = std::time::Instant::now();
        write_mesh(&grid, &path, None).unwrap();
        let elapsed = start.elapsed();
        let size = std::fs::metadata(&path).unwrap().len();
        writeln!(
            std::io::stderr(),
            "{format:?}: {elapsed:?}, {} MB",
            size / 1_000_000
        )
        .unwrap();
    }
}

#[test]
fn glb_reads_back_in_a_gltf_reader_and_is_never_read_as_a_mesh() {
    let vertices = (0..35)
        .map(|k| DVec3::new((k / 5) as f64, (k % 5) as f64 * 0.7, (k as f64 * 0.3).sin()))
        .collect();
    let grid = QuadGrid::new(7, 5, vertices, Vec::new());
    let mut bytes = Vec::new();
    monge_io::write_mesh_to(&grid, MeshFormat::Glb, &mut bytes).unwrap();
    let gltf = gltf::Gltf::from_slice(&bytes).unwrap();
    let blob = gltf.blob.as_deref().unwrap();
    let mesh = gltf.meshes().next().unwrap();
    let prim = mesh.primitives().next().unwrap();
    let reader = prim.reader(|_| Some(blob));
    let positions: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
    assert_eq!(positions.len(), grid.vertices.len());
    for (p, v) in positions.iter().zip(&grid.vertices) {
        assert_eq!(*p, v.as_vec3().to_array());
    }
    let indices: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
    assert_eq!(indices.len(), 6 * grid.face_count());
    // Face (0, 0) is (0,0) (1,0) (1,1) (0,1): two triangles over it.
    let c = grid.cols as u32;
    assert_eq!(&indices[..6], &[0, c, c + 1, 0, c + 1, 1]);
    // glTF is written for viewers, never read back to be measured.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("m.glb");
    std::fs::write(&path, &bytes).unwrap();
    let e = monge_io::read_mesh(&path).unwrap_err().to_string();
    assert!(
        e.contains("glTF") && e.contains("`.obj`, `.ply` or `.json`"),
        "{e}"
    );
    assert!(monge_io::read_mesh_from(&bytes[..], MeshFormat::Glb).is_err());
}

#[test]
fn binary_ply_reads_back_identically_with_ply_rs_and_monge() {
    use ply_rs_bw::{parser::Parser, ply::DefaultElement, ply::Property};
    for (format, f32) in [(MeshFormat::PlyBinary, false), (MeshFormat::PlyF32, true)] {
        for normals in [false, true] {
            let mut grid = random_grid(5, 4, normals, 23);
            if f32 {
                // f32 cannot hold random f64 bit patterns: ordinary coordinates.
                for p in &mut grid.vertices {
                    *p = DVec3::new(p.x % 1e3, p.y % 1e3, p.z % 1e3);
                }
            }
            let mut bytes = Vec::new();
            write_mesh_to(&grid, format, &mut bytes).unwrap();
            let ply = Parser::<DefaultElement>::new()
                .read_ply(&mut bytes.as_slice())
                .unwrap();
            assert_eq!(
                ply.header.encoding,
                ply_rs_bw::ply::Encoding::BinaryLittleEndian
            );
            // What each coordinate must read back as: the f64, or its f32 rounding.
            let expected = |x: f64| if f32 { x as f32 as f64 } else { x };
            let value = |p: &Property| match (p, f32) {
                (Property::Double(x), false) => *x,
                (Property::Float(x), true) => f64::from(*x),
                (other, _) => panic!("unexpected {other:?}"),
            };
            let vertices = &ply.payload["vertex"];
            assert_eq!(vertices.len(), 20);
            for (k, e) in vertices.iter().enumerate() {
                let keys: &[(&str, &str, &str, &[DVec3])] = if normals {
                    &[
                        ("x", "y", "z", &grid.vertices),
                        ("nx", "ny", "nz", &grid.normals),
                    ]
                } else {
                    &[("x", "y", "z", &grid.vertices)]
                };
                assert_eq!(e.contains_key("nx"), normals);
                for (x, y, z, points) in keys {
                    let read = [value(&e[*x]), value(&e[*y]), value(&e[*z])];
                    let want = points[k].to_array().map(expected);
                    assert_eq!(read.map(f64::to_bits), want.map(f64::to_bits), "vertex {k}");
                }
            }
            let faces = &ply.payload["face"];
            let text_faces = Parser::<DefaultElement>::new()
                .read_ply(&mut to_string(&grid, MeshFormat::Ply).as_bytes())
                .unwrap();
            assert_eq!(faces, &text_faces.payload["face"], "the ASCII PLY's faces");

            // monge reads it back (as `check` does), f32 rounded exactly to f64.
            let read = read_mesh_from(bytes.as_slice(), MeshFormat::Ply).unwrap();
            let mut want = grid.clone();
            for p in want.vertices.iter_mut().chain(&mut want.normals) {
                *p = DVec3::from_array(p.to_array().map(expected));
            }
            assert_bits_eq(&read, &want);
        }
    }
}

#[test]
fn binary_ply_format_names_and_files() {
    assert_eq!(
        MeshFormat::from_extension("ply-binary"),
        Some(MeshFormat::PlyBinary)
    );
    assert_eq!(MeshFormat::PlyF32.name(), "ply-f32");
    assert_eq!(MeshFormat::PlyF32.extension(), "ply");
    let dir = tempfile::tempdir().unwrap();
    let grid = random_grid(3, 3, true, 9);
    let path = dir.path().join("mesh.ply");
    write_mesh(&grid, &path, Some(MeshFormat::PlyBinary)).unwrap();
    // A third of the ASCII size or less: 48 bytes a vertex, 17 a face.
    let size = std::fs::metadata(&path).unwrap().len() as usize;
    assert!(size < to_string(&grid, MeshFormat::Ply).len());
    assert_bits_eq(&read_mesh(&path).unwrap(), &grid);
}

/// Every text format's numbers read back bit for bit by Python's `float()`,
/// an independent correctly rounding reader: random bit patterns (subnormals,
/// huge, tiny, negative zero included).
#[test]
fn python_float_reads_every_written_f64_exactly() {
    let ok = std::process::Command::new("python3")
        .args(["-c", "print(1)"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !ok {
        eprintln!("SKIPPED python_float_reads_every_written_f64_exactly: no python3");
        return;
    }
    let mut grid = random_grid(40, 50, true, 0x5eed);
    grid.vertices[0] = DVec3::new(-0.0, 5e-324, f64::MAX);
    grid.vertices[1] = DVec3::new(f64::MIN_POSITIVE, 1e-7, 1e16);
    // Every number token of the text, as Python reads it, as the hex of its bits.
    const SCRIPT: &str = r#"
import re, struct, sys
text = sys.stdin.read()
if text.startswith("{"):
    text = text[text.index('"vertices"'):]
elif text.startswith("ply"):
    text = text[text.index("end_header") + 10:]
nums = re.findall(r"-?[0-9][0-9.e+-]*", text)
print("\n".join(struct.pack(">d", float(t)).hex() for t in nums if "." in t or "e" in t))
"#;
    for format in FORMATS {
        let text = to_string(&grid, format);
        let mut child = std::process::Command::new("python3")
            .args(["-c", SCRIPT])
            .stdin(std::process::Stdio::piped())
            .stdout(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        child
            .stdin
            .take()
            .unwrap()
            .write_all(text.as_bytes())
            .unwrap();
        let out = child.wait_with_output().unwrap();
        assert!(out.status.success());
        let read: Vec<u64> = String::from_utf8(out.stdout)
            .unwrap()
            .lines()
            .map(|h| u64::from_str_radix(h, 16).unwrap())
            .collect();
        let want: Vec<u64> = match format {
            // OBJ and JSON list all vertices, then all normals; PLY puts
            // each normal after its vertex.
            MeshFormat::Ply => grid
                .vertices
                .iter()
                .zip(&grid.normals)
                .flat_map(|(p, n)| p.to_array().into_iter().chain(n.to_array()))
                .map(f64::to_bits)
                .collect(),
            _ => grid
                .vertices
                .iter()
                .chain(&grid.normals)
                .flat_map(|p| p.to_array())
                .map(f64::to_bits)
                .collect(),
        };
        assert_eq!(read.len(), want.len(), "{format:?}");
        assert_eq!(read, want, "{format:?}");
    }
}

/// glTF and `float` PLY hold `f32`: a coordinate beyond its range (or NaN) is an
/// error before anything is written, not an infinite position or `min`/`max` of
/// `null` (both once written).
#[test]
fn f32_formats_refuse_coordinates_beyond_f32() {
    for bad in [1e39, f64::NAN] {
        let mut vertices: Vec<DVec3> = (0..9)
            .map(|k| DVec3::new((k / 3) as f64, (k % 3) as f64, 0.0))
            .collect();
        vertices[4].z = bad;
        let grid = QuadGrid::new(3, 3, vertices, Vec::new());
        for format in [MeshFormat::Glb, MeshFormat::PlyF32] {
            let mut out = Vec::new();
            let e = write_mesh_to(&grid, format, &mut out).unwrap_err();
            assert!(
                e.to_string().contains("32-bit floats") || e.to_string().contains("not finite"),
                "{format:?} {bad}: {e}"
            );
        }
    }
    // 1e39 is finite in f64: the other formats write it exactly.
    let mut vertices: Vec<DVec3> = (0..4).map(|k| DVec3::splat(k as f64)).collect();
    vertices[3].x = 1e39;
    let grid = QuadGrid::new(2, 2, vertices, Vec::new());
    for format in [MeshFormat::Obj, MeshFormat::PlyBinary, MeshFormat::Json] {
        write_mesh_to(&grid, format, &mut Vec::new()).unwrap();
    }
}
