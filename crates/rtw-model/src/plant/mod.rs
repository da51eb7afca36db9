//! The plant: the RTW as a hybrid system, from its parts to its start.
//!
//! | module | what it computes |
//! |---|---|
//! | [`geometry`] | rods, tips, connection points, the rest star |
//! | [`strings`] | the hexagon of strings: forces, potential, dissipation |
//! | [`contact`] | per-rod modes: free / stick / slide dynamics, λ, impacts, mode choice |
//! | [`slots`] | the state vector's layout, named slot by slot |
//! | [`rtw`] | the RTW as a [`HybridSystem`](hybrid_ode::HybridSystem): dynamics, guards, resets |
//! | [`terrain`] | the ground: the flat slope, a step down, or the rough slope |
//! | [`face`] | a tip against a face of the ground: its impact, the wall slide, the corner |
//! | [`initial`] | the initial state (rigid star, static equilibrium, or set down and settled) |

pub mod contact;
pub mod face;
pub mod geometry;
pub mod initial;
pub mod rtw;
pub mod slots;
pub mod strings;
pub mod terrain;
