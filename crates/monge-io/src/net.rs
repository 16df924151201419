//! The cyclidic net's JSON (§4.4): what `monge smooth -o net.json` writes and
//! the explorer page exports, patches sampled and curvature lines as chains of
//! circular arcs, streamed one patch and one line at a time.

use std::io::{self, Write};

use monge_core::cyclidic::{Arc, CyclidicNet, Family};
use serde::{Serialize, Serializer};

/// The JSON contract of `monge smooth -o net.json`: `cols`, `lines` (chains of
/// arcs), `patches` (each sampled on a K × K grid of its own (u, v), row-major)
/// and `rows`, keys in this (alphabetical) order. Streamed: one patch, one line
/// at a time.
///
/// ```
/// use monge_core::cyclidic::{CyclidicNet, CyclidicOptions};
/// use monge_core::{generate, Design, GenerateOptions};
/// let file = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/fig13-freeform.json");
/// let design: Design = serde_json::from_str(&std::fs::read_to_string(file).unwrap()).unwrap();
/// let grid = generate(&design, &GenerateOptions::default()).unwrap().grid;
/// let net = CyclidicNet::from_normals(&grid, &CyclidicOptions::default()).unwrap();
/// let mut out = Vec::new();
/// monge_io::write_net_json(&net, 3, &mut out).unwrap();
/// let v: serde_json::Value = serde_json::from_slice(&out).unwrap();
/// assert_eq!(v["patches"].as_array().unwrap().len(), (grid.rows - 1) * (grid.cols - 1));
/// ```
pub fn write_net_json(net: &CyclidicNet, k: usize, w: &mut dyn Write) -> io::Result<()> {
    let doc = NetJson {
        cols: net.cols(),
        lines: Lines(net),
        patches: Patches { net, k },
        rows: net.rows(),
    };
    serde_json::to_writer(&mut *w, &doc)?;
    writeln!(w)
}

/// Why a conical design has no cyclidic net (§4.4), naming its file `name`:
/// the message of `monge smooth` and of the explorer page.
///
/// ```
/// assert!(monge_io::conical_has_no_net("roof.json").starts_with("roof.json: "));
/// ```
pub fn conical_has_no_net(name: &str) -> String {
    format!(
        "{name}: the design asks for a conical mesh (`\"mesh\": \"conical\"`), but the cyclidic \
         net (§4.4) is built on circular meshes: each patch is a Dupin cyclide through the \
         four corners of a circular face, and a conical mesh's faces are not circular. \
         Remove `\"mesh\": \"conical\"` to get the net of the design's circular mesh \
         (whose conical dual, §2.3, the design describes)"
    )
}

/// The document of [`write_net_json`]; fields in alphabetical order.
#[derive(Serialize)]
struct NetJson<'a> {
    cols: usize,
    lines: Lines<'a>,
    patches: Patches<'a>,
    rows: usize,
}

/// Every curvature line of a net, serialised one at a time (§4.4).
struct Lines<'a>(&'a CyclidicNet);

impl Serialize for Lines<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_seq(self.0.curvature_lines_iter().map(|l| LineJson {
            arcs: l.arcs.iter().map(ArcJson::from).collect(),
            family: match l.family {
                Family::U => "u",
                Family::V => "v",
            },
            index: l.index,
        }))
    }
}

/// One curvature line; fields in alphabetical order.
#[derive(Serialize)]
struct LineJson {
    arcs: Vec<ArcJson>,
    family: &'static str,
    index: usize,
}

/// One circular arc; fields in alphabetical order.
#[derive(Serialize)]
struct ArcJson {
    center: [f64; 3],
    end: [f64; 3],
    normal: [f64; 3],
    radius: f64,
    start: [f64; 3],
    sweep_deg: f64,
}

impl From<&Arc> for ArcJson {
    fn from(a: &Arc) -> Self {
        ArcJson {
            center: a.center.to_array(),
            end: a.end.to_array(),
            normal: a.normal.to_array(),
            radius: a.radius,
            start: a.start.to_array(),
            sweep_deg: a.sweep().to_degrees(),
        }
    }
}

/// Every patch of a net sampled on a `k × k` grid, serialised one at a time (§4.4).
struct Patches<'a> {
    net: &'a CyclidicNet,
    k: usize,
}

impl Serialize for Patches<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let (net, k) = (self.net, self.k);
        s.collect_seq(
            (0..net.rows() - 1)
                .flat_map(|i| (0..net.cols() - 1).map(move |j| (i, j)))
                .map(|(i, j)| PatchJson {
                    cols: k,
                    i,
                    j,
                    points: net
                        .sample_patch(i, j, k)
                        .into_iter()
                        .map(|p| p.to_array())
                        .collect(),
                    rows: k,
                }),
        )
    }
}

/// One sampled patch; fields in alphabetical order.
#[derive(Serialize)]
struct PatchJson {
    cols: usize,
    i: usize,
    j: usize,
    points: Vec<[f64; 3]>,
    rows: usize,
}
