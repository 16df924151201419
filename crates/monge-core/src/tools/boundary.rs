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
use serde::{Deserialize, Serialize};

use crate::design::{Design, GuideSpec, Xyz};
use crate::gauss_map::pencil_axes;
use crate::generate::{generate, GenerateOptions, SINGULAR_WINDOW_DEG};
use crate::measure::measure;
use crate::projective::Line;
use crate::QuadGrid;

/// Largest angle (radians) by which the directions of P1 ∩ P2 and P3 ∩ P4 may miss
/// 90°, and by which façade planes may miss vertical / parallel / orthogonal.
pub const ANGLE_TOLERANCE: f64 = 1e-10;

/// Largest distance of a boundary line from its plane, relative to the mesh size,
/// that [`align`] accepts for a candidate.
pub const BOUNDARY_TOLERANCE: f64 = 1e-9;

/// Sine below which two planes count as parallel (their intersection line would
/// be determined by round-off).
const PARALLEL_SINE: f64 = 1e-6;

/// A plane as written in an alignment file: a point of it and a normal (need not be unit).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlaneSpec {
    /// A point of the plane.
    pub point: Xyz,
    /// A normal of the plane (non-zero; its sign does not matter).
    pub normal: Xyz,
}

/// How much each façade guide rises between its two horizontal ends (§4.5, Figure 16).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Rise {
    /// Height gained along guide_u (from the corner to P2); may be negative, not zero.
    pub guide_u: f64,
    /// Height gained along guide_v (from the corner to P4); may be negative, not zero.
    pub guide_v: f64,
}

/// The input of [`align`]: four boundary planes and optional choices (§4.5).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoundarySpec {
    /// P1: holds the first row (`i = 0`), i.e. guide_v.
    pub first_row: PlaneSpec,
    /// P2: holds the last row (`i = rows − 1`).
    pub last_row: PlaneSpec,
    /// P3: holds the first column (`j = 0`), i.e. guide_u.
    pub first_column: PlaneSpec,
    /// P4: holds the last column (`j = cols − 1`).
    pub last_column: PlaneSpec,
    /// θ of the design; without it, [`align`] chooses one (see the module docs).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub theta_deg: Option<f64>,
    /// The guides' common start point; projected onto the line P1 ∩ P3. Default:
    /// the point of that line nearest to the mean of the four planes' points.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub corner: Option<Xyz>,
    /// Samples per guide; [`AlignOptions::samples`] when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub samples: Option<usize>,
    /// Façade case only: the guides' rises. Default: a quarter of each guide's run.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rise: Option<Rise>,
    /// The façade case (four vertical planes, a rectangle in plan, Figure 16).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub facade: bool,
}

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

/// Why four planes cannot be aligned with (§4.5).
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum AlignError {
    /// A plane's point or normal is not finite, or its normal is zero.
    #[error("{plane}: the {what} is {value:?}; give finite numbers and a non-zero normal")]
    InvalidPlane {
        /// `first_row`, `last_row`, `first_column` or `last_column`.
        plane: &'static str,
        /// `point` or `normal`.
        what: &'static str,
        /// The value given.
        value: Xyz,
    },
    /// Two planes whose intersection line is needed are parallel.
    #[error(
        "{first} and {second} are parallel (their normals make {angle_deg:.3e}°): their intersection \
         line, the axis of the pencil of the {family}, does not exist. Tilt one of them{hint}"
    )]
    ParallelPlanes {
        /// The first plane.
        first: &'static str,
        /// The second plane.
        second: &'static str,
        /// Angle between the normals, in degrees (0 or near 180 folded to near 0).
        angle_deg: f64,
        /// `rows` or `columns`.
        family: &'static str,
        /// A hint (the façade option for vertical rectangles).
        hint: &'static str,
    },
    /// The directions of P1 ∩ P2 and P3 ∩ P4 are not orthogonal.
    #[error(
        "the intersection lines first_row ∩ last_row (direction {d12:?}) and first_column ∩ \
         last_column (direction {d34:?}) make {angle_deg:.9}°, off 90° by {off_deg:.3e}° (tolerance \
         {tolerance_deg:.1e}°): a mesh with planar curvature lines fits four planes only if these \
         directions are orthogonal (§4.5). Turn one plane about its line with the other pair's plane"
    )]
    NotOrthogonal {
        /// Unit direction of P1 ∩ P2.
        d12: Xyz,
        /// Unit direction of P3 ∩ P4.
        d34: Xyz,
        /// Angle between them, degrees.
        angle_deg: f64,
        /// `|angle − 90°|`.
        off_deg: f64,
        /// The tolerance, degrees.
        tolerance_deg: f64,
    },
    /// A corner of the mesh (a row plane meeting a column plane) does not exist.
    #[error(
        "the corner {row_plane} ∩ {column_plane} does not exist: the planes are parallel (normals \
         {angle_deg:.3e}° apart), so the {what} cannot end there. Make every row plane cross every \
         column plane"
    )]
    NoCorner {
        /// The row plane.
        row_plane: &'static str,
        /// The column plane.
        column_plane: &'static str,
        /// Angle between the normals, degrees.
        angle_deg: f64,
        /// Which boundary line needed it.
        what: &'static str,
    },
    /// No θ gives an aligned mesh (or the θ asked for does not).
    #[error("no admissible θ: {detail}")]
    NoAdmissibleTheta {
        /// θ asked for, if any.
        requested: Option<f64>,
        /// What was tried and why it failed.
        detail: String,
    },
    /// Façade: a plane is not vertical.
    #[error(
        "--facade needs vertical planes, but {plane} is tilted {tilt_deg:.3e}° from vertical \
         (normal {normal:?} has a z component). Give normals with z = 0, or leave out --facade"
    )]
    NotVertical {
        /// The plane.
        plane: &'static str,
        /// Tilt, degrees.
        tilt_deg: f64,
        /// Its normal as given.
        normal: Xyz,
    },
    /// Façade: the planes do not form a rectangle in plan.
    #[error(
        "--facade needs the planes to form a rectangle in plan (first_row ∥ last_row, first_column \
         ∥ last_column, first_row ⊥ first_column), but {what} is off by {off_deg:.3e}°. For planes \
         in general position leave out --facade"
    )]
    NotRectangle {
        /// Which condition fails.
        what: &'static str,
        /// By how much, degrees.
        off_deg: f64,
    },
    /// Façade: a guide has no run or no rise.
    #[error("--facade: {guide} {problem}")]
    Facade {
        /// The guide.
        guide: &'static str,
        /// What is wrong.
        problem: String,
    },
    /// Fewer than 3 samples per guide, or more than the vertex limit allows.
    #[error(
        "samples is {given}: give 3 to {max} samples per guide (the mesh has samples² vertices, \
         at most the {} a generated mesh may have)",
        max * max
    )]
    Samples {
        /// Samples given.
        given: usize,
        /// The most samples whose square is within the generator's vertex limit.
        max: usize,
    },
}

/// Names of P1 … P4 as in the file format.
pub const PLANE_NAMES: [&str; 4] = ["first_row", "last_row", "first_column", "last_column"];

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

/// The point of the line `{p_a · x = d_a} ∩ {p_b · x = d_b}` nearest to `near`.
fn line_point(pa: DVec3, da: f64, pb: DVec3, db: f64, near: DVec3) -> DVec3 {
    let (alpha, beta) = solve_gram(pa.dot(pb), da, db);
    let x0 = alpha * pa + beta * pb;
    let e = pa.cross(pb).normalize();
    x0 + e * e.dot(near - x0)
}

/// `(α, β)` with `α + g β = a`, `g α + β = b` (the Gram system of two unit vectors).
fn solve_gram(g: f64, a: f64, b: f64) -> (f64, f64) {
    let det = 1.0 - g * g;
    ((a - g * b) / det, (b - g * a) / det)
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

/// One candidate design with its quality (lower is better) and the c's.
struct Candidate {
    design: Design,
    c: [f64; 4],
    turning: f64,
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

/// The general case: four planes with orthogonal intersection-line directions.
struct General {
    p: [DVec3; 4],
    d: [f64; 4],
    /// `M = γ δᵀ`.
    gamma: [f64; 2],
    delta: [f64; 2],
    /// Distance of `{n·p1 = γ1} ∩ {n·p2 = γ2}` from the centre.
    d0: f64,
    corner: DVec3,
    samples: usize,
}

impl General {
    fn new(spec: &BoundarySpec, p: [DVec3; 4], d: [f64; 4], samples: usize) -> Self {
        let m = [
            [p[0].dot(p[2]), p[0].dot(p[3])],
            [p[1].dot(p[2]), p[1].dot(p[3])],
        ];
        let (mut a, mut b) = (0, 0);
        for i in 0..2 {
            for j in 0..2 {
                if m[i][j].abs() > m[a][b].abs() {
                    (a, b) = (i, j);
                }
            }
        }
        let gamma = [m[0][b], m[1][b]];
        let delta = [m[a][0] / m[a][b], m[a][1] / m[a][b]];
        let (al, be) = solve_gram(p[0].dot(p[1]), gamma[0], gamma[1]);
        let d0 = (al * p[0] + be * p[1]).length();
        let mean = [
            spec.first_row,
            spec.last_row,
            spec.first_column,
            spec.last_column,
        ]
        .iter()
        .map(|q| DVec3::from(q.point))
        .sum::<DVec3>()
            / 4.0;
        let near = spec.corner.map(DVec3::from).unwrap_or(mean);
        let corner = line_point(p[0], d[0], p[2], d[2], near);
        General {
            p,
            d,
            gamma,
            delta,
            d0,
            corner,
            samples,
        }
    }

    fn candidates(&self, theta: f64) -> Result<Vec<Candidate>, String> {
        let a = (theta.to_radians() / 2.0).tan().abs();
        if !a.is_finite() || a == 0.0 {
            return Err(
                "θ = 0° and ±180° put an axis at infinity or through the centre, where \
                        P1 ∩ P2 and P3 ∩ P4 (both finite) cannot be"
                    .into(),
            );
        }
        let tabs = a / self.d0;
        let mut out = Vec::new();
        let mut why = "the Gauss circles of the planes would not exist (|c| ≥ 1)".to_string();
        for t in [tabs, -tabs] {
            let c = [
                t * self.gamma[0],
                t * self.gamma[1],
                self.delta[0] / t,
                self.delta[1] / t,
            ];
            if c.iter().any(|x| x.abs() >= 1.0) {
                continue;
            }
            why = "the Gauss circles of first_row and first_column do not meet".into();
            let p = &self.p;
            // Corner normals: circle 1 ∩ circle 3.
            let (al, be) = solve_gram(p[0].dot(p[2]), c[0], c[2]);
            let base = al * p[0] + be * p[2];
            let h2 = 1.0 - base.length_squared();
            if h2 <= 0.0 {
                continue;
            }
            let e = p[0].cross(p[2]).normalize();
            why = "no arc from the corner reaches the far planes with the right end normal".into();
            for branch in [1.0, -1.0] {
                let n_p = base + branch * h2.sqrt() * e;
                for eps in [1.0, -1.0] {
                    let t_v = eps * p[0].cross(n_p).normalize();
                    let t_u = t_v.cross(n_p);
                    let arcs_v = arcs(self.corner, t_v, n_p, p[0], c[0], p[3], c[3], self.d[3]);
                    let arcs_u = arcs(self.corner, t_u, n_p, p[2], c[2], p[1], c[1], self.d[1]);
                    for av in &arcs_v {
                        for au in &arcs_u {
                            let mut design = Design {
                                theta_deg: theta.abs(),
                                guide_u: au.spec(self.samples),
                                guide_v: av.spec(self.samples),
                                mesh: Default::default(),
                                tolerance: None,
                            };
                            // L1 = {n·p1 = c1} ∩ {n·p2 = c2}; which sign of θ makes it?
                            let (x, y) = solve_gram(p[0].dot(p[1]), c[0], c[1]);
                            let x0 = x * p[0] + y * p[1];
                            let dir = p[0].cross(p[1]);
                            let l1 = Line {
                                dir,
                                moment: x0.cross(dir),
                            };
                            let Some(sign) = theta_sign(&design, &l1, theta.abs()) else {
                                continue;
                            };
                            if theta != 0.0 && sign != theta.signum() {
                                continue;
                            }
                            design.theta_deg = sign * theta.abs();
                            out.push(Candidate {
                                design,
                                c,
                                turning: av.turning.abs() + au.turning.abs(),
                            });
                        }
                    }
                }
            }
        }
        if out.is_empty() {
            Err(why)
        } else {
            Ok(out)
        }
    }
}

/// The sign of θ (±1) for which the design's pencil axis L1 is `l1`, if either.
fn theta_sign(design: &Design, l1: &Line, theta_abs: f64) -> Option<f64> {
    let info = crate::generate::inspect(design, &GenerateOptions::default()).ok()?;
    let norm = |l: &Line| {
        let s = (l.dir.length_squared() + l.moment.length_squared()).sqrt();
        (l.dir / s, l.moment / s)
    };
    let (d, m) = norm(l1);
    [1.0, -1.0].into_iter().find(|&sign| {
        pencil_axes(&info.frame, sign * theta_abs).is_ok_and(|axes| {
            let (d2, m2) = norm(&axes.l1);
            let same = (d - d2).length() + (m - m2).length();
            let opposite = (d + d2).length() + (m + m2).length();
            same.min(opposite) < 1e-7
        })
    })
}

/// A circular arc guide: start, unit start tangent, signed turning angle about `axis`.
struct ArcGuide {
    start: DVec3,
    tangent: DVec3,
    axis: DVec3,
    turning: f64,
    chord: f64,
}

impl ArcGuide {
    fn spec(&self, samples: usize) -> GuideSpec {
        let half = self.turning.abs() / 2.0;
        let r = self.chord / (2.0 * half.sin());
        let w = self.axis.cross(self.tangent) * self.turning.signum();
        let center = self.start + r * w;
        let normal = self.axis * self.turning.signum();
        GuideSpec::arc(
            center.to_array(),
            self.start.to_array(),
            normal.to_array(),
            self.turning.abs().to_degrees(),
            samples,
        )
    }
}

/// The arcs in plane `(p, on circle c)` from `start` with tangent `t0` and normal
/// `n0`, whose end normal lies on `{n · q = cq}` and whose end point lies in
/// `{q · x = dq}` (zero, one or two).
#[allow(clippy::too_many_arguments)]
fn arcs(
    start: DVec3,
    t0: DVec3,
    n0: DVec3,
    p: DVec3,
    c: f64,
    q: DVec3,
    cq: f64,
    dq: f64,
) -> Vec<ArcGuide> {
    // N(φ) = c p + cos φ m0 + sin φ (p × m0) as the tangent turns by φ about p.
    let m0 = n0 - c * p;
    let (a, b) = (m0.dot(q), p.cross(m0).dot(q));
    let rhs = cq - c * p.dot(q);
    let r = a.hypot(b);
    if r == 0.0 || rhs.abs() > r {
        return Vec::new();
    }
    let base = b.atan2(a);
    let spread = (rhs / r).clamp(-1.0, 1.0).acos();
    let mut out = Vec::new();
    for phi in [base + spread, base - spread] {
        // Principal value in (−π, π].
        let phi = (phi + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI)
            - std::f64::consts::PI;
        if phi.abs() < 1e-6 {
            continue;
        }
        let (s, co) = (phi / 2.0).sin_cos();
        let mid = co * t0 + s * p.cross(t0);
        let denom = q.dot(mid);
        if denom.abs() < 1e-12 {
            continue;
        }
        let lambda = (dq - q.dot(start)) / denom;
        if lambda == 0.0 || !lambda.is_finite() {
            continue;
        }
        let turning = if lambda > 0.0 {
            phi
        } else {
            phi - 2.0 * std::f64::consts::PI * phi.signum()
        };
        out.push(ArcGuide {
            start,
            tangent: t0,
            axis: p,
            turning,
            chord: lambda.abs(),
        });
    }
    out
}

/// The façade case: four vertical planes, a rectangle in plan (Figure 16).
struct Facade {
    guide_u: Vec<DVec3>,
    guide_v: Vec<DVec3>,
    t_u: DVec3,
    t_v: DVec3,
    turning: f64,
}

impl Facade {
    fn new(
        spec: &BoundarySpec,
        p: [DVec3; 4],
        d: [f64; 4],
        samples: usize,
    ) -> Result<Self, AlignError> {
        let given = [
            spec.first_row,
            spec.last_row,
            spec.first_column,
            spec.last_column,
        ];
        for k in 0..4 {
            let tilt = p[k].z.abs().min(1.0).asin();
            if tilt > ANGLE_TOLERANCE {
                return Err(AlignError::NotVertical {
                    plane: PLANE_NAMES[k],
                    tilt_deg: tilt.to_degrees(),
                    normal: given[k].normal,
                });
            }
        }
        for (a, b, what) in [
            (0, 1, "first_row ∥ last_row"),
            (2, 3, "first_column ∥ last_column"),
        ] {
            let off = p[a].cross(p[b]).length().min(1.0).asin();
            if off > ANGLE_TOLERANCE {
                return Err(AlignError::NotRectangle {
                    what,
                    off_deg: off.to_degrees(),
                });
            }
        }
        let off = p[0].dot(p[2]).abs().min(1.0).asin();
        if off > ANGLE_TOLERANCE {
            return Err(AlignError::NotRectangle {
                what: "first_row ⊥ first_column",
                off_deg: off.to_degrees(),
            });
        }
        let mean = given.iter().map(|q| DVec3::from(q.point)).sum::<DVec3>() / 4.0;
        let near = spec.corner.map(DVec3::from).unwrap_or(mean);
        let corner = line_point(p[0], d[0], p[2], d[2], near);
        // Horizontal start tangents, towards the far planes.
        let toward = |plane: DVec3, far: usize| {
            let t = plane.cross(DVec3::Z).normalize();
            let run = (d[far] - p[far].dot(corner)) / p[far].dot(t);
            if run < 0.0 {
                (-t, -run)
            } else {
                (t, run)
            }
        };
        let (t_v, run_v) = toward(p[0], 3);
        let (t_u, run_u) = toward(p[2], 1);
        let size = run_u.max(run_v);
        for (guide, run, far) in [
            ("guide_u", run_u, "last_row"),
            ("guide_v", run_v, "last_column"),
        ] {
            if run.is_nan() || run <= 1e-9 * size || !run.is_finite() {
                return Err(AlignError::Facade {
                    guide,
                    problem: format!(
                        "would have length {run:e}: the corner lies in {far}. Move {far} away"
                    ),
                });
            }
        }
        let rise = spec.rise.unwrap_or(Rise {
            guide_u: 0.25 * run_u,
            guide_v: 0.25 * run_v,
        });
        for (guide, h) in [("guide_u", rise.guide_u), ("guide_v", rise.guide_v)] {
            if !h.is_finite() || h == 0.0 {
                return Err(AlignError::Facade {
                    guide,
                    problem: format!(
                        "has rise {h}: a guide with horizontal ends that does not rise is straight, \
                         and the normal would not turn along it. Give a non-zero `rise`"
                    ),
                });
            }
        }
        let (guide_u, phi_u) = s_curve(corner, t_u, run_u, rise.guide_u, samples);
        let (guide_v, phi_v) = s_curve(corner, t_v, run_v, rise.guide_v, samples);
        Ok(Facade {
            guide_u,
            guide_v,
            t_u,
            t_v,
            turning: phi_u + phi_v,
        })
    }

    fn candidates(&self, theta: f64) -> Result<Vec<Candidate>, String> {
        let pts = |v: &[DVec3]| v.iter().map(|x| x.to_array()).collect::<Vec<_>>();
        Ok(vec![Candidate {
            design: Design {
                theta_deg: theta,
                guide_u: GuideSpec {
                    tangent: Some(self.t_u.to_array()),
                    ..GuideSpec::points(pts(&self.guide_u))
                },
                guide_v: GuideSpec {
                    tangent: Some(self.t_v.to_array()),
                    ..GuideSpec::points(pts(&self.guide_v))
                },
                mesh: Default::default(),
                tolerance: None,
            },
            c: [0.0; 4],
            turning: self.turning,
        }])
    }
}

/// An S-shaped bi-arc from `start` along horizontal `t`, covering `run`
/// horizontally and `rise` vertically, horizontal at both ends, sampled at
/// `samples` points (the junction is a sample, so the torsion-free normals are
/// exact at every sample). Returns the points and the turning angle of each arc.
fn s_curve(start: DVec3, t: DVec3, run: f64, rise: f64, samples: usize) -> (Vec<DVec3>, f64) {
    let phi = 2.0 * (rise.abs() / run).atan();
    let r = run / (2.0 * phi.sin());
    let w = DVec3::Z * rise.signum();
    let first = (samples - 1) / 2;
    let second = samples - 1 - first;
    let on_first = |psi: f64| {
        let half = (psi / 2.0).sin();
        start + r * (psi.sin() * t + 2.0 * half * half * w)
    };
    let junction = on_first(phi);
    let end = start + run * t + rise * DVec3::Z;
    let mut points: Vec<DVec3> = (0..=first)
        .map(|k| on_first(phi * k as f64 / first as f64))
        .collect();
    // The second arc is the first one turned by 180° about the junction.
    for k in 1..=second {
        let psi = phi * (1.0 - k as f64 / second as f64);
        points.push(if k == second {
            end
        } else {
            2.0 * junction - on_first(psi)
        });
    }
    (points, phi)
}
