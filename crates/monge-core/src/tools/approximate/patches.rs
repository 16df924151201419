//! The second step of an approximation (§4.7): where one patch cannot follow the
//! target, several patches with piecewise planar curvature lines.
//!
//! The single patch's `guide_u` is cut into `K` pieces of nearly equal numbers of
//! samples. Patch 0 keeps the first piece and `guide_v`; patch `k` is attached to the
//! last row of patch `k − 1` and continues along piece `k` (one planar bottom guide
//! cut into pieces, which [`crate::multipatch::build`] always accepts), with its own
//! θ: the curvature lines across `guide_u` are planar in each patch and change plane
//! at each seam, where the beams stay C¹ (§4.7). Each new patch's θ comes from a scan
//! every 10° with the earlier patches fixed, then BOBYQA moves all the θ together,
//! with the objective of the single patch (folded meshes infeasible).

use super::{
    ApproxError, ApproxOptions, Approximation, Deviation, Progress, TargetCloud, OBJECTIVE_POINTS,
};
use crate::design::{GuideSpec, MeshKind};
use crate::generate::GenerateOptions;
use crate::grid::QuadGrid;
use crate::guide::{Guide, GuideName};
use crate::multipatch::{build, Attach, MultiPatchDesign, PatchSpec, Side};

/// The result of [`approximate_patches`].
#[derive(Clone, Debug)]
pub struct PatchApproximation {
    /// The multi-patch design found (§4.7).
    pub design: MultiPatchDesign,
    /// Its mesh, the patches merged (shared lines once).
    pub grid: QuadGrid,
    /// Deviation of the single patch it started from.
    pub before: Deviation,
    /// Deviation of the multi-patch mesh.
    pub after: Deviation,
    /// Meshes generated in all.
    pub evaluations: usize,
}

/// Several patches following the target more closely than the single patch `single`
/// (§4.7; see the module documentation): `patches` pieces of its `guide_u`, each with
/// its own θ. Circular meshes only; every piece needs at least two faces.
///
/// ```
/// use glam::DVec3;
/// use monge_core::approximate::{approximate, approximate_patches, ApproxOptions};
/// // A paraboloid, which has no planar curvature lines.
/// let target: Vec<DVec3> = (0..121)
///     .map(|k| {
///         let (x, y) = ((k % 11) as f64, (k / 11) as f64);
///         DVec3::new(x, y, 0.04 * x * x + 0.1 * y * y)
///     })
///     .collect();
/// let options = ApproxOptions { faces: (8, 8), starts: 1, max_evaluations: 60, ..Default::default() };
/// let single = approximate(&target, &options, &mut |_| {}).unwrap();
/// let two = approximate_patches(&target, &single, 2, &options, &mut |_| {}).unwrap();
/// assert_eq!(two.design.patches.len(), 2);
/// assert!(two.after.mesh_to_target_rms.is_finite());
/// ```
pub fn approximate_patches(
    points: &[glam::DVec3],
    single: &Approximation,
    patches: usize,
    options: &ApproxOptions,
    progress: &mut dyn FnMut(&Progress),
) -> Result<PatchApproximation, ApproxError> {
    if single.design.mesh != MeshKind::Circular {
        return Err(ApproxError::PatchesNotCircular);
    }
    let guide: Vec<_> = single.grid.column(0).map(|p| p.to_array()).collect();
    let segments = guide.len() - 1;
    if patches < 2 || segments < 2 * patches {
        return Err(ApproxError::TooManyPatches { patches, segments });
    }
    let target = TargetCloud::new(points)?;
    // The first piece keeps guide_u's own start tangent (a polyline's would be its
    // first chord).
    let tangent = Guide::from_spec(
        &single.design.guide_u,
        GuideName::U,
        &single.design.tolerance.unwrap_or_default(),
    )
    .map_err(|_| ApproxError::NoPatchStart { patch: 0 })?
    .tangent
    .to_array();
    let stride = points.len().div_ceil(OBJECTIVE_POINTS);
    let cut = |k: usize| k * segments / patches;
    let specs: Vec<PatchSpec> = (0..patches)
        .map(|k| {
            let piece = guide[cut(k)..=cut(k + 1)].to_vec();
            if k == 0 {
                PatchSpec {
                    theta_deg: single.design.theta_deg,
                    guide_u: Some(GuideSpec::Points {
                        points: piece,
                        tangent: Some(tangent),
                    }),
                    guide_v: Some(single.design.guide_v.clone()),
                    attach: None,
                    guide: None,
                }
            } else {
                PatchSpec {
                    theta_deg: 0.0,
                    guide_u: None,
                    guide_v: None,
                    attach: Some(Attach {
                        patch: k - 1,
                        side: Side::LastRow,
                    }),
                    guide: Some(GuideSpec::points(piece)),
                }
            }
        })
        .collect();
    let tolerance = single.design.tolerance;
    let design_of = |thetas: &[f64]| MultiPatchDesign {
        patches: specs
            .iter()
            .zip(thetas)
            .map(|(s, t)| PatchSpec {
                theta_deg: *t,
                ..s.clone()
            })
            .collect(),
        tolerance,
        fit: None,
        symmetry: vec![],
    };
    let mut evaluations = 0;
    let budget = patches * 359 + options.max_evaluations;
    let mut best = f64::INFINITY;
    // The objective of the first `thetas.len()` patches; NaN when they cannot be built
    // or fold.
    let mut objective = |thetas: &[f64]| -> f64 {
        evaluations += 1;
        let f = build(&design_of(thetas), &GenerateOptions::default())
            .ok()
            .filter(|mp| mp.grid.folds().count() == 0)
            .map_or(f64::NAN, |mp| {
                target.deviation_strided(&mp.grid, stride).objective()
            });
        if f < best {
            best = f;
        }

        progress(&Progress {
            evaluations,
            budget,
            best_rms: best.sqrt(),
        });
        f
    };
    // The single patch's θ continues its surface in every patch (the same θ in each
    // patch's own frame); where that folds, each new patch's θ by a scan, the earlier
    // ones fixed.
    let mut thetas = vec![single.design.theta_deg; patches];
    if !objective(&thetas).is_finite() {
        thetas.truncate(1);
        for patch in 1..patches {
            // Every degree: the θ that keep a continuation fair can be a narrow window.
            let scan = (-179..=179).map(f64::from);
            let theta = scan
                .map(|theta| {
                    let mut trial = thetas.clone();
                    trial.push(theta);
                    (objective(&trial), theta)
                })
                .filter(|(f, _)| f.is_finite())
                .min_by(|a, b| a.0.total_cmp(&b.0))
                .ok_or(ApproxError::NoPatchStart { patch })?
                .1;
            thetas.push(theta);
        }
    }
    // All θ together, within 30° of their start.
    let unit = objective(&thetas);
    if !unit.is_finite() {
        return Err(ApproxError::NoPatchStart { patch: 0 });
    }
    let lower: Vec<f64> = thetas.iter().map(|t| (t - 30.0).max(-179.0)).collect();
    let upper: Vec<f64> = thetas.iter().map(|t| (t + 30.0).min(179.0)).collect();
    let to_real = |t: &[f64]| -> Vec<f64> {
        t.iter()
            .zip(lower.iter().zip(&upper))
            .map(|(t, (l, u))| l + t * (u - l))
            .collect()
    };
    let mut t: Vec<f64> = thetas
        .iter()
        .zip(lower.iter().zip(&upper))
        .map(|(x, (l, u))| (x - l) / (u - l))
        .collect();
    let mut config = bobyqa::Config::new(patches);
    config.rho_begin = 0.05;
    config.rho_end = 1e-7;
    config.max_fun = options.max_evaluations.max(2 * patches + 2);
    let mut solver = bobyqa::Bobyqa::new(patches, config).expect("a valid BOBYQA configuration");
    let outcome = solver.minimize(
        |t: &[f64]| objective(&to_real(t)) / unit,
        &mut t,
        &vec![0.0; patches],
        &vec![1.0; patches],
    );
    if outcome.found_finite() && outcome.f < 1.0 {
        thetas = to_real(&t);
    }
    let design = design_of(&thetas);
    let grid = build(&design, &GenerateOptions::default())
        .map_err(|_| ApproxError::NoPatchStart { patch: 0 })?
        .grid;
    Ok(PatchApproximation {
        after: target.deviation(&grid),
        before: single.after,
        design,
        grid,
        evaluations,
    })
}
