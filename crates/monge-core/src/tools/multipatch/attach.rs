//! A patch attached to a side of an earlier patch (§4.7): the boundary line and
//! the continuation (or another earlier patch's line) as its guides, with the start
//! tangents that carry the normals across the seams.

use glam::DVec3;

use crate::design::{Design, GuideSpec, MeshKind, Tolerances, Xyz};
use crate::generate::{check_grid_size, generate, GenerateOptions};
use crate::guide::{Guide, GuideName};
use crate::QuadGrid;

use super::assemble::Built;
use super::error::MultiPatchError;
use super::planes::fit_plane;
use super::side::{Attach, Side};
use super::spec::PatchSpec;

/// Where the continuation of a patch attached to an earlier one starts (§4.7): what
/// its guide must respect to be accepted (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContinuationStart {
    /// The boundary's first vertex, where the continuation starts.
    pub corner: DVec3,
    /// The forced start tangent of the continuation (unit).
    pub tangent: DVec3,
    /// The node axis at the corner, in the new patch's orientation (unit).
    pub axis: DVec3,
    /// Unit normal of a plane containing `tangent`: that of the earlier patch's line
    /// the continuation continues (its guide on that side), made orthogonal to `tangent`.
    pub plane_normal: DVec3,
}

/// Chooses the continuation of patch `k` from where it starts and the design's own
/// `guide` ([`build_with`](super::build_with)).
pub type Continuation<'a> = dyn FnMut(usize, &ContinuationStart, &GuideSpec) -> GuideSpec + 'a;

/// The line on `side` of a patch's own grid, with its node axes.
pub(super) fn own_line(grid: &QuadGrid, side: Side) -> (Vec<DVec3>, Vec<DVec3>) {
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

/// A side's line of an earlier patch as a guide of patch `k`, with its node axes and
/// its start tangent (orthogonal to the corner's axis, in the line's plane).
struct Line {
    points: Vec<DVec3>,
    axes: Vec<DVec3>,
    guide: Guide,
    tangent: DVec3,
}

fn line_of(
    k: usize,
    at: Attach,
    built: &Built,
    tol: &Tolerances,
) -> Result<(Line, Vec<Xyz>), MultiPatchError> {
    let (points, axes) = own_line(&built.generated.grid, at.side);
    let name = if at.side.is_row() {
        GuideName::V
    } else {
        GuideName::U
    };
    let raw: Vec<Xyz> = points.iter().map(|p| p.to_array()).collect();
    let guide = Guide::from_spec(&GuideSpec::points(raw.clone()), name, tol).map_err(|source| {
        MultiPatchError::Boundary {
            patch: k,
            side: at.side.name(),
            to: at.patch,
            source,
        }
    })?;
    let mut tangent = guide.plane_normal.cross(axes[0]).normalize();
    if tangent.dot(points[1] - points[0]) < 0.0 {
        tangent = -tangent;
    }
    Ok((
        Line {
            points,
            axes,
            guide,
            tangent,
        },
        raw,
    ))
}

/// Largest distance between the shared line as patch `k` generated it (its first row
/// or column) and the earlier patch's, and between their node axes (`s` the sign of
/// the new patch's normals relative to the earlier one's).
fn gaps(generated: &QuadGrid, row: bool, line: &Line, s: f64) -> (f64, f64) {
    let side = if row {
        Side::FirstRow
    } else {
        Side::FirstColumn
    };
    let (own, own_axes) = own_line(generated, side);
    let seam = own
        .iter()
        .zip(&line.points)
        .map(|(a, b)| a.distance(*b))
        .fold(0.0, f64::max);
    let axis = own_axes
        .iter()
        .zip(&line.axes)
        .map(|(a, b)| (s * *a).distance(*b))
        .fold(0.0, f64::max);
    (seam, axis)
}

/// Generate patch `k` attached to `attach` of `parent`, its other guide the
/// continuation (`continuation` chooses it) or the `guide_from` line of `from` (see
/// the module docs).
#[allow(clippy::too_many_arguments)]
pub(super) fn attach_patch(
    k: usize,
    spec: &PatchSpec,
    parent: &Built,
    from: Option<&Built>,
    tol: &Tolerances,
    tolerance: Option<Tolerances>,
    options: &GenerateOptions,
    continuation: &mut Continuation,
) -> Result<Built, MultiPatchError> {
    let attach = spec.attach.expect("checked");
    let side = attach.side;
    let (boundary, boundary_points) = line_of(k, attach, parent, tol)?;
    let (corner, n_c) = (boundary.points[0], boundary.axes[0]);
    let t_b = boundary.tangent;
    let s = if side.is_last() { 1.0 } else { -1.0 };
    let n_target = s * n_c;
    let (other_guide, boundary_tangent, kink_deg, other) = match (from, spec.guide_from) {
        (Some(from_built), Some(at)) => {
            let (line, raw) = line_of(k, at, from_built, tol)?;
            let distance = line.points[0].distance(corner);
            let relative = distance / line.guide.size.max(boundary.guide.size);
            if relative.is_nan() || relative > tol.start {
                return Err(MultiPatchError::CornerMismatch {
                    patch: k,
                    attach,
                    from: at,
                    corner: corner.to_array(),
                    other: line.points[0].to_array(),
                    distance,
                    relative,
                    tolerance: tol.start,
                });
            }
            let other_axis = if at.side.is_last() { 1.0 } else { -1.0 } * line.axes[0];
            let angle = n_target
                .cross(other_axis)
                .length()
                .atan2(n_target.dot(other_axis));
            if angle.is_nan() || angle > tol.angle {
                return Err(MultiPatchError::AxisMismatch {
                    patch: k,
                    attach,
                    from: at,
                    axis: n_target.to_array(),
                    other: other_axis.to_array(),
                    angle,
                    tolerance: tol.angle,
                });
            }
            // The lines' own start tangents meet at 90° only in the limit: each is
            // turned about the axis by half the difference, so that they meet at 90°
            // (the nearest orthonormal pair, with the same orientation).
            let (t_u0, t_v0) = if side.is_row() {
                (line.tangent, t_b)
            } else {
                (t_b, line.tangent)
            };
            let (w1, w2) = ((t_u0 + t_v0).normalize(), (t_u0 - t_v0).normalize());
            let (t_u, t_v) = ((w1 + w2).normalize(), (w1 - w2).normalize());
            let turned = t_u.dot(t_u0).clamp(-1.0, 1.0).acos().to_degrees();
            let (own, boundary_tangent) = if side.is_row() {
                (t_u, t_v)
            } else {
                (t_v, t_u)
            };
            let (rows, cols) = if side.is_row() {
                (line.points.len(), boundary.points.len())
            } else {
                (boundary.points.len(), line.points.len())
            };
            check_grid_size(rows, cols, options)
                .map_err(|source| MultiPatchError::Generate { patch: k, source })?;
            let guide = GuideSpec::Points {
                points: raw,
                tangent: Some(own.to_array()),
            };
            (guide, boundary_tangent, turned, Some((line, at)))
        }
        _ => {
            let t_cont = if side.is_row() {
                t_b.cross(n_target)
            } else {
                n_target.cross(t_b)
            }
            .normalize();
            // The parent's line through the corner that the continuation continues.
            let (along, _) = own_line(
                &parent.generated.grid,
                if side.is_row() {
                    Side::FirstColumn
                } else {
                    Side::FirstRow
                },
            );
            let m = fit_plane(&along).1;
            let start = ContinuationStart {
                corner,
                tangent: t_cont,
                axis: n_target,
                plane_normal: (m - m.dot(t_cont) * t_cont).normalize_or_zero(),
            };
            let cont_spec = continuation(k, &start, spec.guide.as_ref().expect("checked"));
            let (cont, kink_deg) =
                continue_from(k, &cont_spec, &start, &boundary, attach, tol, options)?;
            (cont, t_b, kink_deg, None)
        }
    };
    let boundary_guide = GuideSpec::Points {
        points: boundary_points,
        tangent: Some(boundary_tangent.to_array()),
    };
    let (guide_u, guide_v) = if side.is_row() {
        (other_guide, boundary_guide)
    } else {
        (boundary_guide, other_guide)
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
    let (mut seam_gap_abs, mut axis_gap) = gaps(&generated.grid, side.is_row(), &boundary, s);
    if let Some((line, at)) = &other {
        let s_f = if at.side.is_last() { 1.0 } else { -1.0 };
        let (seam, axis) = gaps(&generated.grid, !side.is_row(), line, s_f);
        seam_gap_abs = seam_gap_abs.max(seam);
        axis_gap = axis_gap.max(axis);
    }
    Ok(Built {
        generated,
        design,
        seam_gap_abs,
        axis_gap,
        kink_deg,
    })
}

/// The continuation `cont_spec` of patch `k` checked against its start and made to
/// start there with the forced tangent; with the kink it had.
fn continue_from(
    k: usize,
    cont_spec: &GuideSpec,
    start: &ContinuationStart,
    boundary: &Line,
    attach: Attach,
    tol: &Tolerances,
    options: &GenerateOptions,
) -> Result<(GuideSpec, f64), MultiPatchError> {
    let (to, side) = (attach.patch, attach.side);
    let (corner, t_cont) = (start.corner, start.tangent);
    // The patch's grid, refused before its guide is sampled if too large.
    let (rows, cols) = if side.is_row() {
        (cont_spec.sample_count(), boundary.points.len())
    } else {
        (boundary.points.len(), cont_spec.sample_count())
    };
    check_grid_size(rows, cols, options)
        .map_err(|source| MultiPatchError::Generate { patch: k, source })?;
    let cont_name = if side.is_row() {
        GuideName::U
    } else {
        GuideName::V
    };
    let cont = Guide::from_spec(cont_spec, cont_name, tol)
        .map_err(|source| MultiPatchError::Guide { patch: k, source })?;
    let size = cont.size.max(boundary.guide.size);
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
            axis: boundary.axes[0].to_array(),
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
    Ok((
        GuideSpec::Points {
            points: cont_points,
            tangent: Some(t_cont.to_array()),
        },
        kink_deg,
    ))
}
