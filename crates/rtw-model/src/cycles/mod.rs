//! Limit cycles of the RTW's gaits, on a Poincaré section at each new foot's
//! touchdown, in three folders by topic: `map/` (the step map and its fixed
//! points), `branches/` (following a gait as a parameter moves, through
//! changes of its contact modes) and `robustness/` (what a gait does when it
//! is pushed off its cycle).
//!
//! | file | what it computes | public face |
//! |---|---|---|
//! | `map/section.rs` | which touchdowns cross the section, its points in canonical labels (the 60° symmetry), the log of a run's crossings | [`Section`], [`SectionPoint`] |
//! | `map/stepmap.rs` | the step map, its Jacobian (variational or differences), its iterates and periods | [`StepMap`], [`CycleOptions`], [`Jacobian`], [`Step`], [`StepError`] |
//! | `map/limit_cycle.rs` | fixed points of the map's power by Newton, Floquet multipliers, the limit cycle of a finished run | [`LimitCycle`], [`CycleError`] |
//! | `robustness/gsn.rs` | the gait sensitivity norm: the map linearised with the floor height as input, its H2 norm | (crate-private; a run's `gsn`) |
//! | `branches/continuation.rs` | the step map as a map with a parameter, for branches and bifurcations ([`hybrid_ode::continuation`]) | [`StepMapFamily`], [`StepMapPlane`], [`diagram`] |
//! | `branches/nonsmooth.rs` | where a branch's mode sequence changes (grazing, corner, the gait lost): the orbit's mode sequence and closest approaches, the located end | [`ModeSequence`], [`ModeEvent`], [`Approach`], [`Orbit`], [`Setting`], [`EndOptions`], [`EndKind`], [`BranchEnd`] |
//! | `robustness/basin.rs` | a slice of a gait's basin of attraction: a grid of perturbed section points, each iterated and classified | [`Basin`], [`BasinSpec`] |
//! | `branches/segments.rs` | a branch continued through those changes, segment by segment | [`Segment`], [`continue_segments`] |

pub(crate) mod branches;
pub(crate) mod map;
pub(crate) mod robustness;

pub use branches::continuation::{
    Diagram, DiagramBranch, DiagramError, DiagramOptions, StepMapFamily, StepMapPlane, diagram,
};
pub use branches::nonsmooth::{
    Approach, BranchEnd, EndKind, EndOptions, ModeEvent, ModeSequence, Orbit, Setting,
};
pub use branches::segments::{Segment, continue_segments};
pub use map::limit_cycle::{CycleError, LimitCycle};
pub use map::section::{Section, SectionPoint};
pub use map::stepmap::{CycleOptions, Jacobian, Step, StepError, StepMap};
pub use robustness::basin::{Axis, Basin, BasinError, BasinPoint, BasinSpec, Coord, Fate};
