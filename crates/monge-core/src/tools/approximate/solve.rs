//! The searches of [`approximate`](super::approximate) (monge's extension): the θ scan
//! of the starts, Levenberg–Marquardt on the residuals, with a finite-difference
//! Jacobian, θ restarts where the least squares stall, and θ alone (the guides kept).

use crate::gauss_map::admissible_theta_at;

use super::{
    design_of, fair_mesh, refine_guides, samples_for, start_parameters, sum_of_squares, Matches,
    Progress, Search, Start,
};

impl Search<'_> {
    /// The θ scan ([`Search::scan_theta`]) of the starts in `guesses`, a corner's
    /// boundary traced again ([`Start::retraced`]) only where its boundary starts fold at
    /// every θ or could not be traced: as (objective, start, θ).
    pub(super) fn scan_starts(
        &mut self,
        guesses: &[Start],
        faces: (usize, usize),
    ) -> Vec<(f64, usize, f64)> {
        let all = 0..guesses.len();
        let mut scan = self.scan_theta(
            guesses,
            all.clone().filter(|g| !guesses[*g].retraced),
            faces,
        );
        let holds = |corner: usize| {
            scan.iter()
                .any(|s| guesses[s.1].on_boundary && guesses[s.1].at_corner == corner)
        };
        let again: Vec<usize> = all
            .filter(|g| guesses[*g].retraced && !holds(guesses[*g].at_corner))
            .collect();
        scan.extend(self.scan_theta(guesses, again.into_iter(), faces));
        scan
    }

    /// The θ scan of the starts (§4.3): the objective on a grid of `faces` at every 10°
    /// from each start `which` of `guesses` (but 90°, where the guides' planes
    /// coincide), the meshes in parallel; the feasible ones as (objective, start, θ), in
    /// the starts' order.
    pub(super) fn scan_theta(
        &mut self,
        guesses: &[Start],
        which: impl Iterator<Item = usize>,
        faces: (usize, usize),
    ) -> Vec<(f64, usize, f64)> {
        let trials: Vec<(usize, Vec<f64>, f64)> = which
            .flat_map(|g| {
                (-17..=18)
                    .filter(|k| *k != 9)
                    .map(move |k| (g, 10.0 * f64::from(k)))
            })
            .map(|(g, theta)| (g, start_parameters(&guesses[g], theta), theta))
            .collect();
        self.objectives(guesses, &trials, faces)
            .into_iter()
            .map(|(f, k)| (f, trials[k].0, trials[k].2))
            .collect()
    }

    /// The objective on a grid of `faces` of each of `trials` (a start's index in
    /// `guesses`, parameters, and a tag), the meshes in parallel, counted: the feasible
    /// ones as (objective, index in `trials`), in `trials`' order.
    fn objectives<T: Sync>(
        &mut self,
        guesses: &[Start],
        trials: &[(usize, Vec<f64>, T)],
        faces: (usize, usize),
    ) -> Vec<(f64, usize)> {
        // The objective, NaN when infeasible, `None` once stopped.
        let values = crate::tasks::map(trials.len(), |k| {
            let (g, x, _) = &trials[k];
            (!(self.stop)()).then(|| {
                self.sum_of_squares_at(&guesses[*g], x, faces)
                    .unwrap_or(f64::NAN)
            })
        });
        let mut feasible = Vec::with_capacity(trials.len());
        for (k, f) in values.into_iter().enumerate() {
            match f {
                Some(f) => {
                    self.evaluations += 1;
                    if f.is_finite() {
                        self.best = self.best.min(f);
                        feasible.push((f, k));
                    }
                }
                None => self.timed_out = true,
            }
        }
        feasible
    }

    /// The Jacobian of the residuals at `x` (real units), measured against the
    /// `matches` of `x`'s own mesh (no spatial search: the residuals are smooth there),
    /// by forward differences of [`FD_STEP`] of each parameter's scale, the columns in
    /// parallel (in their order, whatever the threads); a column whose step is
    /// infeasible is taken backwards, and nil if that is infeasible too. `None` once
    /// stopped.
    fn jacobian(
        &mut self,
        start: &Start,
        x: &[f64],
        (r, matches): (&[f64], &Matches),
        scale: &[f64],
        faces: (usize, usize),
    ) -> Option<nalgebra::DMatrix<f64>> {
        // A column, the meshes it generated, and whether the stop came first.
        let column = |k: usize| -> (Vec<f64>, usize, bool) {
            let mut evaluations = 0;
            for sign in [1.0, -1.0] {
                if (self.stop)() {
                    return (Vec::new(), evaluations, true);
                }
                let mut xk = x.to_vec();
                xk[k] += sign * FD_STEP * scale[k];
                evaluations += 1;
                if let Some(grid) = self.mesh(start, &xk, faces) {
                    let rk = self.residuals_against(&grid, matches);
                    let column = rk.iter().zip(r).map(|(a, b)| sign * (a - b) / FD_STEP);
                    return (column.collect(), evaluations, false);
                }
            }
            (vec![0.0; r.len()], evaluations, false)
        };
        let columns = crate::tasks::map(x.len(), column);
        self.evaluations += columns.iter().map(|c| c.1).sum::<usize>();
        if columns.iter().any(|c| c.2) {
            self.timed_out = true;
            return None;
        }
        Some(nalgebra::DMatrix::from_fn(r.len(), x.len(), |i, k| {
            columns[k].0[i]
        }))
    }

    /// One Levenberg–Marquardt run from `x0` on `faces` (parameters in units of their
    /// scale, [`scales`]; Marquardt's diagonal damping; a step is kept only when it
    /// lowers the objective, so the result is never worse than `x0`), until a step
    /// gains less than [`LM_GAIN`] of the objective (or [`LM_FLOOR`] squared), the damping grows past any use,
    /// the run's budget is spent or the search is stopped; the best point and its
    /// objective (NaN, `x0` when `x0` is infeasible).
    pub(super) fn run(
        &mut self,
        start: &Start,
        x0: &[f64],
        faces: (usize, usize),
        progress: &mut dyn FnMut(&Progress),
    ) -> (f64, Vec<f64>) {
        let scale = scales(x0.len(), self.target.size);
        self.run_scaled(start, x0, faces, &scale, progress)
    }

    /// [`Search::run`] with the parameters' scales given: a parameter of scale 0 stays
    /// where it is.
    pub(super) fn run_scaled(
        &mut self,
        start: &Start,
        x0: &[f64],
        faces: (usize, usize),
        scale: &[f64],
        progress: &mut dyn FnMut(&Progress),
    ) -> (f64, Vec<f64>) {
        let n = x0.len();
        let first = self.evaluations;
        let mut x = x0.to_vec();
        let Some((mut r, mut matches)) = self.evaluate(start, &x, faces) else {
            return (f64::NAN, x);
        };
        let mut f = sum_of_squares(&r);
        let mut damping = 1e-3;
        while self.evaluations - first + n < self.budget {
            let Some(jacobian) = self.jacobian(start, &x, (&r, &matches), scale, faces) else {
                break;
            };
            progress(&self.progress());
            let jtj = jacobian.transpose() * &jacobian;
            let gradient = jacobian.transpose() * nalgebra::DVector::from_column_slice(&r);
            let floor = 1e-12 * jtj.diagonal().max().max(f64::MIN_POSITIVE);
            let mut gain = 0.0;
            while damping < 1e12 && self.evaluations - first < self.budget {
                let mut system = jtj.clone();
                for k in 0..n {
                    system[(k, k)] += damping * jtj[(k, k)].max(floor);
                }
                let Some(step) = system.cholesky().map(|c| c.solve(&gradient)) else {
                    damping *= 4.0;
                    continue;
                };
                let trial: Vec<f64> = x
                    .iter()
                    .zip(step.iter().zip(scale))
                    .map(|(x, (s, scale))| x - s * scale)
                    .collect();
                let trial_r = self.evaluate(start, &trial, faces);
                if self.timed_out {
                    break;
                }
                let Some((trial_r, trial_matches)) = trial_r else {
                    damping *= 4.0;
                    continue;
                };
                let value = sum_of_squares(&trial_r);
                if value < f {
                    gain = (f - value) / f.max(LM_FLOOR * LM_FLOOR / LM_GAIN);
                    (x, r, matches, f) = (trial, trial_r, trial_matches, value);
                    damping = (damping / 3.0).max(1e-9);
                    break;
                }
                damping *= 4.0;
            }
            progress(&self.progress());
            if gain < LM_GAIN || self.timed_out {
                break;
            }
        }
        (f, x)
    }

    /// Where the least squares stall away from the target from every start: new starts
    /// from each of their finite `results` (objective, start, parameters), θ moved to
    /// the best [`THETA_RESTARTS`] of a scan every 10° (the other parameters kept, θ
    /// more than 15° from its own). The least squares settle in the basin of their θ;
    /// a scan of 8 000 points of a moulding stalled at θ 22.7°, 3.3e-2 of its size off,
    /// and from θ 0° came to 7.8e-4 (BOBYQA's polish, which this replaces, took 23 s to
    /// 1.6e-3). Where one patch cannot follow the target, the restarts stall too, in
    /// about a second (BOBYQA took 10 to 18 s there for 5 % at most).
    pub(super) fn theta_restarts(
        &mut self,
        guesses: &[Start],
        results: &[(f64, usize, Vec<f64>)],
        faces: (usize, usize),
    ) -> Vec<(usize, Vec<f64>)> {
        // The scan's trials: start, parameters, and the index of the finite result.
        let trials: Vec<(usize, Vec<f64>, usize)> = results
            .iter()
            .enumerate()
            .filter(|(_, r)| r.0.is_finite())
            .flat_map(|(n, (_, g, x))| {
                (-17..=18)
                    .map(|k| 10.0 * f64::from(k))
                    .filter(|t| {
                        let d = (t - x[8]).rem_euclid(360.0);
                        d.min(360.0 - d) > 15.0
                    })
                    .map(move |t| {
                        let mut y = x.clone();
                        y[8] = t;
                        (*g, y, n)
                    })
            })
            .collect();
        let mut scanned: Vec<(usize, f64, usize)> = self
            .objectives(guesses, &trials, faces)
            .into_iter()
            .map(|(f, k)| (trials[k].2, f, k))
            .collect();
        // The best few of each result's scan, in the results' order.
        scanned.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));
        let mut restarts = Vec::new();
        for (n, (result, _, k)) in scanned.iter().enumerate() {
            if scanned[..n].iter().filter(|s| s.0 == *result).count() < THETA_RESTARTS {
                let (g, y, _) = &trials[*k];
                restarts.push((*g, y.clone()));
            }
        }
        restarts
    }

    /// The least squares ([`Search::run`]) from `x` on `faces` again with finer guides
    /// ([`refine_guides`]: the same design to round-off), up to [`GUIDE_REFINEMENTS`]
    /// times, each kept only when it lowers the objective and comes closer to the target
    /// by the largest distance both ways ([`Deviation::closer_than`](super::Deviation::closer_than)).
    /// A guide of five control points may not follow a target's curve (a profile with an
    /// inflection, the offset of a parabola) as closely as θ and the rest of the design
    /// could; where the residual is a scan's noise and its sparse edges, finer guides
    /// would chase those, and the largest distance says so.
    pub(super) fn finer_guides(
        &mut self,
        start: &Start,
        mut x: Vec<f64>,
        faces: (usize, usize),
        progress: &mut dyn FnMut(&Progress),
    ) -> Vec<f64> {
        let samples = samples_for(faces, self.kind);
        let reading = |s: &Self, x: &[f64]| {
            fair_mesh(&design_of(start, x, samples, s.kind), s.outline)
                .map(|m| s.target.deviation(&m))
        };
        // The current design's objective and reading, each measured once.
        let (mut f, mut read) = (None, None);
        for _ in 0..GUIDE_REFINEMENTS {
            // Each knot span sampled by enough of the mesh's faces: between its samples, a
            // guide finer than its mesh is free to wiggle, and a design is regenerated
            // at any resolution.
            let control_points = (super::per_guide(&x) - 1) / 2 + 2;
            let spans = 2 * (control_points - 3);
            if faces.0.min(faces.1) < FACES_PER_SPAN * spans {
                break;
            }
            let Some(f_x) = f.or_else(|| self.sum_of_squares_at(start, &x, faces)) else {
                break;
            };
            if self.timed_out || f_x.sqrt() <= LM_FLOOR {
                break;
            }
            let (g, y) = self.run(start, &refine_guides(&x), faces, progress);
            // Kept only when lower (not when either is NaN).
            if g.partial_cmp(&f_x) != Some(std::cmp::Ordering::Less) {
                break;
            }
            let read_x = read.unwrap_or_else(|| reading(self, &x));
            let read_y = reading(self, &y);
            if !matches!((read_y, read_x), (Some(a), Some(b)) if a.closer_than(&b)) {
                break;
            }
            (x, f, read) = (y, Some(g), Some(read_y));
        }
        x
    }

    /// The nearest surface of revolution or moulding surface (§4.1: θ = 0° or 180°, φ at
    /// an end of the admissible range, the other guide's plane through the node axis:
    /// the rail's profile in its normal planes) to the design `x` on `faces`, by the
    /// least squares with those two parameters held, when `x`'s θ is within
    /// [`MOULDING_THETA`] of 0° or 180°; kept when its objective is within
    /// [`MOULDING_RATIO`] of `x`'s. Near an end of its range the axes turn only as the
    /// square root of θ's distance to it (§3.2), so that a scan's noise and its sparse
    /// edges move θ by degrees for a small gain: the family of the paper's examples is
    /// what a designer expects back.
    pub(super) fn moulding(
        &mut self,
        start: &Start,
        x: Vec<f64>,
        faces: (usize, usize),
        progress: &mut dyn FnMut(&Progress),
    ) -> Vec<f64> {
        let theta = admissible_theta_at(x[6].sin(), x[7].sin(), x[8]).rem_euclid(180.0);
        if theta.min(180.0 - theta) > MOULDING_THETA || self.timed_out {
            return x;
        }
        let Some(f) = self.sum_of_squares_at(start, &x, faces) else {
            return x;
        };
        let mut best = (MOULDING_RATIO * f, x.clone());
        // θ = 0° (φ = 0°) with guide_v's plane untilted, θ = 180° with guide_u's.
        for (phi, tilt) in [(0.0, 7), (180.0, 6)] {
            let mut y = x.clone();
            (y[8], y[tilt]) = (phi, 0.0);
            let mut scale = scales(y.len(), self.target.size);
            (scale[8], scale[tilt]) = (0.0, 0.0);
            let (g, z) = self.run_scaled(start, &y, faces, &scale, progress);
            if g <= best.0 {
                best = (g, z);
            }
        }
        best.1
    }

    /// θ alone from `x0`, the rest fixed: every tenth of `half_width` degrees on both
    /// sides, then golden-section search around the best; the best point and its
    /// objective.
    pub(super) fn run_theta(
        &mut self,
        start: &Start,
        x0: &[f64],
        faces: (usize, usize),
        half_width: f64,
        progress: &mut dyn FnMut(&Progress),
    ) -> (f64, Vec<f64>) {
        let mut f = |search: &mut Self, theta: f64| {
            let mut x = x0.to_vec();
            x[8] = theta.clamp(-179.0, 179.0);
            let value = search.objective(start, &x, faces);
            progress(&search.progress());
            (
                if value.is_finite() {
                    value
                } else {
                    f64::INFINITY
                },
                x,
            )
        };
        let step = half_width / 10.0;
        let mut best = f(self, x0[8]);
        for k in -10..=10 {
            let trial = f(self, x0[8] + f64::from(k) * step);
            if trial.0 < best.0 {
                best = trial;
            }
        }
        let golden = 0.5 * (5f64.sqrt() - 1.0);
        let (mut a, mut b) = (best.1[8] - step, best.1[8] + step);
        let (mut c, mut d) = (b - golden * (b - a), a + golden * (b - a));
        let (mut fc, mut fd) = (f(self, c), f(self, d));
        while b - a > 1e-6 && !self.timed_out {
            if fc.0 < fd.0 {
                (b, d, fd) = (d, c, fc);
                c = b - golden * (b - a);
                fc = f(self, c);
            } else {
                (a, c, fc) = (c, d, fd);
                d = a + golden * (b - a);
                fd = f(self, d);
            }
        }
        for trial in [fc, fd] {
            if trial.0 < best.0 {
                best = trial;
            }
        }
        if best.0.is_finite() {
            best
        } else {
            (f64::NAN, x0.to_vec())
        }
    }
}

/// How near θ must lie to 0° or 180° for [`Search::moulding`] to try the moulding
/// surface or surface of revolution there (degrees).
const MOULDING_THETA: f64 = 5.0;

/// How much larger than the free design's objective that of the moulding surface or
/// surface of revolution may be and be kept ([`Search::moulding`]): on the held-out
/// scans of such surfaces (2 000 points noised by 1e-4) it was 1.08 to 1.43 of theirs,
/// on targets far from that family hundreds of times.
const MOULDING_RATIO: f64 = 1.5;

/// Times [`Search::finer_guides`] refines the guides: from 5 control points to 7, then 11.
const GUIDE_REFINEMENTS: usize = 2;

/// Fewest faces of the mesh along each knot span of a refined guide
/// once refined ([`Search::finer_guides`]): 40 faces take guides of 11 control points
/// (8 spans), 20 of 7 (4 spans).
const FACES_PER_SPAN: usize = 5;

/// New starts of [`Search::theta_restarts`] from each stalled result.
const THETA_RESTARTS: usize = 2;

/// Forward-difference step of the Jacobian, in units of each parameter's scale.
const FD_STEP: f64 = 1e-6;

/// A Levenberg–Marquardt run stops when a step lowers the objective by less than
/// this fraction of it, or by less than [`LM_FLOOR`] squared.
const LM_GAIN: f64 = 1e-4;

/// Relative RMS distance below whose square a step's gain is not worth another
/// Jacobian: an exact target's objective keeps falling by large fractions of itself
/// long after the distances are well under any tolerance.
const LM_FLOOR: f64 = 3e-6;

/// The scale of each parameter (real units), for a target of `size`: the unit in which
/// the least squares moves it (corner, rotation, tilts, θ in degrees, control points).
fn scales(n: usize, size: f64) -> Vec<f64> {
    [0.1 * size; 3]
        .into_iter()
        .chain([0.35; 3])
        .chain([0.8; 2])
        .chain([10.0])
        .chain(std::iter::repeat(0.3 * size))
        .take(n)
        .collect()
}
