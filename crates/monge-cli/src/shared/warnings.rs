//! The warnings of a generated mesh (the singular θ, folds and pinches §5.2,
//! patches above their tolerance) and the admissible θ in words, for every
//! command that generates or reports on a mesh.

use monge_core::combescure::CombescureReport;
use monge_core::gauss_map::ThetaRange;
use monge_core::measure::measure;
use monge_core::multipatch::MultiPatch;
use monge_core::Mode;
use monge_io::generated::near_singular;

use crate::shared::output::{inexact_warning, num};

/// Below this smallest crossing sine the summary warns that the mesh nearly pinches (§5.2).
const LOW_CROSSING_SINE: f64 = 1e-3;

/// What the summary says about folds and pinches (§5.2),
/// taken from a [`CombescureReport`].
#[derive(Clone, Copy, Debug, PartialEq)]
struct Pinching {
    /// Faces oriented against face (0, 0).
    folded_faces: usize,
    /// The first of them, row-major.
    first_fold: Option<(usize, usize)>,
    /// The smallest sine between the two lines that defined a vertex.
    min_sine: f64,
    /// The face where it occurred.
    min_face: (usize, usize),
}

impl From<&CombescureReport> for Pinching {
    fn from(r: &CombescureReport) -> Self {
        Pinching {
            folded_faces: r.folded_faces,
            first_fold: r.first_fold,
            min_sine: r.min_crossing.sine,
            min_face: r.min_crossing.face,
        }
    }
}

/// Below this |θ| in degrees, the lower end of an admissible range is 0 up to
/// round-off (c_v = 0 in §3.2 computes as about 1e-15°).
const ZERO_DEG: f64 = 1e-9;

/// The admissible θ in words, both signs (§3.2); a range from 0 (up to
/// round-off) is one interval, without `−0°`.
pub fn range_text(mode: Mode, r: &ThetaRange) -> String {
    match mode {
        Mode::Characteristic => "every θ in (−180°, 180°]".to_owned(),
        Mode::Arbitrary if r.min_deg.abs() < ZERO_DEG => format!(
            "|θ| ≤ {max}°, i.e. θ in [−{max}°, {max}°]",
            max = num(r.max_deg)
        ),
        Mode::Arbitrary => format!(
            "|θ| in [{min}°, {max}°], i.e. θ in [−{max}°, −{min}°] ∪ [{min}°, {max}°]",
            min = num(r.min_deg),
            max = num(r.max_deg)
        ),
    }
}

/// The warnings of a generation at `theta_deg` (near-singular θ, folds and
/// pinches, §5.2) whose mesh `report` describes (for a conical mesh, its own
/// folds), one line each, for every command that builds on a generated mesh.
pub fn generation_warnings(theta_deg: f64, report: &CombescureReport) -> String {
    warnings(theta_deg, &Pinching::from(report)).concat()
}

/// Warnings about the singular θ and about folds and pinches (§5.2), one line each.
fn warnings(theta_deg: f64, r: &Pinching) -> Vec<String> {
    let mut w = Vec::new();
    if near_singular(theta_deg) {
        w.push(format!(
            "warning: θ = {}° is at or near the singular θ = +90°, where every Gauss circle passes \
             through the corner normal: expect a degenerate mesh; run `monge check` on it.\n",
            num(theta_deg)
        ));
    }
    if let Some((i, j)) = r.first_fold {
        w.push(format!(
            "warning: the mesh folds over itself / pinches (§5.2) in {} faces, first at face ({i}, {j}).\n",
            r.folded_faces
        ));
    }
    if r.min_sine < LOW_CROSSING_SINE {
        let (i, j) = r.min_face;
        w.push(format!(
            "warning: low crossing sine {:.1e} at face ({i}, {j}): vertex ({}, {}) is defined by two \
             nearly parallel lines, the mesh nearly pinches there (§5.2); try another θ.\n",
            r.min_sine,
            i + 1,
            j + 1
        ));
    }
    w
}

/// A warning for each patch of a multi-patch mesh whose measured error exceeds
/// its design's tolerance, with the likely cause ([`inexact_warning`]).
pub fn patch_warnings(mp: &MultiPatch) -> String {
    mp.patches
        .iter()
        .enumerate()
        .map(|(k, p)| {
            let grid = mp.patch_grid(k);
            inexact_warning(
                &format!("patch {k}"),
                measure(&grid).max_error(),
                p.design.tolerance.unwrap_or_default().planarity,
                &grid.vertices,
                p.folded_faces,
                Some(p.design.theta_deg),
            )
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn report(folded_faces: usize, min_sine: f64) -> Pinching {
        Pinching {
            folded_faces,
            first_fold: (folded_faces > 0).then_some((5, 6)),
            min_sine,
            min_face: (3, 4),
        }
    }

    #[test]
    fn a_clean_mesh_has_no_warnings() {
        assert!(warnings(30.0, &report(0, 0.5)).is_empty());
    }

    #[test]
    fn folds_and_low_sines_are_reported_with_their_faces() {
        let w = warnings(-90.0, &report(7, 1e-4));
        assert_eq!(w.len(), 2);
        assert!(
            w[0].contains("in 7 faces, first at face (5, 6)"),
            "{}",
            w[0]
        );
        assert!(w[1].contains("1.0e-4 at face (3, 4)"), "{}", w[1]);
    }

    #[test]
    fn only_plus_ninety_is_singular() {
        assert!(near_singular(90.0));
        assert!(near_singular(89.5));
        assert!(!near_singular(-90.0));
        assert!(!near_singular(30.0));
        let w = warnings(90.0, &report(0, 0.5));
        assert_eq!(w.len(), 1);
        assert!(w[0].contains("singular θ = +90°"), "{}", w[0]);
    }

    #[test]
    fn ranges_have_both_signs() {
        let r = ThetaRange {
            min_deg: 61.9,
            max_deg: 170.0,
        };
        assert_eq!(
            range_text(Mode::Arbitrary, &r),
            "|θ| in [61.9°, 170°], i.e. θ in [−170°, −61.9°] ∪ [61.9°, 170°]"
        );
        for min_deg in [0.0, -0.0, 1.3e-15] {
            let r = ThetaRange {
                min_deg,
                max_deg: 170.0,
            };
            let text = range_text(Mode::Arbitrary, &r);
            assert_eq!(text, "|θ| ≤ 170°, i.e. θ in [−170°, 170°]");
        }
    }
}
