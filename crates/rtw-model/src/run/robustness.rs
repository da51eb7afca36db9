//! How much disturbance a gait survives (docs/robustness.md): the largest
//! step down it walks on from, and the gait sensitivity norm
//! ([`crate::cycles::robustness::gsn`]).
//!
//! **Survives** (docs/model.md §5, "Robustness"): the gait is met by a step
//! down of height `h` when it has settled (the state the flat run ended in,
//! with `stop_when_settled` at a touchdown), the step's edge
//! [`EDGE_AHEAD`]` × L` ahead of its front-most grounded tip; the run from
//! there, on the stepped ground, under the same options for
//! [`SURVIVAL_STEPS`](crate::run::settled::SURVIVAL_STEPS) (20) steps of the flat gait (a step is a new foot's
//! touchdown: `20 / f_w_newfoot` seconds, at most `t_max`), must
//! not fail and must have the flat gait's label over the second half of
//! them (`analysis_window = 0.5`). Anything else (a collapse, a trip on the
//! riser, a stall, another gait, or still hopping ten steps after the drop)
//! fails.
//!
//! **Largest survivable step down** (`step_down_max`, m): the heights
//! `h = 0.05 L · 1.25ᵏ` are tried from below until one fails (at most
//! [`STEP_DOWN_CAP`]` × L`, reported as the cap when even it survives), then
//! the last survivor and the first failure are bisected until they are
//! within [`STEP_DOWN_RTOL`] of the survivor or [`STEP_DOWN_ATOL`]` × L`,
//! whichever is larger; the survivor is reported. Survival is not monotone
//! in `h` for large drops (at Fig. 7(a) the walk survives every step up to
//! 2.6 m, and then 2.8 m and 3.0–3.4 m but not 2.7 or 2.9 m: how a star lands
//! from a large drop is chaotic), so the ladder climbs from below in
//! steps of 1.25: every rung below the reported height survived, the first
//! one above it failed. It is the **best phase**: the edge
//! [`EDGE_AHEAD`]` × L` ahead of the front-most grounded tip, where the next
//! foot lands beyond it.
//!
//! **Step down over every phase** (`step_down_h50`, m): the height at which
//! half of the edge positions spread over one step of the gait survive. The
//! edge lies `(i + ½) ℓ / `[`H50_POSITIONS`] ahead of the front-most grounded
//! tip, `i = 0 … 19`, with `ℓ = speed / f_w_newfoot` the flat gait's step
//! length (a uniform edge position within one step, in 20 strata); the
//! survival probability `S(h)` is the share of them that survive `h`. The
//! heights are bracketed as for `step_down_max`: the ladder
//! `0.05 L · 1.25ᵏ` from below until `S(h) < ½`, then bisection to the same
//! tolerance; the last height with `S ≥ ½` is reported (0 when even the first
//! rung, bisected down to `STEP_DOWN_ATOL × L`, has `S < ½`).

use crate::options::TerrainOptions;
use crate::options::{MfptMethod, Options};
use crate::outcome::{Label, Outcome, PhaseSurvival, Robustness};
use crate::params::{Params, Physical};
use crate::plant::rtw::Rtw;
use crate::plant::slots::N;
use crate::run::settled::{EDGE_AHEAD, SettledGait, settled};
use crate::run::steps_to_fall::steps_to_fall;
use hybrid_ode::Work;

/// The first height tried, in rod lengths.
pub const STEP_DOWN_START: f64 = 0.05;
/// Each height tried is this many times the last, until one fails.
pub const STEP_DOWN_RATIO: f64 = 1.25;
/// The largest height tried, in rod lengths.
pub const STEP_DOWN_CAP: f64 = 16.0;
/// Bisection stops within this fraction of the survivor …
pub const STEP_DOWN_RTOL: f64 = 0.05;
/// … or this many rod lengths, whichever is larger.
pub const STEP_DOWN_ATOL: f64 = 1e-3;
/// Edge positions over one step of the gait per height of `step_down_h50`.
pub const H50_POSITIONS: usize = 20;

impl SettledGait<'_> {
    /// The run over a step of `h`: its outcome and whether the gait survived.
    pub(crate) fn meet_step(&self, h: f64, work: &mut Work) -> (Outcome, bool) {
        self.meet_step_at(h, self.edge, work)
    }

    /// [`meet_step`](Self::meet_step) with the edge at `edge` (m).
    fn meet_step_at(&self, h: f64, edge: f64, work: &mut Work) -> (Outcome, bool) {
        let o = self.run_on(TerrainOptions::step(h, edge), &self.options, work);
        (o, o.label == self.flat.label)
    }

    /// Edge position `i` of `step_down_h50` (m): stratum `i` of
    /// [`H50_POSITIONS`] of a uniform position over one step of the gait
    /// (module doc).
    fn phase_edge(&self, i: usize) -> f64 {
        let step = self.flat.speed.abs() / self.flat.f_w_newfoot;
        let step = if step.is_finite() && step > 0.0 {
            step
        } else {
            self.phys.length
        };
        let u = (i as f64 + 0.5) / H50_POSITIONS as f64;
        self.front + u * step
    }

    /// The runs over a step of `h` with its edge at each of the
    /// [`H50_POSITIONS`] positions over one step of the gait (module doc).
    pub(crate) fn over_every_phase(&self, h: f64, work: &mut Work) -> Vec<(Outcome, bool)> {
        (0..H50_POSITIONS)
            .map(|i| self.meet_step_at(h, self.phase_edge(i), work))
            .collect()
    }

    /// How the gait meets a step of `h` at each of the [`H50_POSITIONS`]
    /// edge positions over one step: the shares that survive and that fail
    /// by each kind (a point of the survival curve).
    pub(crate) fn survival_at(&self, h: f64, work: &mut Work) -> PhaseSurvival {
        // Counted, then divided: each share is exactly k / 20.
        let mut count = [0u32; 5];
        for (o, survived) in self.over_every_phase(h, work) {
            count[match o.label {
                _ if survived => 0,
                Label::Collapse => 1,
                Label::Stall => 2,
                Label::Skip | Label::Walk | Label::Crawl => 3,
                Label::Diverged => 4,
            }] += 1;
        }
        let share = |k: usize| f64::from(count[k]) / H50_POSITIONS as f64;
        PhaseSurvival {
            survived: share(0),
            collapse: share(1),
            stall: share(2),
            other_gait: share(3),
            diverged: share(4),
        }
    }

    /// Do at least half of the edge positions survive a step of `h`? The
    /// runs stop once the answer is known (ten survivors, or eleven
    /// failures, of twenty): a height the gait survives at every phase
    /// costs half the runs, with the same answer.
    fn half_survive(&self, h: f64, work: &mut Work) -> bool {
        at_least_half(H50_POSITIONS, |i| {
            self.meet_step_at(h, self.phase_edge(i), work).1
        })
    }
}

/// Whether at least half of `n` trials pass (`2 · passed ≥ n`), asking
/// `passes(i)` for `i = 0, 1, …` only until the answer is known.
fn at_least_half(n: usize, mut passes: impl FnMut(usize) -> bool) -> bool {
    let need = n.div_ceil(2);
    let (mut passed, mut failed) = (0, 0);
    for i in 0..n {
        if passed >= need || failed > n - need {
            break;
        }
        if passes(i) {
            passed += 1;
        } else {
            failed += 1;
        }
    }
    passed >= need
}

/// The largest survivable step down of a settled gait and the failing
/// height just above it (see the module doc).
pub(crate) fn step_down_max(s: &SettledGait<'_>, work: &mut Work) -> (f64, Option<f64>) {
    largest_height(s.phys.length, |h| s.meet_step(h, work).1)
}

/// The largest height that `survives` on the ladder from below, bisected
/// against the first that does not (the module doc), and that first
/// failure (`None` when even the cap survived).
fn largest_height(length: f64, mut survives: impl FnMut(f64) -> bool) -> (f64, Option<f64>) {
    let (mut lo, mut hi) = (0.0, STEP_DOWN_START * length);
    loop {
        if !survives(hi) {
            break;
        }
        lo = hi;
        if hi >= STEP_DOWN_CAP * length {
            return (lo, None);
        }
        hi = (STEP_DOWN_RATIO * hi).min(STEP_DOWN_CAP * length);
    }
    while hi - lo > (STEP_DOWN_RTOL * lo).max(STEP_DOWN_ATOL * length) {
        let mid = 0.5 * (lo + hi);
        if survives(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    (lo, Some(hi))
}

/// The measures `options.robustness` asks for, of the stable flat run that
/// ended in `rtw`, `y` with outcome `flat`.
pub(crate) fn measure(
    params: &Params,
    options: &Options,
    phys: &Physical,
    rtw: &Rtw,
    y: &[f64; N],
    flat: &Outcome,
) -> Robustness {
    let s = settled(params, options, phys, rtw, y, flat);
    let mut work = Work::default();
    let (step_down_max, step_down_fail) = match options.robustness.step_down {
        true => {
            let (max, fail) = step_down_max(&s, &mut work);
            (Some(max), fail)
        }
        false => (None, None),
    };
    let step_down_h50 = options
        .robustness
        .step_down_h50
        .then(|| largest_height(phys.length, |h| s.half_survive(h, &mut work)).0);
    let step_down_at = (options.robustness.step_down_at > 0.0)
        .then(|| s.survival_at(options.robustness.step_down_at, &mut work));
    let gsn = options.robustness.gsn.then(|| {
        crate::cycles::robustness::gsn::settled_cycle(params, options, rtw, y, &mut work)
            .map_or(f64::NAN, |(map, orbit)| {
                crate::cycles::robustness::gsn::gsn(&map, &orbit, EDGE_AHEAD)
            })
    });
    let steps_to_fall = options.robustness.steps_to_fall.then(|| {
        steps_to_fall(
            |ground, o| s.run_on(ground, o, &mut work),
            flat,
            options.t_max,
            s.edge,
            &s.options,
            &options.robustness,
            options.terrain,
        )
    });
    // None also when the stop flag cut it (the result is then refused).
    let (mfpt, mfpt_chain) = match (options.robustness.mfpt, options.robustness.mfpt_method) {
        (false, _) => (None, None),
        (true, MfptMethod::Chain) => crate::run::mfpt_chain::chain_first_passage(
            &s,
            &options.robustness,
            options.terrain,
            &mut work,
        )
        .map_or((None, None), |(m, d)| (Some(m), Some(d))),
        (true, MfptMethod::Splitting) => (
            crate::run::mfpt_splitting::mean_first_passage_splitting(
                &s,
                &options.robustness,
                options.terrain,
                &mut work,
            )
            .map(|m| m.mean_first_passage()),
            None,
        ),
        (true, MfptMethod::Counted) => (
            crate::run::mfpt::mean_first_passage(
                &s,
                &options.robustness,
                options.terrain,
                &mut work,
            ),
            None,
        ),
    };
    Robustness {
        asked: options.robustness,
        step_down_max,
        step_down_fail,
        step_down_h50,
        step_down_at,
        gsn,
        steps_to_fall,
        mfpt,
        mfpt_chain,
        work,
    }
}

/// A stable gait's settled state met by a step of `h` (m): the outcome of
/// the run over it and whether it survived (see the module doc). `None`
/// when the flat run is not a stable gait.
#[cfg(test)]
pub(crate) fn meet_step(params: &Params, options: &Options, h: f64) -> Option<(Outcome, bool)> {
    let mut flat_options = *options;
    flat_options.robustness = crate::options::RobustnessOptions::default();
    crate::run::recorder::with_end_state(params, &flat_options, |phys, rtw, y, flat| {
        flat.label.is_stable().then(|| {
            settled(params, options, phys, rtw, y, flat).meet_step(h, &mut Work::default())
        })
    })
    .flatten()
}

/// A stable gait's settled state met by a step of `h` (m) at every edge
/// position of `step_down_h50`: each run's outcome and whether it survived;
/// and the gait's `step_down_h50` with the failing height just above it.
/// `None` when the flat run is not a stable gait.
#[cfg(test)]
#[allow(clippy::type_complexity)]
pub(crate) fn every_phase(
    params: &Params,
    options: &Options,
    heights: &[f64],
) -> Option<(Vec<Vec<(Outcome, bool)>>, (f64, Option<f64>))> {
    let mut flat_options = *options;
    flat_options.robustness = crate::options::RobustnessOptions::default();
    crate::run::recorder::with_end_state(params, &flat_options, |phys, rtw, y, flat| {
        flat.label.is_stable().then(|| {
            let s = settled(params, options, phys, rtw, y, flat);
            let mut work = Work::default();
            let runs = heights
                .iter()
                .map(|&h| s.over_every_phase(h, &mut work))
                .collect();
            let h50 = largest_height(phys.length, |h| s.half_survive(h, &mut work));
            (runs, h50)
        })
    })
    .flatten()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::run::recorder::with_end_state;
    use crate::run::settled::SURVIVAL_STEPS;

    /// A step is a new foot's touchdown (docs/model.md, the step map's
    /// section), not any touchdown: the window a step down is judged over
    /// must hold `SURVIVAL_STEPS` steps of the flat gait, counted in the run
    /// itself, however often a skip bounces within a step. Timed by the
    /// touchdown rate `f_w`, this skip's window held only half of them.
    #[test]
    fn the_survival_window_holds_its_steps_in_new_feet_for_a_skip() {
        let p = crate::tests::two_touchdown_skip();
        let o = Options::default();
        with_end_state(&p, &o, |phys, rtw, y, flat| {
            assert_eq!(flat.label, Label::Skip);
            assert!(flat.f_w > 1.9 * flat.f_w_newfoot, "{flat:?}");
            let s = settled(&p, &o, phys, rtw, y, flat);
            // The same window on the flat slope, every step of it counted.
            let whole = Options {
                analysis_window: 1.0,
                stop_when_settled: false,
                ..s.options
            };
            let run = s.run_on(TerrainOptions::default(), &whole, &mut Work::default());
            assert_eq!(run.label, Label::Skip);
            let steps = run.step_shares.steps as f64;
            assert!(
                (steps - SURVIVAL_STEPS).abs() <= 1.0,
                "{steps} steps in a window of {} s",
                whole.t_max
            );
        })
        .unwrap();
    }

    /// `step_down_h50`'s test of a height stops its runs once the answer is
    /// known; the answer must be the full count's, `2 · passed ≥ n`, for
    /// every pattern of passes, and no trial may be asked for after it is
    /// known (nor one skipped before). Every pattern of up to 12 trials,
    /// and random ones of the 20 positions.
    #[test]
    fn half_of_the_trials_stops_when_the_answer_is_known_and_gives_the_full_counts() {
        let check = |n: usize, pattern: &dyn Fn(usize) -> bool| {
            let full = 2 * (0..n).filter(|&i| pattern(i)).count() >= n;
            let mut asked = Vec::new();
            let answer = at_least_half(n, |i| {
                asked.push(i);
                pattern(i)
            });
            assert_eq!(answer, full, "n = {n}");
            assert_eq!(asked, (0..asked.len()).collect::<Vec<_>>(), "n = {n}");
            // Known after the trials asked, and not before the last of them.
            let known = |k: usize| {
                let passed = (0..k).filter(|&i| pattern(i)).count();
                2 * passed >= n || 2 * (passed + n - k) < n
            };
            assert!(
                known(asked.len()),
                "n = {n}: stopped before the answer was known"
            );
            if let Some(k) = asked.len().checked_sub(1) {
                assert!(
                    !known(k),
                    "n = {n}: asked trial {k} after the answer was known"
                );
            }
        };
        for n in 0..=12 {
            for bits in 0u32..1 << n {
                check(n, &|i| bits >> i & 1 == 1);
            }
        }
        let mut rng = hybrid_ode::metastable::Rng::new(7);
        for _ in 0..2000 {
            let bits = rng.next_u64();
            check(H50_POSITIONS, &|i| bits >> i & 1 == 1);
        }
    }
}
