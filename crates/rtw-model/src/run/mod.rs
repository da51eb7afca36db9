//! One run of the RTW and what it records.
//!
//! | module | what it computes |
//! |---|---|
//! | [`simulate`](mod@simulate) | `simulate(params, options) -> Outcome`: the plant run with its recorder |
//! | `robustness` (crate-private; `meet_step` is re-exported) | how much disturbance a gait survives: the largest step down |
//! | `steps_to_fall` (crate-private) | the mean steps to fall on seeded rough slopes (Monte Carlo) |
//! | `mfpt` (crate-private) | the mean first-passage time on rough slopes, uncensored (Fleming–Viot) |
//! | `mfpt_chain` (crate-private) | the same by a Markov chain on a mesh of the extended states reached |
//! | `mfpt_splitting` (crate-private) | the same by adaptive multilevel splitting with a learned score of the extended state |
//! | `settled` (crate-private) | the settled gait every robustness measure starts from, and the run from it on other ground |
//! | `gait` (crate-private) | the statistics over the analysis window, the return map and the settled-gait test |

pub(crate) mod gait;
pub(crate) mod mfpt;
pub(crate) mod mfpt_chain;
pub(crate) mod mfpt_splitting;
pub(crate) mod recorder;
pub(crate) mod robustness;
pub(crate) mod settled;
pub(crate) mod simulate;
pub(crate) mod steps_to_fall;
