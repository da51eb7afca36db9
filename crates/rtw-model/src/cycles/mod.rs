//! Limit cycles of the RTW's gaits, on a Poincaré section at each new foot's
//! touchdown.
//!
//! | module | what it computes |
//! |---|---|
//! | [`section`] | the section's points in canonical labels (the 60° symmetry), the log of a run's crossings |
//! | [`stepmap`] | the step map, its Jacobian (variational or differences), periods, fixed points, Floquet multipliers |

pub mod section;
pub mod stepmap;
