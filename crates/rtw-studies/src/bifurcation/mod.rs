//! Bifurcation diagrams: one parameter swept with continuation on the step
//! map ([`rtw_model::cycles::StepMap`]), a step quantity recorded after transients,
//! and the limit cycle's Floquet multipliers at every value.
//!
//! At each value, in sweep order, the map starts from the previous value's
//! last section point (continuation: the gait followed is the one the robot
//! was in, not the one a fresh start finds); the first value, and any value
//! where the map fails from the continued point, starts from the initial
//! state instead (`restarted`). After `transient` steps, `record` steps are
//! kept (post-impact angular velocity of the new stance rod, step time); the
//! period is detected on their section points, and a periodic gait is solved
//! for the fixed point of `Pⁿ` by Newton with variational Jacobians, giving
//! its multipliers. The gait label comes from the recorded steps' contact
//! fractions; a failed step gets the scan's failure label (collapse, stall,
//! diverged) or, when the map itself stopped, `failure` (`PointLabel`),
//! and its reason.
//!
//! Output: `FILE.parquet`, one row per parameter value (`points_schema`),
//! and `FILE.steps.parquet`, one row per recorded step (`steps_schema`),
//! with the resolved options, the swept parameter and the base point in the
//! metadata; and a markdown summary (`summary_markdown`).

pub(crate) mod files;
mod study;
pub(crate) mod summary;
pub(crate) mod sweep;

pub use study::{SweepFiles, run_to_files};
pub use sweep::Sweep;
