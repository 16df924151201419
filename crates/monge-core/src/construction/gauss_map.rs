//! The discrete Gauss map of a surface with planar curvature lines
//! (§2.1.2, §2.2.1, §3.1, §3.2).
//!
//! Conventions (they fix the meaning of θ, see the README):
//! - `t_u`, `t_v` are the unit start tangents of guide_u and guide_v, and
//!   `N_p = t_u × t_v / |t_u × t_v|` is the normal at the common start point.
//! - Along guide_u the normals stay at a constant angle to its plane (unit normal
//!   `n_u`), so they lie on the circle `C_u = S² ∩ {N · n_u = c_u}`, `c_u = N_p · n_u`
//!   (the paper's C1); likewise `C_v` (C2). `c_u = c_v = 0` is the characteristic
//!   case of §3.1, anything else the arbitrary case of §3.2.
//! - The v-lines of the Gauss map (fixed `i`) are the circles of the pencil of
//!   planes through the axis `L1`: it passes through the apex `A1 = (n_u : c_u)` of
//!   the cone tangent to S² along `C_u` and lies in the plane of `C_v`, at distance
//!   `|a| = |tan(θ/2)|` from the centre. The u-lines (fixed `j`) are the circles of
//!   the pencil through its polar reciprocal `L2`.
//! - Sign: positive θ tilts `L1` from the line `A1 Q2` (`Q2` the centre of `C_v`)
//!   towards `N_p`. In the characteristic case `L1 = {tan(θ/2)·N_p + s·t_v}` and
//!   `L2 = {cot(θ/2)·N_p + s·t_u}`; θ = 0 makes guide_u the rail of a moulding
//!   surface, θ = +90° puts both axes tangent to S² at `N_p` (singular).

use glam::DVec3;

use crate::coords::Coords;
use crate::projective::{HPoint, Line};

/// Round-off allowed when testing whether θ is admissible.
const ADMISSIBLE_SLACK: f64 = 1e-12;

/// Normals along a guide polyline, propagated without torsion from `start` (§3.2).
///
/// Each normal is the previous one reflected in the plane orthogonal to the edge
/// between them (a discrete rotation-minimising frame), so every guide edge is
/// parallel to the difference of its end normals: the guide is a Combescure
/// transform of its Gauss image. The normals keep their angle with the plane of a
/// planar guide, so they lie on one circle of S².
///
/// ```
/// use glam::DVec3;
/// use monge_core::gauss_map::guide_normals;
/// let pts = [DVec3::ZERO, DVec3::new(1.0, 0.0, 0.1), DVec3::new(2.0, 0.0, 0.4)];
/// let n = guide_normals(&pts, DVec3::Z);
/// let e = pts[1] - pts[0];
/// assert!((n[1] - n[0]).cross(e).length() < 1e-15);
/// assert!((n[2].length() - 1.0).abs() < 1e-15);
/// ```
pub fn guide_normals(points: &[DVec3], start: DVec3) -> Vec<DVec3> {
    let mut normals = Vec::with_capacity(points.len());
    let mut n = start;
    normals.push(n);
    for w in points.windows(2) {
        let e = w[1] - w[0];
        n -= 2.0 * n.dot(e) / e.length_squared() * e;
        normals.push(n);
    }
    normals
}

/// The frame at the common start point of the two guides (§3.2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StartFrame {
    /// Unit start tangent of guide_u.
    pub t_u: DVec3,
    /// Unit start tangent of guide_v.
    pub t_v: DVec3,
    /// Unit normal `N_p = t_u × t_v / |t_u × t_v|`.
    pub n_p: DVec3,
    /// Unit normal of guide_u's plane.
    pub n_u: DVec3,
    /// Unit normal of guide_v's plane.
    pub n_v: DVec3,
}

impl StartFrame {
    /// The frame from the start tangents and the guide planes' normals (§3.2).
    pub fn new(t_u: DVec3, t_v: DVec3, n_u: DVec3, n_v: DVec3) -> Self {
        StartFrame {
            t_u,
            t_v,
            n_p: t_u.cross(t_v).normalize(),
            n_u,
            n_v,
        }
    }

    /// `c_u = N_p · n_u`: the normals along guide_u lie on `S² ∩ {N · n_u = c_u}` (§3.2).
    pub fn c_u(&self) -> f64 {
        self.n_p.dot(self.n_u)
    }

    /// `c_v = N_p · n_v` (§3.2).
    pub fn c_v(&self) -> f64 {
        self.n_p.dot(self.n_v)
    }

    /// Whether this is the characteristic case of §3.1 (both Gauss circles are
    /// great circles, to round-off).
    pub fn is_characteristic(&self) -> bool {
        self.c_u().abs() <= ADMISSIBLE_SLACK && self.c_v().abs() <= ADMISSIBLE_SLACK
    }

    /// The admissible values of θ (§3.2).
    pub fn admissible_theta(&self) -> ThetaRange {
        ThetaRange::new(self.c_u(), self.c_v())
    }
}

/// The admissible θ of a design: `|θ| ∈ [min_deg, max_deg]`, i.e.
/// `a² = tan²(θ/2)` between `|OQ2|² = c_v²` and `|OA1|² = 1/c_u²` (§3.2).
///
/// ```
/// use monge_core::gauss_map::ThetaRange;
/// let r = ThetaRange::new(0.0, 0.0); // characteristic case: every θ
/// assert!(r.contains(180.0) && r.contains(-90.0) && r.contains(0.0));
/// let r = ThetaRange::new(0.5, 0.2);
/// assert!(!r.contains(0.0) && r.contains(45.0) && r.contains(-45.0));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ThetaRange {
    /// Smallest admissible |θ| in degrees, `2·atan|c_v|`.
    pub min_deg: f64,
    /// Largest admissible |θ| in degrees, `180 − 2·atan|c_u|`.
    pub max_deg: f64,
}

impl ThetaRange {
    /// The range for the Gauss circles `{N · n_u = c_u}` and `{N · n_v = c_v}` (§3.2).
    pub fn new(c_u: f64, c_v: f64) -> Self {
        ThetaRange {
            min_deg: 2.0 * libm::atan(c_v.abs()).to_degrees(),
            max_deg: 180.0 - 2.0 * libm::atan(c_u.abs()).to_degrees(),
        }
    }

    /// Whether θ (degrees, any value; taken modulo 360) is admissible.
    pub fn contains(&self, theta_deg: f64) -> bool {
        let t = normalize_theta_deg(theta_deg).abs();
        t >= self.min_deg - 1e-9 && t <= self.max_deg + 1e-9
    }
}

/// The admissible θ (degrees) at the angle `phi_deg` around the circle of admissible
/// values (§3.2): θ and −θ at either end of the range give the same axes (`E = 0`: `M =
/// Q2`; `D = 0`: `M` at infinity), so the admissible θ form a circle, and along it
/// `√E = √E_max·|sin(φ/2)|`, `√D = √a·|cos(φ/2)|` (`a = 1/(1 + c_v²)`, `E_max = a/(a +
/// δ²)`): the axes of [`pencil_axes`] turn smoothly with φ, across both ends, where they
/// turn as the square root of θ's distance to the end. φ (taken modulo 360°, in
/// (−180°, 180°]) = 0 gives `min_deg`, 180° `max_deg`, −φ gives −θ; in the
/// characteristic case (`c_u = c_v = 0`) θ = φ.
///
/// ```
/// use monge_core::gauss_map::{admissible_theta_at, ThetaRange};
/// assert!((admissible_theta_at(0.0, 0.0, 37.0) - 37.0).abs() < 1e-12);
/// let r = ThetaRange::new(0.5, 0.2);
/// assert!((admissible_theta_at(0.5, 0.2, 0.0) - r.min_deg).abs() < 1e-9);
/// assert!((admissible_theta_at(0.5, 0.2, 180.0) - r.max_deg).abs() < 1e-9);
/// ```
pub fn admissible_theta_at(c_u: f64, c_v: f64, phi_deg: f64) -> f64 {
    let phi = normalize_theta_deg(phi_deg).to_radians();
    let a = 1.0 / (1.0 + c_v * c_v);
    let delta2 = c_u * c_u / (1.0 - c_u * c_u * c_v * c_v);
    let e = a / (a + delta2) * libm::sin(0.5 * phi).powi(2);
    // E = S² − c_v²C² = S²(1 + c_v²) − c_v².
    let s2 = ((e + c_v * c_v) * a).clamp(0.0, 1.0);
    phi.signum() * 2.0 * libm::asin(s2.sqrt()).to_degrees()
}

/// θ in degrees reduced to (−180, 180] (§2.1.2: θ and θ ± 360° are the same).
///
/// ```
/// use monge_core::gauss_map::normalize_theta_deg;
/// assert_eq!(normalize_theta_deg(-180.0), 180.0);
/// assert_eq!(normalize_theta_deg(370.0), 10.0);
/// ```
pub fn normalize_theta_deg(theta_deg: f64) -> f64 {
    let t = theta_deg.rem_euclid(360.0);
    if t > 180.0 {
        t - 360.0
    } else {
        t
    }
}

/// The two polar reciprocal axes of the pencils of planes of the Gauss map (§2.1.2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PencilAxes {
    /// Axis of the pencil whose circles are the v-lines (fixed `i`); it lies in
    /// the plane of `C_v` and passes through the apex of the cone tangent along `C_u`.
    pub l1: Line,
    /// Its polar reciprocal: the axis of the u-lines (fixed `j`).
    pub l2: Line,
}

/// θ is outside the admissible range of the design (§3.2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Inadmissible {
    /// θ in degrees, reduced to (−180, 180].
    pub theta_deg: f64,
    /// The admissible range.
    pub range: ThetaRange,
}

/// The pencil axes for θ (degrees) (§2.1.2, §3.2).
///
/// Formulated projectively, with `S = sin(θ/2)`, `C = cos(θ/2)`, `δ² = c_u²/(1 − c_u²c_v²)`,
/// `E = S² − c_v²C²`, `D = C² − δ²E` (admissible iff `E ≥ 0` and `D ≥ 0`): `L1` joins
/// `A1 = (n_u : c_u)` and `M = (√D·Q2 + sign(θ)·√E·v : √D)`, where `Q2 = c_v·n_v` and `v`
/// is the unit vector of the plane of `C_v` orthogonal to `A1Q2`, towards `N_p`; `L2` is
/// its polar. Axes at infinity (θ = ±180°, great circles) are ordinary values.
///
/// ```
/// use glam::DVec3;
/// use monge_core::gauss_map::{pencil_axes, StartFrame};
/// // Characteristic frame: t_u = x, t_v = y, N_p = z; guide_u in the plane y = 0.
/// let f = StartFrame::new(DVec3::X, DVec3::Y, DVec3::Y, DVec3::X);
/// let axes = pencil_axes(&f, 60.0).unwrap();
/// let a = (30.0f64).to_radians().tan();
/// assert!((axes.l1.distance_to_origin() - a).abs() < 1e-15);
/// assert!((axes.l2.distance_to_origin() - 1.0 / a).abs() < 1e-14);
/// ```
pub fn pencil_axes(frame: &StartFrame, theta_deg: f64) -> Result<PencilAxes, Inadmissible> {
    let theta_deg = normalize_theta_deg(theta_deg);
    let (c_u, c_v) = (frame.c_u(), frame.c_v());
    let half = theta_deg.to_radians() / 2.0;
    let (s, c) = (libm::sin(half), libm::cos(half));
    let delta2 = c_u * c_u / (1.0 - c_u * c_u * c_v * c_v);
    let e = s * s - c_v * c_v * c * c;
    let d = c * c - delta2 * e;
    if e < -ADMISSIBLE_SLACK || d < -ADMISSIBLE_SLACK {
        return Err(Inadmissible {
            theta_deg,
            range: ThetaRange::new(c_u, c_v),
        });
    }
    let (sqrt_e, sqrt_d) = (e.max(0.0).sqrt(), d.max(0.0).sqrt());
    let q2 = c_v * frame.n_v;
    // Direction of A1 → Q2 (up to sign), defined when A1 is at infinity too.
    let toward_q2 = c_u * q2 - frame.n_u;
    let mut v = frame.n_v.cross(toward_q2).normalize();
    if v.dot(frame.n_p - q2) < 0.0 {
        v = -v;
    }
    let apex = HPoint::new(frame.n_u, c_u);
    let m = HPoint::new(sqrt_d * q2 + s.signum() * sqrt_e * v, sqrt_d);
    let l1 = Line::join(apex, m);
    Ok(PencilAxes { l1, l2: l1.polar() })
}

/// The discrete Gauss map: a circular mesh on S² with planar lines (§2.2.1).
#[derive(Clone, Debug, PartialEq)]
pub struct GaussMap {
    /// Number of rows (samples of guide_u).
    pub rows: usize,
    /// Number of columns (samples of guide_v).
    pub cols: usize,
    /// Unit normals, row-major (`(i, j)` at `i * cols + j`).
    pub normals: Vec<DVec3>,
}

/// The Gauss map spanned by the normals along the two guides (§2.2.1, §3.1 iii).
///
/// `along_u[i]` and `along_v[j]` are the normals along guide_u and guide_v
/// (`along_u[0] == along_v[0] == N_p`). Vertex `(i, j)` is the point of
/// `S² ∩ plane(L1, along_u[i]) ∩ plane(L2, along_v[j])` that is concyclic with
/// `N_p`, `along_u[i]` and `along_v[j]` (Proposition 1: any two circles of each
/// family meet in four concyclic points). That makes it the intersection of three
/// planes: a closed form with no choice of sphere intersection, so no branch can
/// be jumped, and no special case for axes at infinity or tangent to S².
///
/// ```
/// use glam::DVec3;
/// use monge_core::gauss_map::{gauss_map, pencil_axes, StartFrame};
/// let f = StartFrame::new(DVec3::X, DVec3::Y, DVec3::Y, DVec3::X);
/// let axes = pencil_axes(&f, 0.0).unwrap(); // θ = 0: parallels and meridians
/// let (a, b) = (0.3f64, 0.2f64);
/// let nu = [DVec3::Z, DVec3::new(a.sin(), 0.0, a.cos())];
/// let nv = [DVec3::Z, DVec3::new(0.0, b.sin(), b.cos())];
/// let g = gauss_map(&axes, &nu, &nv);
/// let expected = DVec3::new(b.cos() * a.sin(), b.sin(), b.cos() * a.cos());
/// assert!(g.normals[3].abs_diff_eq(expected, 1e-15));
/// ```
pub fn gauss_map(axes: &PencilAxes, along_u: &[DVec3], along_v: &[DVec3]) -> GaussMap {
    let gauss = GaussRows::new(axes, along_u, along_v);
    let (rows, cols) = (along_u.len(), along_v.len());
    let mut normals = Vec::with_capacity(rows * cols);
    let mut row = Coords::zeros(cols);
    for i in 0..rows {
        gauss.row_into(i, 0..cols, &mut row);
        normals.extend((0..cols).map(|j| row.get(j)));
    }
    GaussMap {
        rows,
        cols,
        normals,
    }
}

/// The pencil planes of the Gauss map's rows and columns (§2.2.1), from which
/// [`gauss_map`] computes every vertex and [`crate::combescure::combescure`]
/// the mesh, row after row (the columns of a row in SIMD lanes).
#[derive(Clone, Debug)]
pub struct GaussRows<'a> {
    along_u: &'a [DVec3],
    along_v: &'a [DVec3],
    /// Per row: the plane through L1 and N_i0, as `n1 · (Y − N00) = e1`, with `u = N_i0 − N00`.
    row_planes: Vec<(DVec3, DVec3, f64)>,
    /// Per column: the plane through L2 and N_0j, likewise, coordinate by
    /// coordinate: normals `n2`, `w = N_0j − N00`, offsets `e2`.
    col_n2: Coords,
    col_w: Coords,
    col_e2: Vec<f64>,
}

impl<'a> GaussRows<'a> {
    /// The pencil planes of every row and column (§2.2.1, §3.1 iii).
    pub fn new(axes: &PencilAxes, along_u: &'a [DVec3], along_v: &'a [DVec3]) -> Self {
        let n00 = along_u[0];
        let col_planes: Vec<_> = along_v
            .iter()
            .map(|&nj| offset_plane(&axes.l2, nj, n00))
            .collect();
        GaussRows {
            along_u,
            along_v,
            row_planes: along_u
                .iter()
                .map(|&ni| offset_plane(&axes.l1, ni, n00))
                .collect(),
            col_n2: Coords::from_points(col_planes.iter().map(|p| p.0)),
            col_w: Coords::from_points(col_planes.iter().map(|p| p.1)),
            col_e2: col_planes.iter().map(|p| p.2).collect(),
        }
    }

    /// Unit normal of the pencil plane of row `i` (§2.2.1): by Combescure
    /// parallelism (Joachimsthal) the mesh's row `i` lies in a plane with this
    /// normal too.
    pub fn row_normal(&self, i: usize) -> DVec3 {
        self.row_planes[i].0
    }

    /// Unit normal of the pencil plane of column `j` (§2.2.1): by Combescure
    /// parallelism (Joachimsthal) the mesh's column `j` lies in a plane with this
    /// normal too.
    pub fn column_normal(&self, j: usize) -> DVec3 {
        self.col_n2.get(j)
    }

    /// The Gauss vertices `(i, j)` of row `i`, `j` in `cols`, into `out[j − cols.start]`
    /// (§2.2.1, §3.1 iii): the intersection of the row's pencil plane, the
    /// column's, and the plane through `N00`, `N_i0` and `N_0j` (Proposition 1),
    /// in closed form; guide_u's and guide_v's normals themselves in column and
    /// row 0. The columns are independent: the loop runs in SIMD lanes.
    #[inline(always)]
    pub(crate) fn row_into(&self, i: usize, cols: std::ops::Range<usize>, out: &mut Coords) {
        if i == 0 {
            for (k, j) in cols.enumerate() {
                out.set(k, self.along_v[j]);
            }
            return;
        }
        let (n1, u, e1) = self.row_planes[i];
        let n00 = self.along_u[0];
        let m = cols.len();
        let n2s = self.col_n2.view(cols.end);
        let ws = self.col_w.view(cols.end);
        let e2s = &self.col_e2[..cols.end];
        let mut out = out.view_mut(m);
        for (k, j) in cols.clone().enumerate() {
            let (n2, w, e2) = (n2s.get(j), ws.get(j), e2s[j]);
            let alpha = n1.dot(w);
            let beta = n2.dot(u);
            let inv_det = 1.0 / (e1 * e2 - alpha * beta);
            let n = n00 + u * (e2 * (e1 - alpha) * inv_det) + w * (e1 * (e2 - beta) * inv_det);
            // n is on S² up to round-off: one Newton step makes it unit to round-off.
            out.set(k, n * (1.5 - 0.5 * n.dot(n)));
        }
        if cols.start == 0 {
            out.set(0, self.along_u[i]);
        }
    }
}

/// The plane through `axis` and `n`, written relative to `origin`:
/// returns `(unit normal, n − origin, offset)` with `normal · (Y − origin) = offset`.
fn offset_plane(axis: &Line, n: DVec3, origin: DVec3) -> (DVec3, DVec3, f64) {
    let normal = axis.plane_through(n).normal.normalize_or_zero();
    let d = n - origin;
    (normal, d, normal.dot(d))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn characteristic() -> StartFrame {
        StartFrame::new(DVec3::X, DVec3::Y, DVec3::Y, DVec3::X)
    }

    #[test]
    fn characteristic_axes_follow_the_contract() {
        let f = characteristic();
        for theta in [-170.0, -90.0, -30.0, 10.0, 45.0, 120.0] {
            let axes = pencil_axes(&f, theta).unwrap();
            let a = (theta / 2.0).to_radians().tan();
            // L1 = {a N_p + s t_v}: contains a·N_p, direction t_v.
            let l1 = axes.l1;
            assert!(l1.dir.normalize().cross(DVec3::Y).length() < 1e-14);
            let p = l1.dir.cross(l1.moment) / l1.dir.length_squared();
            assert!(p.abs_diff_eq(a * DVec3::Z, 1e-12), "{theta}: {p}");
            let l2 = axes.l2;
            let q = l2.dir.cross(l2.moment) / l2.dir.length_squared();
            assert!(q.abs_diff_eq(DVec3::Z / a, 1e-11 * (1.0 + 1.0 / a.abs())));
            assert!(l2.dir.normalize().cross(DVec3::X).length() < 1e-14);
        }
        // θ = 180°: L1 at infinity, L2 = the t_u axis through the centre.
        let axes = pencil_axes(&f, 180.0).unwrap();
        assert!(axes.l1.distance_to_origin() > 1e15);
        assert!(axes.l2.distance_to_origin() < 1e-15);
    }

    #[test]
    fn admissible_range_of_the_arbitrary_case() {
        // Guide planes at 60° to each other: c_u = N_p·n_u ≠ 0.
        let t_u = DVec3::X;
        let t_v = DVec3::Y;
        let n_u = DVec3::new(0.0, 0.8, 0.6); // guide_u plane contains x
        let n_v = DVec3::new(1.0, 0.0, 0.0);
        let f = StartFrame::new(t_u, t_v, n_u, n_v);
        assert!((f.c_u() - 0.6).abs() < 1e-15);
        let r = f.admissible_theta();
        assert!((r.max_deg - (180.0 - 2.0 * 0.6f64.atan().to_degrees())).abs() < 1e-12);
        assert_eq!(r.min_deg, 0.0);
        assert!(pencil_axes(&f, 170.0).is_err());
        assert!(pencil_axes(&f, -170.0).is_err());
        for theta in [-r.max_deg, -100.0, -10.0, 0.0, 30.0, 90.0, r.max_deg] {
            let axes = pencil_axes(&f, theta).unwrap();
            // L1 at distance |tan θ/2|, through A1 = n_u / c_u, in the plane of C_v.
            let a = (theta / 2.0).to_radians().tan().abs();
            assert!((axes.l1.distance_to_origin() - a).abs() < 1e-9, "{theta}");
            let a1 = n_u / f.c_u();
            assert!(
                axes.l1.plane_through(a1).normal.length() < 1e-12 * axes.l1.dir.length().max(1.0)
            );
            assert!(axes.l1.dir.dot(n_v).abs() < 1e-12 * axes.l1.dir.length());
        }
    }

    fn arc_normals(plane_normal: DVec3, c: f64, start: DVec3, angles: &[f64]) -> Vec<DVec3> {
        // Points of S² ∩ {N·n = c} starting at `start`, by rotation about n.
        angles
            .iter()
            .map(|&t| {
                let q = c * plane_normal;
                let r = start - q;
                q + r * t.cos() + plane_normal.cross(r) * t.sin()
            })
            .collect()
    }

    /// Independent check: every Gauss vertex on S², rows on planes through L1,
    /// columns on planes through L2, faces concyclic.
    fn check_gauss(f: &StartFrame, theta: f64, steps_u: &[f64], steps_v: &[f64]) -> f64 {
        let axes = pencil_axes(f, theta).unwrap();
        let nu = arc_normals(f.n_u, f.c_u(), f.n_p, steps_u);
        let nv = arc_normals(f.n_v, f.c_v(), f.n_p, steps_v);
        let g = gauss_map(&axes, &nu, &nv);
        let mut worst: f64 = 0.0;
        for (i, ni) in nu.iter().enumerate() {
            let pl = axes.l1.plane_through(*ni);
            for (j, nj) in nv.iter().enumerate() {
                let n = g.normals[i * g.cols + j];
                worst = worst.max((n.length() - 1.0).abs());
                worst = worst.max(pl.signed_distance(n).abs());
                worst = worst.max(axes.l2.plane_through(*nj).signed_distance(n).abs());
            }
        }
        for i in 0..g.rows - 1 {
            for j in 0..g.cols - 1 {
                let p = |a: usize, b: usize| g.normals[(i + a) * g.cols + j + b];
                let (a, b, c, d) = (p(0, 0), p(1, 0), p(1, 1), p(0, 1));
                // Four points of S² are concyclic iff coplanar.
                let vol = (b - a).cross(c - a).dot(d - a);
                let size = (c - a).length() * (d - b).length();
                worst = worst.max(vol.abs() / size / (b - a).length().max((d - a).length()));
            }
        }
        worst
    }

    #[test]
    fn gauss_map_is_circular_with_planar_lines_for_all_theta() {
        let f = characteristic();
        let su: Vec<f64> = (0..12).map(|k| k as f64 * 0.11).collect();
        let sv: Vec<f64> = (0..9).map(|k| -(k as f64) * 0.13).collect();
        for k in 0..72 {
            let theta = -177.5 + 5.0 * k as f64;
            if (theta - 90.0).abs() < 3.0 {
                continue;
            }
            let w = check_gauss(&f, theta, &su, &sv);
            assert!(w < 1e-12, "theta {theta}: {w}");
        }
        for theta in [180.0, 0.0, -90.0] {
            assert!(check_gauss(&f, theta, &su, &sv) < 1e-12);
        }
        // Arbitrary case.
        let f = StartFrame::new(
            DVec3::X,
            DVec3::Y,
            DVec3::new(0.0, 0.8, 0.6),
            DVec3::new(0.96, 0.0, -0.28),
        );
        let r = f.admissible_theta();
        for k in 0..=20 {
            let theta = r.min_deg + (r.max_deg - r.min_deg) * k as f64 / 20.0;
            for t in [theta, -theta] {
                if (t - 90.0).abs() < 3.0 {
                    continue;
                }
                let w = check_gauss(&f, t, &su, &sv);
                assert!(w < 1e-12, "theta {t}: {w}");
            }
        }
    }

    #[test]
    fn theta_sweep_has_no_jump() {
        // The Gauss map must vary continuously with θ over the whole circle
        // (except at the singular θ = +90°, near which it contracts fast).
        let f = characteristic();
        let su: Vec<f64> = (0..40).map(|k| k as f64 * 0.05).collect();
        let sv: Vec<f64> = (0..40).map(|k| k as f64 * 0.05).collect();
        let nu = arc_normals(f.n_u, 0.0, f.n_p, &su);
        let nv = arc_normals(f.n_v, 0.0, f.n_p, &sv);
        let at = |t: f64| gauss_map(&pencil_axes(&f, t).unwrap(), &nu, &nv).normals;
        let mut prev = at(-180.0 + 0.25);
        let mut t: f64 = -180.0 + 0.5;
        while t <= 180.0 {
            if (t - 90.0).abs() > 6.0 && (t - 0.25 - 90.0).abs() > 6.0 {
                let cur = at(t);
                let jump = prev
                    .iter()
                    .zip(&cur)
                    .map(|(a, b)| (*a - *b).length())
                    .fold(0.0, f64::max);
                assert!(jump < 0.05, "jump {jump} at theta {t}");
                prev = cur;
            } else {
                prev = at(t);
            }
            t += 0.25;
        }
        // Closer to 90°, it is still continuous: halving the step halves the change.
        for t0 in [84.0, 89.0, 91.0, 95.0] {
            let change = |h: f64| {
                at(t0)
                    .iter()
                    .zip(&at(t0 + h))
                    .map(|(a, b)| (*a - *b).length())
                    .fold(0.0, f64::max)
            };
            let (big, small) = (change(1e-3), change(5e-4));
            assert!((big / small - 2.0).abs() < 0.05, "{t0}: {big} {small}");
        }
        // θ = 180° and θ = −180° are the same design.
        assert_eq!(at(180.0), at(-180.0));
    }

    #[test]
    fn guide_normals_keep_their_angle_with_the_plane() {
        let pts: Vec<DVec3> = (0..50)
            .map(|k| {
                let t = k as f64 * 0.1;
                DVec3::new(t, 0.0, 0.3 * t * t - 0.05 * t * t * t)
            })
            .collect();
        let start = DVec3::new(0.0, 0.6, 0.8);
        let n = guide_normals(&pts, start);
        for (k, nk) in n.iter().enumerate() {
            assert!((nk.y - 0.6).abs() < 1e-14, "{k}");
            assert!((nk.length() - 1.0).abs() < 1e-14);
        }
        for k in 0..pts.len() - 1 {
            let e = (pts[k + 1] - pts[k]).normalize();
            assert!((n[k + 1] - n[k]).cross(e).length() < 1e-14);
        }
    }

    #[test]
    fn the_admissible_thetas_are_a_circle_the_axes_follow_smoothly() {
        // A frame whose guide planes are tilted (c_u = 0.5, c_v = 0.2): every φ gives an
        // admissible θ, the ends of the range at 0° and ±180°, and the axes' point M on
        // L1 (as an affine point, or a direction at infinity) moves smoothly with φ,
        // across both ends: second differences of the order of the step squared.
        let n_u = DVec3::new(0.0, -(1.0f64 - 0.25).sqrt(), 0.5);
        let n_v = DVec3::new(-(1.0f64 - 0.04).sqrt(), 0.0, 0.2);
        let f = StartFrame::new(DVec3::X, DVec3::Y, n_u, n_v);
        let (c_u, c_v) = (f.c_u(), f.c_v());
        let range = f.admissible_theta();
        let theta = |phi: f64| admissible_theta_at(c_u, c_v, phi);
        assert!((theta(0.0) - range.min_deg).abs() < 1e-9);
        assert!((theta(180.0) - range.max_deg).abs() < 1e-9);
        assert!((theta(-90.0) + theta(90.0)).abs() < 1e-12);
        // L1's Plücker coordinates, unit, their sign that of the middle sample's.
        let line = |phi: f64| {
            let l1 = pencil_axes(&f, theta(phi)).unwrap().l1;
            let v = [
                l1.dir.x,
                l1.dir.y,
                l1.dir.z,
                l1.moment.x,
                l1.moment.y,
                l1.moment.z,
            ];
            let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
            v.map(|x| x / norm)
        };
        let h = 0.01;
        for phi in [0.0, 45.0, 179.99, -120.0] {
            let b = line(phi);
            let [a, c] = [line(phi - h), line(phi + h)].map(|x| {
                let sign = x.iter().zip(&b).map(|(x, b)| x * b).sum::<f64>().signum();
                x.map(|x| sign * x)
            });
            let second = (0..6)
                .map(|k| (a[k] - 2.0 * b[k] + c[k]).abs())
                .fold(0.0, f64::max);
            // Smooth: of the order of (h in radians)², 3e-8; θ itself as the
            // parameter would leave √h, 1e-2, at φ = 0.
            assert!(second < 1e-6, "φ {phi}: {second:e}");
        }
    }

    #[test]
    fn normalize_theta() {
        assert_eq!(normalize_theta_deg(180.0), 180.0);
        assert_eq!(normalize_theta_deg(-190.0), 170.0);
        assert_eq!(normalize_theta_deg(0.0), 0.0);
    }
}
