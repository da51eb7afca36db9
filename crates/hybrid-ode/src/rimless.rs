//! McGeer's rigid rimless wheel on the generic engine: a closed-form check of
//! [`run`].
//!
//! A hub of point mass on `n` massless spokes of length `l`, the angle between
//! neighbouring spokes `2α` (`α = π/n`), rolls down a slope of angle `γ` under
//! gravity `g` (McGeer 1990, "Passive dynamic walking"; the same model as
//! Drake's rimless-wheel example).
//!
//! **State** `[θ, θ̇]` (`N = 2`): `θ` is the angle of the stance spoke from the
//! *vertical*, positive when the hub is downhill of the contact point (the
//! rolling direction). In stance the wheel is an inverted pendulum,
//!
//! `θ̈ = (g/l) sin θ`.
//!
//! When both spokes touch the slope they are symmetric about the slope normal,
//! which leans `γ` downhill from the vertical; so a stance phase starts at
//! `θ = γ − α` and the next spoke touches down at `θ = γ + α`.
//!
//! **Guards**: index [`GUARD_TOUCHDOWN`], `θ − (γ + α)` rising (the next spoke
//! hits the slope); index [`GUARD_ROLLBACK`], `θ − (γ − α)` falling (the wheel
//! failed to pass the apex and rolled back onto the previous spoke: the run
//! stops).
//!
//! **Reset** (touchdown): the new spoke becomes the stance spoke,
//! `θ ← θ − 2α`, and the impact — inelastic, no slip, no bounce — conserves
//! the angular momentum about the new contact point. With all mass at the
//! hub, the velocity component along the new spoke is lost and the one normal
//! to it is kept, so `θ̇⁺ = θ̇⁻ cos 2α`.
//!
//! **Step-to-step map** of the post-impact rate `ω = θ̇⁺`. Energy is conserved
//! in stance, `θ̇²/2 + (g/l) cos θ = const`, so from `θ = γ − α` to `γ + α`
//!
//! `θ̇⁻² = ω² + 2(g/l)(cos(γ−α) − cos(γ+α)) = ω² + 4(g/l) sin α sin γ`,
//!
//! and `P(ω) = cos 2α · sqrt(ω² + 4(g/l) sin α sin γ)`. Its fixed point solves
//! `ω² = cos²2α (ω² + 4(g/l) sin α sin γ)`:
//!
//! `ω* = cot 2α · sqrt(4 (g/l) sin α sin γ)`.
//!
//! The slope `dP/dω = cos 2α · ω / sqrt(ω² + 4(g/l) sin α sin γ)`, and since
//! `sqrt(ω*² + 4(g/l) sin α sin γ) = ω*/cos 2α` at the fixed point,
//! `dP/dω(ω*) = cos² 2α` — the gait is stable for every `α ∈ (0, π/4)`.
//! (A stance phase only completes if the wheel passes the apex `θ = 0`, which
//! when `γ < α` needs `ω² > 2(g/l)(1 − cos(α − γ))`.)
//!
//! `tests/rimless.rs` checks `ω*`, `cos² 2α` and the reset against simulations
//! through [`run`].

use crate::engine::{EndReason, EngineOptions, RunEnd, run};
use crate::system::{Crossing, EndsRun, Flow, Guards, HybridSystem, Observer};
use crate::variational::Variational;

/// Index of the touchdown guard `θ − (γ + α)` (rising).
pub const GUARD_TOUCHDOWN: usize = 0;
/// Index of the roll-back guard `θ − (γ − α)` (falling).
pub const GUARD_ROLLBACK: usize = 1;

/// McGeer's rigid rimless wheel as a [`HybridSystem<2>`] (see the module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RimlessWheel {
    /// Spoke length (m).
    pub l: f64,
    /// Half the angle between neighbouring spokes (rad); `α = π/n` for `n` spokes.
    pub alpha: f64,
    /// Slope angle (rad), positive downhill in the rolling direction.
    pub gamma: f64,
    /// Gravity (m/s²).
    pub g: f64,
}

/// What a reset of the wheel did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Stride {
    /// The next spoke touched down: `θ̇` just before and just after the impact.
    Touchdown {
        /// `θ̇⁻`.
        rate_minus: f64,
        /// `θ̇⁺ = θ̇⁻ cos 2α`.
        rate_plus: f64,
    },
    /// The wheel rolled back onto the previous spoke: the run ends.
    RolledBack,
}

impl EndsRun for Stride {
    fn ends_run(&self) -> bool {
        *self == Stride::RolledBack
    }
}

/// The observer of a walk: counts touchdowns, keeps the latest impact, and
/// stops after a number of them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Walk {
    /// Stop the run after this many touchdowns (0: never).
    pub stop_after: u64,
    /// Touchdowns so far.
    pub impacts: u64,
    /// `θ̇` just before the last touchdown (NaN before the first).
    pub last_rate_minus: f64,
    /// `θ̇` just after the last touchdown (NaN before the first).
    pub last_rate_plus: f64,
    /// Time of the last touchdown (NaN before the first).
    pub last_impact_time: f64,
    /// The wheel rolled back onto the previous spoke (the run was stopped).
    pub rolled_back: bool,
}

impl Walk {
    /// A walk of `steps` touchdowns (0: unbounded), none yet.
    pub fn stopping_after(steps: u64) -> Self {
        Self {
            stop_after: steps,
            impacts: 0,
            last_rate_minus: f64::NAN,
            last_rate_plus: f64::NAN,
            last_impact_time: f64::NAN,
            rolled_back: false,
        }
    }
}

impl Observer<2, RimlessWheel> for Walk {
    fn on_transition(&mut self, _: &RimlessWheel, t: f64, _: &[f64; 2], stride: &Stride) -> Flow {
        match *stride {
            Stride::RolledBack => {
                self.rolled_back = true;
                Flow::Stop
            }
            Stride::Touchdown {
                rate_minus,
                rate_plus,
            } => {
                self.last_rate_minus = rate_minus;
                self.last_rate_plus = rate_plus;
                self.last_impact_time = t;
                self.impacts += 1;
                if self.stop_after > 0 && self.impacts >= self.stop_after {
                    Flow::Stop
                } else {
                    Flow::Continue
                }
            }
        }
    }

    fn reads_interior(&self, _: &RimlessWheel, _t0: f64, _t1: f64) -> bool {
        false
    }
}

impl RimlessWheel {
    /// A wheel with spokes `l`, half inter-spoke angle `alpha`, on slope
    /// `gamma`, under gravity `g`.
    pub fn new(l: f64, alpha: f64, gamma: f64, g: f64) -> Self {
        Self { l, alpha, gamma, g }
    }
    /// A wheel with `n` spokes (`α = π/n`).
    pub fn with_spokes(n: u32, l: f64, gamma: f64, g: f64) -> Self {
        Self::new(l, core::f64::consts::PI / n as f64, gamma, g)
    }

    /// `θ` at the start of a stance phase, `γ − α`.
    #[inline]
    pub fn stance_start(&self) -> f64 {
        self.gamma - self.alpha
    }

    /// `θ` at touchdown of the next spoke, `γ + α`.
    #[inline]
    pub fn touchdown_angle(&self) -> f64 {
        self.gamma + self.alpha
    }

    /// The state at the start of a stance phase with rate `omega`: `[γ − α, ω]`.
    #[inline]
    pub fn initial_state(&self, omega: f64) -> [f64; 2] {
        [self.stance_start(), omega]
    }

    /// The impact's rate ratio `θ̇⁺/θ̇⁻ = cos 2α`.
    #[inline]
    pub fn impact_ratio(&self) -> f64 {
        (2.0 * self.alpha).cos()
    }

    /// The stance phase's gain `θ̇⁻² − θ̇⁺² = 4 (g/l) sin α sin γ`.
    #[inline]
    pub fn stance_gain(&self) -> f64 {
        4.0 * (self.g / self.l) * self.alpha.sin() * self.gamma.sin()
    }

    /// Smallest `θ̇⁺²` that carries the hub over the apex `θ = 0`:
    /// `2(g/l)(1 − cos(α − γ))` if `γ < α`, else 0.
    #[inline]
    pub fn apex_rate_sq(&self) -> f64 {
        if self.gamma < self.alpha {
            2.0 * (self.g / self.l) * (1.0 - (self.alpha - self.gamma).cos())
        } else {
            0.0
        }
    }

    /// McGeer's fixed point of the post-impact rate,
    /// `ω* = cot 2α · sqrt(4 (g/l) sin α sin γ)`.
    #[inline]
    pub fn omega_star(&self) -> f64 {
        self.stance_gain().sqrt() / (2.0 * self.alpha).tan()
    }

    /// The closed-form step-to-step map `P(ω) = cos 2α · sqrt(ω² + 4(g/l) sin α sin γ)`,
    /// or `None` if a wheel with `θ̇⁺ = ω` does not pass the apex.
    pub fn step_map_closed_form(&self, omega: f64) -> Option<f64> {
        if omega > 0.0 && omega * omega > self.apex_rate_sq() {
            Some(self.impact_ratio() * (omega * omega + self.stance_gain()).sqrt())
        } else {
            None
        }
    }

    /// The closed-form slope `dP/dω = cos 2α · ω / sqrt(ω² + 4(g/l) sin α sin γ)`;
    /// at `ω*` it equals `cos² 2α`.
    pub fn step_map_slope(&self, omega: f64) -> f64 {
        self.impact_ratio() * omega / (omega * omega + self.stance_gain()).sqrt()
    }

    /// The touchdown reset: `θ ← θ − 2α`, `θ̇ ← θ̇ cos 2α`.
    #[inline]
    pub fn impact(&self, y: &mut [f64; 2]) {
        y[0] -= 2.0 * self.alpha;
        y[1] *= self.impact_ratio();
    }

    /// Time horizon of one stance phase in [`RimlessWheel::step_map`]:
    /// `1000 sqrt(l/g)`, far longer than any stance that passes the apex
    /// other than from a rate within rounding of the apex rate.
    pub fn stance_horizon(&self) -> f64 {
        1000.0 * (self.l / self.g).sqrt()
    }

    /// The step-to-step map by simulation: starts the wheel at `θ = γ − α`,
    /// `θ̇ = omega`, runs it through [`run`] up to the first
    /// touchdown, and returns the post-impact rate. `None` if the wheel
    /// rolled back, the run ended otherwise (time horizon
    /// [`RimlessWheel::stance_horizon`], step underflow, …).
    pub fn step_map(&self, omega: f64, opts: &EngineOptions) -> Option<f64> {
        let mut w = *self;
        let mut walk = Walk::stopping_after(1);
        let mut y = w.initial_state(omega);
        let end = run(&mut w, &mut walk, 0.0, &mut y, self.stance_horizon(), opts);
        (end.reason == EndReason::Stopped && walk.impacts == 1).then_some(y[1])
    }

    /// [`step_map`](Self::step_map) and its derivative `dP/dω`, by the
    /// variational equations integrated through the stance and the touchdown's
    /// saltation ([`Variational`]): the same machinery as the RTW's step map.
    pub fn step_map_with_slope(&self, omega: f64, opts: &EngineOptions) -> Option<(f64, f64)> {
        let rate = (self.g / self.l).sqrt();
        let mut var = Variational::new(*self, Walk::stopping_after(1), [1.0, rate]);
        let mut z: [f64; 6] = Variational::<Self, Walk, 2>::initial(&self.initial_state(omega));
        let end = var.run(0.0, &mut z, self.stance_horizon(), opts);
        // Column 1 of Φ: the response to the post-impact rate (θ is fixed
        // by the section).
        (end.reason == EndReason::Stopped && var.observer.impacts == 1)
            .then(|| (z[1], Variational::<Self, Walk, 2>::sensitivity(&z, 1, 1)))
    }

    /// Runs the wheel from `θ = γ − α`, `θ̇ = omega` at `t = 0` for `steps`
    /// touchdowns (or up to `t_end`) in one [`run`]. Returns the
    /// run's end and its [`Walk`] (`walk.last_rate_plus` is the last
    /// post-impact rate); `y` is the final state.
    pub fn walk(
        &self,
        omega: f64,
        steps: u64,
        t_end: f64,
        opts: &EngineOptions,
        y: &mut [f64; 2],
    ) -> (RunEnd, Walk) {
        let mut walk = Walk::stopping_after(steps);
        *y = self.initial_state(omega);
        let end = run(&mut { *self }, &mut walk, 0.0, y, t_end, opts);
        (end, walk)
    }
}

impl HybridSystem<2> for RimlessWheel {
    type Aux = ();
    type Transition = Stride;

    #[inline]
    fn rhs(&self, _t: f64, y: &[f64; 2], dy: &mut [f64; 2]) {
        dy[0] = y[1];
        dy[1] = (self.g / self.l) * y[0].sin();
    }

    #[inline]
    fn guards(&self, _t: f64, y: &[f64; 2], out: &mut Guards) {
        out.clear();
        out.push(y[0] - self.touchdown_angle(), Crossing::Rising);
        out.push(y[0] - self.stance_start(), Crossing::Falling);
    }

    fn reset(&mut self, _t: f64, y: &mut [f64; 2], index: usize) -> Stride {
        if index == GUARD_ROLLBACK {
            return Stride::RolledBack;
        }
        let rate_minus = y[1];
        self.impact(y);
        Stride::Touchdown {
            rate_minus,
            rate_plus: y[1],
        }
    }
}
