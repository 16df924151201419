//! The initial guesses of an approximation (§4.7, monge's extension, step 1): corner,
//! principal frame and guides fitted to the target's sections at each corner, and
//! the start along the target's own boundary, its curves leaving a corner traced
//! through the target's points, and the start on the whole target's quadric.

use glam::DVec3;

use super::error::{ApproxError, MIN_POINTS};
use super::fit_guide::{fit_guide, section_guide, Parameters};
use super::index::TargetCloud;
use super::quadric::{
    check_curvature, plan_sides, principal_axes, principal_axes_about, Principal, Quadric,
};

/// The initial guess: corner, frame and each guide's control points in its plane.
#[derive(Clone, Debug)]
pub(super) struct Start {
    pub(super) corner: DVec3,
    /// guide_u's start tangent, guide_v's, and their normal.
    pub(super) frame: [DVec3; 3],
    /// Per guide: the second control point's distance along the tangent, then
    /// `(along, up)` of each later control point.
    pub(super) guides: [Vec<f64>; 2],
    /// Tilt of each guide's plane about its start tangent (see [`design_of`](super::design_of)).
    pub(super) tilts: [f64; 2],
    /// Whether the guides are the target's own boundary curves ([`boundary_start`]).
    pub(super) on_boundary: bool,
    /// Whether it is a boundary start traced along the chord of several steps, tried
    /// only at a corner whose boundary starts fold at every θ ([`TRACE_CHORD`]).
    pub(super) retraced: bool,
    pub(super) curvatures: (f64, f64),
    /// Which of the target's four corners it starts from (0 to 3): the scan's choice
    /// of starts takes the best of each corner first.
    pub(super) at_corner: usize,
}

/// The starts of the least squares from the θ scan (objective, start, φ), `wanted` of
/// them: the best φ of each corner first (whichever of the corner's starts it is: they
/// compete for its place), then the best φ of each other start, then further φ, each at
/// least 15° from its start's others. Taking the best of each start first let two
/// corners' curvature-line starts (the best of the scan) push the other two corners
/// out, and with them the least squares that came nearest to the held-out hyperbolic
/// paraboloid.
pub(super) fn choose_starts(
    mut scan: Vec<(f64, usize, f64)>,
    corners: &[usize],
    wanted: usize,
) -> Vec<(usize, f64)> {
    scan.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut chosen: Vec<(usize, f64)> = Vec::new();
    // Pass 0: a corner not chosen yet; 1: a start not chosen yet; 2: φ apart.
    let allowed = |pass: usize, chosen: &[(usize, f64)], g: usize, phi: f64| {
        chosen.iter().all(|(h, t)| match pass {
            0 => corners[*h] != corners[g],
            1 => *h != g,
            _ => *h != g || (t - phi).abs() > 15.0,
        })
    };
    for pass in 0..3 {
        for (_, g, phi) in &scan {
            if chosen.len() < wanted && allowed(pass, &chosen, *g, *phi) {
                chosen.push((*g, *phi));
            }
        }
    }
    chosen
}

/// Corner, principal frame and guides fitted to the target's sections (step 1), at
/// each of the target's four corners along the principal directions at its centre;
/// there too the start along its boundary ([`boundary_start`]) and on its quadric
/// ([`quadric_start`]).
pub(super) fn initial_guesses(target: &TargetCloud) -> Result<Vec<Start>, ApproxError> {
    let points = &target.points;
    let size = target.size;
    let centroid = points.iter().copied().sum::<DVec3>() / points.len() as f64;
    let global = Quadric::fit(points, centroid, principal_axes(points).2);
    let (u, v) = global.uv(centroid);
    let centre = global.principal(u, v);
    // The directions along which the corners are sought: the principal directions at
    // the centre, or, where it is umbilic (a dome of revolution, a spherical cap), the
    // sides of the target's plan.
    let (c1, c2) = match check_curvature(&centre, size, "the centre") {
        Ok(()) => (centre.d1, centre.d2),
        Err(ApproxError::Umbilic { .. }) => plan_sides(points, centre.normal),
        Err(e) => return Err(e),
    };
    let mut starts = Vec::with_capacity(12);
    let mut refused = None;
    let signs = [(1.0, 1.0), (-1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)];
    for (at_corner, (s1, s2)) in signs.into_iter().enumerate() {
        let first = starts.len();
        let (d1, d2) = (s1 * c1, s2 * c2);
        // The corner: least coordinates along the principal directions at the centre.
        let low = |d: DVec3| {
            points
                .iter()
                .map(|p| (*p - centre.point).dot(d))
                .fold(f64::INFINITY, f64::min)
        };
        let guess = centre.point + low(d1) * d1 + low(d2) * d2;
        // The whole target's quadric there, along the centre's directions, where the
        // target is a dome or a bowl at its centre (a saddle's corners are its own).
        if centre.k1 * centre.k2 > 0.0 {
            starts.extend(quadric_start(target, &global, guess, d1, d2));
        }
        // The corner's own quadric, from its nearest tenth of the target.
        let count = (points.len() / 10).max(MIN_POINTS);
        let near = target.nearest(guess, count);
        let (cu, cv) = global.uv(guess);
        let local = Quadric::fit(&near, global.principal(cu, cv).point, centre.normal);
        let (lu, lv) = local.uv(guess);
        let corner = local.principal(lu, lv);
        // Where the corner is umbilic, its principal directions are none: the boundary
        // and quadric starts there only.
        match check_curvature(&corner, size, "a corner") {
            Ok(()) => starts.push(corner_start(points, &corner, d1, d2, size)),
            Err(e) => {
                refused.get_or_insert(e);
            }
        }
        // The target's own corner there, and its boundary curves from it.
        starts.extend(boundary_start(target, d1, d2, (corner.k1, corner.k2)));
        // Its curvature lines to that corner, and from it.
        starts.extend(curvature_line_start(
            target,
            centre.point,
            d1,
            d2,
            (corner.k1, corner.k2),
        ));
        for start in &mut starts[first..] {
            start.at_corner = at_corner;
        }
    }
    match refused {
        Some(e) if starts.is_empty() => Err(e),
        _ => Ok(starts),
    }
}

/// The start at a corner of the target from its own quadric there (`corner`, not
/// umbilic): the frame along its principal directions, each turned along the nearer of
/// `d1` and `d2` (into the target), and each guide fitted to the target's section by
/// the normal plane of the other direction.
fn corner_start(points: &[DVec3], corner: &Principal, d1: DVec3, d2: DVec3, size: f64) -> Start {
    // Start tangents pointing into the target: the corner's principal direction
    // nearer each of the centre's, turned along it.
    let (a, b) = if corner.d1.dot(d1).abs() >= corner.d1.dot(d2).abs() {
        (corner.d1, corner.d2)
    } else {
        (corner.d2, corner.d1)
    };
    let t_u = a * a.dot(d1).signum();
    let t_v = b * b.dot(d2).signum();
    let n = t_u.cross(t_v);
    let guide = |t: DVec3, other: DVec3| section_guide(points, corner.point, t, other, n, size);
    Start {
        corner: corner.point,
        frame: [t_u, t_v, n],
        guides: [guide(t_u, t_v), guide(t_v, t_u)],
        tilts: [0.0; 2],
        on_boundary: false,
        retraced: false,
        curvatures: (corner.k1, corner.k2),
        at_corner: 0,
    }
}

/// The start on the quadric fitted to the whole target, at its point nearest to `guess`
/// (a corner of the target): the frame along the principal directions at the target's
/// centre (`d1`, `d2`, turned towards that corner) made tangent there, and each guide
/// the quadric's section by the plane of its tangent and the normal. Where the corners
/// themselves mislead (a dome whose edges lie flat: its corners are saddles, their
/// principal directions along the diagonals, its edges straight), the whole target's
/// shape still gives the arches of a dome along its edges. Only where the centre is
/// elliptic: on a saddle (a hyperbolic paraboloid) these starts lead the search away
/// from better ones. `None` when the quadric has no section there.
fn quadric_start(
    target: &TargetCloud,
    global: &Quadric,
    guess: DVec3,
    d1: DVec3,
    d2: DVec3,
) -> Option<Start> {
    let (u, v) = global.uv(guess);
    let corner = global.principal(u, v);
    let normal = corner.normal;
    let t_u = (d1 - d1.dot(normal) * normal).normalize_or_zero();
    let t_v = normal.cross(t_u) * normal.cross(t_u).dot(d2).signum();
    let n = t_u.cross(t_v);
    if !n.is_normalized() {
        return None;
    }
    let guide = |t: DVec3| -> Option<Vec<f64>> {
        let length = target
            .points
            .iter()
            .map(|p| (*p - corner.point).dot(t))
            .fold(0.0, f64::max);
        // The section: for each step along t, the height along n where the quadric is
        // (Newton's method on the height above it, from the previous step's).
        let (steps, h) = (24, 1e-6 * target.size);
        let mut w = 0.0;
        let mut section = Vec::with_capacity(steps + 1);
        for k in 0..=steps {
            let s = length * k as f64 / steps as f64;
            let at = |w: f64| global.height_above(corner.point + s * t + w * n);
            for _ in 0..8 {
                let (g, slope) = (at(w), (at(w + h) - at(w)) / h);
                w -= g / slope;
            }
            if !w.is_finite() || at(w).abs() > 1e-6 * target.size {
                return None;
            }
            section.push((s, w));
        }
        let p = fit_guide(&section, false, Parameters::Fitted)?;
        let mut guide = vec![p[1].0];
        guide.extend(p[2..].iter().flat_map(|(s, w)| [*s, *w]));
        Some(guide)
    };
    Some(Start {
        corner: corner.point,
        frame: [t_u, t_v, n],
        guides: [guide(t_u)?, guide(t_v)?],
        tilts: [0.0; 2],
        on_boundary: false,
        retraced: false,
        curvatures: (corner.k1, corner.k2),
        at_corner: 0,
    })
}

/// The start along the target's curvature lines at its corner lowest along `d1` and
/// `d2` (the directions at its centre, turned towards that corner): from the target's
/// point nearest to its centre, the curvature line nearest to `−d1` is followed to the
/// boundary, then the other family's, towards `−d2`, to the target's corner; from there
/// the two curvature lines leaving it are the curves of [`curves_start`]. On a target cut along
/// its planar curvature lines (a moulding, a surface of revolution) these are its own
/// guides, their planes tilted as the target's are (a moulding's rail, level, leaves
/// the surface's normal at the slope of its profile), wherever its corners lie.
fn curvature_line_start(
    target: &TargetCloud,
    centre: DVec3,
    d1: DVec3,
    d2: DVec3,
    curvatures: (f64, f64),
) -> Option<Start> {
    let from = DVec3::from_array(*target.tree.nearest_neighbor(centre.to_array())?.geom());
    // Each turn onto the other family: across the direction of arrival, in the tangent
    // plane (the centre's directions may have turned far on a strongly curved target).
    let (to_edge, a1, n1) = follow_curvature_line(target, from, -d1);
    let edge = *to_edge.last()?;
    let across = n1.cross(a1);
    let (to_corner, a2, n2) =
        follow_curvature_line(target, edge, across * across.dot(-d2).signum());
    let corner = *to_corner.last()?;
    let inward = n2.cross(a2);
    let inward = inward * inward.dot(from - corner).signum();
    let (path_u, ..) = follow_curvature_line(target, corner, inward);
    let (path_v, ..) = follow_curvature_line(target, corner, -a2);
    curves_start(
        corner,
        &path_u,
        &path_v,
        curvatures,
        false,
        Parameters::Fitted,
    )
}

/// Target points whose quadric gives the principal directions along a curvature line.
const LINE_NEIGHBOURS: usize = 48;

/// The curvature line of the target through `from` along the principal direction
/// nearest to `along` (Heun's steps of 2.5 mean spacings, each point on the quadric
/// fitted to its [`LINE_NEIGHBOURS`] nearest target points; straight on where the
/// target is umbilic), until the target ends: its points, `from` first, and the
/// direction and the normal at the last. The target ends where the centroid of a
/// point's neighbours lags behind it by 0.3 of their radius (a half disc's lags 0.42).
fn follow_curvature_line(
    target: &TargetCloud,
    from: DVec3,
    along: DVec3,
) -> (Vec<DVec3>, DVec3, DVec3) {
    let step = 2.5 * target.spacing;
    let longest = (4.0 * target.size / step) as usize + 4;
    // The surface point at `p`, the principal direction there nearest to `d` (turned
    // along it), whether the target goes on beyond `p` along `d`, and the normal.
    let at = |p: DVec3, d: DVec3| -> (DVec3, DVec3, bool, DVec3) {
        let near = target.nearest(p, LINE_NEIGHBOURS);
        let count = near.len() as f64;
        let centroid = near.iter().copied().sum::<DVec3>() / count;
        let radius = near.iter().map(|q| q.distance(p)).fold(0.0, f64::max);
        let inside = (centroid - p).dot(d) > -0.3 * radius;
        let normal = principal_axes_about(&near, centroid).2;
        let quadric = Quadric::fit(&near, p, normal);
        let (u, v) = quadric.uv(p);
        let here = quadric.principal(u, v);
        let tangent = |e: DVec3| e - e.dot(here.normal) * here.normal;
        let e = if check_curvature(&here, target.size, "a curvature line").is_err() {
            tangent(d)
        } else if here.d1.dot(d).abs() >= here.d2.dot(d).abs() {
            here.d1
        } else {
            here.d2
        };
        let e = (e * e.dot(d).signum()).normalize_or_zero();
        (here.point, e, inside, here.normal)
    };
    let (mut p, mut d, mut inside, mut normal) = at(from, along);
    let mut path = vec![p];
    while inside && d != DVec3::ZERO && path.len() < longest {
        let (_, ahead, _, _) = at(p + step * d, d);
        let next = p + 0.5 * step * (d + ahead);
        (p, d, inside, normal) = at(next, d + ahead);
        path.push(p);
    }
    (path, d, normal)
}

/// Widest sector of a target's corner (radians): along a side, a boundary point's
/// neighbours fill half a turn, at a right-angled corner a quarter.
const CORNER_SECTOR: f64 = 0.75 * std::f64::consts::PI;

/// Longest inward turn of the boundary between two steps of [`trace_boundary`]
/// (radians): a sharper one is the target's next corner.
const BOUNDARY_TURN: f64 = 0.75;

/// Steps of [`trace_boundary`] whose chord is the direction ahead for the boundary
/// starts traced again ([`Start::retraced`]). Along the last step alone, a random
/// sampling's outermost point well out to one side can turn the path off the boundary:
/// it stops a third of the way along a side, or goes on round the next corner, and the
/// guides fitted to it fold at every θ.
pub(super) const TRACE_CHORD: usize = 3;

/// The start along the target's boundary at its corner lowest along `d1` and `d2` (the
/// principal directions at its centre, turned towards that corner; a corner: a boundary
/// point whose neighbours fill a sector of at most [`CORNER_SECTOR`]): the boundary
/// curves leaving the corner along that sector's edges ([`corner_sides`]), traced
/// through the target's points, give the frame (a
/// plane fitted to each curve through the corner meets the tangent plane in a start
/// tangent) and the guides (a cubic B-spline fitted to each curve in its plane). A
/// target whose boundary is made of curvature lines (one generated by monge, or any
/// patch of a surface with planar curvature lines cut along them) is then started from
/// its own guides. Two starts: the guides fitted with the points' parameters (a mesh's
/// boundary, exactly) and at their chord lengths, with each curve's start tangent from
/// the cubic nearest to it all (a scan's, whose outermost points zigzag; see
/// [`Parameters`]); and the same two of the boundary traced along chords
/// ([`TRACE_CHORD`], [`Start::retraced`]) where that traces it otherwise. None when the
/// boundary cannot be traced (too few points on it).
fn boundary_start(
    target: &TargetCloud,
    d1: DVec3,
    d2: DVec3,
    curvatures: (f64, f64),
) -> Vec<Start> {
    let points = &target.points;
    let diagonal = d1 + d2;
    let step = 2.5 * target.spacing;
    // The corner: of the boundary points whose neighbours fill a sector of at most
    // [`CORNER_SECTOR`], the lowest along the diagonal (the lowest point of all may lie
    // in the middle of a side that bulges out, an onion dome's); else that lowest point.
    let lowest = |i: &usize, j: &usize| {
        points[*i]
            .dot(diagonal)
            .total_cmp(&points[*j].dot(diagonal))
    };
    let sharp = (0..points.len())
        .filter(|&i| target.outward[i] != DVec3::ZERO)
        .filter_map(|i| {
            let (gap, sides) = corner_sides(target, i, 2.5 * step)?;
            (gap >= std::f64::consts::TAU - CORNER_SECTOR).then_some((i, sides))
        })
        .min_by(|a, b| lowest(&a.0, &b.0));
    let (corner_index, [a, b]) = match sharp {
        Some(found) => found,
        None => {
            let sides = (0..points.len())
                .min_by(lowest)
                .and_then(|i| Some((i, corner_sides(target, i, 2.5 * step)?.1)));
            let Some(found) = sides else {
                return Vec::new();
            };
            found
        }
    };
    let corner = points[corner_index];
    // The two sides leave the corner along its sector's edges, guide_u's the one
    // nearer d1: the centre's directions may be far from them where the target turns.
    let (e_u, e_v) = if a.dot(d1).abs() + b.dot(d2).abs() >= b.dot(d1).abs() + a.dot(d2).abs() {
        (a, b)
    } else {
        (b, a)
    };
    let trace = |chord: usize| {
        [
            trace_boundary(target, corner_index, e_u, -e_v, step, chord),
            trace_boundary(target, corner_index, e_v, -e_u, step, chord),
        ]
    };
    let first = trace(1);
    let again = Some(trace(TRACE_CHORD)).filter(|paths| *paths != first);
    std::iter::once((first, false))
        .chain(again.map(|paths| (paths, true)))
        .flat_map(|([path_u, path_v], retraced)| {
            [Parameters::Fitted, Parameters::ChordLength]
                .into_iter()
                .filter_map(move |p| {
                    let start = curves_start(corner, &path_u, &path_v, curvatures, true, p);
                    start.map(|s| Start { retraced, ..s })
                })
        })
        .collect()
}

/// The directions of the two sides of the target leaving its boundary point `at`, in
/// its tangent plane: the edges of the sector its neighbours within `reach` fill (those
/// bounding the widest angle without points) and that angle. `None` with fewer than
/// two neighbours.
fn corner_sides(target: &TargetCloud, at: usize, reach: f64) -> Option<(f64, [DVec3; 2])> {
    let (q, normal) = (target.points[at], target.normals[at]);
    let mut around: Vec<(f64, DVec3)> = target
        .tree
        .locate_within_distance(q.to_array(), reach * reach)
        .filter(|n| n.data != at)
        .map(|n| {
            let v = DVec3::from_array(*n.geom()) - q;
            (v - v.dot(normal) * normal).normalize_or_zero()
        })
        .filter(|e| *e != DVec3::ZERO)
        .map(|e| (0.0, e))
        .collect();
    let x = around.first()?.1;
    let y = normal.cross(x);
    for (angle, e) in &mut around {
        *angle = e.dot(y).atan2(e.dot(x));
    }
    around.sort_by(|a, b| a.0.total_cmp(&b.0));
    let n = around.len();
    if n < 2 {
        return None;
    }
    // The widest gap between neighbours in angle, the last to the first around.
    let gap = |k: usize| (around[(k + 1) % n].0 - around[k].0).rem_euclid(std::f64::consts::TAU);
    let widest = (0..n).max_by(|&i, &j| gap(i).total_cmp(&gap(j)))?;
    Some((gap(widest), [around[widest].1, around[(widest + 1) % n].1]))
}

/// The start whose guides follow two curves of the target leaving `corner` (its
/// boundary curves, or its curvature lines): a plane fitted to each curve through the
/// corner meets the tangent plane in a start tangent, and a cubic B-spline fitted to
/// each curve in the plane through its tangent nearest to the curve's plane is its
/// guide. `None` when a curve has too few points.
fn curves_start(
    corner: DVec3,
    path_u: &[DVec3],
    path_v: &[DVec3],
    curvatures: (f64, f64),
    on_boundary: bool,
    parameters: Parameters,
) -> Option<Start> {
    if path_u.len() < 4 || path_v.len() < 4 {
        return None;
    }
    // Each curve's plane through the corner.
    let (m_u, m_v) = (
        principal_axes_about(path_u, corner).2,
        principal_axes_about(path_v, corner).2,
    );
    // Each curve's own start tangent: at chord lengths (a boundary traced through a
    // scan's outermost points, which zigzag by about a spacing) the slope of the cubic
    // nearest to the whole curve ([`start_slope`]), which their first few points do not
    // turn (with a free-tangent guide's instead, a held-out sine moulding's scan still
    // fell off the target, 7.5e-2 of its size); else a guide fitted in its plane,
    // tangent free.
    let tangent = |m: DVec3, path: &[DVec3]| -> Option<DVec3> {
        let chord = path[path.len() - 1] - corner;
        let e1 = (chord - chord.dot(m) * m).normalize_or_zero();
        let e2 = m.cross(e1);
        let section: Vec<(f64, f64)> = path
            .iter()
            .map(|p| ((*p - corner).dot(e1), (*p - corner).dot(e2)))
            .collect();
        if parameters == Parameters::ChordLength {
            let slope = start_slope(&section)?;
            return Some((e1 + slope * e2).normalize_or_zero());
        }
        let p1 = fit_guide(&section, true, Parameters::Fitted)?[1];
        Some((p1.0 * e1 + p1.1 * e2).normalize_or_zero())
    };
    let (a, b) = (tangent(m_u, path_u)?, tangent(m_v, path_v)?);
    // Orthonormal, symmetric about their bisector: curvature lines meet at 90°.
    let (bisector, half) = ((a + b).normalize_or_zero(), (a - b).normalize_or_zero());
    let t_u = (bisector + half) * std::f64::consts::FRAC_1_SQRT_2;
    let t_v = (bisector - half) * std::f64::consts::FRAC_1_SQRT_2;
    let n = t_u.cross(t_v);
    if !n.is_normalized() {
        return None;
    }
    // Each guide in the plane through its tangent nearest to the curve's plane.
    let guide = |t: DVec3, other: DVec3, m: DVec3, path: &[DVec3]| {
        let up = m.cross(t).normalize_or_zero();
        let up = if up.dot(n) < 0.0 { -up } else { up };
        let tilt = (-up.dot(other)).atan2(up.dot(n));
        let section: Vec<(f64, f64)> = path
            .iter()
            .map(|p| ((*p - corner).dot(t), (*p - corner).dot(up)))
            .collect();
        let p = fit_guide(&section, false, parameters)?;
        let mut guide = vec![p[1].0];
        guide.extend(p[2..].iter().flat_map(|(s, w)| [*s, *w]));
        Some((guide, tilt))
    };
    let (g_u, tilt_u) = guide(t_u, t_v, m_u, path_u)?;
    let (g_v, tilt_v) = guide(t_v, t_u, m_v, path_v)?;
    Some(Start {
        corner,
        frame: [t_u, t_v, n],
        guides: [g_u, g_v],
        tilts: [tilt_u, tilt_v],
        on_boundary,
        retraced: false,
        curvatures,
        at_corner: 0,
    })
}

/// The slope at the corner `(0, 0)` of the cubic `w = c₁s + c₂s² + c₃s³` nearest to a
/// curve's points `(s, w)` by least squares (`c₁`): the whole curve's start direction,
/// which the noise of its first few points does not turn.
fn start_slope(section: &[(f64, f64)]) -> Option<f64> {
    let length = section.iter().map(|p| p.0.abs()).fold(0.0, f64::max);
    if length.is_nan() || length <= 0.0 {
        return None;
    }
    let (mut a, mut b) = (
        nalgebra::Matrix3::<f64>::zeros(),
        nalgebra::Vector3::zeros(),
    );
    for (s, w) in section {
        let x = s / length;
        let row = nalgebra::Vector3::new(x, x * x, x * x * x);
        a += row * row.transpose();
        b += row * (w / length);
    }
    let c = a.try_inverse()? * b;
    c[0].is_finite().then_some(c[0])
}

/// The target's boundary from point `from` along `along`, with the target on the
/// side opposite to `outside` (both tangent): gift wrapping, each step to the point
/// ahead (between half a step and two and a half steps away, or six across a gap of
/// the sampling) that lies furthest outside, "ahead" along the chord of the last
/// `chord` steps (once it has taken as many; 1: the last step), until the boundary
/// ends or turns inwards sharper than [`BOUNDARY_TURN`] (the target's next corner).
/// The points, `from` first.
fn trace_boundary(
    target: &TargetCloud,
    from: usize,
    along: DVec3,
    outside: DVec3,
    step: f64,
    chord: usize,
) -> Vec<DVec3> {
    let mut path = vec![target.points[from]];
    let (mut at, mut d, mut out) = (from, along, outside);
    let longest = (4.0 * target.size / step) as usize + 4;
    while path.len() < longest {
        let q = target.points[at];
        let normal = target.normals[at];
        let d_t = (d - d.dot(normal) * normal).normalize_or_zero();
        let o_t = normal.cross(d_t) * normal.cross(d_t).dot(out).signum();
        // Furthest outside among the points ahead; further ahead across a gap.
        let mut best: Option<(f64, usize)> = None;
        for reach in [2.5 * step, 6.0 * step] {
            for near in target
                .tree
                .locate_within_distance(q.to_array(), reach * reach)
            {
                let v = DVec3::from_array(*near.geom()) - q;
                let ahead = v.dot(d_t);
                if ahead < 0.5 * step {
                    continue;
                }
                let angle = v.dot(o_t).atan2(ahead);
                if best.is_none_or(|(b, _)| angle > b) {
                    best = Some((angle, near.data));
                }
            }
            if best.is_some_and(|(angle, _)| angle > -0.2) {
                break;
            }
        }
        // The boundary ends, or turns inwards at the target's next corner.
        let Some((angle, next)) = best else { break };
        if angle < -BOUNDARY_TURN {
            break;
        }
        let from = path.len().checked_sub(chord).map_or(q, |k| path[k]);
        d = (target.points[next] - from).normalize();
        out = o_t;
        at = next;
        path.push(target.points[next]);
    }
    path
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_zigzag_curves_start_slope_is_its_whole_curves() {
        // The curve w = 0.3 s + 0.5 s² from the corner through 20 points that zigzag
        // across it by ±0.01 (a scan's outermost points): its first leg alone slopes at
        // 0.525.
        let section: Vec<(f64, f64)> = (0..=20)
            .map(|k| {
                let s = k as f64 / 20.0;
                let zigzag = match k {
                    0 => 0.0,
                    _ if k % 2 == 1 => 0.01,
                    _ => -0.01,
                };
                (s, 0.3 * s + 0.5 * s * s + zigzag)
            })
            .collect();
        let first_leg = section[1].1 / section[1].0;
        assert!((first_leg - 0.3).abs() > 0.2, "{first_leg}");
        let slope = start_slope(&section).unwrap();
        assert!((slope - 0.3).abs() < 0.05, "{slope}");
        assert_eq!(start_slope(&[(0.0, 0.0)]), None);
    }

    #[test]
    fn the_boundary_start_is_at_a_corner_when_a_side_bulges_out() {
        // An onion dome's side: the profile r = 1 + 0.5 sin(πt) − 0.4t², z = 1.6t, turned
        // through 150°. Its sides (meridians) bulge out halfway up: there, not at a
        // corner, lies the point lowest along the centre's directions.
        let n = 31;
        let at = |i: usize, j: usize| {
            let (a, t) = (
                150f64.to_radians() * (i as f64 / 30.0 - 0.5),
                j as f64 / 30.0,
            );
            let r = 1.0 + 0.5 * (std::f64::consts::PI * t).sin() - 0.4 * t * t;
            DVec3::new(r * a.cos(), r * a.sin(), 1.6 * t)
        };
        let points: Vec<DVec3> = (0..n * n).map(|k| at(k / n, k % n)).collect();
        let target = TargetCloud::new(&points).unwrap();
        // The centre's directions (the parallel's and the meridian's tangents at the
        // centre): the corner at (i, j) = (0, 0) is the lowest along them.
        let (d1, d2) = (DVec3::Y, (at(15, 16) - at(15, 14)).normalize());
        let bulge = (0..n)
            .map(|j| at(0, j))
            .min_by(|p, q| p.dot(d1 + d2).total_cmp(&q.dot(d1 + d2)));
        assert_ne!(bulge, Some(at(0, 0)), "the lowest point is not the corner");
        // Both starts there (guides fitted with their points' parameters, and at their
        // chord lengths).
        let starts = boundary_start(&target, d1, d2, (1.0, 0.5));
        assert_eq!(starts.len(), 2);
        assert!(starts.iter().all(|s| s.corner == at(0, 0)));
        // The frame along the sides leaving it: the parallel (t = 0) and the meridian.
        let parallel = (at(1, 0) - at(0, 0)).normalize();
        let meridian = (at(0, 1) - at(0, 0)).normalize();
        let [t_u, t_v, _] = starts[0].frame;
        assert!(
            t_u.dot(parallel) > 0.99 && t_v.dot(meridian) > 0.99,
            "{t_u} {t_v}"
        );
    }

    #[test]
    fn the_starts_take_the_best_of_each_corner_first() {
        // Starts 0 and 1 at corner 0, 2 and 3 at corner 1, 4 at corner 2, 5 at corner 3;
        // the scan (objective, start, φ) best at corners 0 and 1.
        let corners = [0, 0, 1, 1, 2, 3];
        let scan = vec![
            (1.0, 0, 10.0),
            (2.0, 1, 80.0),
            (3.0, 2, 40.0),
            (4.0, 3, 50.0),
            (5.0, 0, 100.0),
            (6.0, 4, 140.0),
            (7.0, 0, 20.0),
            (8.0, 5, 30.0),
        ];
        // Every corner once, each by its best start and φ.
        let four = [(0, 10.0), (2, 40.0), (4, 140.0), (5, 30.0)];
        assert_eq!(choose_starts(scan.clone(), &corners, 4), four);
        // Then the best φ of each start not chosen yet, then further φ of a start, at
        // least 15° from its others (φ 20° of start 0 is within 15° of its 10°).
        let all = choose_starts(scan, &corners, 8);
        assert_eq!(all[..4], four);
        assert_eq!(all[4..], [(1, 80.0), (3, 50.0), (0, 100.0)]);
    }
}
