//! Building a multi-patch mesh (§4.7): the first patch from its two guides, every
//! later one attached to earlier ones, then one grid.

use crate::design::{Design, MeshKind};
use crate::generate::{generate, GenerateOptions};

use super::assemble::{assemble, Built};
use super::attach::{attach_patch, Continuation};
use super::error::MultiPatchError;
use super::layout::check_layout;
use super::mesh::MultiPatch;
use super::spec::MultiPatchDesign;

/// Build a multi-patch mesh (§4.7): every patch in design order, then one grid.
///
/// ```
/// use monge_core::multipatch::{build, Attach, MultiPatchDesign, PatchSpec, Side};
/// use monge_core::{GenerateOptions, GuideSpec};
/// let arc = |c: [f64; 3], s: [f64; 3], n: [f64; 3], a: f64| GuideSpec::arc(c, s, n, a, 7);
/// let design = MultiPatchDesign {
///     patches: vec![
///         PatchSpec { theta_deg: 30.0, guide_u: Some(arc([0.0, 0.0, -4.0], [0.0; 3], [0.0, -1.0, 0.0], 20.0)),
///                     guide_v: Some(arc([0.0, 0.0, -3.0], [0.0; 3], [1.0, 0.0, 0.0], 25.0)), attach: None, guide: None,
///                     guide_from: None },
///         PatchSpec { theta_deg: -20.0, guide_u: None, guide_v: None,
///                     attach: Some(Attach { patch: 0, side: Side::LastRow }),
///                     guide: Some(arc([0.0, 0.0, -4.0], [-4.0 * 20f64.to_radians().sin(), 0.0, 4.0 * 20f64.to_radians().cos() - 4.0],
///                                     [0.0, -1.0, 0.0], 20.0)), guide_from: None },
///     ],
///     tolerance: None, fit: None, symmetry: vec![],
/// };
/// let mp = build(&design, &GenerateOptions::default()).unwrap();
/// assert_eq!((mp.grid.rows, mp.grid.cols), (13, 7));
/// assert_eq!(mp.boundary(0, Side::LastRow), mp.boundary(1, Side::FirstRow));
/// ```
pub fn build(
    design: &MultiPatchDesign,
    options: &GenerateOptions,
) -> Result<MultiPatch, MultiPatchError> {
    build_with(design, options, &mut |_, _, guide| guide.clone())
}

/// [`build`], each continuation chosen by `continuation` from where it starts
/// ([`ContinuationStart`](super::ContinuationStart)) and the design's own `guide` (the
/// guide it returns must start at the corner, with the forced tangent in its plane):
/// a search can move a continuation in the plane it must lie in, which depends on
/// the patches before it.
pub fn build_with(
    design: &MultiPatchDesign,
    options: &GenerateOptions,
    continuation: &mut Continuation,
) -> Result<MultiPatch, MultiPatchError> {
    let tol = design.tolerance.unwrap_or_default();
    let layout = check_layout(design)?;
    let mut built: Vec<Built> = Vec::with_capacity(design.patches.len());
    for (k, spec) in design.patches.iter().enumerate() {
        let Some(attach) = spec.attach else {
            let d = Design {
                theta_deg: spec.theta_deg,
                guide_u: spec.guide_u.clone().expect("checked"),
                guide_v: spec.guide_v.clone().expect("checked"),
                mesh: MeshKind::Circular,
                tolerance: design.tolerance,
            };
            let generated = generate(&d, options)
                .map_err(|source| MultiPatchError::Generate { patch: k, source })?;
            built.push(Built {
                generated,
                design: d,
                seam_gap_abs: 0.0,
                axis_gap: 0.0,
                kink_deg: 0.0,
            });
            continue;
        };
        let from = spec.guide_from.map(|f| &built[f.patch]);
        let next = attach_patch(
            k,
            spec,
            &built[attach.patch],
            from,
            &tol,
            design.tolerance,
            options,
            continuation,
        )?;
        built.push(next);
    }
    Ok(assemble(built, &layout))
}
