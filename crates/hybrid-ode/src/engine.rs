//! The event-driven step loop: [`run`] integrates a [`HybridSystem`] with an
//! adaptive embedded Runge–Kutta method (or fixed-step RK4), locates events
//! by root finding on the dense output, applies the resets, and hands every
//! step and transition to an [`Observer`]. It never allocates inside the
//! step loop: the state is a fixed-size array and modes change which
//! components are live, not the storage.

use crate::dense::Dense;
use crate::events::{Scratch, any_crossing, locate_earliest};
use crate::integrate::{Method, Stages, fill_dense, hinit, trial};
use crate::system::{EndsRun, Flow, Guards, HybridSystem, MAX_GUARDS, Observer, StepEnd};

/// Settings of [`run`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EngineOptions {
    /// The Runge–Kutta method.
    pub method: Method,
    /// Relative tolerance of the adaptive methods.
    pub rtol: f64,
    /// Absolute tolerance of the adaptive methods.
    pub atol: f64,
    /// Largest step allowed (≤ 0: none). Event detection does not need one:
    /// a crossing that goes out and back inside a step is found too.
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
    /// See [`zeno_events`](EngineOptions::zeno_events) (seconds).
    pub zeno_window: f64,
    /// The fixed step of [`Method::Rk4`] (s).
    pub rk4_step: f64,
    /// Also find the crossings that the guards' values and rates at a step's
    /// ends hide: a guard that dips where the right-hand side kinks inside
    /// the step ([`HybridSystem::kink_sides`]: the step is split there and
    /// each piece searched as a step of its own), one on its crossed side at
    /// another guard's event, and a first crossing before the root a
    /// bracket converged to. Off until the committed results are remade
    /// with it: it changes runs where such a crossing was missed.
    pub hidden_crossings: bool,
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
            rk4_step: 1e-3,
            hidden_crossings: false,
        }
    }
}

/// Integrator work over a run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Work {
    /// Accepted steps.
    pub steps: u64,
    /// Rejected trial steps.
    pub rejected: u64,
    /// Right-hand-side evaluations.
    pub rhs_evals: u64,
    /// Events located (resets applied).
    pub events: u64,
}

impl std::ops::AddAssign for Work {
    fn add_assign(&mut self, other: Work) {
        self.steps += other.steps;
        self.rejected += other.rejected;
        self.rhs_evals += other.rhs_evals;
        self.events += other.events;
    }
}

/// Why [`run`] returned.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EndReason {
    /// Reached `t_end`.
    TimeUp,
    /// The observer returned [`Flow::Stop`], or a transition
    /// [ended the run](crate::EndsRun::ends_run).
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
    /// Time at which the run ended (the state is the one at this time).
    pub t: f64,
    /// Why it ended.
    pub reason: EndReason,
    /// The integrator work done.
    pub work: Work,
}

// ---------------------------------------------------------------------------
// The engine
// ---------------------------------------------------------------------------

/// Safety factor of the step-size controller.
const SAFE: f64 = 0.9;
/// Smallest step-size ratio `h_new / h` of the controller.
const FAC_MIN: f64 = 0.2;
/// Largest step-size ratio `h_new / h` (1 right after a rejection).
const FAC_MAX: f64 = 10.0;

/// `true` iff every component is finite (`x·0` is NaN exactly for NaN/±∞).
#[inline]
fn all_finite<const N: usize>(v: &[f64; N]) -> bool {
    let mut s = 0.0;
    for x in v {
        s += x * 0.0;
    }
    s == 0.0
}

/// Hairer's step-size controller (`dopri5`: PI with β = 0.04; `dop853`: β = 0).
#[derive(Clone, Copy)]
struct Control {
    /// Exponent of the error, `1/(q+1) − 0.75 β` with `q` the lower order.
    expo: f64,
    beta: f64,
}

impl Control {
    fn new(method: Method) -> Self {
        match method {
            Method::Dop853 => Self {
                expo: 1.0 / 8.0,
                beta: 0.0,
            },
            _ => Self {
                expo: 0.2 - 0.04 * 0.75,
                beta: 0.04,
            },
        }
    }

    /// Next step after an accepted step `h` with error norm `err <= 1`;
    /// `ln_facold` is the log of the previous accepted error (≥ 1e-4). Done in
    /// the log domain: one `ln` and one `exp` instead of two `powf`.
    #[inline]
    fn accept(&self, err: f64, h: f64, ln_facold: &mut f64, after_reject: bool) -> f64 {
        let ln_err = err.ln();
        // fac = err^expo / facold^beta = h / h_new before the safety factor.
        let fac = (self.expo * ln_err - self.beta * *ln_facold).exp();
        let fac = (fac / SAFE).clamp(1.0 / FAC_MAX, 1.0 / FAC_MIN);
        *ln_facold = ln_err.max(LN_FACOLD_MIN);
        let h_new = h / fac;
        if after_reject { h_new.min(h) } else { h_new }
    }

    /// Next trial after a rejected step `h` with error norm `err > 1`.
    #[inline]
    fn reject(&self, err: f64, h: f64) -> f64 {
        h / ((self.expo * err.ln()).exp() / SAFE).min(1.0 / FAC_MIN)
    }
}

/// `ln 1e-4`: the floor of the previous error in the PI controller.
const LN_FACOLD_MIN: f64 = -9.210340371976182;

/// Integrates `sys` from `(t0, y)` to `t_end`, locating and applying events,
/// with `observer` watching. On return `y` holds the state at `RunEnd::t`.
///
/// The step loop, per accepted step `[t, t + h]`:
///
/// 1. the guards are evaluated at the step's end and compared with their
///    values at its start (same index): guard `i` fires when it crosses in its
///    [`Crossing`](crate::Crossing) direction, strictly from the other side (a guard exactly 0
///    at the start does not fire, so a reset that leaves its guard at 0 is not
///    re-triggered), or, with both ends on its uncrossed side, when it
///    crossed and came
///    back inside the step: from the guards' values and rates at both ends
///    ([`HybridSystem::guard_rates`]) the guard's cubic model says where a
///    dip cannot be excluded, and the dense output is searched there (a dip
///    counts when deeper than the step's error estimate moves the guard);
/// 2. for each guard that crossed, its root on the step's dense output is
///    located by the Illinois method to `event_time_tol`; the earliest wins
///    (ties: lower index), and the event state is the crossed end of the
///    final bracket (the guard is on its crossed side there);
/// 3. with an event at `te`: [`Observer::on_step`] gets the dense output cut
///    to `[t, te]` ([`StepEnd::Event`]), then `reset(te, y, i)` and
///    [`Observer::on_transition`]; the integrator restarts at `te`
///    (fresh `f`, no FSAL reuse, step = the last accepted one, ≤ `h_max`), and
///    the guards at the post-reset state become the new start values;
/// 4. without an event: [`Observer::on_step`] gets the whole step
///    ([`StepEnd::Step`]).
///
/// Step-size control (adaptive methods) is Hairer's: RMS error norm with
/// scale `atol + rtol·max(|y0|, |y1|)`, safety 0.9, ratio bounds [0.2, 10]
/// (no growth right after a rejection), PI control for DP5 (β = 0.04),
/// `hinit` for the first step, every step ≤ `h_max` (none needed for event
/// detection). The last step is clamped
/// to end at `t_end` exactly. A trial step that produces a non-finite state or
/// derivative is rejected and retried 5× shorter; if that drives the step
/// below `h_min` the run ends as [`EndReason::NonFinite`] (otherwise an
/// undersized step is [`EndReason::StepUnderflow`]). RK4 takes fixed steps of
/// `min(h, h_max)` (the last one shortened) and ends at the first non-finite
/// value.
///
/// The run allocates nothing: all storage is fixed-size arrays on the stack.
#[allow(clippy::neg_cmp_op_on_partial_ord)]
pub fn run<const N: usize, S: HybridSystem<N>, O: Observer<N, S>>(
    sys: &mut S,
    observer: &mut O,
    t0: f64,
    y: &mut [f64; N],
    t_end: f64,
    opts: &EngineOptions,
) -> RunEnd {
    let method = opts.method;
    let adaptive = method.is_adaptive();
    let mut work = Work::default();
    let mut t = t0;
    macro_rules! finish {
        ($reason:expr) => {
            return RunEnd {
                t,
                reason: $reason,
                work,
            }
        };
    }

    if !all_finite(y) {
        finish!(EndReason::NonFinite);
    }
    let mut st = Stages::<N>::new();
    // By-products of the latest `rhs_aux` call, reused by the guards there.
    let mut aux = S::Aux::default();
    sys.rhs_aux(t, y, &mut st.k[0], &mut aux);
    work.rhs_evals += 1;
    if !all_finite(&st.k[0]) {
        finish!(EndReason::NonFinite);
    }
    let mut gp = Guards::default();
    let mut gn = Guards::default();
    // The guards' rates at the step's start and end, for the test of a
    // crossing that goes out and back inside a step.
    let mut rp = [0.0; MAX_GUARDS];
    let mut rn = [0.0; MAX_GUARDS];
    sys.guards_aux(t, y, &aux, &mut gp);
    sys.guard_rates(t, y, &st.k[0], &aux, &gp, &mut rp);
    // The sides of the right-hand side's kinks at the step's start (all 0
    // unless the hidden crossings are sought).
    let hidden = opts.hidden_crossings;
    let kink_sides = |sys: &S, t: f64, y: &[f64; N], aux: &S::Aux| {
        if hidden { sys.kink_sides(t, y, aux) } else { 0 }
    };
    let mut kp = kink_sides(sys, t, y, &aux);
    if !(t < t_end) {
        finish!(EndReason::TimeUp);
    }

    let h_max = if opts.h_max > 0.0 {
        opts.h_max
    } else {
        f64::INFINITY
    };
    let h_fixed = match method {
        Method::Rk4 => opts.rk4_step.min(h_max),
        _ => 0.0,
    };
    let mut h = if adaptive {
        work.rhs_evals += 1;
        hinit(
            &mut |tt, yy, dd| sys.rhs(tt, yy, dd),
            t,
            y,
            method.order(),
            h_max,
            opts.atol,
            opts.rtol,
            &mut st,
        )
    } else {
        h_fixed
    };
    if !(h > 0.0) {
        finish!(EndReason::StepUnderflow);
    }
    // Fixed steps are stretched by at most a hair to reach t_end, adaptive
    // ones by 1 % (as in Hairer's codes) to avoid a sliver of a last step.
    let stretch = if adaptive { 1.01 } else { 1.0 + 1e-9 };
    let ctrl = Control::new(method);
    let mut ln_facold = LN_FACOLD_MIN;
    let mut after_reject = false;
    let mut nonfinite_trial = false;
    let mut dense = Dense::<N>::constant(t, y);
    let mut sc = Scratch::new();
    let mut zeno_count = 0u32;
    let mut last_event = f64::NEG_INFINITY;

    loop {
        if work.steps + work.rejected >= opts.max_steps {
            finish!(EndReason::WorkBudget);
        }
        if adaptive && !(h >= opts.h_min) {
            finish!(if nonfinite_trial {
                EndReason::NonFinite
            } else {
                EndReason::StepUnderflow
            });
        }
        let mut hs = h;
        let mut last = false;
        if t + stretch * hs >= t_end {
            hs = t_end - t;
            last = true;
        }
        if !(t + hs > t) {
            // The step is below the resolution of t.
            finish!(EndReason::StepUnderflow);
        }

        // Every method's last evaluation in a trial is `f(t + hs, ynew)`, so
        // `aux` ends up holding the by-products at the step's end.
        let err = trial(
            method,
            &mut |tt, yy, dd| sys.rhs_aux(tt, yy, dd, &mut aux),
            t,
            y,
            hs,
            opts.atol,
            opts.rtol,
            &mut st,
        );
        work.rhs_evals += method.evals_per_step();

        if !(all_finite(&st.ynew) && all_finite(&st.fnew)) || err.is_nan() {
            if !adaptive {
                finish!(EndReason::NonFinite);
            }
            work.rejected += 1;
            h = hs * FAC_MIN;
            after_reject = true;
            nonfinite_trial = true;
            continue;
        }
        nonfinite_trial = false;
        if adaptive && err > 1.0 {
            work.rejected += 1;
            h = ctrl.reject(err, hs);
            after_reject = true;
            continue;
        }

        // Accepted.
        work.steps += 1;
        let t_new = if last { t_end } else { t + hs };
        let h_next = if adaptive {
            ctrl.accept(err, hs, &mut ln_facold, after_reject)
                .min(h_max)
        } else {
            h_fixed
        };
        after_reject = false;

        sys.guards_aux(t_new, &st.ynew, &aux, &mut gn);
        sys.guard_rates(t_new, &st.ynew, &st.fnew, &aux, &gn, &mut rn);
        // A guard crossed at the step's end, or may have inside it, or the
        // right-hand side kinked inside it.
        let kn = kink_sides(sys, t_new, &st.ynew, &aux);
        let crossed = any_crossing(&gp, &gn, &rp, &rn, t, t_new) || kn != kp;
        let full = crossed || observer.reads_interior(sys, t, t_new);
        work.rhs_evals += fill_dense(
            method,
            &mut |tt, yy, dd| sys.rhs(tt, yy, dd),
            t,
            y,
            hs,
            t_new,
            &mut st,
            full,
            &mut dense,
        );

        let event = if crossed {
            locate_earliest(
                &*sys,
                &dense,
                &gp,
                &gn,
                &rp,
                &rn,
                &st.err,
                opts.event_time_tol,
                (hidden, (kp, kp ^ kn)),
                &mut sc,
            )
        } else {
            None
        };
        if let Some((idx, te)) = event {
            dense.t1 = te;
            dense.y1 = sc.ybest;
            t = te;
            *y = sc.ybest;
            if observer.on_step(sys, &dense, StepEnd::Event { guard: idx }) == Flow::Stop {
                finish!(EndReason::Stopped);
            }
            work.events += 1;
            if t - last_event < opts.zeno_window {
                zeno_count += 1;
            } else {
                zeno_count = 1;
            }
            last_event = t;
            let transition = sys.reset(t, y, idx);
            let flow = observer.on_transition(sys, t, y, &transition);
            if flow == Flow::Stop || transition.ends_run() {
                finish!(EndReason::Stopped);
            }
            if zeno_count > opts.zeno_events {
                finish!(EndReason::Zeno);
            }
            if !all_finite(y) {
                finish!(EndReason::NonFinite);
            }
            // Clean restart: fresh derivative, guards at the post-reset state.
            sys.rhs_aux(t, y, &mut st.k[0], &mut aux);
            work.rhs_evals += 1;
            if !all_finite(&st.k[0]) {
                finish!(EndReason::NonFinite);
            }
            sys.guards_aux(t, y, &aux, &mut gp);
            sys.guard_rates(t, y, &st.k[0], &aux, &gp, &mut rp);
            kp = kink_sides(sys, t, y, &aux);
            if t >= t_end {
                finish!(EndReason::TimeUp);
            }
            h = if adaptive { hs.min(h_max) } else { h_fixed };
            ln_facold = LN_FACOLD_MIN;
            continue;
        }

        t = t_new;
        *y = st.ynew;
        st.k[0] = st.fnew;
        core::mem::swap(&mut gp, &mut gn);
        core::mem::swap(&mut rp, &mut rn);
        kp = kn;
        // `fill_dense` evaluates with plain `rhs`: `aux` is still at `y`.
        if observer.on_step(sys, &dense, StepEnd::Step { aux: &aux }) == Flow::Stop {
            finish!(EndReason::Stopped);
        }
        if last {
            finish!(EndReason::TimeUp);
        }
        h = h_next;
    }
}
