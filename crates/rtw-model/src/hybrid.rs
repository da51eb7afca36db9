//! A hybrid-system engine that knows nothing about tensegrities.
//!
//! A hybrid system is written, as in Drake's rimless-wheel example, as three
//! named pieces over the [`HybridSystem`] trait:
//!
//! * **continuous dynamics** — [`HybridSystem::rhs`], `ẏ = f(t, y)` in the
//!   current mode (the mode lives inside the system value);
//! * **guards** — [`HybridSystem::guards`], scalar functions of the state,
//!   each with a crossing direction; an event fires where one crosses zero;
//! * **resets** — [`HybridSystem::reset`], applied at the located event time,
//!   may change the mode and jump the state.
//!
//! [`run`] integrates with an adaptive embedded Runge–Kutta method (or
//! fixed-step RK4), locates events by root finding on the dense output, and
//! never allocates inside the step loop: the state is a fixed-size array and
//! modes change which components are live, not the storage.

use crate::integrate::{Dense, Method};

/// Capacity of a [`Guards`] set. Fixed so that guard evaluation never allocates.
pub const MAX_GUARDS: usize = 16;

/// The direction in which a guard must cross zero to fire.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Crossing {
    /// From `g > 0` to `g <= 0` (e.g. a tip height reaching the ground).
    Falling,
    /// From `g < 0` to `g >= 0`.
    Rising,
    /// Either direction.
    Either,
}

/// Values of a system's guard functions at one state, in a fixed-capacity set.
#[derive(Clone, Copy, Debug)]
pub struct Guards {
    pub value: [f64; MAX_GUARDS],
    pub crossing: [Crossing; MAX_GUARDS],
    pub len: usize,
}

impl Default for Guards {
    fn default() -> Self {
        Self {
            value: [0.0; MAX_GUARDS],
            crossing: [Crossing::Either; MAX_GUARDS],
            len: 0,
        }
    }
}

impl Guards {
    pub fn clear(&mut self) {
        self.len = 0;
    }

    /// Adds a guard; its index is the number of guards pushed before it.
    pub fn push(&mut self, value: f64, crossing: Crossing) {
        assert!(self.len < MAX_GUARDS, "more than MAX_GUARDS guards");
        self.value[self.len] = value;
        self.crossing[self.len] = crossing;
        self.len += 1;
    }
}

/// Whether the run goes on after a reset or an observed step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Flow {
    Continue,
    /// The system ended the run itself (a failure it detected, or a settled gait).
    Stop,
}

/// A hybrid dynamical system with an `N`-dimensional state.
pub trait HybridSystem<const N: usize> {
    /// Continuous dynamics of the current mode: writes `ẏ = f(t, y)` into `dy`.
    fn rhs(&self, t: f64, y: &[f64; N], dy: &mut [f64; N]);

    /// Guard functions of the current mode, evaluated at `(t, y)`. The set of
    /// guards (count and meaning of each index) may depend on the mode but not
    /// on `(t, y)`: the engine compares values of the same index across a step.
    fn guards(&self, t: f64, y: &[f64; N], out: &mut Guards);

    /// The reset of guard `index`, applied at its located event time `t` with
    /// `y` the state there: may change the mode and jump `y`.
    fn reset(&mut self, t: f64, y: &mut [f64; N], index: usize) -> Flow;

    /// Called after every accepted step `[dense.t0, dense.t1]` (and after the
    /// part of a step that ends at an event, before its reset), with the dense
    /// output of that step. Statistics, recording and run-level failure checks
    /// go here. The default does nothing.
    fn observe(&mut self, _dense: &Dense<N>) -> Flow {
        Flow::Continue
    }
}

/// Settings of [`run`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EngineOptions {
    pub method: Method,
    /// Relative tolerance of the adaptive methods.
    pub rtol: f64,
    /// Absolute tolerance of the adaptive methods.
    pub atol: f64,
    /// Largest step allowed (also bounds how far apart guard samples are).
    pub h_max: f64,
    /// A step below this is a step-size underflow (the run ends as such).
    pub h_min: f64,
    /// Work budget: accepted + rejected steps.
    pub max_steps: u64,
    /// Absolute tolerance on located event times (seconds).
    pub event_time_tol: f64,
    /// Zeno guard: more than `zeno_events` events within `zeno_window`
    /// seconds of each other ends the run.
    pub zeno_events: u32,
    pub zeno_window: f64,
}

impl Default for EngineOptions {
    fn default() -> Self {
        Self {
            method: Method::Dp54,
            rtol: 1e-8,
            atol: 1e-10,
            h_max: 0.01,
            h_min: 1e-14,
            max_steps: 5_000_000,
            event_time_tol: 1e-13,
            zeno_events: 50,
            zeno_window: 1e-6,
        }
    }
}

/// Integrator work over a run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Work {
    pub steps: u64,
    pub rejected: u64,
    pub rhs_evals: u64,
    pub events: u64,
}

/// Why [`run`] returned.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EndReason {
    /// Reached `t_end`.
    TimeUp,
    /// The system returned [`Flow::Stop`].
    Stopped,
    /// The step size fell below `h_min`.
    StepUnderflow,
    /// A state component or derivative became NaN or infinite.
    NonFinite,
    /// `max_steps` exhausted.
    WorkBudget,
    /// Too many events in too short a time.
    Zeno,
}

/// Result of [`run`]: the final time, why it ended, and the work done.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunEnd {
    pub t: f64,
    pub reason: EndReason,
    pub work: Work,
}

/// Integrates `sys` from `(t0, y)` to `t_end`, locating and applying events.
/// On return `y` holds the state at `RunEnd::t`.
pub fn run<const N: usize, S: HybridSystem<N>>(
    sys: &mut S,
    t0: f64,
    y: &mut [f64; N],
    t_end: f64,
    opts: &EngineOptions,
) -> RunEnd {
    let _ = (sys, t0, y, t_end, opts);
    todo!("engine: implemented in the integrator work")
}
