//! Limit cycles of the RTW's gaits, on a Poincaré section at each new foot's
//! touchdown.
//!
//! | file | what it computes | public face |
//! |---|---|---|
//! | `section.rs` | which touchdowns cross the section, its points in canonical labels (the 60° symmetry), the log of a run's crossings | [`Section`], [`SectionPoint`] |
//! | `stepmap.rs` | the step map, its Jacobian (variational or differences), its iterates and periods | [`StepMap`], [`CycleOptions`], [`Jacobian`], [`Step`], [`StepError`] |
//! | `limit_cycle.rs` | fixed points of the map's power by Newton, Floquet multipliers, the limit cycle of a finished run | [`LimitCycle`], [`CycleError`] |
//! | `continuation.rs` | the step map as a map with a parameter, for branches and bifurcations ([`hybrid_ode::continuation`]) | [`StepMapFamily`], [`StepMapFamily2`], [`diagram`] |

pub(crate) mod continuation;
pub(crate) mod limit_cycle;
pub(crate) mod section;
pub(crate) mod stepmap;

pub use continuation::{
    Diagram, DiagramBranch, DiagramError, DiagramOptions, StepMapFamily, StepMapFamily2, diagram,
};
pub use limit_cycle::{CycleError, LimitCycle};
pub use section::{Section, SectionPoint};
pub use stepmap::{CycleOptions, Jacobian, Step, StepError, StepMap};
