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

use crate::integrate::{Dense, Method, Stages, fill_dense, hinit, trial};

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
    /// By-products of the right-hand side that the guards (or `observe`) also
    /// need at the same state, such as constraint forces; `()` if none.
    type Aux: Copy + Default;

    /// Continuous dynamics of the current mode: writes `ẏ = f(t, y)` into `dy`.
    fn rhs(&self, t: f64, y: &[f64; N], dy: &mut [f64; N]);

    /// [`rhs`](HybridSystem::rhs) that also writes its by-products at `y` into
    /// `aux`. The engine calls it where it evaluates the guards at the same
    /// state next: the last stage of a trial step (FSAL: `f(t + h, y_new)`),
    /// the start and each restart. The default leaves `aux` alone.
    #[inline]
    fn rhs_aux(&self, t: f64, y: &[f64; N], dy: &mut [f64; N], _aux: &mut Self::Aux) {
        self.rhs(t, y, dy);
    }

    /// Guard functions of the current mode, evaluated at `(t, y)`. The set of
    /// guards (count and meaning of each index) may depend on the mode but not
    /// on `(t, y)`: the engine compares values of the same index across a step.
    fn guards(&self, t: f64, y: &[f64; N], out: &mut Guards);

    /// Guard `index` alone at `(t, y)`: must equal, bit for bit, the value
    /// [`guards`](HybridSystem::guards) gives it there. The root finder calls
    /// it at every iterate, where only the guard being located matters, so a
    /// system whose guards are cheap one by one (a tip height needs one rod's
    /// `sin_cos`, not every string force) should override it. The default
    /// evaluates all guards and keeps one.
    #[inline]
    fn guard(&self, t: f64, y: &[f64; N], index: usize) -> f64 {
        let mut g = Guards::default();
        self.guards(t, y, &mut g);
        g.value[index]
    }

    /// [`guards`](HybridSystem::guards) at a state where `rhs_aux` has just
    /// written `aux`; must give the same values, bit for bit. The default
    /// ignores `aux`.
    #[inline]
    fn guards_aux(&self, t: f64, y: &[f64; N], _aux: &Self::Aux, out: &mut Guards) {
        self.guards(t, y, out);
    }

    /// The reset of guard `index`, applied at its located event time `t` with
    /// `y` the state there: may change the mode and jump `y`.
    fn reset(&mut self, t: f64, y: &mut [f64; N], index: usize) -> Flow;

    /// The reset of guard `index` at `y`, making every discrete choice (a new
    /// mode, a kind of impact) as `nominal` made it in its latest reset.
    /// Differentiating a reset needs its choices fixed: at an event the state
    /// sits on the boundary between them (a lift-off at zero normal force).
    /// The default is [`reset`](HybridSystem::reset), right for systems
    /// whose resets make no choice.
    fn reset_replaying(&mut self, t: f64, y: &mut [f64; N], index: usize, _nominal: &Self) -> Flow
    where
        Self: Sized,
    {
        self.reset(t, y, index)
    }

    /// Called after every accepted step `[dense.t0, dense.t1]` (and after the
    /// part of a step that ends at an event, before its reset), with the dense
    /// output of that step. Statistics, recording and run-level failure checks
    /// go here. The default does nothing.
    fn observe(&mut self, _dense: &Dense<N>) -> Flow {
        Flow::Continue
    }

    /// [`observe`](HybridSystem::observe) on a step without an event, whose
    /// end state `dense.y1` is the one `rhs_aux` wrote `aux` at. The default
    /// calls `observe`.
    #[inline]
    fn observe_aux(&mut self, dense: &Dense<N>, _aux: &Self::Aux) -> Flow {
        self.observe(dense)
    }

    /// Whether [`observe`](HybridSystem::observe) evaluates the dense output
    /// strictly inside a step (`Dense::eval` at `t ∈ (t0, t1)`). If it only
    /// reads `t0, t1, y0, y1`, returning `false` lets the engine hand it a
    /// cheaper interpolant (cubic Hermite) on steps without an event: DOP853
    /// then skips the 3 extra stages of its 7th-order dense output (20 % fewer
    /// right-hand-side evaluations). Event location always uses the method's
    /// full dense output. The default is `true`.
    fn observes_interior(&self) -> bool {
        true
    }

    /// [`observes_interior`](HybridSystem::observes_interior) for the step
    /// `[t0, t1]` just accepted (asked before [`observe`](HybridSystem::observe)
    /// gets it): a system that reads the interior only at known times (a trace
    /// sample, the start of a statistics window) says so here, and every other
    /// step gets the cheap interpolant. The default asks `observes_interior`.
    #[inline]
    fn observes_interior_on(&self, _t0: f64, _t1: f64) -> bool {
        self.observes_interior()
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

// ---------------------------------------------------------------------------
// The engine
// ---------------------------------------------------------------------------

/// Safety factor of the step-size controller.
const SAFE: f64 = 0.9;
/// Smallest step-size ratio `h_new / h` of the controller.
const FAC_MIN: f64 = 0.2;
/// Largest step-size ratio `h_new / h` (1 right after a rejection).
const FAC_MAX: f64 = 10.0;
/// Iteration cap of the event root finder (it normally needs 5–15).
const ROOT_MAX_ITER: u32 = 200;

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

/// The direction in which guard `kind` crossed from `p` (step start) to `q`
/// (step end): `Some(true)` falling, `Some(false)` rising, `None` no crossing.
/// A start value of exactly 0 never counts as a crossing.
#[inline]
fn crossing_dir(kind: Crossing, p: f64, q: f64) -> Option<bool> {
    let falls = p > 0.0 && q <= 0.0;
    let rises = p < 0.0 && q >= 0.0;
    match kind {
        Crossing::Falling if falls => Some(true),
        Crossing::Rising if rises => Some(false),
        Crossing::Either if falls => Some(true),
        Crossing::Either if rises => Some(false),
        _ => None,
    }
}

/// Whether a guard value is on the crossed side.
#[inline]
fn is_crossed(falling: bool, v: f64) -> bool {
    if falling { v <= 0.0 } else { v >= 0.0 }
}

/// Fixed-size scratch of event location.
struct Scratch<const N: usize> {
    /// State at a trial time.
    ya: [f64; N],
    /// State at the crossed end of the current bracket.
    yc: [f64; N],
    /// State at the earliest event found so far.
    ybest: [f64; N],
}

/// Illinois (modified regula falsi) on guard `idx` along `dense`, from the
/// bracket `[a, b]` with `ga` not crossed at `a` and `gb` crossed at `b`
/// (`sc.yc` holds the state at `b`). Shrinks the bracket to `b − a <= tol`
/// and returns `b`, the crossed end; `sc.yc` is then the state there. Only
/// guard `idx` is evaluated ([`HybridSystem::guard`]).
// `!(a < b)` is deliberate throughout the engine: it is true for NaN too.
#[allow(clippy::too_many_arguments, clippy::neg_cmp_op_on_partial_ord)]
fn illinois<const N: usize, S: HybridSystem<N>>(
    sys: &S,
    dense: &Dense<N>,
    idx: usize,
    falling: bool,
    a: f64,
    ga: f64,
    b: f64,
    gb: f64,
    tol: f64,
    sc: &mut Scratch<N>,
) -> f64 {
    // s(t) > 0 before the crossing, s(t) <= 0 after it.
    let sgn = if falling { 1.0 } else { -1.0 };
    let (mut a, mut fa) = (a, sgn * ga);
    let (mut b, mut fb) = (b, sgn * gb);
    // Never ask for less than a few ulps of t.
    let tol = tol.max(4.0 * f64::EPSILON * a.abs().max(b.abs()).max(1e-300));
    let half = 0.5 * tol;
    let mut side = 0i8;
    let mut w_check = b - a;
    let mut since_check = 0u32;
    for _ in 0..ROOT_MAX_ITER {
        let w = b - a;
        if !(w > tol) {
            break;
        }
        // Safeguard: if four iterations did not halve the bracket, bisect.
        since_check += 1;
        let mut bisect = false;
        if since_check == 4 {
            bisect = w > 0.5 * w_check;
            since_check = 0;
            w_check = w;
        }
        let mut c = if !bisect && fa.is_finite() && fb.is_finite() && fa != fb {
            a + w * (fa / (fa - fb))
        } else {
            a + 0.5 * w
        };
        // Keep the trial at least tol/2 inside the bracket, so that a root
        // within tol/2 of an end closes the bracket on the next evaluation.
        if !(c >= a + half) {
            c = a + half;
        } else if !(c <= b - half) {
            c = b - half;
        }
        dense.eval(c, &mut sc.ya);
        let fc = sgn * sys.guard(c, &sc.ya, idx);
        if fc <= 0.0 {
            b = c;
            fb = fc;
            sc.yc = sc.ya;
            if side < 0 {
                fa *= 0.5;
            }
            side = -1;
        } else {
            a = c;
            fa = fc;
            if side > 0 {
                fb *= 0.5;
            }
            side = 1;
        }
    }
    b
}

/// Locates the earliest root, on `dense`, of the guards that crossed between
/// `gp` (at `dense.t0`) and `gn` (at `dense.t1`). Returns the guard's index
/// and its event time; `sc.ybest` is the state there (on the crossed side).
/// Ties go to the lower index.
fn locate_earliest<const N: usize, S: HybridSystem<N>>(
    sys: &S,
    dense: &Dense<N>,
    gp: &Guards,
    gn: &Guards,
    tol: f64,
    sc: &mut Scratch<N>,
) -> Option<(usize, f64)> {
    let len = gp.len.min(gn.len);
    let mut best: Option<(usize, f64)> = None;
    for i in 0..len {
        let Some(falling) = crossing_dir(gn.crossing[i], gp.value[i], gn.value[i]) else {
            continue;
        };
        // Right end of the bracket: the step's end, or the earliest event so
        // far if this guard has already crossed there (else its root is later).
        let (b, gb) = match best {
            None => {
                sc.yc = dense.y1;
                (dense.t1, gn.value[i])
            }
            Some((_, t_best)) => {
                let v = sys.guard(t_best, &sc.ybest, i);
                if !is_crossed(falling, v) {
                    continue;
                }
                sc.yc = sc.ybest;
                (t_best, v)
            }
        };
        let t_i = illinois(
            sys,
            dense,
            i,
            falling,
            dense.t0,
            gp.value[i],
            b,
            gb,
            tol,
            sc,
        );
        if best.is_none_or(|(_, t_best)| t_i < t_best) {
            best = Some((i, t_i));
            sc.ybest = sc.yc;
        }
    }
    best
}

/// Integrates `sys` from `(t0, y)` to `t_end`, locating and applying events.
/// On return `y` holds the state at `RunEnd::t`.
///
/// The step loop, per accepted step `[t, t + h]`:
///
/// 1. the guards are evaluated at the step's end and compared with their
///    values at its start (same index): guard `i` fires when it crosses in its
///    [`Crossing`] direction, strictly from the other side (a guard exactly 0
///    at the start does not fire, so a reset that leaves its guard at 0 is not
///    re-triggered);
/// 2. for each guard that crossed, its root on the step's dense output is
///    located by the Illinois method to `event_time_tol`; the earliest wins
///    (ties: lower index), and the event state is the crossed end of the
///    final bracket (the guard is on its crossed side there);
/// 3. with an event at `te`: `observe` gets the dense output cut to
///    `[t, te]`, then `reset(te, y, i)`; the integrator restarts at `te`
///    (fresh `f`, no FSAL reuse, step = the last accepted one, ≤ `h_max`), and
///    the guards at the post-reset state become the new start values;
/// 4. without an event: `observe` gets the whole step.
///
/// Step-size control (adaptive methods) is Hairer's: RMS error norm with
/// scale `atol + rtol·max(|y0|, |y1|)`, safety 0.9, ratio bounds [0.2, 10]
/// (no growth right after a rejection), PI control for DP5 (β = 0.04),
/// `hinit` for the first step, every step ≤ `h_max`. The last step is clamped
/// to end at `t_end` exactly. A trial step that produces a non-finite state or
/// derivative is rejected and retried 5× shorter; if that drives the step
/// below `h_min` the run ends as [`EndReason::NonFinite`] (otherwise an
/// undersized step is [`EndReason::StepUnderflow`]). RK4 takes fixed steps of
/// `min(h, h_max)` (the last one shortened) and ends at the first non-finite
/// value.
///
/// The run allocates nothing: all storage is fixed-size arrays on the stack.
#[allow(clippy::neg_cmp_op_on_partial_ord)]
pub fn run<const N: usize, S: HybridSystem<N>>(
    sys: &mut S,
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
    sys.guards_aux(t, y, &aux, &mut gp);
    if !(t < t_end) {
        finish!(EndReason::TimeUp);
    }

    let h_max = if opts.h_max > 0.0 {
        opts.h_max
    } else {
        f64::INFINITY
    };
    let h_fixed = match method {
        Method::Rk4 { h } => h.min(h_max),
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
    let mut sc = Scratch {
        ya: [0.0; N],
        yc: [0.0; N],
        ybest: [0.0; N],
    };
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
        let len = gp.len.min(gn.len);
        let mut crossed = false;
        for i in 0..len {
            if crossing_dir(gn.crossing[i], gp.value[i], gn.value[i]).is_some() {
                crossed = true;
                break;
            }
        }
        let full = crossed || sys.observes_interior_on(t, t_new);
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

        if crossed {
            let Some((idx, te)) =
                locate_earliest(&*sys, &dense, &gp, &gn, opts.event_time_tol, &mut sc)
            else {
                unreachable!("a crossing was detected");
            };
            dense.t1 = te;
            dense.y1 = sc.ybest;
            t = te;
            *y = sc.ybest;
            if sys.observe(&dense) == Flow::Stop {
                finish!(EndReason::Stopped);
            }
            work.events += 1;
            if t - last_event < opts.zeno_window {
                zeno_count += 1;
            } else {
                zeno_count = 1;
            }
            last_event = t;
            if sys.reset(t, y, idx) == Flow::Stop {
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
        // `fill_dense` evaluates with plain `rhs`: `aux` is still at `y`.
        if sys.observe_aux(&dense, &aux) == Flow::Stop {
            finish!(EndReason::Stopped);
        }
        if last {
            finish!(EndReason::TimeUp);
        }
        h = h_next;
    }
}
