//! `monge render`: the smooth surface and the deviation colouring.

use std::fs;

use predicates::prelude::*;
use tempfile::TempDir;

use crate::common;
use common::{example, monge, refuses};

#[test]
fn render_smooth_draws_the_net_and_refuses_conical_designs() {
    let dir = TempDir::new().unwrap();
    let png = dir.path().join("s.png");
    monge()
        .arg("render")
        .arg(example("fig15-smooth.json"))
        .args(["--smooth", "4", "--size", "300x200", "-o"])
        .arg(&png)
        .assert()
        .success();
    assert!(fs::read(&png).unwrap().starts_with(b"\x89PNG"));
    refuses(
        monge()
            .arg("render")
            .arg(example("fig13-conical.json"))
            .args(["--smooth", "4", "-o"])
            .arg(dir.path().join("c.png")),
        &["--smooth draws the cyclidic net of a circular mesh"],
        &[],
    );
}

/// The fills of an SVG's polygons, as `(r, g, b)`.
fn svg_fills(svg: &str) -> Vec<(u8, u8, u8)> {
    svg.split("fill=\"#")
        .skip(1)
        .filter_map(|s| {
            let hex = s.get(..6)?;
            let c = |k: usize| u8::from_str_radix(&hex[k..k + 2], 16).ok();
            Some((c(0)?, c(2)?, c(4)?))
        })
        .collect()
}

/// Issue 14: `render --deviation TARGET` colours the mesh by its distance to a target.
#[test]
fn render_deviation_colours_the_mesh_by_its_distance_to_a_target() {
    let dir = TempDir::new().unwrap();
    let mesh = dir.path().join("mesh.obj");
    monge()
        .arg("generate")
        .arg(example("fig13-freeform.json"))
        .arg("-o")
        .arg(&mesh)
        .assert()
        .success();
    // Its own mesh as target: every face white (shaded grey), the scale at its floor.
    let svg = dir.path().join("self.svg");
    monge()
        .arg("render")
        .arg(example("fig13-freeform.json"))
        .arg("--deviation")
        .arg(&mesh)
        .arg("-o")
        .arg(&svg)
        .assert()
        .success()
        .stderr(predicate::str::contains("coloured by its distance to"));
    let text = fs::read_to_string(&svg).unwrap();
    let fills = svg_fills(&text);
    assert!(fills.len() > 100);
    // No warm colour of the scale (they have r well above b).
    let warm = |(r, _, b): &&(u8, u8, u8)| u16::from(*r) > u16::from(*b) + 20;
    assert_eq!(fills.iter().filter(warm).count(), 0);
    // The same target lifted by 0.5 along z: the faces turn red, the scale ends at
    // the distance, 0.5 along z (a little less to the tilted tangent planes).
    let lifted: String = fs::read_to_string(&mesh)
        .unwrap()
        .lines()
        .filter_map(|l| {
            let v: Vec<f64> = l
                .strip_prefix("v ")?
                .split_whitespace()
                .map(|x| x.parse().unwrap())
                .collect();
            Some(format!("v {} {} {}\n", v[0], v[1], v[2] + 0.5))
        })
        .collect();
    let target = dir.path().join("lifted.obj");
    fs::write(&target, lifted).unwrap();
    let svg = dir.path().join("lifted.svg");
    monge()
        .arg("render")
        .arg(example("fig13-freeform.json"))
        .arg("--deviation")
        .arg(&target)
        .arg("-o")
        .arg(&svg)
        .assert()
        .success()
        .stderr(predicate::str::contains("95th percentile 0.49"));
    let fills = svg_fills(&fs::read_to_string(&svg).unwrap());
    let red = fills
        .iter()
        .filter(|(r, g, b)| *r > 60 && u16::from(*g) + u16::from(*b) < 60)
        .count();
    assert!(red > 100, "{red} red faces");
    // One design only.
    refuses(
        monge()
            .arg("render")
            .arg(example("fig13-freeform.json"))
            .arg(example("fig14.json"))
            .arg("--deviation")
            .arg(&mesh)
            .arg("-o")
            .arg(dir.path().join("two.svg")),
        &["--deviation colours one design"],
        &[],
    );
}
