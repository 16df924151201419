//! Builders shared by the monge-core integration tests: guides, designs, the
//! named designs of the paper that several test files use, and the helpers of
//! tests split over several files (the submodules).

pub mod cyclidic;
pub mod developable;
pub mod random_designs;

use glam::DVec3;
use monge_core::{generate, Design, GenerateError, GenerateOptions, GuideSpec, QuadGrid};
use nalgebra::DMatrix;

/// Every property must hold to this, relative to the model size.
pub const TOL: f64 = 1e-9;

/// The default generation options.
pub fn opts() -> GenerateOptions {
    GenerateOptions::default()
}

/// An arc guide starting at the origin.
pub fn arc(center: [f64; 3], normal: [f64; 3], angle_deg: f64, samples: usize) -> GuideSpec {
    GuideSpec::arc(center, [0.0; 3], normal, angle_deg, samples)
}

/// A clamped uniform cubic B-spline guide.
pub fn bspline(control_points: Vec<[f64; 3]>, samples: usize) -> GuideSpec {
    GuideSpec::bspline(3, control_points, samples)
}

/// A design of two guides at angle θ, with the default mesh options and tolerances.
pub fn design(theta_deg: f64, guide_u: GuideSpec, guide_v: GuideSpec) -> Design {
    Design {
        mesh: Default::default(),
        theta_deg,
        guide_u,
        guide_v,
        tolerance: None,
    }
}

/// The mesh of `design` with the default options; panics with the refusal.
pub fn mesh(design: &Design) -> QuadGrid {
    generate(design, &opts())
        .unwrap_or_else(|e| panic!("design refused: {e}"))
        .grid
}

/// The error `generate` refuses `design` with; panics if it is accepted.
pub fn refused(design: &Design, options: &GenerateOptions) -> GenerateError {
    match generate(design, options) {
        Ok(_) => panic!("design accepted: {design:?}"),
        Err(e) => e,
    }
}

/// Asserts that `message` contains every one of `parts`, and prints it.
pub fn assert_mentions(message: &str, parts: &[&str]) {
    for p in parts {
        assert!(message.contains(p), "message lacks {p:?}: {message}");
    }
    eprintln!("message: {message}");
}

/// Least-squares plane of `points` by SVD: (centroid, unit normal, largest distance).
pub fn plane_fit(points: &[DVec3]) -> (DVec3, DVec3, f64) {
    let c = points.iter().copied().sum::<DVec3>() / points.len() as f64;
    let m = DMatrix::from_fn(points.len(), 3, |r, k| (points[r] - c)[k]);
    let svd = m.svd(false, true);
    let v_t = svd.v_t.unwrap();
    let k = svd.singular_values.imin();
    let n = DVec3::new(v_t[(k, 0)], v_t[(k, 1)], v_t[(k, 2)]).normalize();
    let d = points
        .iter()
        .map(|p| (*p - c).dot(n).abs())
        .fold(0.0, f64::max);
    (c, n, d)
}

/// Circle through three points: centre, unit normal, radius.
pub fn circle3(a: DVec3, b: DVec3, c: DVec3) -> (DVec3, DVec3, f64) {
    let (ab, ac) = (b - a, c - a);
    let n = ab.cross(ac);
    let center = a
        + (n.cross(ab) * ac.length_squared() + ac.cross(n) * ab.length_squared())
            / (2.0 * n.length_squared());
    (center, n.normalize(), center.distance(a))
}

/// Distance of `p` from the circle `(center, normal, radius)`.
pub fn circle_distance(p: DVec3, (center, normal, radius): (DVec3, DVec3, f64)) -> f64 {
    let q = p - center;
    let h = q.dot(normal);
    let r = (q - h * normal).length();
    (h * h + (r - radius).powi(2)).sqrt()
}

/// Distance of one corner of a quad from the plane of the other three, for the
/// triple of largest area (0 if all four are collinear).
pub fn own_face_planarity(q: &[DVec3; 4]) -> f64 {
    let mut best = (0.0, 0.0);
    for k in 0..4 {
        let (a, b, c) = (q[(k + 1) % 4], q[(k + 2) % 4], q[(k + 3) % 4]);
        let n = (b - a).cross(c - a);
        let area = n.length();
        if area > best.0 {
            best = (area, (q[k] - a).dot(n).abs() / area);
        }
    }
    best.1
}

/// The bits of the coordinates of `points`, to compare them exactly.
pub fn bits(points: &[DVec3]) -> Vec<[u64; 3]> {
    points
        .iter()
        .map(|p| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()])
        .collect()
}

/// A small deterministic generator (a 64-bit LCG: no dependency, fixed seeds).
pub struct Lcg(pub u64);

impl Lcg {
    /// Uniform in [0, 1).
    pub fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in [−1, 1)³.
    pub fn vec(&mut self) -> DVec3 {
        DVec3::new(self.signed(), self.signed(), self.signed())
    }

    /// A unit vector: [`Lcg::vec`] normalised, if its length is in [0.1, 1).
    pub fn unit(&mut self) -> DVec3 {
        loop {
            let v = self.vec();
            if (0.1..1.0).contains(&v.length()) {
                return v.normalize();
            }
        }
    }

    /// Uniform in [−1, 1).
    fn signed(&mut self) -> f64 {
        self.next() * 2.0 - 1.0
    }
}

/// ulp of `x` (0 for 0).
pub fn ulp(x: f64) -> f64 {
    if x == 0.0 {
        0.0
    } else {
        (f64::from_bits(x.to_bits() + 1) - x).abs()
    }
}

/// Radius of guide_u of [`two_circles`].
pub const RAIL_RADIUS: f64 = 10.0;
/// Radius of guide_v of [`two_circles`].
pub const PROFILE_RADIUS: f64 = 3.0;

/// Torus (θ = 0, §4.1.1) and Dupin cyclides (θ ≠ 0, §4.1.3, Figure 12):
/// guide_u an arc of radius [`RAIL_RADIUS`] in y = 0 centred at (0, 0, −10)
/// (start tangent ±x) over `rail_deg` in `rows` samples; guide_v an arc of
/// radius [`PROFILE_RADIUS`] in x = 0 centred at (0, 0, −3) (start tangent ±y)
/// over `profile_deg` in `cols` samples.
pub fn two_circles(
    theta_deg: f64,
    rail_deg: f64,
    rows: usize,
    profile_deg: f64,
    cols: usize,
) -> Design {
    design(
        theta_deg,
        arc([0.0, 0.0, -RAIL_RADIUS], [0.0, 1.0, 0.0], rail_deg, rows),
        arc(
            [0.0, 0.0, -PROFILE_RADIUS],
            [-1.0, 0.0, 0.0],
            profile_deg,
            cols,
        ),
    )
}

/// The free-form design of Figure 13 (§4.2): cubic B-spline guides in
/// y = 0 and x = 0, with `rows` and `cols` samples.
pub fn freeform(theta_deg: f64, rows: usize, cols: usize) -> Design {
    design(
        theta_deg,
        bspline(
            vec![
                [0.0, 0.0, 0.0],
                [4.0, 0.0, 0.0],
                [8.0, 0.0, 2.5],
                [12.0, 0.0, 1.0],
                [16.0, 0.0, 3.5],
            ],
            rows,
        ),
        freeform_guide_v(cols),
    )
}

/// guide_v of [`freeform`]: a cubic B-spline in x = 0 with `samples` samples.
pub fn freeform_guide_v(samples: usize) -> GuideSpec {
    bspline(
        vec![
            [0.0, 0.0, 0.0],
            [0.0, 3.0, 0.0],
            [0.0, 6.0, -1.5],
            [0.0, 10.0, 1.0],
        ],
        samples,
    )
}

/// Figure-22-like (§4.8): cubic B-spline guides, nearly straight at first and
/// sharply bent near their ends, so uniform parameters give elongated faces;
/// `samples` samples on each guide.
pub fn figure22(samples: usize) -> Design {
    design(
        -30.0,
        bspline(
            vec![[0.0; 3], [4.0, 0.0, 0.0], [6.0, 0.0, 0.4], [6.5, 0.0, 3.0]],
            samples,
        ),
        bspline(
            vec![[0.0; 3], [0.0, 3.0, 0.0], [0.0, 5.0, 0.3], [0.0, 5.4, 2.5]],
            samples,
        ),
    )
}

/// Radius of [`arc_u`].
pub const R_U: f64 = 4.0;

/// The bottom guide of the multi-patch designs (§4.7): an arc of the circle of
/// radius [`R_U`] centred at (0, 0, −R_U) in the plane y = 0 (axis y, towards
/// +x for positive angles), starting at angle `from_deg`.
pub fn arc_u(from_deg: f64, angle_deg: f64, samples: usize) -> GuideSpec {
    let a = from_deg.to_radians();
    GuideSpec::arc(
        [0.0, 0.0, -R_U],
        [R_U * a.sin(), 0.0, R_U * a.cos() - R_U],
        [0.0, angle_deg.signum(), 0.0],
        angle_deg.abs(),
        samples,
    )
}

/// Distance from a point to a triangle by projection and edges (a different formula
/// from the library's region test).
pub fn triangle_distance(p: DVec3, [a, b, c]: [DVec3; 3]) -> f64 {
    let n = (b - a).cross(c - a).normalize();
    let q = p - n * (p - a).dot(n);
    let edges = [(a, b), (b, c), (c, a)];
    if edges
        .iter()
        .all(|(u, v)| (*v - *u).cross(q - *u).dot(n) >= 0.0)
        || edges
            .iter()
            .all(|(u, v)| (*v - *u).cross(q - *u).dot(n) <= 0.0)
    {
        return (p - a).dot(n).abs();
    }
    edges
        .iter()
        .map(|(u, v)| {
            let e = *v - *u;
            let t = ((p - *u).dot(e) / e.length_squared()).clamp(0.0, 1.0);
            p.distance(*u + t * e)
        })
        .fold(f64::INFINITY, f64::min)
}
