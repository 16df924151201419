//! The nodes of a gridshell (§2.2, §6): node axis, angles between the beams meeting
//! there, node height across the layers, torsion, and node types.

use glam::DVec3;
use rustc_hash::FxHashMap;
use serde::Serialize;

use super::layers::LayerMesh;
use super::panels::angle_between;

/// A node of the gridshell (§2.2, §6).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Node {
    /// Index along guide_u.
    pub i: usize,
    /// Index along guide_v.
    pub j: usize,
    /// Position on the layer at distance 0 (the base mesh).
    pub position: DVec3,
    /// Unit node axis.
    pub axis: DVec3,
    /// Directions present, in the order `+i, +j, −i, −j` (which neighbours exist).
    pub directions: Vec<&'static str>,
    /// Angles between consecutive present edges (in that cyclic order), radians.
    pub beam_angles: Vec<f64>,
    /// Angle between each present edge and the node axis, radians.
    pub axis_angles: Vec<f64>,
    /// Distance between the node's positions on the first and the last layer.
    pub height: f64,
    /// Largest torsion of its edges (see [`Beam::torsion`](super::Beam::torsion)).
    pub torsion: f64,
    /// Its node type: nodes of one type agree within `angle_tol`.
    pub node_type: usize,
}

/// Neighbour offsets in the cyclic order `+i, +j, −i, −j`, with their names.
const DIRECTIONS: [((isize, isize), &str); 4] = [
    ((1, 0), "+i"),
    ((0, 1), "+j"),
    ((-1, 0), "-i"),
    ((0, -1), "-j"),
];

/// The node at vertex `(i, j)` (§6), its type 0; `extremes` are the layers of
/// the smallest and the largest distance ([`extreme_layers`]).
pub(super) fn node_at(layers: &[LayerMesh], (lo, hi): (usize, usize), i: usize, j: usize) -> Node {
    let base = &layers[0].grid;
    let x = base.vertex(i, j);
    let axis = base.normals[base.index(i, j)];
    let mut edges = Vec::new();
    let mut directions = Vec::new();
    let mut torsion: f64 = 0.0;
    for ((di, dj), name) in DIRECTIONS {
        let (ni, nj) = (i as isize + di, j as isize + dj);
        if ni < 0 || nj < 0 || ni as usize >= base.rows || nj as usize >= base.cols {
            continue;
        }
        let (ni, nj) = (ni as usize, nj as usize);
        let e = base.vertex(ni, nj) - x;
        let other = base.normals[base.index(ni, nj)];
        torsion = torsion.max(e.normalize().dot(axis.cross(other)).abs());
        edges.push(e);
        directions.push(name);
    }
    let beam_angles = if edges.len() < 2 {
        Vec::new()
    } else {
        let pairs = if edges.len() == 2 { 1 } else { edges.len() };
        (0..pairs)
            .map(|k| angle_between(edges[k], edges[(k + 1) % edges.len()]))
            .collect()
    };
    let axis_angles = edges.iter().map(|&e| angle_between(e, axis)).collect();
    let k = base.index(i, j);
    let height = (layers[hi].grid.vertices[k] - layers[lo].grid.vertices[k]).length();
    Node {
        i,
        j,
        position: x,
        axis,
        directions,
        beam_angles,
        axis_angles,
        height,
        torsion,
        node_type: 0,
    }
}

/// What the summary needs of the nodes (§6).
pub(super) struct NodeSummary {
    pub(super) count: usize,
    pub(super) types: usize,
    pub(super) height: (f64, f64),
    pub(super) max_torsion: f64,
}

/// The type of every node, row-major, and their summary (§6): nodes computed
/// a block of rows at a time (rows side by side), typed in order.
pub(super) fn build_nodes(layers: &[LayerMesh], angle_tol: f64) -> (Vec<usize>, NodeSummary) {
    let base = &layers[0].grid;
    let extremes = extreme_layers(layers);
    let mut types = NodeTypes::new(angle_tol);
    let mut node_types = Vec::with_capacity(base.vertices.len());
    let (mut height, mut max_torsion): ((f64, f64), f64) = ((f64::INFINITY, 0.0), 0.0);
    let block = (crate::tasks::BLOCK / base.cols).max(1);
    for first in (0..base.rows).step_by(block) {
        let rows = crate::tasks::map(block.min(base.rows - first), |r| {
            (0..base.cols)
                .map(|j| node_at(layers, extremes, first + r, j))
                .collect::<Vec<_>>()
        });
        for n in rows.iter().flatten() {
            node_types.push(types.of(n));
            height = (height.0.min(n.height), height.1.max(n.height));
            max_torsion = max_torsion.max(n.torsion);
        }
    }
    let sum = NodeSummary {
        count: node_types.len(),
        types: types.count,
        height,
        max_torsion,
    };
    (node_types, sum)
}

/// Indices of the layers with the smallest and the largest distance.
pub(super) fn extreme_layers(layers: &[LayerMesh]) -> (usize, usize) {
    let by =
        |a: &(usize, &LayerMesh), b: &(usize, &LayerMesh)| a.1.distance.total_cmp(&b.1.distance);
    let lo = layers.iter().enumerate().min_by(by).map_or(0, |p| p.0);
    let hi = layers.iter().enumerate().max_by(by).map_or(0, |p| p.0);
    (lo, hi)
}

/// Groups nodes whose directions agree and whose angles agree within
/// `angle_tol` (§6): greedy, each node joins the matching type of smallest
/// index (a type is represented by its first node). Candidates are looked up in
/// a hash grid of cell `angle_tol` over two of the angles (every signature has
/// at least three), so each node compares with the types in the 3 × 3 cells
/// around it, kept side by side with their angles: on a fine curvature-line
/// mesh every angle is close to 90° and a cell holds many types, so comparing
/// must not chase pointers.
struct NodeTypes {
    angle_tol: f64,
    /// Types so far.
    count: usize,
    cells: FxHashMap<(i64, i64), Vec<Type>>,
}

/// A node type: its index, its first node's directions (a bit per entry of
/// [`DIRECTIONS`]) and angles (beam angles then axis angles, the first `len`
/// of `angles`).
struct Type {
    index: usize,
    directions: u8,
    len: usize,
    angles: [f64; SIGNATURE],
}

impl NodeTypes {
    pub(super) fn new(angle_tol: f64) -> Self {
        NodeTypes {
            angle_tol,
            count: 0,
            cells: FxHashMap::default(),
        }
    }

    /// The type of `node`: the first matching one, or a new one.
    fn of(&mut self, node: &Node) -> usize {
        let angle_tol = self.angle_tol;
        let cell_width = angle_tol.max(1e-15);
        let cell = |a: f64| (a / cell_width).floor() as i64;
        let mut angles = [0.0; SIGNATURE];
        let sig = node.beam_angles.iter().chain(&node.axis_angles);
        // At most one beam angle and one axis angle per direction.
        let len = sig.clone().count();
        for (slot, &a) in angles.iter_mut().zip(sig) {
            *slot = a;
        }
        let directions = DIRECTIONS
            .iter()
            .enumerate()
            .filter(|(_, (_, name))| node.directions.contains(name))
            .fold(0, |mask, (k, _)| mask | 1 << k);
        // The first beam angle and the first axis angle: on a curvature-line
        // mesh the beam angles are nearly equal (all near 90°), the axis
        // angles tell more apart (42 candidates per node at 1000 × 1000 faces
        // against 184 with the first two beam angles).
        let key = match angles[..len] {
            [a, _, ..] => (cell(a), cell(angles[len / 2])),
            [a] => (cell(a), 0),
            [] => (0, 0),
        };
        let matches = |t: &&Type| {
            // The angles first: they tell most candidates apart, and cheaply.
            t.len == len
                && t.angles[..len]
                    .iter()
                    .zip(&angles[..len])
                    .all(|(a, b)| (a - b).abs() <= angle_tol)
                && t.directions == directions
        };
        let found = (key.0 - 1..=key.0 + 1)
            .flat_map(|a| (key.1 - 1..=key.1 + 1).map(move |b| (a, b)))
            .filter_map(|c| self.cells.get(&c))
            .flatten()
            .filter(matches)
            .map(|t| t.index)
            .min();
        found.unwrap_or_else(|| {
            let index = self.count;
            self.count += 1;
            let cell = self.cells.entry(key).or_default();
            // Most cells hold one type or a few: grown by a quarter, not
            // doubled (a doubled cell has room for four types at least; the
            // 684 000 types of 1000 × 1000 faces took 99 MB so, about 60 now).
            if cell.len() == cell.capacity() {
                cell.reserve_exact(cell.len() / 4 + 1);
            }
            cell.push(Type {
                index,
                directions,
                len,
                angles,
            });
            index
        })
    }
}

/// Most angles that tell node types apart: a beam angle and an axis angle
/// per direction.
const SIGNATURE: usize = 2 * DIRECTIONS.len();

/// Distinct values within `tol` of their group's smallest member, ascending.
pub(super) fn distinct(mut values: Vec<f64>, tol: f64) -> Vec<f64> {
    values.sort_by(f64::total_cmp);
    let mut out: Vec<f64> = Vec::new();
    for v in values {
        match out.last() {
            Some(&first) if v - first <= tol => {}
            _ => out.push(v),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distinct_groups_within_tolerance() {
        assert_eq!(
            distinct(vec![3.0, 1.0, 1.0 + 1e-12, 2.0], 1e-9),
            vec![1.0, 2.0, 3.0]
        );
    }
}
