//! A gait's branch followed in one input (stable and unstable), its
//! bifurcations, the period-2 branches born there, and fold and
//! period-doubling curves in two inputs: [`Continuation`] checks the
//! settings, [`run_to_files`] runs the diagram and writes its files.

pub use crate::continuation::study::{THROUGH_MAX, check_through, run_to_files};
pub use crate::continuation::{Continuation, CurveSettings};
