//! `simulate(params, options) -> Outcome`: one run of the RTW (the run and
//! its `Recorder`, recorder.rs), with the robustness measures the options ask
//! for (robustness.rs) added to a stable gait's outcome.

use crate::options::Options;
use crate::outcome::Robustness;
use crate::outcome::{Outcome, TraceSample};
use crate::params::Params;
use crate::run::recorder::start_and_run;
use crate::run::robustness::measure;

/// Simulates one RTW run.
///
/// # Panics
/// If `params` or `options` are invalid (call their `validate` first).
pub fn simulate(params: &Params, options: &Options) -> Outcome {
    simulate_inner(params, options, None)
}

/// [`simulate`], calling `trace` with the state at every step end, event and
/// the start (or every `options.trace_dt` seconds).
pub fn simulate_traced(
    params: &Params,
    options: &Options,
    trace: &mut dyn FnMut(&TraceSample),
) -> Outcome {
    simulate_inner(params, options, Some(trace))
}

fn simulate_inner(
    params: &Params,
    options: &Options,
    trace: Option<&mut dyn FnMut(&TraceSample)>,
) -> Outcome {
    let (phys, ended) = start_and_run(params, options, trace);
    match ended {
        Ok((mut outcome, rtw, y)) => {
            if !options.robustness.is_off() {
                outcome.robustness = Some(match outcome.label.is_stable() {
                    true => measure(params, options, &phys, &rtw, &y, &outcome),
                    false => Robustness {
                        asked: options.robustness,
                        ..Default::default()
                    },
                });
            }
            outcome
        }
        Err(failed) => failed,
    }
}
