//! Held-out targets for `approximate`, built independently of monge-core (closed forms,
//! no call to its construction), and distances measured by brute force on fine
//! samplings of the target and of the result (not by the approximation's objective).
//!
//! Surfaces with planar curvature lines (§4.1): a torus patch (revolution), a moulding
//! surface (a planar profile swept along a planar rail in its normal planes), a Dupin
//! cyclide patch; free-form ones: an elliptic paraboloid, a hyperbolic paraboloid, a
//! bicubic Bézier roof. Each is scaled to a size (bounding-box diagonal), rotated by a
//! random rotation and moved far from the origin.

#![allow(dead_code)]

use glam::{DQuat, DVec3};
use monge_core::approximate::TrimmedMesh;
use monge_core::QuadGrid;

use crate::common::triangle_distance;

/// A deterministic random stream (splitmix64).
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Rng(seed)
    }

    /// Uniform in [0, 1).
    pub fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Standard normal (Box–Muller).
    pub fn gauss(&mut self) -> f64 {
        let (a, b) = (self.uniform().max(1e-300), self.uniform());
        (-2.0 * a.ln()).sqrt() * (std::f64::consts::TAU * b).cos()
    }
}

/// A parametrised surface over `[0, 1]²` (curvature-line parameters for the PCL ones).
pub type Surface = fn(f64, f64) -> DVec3;

/// A held-out target: its closed form, placed (scaled, rotated, moved).
pub struct Target {
    pub name: &'static str,
    surface: Surface,
    /// Whether it has planar curvature lines (then `theta_folded` is its θ).
    pub pcl: bool,
    /// θ of its Gauss map folded into [0°, 90°] (see [`fold_theta`]); NaN if free-form.
    pub theta_folded: f64,
    scale: f64,
    rotation: DQuat,
    offset: DVec3,
    /// Bounding-box diagonal once placed.
    pub size: f64,
}

/// θ up to the symmetries of the Gauss map (§2.1): exchanging the axes (π − θ) and
/// mirroring (−θ) give the same surface family, so compare θ folded into [0°, 90°].
pub fn fold_theta(theta_deg: f64) -> f64 {
    let t = theta_deg.rem_euclid(360.0);
    let t = if t > 180.0 { 360.0 - t } else { t };
    t.min(180.0 - t)
}

fn torus(u: f64, v: f64) -> DVec3 {
    let (big, small) = (10.0, 4.0);
    let (a, b) = (1.3 * u, -0.6 + 1.9 * v);
    let r = big + small * b.cos();
    DVec3::new(r * a.cos(), r * a.sin(), small * b.sin())
}

/// A planar rail `c(u) = (s, 0.3 s²)` and a profile `(0.8 t, 0.5 (1 − t²) + 0.2 t³)` in
/// the rail's normal plane (spanned by its in-plane normal and the vertical).
fn moulding(u: f64, v: f64) -> DVec3 {
    let (s, t) = (2.0 * u - 1.0, 2.0 * v - 1.0);
    let c = DVec3::new(s, 0.3 * s * s, 0.0);
    let tangent = DVec3::new(1.0, 0.6 * s, 0.0).normalize();
    let normal = DVec3::new(-tangent.y, tangent.x, 0.0);
    c + 0.8 * t * normal + (0.5 * (1.0 - t * t) + 0.2 * t * t * t) * DVec3::Z
}

/// A second moulding: the planar rail `c(u) = (s, 0.2 s² + 0.1 s³)` and the profile
/// `(0.6 t, 0.25 sin(1.5 t + 0.5))` in the rail's normal planes.
fn moulding_sine(u: f64, v: f64) -> DVec3 {
    let (s, t) = (2.0 * u - 1.0, 2.0 * v - 1.0);
    let c = DVec3::new(s, 0.2 * s * s + 0.1 * s * s * s, 0.0);
    let tangent = DVec3::new(1.0, 0.4 * s + 0.3 * s * s, 0.0).normalize();
    let normal = DVec3::new(-tangent.y, tangent.x, 0.0);
    c + 0.6 * t * normal + 0.25 * (1.5 * t + 0.5).sin() * DVec3::Z
}

/// An onion dome's side: the profile `r = 1 + 0.5 sin(πt) − 0.4 t²`, `z = 1.6 t`, turned
/// through 150° about the z axis (its u-lines parallels, its v-lines meridians).
fn onion(u: f64, v: f64) -> DVec3 {
    let (angle, t) = (150f64.to_radians() * u, v);
    let r = 1.0 + 0.5 * (std::f64::consts::PI * t).sin() - 0.4 * t * t;
    DVec3::new(r * angle.cos(), r * angle.sin(), 1.6 * t)
}

/// A shallow dome of revolution over a square plan: the paraboloid `z = −0.1 ρ²`, its
/// axis at (0.3, −0.2), off the plan's centre (so that its corners see different
/// curvatures, one nearly umbilic), over [−1, 1]² (rise 0.31 over a span of 2). Its
/// curvature lines are planar (meridians and parallels), its plan not cut along them.
fn dome_of_revolution(u: f64, v: f64) -> DVec3 {
    let (x, y) = (2.0 * u - 1.0, 2.0 * v - 1.0);
    DVec3::new(x, y, -0.1 * ((x - 0.3).powi(2) + (y + 0.2).powi(2)))
}

/// A spherical cap of radius 3 over [−1, 1]² (rise 0.35 over a span of 2): umbilic
/// everywhere.
fn spherical_cap(u: f64, v: f64) -> DVec3 {
    let (x, y) = (2.0 * u - 1.0, 2.0 * v - 1.0);
    DVec3::new(x, y, (9.0 - x * x - y * y).sqrt())
}

/// A ring Dupin cyclide (a = 10, c = 3, μ = 5) over part of its curvature-line
/// parameters (its u- and v-lines are circles).
fn cyclide(u: f64, v: f64) -> DVec3 {
    let (a, c, mu) = (10.0f64, 3.0, 5.0);
    let b2 = a * a - c * c;
    let b = b2.sqrt();
    let (u, v) = (0.2 + 1.4 * u, -0.7 + 1.6 * v);
    let den = a - c * u.cos() * v.cos();
    DVec3::new(
        (mu * (c - a * u.cos() * v.cos()) + b2 * u.cos()) / den,
        b * u.sin() * (a - mu * v.cos()) / den,
        b * v.sin() * (c * u.cos() - mu) / den,
    )
}

fn paraboloid(u: f64, v: f64) -> DVec3 {
    let (x, y) = (2.0 * u - 1.0, 1.4 * v - 0.7);
    DVec3::new(x, y, -0.35 * x * x - 0.2 * y * y)
}

fn hypar(u: f64, v: f64) -> DVec3 {
    let (x, y) = (2.0 * u - 1.0, 2.0 * v - 1.0);
    DVec3::new(x, y, 0.25 * x * y + 0.05 * x * x)
}

fn bernstein(t: f64) -> [f64; 4] {
    let s = 1.0 - t;
    [s * s * s, 3.0 * s * s * t, 3.0 * s * t * t, t * t * t]
}

/// A bicubic Bézier roof over a 1 × 1.3 rectangle, rise about 25 %.
fn bezier(u: f64, v: f64) -> DVec3 {
    const HEIGHTS: [[f64; 4]; 4] = [
        [0.0, 0.15, 0.1, 0.0],
        [0.1, 0.45, 0.35, 0.05],
        [0.05, 0.4, 0.5, 0.15],
        [0.0, 0.1, 0.2, 0.05],
    ];
    let (bu, bv) = (bernstein(u), bernstein(v));
    let mut z = 0.0;
    for (i, row) in HEIGHTS.iter().enumerate() {
        for (j, h) in row.iter().enumerate() {
            z += bu[i] * bv[j] * h;
        }
    }
    DVec3::new(u, 1.3 * v + 0.1 * u * v, z)
}

/// A designer's dome over a 1 × 0.8 plan whose four edges lie flat at z = 0: a bicubic
/// Bézier patch, its boundary control points at height 0 and its four inner ones at 0.15
/// (rise 0.084). Its edges are straight asymptotic lines, its corners saddles (the
/// twist), its centre elliptic.
fn flat_edge_dome(u: f64, v: f64) -> DVec3 {
    let (bu, bv) = (bernstein(u), bernstein(v));
    let inner = (bu[1] + bu[2]) * (bv[1] + bv[2]);
    DVec3::new(u, 0.8 * v, 0.15 * inner)
}

/// A random rotation (uniform quaternion).
fn random_rotation(rng: &mut Rng) -> DQuat {
    DQuat::from_xyzw(rng.gauss(), rng.gauss(), rng.gauss(), rng.gauss()).normalize()
}

/// Bounding-box diagonal of points.
pub fn diagonal(points: &[DVec3]) -> f64 {
    let (lo, hi) = points.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    (hi - lo).length()
}

impl Target {
    /// The surface `surface`, scaled to `size`, randomly rotated (from `seed`) and
    /// moved `far` from the origin.
    fn placed(
        name: &'static str,
        surface: Surface,
        pcl: bool,
        size: f64,
        far: f64,
        seed: u64,
    ) -> Self {
        let raw = grid_points(surface, 60);
        let scale = size / diagonal(&raw);
        let mut rng = Rng::new(seed);
        let rotation = random_rotation(&mut rng);
        let direction = DVec3::new(rng.gauss(), rng.gauss(), rng.gauss()).normalize();
        let mut target = Target {
            name,
            surface,
            pcl,
            theta_folded: f64::NAN,
            scale,
            rotation,
            offset: far * direction,
            size,
        };
        if pcl {
            target.theta_folded = gauss_map_theta(surface);
        }
        target.size = diagonal(&target.grid(60));
        target
    }

    /// The point at parameters `(u, v)`.
    pub fn at(&self, u: f64, v: f64) -> DVec3 {
        self.offset + self.rotation * ((self.surface)(u, v) * self.scale)
    }

    /// The `n × n` vertices at even parameters (a mesh's vertices).
    pub fn grid(&self, n: usize) -> Vec<DVec3> {
        self.grid_over(n, (0.0, 1.0), (0.0, 1.0))
    }

    /// The `n × n` vertices at even parameters over `u.0..u.1` × `v.0..v.1`, within the
    /// square or beyond it (the closed form extended).
    pub fn grid_over(&self, n: usize, u: (f64, f64), v: (f64, f64)) -> Vec<DVec3> {
        let step = 1.0 / (n - 1) as f64;
        let at = |(lo, hi): (f64, f64), k: usize| lo + k as f64 * step * (hi - lo);
        (0..n * n)
            .map(|k| self.at(at(u, k / n), at(v, k % n)))
            .collect()
    }

    /// `count` points at random parameters, each coordinate noised by `noise` × size
    /// (Gaussian): a scan.
    pub fn scan(&self, count: usize, noise: f64, seed: u64) -> Vec<DVec3> {
        self.scan_with_parameters(count, noise, seed)
            .into_iter()
            .map(|(_, p)| p)
            .collect()
    }

    /// [`Target::scan`], each point with the parameters `(u, v)` it was drawn at.
    pub fn scan_with_parameters(
        &self,
        count: usize,
        noise: f64,
        seed: u64,
    ) -> Vec<((f64, f64), DVec3)> {
        let mut rng = Rng::new(seed);
        (0..count)
            .map(|_| {
                let (u, v) = (rng.uniform(), rng.uniform());
                let p = self.at(u, v);
                let noised =
                    p + noise * self.size * DVec3::new(rng.gauss(), rng.gauss(), rng.gauss());
                ((u, v), noised)
            })
            .collect()
    }

    /// The fine triangulation of the target (`n × n` vertices, two triangles a quad).
    pub fn triangles(&self, n: usize) -> Vec<[DVec3; 3]> {
        let p = self.grid(n);
        grid_triangles(&p, n, n)
    }
}

fn grid_points(surface: Surface, n: usize) -> Vec<DVec3> {
    let step = 1.0 / (n - 1) as f64;
    (0..n * n)
        .map(|k| surface((k / n) as f64 * step, (k % n) as f64 * step))
        .collect()
}

/// Two triangles per quad of a `rows × cols` grid of points.
fn grid_triangles(p: &[DVec3], rows: usize, cols: usize) -> Vec<[DVec3; 3]> {
    let mut out = Vec::with_capacity(2 * (rows - 1) * (cols - 1));
    for i in 0..rows - 1 {
        for j in 0..cols - 1 {
            let (a, b, c, d) = (
                p[i * cols + j],
                p[i * cols + j + 1],
                p[(i + 1) * cols + j + 1],
                p[(i + 1) * cols + j],
            );
            out.push([a, b, c]);
            out.push([a, c, d]);
        }
    }
    out
}

/// The unit normal of `surface` at `(u, v)` (central differences).
fn normal(surface: Surface, u: f64, v: f64) -> DVec3 {
    let h = 1e-5;
    let du = surface(u + h, v) - surface(u - h, v);
    let dv = surface(u, v + h) - surface(u, v - h);
    du.cross(dv).normalize()
}

/// θ of a PCL surface from its Gauss map (§2.1), folded ([`fold_theta`]): the normals
/// along each u-line lie on a circle of the sphere; the planes of those circles meet
/// in an axis at distance `|tan(θ/2)|` from the centre (or its inverse, for the other
/// family).
fn gauss_map_theta(surface: Surface) -> f64 {
    // The plane of the normals along the u-line at `v`: n·x = d.
    let plane = |v: f64| -> (DVec3, f64) {
        let normals: Vec<DVec3> = (0..=20)
            .map(|k| normal(surface, k as f64 / 20.0, v))
            .collect();
        let centroid = normals.iter().copied().sum::<DVec3>() / normals.len() as f64;
        let mut m = nalgebra::Matrix3::zeros();
        for p in &normals {
            let d = *p - centroid;
            let d = nalgebra::Vector3::new(d.x, d.y, d.z);
            m += d * d.transpose();
        }
        let eig = nalgebra::SymmetricEigen::new(m);
        let k = eig.eigenvalues.imin();
        let n = eig.eigenvectors.column(k);
        let n = DVec3::new(n[0], n[1], n[2]);
        (n, n.dot(centroid))
    };
    let (n1, d1) = plane(0.1);
    let (n2, d2) = plane(0.9);
    let direction = n1.cross(n2);
    if direction.length() < 1e-9 {
        // Parallel planes: the axis is at infinity (θ = ±180°, folded 0°).
        return 0.0;
    }
    // The point of the axis nearest to the centre.
    let point = (d1 * n2 - d2 * n1).cross(direction) / direction.length_squared();
    let distance = point.length();
    fold_theta(2.0 * distance.min(1.0 / distance).atan().to_degrees())
}

/// The held-out targets, sizes 1 m to 100 m, 1e3 to 1e5 from the origin.
pub fn targets() -> Vec<Target> {
    vec![
        Target::placed("torus patch", torus, true, 30.0, 1e4, 1),
        Target::placed("moulding", moulding, true, 1.5, 1e3, 2),
        Target::placed("Dupin cyclide", cyclide, true, 100.0, 1e5, 3),
        Target::placed("paraboloid", paraboloid, false, 20.0, 1e4, 4),
        Target::placed("hyperbolic paraboloid", hypar, false, 10.0, 1e3, 5),
        Target::placed("Bézier roof", bezier, false, 50.0, 1e5, 6),
        Target::placed("flat-edge dome", flat_edge_dome, false, 100.0, 1e4, 7),
        Target::placed("flat-edge dome 1 m", flat_edge_dome, false, 1.0, 1e3, 8),
        Target::placed("sine moulding", moulding_sine, true, 5.0, 1e4, 9),
        Target::placed("onion dome", onion, true, 20.0, 1e5, 10),
        // Planar curvature lines, but not along the square plan's parameters: θ untested.
        Target::placed(
            "dome of revolution",
            dome_of_revolution,
            false,
            30.0,
            1e4,
            11,
        ),
        Target::placed("spherical cap", spherical_cap, false, 10.0, 1e3, 12),
    ]
}

/// The held-out target named `name` (one of [`targets`]).
pub fn target(name: &str) -> Target {
    targets()
        .into_iter()
        .find(|t| t.name == name)
        .unwrap_or_else(|| panic!("no held-out target `{name}`"))
}

/// Triangles with their bounding spheres, for a brute-force search that skips the far ones.
pub struct Triangles {
    triangles: Vec<([DVec3; 3], DVec3, f64)>,
}

impl Triangles {
    pub fn new(triangles: Vec<[DVec3; 3]>) -> Self {
        Triangles {
            triangles: triangles
                .into_iter()
                .map(|t| {
                    let c = (t[0] + t[1] + t[2]) / 3.0;
                    let r = t.iter().map(|p| p.distance(c)).fold(0.0, f64::max);
                    (t, c, r)
                })
                .collect(),
        }
    }

    /// The faces of a quad grid, two triangles each.
    pub fn of_grid(grid: &QuadGrid) -> Self {
        Self::new(grid_triangles(&grid.vertices, grid.rows, grid.cols))
    }

    /// Distance from `p` to the nearest triangle (every triangle considered).
    pub fn distance(&self, p: DVec3) -> f64 {
        let mut best = f64::INFINITY;
        for (t, c, r) in &self.triangles {
            if p.distance(*c) - r < best {
                best = best.min(triangle_distance(p, *t));
            }
        }
        best
    }
}

/// Largest distances both ways between a result mesh and the target, relative to the
/// target's size: (result → target, target → result).
pub fn max_both_ways(target: &Target, grid: &QuadGrid) -> (f64, f64) {
    both_ways(target, &grid.vertices, Triangles::of_grid(grid))
}

/// Largest distances both ways between a result mesh trimmed to the target's outline
/// and the target, relative to the target's size: (result → target, from every vertex
/// of the trimmed mesh, its cuts too; target → result, to its polygons, each cut into
/// a fan of triangles).
pub fn max_both_ways_trimmed(target: &Target, trimmed: &TrimmedMesh) -> (f64, f64) {
    let fans = trimmed
        .faces
        .iter()
        .flat_map(|f| {
            (1..f.len() - 1).map(|k| {
                [
                    trimmed.vertices[f[0]],
                    trimmed.vertices[f[k]],
                    trimmed.vertices[f[k + 1]],
                ]
            })
        })
        .collect();
    both_ways(target, &trimmed.vertices, Triangles::new(fans))
}

/// Largest distances, relative to the target's size, from `vertices` to the target (its
/// fine triangulation) and from the target (a 61 × 61 sampling) to `mesh`.
fn both_ways(target: &Target, vertices: &[DVec3], mesh: Triangles) -> (f64, f64) {
    let fine = Triangles::new(target.triangles(121));
    let to_target = vertices
        .iter()
        .map(|v| fine.distance(*v))
        .fold(0.0, f64::max);
    let to_result = target
        .grid(61)
        .iter()
        .map(|p| mesh.distance(*p))
        .fold(0.0, f64::max);
    (to_target / target.size, to_result / target.size)
}
