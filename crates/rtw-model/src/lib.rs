//! # rtw-model
//!
//! The 9-DOF hybrid model of the rimless wheel-like tensegrity (RTW) of Zheng,
//! Asano, Yan, Li and Tokuda, as specified in the project's `docs/model.md`: three
//! rods joined by six Kelvin–Voigt strings, rolling down a slope, with per-rod
//! contact modes (free, stick, slide), inelastic touchdowns and lift-offs.
//!
//! Map of the crate, in the order a run uses it:
//!
//! | module | what it computes |
//! |---|---|
//! | [`params`] | normalized inputs (L, ρ, α, f_n, ζ, φ) → physical (m, l_c, I, r, k, c) |
//! | [`options`] | every modelling and numerical choice, with the adopted defaults (docs/model.md §9) |
//! | [`geometry`] | rods, tips, connection points, the rest star |
//! | [`strings`] | the hexagon of strings: forces, potential, dissipation |
//! | [`contact`] | per-rod modes: free / stick / slide dynamics, λ, impacts, mode choice |
//! | [`rtw`] | the RTW as a [`hybrid::HybridSystem`]: dynamics, guards, resets |
//! | [`initial`] | the initial state (rigid star or static equilibrium) |
//! | [`gait`] | statistics over the window and the gait label |
//! | [`simulate`](mod@simulate) | `simulate(params, options) -> Outcome` |
//! | [`integrate`], [`hybrid`] | Runge–Kutta with dense output; the generic event-driven engine |
//! | [`rimless`] | McGeer's rimless wheel on the same engine (a closed-form check) |
//! | [`variational`] | sensitivities `∂y/∂y₀` through flows, impacts and mode switches |
//! | [`stepmap`] | the step map at each new foot's touchdown, reduced by the 60° symmetry |
//! | [`limit`] | fixed points by Newton, Floquet multipliers (any return map) |
//! | [`continuation`] | branches of fixed points in a parameter, their bifurcations, curves of them in two |
//! | [`modal`] | eigen-frequencies of the approximate and of the full model |
//!
//! The crate does no I/O.

pub mod contact;
pub mod continuation;
pub mod gait;
pub mod geometry;
pub mod hybrid;
pub mod initial;
pub mod integrate;
pub mod limit;
pub mod modal;
pub mod options;
pub mod outcome;
pub mod params;
pub mod rimless;
pub mod rtw;
pub mod simulate;
pub mod stepmap;
pub mod strings;
pub mod variational;

pub use options::Options;
pub use outcome::{CycleSummary, Label, Outcome, TraceSample};
pub use params::{Normalization, ParamError, Params, Physical};
pub use simulate::{simulate, simulate_traced};
