#![doc = include_str!("../README.md")]
#![warn(missing_docs)]

pub mod continuation;
pub mod counting;
pub mod dense;
pub mod engine;
mod events;
pub mod integrate;
pub mod limit;
pub mod nonsmooth;
pub mod rimless;
pub mod system;
mod tableau;
pub mod variational;

pub use dense::Dense;
pub use engine::{EndReason, EngineOptions, RunEnd, Work, run};
pub use integrate::Method;
pub use system::{Crossing, EndsRun, Flow, Guards, HybridSystem, Observer, StepEnd};
pub use variational::Variational;
