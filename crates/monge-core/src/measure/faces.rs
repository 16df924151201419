//! Planarity and circularity of one quad face (§2.2): the distance between its
//! diagonals, and how far its fourth corner is from the circle through the other three.

use glam::DVec3;

/// Face planarity of a quad `[A, B, C, D]` (§2.2): the distance between the
/// lines `AC` and `BD` of its diagonals, in absolute length units.
///
/// The four corners are coplanar iff the two diagonal lines meet (or are
/// parallel), so this is 0 exactly for planar quads; for a nearly planar convex
/// quad it is the width of the thinnest slab containing the corners. For a
/// non-convex or crossed face the lines meet outside the face and their
/// distance magnifies the deviation from a plane; when the diagonals are
/// (nearly) parallel — the angle between them below 1e-6 rad, only possible
/// for such a degenerate face — the magnification is unbounded, so the distance
/// of the remaining corner from the plane of the best-shaped corner triple (see
/// [`circularity`]) is used instead; 0 if all four corners are collinear.
///
/// ```
/// use glam::DVec3;
/// use monge_core::measure::face_planarity;
/// // A twisted unit square: C lifted by h. Diagonal AC rises h over its length.
/// let h = 0.25;
/// let q = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, h), DVec3::Y];
/// // Line AC at its crossing with BD (x = y = 1/2) is at height h/2; BD is at 0.
/// let expect = h / 2.0 / (1.0 + h * h / 2.0).sqrt();
/// assert!((face_planarity(&q) - expect).abs() < 1e-16);
/// ```
pub fn face_planarity(quad: &[DVec3; 4]) -> f64 {
    let [a, b, c, d] = *quad;
    let (ac, bd) = (c - a, d - b);
    let n = ac.cross(bd);
    let nn = n.length();
    if nn > 1e-6 * ac.length() * bd.length() {
        (b - a).dot(n).abs() / nn
    } else {
        let k = best_triple(quad);
        let [p, q, r] = triple(quad, k);
        let normal = (q - p).cross(r - p).normalize_or_zero();
        (quad[k] - p).dot(normal).abs()
    }
}

/// Circularity of a quad `[A, B, C, D]` (§2.2): the distance of one corner from
/// the circle through the other three, in absolute length units.
///
/// The omitted corner is the one whose complementary triple is best shaped
/// (largest `2·area / longest edge²`, i.e. farthest from collinear): the
/// circumcircle of that triple is the best-conditioned one, so noise on a thin
/// or nearly straight corner cannot blow the value up. For a cyclic quad all
/// four triples share one circle, so the choice only matters for conditioning;
/// taking the maximum over all four triples instead would let a near-collinear
/// triple (huge, unstable circumcircle) report a spurious large error.
///
/// The distance from a point `P` to a circle (centre `c`, radius `r`, unit
/// normal `ν`) is `√(h² + (|P' − c| − r)²)` with `h = (P − c)·ν` the
/// out-of-plane offset and `P' = P − hν` the in-plane projection. It is 0 iff
/// the quad is planar and its corners are concyclic. All corners on one line
/// (a circle of infinite radius) measure 0.
///
/// ```
/// use glam::DVec3;
/// use monge_core::measure::circularity;
/// // Kite A(−1,0) B(0,−1) C(2,0) D(0,1): the best triple BCD has the circle
/// // centred at (3/4, 0) with radius 5/4; A is at distance 7/4 from the centre.
/// let q = [DVec3::new(-1.0, 0.0, 0.0), DVec3::new(0.0, -1.0, 0.0), DVec3::new(2.0, 0.0, 0.0), DVec3::new(0.0, 1.0, 0.0)];
/// assert!((circularity(&q) - 0.5).abs() < 1e-15);
/// ```
pub fn circularity(quad: &[DVec3; 4]) -> f64 {
    let k = best_triple(quad);
    let [a, b, c] = triple(quad, k);
    // Relative to corner c, so that no coordinate far from the origin rounds, and
    // in units of a power of two near the triple's size (exact), so that the
    // fifth powers of lengths below neither overflow nor underflow.
    let unit = power_of_two_below((a - c).abs().max((b - c).abs()).max_element());
    if unit == 0.0 {
        return 0.0; // the triple is one point: the four corners are collinear
    }
    let (u, v) = ((a - c) / unit, (b - c) / unit);
    let w = u.cross(v);
    let w2 = w.length_squared();
    if w2 == 0.0 {
        return 0.0; // all four corners collinear (the best triple is)
    }
    let centre = (u.length_squared() * v - v.length_squared() * u).cross(w) / (2.0 * w2);
    let radius = ((u - centre).length() + (v - centre).length() + centre.length()) / 3.0;
    let normal = w / w2.sqrt();
    let p = (quad[k] - c) / unit - centre;
    let h = p.dot(normal);
    h.hypot((p - h * normal).length() - radius) * unit
}

/// The largest power of two `≤ x` for a positive normal `x` (its exponent
/// bits alone); 0 for 0, and `x` itself when it is subnormal or not finite.
fn power_of_two_below(x: f64) -> f64 {
    if x.is_normal() {
        f64::from_bits(x.to_bits() & 0x7ff0_0000_0000_0000)
    } else {
        x
    }
}

/// The three corners of `quad` other than corner `k`, in cyclic order.
fn triple(quad: &[DVec3; 4], k: usize) -> [DVec3; 3] {
    [quad[(k + 1) % 4], quad[(k + 2) % 4], quad[(k + 3) % 4]]
}

/// The corner whose complementary triple is best shaped: largest
/// `2·area / longest edge²` (0 for collinear, √3/2 for equilateral); the first on ties.
fn best_triple(quad: &[DVec3; 4]) -> usize {
    let shape = |[a, b, c]: [DVec3; 3]| {
        let longest = (b - a)
            .length_squared()
            .max((c - b).length_squared())
            .max((a - c).length_squared());
        let area2 = (b - a).cross(c - a).length();
        if longest > 0.0 {
            area2 / longest
        } else {
            0.0
        }
    };
    let mut best = (0, shape(triple(quad, 0)));
    for k in 1..4 {
        let s = shape(triple(quad, k));
        if s > best.1 {
            best = (k, s);
        }
    }
    best.0
}
