//! Limit cycles of the RTW's gaits, on a Poincaré section at each new foot's
//! touchdown.
//!
//! | module | what it computes |
//! |---|---|
//! | [`section`] | which touchdowns cross the section, its points in canonical labels (the 60° symmetry), the log of a run's crossings |
//! | [`stepmap`] | the step map, its Jacobian (variational or differences), its iterates and periods |
//! | [`limit_cycle`] | fixed points of the map's power by Newton, Floquet multipliers, the limit cycle of a finished run |
//! | [`continuation`] | the step map as a map with a parameter, for branches and bifurcations ([`hybrid_ode::continuation`]) |
//! | [`nonsmooth`] | where a branch's mode sequence changes (grazing, corner, the gait lost), and the branch continued through it segment by segment |

pub mod continuation;
pub mod limit_cycle;
pub mod nonsmooth;
pub mod section;
pub mod stepmap;
