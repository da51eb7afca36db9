//! The RTW as a hybrid system (docs/model.md §2–§5): continuous dynamics of the
//! three rods in their contact modes, the guards that end a mode, and the
//! resets (touchdown, lift-off, re-stick, slip, failure).
//!
//! State: three rods × six slots and two dissipated energies
//! ([`crate::plant::slots`]). [`Rtw`] is the one [`HybridSystem`](hybrid_ode::HybridSystem)
//! of the model; what a run records is its observer's business
//! ([`crate::run::simulate`], [`crate::cycles::map::stepmap`],
//! [`crate::plant::initial`]'s settling).
//!
//! | file | what it holds |
//! |---|---|
//! | `model.rs` | [`Rtw`], its constants and modes, and the types its guards and resets speak |
//! | `dynamics.rs` | loads and the continuous dynamics `ẏ = f(y)` with the contact forces λ |
//! | `guards.rs` | the guards of the current modes, their values and kinematic rates |
//! | `resets.rs` | the resets: touchdown and the re-choice of a grounded rod's mode |
//! | `diagnostics.rs` | what observers read: friction ratio, energy, centre of mass, contact counts |
//! | `hybrid.rs` | [`Rtw`] as a [`HybridSystem`](hybrid_ode::HybridSystem), from the pieces above |
//!
//! Each file imports only `model.rs` (and modules outside `plant::rtw`), so
//! none imports another that imports it back.

mod diagnostics;
mod dynamics;
mod guards;
mod hybrid;
mod model;
mod resets;

pub(crate) use model::Choice;
pub use model::{AtState, GuardKind, Rtw, Transition};
