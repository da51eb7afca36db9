//! How much disturbance a gait survives (docs/robustness.md): the largest
//! step down it walks on from, and the gait sensitivity norm
//! ([`crate::cycles::gsn`]).
//!
//! **Survives** (docs/model.md §5, "Robustness"): the gait is met by a step
//! down of height `h` when it has settled (the state the flat run ended in,
//! with `stop_when_settled` at a touchdown), the step's edge
//! [`EDGE_AHEAD`]` × L` ahead of its front-most grounded tip; the run from
//! there, on the stepped ground, under the same options for
//! [`SURVIVAL_STEPS`] (20) steps of the flat gait (a step is a new foot's
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
//! one above it failed.

use crate::options::TerrainOptions;
use crate::options::{Options, RobustnessOptions};
use crate::outcome::{Outcome, Robustness};
use crate::params::{Params, Physical};
use crate::plant::rtw::Rtw;
use crate::plant::slots::{DISSIPATED, FRICTION, N};
use crate::run::gait::steps_to_time;
use crate::run::recorder::run_from;
use crate::run::steps_to_fall::steps_to_fall;
use hybrid_ode::Work;

/// The step's edge lies this many rod lengths ahead of the front-most
/// grounded tip of the settled gait: the next foot lands beyond it, and far
/// from the riser.
pub const EDGE_AHEAD: f64 = 0.05;
/// A step down is survived when, this many steps of the flat gait (at its
/// new-foot rate `f_w_newfoot`) after the settled state, the run has not failed
/// and the second half of them has the flat gait's label.
pub const SURVIVAL_STEPS: f64 = 20.0;
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

/// The settled gait of a stable flat run, ready to meet a step.
pub(crate) struct SettledGait<'a> {
    params: &'a Params,
    options: Options,
    phys: &'a Physical,
    rtw: &'a Rtw,
    y: &'a [f64; N],
    flat: &'a Outcome,
    /// Where the ground ahead of the gait starts (m): a step's edge, or the
    /// first rough patch.
    edge: f64,
}

impl SettledGait<'_> {
    /// The run from the settled state on `terrain` under `options`.
    fn run_on(&self, terrain: TerrainOptions, options: &Options, work: &mut Work) -> Outcome {
        let mut sys = self.rtw.clone();
        sys.terrain = terrain;
        // The energy dissipated so far is the flat run's, not this one's.
        let mut y = *self.y;
        y[DISSIPATED] = 0.0;
        y[FRICTION] = 0.0;
        let (o, _, _) = run_from(
            self.params,
            options,
            self.phys,
            sys,
            y,
            self.flat.start,
            Work::default(),
            None,
        );
        *work += o.work;
        o
    }

    /// The run over a step of `h`: its outcome and whether the gait survived.
    pub(crate) fn meet_step(&self, h: f64, work: &mut Work) -> (Outcome, bool) {
        let o = self.run_on(TerrainOptions::step(h, self.edge), &self.options, work);
        (o, o.label == self.flat.label)
    }
}

/// The settled state of a flat run that ended in `rtw`, `y` with outcome
/// `flat`.
pub(crate) fn settled<'a>(
    params: &'a Params,
    options: &Options,
    phys: &'a Physical,
    rtw: &'a Rtw,
    y: &'a [f64; N],
    flat: &'a Outcome,
) -> SettledGait<'a> {
    // Every stable gait has a foot down at a touchdown; a run that ended
    // mid-flight (no early stop) measures from its centre of mass instead.
    let front = rtw
        .front_foot(y)
        .map_or_else(|| rtw.centre_of_mass(y)[0], |(_, x)| x);
    let mut options = *options;
    options.limit_cycle = false;
    options.robustness = RobustnessOptions::default();
    // Judged over `SURVIVAL_STEPS` steps of the flat gait after the edge,
    // the label over their second half; at most the run's own `t_max`.
    options.t_max = steps_to_time(SURVIVAL_STEPS, flat, options.t_max).min(options.t_max);
    options.analysis_window = 0.5;
    SettledGait {
        params,
        options,
        phys,
        rtw,
        y,
        flat,
        edge: front + EDGE_AHEAD * phys.length,
    }
}

/// The largest survivable step down of a settled gait and the failing
/// height just above it (see the module doc).
pub(crate) fn step_down_max(s: &SettledGait<'_>, work: &mut Work) -> (f64, Option<f64>) {
    let length = s.phys.length;
    let (mut lo, mut hi) = (0.0, STEP_DOWN_START * length);
    loop {
        if !s.meet_step(hi, work).1 {
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
        if s.meet_step(mid, work).1 {
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
    let gsn = options.robustness.gsn.then(|| {
        crate::cycles::gsn::settled_cycle(params, options, rtw, y, &mut work)
            .map_or(f64::NAN, |(map, orbit)| {
                crate::cycles::gsn::gsn(&map, &orbit, EDGE_AHEAD)
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
    let mfpt = options.robustness.mfpt.then(|| {
        let settled = crate::run::mfpt::Settled {
            params: s.params,
            options: s.options,
            phys: s.phys,
            rtw: s.rtw,
            y: s.y,
            flat: s.flat,
            edge: s.edge,
        };
        crate::run::mfpt::mean_first_passage(
            &settled,
            &options.robustness,
            options.terrain,
            &mut work,
        )
    });
    Robustness {
        asked: options.robustness,
        step_down_max,
        step_down_fail,
        gsn,
        steps_to_fall,
        mfpt,
        work,
    }
}

/// A stable gait's settled state met by a step of `h` (m): the outcome of
/// the run over it and whether it survived (see the module doc). `None`
/// when the flat run is not a stable gait.
#[cfg(test)]
pub(crate) fn meet_step(params: &Params, options: &Options, h: f64) -> Option<(Outcome, bool)> {
    let mut flat_options = *options;
    flat_options.robustness = RobustnessOptions::default();
    crate::run::recorder::with_end_state(params, &flat_options, |phys, rtw, y, flat| {
        flat.label.is_stable().then(|| {
            settled(params, options, phys, rtw, y, flat).meet_step(h, &mut Work::default())
        })
    })
    .flatten()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::outcome::Label;
    use crate::run::recorder::with_end_state;

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
}
