//! # rtw-model
//!
//! The 9-DOF hybrid model of the rimless wheel-like tensegrity (RTW) of Zheng,
//! Asano, Yan, Li and Tokuda, as specified in the project's `docs/model.md`: three
//! rods joined by six Kelvin–Voigt strings, rolling down a slope, with per-rod
//! contact modes (free, stick, slide), inelastic touchdowns and lift-offs.
//! It runs on the generic engine of the `hybrid-ode` crate.
//!
//! The public API: [`simulate`] (and [`simulate_traced`]) runs one design
//! ([`Params`], turned into [`Physical`] constants) with its [`Options`] and
//! returns an [`Outcome`] with its [`Label`]; [`cycles`] holds the step map,
//! its limit cycles and their continuation; [`modal`] the eigen-frequencies.
//!
//! Map of the crate, by layer (each uses only the ones above it; the private
//! modules are named in code font):
//!
//! | module | what it holds |
//! |---|---|
//! | `cancel` ([`cancellable`]) | a stop flag that ends every run of a computation at its next step end |
//! | `params` | normalized inputs (L, ρ, α, f_n, ζ, φ), their names and ranges ([`Param`]) → physical (m, l_c, I, r, k, c) |
//! | [`options`] | every modelling and numerical choice, with the adopted defaults (docs/model.md §9) |
//! | [`outcome`] | what a run produces: label, failure, metrics, and the gait-labelling rule |
//! | `plant` | the RTW as a hybrid system: geometry, strings, contact ([`RodMode`]), state slots, the system, its start |
//! | [`cycles`] | the step map on the section at each new foot's touchdown, limit cycles, Floquet multipliers |
//! | `run` | [`simulate`]: the plant run with its recorder |
//! | [`modal`] | eigen-frequencies of the approximate and of the full model |
//!
//! The tests of the private modules are in the crate (`src/tests/` and each
//! file's `tests` module); `tests/` holds the tests of the public API.
//!
//! The crate does no I/O.
#![warn(missing_docs)]

mod cancel;
pub mod cycles;
pub mod modal;
pub mod options;
pub mod outcome;
mod params;
// The plant's internals are public only for the criterion bench of the hot
// path (`--features internals`); they are not part of the library's API.
#[cfg(feature = "internals")]
pub mod plant;
#[cfg(not(feature = "internals"))]
mod plant;
mod run;

#[cfg(test)]
mod tests;

// hybrid-ode's own item, documented (and counted) there.
pub use cancel::cancellable;
#[doc(no_inline)]
pub use options::Method;
pub use options::Options;
pub use outcome::{CycleSummary, Label, Outcome, TraceSample};
pub use params::{Normalization, Num, Param, ParamError, Params, Physical};
pub use plant::contact::RodMode;
pub use plant::geometry::Tip;
/// The star's geometry for drawings: spoke order, strings, tips and connection points.
pub use plant::geometry::{SPOKES, STRINGS, Vec2, spoke_points};
pub use plant::rtw::GuardKind;
pub use run::simulate::{simulate, simulate_traced};
