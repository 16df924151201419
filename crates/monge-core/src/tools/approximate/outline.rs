//! The target's outline (monge's extension of §4.7): the polygon a mesh that covers
//! the target is cut by ([`trim`](super::trim())), and its form in a design file (the key
//! `trim` of a trimmed design), read back only as a valid outline ([`OutlineError`]).

use glam::{DVec2, DVec3};
use serde::{Deserialize, Serialize};

use super::clip::polygon_area;
use super::error::ApproxError;
use super::index::TargetCloud;

/// The target's outline: its boundary points, seen along the normal of the plane
/// fitted to all its points, as a polygon around their centroid.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "OutlineFile")]
pub struct Outline {
    /// The centroid of the target's points: the origin of the outline's plane.
    pub(super) origin: DVec3,
    /// The outline's plane's axes.
    pub(super) axes: [DVec3; 2],
    /// The direction along which the target is seen (the normal of its plane).
    pub(super) up: DVec3,
    /// The polygon, counter-clockwise in the outline's plane.
    pub(super) polygon: Vec<DVec2>,
}

/// Target points allowed outside the outline by more than this many mean spacings:
/// none.
const OUTSIDE_SPACINGS: f64 = 2.0;

/// A boundary point farther inside the outline than this many mean spacings is not on
/// it (a random sampling's boundary test marks points up to about two spacings inside).
const HIDDEN_SPACINGS: f64 = 4.0;

/// Share of the boundary points allowed farther inside the outline than
/// [`HIDDEN_SPACINGS`] (a few stray ones of a scan): more, and the target has a hole or
/// an edge the outline does not follow.
const HIDDEN_SHARE: f64 = 0.02;

impl Outline {
    /// The outline of `target` (see the type): its boundary points in angular sectors
    /// around the centroid of its points, seen along its normal, the farthest of each
    /// sector (about two boundary points per sector). A target whose outline is not
    /// star-shaped around its centroid (an L-shaped or ring-shaped roof), or seen
    /// edge-on (a dome closed round its axis), is refused.
    ///
    /// ```
    /// use glam::DVec3;
    /// use monge_core::approximate::{Outline, TargetCloud};
    /// // A 21 × 21 sampling of a dome over the square [0, 10]².
    /// let points: Vec<DVec3> = (0..441)
    ///     .map(|k| {
    ///         let (x, y) = ((k % 21) as f64 * 0.5, (k / 21) as f64 * 0.5);
    ///         DVec3::new(x, y, 3.0 - 0.02 * ((x - 5.0).powi(2) + (y - 5.0).powi(2)))
    ///     })
    ///     .collect();
    /// let outline = Outline::of(&TargetCloud::new(&points).unwrap()).unwrap();
    /// // Its area is the square's, its corners on it.
    /// assert!((outline.area() - 100.0).abs() < 1e-6);
    /// ```
    pub fn of(target: &TargetCloud) -> Result<Self, ApproxError> {
        let points = &target.points;
        let origin = points.iter().copied().sum::<DVec3>() / points.len() as f64;
        let up = target.up;
        let x = up.any_orthonormal_vector();
        let mut outline = Outline {
            origin,
            axes: [x, up.cross(x)],
            up,
            polygon: Vec::new(),
        };
        let boundary: Vec<DVec2> = points
            .iter()
            .zip(&target.outward)
            .filter(|(_, o)| **o != DVec3::ZERO)
            .map(|(p, _)| outline.flat(*p))
            .collect();
        let sectors = (boundary.len() / 2).max(8);
        let mut farthest: Vec<Option<DVec2>> = vec![None; sectors];
        for q in &boundary {
            let angle = q.y.atan2(q.x).rem_euclid(std::f64::consts::TAU);
            let k = ((angle / std::f64::consts::TAU * sectors as f64) as usize).min(sectors - 1);
            if farthest[k].is_none_or(|f| q.length() > f.length()) {
                farthest[k] = Some(*q);
            }
        }
        outline.polygon = farthest.into_iter().flatten().collect();
        let reach = OUTSIDE_SPACINGS * target.spacing;
        let outside = points
            .iter()
            .map(|p| outline.flat(*p))
            .filter(|q| !outline.contains_flat(*q) && outline.distance_flat(*q) > reach)
            .count();
        // Boundary points far inside the outline: a hole's edge, or an edge that the
        // outline's sectors do not see (an L-shaped target's inner corner).
        let hidden = boundary
            .iter()
            .filter(|q| outline.distance_flat(**q) > HIDDEN_SPACINGS * target.spacing)
            .count();
        if outline.polygon.len() < 3
            || outside > 0
            || hidden as f64 > HIDDEN_SHARE * boundary.len() as f64
            || outline.area() <= 0.0
        {
            return Err(ApproxError::NoOutline {
                outside,
                hidden,
                points: points.len(),
            });
        }
        Ok(outline)
    }

    /// The area the outline encloses (model units squared).
    pub fn area(&self) -> f64 {
        polygon_area(&self.polygon)
    }

    /// The outline's corners in space: its polygon's points on the target.
    pub fn polygon(&self) -> Vec<DVec3> {
        self.polygon.iter().map(|q| self.lift(*q)).collect()
    }

    /// A point of the outline's plane in space.
    pub(super) fn lift(&self, q: DVec2) -> DVec3 {
        self.origin + q.x * self.axes[0] + q.y * self.axes[1]
    }

    /// `p` seen along the outline's direction, in its plane.
    pub(super) fn flat(&self, p: DVec3) -> DVec2 {
        let d = p - self.origin;
        DVec2::new(d.dot(self.axes[0]), d.dot(self.axes[1]))
    }

    /// Whether `p`, seen along the outline's direction, lies inside it.
    pub fn contains(&self, p: DVec3) -> bool {
        self.contains_flat(self.flat(p))
    }

    /// Whether `q` lies inside the polygon (even–odd rule).
    pub(super) fn contains_flat(&self, q: DVec2) -> bool {
        let mut inside = false;
        for (a, b) in self.polygon.iter().zip(self.polygon.iter().cycle().skip(1)) {
            if (a.y > q.y) != (b.y > q.y) {
                let x = a.x + (q.y - a.y) / (b.y - a.y) * (b.x - a.x);
                if q.x < x {
                    inside = !inside;
                }
            }
        }
        inside
    }

    /// Distance from `q` to the polygon's sides.
    fn distance_flat(&self, q: DVec2) -> f64 {
        self.polygon
            .iter()
            .zip(self.polygon.iter().cycle().skip(1))
            .map(|(a, b)| {
                let ab = *b - *a;
                let t =
                    ((q - *a).dot(ab) / ab.length_squared().max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
                q.distance(*a + t * ab)
            })
            .fold(f64::INFINITY, f64::min)
    }
}

/// Largest departure of a design file's outline frame from an orthonormal, right-handed
/// one (`up = axes[0] × axes[1]`): far above the round-off of one written by monge
/// (about 1e-16), far below a frame a person writes by hand with a few digits' error.
pub const OUTLINE_FRAME_TOL: f64 = 1e-9;

/// Why a design file's outline is not one ([`Outline`]'s form in a file).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum OutlineError {
    /// `axes` and `up` are not unit vectors at right angles with `up = axes[0] × axes[1]`.
    #[error(
        "the outline's axes and up are {by:e} from an orthonormal frame with up = axes[0] × \
         axes[1] (at most {OUTLINE_FRAME_TOL:e}): give unit vectors at right angles, up the \
         cross product of the two axes"
    )]
    Frame {
        /// The largest departure (of a length from 1, a dot product from 0, or of
        /// `axes[0] × axes[1]` from `up`).
        by: f64,
    },
    /// The polygon has fewer than three corners.
    #[error("the outline's polygon has {corners} corners: it needs 3 or more")]
    Corners {
        /// Its corners.
        corners: usize,
    },
    /// The polygon does not run counter-clockwise around a positive area (seen along `up`).
    #[error(
        "the outline's polygon encloses a signed area of {area} (model units squared): its \
         corners must run counter-clockwise seen along up, around a positive area; reverse \
         their order"
    )]
    Area {
        /// Its signed area in the outline's plane.
        area: f64,
    },
}

/// An [`Outline`] as a design file has it, checked before it is one.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct OutlineFile {
    origin: DVec3,
    axes: [DVec3; 2],
    up: DVec3,
    polygon: Vec<DVec2>,
}

impl TryFrom<OutlineFile> for Outline {
    type Error = OutlineError;

    /// The outline of a design file: its frame orthonormal and right-handed within
    /// [`OUTLINE_FRAME_TOL`], its polygon of three corners or more counter-clockwise
    /// around a positive area.
    fn try_from(f: OutlineFile) -> Result<Self, OutlineError> {
        let [x, y] = f.axes;
        let by = [
            (x.length() - 1.0).abs(),
            (y.length() - 1.0).abs(),
            (f.up.length() - 1.0).abs(),
            x.dot(y).abs(),
            x.cross(y).distance(f.up),
        ]
        .into_iter()
        .fold(0.0, f64::max);
        // NaN (not finite) fails too.
        if by.is_nan() || by > OUTLINE_FRAME_TOL {
            return Err(OutlineError::Frame { by });
        }
        if f.polygon.len() < 3 {
            return Err(OutlineError::Corners {
                corners: f.polygon.len(),
            });
        }
        let area = polygon_area(&f.polygon);
        if area.is_nan() || area <= 0.0 {
            return Err(OutlineError::Area { area });
        }
        Ok(Outline {
            origin: f.origin,
            axes: f.axes,
            up: f.up,
            polygon: f.polygon,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 21 × 21 sampling of a dome over the square [0, 10]², its outline.
    fn dome_outline() -> Outline {
        let points: Vec<DVec3> = (0..441)
            .map(|k| {
                let (x, y) = ((k % 21) as f64 * 0.5, (k / 21) as f64 * 0.5);
                DVec3::new(x, y, 3.0 - 0.02 * ((x - 5.0).powi(2) + (y - 5.0).powi(2)))
            })
            .collect();
        Outline::of(&TargetCloud::new(&points).unwrap()).unwrap()
    }

    #[test]
    fn an_outline_read_back_from_its_file_is_the_same_to_the_bit() {
        let outline = dome_outline();
        let text = serde_json::to_string(&outline).unwrap();
        assert!(text.starts_with(r#"{"origin":["#), "{text}");
        let back: Outline = serde_json::from_str(&text).unwrap();
        assert_eq!(back, outline);
        // Its corners in space, lifted from the file's numbers, are the same too.
        assert_eq!(back.polygon(), outline.polygon());
    }

    #[test]
    fn an_outline_file_that_is_not_one_says_why() {
        let read = |edit: &dyn Fn(&mut serde_json::Value)| {
            let mut value = serde_json::to_value(dome_outline()).unwrap();
            edit(&mut value);
            serde_json::from_value::<Outline>(value)
                .unwrap_err()
                .to_string()
        };
        // An axis a little off unit length (1e-6), beyond the frame's tolerance.
        let e =
            read(&|v| v["axes"][0][1] = (v["axes"][0][1].as_f64().unwrap() * (1.0 + 1e-6)).into());
        assert!(e.contains("orthonormal frame"), "{e}");
        // up reversed: a left-handed frame.
        let e = read(&|v| {
            for k in 0..3 {
                v["up"][k] = (-v["up"][k].as_f64().unwrap()).into();
            }
        });
        assert!(e.contains("up = axes[0] × axes[1]"), "{e}");
        let e = read(&|v| v["polygon"] = serde_json::json!([[0, 0], [1, 0]]));
        assert!(e.contains("has 2 corners"), "{e}");
        // Clockwise.
        let e = read(&|v| v["polygon"].as_array_mut().unwrap().reverse());
        assert!(e.contains("signed area of -"), "{e}");
        let e = read(&|v| v["corners"] = 4.into());
        assert!(e.contains("unknown field `corners`"), "{e}");
        // The errors themselves, as typed.
        let file = |polygon: Vec<DVec2>| OutlineFile {
            origin: DVec3::ZERO,
            axes: [DVec3::X, DVec3::Y],
            up: DVec3::Z,
            polygon,
        };
        let square = vec![DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y];
        assert!(Outline::try_from(file(square.clone())).is_ok());
        assert_eq!(
            Outline::try_from(file(square[..2].to_vec())),
            Err(OutlineError::Corners { corners: 2 })
        );
        assert_eq!(
            Outline::try_from(file(square.into_iter().rev().collect())),
            Err(OutlineError::Area { area: -1.0 })
        );
        let skew = OutlineFile {
            axes: [DVec3::X, DVec3::new(0.0, 1.0, 1e-6).normalize()],
            ..file(vec![])
        };
        assert!(matches!(Outline::try_from(skew), Err(OutlineError::Frame { by }) if by > 9e-7));
    }

    #[test]
    fn a_ring_shaped_target_has_no_outline() {
        // An annulus: its centre is outside it, its inner boundary points are outside
        // the polygon of the outer ones' sectors.
        let points: Vec<DVec3> = (0..2000)
            .map(|k| {
                let (r, a) = (2.0 + 2.0 * ((k as f64 + 0.5) / 2000.0), k as f64 * 2.399963);
                DVec3::new(r * a.cos(), r * a.sin(), 0.02 * r * r)
            })
            .collect();
        let error = Outline::of(&TargetCloud::new(&points).unwrap()).unwrap_err();
        assert!(matches!(error, ApproxError::NoOutline { .. }), "{error}");
    }
}
