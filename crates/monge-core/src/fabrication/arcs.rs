//! The circular and straight segments of a beam (§4.6, Proposition 4): a beam's
//! nodes in its plane ([`PlaneFrame`]) cut into the arcs a roller bender makes
//! (bi-arcs, n-arcs).

use glam::{DVec2, DVec3};
use serde::Serialize;

/// A local orthonormal frame of a plane (§6): `point = origin + x·x_axis + y·y_axis`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PlaneFrame {
    /// Origin of the plane coordinates.
    pub origin: DVec3,
    /// First axis (unit).
    pub x_axis: DVec3,
    /// Second axis (unit, orthogonal to the first).
    pub y_axis: DVec3,
    /// Unit normal, `x_axis × y_axis`.
    pub normal: DVec3,
}

impl PlaneFrame {
    /// A frame with origin `origin`, normal along `normal` and first axis along
    /// the part of `x` orthogonal to it (§6). Both must be non-zero and not parallel.
    pub(super) fn new(origin: DVec3, normal: DVec3, x: DVec3) -> Self {
        let normal = normal.normalize();
        let x_axis = (x - x.dot(normal) * normal).normalize();
        PlaneFrame {
            origin,
            x_axis,
            y_axis: normal.cross(x_axis),
            normal,
        }
    }

    /// Plane coordinates of `p` (its orthogonal projection) (§6).
    pub fn to_plane(&self, p: DVec3) -> DVec2 {
        let d = p - self.origin;
        DVec2::new(d.dot(self.x_axis), d.dot(self.y_axis))
    }

    /// The 3D point at plane coordinates `q` (§6).
    pub fn to_space(&self, q: DVec2) -> DVec3 {
        self.origin + q.x * self.x_axis + q.y * self.y_axis
    }

    /// Signed distance of `p` from the plane (§6).
    pub fn height(&self, p: DVec3) -> f64 {
        (p - self.origin).dot(self.normal)
    }
}

/// The shape of one piece of a beam between two split nodes (§4.6).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "lowercase", tag = "kind")]
pub enum SegmentShape {
    /// A circular arc through the segment's nodes.
    Arc {
        /// Centre in the beam's plane coordinates.
        center: DVec2,
        /// Centre in space.
        center_3d: DVec3,
        /// Radius.
        radius: f64,
        /// Signed sweep angle from the first to the last node, radians
        /// (positive counter-clockwise about the plane normal).
        sweep: f64,
        /// Arc length, `radius · |sweep|`.
        length: f64,
    },
    /// A straight piece: the nodes are collinear.
    Straight {
        /// Length from the first to the last node.
        length: f64,
    },
}

/// A piece of a beam that is one circular arc or one straight bar (§4.6).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct BeamSegment {
    /// Index of its first node in the beam.
    pub start: usize,
    /// Index of its last node in the beam (the first node of the next segment).
    pub end: usize,
    /// Its shape.
    pub shape: SegmentShape,
    /// Largest distance of its nodes from the arc or line (absolute).
    pub residual: f64,
}

/// A segment in plane coordinates, before its 3D centre is known.
pub(super) struct PlaneSegment {
    start: usize,
    end: usize,
    /// `Some((centre, radius))` for an arc, `None` for a straight piece.
    circle: Option<(DVec2, f64)>,
}

/// The arc or line through three points (§4.6): `None` when they are collinear within `tol`.
fn circle_through(a: DVec2, b: DVec2, c: DVec2, tol: f64) -> Option<(DVec2, f64)> {
    let (ab, ac) = (b - a, c - a);
    let d = 2.0 * ab.perp_dot(ac);
    // Distance of b from the line a–c.
    let chord = ac.length();
    if chord == 0.0 || (ab.perp_dot(ac) / chord).abs() <= tol {
        return None;
    }
    let centre = a + DVec2::new(
        ac.y * ab.length_squared() - ab.y * ac.length_squared(),
        ab.x * ac.length_squared() - ac.x * ab.length_squared(),
    ) / d;
    let radius = ((a - centre).length() + (b - centre).length() + (c - centre).length()) / 3.0;
    Some((centre, radius))
}

/// Distance of `p` from a circle or from the line through `a` and `b`.
fn off(p: DVec2, circle: Option<(DVec2, f64)>, a: DVec2, b: DVec2) -> f64 {
    match circle {
        Some((c, r)) => ((p - c).length() - r).abs(),
        None => {
            let d = b - a;
            (p - a).perp_dot(d).abs() / d.length()
        }
    }
}

/// Splits plane nodes into maximal circular (or straight) pieces (§4.6): the
/// circle through three consecutive nodes is extended while the next node is
/// within `tol` of it; the next piece starts at the last node of this one. A
/// final piece of one edge continues the previous piece's tangent.
pub(super) fn segments(nodes: &[DVec2], tol: f64) -> Vec<PlaneSegment> {
    let n = nodes.len();
    let mut out: Vec<PlaneSegment> = Vec::new();
    let mut s = 0;
    while s + 1 < n {
        if s + 2 >= n {
            out.push(PlaneSegment {
                start: s,
                end: s + 1,
                circle: tangent_circle(out.last(), nodes, s),
            });
            break;
        }
        let circle = circle_through(nodes[s], nodes[s + 1], nodes[s + 2], tol);
        let mut e = s + 2;
        while e + 1 < n && off(nodes[e + 1], circle, nodes[s], nodes[s + 1]) <= tol {
            e += 1;
        }
        out.push(PlaneSegment {
            start: s,
            end: e,
            circle,
        });
        s = e;
    }
    out
}

/// The circle through nodes `s` and `s + 1` tangent to the previous piece at
/// node `s`; `None` (straight) if there is no previous piece or the tangent
/// points at the next node.
fn tangent_circle(prev: Option<&PlaneSegment>, nodes: &[DVec2], s: usize) -> Option<(DVec2, f64)> {
    let prev = prev?;
    let a = nodes[s];
    let tangent = match prev.circle {
        Some((c, _)) => {
            let radial = a - c;
            // Orient along the direction of travel.
            let t = radial.perp();
            if t.dot(a - nodes[s - 1]) < 0.0 {
                -t
            } else {
                t
            }
        }
        None => a - nodes[prev.start],
    }
    .normalize();
    let chord = nodes[s + 1] - a;
    let normal = tangent.perp();
    let h = chord.dot(normal);
    if h.abs() <= 1e-12 * chord.length() {
        return None;
    }
    let rho = chord.length_squared() / (2.0 * h);
    Some((a + rho * normal, rho.abs()))
}

/// Adds the shape (3D centre, sweep, length) and the residual to a plane segment.
pub(super) fn finish_segment(s: PlaneSegment, nodes: &[DVec2], frame: &PlaneFrame) -> BeamSegment {
    let part = &nodes[s.start..=s.end];
    let (a, b) = (part[0], part[part.len() - 1]);
    let (shape, residual) = match s.circle {
        Some((center, radius)) => {
            let sweep: f64 = part
                .windows(2)
                .map(|w| {
                    let (p, q) = (w[0] - center, w[1] - center);
                    p.perp_dot(q).atan2(p.dot(q))
                })
                .sum();
            let shape = SegmentShape::Arc {
                center,
                center_3d: frame.to_space(center),
                radius,
                sweep,
                length: radius * sweep.abs(),
            };
            (shape, max_off(part, s.circle, a, b))
        }
        None => (
            SegmentShape::Straight {
                length: (b - a).length(),
            },
            max_off(part, None, a, b),
        ),
    };
    BeamSegment {
        start: s.start,
        end: s.end,
        shape,
        residual,
    }
}

/// Largest distance of `part` from a circle or from the line through `a` and `b`.
fn max_off(part: &[DVec2], circle: Option<(DVec2, f64)>, a: DVec2, b: DVec2) -> f64 {
    part.iter()
        .map(|&p| off(p, circle, a, b))
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arcs_split_where_the_circle_changes() {
        // A bi-arc: radius 1 about the origin for 60°, then radius 3 tangent to it.
        let mut nodes: Vec<DVec2> = (0..=6)
            .map(|k| DVec2::from_angle(k as f64 * 10f64.to_radians()))
            .collect();
        let join = nodes[6];
        let c2 = join * -2.0; // centre of the second circle, on the same normal
        for k in 1..=4 {
            let a = 60f64.to_radians() + k as f64 * 5f64.to_radians();
            nodes.push(c2 + 3.0 * DVec2::from_angle(a));
        }
        let segs = segments(&nodes, 1e-12);
        assert_eq!(segs.len(), 2);
        assert_eq!((segs[0].start, segs[0].end, segs[1].end), (0, 6, 10));
        let (c, r) = segs[1].circle.unwrap();
        assert!((r - 3.0).abs() < 1e-12 && (c - c2).length() < 1e-12);
    }

    #[test]
    fn a_last_single_edge_continues_the_tangent() {
        let nodes = [
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, 0.0),
            DVec2::new(2.0, 0.0),
            DVec2::new(3.0, 1.0),
            DVec2::new(4.0, 3.0),
        ];
        let segs = segments(&nodes, 1e-12);
        // Straight 0–2, then an arc 2–4 (three nodes), nothing left over.
        assert_eq!(segs.len(), 2);
        assert!(segs[0].circle.is_none() && segs[1].circle.is_some());
        // Two nodes after a straight piece: tangent to it at node 2.
        let segs = segments(&nodes[..4], 1e-12);
        let (c, r) = segs[1].circle.unwrap();
        assert!(((nodes[3] - c).length() - r).abs() < 1e-12);
        assert!((c - DVec2::new(2.0, 1.0)).length() < 1e-12);
    }
}
