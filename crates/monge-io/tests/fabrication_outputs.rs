//! Fabrication outputs (§6): schedules read back, the DXF drawings opened by a
//! DXF reader (Python's ezdxf), the glTF read back and validated by the `gltf` crate.

use std::path::Path;
use std::process::Command;

use glam::DVec3;
use monge_core::fabrication::{fabricate, BaseMesh, Fabrication, FabricationOptions, SegmentShape};
use monge_core::{generate, Design, GenerateOptions, GuideSpec};
use monge_io::{write_fabrication, ScheduleJson, FABRICATION_FILES};

/// A bi-arc guide_v (radius 3 over 40°, radius 6 over 30°) and an arc guide_u.
fn design() -> Design {
    let c1 = DVec3::new(0.0, 0.0, -3.0);
    let on = |c: DVec3, r: f64, phi: f64| c + r * DVec3::new(0.0, phi.sin(), phi.cos());
    let mut points: Vec<[f64; 3]> = (0..=4)
        .map(|k| on(c1, 3.0, (10.0 * k as f64).to_radians()).to_array())
        .collect();
    let join = on(c1, 3.0, 40f64.to_radians());
    let c2 = join + 2.0 * (c1 - join);
    for k in 1..=4 {
        points.push(on(c2, 6.0, (40.0 + 7.5 * k as f64).to_radians()).to_array());
    }
    Design {
        mesh: Default::default(),
        theta_deg: 30.0,
        guide_u: GuideSpec::arc([0.0, 0.0, -10.0], [0.0; 3], [0.0, 1.0, 0.0], 40.0, 6),
        guide_v: GuideSpec::Points {
            points,
            tangent: Some([0.0, 1.0, 0.0]),
        },
        tolerance: None,
    }
}

fn fabrication() -> Fabrication {
    let grid = generate(&design(), &GenerateOptions::default())
        .unwrap()
        .grid;
    let options = FabricationOptions {
        layers: vec![0.0, 0.1, 0.2],
        ..Default::default()
    };
    fabricate(BaseMesh::Circular(&grid), &options).unwrap()
}

fn write(dir: &Path) -> Fabrication {
    write_with(dir, ScheduleJson::Summary)
}

fn write_with(dir: &Path, json: ScheduleJson) -> Fabrication {
    let f = fabrication();
    let paths = write_fabrication(dir, &f, (0.05, 0.1), json, None).unwrap();
    assert_eq!(paths.len(), FABRICATION_FILES.len());
    for p in &paths {
        assert!(p.is_file(), "{} missing", p.display());
    }
    f
}

#[test]
fn csv_schedules_read_back_exactly() {
    let dir = tempfile::tempdir().unwrap();
    let f = write(dir.path());
    let read = |name: &str| std::fs::read_to_string(dir.path().join(name)).unwrap();
    let panels = read("panels.csv");
    let lines: Vec<&str> = panels.lines().collect();
    assert_eq!(lines.len(), f.panels().len() + 1);
    let header: Vec<&str> = lines[0].split(',').collect();
    let area = header.iter().position(|h| *h == "area").unwrap();
    for (line, p) in lines[1..].iter().zip(f.panels()) {
        let cells: Vec<&str> = line.split(',').collect();
        assert_eq!(cells.len(), header.len());
        assert_eq!(cells[area].parse::<f64>().unwrap(), p.area);
        assert_eq!(cells[4].parse::<f64>().unwrap(), p.outline[0].x);
    }
    let beams = read("beams.csv");
    let rows: Vec<Vec<&str>> = beams
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect())
        .collect();
    assert_eq!(rows.len(), f.beams().len());
    // Rows are bi-arcs split at node 4; columns one arc.
    for (cells, b) in rows.iter().zip(f.beams()) {
        assert_eq!(cells[7].parse::<usize>().unwrap(), b.segments.len());
        if cells[2] == "row" {
            assert_eq!(cells[8], "4");
            assert_eq!(cells[9].split(';').count(), 2);
        }
    }
    let segments = read("segments.csv");
    let n: usize = f.beams().map(|b| b.segments.len()).sum();
    assert_eq!(segments.lines().count(), n + 1);
    // A beam's length is what it is cut to: the sum of its segments' lengths in
    // segments.csv (once the shorter polyline through its nodes), each arc's
    // radius × sweep, measured again from the file's own numbers.
    let header: Vec<&str> = segments.lines().next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (beam, radius, sweep, length) =
        (col("beam"), col("radius"), col("sweep_deg"), col("length"));
    let mut by_beam = std::collections::HashMap::<String, f64>::new();
    for line in segments.lines().skip(1) {
        let c: Vec<&str> = line.split(',').collect();
        let l: f64 = c[length].parse().unwrap();
        if let (Ok(r), Ok(s)) = (c[radius].parse::<f64>(), c[sweep].parse::<f64>()) {
            assert!((r * s.to_radians().abs() - l).abs() <= 1e-12 * l, "{line}");
        }
        *by_beam.entry(c[beam].to_owned()).or_default() += l;
    }
    for cells in &rows {
        let (length, polyline): (f64, f64) = (cells[5].parse().unwrap(), cells[6].parse().unwrap());
        assert!(
            (length - by_beam[cells[0]]).abs() <= 1e-12 * length,
            "{cells:?}"
        );
        assert!(polyline < length, "{cells:?}: chords are shorter than arcs");
    }
    let nodes = read("nodes.csv");
    assert_eq!(nodes.lines().count(), f.nodes().len() + 1);
}

#[test]
fn json_schedule_is_the_summary_by_default() {
    let dir = tempfile::tempdir().unwrap();
    let f = write(dir.path());
    let text = std::fs::read_to_string(dir.path().join("schedule.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let keys: Vec<&String> = v.as_object().unwrap().keys().collect();
    assert_eq!(keys, ["layers", "summary"]);
    assert_eq!(v["summary"]["panels"], f.panels().len());
    assert_eq!(v["layers"], serde_json::json!([0.0, 0.1, 0.2]));
}

#[test]
fn full_json_schedule_has_everything() {
    let dir = tempfile::tempdir().unwrap();
    let f = write_with(dir.path(), ScheduleJson::Full);
    let text = std::fs::read_to_string(dir.path().join("schedule.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(v["summary"]["panels"], f.panels().len());
    assert_eq!(v["summary"]["node_types"], f.summary.node_types);
    assert_eq!(v["panels"].as_array().unwrap().len(), f.panels().len());
    assert_eq!(v["panels"][0]["label"], "L0-P0.0");
    assert_eq!(
        v["beams"][1]["label"],
        monge_io::beam_label(&f.beams().nth(1).unwrap())
    );
    assert_eq!(
        v["panels"].as_array().unwrap().last().unwrap()["label"],
        format!(
            "L2-P{}.{}",
            f.panels().last().unwrap().i,
            f.panels().last().unwrap().j
        )
    );
    assert_eq!(
        v["panels"][0]["area"].as_f64().unwrap(),
        f.panel(0, 0, 0).area
    );
    assert_eq!(v["beams"][0]["segments"][0]["shape"]["kind"], "arc");
    assert_eq!(v["nodes"].as_array().unwrap().len(), f.nodes().len());
    assert_eq!(v["layers"], serde_json::json!([0.0, 0.1, 0.2]));
}

#[test]
fn svg_overview_is_one_document() {
    let dir = tempfile::tempdir().unwrap();
    let f = write(dir.path());
    let text = std::fs::read_to_string(dir.path().join("overview.svg")).unwrap();
    assert!(text.starts_with("<svg") && text.trim_end().ends_with("</svg>"));
    assert_eq!(text.matches("<polyline").count(), f.beams().len());
    assert_eq!(
        text.matches("<polygon").count(),
        f.panels().len() / f.layers.len()
    );
    assert_eq!(text.matches("<g").count(), text.matches("</g>").count());
}

/// Python reading both DXF files with ezdxf: entity counts per type and layer,
/// and, in the beams drawing, the largest distance from an arc's end points to
/// the nearest node marker.
const EZDXF: &str = r#"
import json, math, sys, ezdxf
out = {}
for name in ("panels.dxf", "beams.dxf"):
    doc = ezdxf.readfile(sys.argv[1] + "/" + name)
    auditor = doc.audit()
    counts = {}
    for e in doc.modelspace():
        key = e.dxftype() + ":" + e.dxf.layer
        counts[key] = counts.get(key, 0) + 1
    out[name] = {"counts": counts, "errors": len(auditor.errors), "version": doc.dxfversion}
msp = ezdxf.readfile(sys.argv[1] + "/beams.dxf").modelspace()
marks = [e.dxf.center for e in msp if e.dxftype() == "CIRCLE"]
worst = 0.0
for a in msp.query("ARC"):
    for p in (a.start_point, a.end_point):
        worst = max(worst, min(math.dist((p.x, p.y), (m.x, m.y)) for m in marks))
out["arc_end_to_node"] = worst
print(json.dumps(out))
"#;

#[test]
fn dxf_opens_in_ezdxf() {
    let ok = Command::new("python3")
        .args(["-c", "import ezdxf"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !ok {
        eprintln!("SKIPPED dxf_opens_in_ezdxf: `python3 -c \"import ezdxf\"` failed; install it with `python3 -m pip install ezdxf`");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let f = write(dir.path());
    let out = Command::new("python3")
        .args(["-c", EZDXF, dir.path().to_str().unwrap()])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let panels = &v["panels.dxf"];
    assert_eq!(panels["version"], "AC1009");
    assert_eq!(panels["errors"], 0);
    assert_eq!(panels["counts"]["LINE:PANEL"], 4 * f.panels().len());
    assert_eq!(panels["counts"]["TEXT:LABEL"], f.panels().len());
    let beams = &v["beams.dxf"];
    assert_eq!(beams["errors"], 0);
    let arcs = f
        .beams()
        .flat_map(|b| b.segments)
        .filter(|s| matches!(s.shape, SegmentShape::Arc { .. }))
        .count();
    let nodes: usize = f.beams().map(|b| b.nodes.len()).sum();
    let splits: usize = f.beams().map(|b| b.segments.len() - 1).sum();
    assert_eq!(beams["counts"]["ARC:ARC"], arcs);
    assert_eq!(beams["counts"]["CIRCLE:NODE"], nodes - splits);
    assert_eq!(beams["counts"]["CIRCLE:SPLIT"], splits);
    assert_eq!(beams["counts"]["LINE:EDGE"], nodes - f.beams().len());
    assert_eq!(beams["counts"]["TEXT:LABEL"], f.beams().len());
    // Arcs start and end on nodes (to the precision of the text numbers).
    assert!(v["arc_end_to_node"].as_f64().unwrap() < 1e-9 * f.summary.size);
}

#[test]
fn gltf_reads_back_with_counts_and_bounds() {
    let dir = tempfile::tempdir().unwrap();
    let f = write(dir.path());
    let bytes = std::fs::read(dir.path().join("gridshell.glb")).unwrap();
    let gltf = gltf::Gltf::from_slice(&bytes).unwrap();
    let blob = gltf.blob.as_deref().unwrap();
    assert_eq!(gltf.meshes().count(), 2 * f.layers.len());
    assert_eq!(gltf.nodes().count(), 2 * f.layers.len());
    assert_eq!(
        gltf.scenes().next().unwrap().nodes().count(),
        2 * f.layers.len()
    );
    for (k, layer) in f.layers.iter().enumerate() {
        let mesh = |name: &str| {
            gltf.meshes()
                .find(|m| m.name() == Some(&format!("layer {k} {name}")))
                .unwrap()
        };
        let panels = mesh("panels");
        let prim = panels.primitives().next().unwrap();
        let reader = prim.reader(|_| Some(blob));
        let positions: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
        assert_eq!(positions.len(), layer.grid.vertices.len());
        let indices: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
        assert_eq!(indices.len(), 6 * layer.grid.face_count());
        for (p, v) in positions.iter().zip(&layer.grid.vertices) {
            assert!((DVec3::from(p.map(f64::from)) - *v).length() < 1e-6 * f.summary.size);
        }
        let bounds = prim.bounding_box();
        for (c, lo) in bounds.min.iter().zip([
            layer
                .grid
                .vertices
                .iter()
                .map(|v| v.x)
                .fold(f64::INFINITY, f64::min),
            layer
                .grid
                .vertices
                .iter()
                .map(|v| v.y)
                .fold(f64::INFINITY, f64::min),
            layer
                .grid
                .vertices
                .iter()
                .map(|v| v.z)
                .fold(f64::INFINITY, f64::min),
        ]) {
            assert!((f64::from(*c) - lo).abs() < 1e-6);
        }
        let beams = mesh("beams");
        let prim = beams.primitives().next().unwrap();
        let reader = prim.reader(|_| Some(blob));
        let n: usize = f.layer_beams(k).map(|b| b.nodes.len()).sum();
        let edges = n - f.layer_beams(k).len();
        assert_eq!(reader.read_positions().unwrap().count(), 4 * n);
        let indices: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
        assert_eq!(
            indices.len(),
            3 * (8 * edges + 4 * f.beams().len() / f.layers.len())
        );
        assert!(indices.iter().all(|&i| (i as usize) < 4 * n));
    }
}

#[test]
fn files_written_side_by_side_are_those_written_alone() {
    // write_fabrication writes its files in parallel: each must hold exactly the
    // bytes that its writer gives on its own.
    let dir = tempfile::tempdir().unwrap();
    let f = write(dir.path());
    type Alone = fn(&Fabrication, &mut Vec<u8>) -> std::io::Result<()>;
    let alone: [(&str, Alone); 8] = [
        ("panels.csv", |f, w| monge_io::write_panels_csv(f, w)),
        ("beams.csv", |f, w| monge_io::write_beams_csv(f, w)),
        ("segments.csv", |f, w| monge_io::write_segments_csv(f, w)),
        ("nodes.csv", |f, w| monge_io::write_nodes_csv(f, w)),
        ("panels.dxf", |f, w| monge_io::write_panels_dxf(f, w)),
        ("beams.dxf", |f, w| monge_io::write_beams_dxf(f, w)),
        ("overview.svg", |f, w| monge_io::write_overview_svg(f, w)),
        ("gridshell.glb", |f, w| {
            monge_io::write_glb(f, 0.05, 0.1, None, w)
        }),
    ];
    for (name, writer) in alone {
        let mut bytes = Vec::new();
        writer(&f, &mut bytes).unwrap();
        assert!(!bytes.is_empty(), "{name}");
        assert_eq!(
            std::fs::read(dir.path().join(name)).unwrap(),
            bytes,
            "{name}"
        );
    }
}
