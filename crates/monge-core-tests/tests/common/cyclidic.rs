//! Designs, nets and measures shared by the cyclidic-net tests (§4.4, §4.6,
//! §5.3): circles are fitted to sampled points here (three-point circles),
//! never taken from the patch formulas.

use glam::DVec3;
use monge_core::cyclidic::{CyclidicNet, CyclidicOptions, Frame};
use monge_core::{Design, QuadGrid};

use super::{freeform, mesh, two_circles, Lcg};

/// The torus design (θ = 0, two circular-arc guides).
pub fn torus() -> Design {
    two_circles(0.0, 80.0, 9, 70.0, 7)
}

/// The Dupin cyclide design of Figure 12 (θ = 30°), coarser.
pub fn dupin30() -> Design {
    Design {
        theta_deg: 30.0,
        ..torus()
    }
}

/// A free-form design (Figure 13's B-spline guides, coarser).
pub fn coarse_freeform() -> Design {
    freeform(-30.0, 13, 9)
}

/// The §4.4 net of a design.
pub fn net_of(d: &Design) -> (QuadGrid, CyclidicNet) {
    let g = mesh(d);
    let net = CyclidicNet::from_normals(&g, &CyclidicOptions::default()).unwrap();
    (g, net)
}

/// Apply an inversion in the sphere of radius `r` about `c`: a circular mesh stays
/// circular but its lines stop being planar.
pub fn invert(g: &QuadGrid, c: DVec3, r: f64) -> QuadGrid {
    let v = g
        .vertices
        .iter()
        .map(|p| c + (*p - c) * (r * r / (*p - c).length_squared()))
        .collect();
    QuadGrid::new(g.rows, g.cols, v, vec![])
}

/// The faces of a net.
pub fn faces(net: &CyclidicNet) -> impl Iterator<Item = (usize, usize)> + use<> {
    let c = net.cols() - 1;
    (0..(net.rows() - 1) * c).map(move |k| (k / c, k % c))
}

/// The four nets most tests run on: §4.4 nets of the torus, the Dupin cyclide,
/// the free-form design, and a carried-frame net on an inverted (non-planar-line) mesh.
pub fn nets() -> Vec<(&'static str, QuadGrid, CyclidicNet)> {
    let mut out: Vec<_> = [
        ("torus", torus()),
        ("dupin30", dupin30()),
        ("freeform", coarse_freeform()),
    ]
    .into_iter()
    .map(|(name, d)| {
        let (g, n) = net_of(&d);
        (name, g, n)
    })
    .collect();
    let inv = invert(&mesh(&coarse_freeform()), DVec3::new(3.0, 2.0, 6.0), 8.0);
    let t1 = (inv.vertex(1, 0) - inv.vertex(0, 0)).normalize();
    let t2 = (inv.vertex(0, 1) - inv.vertex(0, 0))
        .reject_from(t1)
        .normalize();
    let net =
        CyclidicNet::from_frame(&inv, Frame::new(t1, t2), &CyclidicOptions::default()).unwrap();
    out.push(("inverted freeform, carried frame", inv, net));
    out
}

/// `n` equally spaced values in [0, 1].
pub fn params(n: usize) -> Vec<f64> {
    (0..n).map(|k| k as f64 / (n - 1) as f64).collect()
}

/// Random circular quads (four points in cyclic order on a random circle) with a
/// random orthonormal frame at the first corner.
pub fn random_patches(seed: u64) -> impl Iterator<Item = ([DVec3; 4], Frame)> {
    let mut rng = Lcg(seed);
    std::iter::repeat_with(move || {
        let (c, n) = (rng.unit() * 3.0, rng.unit());
        let x = n.any_orthonormal_vector();
        let y = n.cross(x);
        let r = 0.5 + 2.0 * rng.next();
        let mut angles: Vec<f64> = (0..4).map(|_| rng.next() * std::f64::consts::TAU).collect();
        angles.sort_by(f64::total_cmp);
        let quad: [DVec3; 4] =
            std::array::from_fn(|k| c + r * (angles[k].cos() * x + angles[k].sin() * y));
        let t1 = rng.unit();
        let t2 = rng.unit().reject_from(t1).normalize();
        (quad, Frame::new(t1, t2))
    })
}
