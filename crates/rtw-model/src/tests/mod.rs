//! Tests of the crate's internals (the plant, its start, the modal
//! analysis's closed forms): they reach items that are not public, so they
//! live inside the crate. Tests of the public API are in `tests/`.

mod basin;
mod cancel;
mod crossings_inside_a_step;
mod limit_cycle;
mod modal;
mod nonsmooth_rtw;
mod physics;
mod rimless_step;
mod standing;
mod step_down;

/// A paper-scan skip (sample 12 of configs/paper.toml) that touches down
/// twice per step: its new foot lands, lifts in flight and lands again. For
/// the tests where a step (a new foot's touchdown) and a touchdown differ.
pub(crate) fn two_touchdown_skip() -> crate::Params {
    crate::Params::new(
        0.8,
        4.654368528507514,
        0.06339175109104485,
        3.6230217333128656,
        0.07319035141659881,
        0.1656710566088282,
    )
    .unwrap()
}

/// A paper-scan skip (sample 432 of configs/paper.toml): period 2, largest
/// multiplier 0.91, where differences of the step map at 1e-6 of each
/// coordinate's scale moved with the orbit (the GSN's and the Floquet
/// column's tests).
pub(crate) fn skip_432() -> crate::Params {
    crate::Params::new(
        0.8,
        4.64144786287552,
        0.35886037492879574,
        2.4815671963934145,
        0.09085796739355585,
        0.22783845008492798,
    )
    .unwrap()
}
