//! Limit cycles of the RTW's gaits, on a Poincaré section at each new foot's
//! touchdown.
//!
//! | file | what it computes | public face |
//! |---|---|---|
//! | `section.rs` | which touchdowns cross the section, its points in canonical labels (the 60° symmetry), the log of a run's crossings | [`Section`], [`SectionPoint`] |
//! | `stepmap.rs` | the step map, its Jacobian (variational or differences), its iterates and periods | [`StepMap`], [`CycleOptions`], [`Jacobian`], [`Step`], [`StepError`] |
//! | `limit_cycle.rs` | fixed points of the map's power by Newton, Floquet multipliers, the limit cycle of a finished run | [`LimitCycle`], [`CycleError`] |
//! | `gsn.rs` | the gait sensitivity norm: the map linearised with the floor height as input, its H2 norm | (crate-private; a run's `gsn`) |
//! | `continuation.rs` | the step map as a map with a parameter, for branches and bifurcations ([`hybrid_ode::continuation`]) | [`StepMapFamily`], [`StepMapFamily2`], [`diagram`] |
//! | `nonsmooth.rs` | where a branch's mode sequence changes (grazing, corner, the gait lost): the orbit's mode sequence and closest approaches, the located end | [`ModeSequence`], [`ModeEvent`], [`Approach`], [`Orbit`], [`Setting`], [`EndOptions`], [`EndKind`], [`BranchEnd`] |
//! | `basin.rs` | a slice of a gait's basin of attraction: a grid of perturbed section points, each iterated and classified | [`Basin`], [`BasinSpec`] |
//! | `segments.rs` | a branch continued through those changes, segment by segment | [`Segment`], [`continue_segments`] |

pub(crate) mod basin;
pub(crate) mod continuation;
pub(crate) mod gsn;
pub(crate) mod limit_cycle;
pub(crate) mod nonsmooth;
pub(crate) mod section;
pub(crate) mod segments;
pub(crate) mod stepmap;

pub use basin::{Axis, Basin, BasinError, BasinPoint, BasinSpec, Coord, Fate};
pub use continuation::{
    Diagram, DiagramBranch, DiagramError, DiagramOptions, StepMapFamily, StepMapFamily2, diagram,
};
pub use limit_cycle::{CycleError, LimitCycle};
pub use nonsmooth::{
    Approach, BranchEnd, EndKind, EndOptions, ModeEvent, ModeSequence, Orbit, Setting,
};
pub use section::{Section, SectionPoint};
pub use segments::{Segment, continue_segments};
pub use stepmap::{CycleOptions, Jacobian, Step, StepError, StepMap};
