//! The assembly of generated patches into one grid along the chain (§4.7): shared
//! lines stored once, every patch running forwards with its normals to one side.

use glam::DVec3;

use crate::design::Design;
use crate::generate::Generated;
use crate::QuadGrid;

use super::chain::Chain;
use super::mesh::{MultiPatch, PatchInfo};

/// One generated patch before assembly.
pub(super) struct Built {
    pub(super) generated: Generated,
    pub(super) design: Design,
    /// `+1` or `−1`: the patch's normals relative to the first patch's orientation.
    pub(super) sign: f64,
    pub(super) parent: Option<usize>,
    pub(super) seam_gap_abs: f64,
    pub(super) axis_gap: f64,
    pub(super) kink_deg: f64,
}

/// Assemble the patches into one grid along the chain.
pub(super) fn assemble(built: Vec<Built>, chain: &Chain) -> MultiPatch {
    let along_rows = chain.along_rows;
    // Every patch as a grid whose rows run along the chain, forwards, with normals
    // in the first patch's orientation.
    let canonical: Vec<QuadGrid> = built
        .iter()
        .map(|b| {
            let g = &b.generated.grid;
            let g = if along_rows {
                g.clone()
            } else {
                g.transposed()
            };
            let (rows, cols) = (g.rows, g.cols);
            let order: Vec<usize> = if b.sign > 0.0 {
                (0..rows).collect()
            } else {
                (0..rows).rev().collect()
            };
            let pick = |v: &[DVec3], scale: f64| -> Vec<DVec3> {
                order
                    .iter()
                    .flat_map(|&i| v[i * cols..(i + 1) * cols].iter().map(move |x| scale * *x))
                    .collect()
            };
            QuadGrid::new(rows, cols, pick(&g.vertices, 1.0), pick(&g.normals, b.sign))
        })
        .collect();
    let mut order = Vec::with_capacity(built.len());
    let mut k = chain.first;
    order.push(k);
    while let Some(n) = chain.next[k] {
        order.push(n);
        k = n;
    }
    let cols = canonical[0].cols;
    let mut vertices: Vec<DVec3> = Vec::new();
    let mut normals: Vec<DVec3> = Vec::new();
    let mut ranges = vec![(0, 0); built.len()];
    for (pos, &k) in order.iter().enumerate() {
        let g = &canonical[k];
        let mut first = 0;
        if pos > 0 && built[k].parent == Some(order[pos - 1]) {
            first = 1; // keep the parent's (earlier) copy of the shared line
        } else if pos > 0 {
            // The patch before was attached to this one: keep this one's copy.
            vertices.truncate(vertices.len() - cols);
            normals.truncate(normals.len() - cols);
        }
        let start = vertices.len() / cols - first;
        vertices.extend_from_slice(&g.vertices[first * cols..]);
        normals.extend_from_slice(&g.normals[first * cols..]);
        ranges[k] = (start, vertices.len() / cols - 1);
    }
    let rows = vertices.len() / cols;
    let mut grid = QuadGrid::new(rows, cols, vertices, normals);
    if !along_rows {
        grid = grid.transposed();
    }
    let scale = grid.bbox_diagonal().max(f64::MIN_POSITIVE);
    let patches = built
        .into_iter()
        .zip(ranges)
        .map(|(b, range)| PatchInfo {
            size: (b.generated.grid.rows, b.generated.grid.cols),
            mode: b.generated.info.mode,
            theta_range: b.generated.info.theta_range,
            folded_faces: b.generated.report.folded_faces,
            design: b.design,
            range,
            reversed: b.sign < 0.0,
            seam_gap: b.seam_gap_abs / scale,
            axis_gap: b.axis_gap,
            kink_deg: b.kink_deg,
        })
        .collect();
    MultiPatch {
        grid,
        along_rows,
        patches,
    }
}
