//! # rtw-model
//!
//! The 9-DOF hybrid model of the rimless wheel-like tensegrity (RTW) of Zheng,
//! Asano, Yan, Li and Tokuda, as specified in the project's `docs/model.md`: three
//! rods joined by six Kelvin–Voigt strings, rolling down a slope, with per-rod
//! contact modes (free, stick, slide), inelastic touchdowns and lift-offs.
//! It runs on the generic engine of the `hybrid-ode` crate.
//!
//! Map of the crate, by layer (each uses only the ones above it):
//!
//! | module | what it holds |
//! |---|---|
//! | [`params`] | normalized inputs (L, ρ, α, f_n, ζ, φ), their names and ranges ([`Param`]) → physical (m, l_c, I, r, k, c) |
//! | [`options`] | every modelling and numerical choice, with the adopted defaults (docs/model.md §9) |
//! | [`outcome`] | what a run produces: label, failure, metrics, and the gait-labelling rule |
//! | [`plant`] | the RTW as a hybrid system: geometry, strings, contact, state slots, the system, its start |
//! | [`cycles`] | the step map on the section at each new foot's touchdown, limit cycles, Floquet multipliers |
//! | [`run`](mod@run) | `simulate(params, options) -> Outcome`: the plant run with its recorder |
//! | [`modal`] | eigen-frequencies of the approximate and of the full model |
//!
//! The crate does no I/O.
#![warn(missing_docs)]

pub mod cycles;
pub mod modal;
pub mod options;
pub mod outcome;
pub mod params;
pub mod plant;
pub mod run;

pub use options::{Method, Options};
pub use outcome::{CycleSummary, Label, Outcome, TraceSample};
pub use params::{Normalization, Num, Param, ParamError, Params, Physical};
pub use run::simulate::{simulate, simulate_traced};
