//! McGeer's rigid rimless wheel on the generic engine: a closed-form check of
//! [`hybrid::run`](crate::hybrid::run).
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
//! through [`hybrid::run`](crate::hybrid::run).

use crate::hybrid::{Crossing, EndReason, EngineOptions, Flow, Guards, HybridSystem, RunEnd, run};
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

impl RimlessWheel {
    /// A wheel with spokes `l`, half inter-spoke angle `alpha`, on slope
    /// `gamma`, under gravity `g`, with no touchdown yet.
    pub fn new(l: f64, alpha: f64, gamma: f64, g: f64) -> Self {
        Self {
            l,
            alpha,
            gamma,
            g,
            stop_after: 0,
            impacts: 0,
            last_rate_minus: f64::NAN,
            last_rate_plus: f64::NAN,
            last_impact_time: f64::NAN,
            rolled_back: false,
        }
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

    /// The step-to-step map by simulation: starts a copy of the wheel (counts
    /// cleared) at `θ = γ − α`, `θ̇ = omega`, runs it through
    /// [`hybrid::run`](crate::hybrid::run) up to the first touchdown, and
    /// returns the post-impact rate. `None` if the wheel rolled back, the run
    /// ended otherwise (time horizon [`RimlessWheel::stance_horizon`], step
    /// underflow, …).
    pub fn step_map(&self, omega: f64, opts: &EngineOptions) -> Option<f64> {
        let mut w = Self {
            stop_after: 1,
            ..Self::new(self.l, self.alpha, self.gamma, self.g)
        };
        let mut y = w.initial_state(omega);
        let end = run(&mut w, 0.0, &mut y, self.stance_horizon(), opts);
        (end.reason == EndReason::Stopped && w.impacts == 1).then_some(y[1])
    }

    /// [`step_map`](Self::step_map) and its derivative `dP/dω`, by the
    /// variational equations integrated through the stance and the touchdown's
    /// saltation ([`Variational`]): the same machinery as the RTW's step map.
    pub fn step_map_with_slope(&self, omega: f64, opts: &EngineOptions) -> Option<(f64, f64)> {
        let w = Self {
            stop_after: 1,
            ..Self::new(self.l, self.alpha, self.gamma, self.g)
        };
        let rate = (self.g / self.l).sqrt();
        let mut var = Variational::new(w, [1.0, rate]);
        let mut z: [f64; 6] = Variational::<Self, 2>::initial(&w.initial_state(omega));
        let end = run(&mut var, 0.0, &mut z, self.stance_horizon(), opts);
        // Column 1 of Φ: the response to the post-impact rate (θ is fixed
        // by the section).
        (end.reason == EndReason::Stopped && var.sys.impacts == 1)
            .then(|| (z[1], Variational::<Self, 2>::sensitivity(&z, 1, 1)))
    }

    /// Runs the wheel from `θ = γ − α`, `θ̇ = omega` at `t = 0` for `steps`
    /// touchdowns (or up to `t_end`) in one [`hybrid::run`](crate::hybrid::run):
    /// sets `stop_after = impacts + steps`. Returns the run's end; `y` is the
    /// final state, `self.last_rate_plus` the last post-impact rate.
    pub fn walk(
        &mut self,
        omega: f64,
        steps: u64,
        t_end: f64,
        opts: &EngineOptions,
        y: &mut [f64; 2],
    ) -> RunEnd {
        self.stop_after = self.impacts + steps;
        *y = self.initial_state(omega);
        run(self, 0.0, y, t_end, opts)
    }
}

impl HybridSystem<2> for RimlessWheel {
    type Aux = ();

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

    fn reset(&mut self, t: f64, y: &mut [f64; 2], index: usize) -> Flow {
        if index == GUARD_ROLLBACK {
            self.rolled_back = true;
            return Flow::Stop;
        }
        self.last_rate_minus = y[1];
        self.impact(y);
        self.last_rate_plus = y[1];
        self.last_impact_time = t;
        self.impacts += 1;
        if self.stop_after > 0 && self.impacts >= self.stop_after {
            Flow::Stop
        } else {
            Flow::Continue
        }
    }

    fn observes_interior(&self) -> bool {
        false
    }
}
