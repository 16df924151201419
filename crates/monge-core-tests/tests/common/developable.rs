//! Measures shared by the developable-mesh tests (§3.3, Figure 11): isosceles
//! trapezoid faces around the meeting point of two rows (computed here from the
//! rows alone), `measure`, columns in their cutting planes, helix segments at
//! slope α.

use glam::DVec3;
use monge_core::developable::{developable, DevelopableMesh, DevelopableSpec};
use monge_core::measure::measure;
use monge_core::GenerateOptions;

use super::TOL;

pub type Xyz = [f64; 3];

/// The point of line `p + s·d` closest to the line `q + t·e` (the lines meet).
pub fn meet(p: DVec3, d: DVec3, q: DVec3, e: DVec3) -> DVec3 {
    // Minimise |p + s d − q − t e|²: [d·d −d·e; d·e −e·e] (s, t) = ((q−p)·d, (q−p)·e).
    let w = q - p;
    let (dd, de, ee) = (d.dot(d), d.dot(e), e.dot(e));
    let (wd, we) = (w.dot(d), w.dot(e));
    let s = (wd * ee - we * de) / (dd * ee - de * de);
    p + s * d
}

/// Worst values measured on a mesh; every one must be ≤ [`TOL`].
#[derive(Debug, Default)]
pub struct Worst {
    /// `|OA − OD|`, `|OB − OC|` / size (O: where rows i and i+1 meet).
    pub apex: f64,
    /// `| |AB| − |DC| |`, `| |AC| − |BD| |` / size (legs and diagonals).
    pub isosceles: f64,
    /// `|AD × BC|` / (|AD| |BC|): the two bases are parallel.
    pub bases: f64,
    /// `measure`: face planarity, circularity, row and column planarity.
    pub measured: f64,
    /// `measure`: torsion and unit length of the node axes.
    pub axes: f64,
    /// `|x · N − h_j|` / size over the vertices of column j.
    pub in_plane: f64,
    /// `|angle(segment, reference plane) − α|` in radians over the helix segments.
    pub slope: f64,
}

impl Worst {
    pub fn max(&self) -> f64 {
        [
            self.apex,
            self.isosceles,
            self.bases,
            self.measured,
            self.axes,
            self.in_plane,
            self.slope,
        ]
        .into_iter()
        .fold(0.0, f64::max)
    }
}

/// Measure `mesh` against `heights`, `normal` and `alpha_deg` without using how
/// it was made.
pub fn check(mesh: &DevelopableMesh, heights: &[f64], normal: DVec3, alpha_deg: f64) -> Worst {
    let g = &mesh.grid;
    let n = normal.normalize();
    let size = g.bbox_diagonal();
    let mut w = Worst::default();
    assert_eq!(g.cols, heights.len());
    assert_eq!(g.rows, mesh.helix.len() - 1);
    let line = |i: usize| (g.vertex(i, 0), g.vertex(i, g.cols - 1) - g.vertex(i, 0));
    for i in 0..g.rows - 1 {
        let (p, d) = line(i);
        let (q, e) = line(i + 1);
        let o = meet(p, d, q, e);
        for j in 0..g.cols - 1 {
            let [a, b, c, dd] = g.face(i, j);
            // Face corners: A = (i, j), B = (i+1, j), C = (i+1, j+1), D = (i, j+1):
            // A, D on row i; B, C on row i + 1; the bases AB and DC lie in the cutting planes.
            w.apex = w
                .apex
                .max(((a - o).length() - (b - o).length()).abs() / size)
                .max(((dd - o).length() - (c - o).length()).abs() / size);
            w.isosceles = w
                .isosceles
                .max(((dd - a).length() - (c - b).length()).abs() / size)
                .max(((c - a).length() - (dd - b).length()).abs() / size);
            let (ab, dc) = ((b - a) / size, (c - dd) / size);
            w.bases = w
                .bases
                .max(ab.cross(dc).length() / (ab.length() * dc.length()));
        }
    }
    let m = measure(g);
    w.measured = [
        m.face_planarity.value,
        m.circularity.value,
        m.row_planarity.value,
        m.column_planarity.value,
    ]
    .into_iter()
    .fold(0.0, f64::max);
    w.axes = m.torsion.unwrap().value.max(m.normal_length.unwrap().value);
    for (j, &h) in heights.iter().enumerate() {
        for x in g.column(j) {
            w.in_plane = w.in_plane.max((x.dot(n) - h).abs() / size);
        }
    }
    for s in mesh.helix.windows(2) {
        let d = s[1] - s[0];
        let angle = d.dot(n).atan2((d - d.dot(n) * n).length());
        w.slope = w.slope.max((angle - alpha_deg.to_radians()).abs());
    }
    w
}

/// The points of `f` at `k` values from `t0` to `t1`, ends included.
pub fn curve(k: usize, t0: f64, t1: f64, f: impl Fn(f64) -> Xyz) -> Vec<Xyz> {
    (0..k)
        .map(|i| f(t0 + (t1 - t0) * i as f64 / (k - 1) as f64))
        .collect()
}

pub fn generate_checked(spec: &DevelopableSpec, alpha_deg: f64) -> (DevelopableMesh, Worst) {
    let mesh = developable(spec, &GenerateOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    let w = check(
        &mesh,
        &spec.heights,
        DVec3::from_array(spec.reference_normal),
        alpha_deg,
    );
    assert!(w.max() <= TOL, "{w:?}");
    (mesh, w)
}

pub fn square() -> Vec<Xyz> {
    vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
    ]
}
