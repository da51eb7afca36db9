//! What the engine integrates, and who watches it.
//!
//! A hybrid system is written, as in Drake's rimless-wheel example, as three
//! named pieces over the [`HybridSystem`] trait:
//!
//! * **continuous dynamics** — [`HybridSystem::rhs`], `ẏ = f(t, y)` in the
//!   current mode (the mode lives inside the system value);
//! * **guards** — [`HybridSystem::guards`], scalar functions of the state,
//!   each with a crossing direction; an event fires where one crosses zero;
//! * **resets** — [`HybridSystem::reset`], applied at the located event time,
//!   may change the mode and jump the state, and say what they did (a
//!   [`HybridSystem::Transition`]).
//!
//! What a run records — statistics, a trace, a Poincaré section, a stopping
//! rule — is not the system's business: it is an [`Observer`], handed to
//! [`run`](crate::run) beside the system (as rapier's step takes an
//! `EventHandler` and the `differential-equations` crate a `Solout`). It sees
//! every step's dense output ([`Observer::on_step`]) and every transition
//! ([`Observer::on_transition`]), and may end the run. One system thus
//! serves a simulation, a step map and a settling run, each with its own
//! observer.

use crate::dense::Dense;

/// Capacity of a [`Guards`] set. Fixed so that guard evaluation never allocates.
pub const MAX_GUARDS: usize = 16;

/// Most kinks of a right-hand side ([`HybridSystem::kink_sides`]: one bit each).
pub(crate) const MAX_KINKS: usize = 32;

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
    /// Guard values; only the first [`len`](Guards::len) are live.
    pub value: [f64; MAX_GUARDS],
    /// The crossing direction of each guard.
    pub crossing: [Crossing; MAX_GUARDS],
    /// Number of guards.
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
    /// Removes every guard.
    pub fn clear(&mut self) {
        self.len = 0;
    }

    /// Adds a guard; its index is the number of guards pushed before it.
    ///
    /// # Panics
    /// With more than [`MAX_GUARDS`] guards.
    #[inline]
    pub fn push(&mut self, value: f64, crossing: Crossing) {
        assert!(self.len < MAX_GUARDS, "more than MAX_GUARDS guards");
        self.value[self.len] = value;
        self.crossing[self.len] = crossing;
        self.len += 1;
    }
}

/// Whether the run goes on after a transition or an observed step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Flow {
    /// Go on integrating.
    Continue,
    /// End the run ([`EndReason::Stopped`](crate::EndReason::Stopped)).
    Stop,
}

/// What a reset reports: whether it ends the run by itself (a failure the
/// system detected), whatever the observer says.
pub trait EndsRun {
    /// `true` if the run cannot go on after this transition.
    fn ends_run(&self) -> bool;
}

/// A system whose resets only say whether the run goes on reports a [`Flow`].
impl EndsRun for Flow {
    fn ends_run(&self) -> bool {
        *self == Flow::Stop
    }
}

/// A hybrid dynamical system with an `N`-dimensional state: the plant.
pub trait HybridSystem<const N: usize> {
    /// By-products of the right-hand side that the guards (or an observer)
    /// also need at the same state, such as constraint forces; `()` if none.
    type Aux: Copy + Default;

    /// What a reset did, handed to the [`Observer`]; [`Flow`] for a system
    /// with nothing more to say.
    type Transition: Copy + EndsRun;

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

    /// The time derivative of guard `index` at `(t, y)` along a motion with
    /// `ẏ = dy` (on a step's dense output, its derivative there). The engine
    /// uses it to test, with the guards' values and rates at both ends of a
    /// step, whether a guard can have crossed zero and come back inside the
    /// step (`events`). The default is a forward difference of
    /// [`guard`](HybridSystem::guard) along `dy` ([`fd_delta`]); a system
    /// with closed-form rates may override it.
    #[inline]
    fn guard_rate(&self, t: f64, y: &[f64; N], dy: &[f64; N], index: usize) -> f64 {
        let d = fd_delta(y, dy);
        if d == 0.0 {
            return 0.0;
        }
        let yd: [f64; N] = core::array::from_fn(|i| y[i] + d * dy[i]);
        (self.guard(t + d, &yd, index) - self.guard(t, y, index)) / d
    }

    /// [`guard_rate`](HybridSystem::guard_rate) of every guard at once, at a
    /// step end `(t, y)` where the guards are `g`, `ẏ = dy`, and
    /// [`rhs_aux`](HybridSystem::rhs_aux) has just written `aux`; writes
    /// `out[i]` for `i < g.len`. The default is a forward difference of
    /// [`guards`](HybridSystem::guards) along `dy`: one evaluation of all
    /// guards per step.
    #[inline]
    fn guard_rates(
        &self,
        t: f64,
        y: &[f64; N],
        dy: &[f64; N],
        _aux: &Self::Aux,
        g: &Guards,
        out: &mut [f64; MAX_GUARDS],
    ) {
        let d = fd_delta(y, dy);
        if d == 0.0 {
            out[..g.len].fill(0.0);
            return;
        }
        let yd: [f64; N] = core::array::from_fn(|i| y[i] + d * dy[i]);
        let mut gd = Guards::default();
        self.guards(t + d, &yd, &mut gd);
        for ((r, a), b) in out.iter_mut().zip(&gd.value).zip(&g.value).take(g.len) {
            *r = (a - b) / d;
        }
    }

    /// Which side of each kink of the right-hand side the state `(t, y)` is
    /// on, one bit per kink (set: below zero), where
    /// [`rhs_aux`](HybridSystem::rhs_aux) has just written `aux`. A kink is
    /// where the right-hand side switches branch without an event (a slack
    /// string going taut); a guard computed from its forces kinks there too,
    /// and no cubic model of the guard across a step holds. The engine
    /// compares the bits at a step's two ends and splits the step at each
    /// kink that changed ([`EngineOptions::hidden_crossings`]). The default,
    /// 0, is right for a smooth right-hand side. It is asked only at step
    /// ends, and only when the hidden crossings are sought.
    ///
    /// [`EngineOptions::hidden_crossings`]: crate::EngineOptions::hidden_crossings
    #[inline]
    fn kink_sides(&self, _t: f64, _y: &[f64; N], _aux: &Self::Aux) -> u32 {
        0
    }

    /// Kink `index`'s value at `(t, y)`: a smooth function of the state whose
    /// sign is bit `index` of [`kink_sides`](HybridSystem::kink_sides). Called
    /// only for a kink whose bit changed over a step; the default (a system
    /// without kinks) is never called.
    #[inline]
    fn kink(&self, _t: f64, _y: &[f64; N], _index: usize) -> f64 {
        0.0
    }

    /// The reset of guard `index`, applied at its located event time `t` with
    /// `y` the state there: may change the mode and jump `y`.
    fn reset(&mut self, t: f64, y: &mut [f64; N], index: usize) -> Self::Transition;

    /// The reset of guard `index` at `y`, making every discrete choice (a new
    /// mode, a kind of impact) as `nominal` made it in its latest reset.
    /// Differentiating a reset needs its choices fixed: at an event the state
    /// sits on the boundary between them (a lift-off at zero normal force).
    /// The default is [`reset`](HybridSystem::reset), right for systems
    /// whose resets make no choice.
    fn reset_replaying(
        &mut self,
        t: f64,
        y: &mut [f64; N],
        index: usize,
        _nominal: &Self,
    ) -> Self::Transition
    where
        Self: Sized,
    {
        self.reset(t, y, index)
    }
}

/// The time increment of a forward difference along `dy` at `y`:
/// `√ε (1 + ‖y‖) / ‖dy‖` (max norms), the usual choice for a directional
/// derivative, which balances truncation against rounding for a function of
/// the state of unit scale. 0 when `dy` is 0 or not finite.
#[inline]
pub fn fd_delta<const N: usize>(y: &[f64; N], dy: &[f64; N]) -> f64 {
    let ny = max_abs(y);
    let nd = max_abs(dy);
    let d = f64::EPSILON.sqrt() * (1.0 + ny) / nd;
    if d.is_finite() { d } else { 0.0 }
}

/// The largest `|v|` of `v` (NaN components skipped, 0 for none), as
/// `fold(0, f64::max)` gives it, without `f64::max`'s NaN handling: a NaN
/// fails the comparison just as `max` would skip it, and the plain
/// comparison is one `maxsd` (`fd_delta` runs at every step end: the NaN
/// handling made it cost a quarter of an RHS evaluation).
#[inline]
fn max_abs<const N: usize>(v: &[f64; N]) -> f64 {
    v.iter()
        .fold(0.0f64, |m, x| if x.abs() > m { x.abs() } else { m })
}

/// How an observed step ended.
#[derive(Clone, Copy, Debug)]
pub enum StepEnd<'a, A> {
    /// At an ordinary step end, where [`HybridSystem::rhs_aux`] wrote `aux`
    /// at `dense.y1`.
    Step {
        /// The right-hand side's by-products at the step's end.
        aux: &'a A,
    },
    /// At an event of guard `guard`: the step was cut there and its reset
    /// follows (the system is still in its mode before it).
    Event {
        /// Index of the guard that fired.
        guard: usize,
    },
}

/// Watches a run of the system `P`: what a run records, apart from what the
/// system is. Every hook may end the run with [`Flow::Stop`]; the defaults
/// do nothing. `()` is the observer that watches nothing.
pub trait Observer<const N: usize, P: HybridSystem<N>> {
    /// Called after every accepted step `[dense.t0, dense.t1]`, and after the
    /// part of a step that ends at an event (before its reset), with the
    /// dense output of that step and the system as it was on it.
    /// Statistics, recording and run-level checks go here.
    #[inline]
    fn on_step(&mut self, _system: &P, _dense: &Dense<N>, _end: StepEnd<'_, P::Aux>) -> Flow {
        Flow::Continue
    }

    /// Called after every reset, with the system and the state `y` after it
    /// and what the reset did. The run ends if this returns [`Flow::Stop`] or
    /// the transition [ends it](EndsRun::ends_run) by itself.
    #[inline]
    fn on_transition(
        &mut self,
        _system: &P,
        _t: f64,
        _y: &[f64; N],
        _transition: &P::Transition,
    ) -> Flow {
        Flow::Continue
    }

    /// Whether [`on_step`](Observer::on_step) evaluates the dense output of
    /// the step `[t0, t1]` strictly inside it (`Dense::eval` at
    /// `t ∈ (t0, t1)`), asked before the step is handed over. An observer
    /// that reads only `t0, t1, y0, y1` there returns `false`, and the engine
    /// hands it a cheaper interpolant (cubic Hermite): DOP853 then skips the
    /// 3 extra stages of its 7th-order dense output (20 % fewer right-hand-side
    /// evaluations). Event location always uses the method's full dense
    /// output. The default is `true`.
    #[inline]
    fn reads_interior(&self, _system: &P, _t0: f64, _t1: f64) -> bool {
        true
    }
}

/// The observer that watches nothing (and reads no interior).
impl<const N: usize, P: HybridSystem<N>> Observer<N, P> for () {
    #[inline]
    fn reads_interior(&self, _system: &P, _t0: f64, _t1: f64) -> bool {
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `max_abs` is bit for bit the `fold(0, f64::max)` of the absolute
    /// values it replaced, NaN components (skipped), infinities, negative
    /// zeros and subnormals included.
    #[test]
    fn max_abs_is_the_fold_of_f64_max() {
        let fold = |v: &[f64; 6]| v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let cases = [
            [0.0, -0.0, 0.0, -0.0, 0.0, 0.0],
            [1.0, -3.5, 2.0, f64::NAN, -7.25, 0.5],
            [f64::NAN, f64::NAN, f64::NAN, f64::NAN, f64::NAN, f64::NAN],
            [f64::NAN, -1e-310, 4e-320, -0.0, f64::NAN, 1e-308],
            [-f64::INFINITY, 1.0, f64::NAN, 2.0, 3.0, 4.0],
            [1e300, -1e300, 1e-300, f64::MAX, -f64::MAX, 5.0],
        ];
        for v in &cases {
            assert_eq!(max_abs(v).to_bits(), fold(v).to_bits(), "{v:?}");
        }
        // And `fd_delta` on a state with a NaN rate is what it was: finite,
        // from the finite components.
        let y = [1.0, -2.0, 0.5, 0.0, 0.0, 0.0];
        let dy = [f64::NAN, 4.0, -8.0, 0.0, 0.0, 0.0];
        assert_eq!(fd_delta(&y, &dy), f64::EPSILON.sqrt() * 3.0 / 8.0);
    }
}
