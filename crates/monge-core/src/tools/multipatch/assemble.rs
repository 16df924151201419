//! The assembly of generated patches into one grid (§4.7): each patch in its block,
//! running the layout's way with its normals to one side, shared lines stored once
//! (the earlier patch's copy).

use glam::DVec3;

use crate::design::Design;
use crate::generate::Generated;
use crate::QuadGrid;

use super::layout::Layout;
use super::mesh::{MultiPatch, PatchInfo};

/// One generated patch before assembly.
pub(super) struct Built {
    pub(super) generated: Generated,
    pub(super) design: Design,
    pub(super) seam_gap_abs: f64,
    pub(super) axis_gap: f64,
    pub(super) kink_deg: f64,
}

/// First index of each block along one direction, from the blocks' vertex counts
/// (neighbouring blocks share a line), and the total.
fn starts(sizes: &[usize]) -> (Vec<usize>, usize) {
    let mut out = Vec::with_capacity(sizes.len());
    let mut at = 0;
    for s in sizes {
        out.push(at);
        at += s - 1;
    }
    (out, at + 1)
}

/// Assemble the patches into one grid, each in its block of the layout.
pub(super) fn assemble(built: Vec<Built>, layout: &Layout) -> MultiPatch {
    let (block_rows, block_cols) = layout.blocks;
    let mut heights = vec![0; block_rows];
    let mut widths = vec![0; block_cols];
    for (b, p) in built.iter().zip(&layout.placements) {
        heights[p.block.0] = b.generated.grid.rows;
        widths[p.block.1] = b.generated.grid.cols;
    }
    let (row_starts, rows) = starts(&heights);
    let (col_starts, cols) = starts(&widths);
    let mut vertices = vec![DVec3::ZERO; rows * cols];
    let mut normals = vec![DVec3::ZERO; rows * cols];
    let mut written = vec![false; rows * cols];
    let mut infos = Vec::with_capacity(built.len());
    for (b, p) in built.into_iter().zip(&layout.placements) {
        let g = &b.generated.grid;
        let origin = (row_starts[p.block.0], col_starts[p.block.1]);
        let sign = p.sign();
        for i in 0..g.rows {
            for j in 0..g.cols {
                let a = origin.0 + if p.flip.0 { g.rows - 1 - i } else { i };
                let c = origin.1 + if p.flip.1 { g.cols - 1 - j } else { j };
                let at = a * cols + c;
                if !written[at] {
                    written[at] = true;
                    vertices[at] = g.vertices[g.index(i, j)];
                    normals[at] = sign * g.normals[g.index(i, j)];
                }
            }
        }
        infos.push((b, *p, origin));
    }
    let grid = QuadGrid::new(rows, cols, vertices, normals);
    let along_rows = block_cols == 1;
    let scale = grid.bbox_diagonal().max(f64::MIN_POSITIVE);
    let patches = infos
        .into_iter()
        .map(|(b, p, origin)| {
            let size = (b.generated.grid.rows, b.generated.grid.cols);
            let rows = (origin.0, origin.0 + size.0 - 1);
            let cols = (origin.1, origin.1 + size.1 - 1);
            PatchInfo {
                size,
                mode: b.generated.info.mode,
                theta_range: b.generated.info.theta_range,
                folded_faces: b.generated.report.folded_faces,
                design: b.design,
                range: if along_rows { rows } else { cols },
                reversed: if along_rows { p.flip.0 } else { p.flip.1 },
                block: p.block,
                rows,
                cols,
                flipped: p.flip,
                seam_gap: b.seam_gap_abs / scale,
                axis_gap: b.axis_gap,
                kink_deg: b.kink_deg,
            }
        })
        .collect();
    MultiPatch {
        grid,
        along_rows,
        layout: layout.blocks,
        patches,
    }
}
