//! A patch attached to a side of an earlier patch (§4.7): the boundary line and
//! the continuation as its guides, with the start tangents that carry the normals
//! across the seam.

use glam::DVec3;

use crate::design::{Design, GuideSpec, MeshKind, Tolerances, Xyz};
use crate::generate::{check_grid_size, generate, GenerateOptions};
use crate::guide::{Guide, GuideName};
use crate::QuadGrid;

use super::assemble::Built;
use super::error::MultiPatchError;
use super::side::{Attach, Side};
use super::spec::PatchSpec;

/// The line on `side` of a patch's own grid, with its node axes.
fn own_line(grid: &QuadGrid, side: Side) -> (Vec<DVec3>, Vec<DVec3>) {
    let idx: Vec<usize> = match side {
        Side::FirstRow => (0..grid.cols).map(|j| grid.index(0, j)).collect(),
        Side::LastRow => (0..grid.cols)
            .map(|j| grid.index(grid.rows - 1, j))
            .collect(),
        Side::FirstColumn => (0..grid.rows).map(|i| grid.index(i, 0)).collect(),
        Side::LastColumn => (0..grid.rows)
            .map(|i| grid.index(i, grid.cols - 1))
            .collect(),
    };
    (
        idx.iter().map(|&k| grid.vertices[k]).collect(),
        idx.iter().map(|&k| grid.normals[k]).collect(),
    )
}

/// Generate patch `k` attached to `attach` of `parent` (see the module docs).
pub(super) fn attach_patch(
    k: usize,
    spec: &PatchSpec,
    attach: Attach,
    parent: &Built,
    tol: &Tolerances,
    tolerance: Option<Tolerances>,
    options: &GenerateOptions,
) -> Result<Built, MultiPatchError> {
    let to = attach.patch;
    let side = attach.side;
    let (line, axes) = own_line(&parent.generated.grid, side);
    let boundary_name = if side.is_row() {
        GuideName::V
    } else {
        GuideName::U
    };
    let boundary_points: Vec<Xyz> = line.iter().map(|p| p.to_array()).collect();
    let boundary_spec = GuideSpec::points(boundary_points.clone());
    let boundary = Guide::from_spec(&boundary_spec, boundary_name, tol).map_err(|source| {
        MultiPatchError::Boundary {
            patch: k,
            side: side.name(),
            to,
            source,
        }
    })?;
    let (corner, n_c) = (line[0], axes[0]);
    let mut t_b = boundary.plane_normal.cross(n_c).normalize();
    if t_b.dot(line[1] - line[0]) < 0.0 {
        t_b = -t_b;
    }
    let n_target = if side.is_last() { n_c } else { -n_c };
    let t_cont = if side.is_row() {
        t_b.cross(n_target)
    } else {
        n_target.cross(t_b)
    }
    .normalize();
    let cont_name = if side.is_row() {
        GuideName::U
    } else {
        GuideName::V
    };
    let cont_spec = spec.guide.as_ref().expect("checked");
    // The patch's grid, refused before its guide is sampled if too large.
    let (rows, cols) = if side.is_row() {
        (cont_spec.sample_count(), line.len())
    } else {
        (line.len(), cont_spec.sample_count())
    };
    check_grid_size(rows, cols, options)
        .map_err(|source| MultiPatchError::Generate { patch: k, source })?;
    let cont = Guide::from_spec(cont_spec, cont_name, tol)
        .map_err(|source| MultiPatchError::Guide { patch: k, source })?;
    let size = cont.size.max(boundary.size);
    let distance = cont.points[0].distance(corner);
    let relative = distance / size;
    if relative.is_nan() || relative > tol.start {
        return Err(MultiPatchError::StartMismatch {
            patch: k,
            side: side.name(),
            to,
            start: cont.points[0].to_array(),
            corner: corner.to_array(),
            distance,
            relative,
            tolerance: tol.start,
        });
    }
    let off = t_cont.dot(cont.plane_normal).abs();
    if off > tol.angle.sin() {
        return Err(MultiPatchError::TangentOffPlane {
            patch: k,
            to,
            tangent: t_cont.to_array(),
            axis: n_c.to_array(),
            plane_normal: cont.plane_normal.to_array(),
            angle_deg: off.clamp(0.0, 1.0).asin().to_degrees(),
        });
    }
    if t_cont.dot(cont.points[1] - corner) <= 0.0 {
        return Err(MultiPatchError::TurnsBack {
            patch: k,
            to,
            tangent: t_cont.to_array(),
        });
    }
    let kink_deg = cont
        .tangent
        .dot(t_cont)
        .clamp(-1.0, 1.0)
        .acos()
        .to_degrees();
    let mut cont_points: Vec<Xyz> = cont.points.iter().map(|p| p.to_array()).collect();
    cont_points[0] = corner.to_array();
    let cont_guide = GuideSpec::Points {
        points: cont_points,
        tangent: Some(t_cont.to_array()),
    };
    let boundary_guide = GuideSpec::Points {
        points: boundary_points,
        tangent: Some(t_b.to_array()),
    };
    let (guide_u, guide_v) = if side.is_row() {
        (cont_guide, boundary_guide)
    } else {
        (boundary_guide, cont_guide)
    };
    let design = Design {
        theta_deg: spec.theta_deg,
        guide_u,
        guide_v,
        mesh: MeshKind::Circular,
        tolerance,
    };
    let generated = generate(&design, options)
        .map_err(|source| MultiPatchError::Generate { patch: k, source })?;
    // The shared line as the child generated it: its guide on the boundary side.
    let child_side = if side.is_row() {
        Side::FirstRow
    } else {
        Side::FirstColumn
    };
    let (own, own_axes) = own_line(&generated.grid, child_side);
    let seam_gap_abs = own
        .iter()
        .zip(&line)
        .map(|(a, b)| a.distance(*b))
        .fold(0.0, f64::max);
    let s = if side.is_last() { 1.0 } else { -1.0 };
    let axis_gap = own_axes
        .iter()
        .zip(&axes)
        .map(|(a, b)| (s * *a).distance(*b))
        .fold(0.0, f64::max);
    Ok(Built {
        generated,
        design,
        sign: s * parent.sign,
        parent: Some(to),
        seam_gap_abs,
        axis_gap,
        kink_deg,
    })
}
