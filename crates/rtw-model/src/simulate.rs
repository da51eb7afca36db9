//! `simulate(params, options) -> Outcome`.

use crate::{Options, Outcome, Params, TraceSample};

/// Simulates one RTW run.
///
/// # Panics
/// If `params` or `options` are invalid (call their `validate` first).
pub fn simulate(params: &Params, options: &Options) -> Outcome {
    simulate_traced(params, options, &mut |_| {})
}

/// [`simulate`], calling `trace` with the state at every step end (or every
/// `options.trace_dt` seconds).
pub fn simulate_traced(
    params: &Params,
    options: &Options,
    trace: &mut dyn FnMut(&TraceSample),
) -> Outcome {
    let _ = (params, options, trace);
    todo!("in progress")
}
