#![doc = include_str!("../README.md")]
#![warn(missing_docs)]

pub mod chain;
pub mod continuation;
// The test fixtures (`counting`, `rimless`, `kernels`) are compiled in every
// build, hidden from the docs, rather than behind a feature the tests turn
// on: a feature only the tests ask for makes `cargo test` build this crate
// and every crate above it a second time (docs/testing.md, "Build times").
#[doc(hidden)]
pub mod counting;
mod dense;
mod engine;
mod events;
mod integrate;
pub mod limit;
pub mod logistic;
pub mod metastable;
pub mod nonsmooth;
#[doc(hidden)]
pub mod rimless;
pub mod splitting;
pub mod system;
mod tableau;
mod variational;

/// The one-step kernels of the integrators, outside the engine: for the
/// integrator's own tests (order, dense output) and the model's benches.
/// Not part of the engine's API.
#[doc(hidden)]
pub mod kernels {
    pub use crate::integrate::{fixed_step_solve, step_with_dense};
}

pub use dense::Dense;
pub use engine::{EndReason, EngineOptions, RunEnd, Work, run};
pub use integrate::Method;
pub use system::{Crossing, EndsRun, Flow, Guards, HybridSystem, Observer, StepEnd};
pub use variational::Variational;
