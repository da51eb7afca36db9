//! Limit cycles of the RTW's gaits, on a Poincaré section at each new foot's
//! touchdown.
//!
//! | module | what it computes |
//! |---|---|
//! | [`section`] | the section's points in canonical labels (the 60° symmetry), the log of a run's crossings |
//! | [`stepmap`] | the step map, its Jacobian (variational or differences), periods, fixed points, Floquet multipliers |
//! | [`continuation`] | the step map as a map with a parameter, for branches and bifurcations ([`hybrid_ode::continuation`]) |

pub mod continuation;
pub mod section;
pub mod stepmap;
