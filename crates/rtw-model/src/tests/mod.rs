//! Tests of the crate's internals (the plant, its start, the modal
//! analysis's closed forms): they reach items that are not public, so they
//! live inside the crate. Tests of the public API are in `tests/`.

mod basin;
mod crossings_inside_a_step;
mod limit_cycle;
mod modal;
mod nonsmooth_rtw;
mod physics;
mod rimless_step;
mod standing;
mod step_down;
