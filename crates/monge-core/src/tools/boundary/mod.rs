//! Aligning a mesh with four boundary planes (§4.5, Figures 16–18).
//!
//! The first row of the mesh (`i = 0`, i.e. guide_v) lies in plane P1
//! ([`BoundarySpec::first_row`]), the last row in P2 ([`BoundarySpec::last_row`]), the
//! first column (`j = 0`, guide_u) in P3 ([`BoundarySpec::first_column`]) and the last
//! column in P4 ([`BoundarySpec::last_column`]). [`align`] returns a [`Design`] whose
//! generated mesh has its four boundary lines in those planes, to round-off.
//!
//! **Why it works** (verified by the tests, not only argued). A planar curvature
//! line keeps a constant angle with its plane (Joachimsthal), so the normals along a
//! line in plane P_k (unit normal `p_k`) lie on the Gauss circle `{n · p_k = c_k}`.
//! The circles of the rows belong to the pencil of planes through the axis L1, those
//! of the columns to the pencil through L2, and L2 is the polar of L1 (§2.1.2). The
//! pole `(p_i : c_i)` of a row circle's plane lies on L2, which lies in every column
//! circle's plane: `c_i c_j = p_i · p_j` for `i ∈ {1, 2}`, `j ∈ {3, 4}`. The 2 × 2 matrix
//! `M_ij = p_i · p_j` must then have rank 1: `(p1·p3)(p2·p4) = (p1·p4)(p2·p3)`, which
//! is `(p1 × p2) · (p3 × p4) = 0` (Binet–Cauchy): the lines P1 ∩ P2 and P3 ∩ P4 have
//! orthogonal directions. Writing `M = γ δᵀ`, the solutions are `c_{1,2} = t γ`,
//! `c_{3,4} = δ / t`; L1 = `{n·p1 = c1} ∩ {n·p2 = c2}` is `t` times a fixed line, at
//! distance `|t|·d0` from the centre, so `|tan(θ/2)| = |t|·d0`: the free scale is θ.
//!
//! Guides: the corner normal `N_p` is a point of circle 1 ∩ circle 3 (two branches),
//! the corner a point of the line P1 ∩ P3. guide_v is a circular arc in P1 from the
//! corner whose end normal lies on circle 4 and whose end point lies in P4 (the
//! turning angle is fixed by the end normal, the radius by where the chord meets P4);
//! guide_u likewise in P3, ending in P2. Along a sampled arc the torsion-free normals
//! of the generator are the arc's exact normals, so the end normals are exact. Then
//! the pencil plane through L1 and the end normal of guide_u *is* circle 2's plane,
//! so the last row (which lies in the plane through its first vertex orthogonal to
//! its Gauss circle's plane) lies in P2; likewise the last column in P4.
//!
//! Of the candidates (sign of `t`, corner branch, direction of the guides, the two
//! end normals of each arc) [`align`] keeps those whose design reproduces the axes
//! (θ derived from L1 and checked against [`crate::gauss_map::pencil_axes`]), whose
//! mesh generates without folds and whose boundaries measure in the planes, and
//! picks the one whose arcs turn least. Without a θ, it scans θ in 1° steps and takes
//! the middle of the longest run of θ that work.
//!
//! **Façade** ([`AlignOptions::facade`], Figure 16): four vertical planes forming a
//! rectangle in plan (P1 ∥ P2 ⊥ P3 ∥ P4). Then P1 ∩ P2 does not exist; the boundary
//! circles are the great circles `{n · p_k = 0}` (characteristic design, §3.1, every
//! θ works) and "the only requirement is that the tangent vectors at the ends of the
//! guiding curves are horizontal" (§4.5). Each guide is an S-shaped bi-arc in its
//! plane, horizontal at both ends, rising by [`BoundarySpec::rise`].

use glam::DVec3;

use crate::design::Design;
use crate::generate::{generate, GenerateOptions, SINGULAR_WINDOW_DEG};
use crate::measure::measure;
use crate::QuadGrid;

mod candidate;
mod facade;
mod general;
mod spec;

use facade::Facade;
use general::General;

use candidate::Candidate;
pub use spec::{
    AlignError, BoundarySpec, PlaneSpec, Rise, ANGLE_TOLERANCE, BOUNDARY_TOLERANCE, PLANE_NAMES,
};

/// Sine below which two planes count as parallel (their intersection line would
/// be determined by round-off).
const PARALLEL_SINE: f64 = 1e-6;

/// Options of [`align`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AlignOptions {
    /// Samples per guide when the spec gives none (≥ 3). Default 21.
    pub samples: usize,
    /// Use the façade construction even if the spec does not say so.
    pub facade: bool,
}

impl Default for AlignOptions {
    fn default() -> Self {
        AlignOptions {
            samples: 21,
            facade: false,
        }
    }
}

/// What [`align`] returns.
#[derive(Clone, Debug)]
pub struct Aligned {
    /// The design: generate it to get the aligned mesh.
    pub design: Design,
    /// The Gauss-circle constants `c_k` of P1 … P4 (`n · p_k = c_k` along the line in
    /// P_k, `p_k` the unit normal as given).
    pub c: [f64; 4],
    /// Largest distance of a boundary line's vertex from its plane, relative to the
    /// mesh's bounding-box diagonal, for P1 … P4.
    pub boundary_distance: [f64; 4],
    /// `measure(...).max_error()` of the generated mesh.
    pub max_error: f64,
    /// The θ values (degrees) that worked, when θ was chosen by a scan: `(first, last)`
    /// of the run the chosen θ is the middle of.
    pub theta_run: Option<(f64, f64)>,
}

/// Largest distance of each boundary line's vertices from its plane (absolute):
/// row 0 from `planes[0]`, the last row from `planes[1]`, column 0 from `planes[2]`,
/// the last column from `planes[3]`.
pub fn boundary_distances(grid: &QuadGrid, planes: &[PlaneSpec; 4]) -> [f64; 4] {
    let lines: [Vec<DVec3>; 4] = [
        grid.row(0).collect(),
        grid.row(grid.rows - 1).collect(),
        grid.column(0).collect(),
        grid.column(grid.cols - 1).collect(),
    ];
    let mut out = [0.0; 4];
    for k in 0..4 {
        let n = DVec3::from(planes[k].normal).normalize();
        let q = DVec3::from(planes[k].point);
        out[k] = lines[k]
            .iter()
            .map(|x| (*x - q).dot(n).abs())
            .fold(0.0, f64::max);
    }
    out
}

/// Unit normals, offsets (`p · x = d`) of the four planes, validated.
fn unit_planes(spec: &BoundarySpec) -> Result<([DVec3; 4], [f64; 4]), AlignError> {
    let planes = [
        spec.first_row,
        spec.last_row,
        spec.first_column,
        spec.last_column,
    ];
    let mut p = [DVec3::ZERO; 4];
    let mut d = [0.0; 4];
    for k in 0..4 {
        let (q, n) = (DVec3::from(planes[k].point), DVec3::from(planes[k].normal));
        if !q.is_finite() {
            return Err(AlignError::InvalidPlane {
                plane: PLANE_NAMES[k],
                what: "point",
                value: planes[k].point,
            });
        }
        let len = n.length();
        if !len.is_finite() || len == 0.0 || !(n / len).is_finite() {
            return Err(AlignError::InvalidPlane {
                plane: PLANE_NAMES[k],
                what: "normal",
                value: planes[k].normal,
            });
        }
        p[k] = n / len;
        d[k] = p[k].dot(q);
    }
    Ok((p, d))
}

/// Angle between the normals of two planes folded to [0°, 90°] (0: parallel).
fn plane_angle_deg(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().min(1.0).asin().to_degrees()
}

/// Samples requested, validated.
fn sample_count(spec: &BoundarySpec, options: &AlignOptions) -> Result<usize, AlignError> {
    let n = spec.samples.unwrap_or(options.samples);
    let max = GenerateOptions::default().max_vertices.isqrt();
    if !(3..=max).contains(&n) {
        return Err(AlignError::Samples { given: n, max });
    }
    Ok(n)
}

/// A design that aligns with the four planes of `spec` (§4.5, Figures 16–18).
///
/// ```
/// use monge_core::boundary::{align, AlignOptions, BoundarySpec, PlaneSpec};
/// let plane = |point, normal| PlaneSpec { point, normal };
/// // Four vertical walls around a 4 × 3 rectangle: the façade case (Figure 16).
/// let spec = BoundarySpec {
///     first_row: plane([0.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
///     last_row: plane([0.0, 3.0, 0.0], [0.0, 1.0, 0.0]),
///     first_column: plane([0.0, 0.0, 0.0], [1.0, 0.0, 0.0]),
///     last_column: plane([4.0, 0.0, 0.0], [1.0, 0.0, 0.0]),
///     theta_deg: Some(-60.0),
///     corner: None,
///     samples: Some(9),
///     rise: None,
///     facade: true,
/// };
/// let aligned = align(&spec, &AlignOptions::default()).unwrap();
/// assert!(aligned.boundary_distance.iter().all(|&d| d <= 1e-12));
/// ```
pub fn align(spec: &BoundarySpec, options: &AlignOptions) -> Result<Aligned, AlignError> {
    let (p, d) = unit_planes(spec)?;
    let samples = sample_count(spec, options)?;
    if spec.facade || options.facade {
        let facade = Facade::new(spec, p, d, samples)?;
        return choose_theta(spec, |theta| facade.candidates(theta));
    }
    // Every intersection line that is needed must exist.
    for (a, b, family) in [(0, 1, "rows"), (2, 3, "columns")] {
        if p[a].cross(p[b]).length() < PARALLEL_SINE {
            let vertical = p.iter().all(|n| n.z.abs() < PARALLEL_SINE);
            return Err(AlignError::ParallelPlanes {
                first: PLANE_NAMES[a],
                second: PLANE_NAMES[b],
                angle_deg: plane_angle_deg(p[a], p[b]),
                family,
                hint: if vertical {
                    " (four vertical planes forming a rectangle in plan are the façade case: use --facade)"
                } else {
                    ""
                },
            });
        }
    }
    for (r, c, what) in [
        (0, 2, "guides' common start point"),
        (0, 3, "guide_v"),
        (1, 2, "guide_u"),
        (1, 3, "last row and last column"),
    ] {
        if p[r].cross(p[c]).length() < PARALLEL_SINE {
            return Err(AlignError::NoCorner {
                row_plane: PLANE_NAMES[r],
                column_plane: PLANE_NAMES[c],
                angle_deg: plane_angle_deg(p[r], p[c]),
                what,
            });
        }
    }
    let d12 = p[0].cross(p[1]).normalize();
    let d34 = p[2].cross(p[3]).normalize();
    let cos = d12.dot(d34).clamp(-1.0, 1.0);
    if cos.abs().asin() > ANGLE_TOLERANCE {
        let angle_deg = cos.acos().to_degrees();
        return Err(AlignError::NotOrthogonal {
            d12: d12.to_array(),
            d34: d34.to_array(),
            angle_deg,
            off_deg: (angle_deg - 90.0).abs(),
            tolerance_deg: ANGLE_TOLERANCE.to_degrees(),
        });
    }
    let general = General::new(spec, p, d, samples);
    choose_theta(spec, |theta| general.candidates(theta))
}

/// Validate a candidate: generate it and measure; `None` if it does not work.
fn accept(candidate: &Candidate, planes: &[PlaneSpec; 4]) -> Option<([f64; 4], f64)> {
    let generated = generate(&candidate.design, &GenerateOptions::default()).ok()?;
    if generated.report.folded_faces > 0 {
        return None;
    }
    let grid = &generated.grid;
    let size = grid.bbox_diagonal();
    let dist = boundary_distances(grid, planes).map(|x| x / size);
    if !dist.iter().all(|x| *x <= BOUNDARY_TOLERANCE) {
        return None;
    }
    let max_error = measure(grid).max_error();
    (max_error <= BOUNDARY_TOLERANCE).then_some((dist, max_error))
}

/// The best candidate for θ, validated.
fn best_for(
    planes: &[PlaneSpec; 4],
    candidates: Vec<Candidate>,
) -> Option<(Candidate, [f64; 4], f64)> {
    let mut cands = candidates;
    cands.sort_by(|a, b| a.turning.total_cmp(&b.turning));
    cands
        .into_iter()
        .find_map(|c| accept(&c, planes).map(|(dist, err)| (c, dist, err)))
}

/// θ as asked for, or the middle of the longest run of working θ in 1° steps.
fn choose_theta(
    spec: &BoundarySpec,
    candidates: impl Fn(f64) -> Result<Vec<Candidate>, String>,
) -> Result<Aligned, AlignError> {
    let planes = [
        spec.first_row,
        spec.last_row,
        spec.first_column,
        spec.last_column,
    ];
    let finish = |(c, dist, err): (Candidate, [f64; 4], f64), run| Aligned {
        design: c.design,
        c: c.c,
        boundary_distance: dist,
        max_error: err,
        theta_run: run,
    };
    if let Some(theta) = spec.theta_deg {
        if !theta.is_finite() || theta.abs() > 180.0 {
            return Err(AlignError::NoAdmissibleTheta {
                requested: Some(theta),
                detail: format!("theta_deg is {theta}; give a finite angle in [−180, 180]"),
            });
        }
        if (theta - 90.0).abs() < SINGULAR_WINDOW_DEG {
            return Err(AlignError::NoAdmissibleTheta {
                requested: Some(theta),
                detail:
                    "θ = +90° is singular (every Gauss circle passes through the corner normal)"
                        .into(),
            });
        }
        let cands = candidates(theta).map_err(|detail| AlignError::NoAdmissibleTheta {
            requested: Some(theta),
            detail: format!("θ = {theta}°: {detail}. Leave theta_deg out to let monge choose one"),
        })?;
        let n = cands.len();
        return best_for(&planes, cands)
            .map(|b| finish(b, None))
            .ok_or_else(|| AlignError::NoAdmissibleTheta {
                requested: Some(theta),
                detail: format!(
                    "θ = {theta}°: none of the {n} candidate designs (corner branch, guide \
                     directions, end normals) generates an unfolded mesh in the planes. Try \
                     another θ, or leave theta_deg out to let monge choose one"
                ),
            });
    }
    // Scan θ = −179° … 180° in 1° steps.
    let thetas: Vec<f64> = (-179..=180).map(f64::from).collect();
    let ok: Vec<bool> = thetas
        .iter()
        .map(|&t| {
            (t - 90.0).abs() >= 1.0
                && candidates(t)
                    .ok()
                    .and_then(|c| best_for(&planes, c))
                    .is_some()
        })
        .collect();
    // Longest run of `true`, cyclically (−179 follows 180).
    let n = ok.len();
    let mut best: Option<(usize, usize)> = None; // (start, length)
    if ok.iter().all(|&x| x) {
        best = Some((0, n));
    } else {
        for start in 0..n {
            if ok[start] && !ok[(start + n - 1) % n] {
                let len = (0..n).take_while(|&k| ok[(start + k) % n]).count();
                if best.is_none_or(|(_, l)| len > l) {
                    best = Some((start, len));
                }
            }
        }
    }
    let Some((start, len)) = best else {
        return Err(AlignError::NoAdmissibleTheta {
            requested: None,
            detail: "no θ in −179° … 180° (1° steps) gives an unfolded mesh with its boundaries \
                     in the planes: the Gauss circles of the planes never meet as the corners \
                     need, or every such mesh folds (§5.2). Move the planes closer to a box"
                .into(),
        });
    };
    let theta = thetas[(start + len / 2) % n];
    let run = (thetas[start], thetas[(start + len - 1) % n]);
    let cands = candidates(theta).map_err(|detail| AlignError::NoAdmissibleTheta {
        requested: None,
        detail,
    })?;
    let b = best_for(&planes, cands).expect("θ was found to work");
    Ok(finish(b, Some(run)))
}
