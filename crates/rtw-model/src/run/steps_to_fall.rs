//! Mean steps to fall on a rough slope (docs/robustness-rough.md), Byl and
//! Tedrake's mean first-passage time by Monte Carlo.
//!
//! The settled gait (the state its stable flat run ended in, as for the
//! step down) walks onto a rough slope ([`TerrainOptions::rough`]) whose
//! first patch starts `EDGE_AHEAD × L` (robustness.rs) ahead of its
//! front-most grounded tip, patches `terrain.patch` long with
//! heights from N(0, σ²), σ = `robustness.sigma`. Trial `i` (of
//! `robustness.trials`) has seed `terrain.seed + i`. It runs for
//! `robustness.max_steps` steps of the flat gait (a step is a new foot's
//! touchdown: `max_steps / f_w_newfoot` seconds, never stopped early as
//! settled); a trial **falls** when its run ends in
//! anything but a stable gait (collapse, a trip on a riser, a stall or a
//! numerical failure), and its steps to fall are `f_w_newfoot × t_end`, the
//! steps the flat gait would have taken by then. A trial that has not
//! fallen is censored at `max_steps`.

use crate::options::{Options, RobustnessOptions, TerrainOptions};
use crate::outcome::{Outcome, StepsToFall};
use crate::run::gait::steps_to_time;

/// Two-sided 95 % quantile of the standard normal.
const Z95: f64 = 1.959_963_984_540_054;

/// The steps to fall of the settled gait of the flat run `flat` (judged
/// over `t_max`) whose
/// ground ahead starts at `edge`, over `r.trials` rough grounds of
/// roughness `r.sigma` with `terrain`'s seed and patch length; `run_on`
/// runs it from its settled state on a ground under options (the step
/// down's runner, robustness.rs).
pub(crate) fn steps_to_fall(
    mut run_on: impl FnMut(TerrainOptions, &Options) -> Outcome,
    flat: &Outcome,
    t_max: f64,
    edge: f64,
    settled_options: &Options,
    r: &RobustnessOptions,
    terrain: TerrainOptions,
) -> StepsToFall {
    let max_steps = f64::from(r.max_steps);
    let t_trial = steps_to_time(max_steps, flat, t_max);
    let options = Options {
        t_max: t_trial,
        stop_when_settled: false,
        max_steps: trial_work_budget(settled_options.max_steps, t_trial, t_max),
        ..*settled_options
    };
    let steps: Vec<f64> = (0..r.trials)
        .map(|i| {
            let ground = TerrainOptions::rough(
                r.sigma,
                terrain.seed.wrapping_add(u64::from(i)),
                edge,
                terrain.patch,
            );
            let o = run_on(ground, &options);
            if o.label.is_stable() {
                max_steps
            } else {
                (flat.f_w_newfoot * o.t_end).min(max_steps)
            }
        })
        .collect();
    summarize(&steps, max_steps)
}

/// The work budget of a trial of `t_trial` seconds: `max_steps` is sized
/// for the flat run of `t_max`, and a trial many times longer gets as much
/// per second of the run, so that its length alone never ends it as
/// diverged (and counts as a fall). With the default budget a trial of
/// Fig. 7(a) ran out of it after about 2.4 × 10⁵ steps of the gait.
/// (`t_max > 0`, as `Options::validate` requires.)
fn trial_work_budget(max_steps: u64, t_trial: f64, t_max: f64) -> u64 {
    // `as` saturates at u64::MAX.
    (max_steps as f64 * (t_trial / t_max).max(1.0)).ceil() as u64
}

/// The censored mean of `steps` (each at most `max_steps`), its normal 95 %
/// interval and how many were censored.
fn summarize(steps: &[f64], max_steps: f64) -> StepsToFall {
    let n = steps.len() as f64;
    let mean = steps.iter().sum::<f64>() / n;
    let var = steps.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    let half = Z95 * (var / n).sqrt();
    StepsToFall {
        mean,
        lo: (mean - half).max(0.0),
        hi: mean + half,
        censored: steps.iter().filter(|&&v| v >= max_steps).count() as u32,
        trials: steps.len() as u32,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_trial_s_work_budget_grows_with_its_length_and_never_shrinks() {
        assert_eq!(trial_work_budget(5_000_000, 60.0, 60.0), 5_000_000);
        assert_eq!(trial_work_budget(5_000_000, 30.0, 60.0), 5_000_000);
        assert_eq!(trial_work_budget(5_000_000, 6000.0, 60.0), 500_000_000);
        assert_eq!(trial_work_budget(u64::MAX, 1e9, 1.0), u64::MAX);
    }

    #[test]
    fn the_summary_is_the_censored_mean_with_a_normal_interval() {
        let s = summarize(&[2.0, 4.0, 10.0, 10.0], 10.0);
        assert_eq!(s.mean, 6.5);
        assert_eq!((s.censored, s.trials), (2, 4));
        // Sample standard deviation 4.123, standard error 2.062.
        let half = Z95 * (17.0f64 / 4.0).sqrt();
        assert!((s.hi - 6.5 - half).abs() < 1e-12 && (6.5 - s.lo - half).abs() < 1e-12);
        let all = summarize(&[10.0; 3], 10.0);
        assert_eq!(
            (all.mean, all.lo, all.hi, all.censored),
            (10.0, 10.0, 10.0, 3)
        );
    }
}
