//! A candidate alignment and the line geometry both solvers share (§4.5).

use glam::DVec3;

use crate::design::Design;

/// The point of the line `{p_a · x = d_a} ∩ {p_b · x = d_b}` nearest to `near`.
pub(super) fn line_point(pa: DVec3, da: f64, pb: DVec3, db: f64, near: DVec3) -> DVec3 {
    let (alpha, beta) = solve_gram(pa.dot(pb), da, db);
    let x0 = alpha * pa + beta * pb;
    let e = pa.cross(pb).normalize();
    x0 + e * e.dot(near - x0)
}

/// `(α, β)` with `α + g β = a`, `g α + β = b` (the Gram system of two unit vectors).
pub(super) fn solve_gram(g: f64, a: f64, b: f64) -> (f64, f64) {
    let det = 1.0 - g * g;
    ((a - g * b) / det, (b - g * a) / det)
}

/// One candidate design with its quality (lower is better) and the c's.
pub(super) struct Candidate {
    pub(super) design: Design,
    pub(super) c: [f64; 4],
    pub(super) turning: f64,
}
