//! The picture of `monge approximate --picture`: the target's points, the initial guess
//! and the result, each coloured by its distance to the other side, on one scale; the
//! boundaries between patches and the trimming's cut drawn on the result.

use anyhow::Context;
use glam::DVec3;
use monge_core::approximate::{
    target_distances, Approximation, Deviation, TargetCloud, TrimmedMesh,
};
use monge_core::conical::conical_dual;
use monge_core::multipatch::MultiPatch;
use monge_core::{generate, Design, GenerateOptions, MeshKind, QuadGrid};
use monge_render::{heat, Dot, Highlight, Panel, RenderOptions, Rgb, Scene};

use crate::shared::output::num;
use crate::shared::picture::{
    cut_highlights, distance_panel, sheet, trimmed_distance_panel, Picture,
};

/// Colour of the target's stray points, which the fit sets aside.
const STRAY_COLOR: Rgb = Rgb::new(30, 100, 220);

/// How far from the box of the points kept a stray point is drawn, in the target's
/// sizes: a point farther off would shrink the target to a speck in its panel.
const STRAY_REACH: f64 = 1.0;

/// Half the length of the arms of the star marking a stray point, in the target's sizes.
const STRAY_STAR: f64 = 0.015;

/// `target`'s stray points (indices into `points`, the points it was given) within
/// [`STRAY_REACH`] of the box of the points it keeps, each a dot in a star of three
/// arms along the axes (a dot alone is lost among the others), and how many lie
/// farther.
fn stray_marks(points: &[DVec3], target: &TargetCloud) -> (Vec<Dot>, Vec<Highlight>, usize) {
    let kept = target.points();
    let (low, high) = kept
        .iter()
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(l, h), p| {
            (l.min(*p), h.max(*p))
        });
    let reach = STRAY_REACH * target.size();
    let (near, far): (Vec<DVec3>, Vec<DVec3>) = target
        .stray()
        .iter()
        .map(|&k| points[k])
        .partition(|p| p.clamp(low, high).distance(*p) <= reach);
    let arm = STRAY_STAR * target.size();
    let stars = near
        .iter()
        .flat_map(|p| {
            [DVec3::X, DVec3::Y, DVec3::Z].map(|axis| Highlight {
                points: vec![*p - arm * axis, *p + arm * axis],
                color: STRAY_COLOR,
            })
        })
        .collect();
    let dots = near
        .into_iter()
        .map(|point| Dot {
            point,
            color: STRAY_COLOR,
        })
        .collect();
    (dots, stars, far.len())
}

/// Colour of the boundaries between patches on the result.
const PATCH_BOUNDARY_COLOR: Rgb = Rgb::new(0, 150, 80);

/// The lines where the patches of `mp` meet (§4.7), in the assembled grid: each
/// patch's first row and first column where another patch lies before it.
pub(super) fn patch_boundaries(mp: &MultiPatch) -> Vec<Highlight> {
    let g = &mp.grid;
    let line = |points: Vec<DVec3>| Highlight {
        points,
        color: PATCH_BOUNDARY_COLOR,
    };
    let mut lines = Vec::new();
    for p in &mp.patches {
        let ((i0, i1), (j0, j1)) = (p.rows, p.cols);
        if i0 > 0 {
            lines.push(line(
                (j0..=j1).map(|j| g.vertices[g.index(i0, j)]).collect(),
            ));
        }
        if j0 > 0 {
            lines.push(line(
                (i0..=i1).map(|i| g.vertices[g.index(i, j0)]).collect(),
            ));
        }
    }
    lines
}

/// The picture: the target's points coloured by their distance to the result, then the
/// initial guess and the result coloured by their distance to the target, all on one
/// scale (dark red from `tolerance` if given, in model units, else from the initial
/// guess's 95th percentile), its stray points in blue stars (`points` are those it
/// was given); the patch boundaries drawn on the result, and, where it is trimmed, the
/// edges of the `trimmed` mesh (the cut).
#[allow(clippy::too_many_arguments)] // the picture's parts, each its own
pub(super) fn picture_bytes(
    r: &Approximation,
    result: &QuadGrid,
    boundaries: Vec<Highlight>,
    points: &[DVec3],
    target: &TargetCloud,
    tolerance: Option<f64>,
    format: Picture,
    trimmed: Option<(&TrimmedMesh, Deviation)>,
) -> anyhow::Result<Vec<u8>> {
    let mesh = |design: &Design| -> anyhow::Result<QuadGrid> {
        let g = generate(design, &GenerateOptions::default())?;
        Ok(match design.mesh {
            MeshKind::Circular => g.grid,
            MeshKind::Conical => conical_dual(&g.grid).grid,
        })
    };
    let (before, scale, _) = distance_panel(
        Scene::new(mesh(&r.initial).context("the initial guess")?),
        target,
        "initial guess",
        tolerance,
    );
    let mut scene = Scene::new(result.clone());
    scene.highlights.extend(boundaries);
    // A trimmed result: the mesh before trimming, the cut drawn on it.
    scene
        .highlights
        .extend(trimmed.iter().flat_map(|t| cut_highlights(t.0)));
    let after = match trimmed {
        Some((_, d)) => trimmed_distance_panel(scene, target, "result", Some(scale), &d).0,
        None => distance_panel(scene, target, "result", Some(scale)).0,
    };
    let distances = target_distances(target, result, trimmed.map(|(mesh, _)| mesh));
    let largest = distances.iter().copied().fold(0.0, f64::max);
    let mut dots: Vec<Dot> = target
        .points()
        .iter()
        .zip(&distances)
        .map(|(p, d)| Dot {
            point: *p,
            color: heat(d / scale),
        })
        .collect();
    let (near, stars, far) = stray_marks(points, target);
    let points_aside = |n: usize| {
        let s = if n == 1 { "" } else { "s" };
        format!("\n{n} stray point{s} set aside")
    };
    let strays = match (near.len(), far) {
        (0, 0) => String::new(),
        (n, 0) => format!("{}, in blue", points_aside(n)),
        (0, f) => format!("{}, too far off to draw", points_aside(f)),
        (n, f) => format!(
            "{}: {n} in blue, {f} too far off to draw",
            points_aside(n + f)
        ),
    };
    dots.extend(near);
    let empty = QuadGrid::new(0, 0, Vec::new(), Vec::new());
    let target_panel = Panel {
        scene: Some(Scene {
            dots,
            highlights: stars,
            ..Scene::new(empty)
        }),
        caption: format!(
            "target, by its distance to the result\nwhite 0, dark red from {}{}\nlargest {}{strays}",
            num(scale),
            if tolerance.is_some() {
                " (the tolerance)"
            } else {
                ""
            },
            num(largest)
        ),
    };
    let options = RenderOptions {
        width: 2100,
        height: 700,
        ..RenderOptions::default()
    };
    sheet(&[target_panel, before, after], 3, &options, format)
}
