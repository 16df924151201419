//! The whole generation method of §3: guides → Gauss map → Combescure transform.

use std::fmt;

use glam::DVec3;

use crate::combescure::{
    combescure, CombescureReport, ParallelLines, MIN_CROSSING_SINE, ZERO_GAUSS_EDGE,
};
use crate::design::Design;
use crate::gauss_map::{
    guide_normals, normalize_theta_deg, pencil_axes, GaussRows, PencilAxes, StartFrame, ThetaRange,
};
use crate::grid::QuadGrid;
use crate::guide::{Guide, GuideError, GuideName};

/// The accepted design sizes (the larger guide's bounding-box diagonal) are those of
/// every model, defined with the grid.
pub use crate::grid::{MAX_SIZE, MIN_SIZE};

/// Options of [`generate`] and [`inspect`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GenerateOptions {
    /// Largest number of grid vertices (`rows · cols`) accepted; larger grids are
    /// refused before anything is allocated. Default `25_000_000` (about 1.2 GB
    /// of vertices and normals).
    pub max_vertices: usize,
}

impl Default for GenerateOptions {
    fn default() -> Self {
        GenerateOptions {
            max_vertices: 25_000_000,
        }
    }
}

/// Which generation mode of the paper a design uses (§3.1, §3.2).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// §3.1: the guide planes are orthogonal and each start tangent is orthogonal
    /// to the other guide's plane; both Gauss circles are great circles and every θ
    /// is admissible.
    Characteristic,
    /// §3.2: any two planar guides meeting at 90°; θ has an admissible range.
    Arbitrary,
}

impl fmt::Display for Mode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Mode::Characteristic => "characteristic (§3.1)",
            Mode::Arbitrary => "arbitrary (§3.2)",
        })
    }
}

/// Everything wrong with a design that stops generation (§3, §5.2).
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum GenerateError {
    /// A guide curve is invalid.
    #[error(transparent)]
    Guide(#[from] GuideError),
    /// The grid would exceed [`GenerateOptions::max_vertices`].
    #[error(
        "the grid would have {rows} × {cols} = {vertices} vertices, more than the limit of {limit}: \
         lower the `samples` of the guides (of a developable design: its helix points or \
         `heights`), or raise the limit (`--max-vertices` on the command line, \
         `GenerateOptions::max_vertices` in the library) if the machine has the memory (48 bytes a vertex)"
    )]
    GridTooLarge {
        /// Samples of guide_u (of a developable mesh: its rulings).
        rows: usize,
        /// Samples of guide_v (of a developable mesh: its cutting planes).
        cols: usize,
        /// `rows · cols` (saturating).
        vertices: usize,
        /// The limit.
        limit: usize,
    },
    /// θ is NaN or infinite.
    #[error("theta_deg is {0}: give a finite angle in degrees, in (−180, 180]")]
    ThetaNotFinite(f64),
    /// A tolerance of the design is negative, NaN or beyond its meaningful range.
    #[error(
        "`tolerance.{name}` is {value}: give a number from 0 to {max} ({unit}; the default, \
         1e-9, suits exact input)"
    )]
    BadTolerance {
        /// `planarity`, `angle` or `start`.
        name: &'static str,
        /// The value given.
        value: f64,
        /// The largest meaningful value: 1 for the relative distances, π/2 for the angle.
        max: f64,
        /// `relative to the guide's size` or `radians`.
        unit: &'static str,
    },
    /// The design is too small or too large for double precision to keep every
    /// property exact (squared lengths would underflow or overflow).
    #[error(
        "the guides' size is {size:e}, outside [{min:e}, {max:e}]: at such scales squared lengths \
         underflow or overflow in double precision and the mesh could not be exact. Rescale the \
         design (e.g. use other units)"
    )]
    ScaleOutOfRange {
        /// The larger guide's bounding-box diagonal.
        size: f64,
        /// Smallest accepted size, [`MIN_SIZE`].
        min: f64,
        /// Largest accepted size, [`MAX_SIZE`].
        max: f64,
    },
    /// The guides do not start at the same point.
    #[error(
        "the guides do not start at the same point: guide_u starts at {u:?}, guide_v at {v:?}, \
         {distance:.3e} apart ({relative:.1e} of the guides' size; tolerance {tolerance:.0e}). {}",
        crate::grid::tolerance_fix(*origin_ratio, *relative, "start", "Make their first points equal")
    )]
    StartPointsDiffer {
        /// First point of guide_u.
        u: [f64; 3],
        /// First point of guide_v.
        v: [f64; 3],
        /// Distance between them.
        distance: f64,
        /// Distance relative to the larger guide's size.
        relative: f64,
        /// The tolerance ([`crate::Tolerances::start`]).
        tolerance: f64,
        /// How far the guides lie from the origin compared with their size
        /// ([`crate::grid::origin_ratio`] of their samples).
        origin_ratio: f64,
    },
    /// The start tangents are not orthogonal.
    #[error(
        "the guides must meet at 90°, but their start tangents make {angle_deg:.9}° \
         (off by {off_deg:.3e}°; tolerance {tolerance_deg:.1e}°). Curvature lines cross at right \
         angles. {}",
        crate::grid::tolerance_fix(
            *origin_ratio,
            off_deg.to_radians(),
            "angle",
            "Turn one guide's start tangent (for a B-spline, P1 − P0) to be orthogonal to the other's"
        )
    )]
    NotOrthogonal {
        /// Angle between the start tangents, in degrees.
        angle_deg: f64,
        /// `|angle − 90°|`.
        off_deg: f64,
        /// The tolerance, in degrees.
        tolerance_deg: f64,
        /// How far the guides lie from the origin compared with their size
        /// ([`crate::grid::origin_ratio`] of their samples).
        origin_ratio: f64,
    },
    /// θ is outside the admissible range of this design (§3.2).
    #[error(
        "theta_deg = {theta_deg}° is not admissible for these guides: |θ| must lie in \
         [{min_deg:.6}°, {max_deg:.6}°] (§3.2: a² = tan²(θ/2) between |OQ2|² and |OA1|²). \
         Pick θ in that range, or change the angle between the guide planes"
    )]
    ThetaInadmissible {
        /// θ, reduced to (−180, 180].
        theta_deg: f64,
        /// Smallest admissible |θ|.
        min_deg: f64,
        /// Largest admissible |θ|.
        max_deg: f64,
    },
    /// θ is at (or within [`SINGULAR_WINDOW_DEG`] of) the singular θ = +90° (§2.2.1).
    #[error(
        "theta_deg = {theta_deg}° is singular: at θ = +90° both pencil axes touch the sphere at the \
         corner normal N_p, every Gauss circle passes through it and the mesh collapses (within \
         {window}° of it the mesh cannot be built to 1e-9). Move θ away from 90°"
    )]
    ThetaSingular {
        /// θ, reduced to (−180, 180].
        theta_deg: f64,
        /// The refused window around +90°, in degrees.
        window: f64,
    },
    /// The surface normal barely turns along a guide: its plane is (nearly) the
    /// tangent plane at the start point, or the guide is (nearly) straight (§2.2, §3.2).
    #[error(
        "the surface normal turns by only {turn:.1e} rad along {guide} (its Gauss image, §2.2; \
         the guide's plane is {plane_deg:.2e}° from the tangent plane at the start point): below \
         {min:.0e} rad the planes of the mesh lines are fixed by normals that rounding cannot \
         tell apart, and the mesh could not be exact to 1e-9 (its error grows as about \
         2e-16 / turn). Tilt {guide}'s plane away from the tangent plane (turn the other \
         guide's start tangent out of it), or curve {guide} more"
    )]
    NormalStill {
        /// The guide.
        guide: GuideName,
        /// The largest distance between two normals along the guide (on the unit sphere).
        turn: f64,
        /// The angle between the guide's plane and the tangent plane at the start point, in degrees.
        plane_deg: f64,
        /// The smallest accepted turn, [`MIN_NORMAL_TURN`].
        min: f64,
    },
    /// The Gauss map degenerates at a face, so the mesh cannot be continued (§5.2).
    #[error(
        "the mesh cannot be built past face ({i}, {j}): its Gauss quad is degenerate ({why}). {hint}",
        i = face.0, j = face.1,
        why = degenerate_cause(*face, *sine, *zero_edge)
    )]
    Degenerate {
        /// The face.
        face: (usize, usize),
        /// Sine of the angle between the two Gauss edges that fix vertex
        /// `(i+1, j+1)` or, where smaller, between the second and the plane of
        /// its row ([`ParallelLines::sine`]); NaN if either is NaN.
        sine: f64,
        /// One of the two Gauss edges has (nearly) zero length
        /// ([`ParallelLines::zero_edge`]): then the sine means nothing.
        zero_edge: bool,
        /// What usually causes it.
        hint: &'static str,
    },
}

/// What [`GenerateError::Degenerate`] says of the Gauss quad of `face`: an
/// edge of (nearly) zero length, or two lines (nearly) parallel and the sine
/// of their angle.
fn degenerate_cause(face: (usize, usize), sine: f64, zero_edge: bool) -> String {
    let vertex = (face.0 + 1, face.1 + 1);
    if zero_edge {
        format!(
            "one of the two Gauss edges that fix vertex {vertex:?} has (nearly) zero length, below \
             {ZERO_GAUSS_EDGE:.0e} on the unit sphere"
        )
    } else {
        format!(
            "the two lines that fix vertex {vertex:?} are (nearly) parallel: the sine of the angle \
             between its two Gauss edges, or between the second and the plane of its row, is \
             {sine:.1e}, below {MIN_CROSSING_SINE:.0e}"
        )
    }
}

/// Smallest accepted turn of the surface normal along a guide (the largest
/// distance between two of its normals on the unit sphere). The mesh's error
/// grows as about 2e-16 divided by the turn (measured: turns of 5e-6, 5e-7
/// and 5e-8 rad give circularity 3e-11, 4e-10 and 4e-9 of the mesh size), so
/// that this bound keeps it 40 times below 1e-9.
pub const MIN_NORMAL_TURN: f64 = 1e-5;

/// Half-width, in degrees, of the window around the singular θ = +90° that
/// [`generate`] refuses: closer to it, the Gauss map contracts onto `N_p` so much
/// that round-off exceeds 1e-9 of the model size (measured: 6e-9 at 1e-5° away).
pub const SINGULAR_WINDOW_DEG: f64 = 1e-3;

/// A validated design, before any mesh is built: what `monge info` prints (§3).
#[derive(Clone, Debug)]
pub struct DesignInfo {
    /// guide_u, sampled and validated.
    pub guide_u: Guide,
    /// guide_v, sampled and validated.
    pub guide_v: Guide,
    /// The frame at the common start point.
    pub frame: StartFrame,
    /// The generation mode.
    pub mode: Mode,
    /// θ in degrees reduced to (−180, 180].
    pub theta_deg: f64,
    /// The admissible θ.
    pub theta_range: ThetaRange,
    /// The surface normal at each sample of guide_u: rotation-minimising
    /// from the start frame's normal (§3.2), whatever θ.
    pub normals_u: Vec<DVec3>,
    /// The surface normal at each sample of guide_v (§3.2).
    pub normals_v: Vec<DVec3>,
}

impl DesignInfo {
    /// Grid size `(rows, cols)`.
    pub fn grid_size(&self) -> (usize, usize) {
        (self.guide_u.points.len(), self.guide_v.points.len())
    }
}

/// What [`generate`] returns: the mesh and what was learnt on the way (§3).
#[derive(Clone, Debug)]
pub struct Generated {
    /// The circular mesh with planar lines, with its node axes (the Gauss map).
    pub grid: QuadGrid,
    /// The validated design.
    pub info: DesignInfo,
    /// The pencil axes of the Gauss map.
    pub axes: PencilAxes,
    /// Pinching and folding seen by the Combescure transform (§5.2).
    pub report: CombescureReport,
}

/// Validate a design without building the mesh (§3); θ is not checked.
///
/// ```
/// use monge_core::{inspect, Design, GenerateOptions, GuideSpec};
/// let d = Design {
///     mesh: Default::default(),
///     theta_deg: 30.0,
///     guide_u: GuideSpec::Points {
///         points: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.2], [2.0, 0.0, 0.7]],
///         tangent: Some([1.0, 0.0, 0.0]), // orthogonal to guide_v's start tangent
///     },
///     guide_v: GuideSpec::points(vec![[0.0, 0.0, 0.0], [0.0, 1.0, 0.1], [0.0, 2.0, 0.5]]),
///     tolerance: None,
/// };
/// let info = inspect(&d, &GenerateOptions::default()).unwrap();
/// assert_eq!(info.grid_size(), (3, 3));
/// ```
pub fn inspect(design: &Design, options: &GenerateOptions) -> Result<DesignInfo, GenerateError> {
    check_grid_size(
        design.guide_u.sample_count(),
        design.guide_v.sample_count(),
        options,
    )?;
    if !design.theta_deg.is_finite() {
        return Err(GenerateError::ThetaNotFinite(design.theta_deg));
    }
    let tol = design.tolerance.unwrap_or_default();
    for (name, value, max, unit) in [
        (
            "planarity",
            tol.planarity,
            1.0,
            "relative to the guide's size",
        ),
        ("angle", tol.angle, std::f64::consts::FRAC_PI_2, "radians"),
        ("start", tol.start, 1.0, "relative to the guides' size"),
    ] {
        if !(0.0..=max).contains(&value) {
            return Err(GenerateError::BadTolerance {
                name,
                value,
                max,
                unit,
            });
        }
    }
    let guide_u = Guide::from_spec(&design.guide_u, GuideName::U, &tol)?;
    let guide_v = Guide::from_spec(&design.guide_v, GuideName::V, &tol)?;
    let size = guide_u.size.max(guide_v.size);
    if !(MIN_SIZE..=MAX_SIZE).contains(&size) {
        return Err(GenerateError::ScaleOutOfRange {
            size,
            min: MIN_SIZE,
            max: MAX_SIZE,
        });
    }
    let origin_ratio =
        crate::grid::origin_ratio(&guide_u.points).max(crate::grid::origin_ratio(&guide_v.points));
    let (pu, pv) = (guide_u.points[0], guide_v.points[0]);
    let distance = pu.distance(pv);
    let relative = distance / guide_u.size.max(guide_v.size);
    if relative.is_nan() || relative > tol.start {
        return Err(GenerateError::StartPointsDiffer {
            u: pu.to_array(),
            v: pv.to_array(),
            distance,
            relative,
            tolerance: tol.start,
            origin_ratio,
        });
    }
    let cos = guide_u.tangent.dot(guide_v.tangent);
    if cos.is_nan() || cos.abs() > libm::sin(tol.angle) {
        let angle_deg = libm::acos(cos.clamp(-1.0, 1.0)).to_degrees();
        return Err(GenerateError::NotOrthogonal {
            angle_deg,
            off_deg: (angle_deg - 90.0).abs(),
            tolerance_deg: tol.angle.to_degrees(),
            origin_ratio,
        });
    }
    let frame = StartFrame::new(
        guide_u.tangent,
        guide_v.tangent,
        guide_u.plane_normal,
        guide_v.plane_normal,
    );
    let n_p = frame.n_p;
    let normals_u = guide_normals(&guide_u.points, n_p);
    let normals_v = guide_normals(&guide_v.points, n_p);
    for (guide, normals, plane) in [
        (GuideName::U, &normals_u, guide_u.plane_normal),
        (GuideName::V, &normals_v, guide_v.plane_normal),
    ] {
        let turn = normal_turn(normals);
        if turn.is_nan() || turn < MIN_NORMAL_TURN {
            return Err(GenerateError::NormalStill {
                guide,
                turn,
                plane_deg: libm::asin(plane.cross(n_p).length().min(1.0)).to_degrees(),
                min: MIN_NORMAL_TURN,
            });
        }
    }
    Ok(DesignInfo {
        mode: if frame.is_characteristic() {
            Mode::Characteristic
        } else {
            Mode::Arbitrary
        },
        theta_range: frame.admissible_theta(),
        theta_deg: normalize_theta_deg(design.theta_deg),
        frame,
        guide_u,
        guide_v,
        normals_u,
        normals_v,
    })
}

/// Refuses a grid of `rows × cols` vertices above [`GenerateOptions::max_vertices`],
/// before any guide is sampled.
pub(crate) fn check_grid_size(
    rows: usize,
    cols: usize,
    options: &GenerateOptions,
) -> Result<(), GenerateError> {
    let vertices = rows.saturating_mul(cols);
    if vertices > options.max_vertices {
        return Err(GenerateError::GridTooLarge {
            rows,
            cols,
            vertices,
            limit: options.max_vertices,
        });
    }
    Ok(())
}

/// How far the surface normal turns along a guide (§2.2): the largest distance
/// between its first normal and another, or between its last and another (at
/// least half the Gauss image's diameter).
fn normal_turn(normals: &[DVec3]) -> f64 {
    let (first, last) = (normals[0], normals[normals.len() - 1]);
    normals
        .iter()
        .map(|n| n.distance(first).max(n.distance(last)))
        .fold(0.0, f64::max)
}

/// Generate the circular mesh with planar curvature lines of `design` (§3).
///
/// Normals along the guides (rotation-minimising, §3.2) → pencil axes from θ
/// (§2.1.2) → Gauss map (§2.2.1) → Combescure transform through the guides (§2.2.3),
/// computed relative to the guides' common start point (added back at the end), so
/// that the error stays relative to the design's size far from the origin.
///
/// ```
/// use monge_core::{generate, Design, GenerateOptions, GuideSpec};
/// let d = Design {
///     mesh: Default::default(),
///     theta_deg: 30.0,
///     guide_u: GuideSpec::Points {
///         points: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.2], [2.0, 0.0, 0.7]],
///         tangent: Some([1.0, 0.0, 0.0]), // orthogonal to guide_v's start tangent
///     },
///     guide_v: GuideSpec::points(vec![[0.0, 0.0, 0.0], [0.0, 1.0, 0.1], [0.0, 2.0, 0.5]]),
///     tolerance: None,
/// };
/// let mesh = generate(&d, &GenerateOptions::default()).unwrap().grid;
/// assert_eq!((mesh.rows, mesh.cols), (3, 3));
/// assert_eq!(mesh.vertex(2, 0).to_array(), [2.0, 0.0, 0.7]);
/// ```
pub fn generate(design: &Design, options: &GenerateOptions) -> Result<Generated, GenerateError> {
    let info = inspect(design, options)?;
    if (info.theta_deg - 90.0).abs() < SINGULAR_WINDOW_DEG {
        return Err(GenerateError::ThetaSingular {
            theta_deg: info.theta_deg,
            window: SINGULAR_WINDOW_DEG,
        });
    }
    let axes =
        pencil_axes(&info.frame, info.theta_deg).map_err(|e| GenerateError::ThetaInadmissible {
            theta_deg: e.theta_deg,
            min_deg: e.range.min_deg,
            max_deg: e.range.max_deg,
        })?;
    let (along_u, along_v) = (&info.normals_u, &info.normals_v);
    let gauss = GaussRows::new(&axes, along_u, along_v);
    let transform = combescure(&gauss, &info.guide_u.points, &info.guide_v.points).map_err(
        |ParallelLines { face, sine, zero_edge }| GenerateError::Degenerate {
            face,
            sine,
            zero_edge,
            hint: if zero_edge {
                "The normal does not turn along that edge: the surface has zero curvature there along a \
                 curvature line (a straight piece of a guide, or a sample exactly on a parabolic line \
                 such as the top circle of a torus). Curve the guide there, or sample it so that no \
                 sample falls exactly on that line"
            } else {
                "The mesh pinches to a point there (§5.2). Change θ or the guides"
            },
        },
    )?;
    let (rows, cols) = (along_u.len(), along_v.len());
    Ok(Generated {
        grid: QuadGrid::new(rows, cols, transform.vertices, transform.normals),
        info,
        axes,
        report: transform.report,
    })
}
