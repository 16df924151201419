//! A built multi-patch mesh (§4.7): the assembled grid, where each patch lies in
//! it, and each patch's own grid and boundaries read back from it.

use glam::DVec3;

use crate::design::Design;
use crate::gauss_map::ThetaRange;
use crate::generate::Mode;
use crate::measure::measure;
use crate::QuadGrid;

use super::side::Side;

/// A patch of a built [`MultiPatch`] (§4.7).
#[derive(Clone, Debug)]
pub struct PatchInfo {
    /// The exact design the patch was generated from (for attached patches: the
    /// boundary and the continuation as `points` guides with their forced tangents).
    pub design: Design,
    /// First and last index, along the chain direction ([`MultiPatch::along_rows`]:
    /// rows, else columns), of the patch in the assembled grid (inclusive).
    pub range: (usize, usize),
    /// Whether the patch runs backwards in the assembled grid (its own `i`, or `j`
    /// for column chains, decreasing); its normals are then negated there.
    pub reversed: bool,
    /// Its block (row, column) in the layout ([`MultiPatch::layout`]).
    pub block: (usize, usize),
    /// First and last row of the patch in the assembled grid (inclusive).
    pub rows: (usize, usize),
    /// First and last column of the patch in the assembled grid (inclusive).
    pub cols: (usize, usize),
    /// Whether the patch's own `i`, then `j`, runs backwards in the assembled grid;
    /// its normals are negated there when exactly one does.
    pub flipped: (bool, bool),
    /// The patch's own grid size `(rows, cols)`.
    pub size: (usize, usize),
    /// The generation mode of the patch (§3.1 or §3.2).
    pub mode: Mode,
    /// The admissible θ of the patch, given the patches it is attached to (§3.2).
    pub theta_range: ThetaRange,
    /// Folded faces found by the Combescure transform (§5.2).
    pub folded_faces: usize,
    /// Largest distance, relative to the assembled grid's size, between the shared
    /// line as this patch generated it and the earlier patch's line kept in the
    /// grid (round-off of the plane projection of the guide; 0 for the first patch).
    pub seam_gap: f64,
    /// Largest difference between this patch's node axes along the shared line and
    /// the earlier patch's (continuity of the normals, §4.7; 0 for the first patch).
    pub axis_gap: f64,
    /// Angle in degrees between the continuation's own start tangent and the forced
    /// one (0 for the first patch): the kink the continuation would have had. For a
    /// patch with `guide_from`: the angle by which each line's start tangent was
    /// turned so that they meet at 90° (half their departure from 90°).
    pub kink_deg: f64,
}

/// A multi-patch mesh (§4.7): one grid and where each patch lies in it.
#[derive(Clone, Debug)]
pub struct MultiPatch {
    /// The assembled grid; shared lines are stored once.
    pub grid: QuadGrid,
    /// Whether the patches follow each other along rows (index `i`), else columns:
    /// true when the layout has one block column.
    pub along_rows: bool,
    /// Block rows × block columns of the layout: `(K, 1)` for patches following each
    /// other along rows, `(1, K)` along columns, `(U, V)` for `U × V` patches.
    pub layout: (usize, usize),
    /// The patches, in design order.
    pub patches: Vec<PatchInfo>,
}

impl MultiPatch {
    /// Assembled-grid index of vertex `(i, j)` of patch `k`'s own grid (§4.7).
    pub fn own_to_grid(&self, k: usize, i: usize, j: usize) -> (usize, usize) {
        let p = &self.patches[k];
        let (rows, cols) = p.size;
        (
            p.rows.0 + if p.flipped.0 { rows - 1 - i } else { i },
            p.cols.0 + if p.flipped.1 { cols - 1 - j } else { j },
        )
    }

    /// The largest error of its patches, each measured on its own grid
    /// ([`MultiPatch::patch_grid`]) as `monge check` measures a mesh: a multi-patch
    /// mesh's curvature lines are planar only piecewise (§4.7).
    pub fn max_error(&self) -> f64 {
        (0..self.patches.len())
            .map(|k| measure(&self.patch_grid(k)).max_error())
            .fold(0.0, f64::max)
    }

    /// Patch `k` as its own grid, cut out of the assembled one (shared lines with
    /// the bits of the assembled grid), with the normals of the assembled grid
    /// negated back where exactly one of its directions is flipped, so that it can be measured (§4.7).
    pub fn patch_grid(&self, k: usize) -> QuadGrid {
        let (rows, cols) = self.patches[k].size;
        let (fi, fj) = self.patches[k].flipped;
        let sign = if fi == fj { 1.0 } else { -1.0 };
        let mut vertices = Vec::with_capacity(rows * cols);
        let mut normals = Vec::with_capacity(rows * cols);
        for i in 0..rows {
            for j in 0..cols {
                let (a, b) = self.own_to_grid(k, i, j);
                let g = self.grid.index(a, b);
                vertices.push(self.grid.vertices[g]);
                normals.push(sign * self.grid.normals[g]);
            }
        }
        QuadGrid::new(rows, cols, vertices, normals)
    }

    /// The line on `side` of patch `k`, in the patch's own order (§4.7).
    pub fn boundary(&self, k: usize, side: Side) -> Vec<DVec3> {
        let (rows, cols) = self.patches[k].size;
        let at = |i: usize, j: usize| {
            let (a, b) = self.own_to_grid(k, i, j);
            self.grid.vertex(a, b)
        };
        match side {
            Side::FirstRow => (0..cols).map(|j| at(0, j)).collect(),
            Side::LastRow => (0..cols).map(|j| at(rows - 1, j)).collect(),
            Side::FirstColumn => (0..rows).map(|i| at(i, 0)).collect(),
            Side::LastColumn => (0..rows).map(|i| at(i, cols - 1)).collect(),
        }
    }
}
