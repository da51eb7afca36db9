//! The RTW as a hybrid system (docs/model.md §2–§5): continuous dynamics of the
//! three rods in their contact modes, the guards that end a mode, and the
//! resets (touchdown, lift-off, re-stick, slip, failure).
//!
//! State: three rods × six slots and two dissipated energies
//! ([`crate::plant::slots`]). [`Rtw`] is the one [`HybridSystem`] of the
//! model; what a run records is its observer's business
//! ([`crate::run::simulate`], [`crate::cycles::stepmap`],
//! [`crate::plant::initial`]'s settling).

use crate::options::Options;
use crate::outcome::FailureDetail;
use crate::params::Physical;
use crate::plant::contact::{ImpactKind, Load, RodBody, RodMode};
use crate::plant::geometry::{RodFrame, RodState, Tip, V2, add, scale};
use crate::plant::slots::{self, DISSIPATED, FRICTION, N, OMEGA, THETA, VX};
use crate::plant::strings::StringSet;
use hybrid_ode::system::{MAX_GUARDS, fd_delta};
use hybrid_ode::{Crossing, EndsRun, Guards, HybridSystem};
use std::ops::ControlFlow;

/// What a guard watches.
#[derive(Clone, Copy, Debug, PartialEq)]
#[allow(missing_docs)] // the fields: the rod (0, 1, 2 for a, b, c) and its tip
pub enum GuardKind {
    /// A free rod's tip reaches the ground moving down.
    Touchdown { rod: usize, tip: Tip },
    /// A grounded rod's normal force falls to zero.
    LiftOff { rod: usize },
    /// A grounded rod's other tip reaches the ground: the rod lies down.
    RodDown { rod: usize },
    /// A sliding tip's tangential velocity reverses.
    Restick { rod: usize },
    /// A sticking tip's force leaves the friction cone (finite μ).
    Slip { rod: usize },
    /// The centre of mass sinks below the collapse height.
    ComLow,
}

/// What a reset did, for the run's observer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Transition {
    /// A touchdown of `tip` of `rod`, with the rod's angular velocity just after.
    Touchdown {
        /// The landing rod.
        rod: usize,
        /// Its landing tip.
        tip: Tip,
        /// Its angular velocity just after the impact.
        omega_after: f64,
    },
    /// Any other change of a rod's mode.
    ModeChange {
        /// The rod.
        rod: usize,
    },
    /// A failure that ends the run: a rod lay down or the centre of mass sank.
    Failure(FailureDetail),
}

impl EndsRun for Transition {
    fn ends_run(&self) -> bool {
        matches!(self, Transition::Failure(_))
    }
}

/// What [`Rtw::dynamics`] computed at a state on the way that the guards
/// also need there.
#[derive(Clone, Copy, Debug, Default)]
pub struct AtState {
    /// The rods' frames.
    pub frames: [RodFrame; 3],
    /// Contact forces λ of the rods (zero when free).
    pub lambda: [V2; 3],
}

/// The discrete choices a reset made: the rod's new mode and, at a
/// touchdown, the kind of impact.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Choice {
    mode: RodMode,
    impact: Option<ImpactKind>,
}

/// The RTW: its constants and its current contact modes.
#[derive(Clone, Debug)]
pub struct Rtw {
    /// The rods' inertial constants.
    pub(crate) body: RodBody,
    /// The strings.
    pub(crate) strings: StringSet,
    /// Gravity in the slope frame, g (sin φ, −cos φ).
    pub(crate) gravity: V2,
    /// Friction coefficient (infinite: no slip, frictionless slide).
    pub(crate) mu: f64,
    /// The rods' contact modes.
    pub(crate) modes: [RodMode; 3],
    /// Touchdown is declared at this tip height (slightly below 0).
    pub(crate) touchdown_height: f64,
    /// A re-stick needs the sliding tip's velocity to reverse by more than this.
    pub(crate) restick_speed: f64,
    /// Collapse when the centre of mass height falls below this.
    pub(crate) collapse_height: f64,
    /// `mu_required` counts a sticking rod only while its normal force
    /// exceeds this: 5 % of a rod's weight.
    pub(crate) mu_floor: f64,
    /// The choices of the last reset that made any.
    pub(crate) last_choice: Option<Choice>,
    /// When set, resets replay these choices instead of making their own: the
    /// derivative of a reset (the variational equations' saltation) is taken
    /// with its discrete choices fixed, as they are at the event itself.
    pub(crate) replay: Option<Choice>,
    /// Rate γ [1/s] of a velocity damping `−γ m v`, `−γ I ω` on every rod,
    /// used only while the star is being set down ([`crate::plant::initial`]'s
    /// dynamic relaxation). It vanishes at rest, so the state it settles to
    /// is a static equilibrium of the real forces. Zero in every run.
    pub(crate) relax: f64,
}

impl Rtw {
    /// The RTW of `phys` with the modelling choices of `opts`, every rod free.
    pub fn new(phys: &Physical, opts: &Options) -> Self {
        let (sin, cos) = phys.phi.sin_cos();
        let gravity = [phys.g * sin, -phys.g * cos];
        Self {
            body: RodBody {
                m: phys.m,
                inertia: phys.inertia,
                half_length: phys.length / 2.0,
            },
            strings: StringSet::new(phys, opts),
            gravity,
            mu: opts.contact.mu,
            modes: [RodMode::Free; 3],
            touchdown_height: -opts.touchdown_offset * phys.length,
            restick_speed: 1e-9 * phys.length,
            collapse_height: opts.collapse_height_ratio * phys.standing_height(),
            mu_floor: 0.05 * phys.m * gravity[0].hypot(gravity[1]),
            last_choice: None,
            replay: None,
            relax: 0.0,
        }
    }

    /// Per-rod frames (full coordinates plus unit vectors) of state `y`.
    #[inline]
    pub fn frames(&self, y: &[f64; N]) -> [RodFrame; 3] {
        std::array::from_fn(|i| self.body.frame(self.modes[i], slots::rod(y, i)))
    }

    /// Full coordinates of the rods.
    pub fn rods(&self, y: &[f64; N]) -> [RodState; 3] {
        std::array::from_fn(|i| self.body.rod_state(self.modes[i], slots::rod(y, i)))
    }

    /// [`rods`](Self::rods) from the frames of `y` (no trigonometry again).
    fn rods_of(y: &[f64; N], frames: &[RodFrame; 3]) -> [RodState; 3] {
        std::array::from_fn(|i| frames[i].state(y[slots::at(i, THETA)]))
    }

    /// Writes the rods back into `y` in the current modes.
    pub fn store(&self, rods: &[RodState; 3], y: &mut [f64; N]) {
        for (i, r) in rods.iter().enumerate() {
            self.body.slots(self.modes[i], r, slots::rod_mut(y, i));
        }
    }

    /// External loads (strings + gravity) on each rod, and the damper power.
    #[inline]
    pub fn loads(&self, frames: &[RodFrame; 3]) -> ([Load; 3], f64) {
        let s = self.strings.loads(frames);
        let weight = scale(self.body.m, self.gravity);
        let mut loads: [Load; 3] = std::array::from_fn(|i| Load {
            force: add(s.force[i], weight),
            torque: s.torque[i],
        });
        if self.relax > 0.0 {
            for (load, f) in loads.iter_mut().zip(frames) {
                load.force = add(load.force, scale(-self.relax * self.body.m, f.v));
                load.torque -= self.relax * self.body.inertia * f.omega;
            }
        }
        (loads, s.dissipation)
    }

    /// Continuous dynamics: `ẏ = f(y)` in the current modes. Returns the
    /// frames and contact forces λ at `y` it computed on the way (λ bit for
    /// bit that of [`contact_forces`](Self::contact_forces)), so that the
    /// guards at the same state need not compute them again.
    #[inline]
    pub fn dynamics(&self, y: &[f64; N], dy: &mut [f64; N]) -> AtState {
        let frames = self.frames(y);
        let (loads, dissipation) = self.loads(&frames);
        let mut friction = 0.0;
        let mut lambda = [[0.0; 2]; 3];
        for i in 0..3 {
            let a = self
                .body
                .accel(self.modes[i], &frames[i], &loads[i], self.mu);
            slots::rod_mut(dy, i).copy_from_slice(&a.deriv);
            if let RodMode::Slide { .. } = self.modes[i] {
                // Power of friction on the sliding tip (λ_x opposes ẋ_t).
                friction -= a.lambda[0] * y[slots::at(i, VX)];
            }
            lambda[i] = a.lambda;
        }
        dy[DISSIPATED] = dissipation;
        dy[FRICTION] = friction;
        AtState { frames, lambda }
    }

    /// Contact forces λ of the rods at `y` (zero when free).
    pub fn contact_forces(&self, y: &[f64; N]) -> [V2; 3] {
        self.contact_forces_of(&self.frames(y))
    }

    /// Contact forces λ of the rods with frames `frames` (zero when free).
    fn contact_forces_of(&self, frames: &[RodFrame; 3]) -> [V2; 3] {
        let (loads, _) = self.loads(frames);
        let mut lambda = [[0.0; 2]; 3];
        for i in 0..3 {
            if self.modes[i] != RodMode::Free {
                lambda[i] = self
                    .body
                    .accel(self.modes[i], &frames[i], &loads[i], self.mu)
                    .lambda;
            }
        }
        lambda
    }

    /// The guards of the current modes, in a fixed order that depends only
    /// on the modes (the engine compares the same index across a step).
    #[inline]
    pub fn guard_kinds(&self, mut visit: impl FnMut(GuardKind)) {
        let _: ControlFlow<()> = self.try_guard_kinds(|kind| {
            visit(kind);
            ControlFlow::Continue(())
        });
    }

    /// [`guard_kinds`](Self::guard_kinds) until `visit` breaks: the lookup
    /// of one guard stops at it (root finding asks at every iterate).
    #[inline]
    fn try_guard_kinds<B>(
        &self,
        mut visit: impl FnMut(GuardKind) -> ControlFlow<B>,
    ) -> ControlFlow<B> {
        for (rod, mode) in self.modes.iter().enumerate() {
            match *mode {
                RodMode::Free => {
                    visit(GuardKind::Touchdown {
                        rod,
                        tip: Tip::Plus,
                    })?;
                    visit(GuardKind::Touchdown {
                        rod,
                        tip: Tip::Minus,
                    })?;
                }
                RodMode::Stick { .. } => {
                    visit(GuardKind::LiftOff { rod })?;
                    visit(GuardKind::RodDown { rod })?;
                    if self.mu.is_finite() {
                        visit(GuardKind::Slip { rod })?;
                    }
                }
                RodMode::Slide { .. } => {
                    visit(GuardKind::LiftOff { rod })?;
                    visit(GuardKind::RodDown { rod })?;
                    visit(GuardKind::Restick { rod })?;
                }
            }
        }
        visit(GuardKind::ComLow)
    }

    fn guards_of(&self, y: &[f64; N], frames: &[RodFrame; 3], lambda: &[V2; 3], out: &mut Guards) {
        out.clear();
        self.guard_kinds(|kind| {
            let value = self.guard_value(kind, y, |rod| frames[rod], |rod| lambda[rod]);
            out.push(value, Crossing::Falling);
        });
    }

    /// The value of guard `kind` at `y`, given each rod's frame and contact
    /// force λ there (asked for only when this guard needs them).
    #[inline]
    fn guard_value(
        &self,
        kind: GuardKind,
        y: &[f64; N],
        frame: impl Fn(usize) -> RodFrame,
        lambda: impl Fn(usize) -> V2,
    ) -> f64 {
        let tip_height =
            |rod: usize, tip: Tip| frame(rod).point(tip.sign() * self.body.half_length).0[1];
        match kind {
            GuardKind::Touchdown { rod, tip } => tip_height(rod, tip) - self.touchdown_height,
            GuardKind::LiftOff { rod } => lambda(rod)[1],
            GuardKind::RodDown { rod } => {
                let tip = self.modes[rod].tip().expect("grounded rod");
                tip_height(rod, tip.other())
            }
            GuardKind::Restick { rod } => {
                let RodMode::Slide { dir, .. } = self.modes[rod] else {
                    unreachable!("restick guard on a sliding rod")
                };
                y[slots::at(rod, VX)] * dir + self.restick_speed
            }
            GuardKind::Slip { rod } => {
                let l = lambda(rod);
                self.mu * l[1] - l[0].abs()
            }
            GuardKind::ComLow => {
                (frame(0).c[1] + frame(1).c[1] + frame(2).c[1]) / 3.0 - self.collapse_height
            }
        }
    }

    /// The time derivative of guard `kind` at a state with frames `frames`
    /// and `ẏ = dy`, where it is kinematic: a tip height's is the tip's
    /// vertical velocity, the centre of mass's its mean vertical velocity, a
    /// re-stick's the sliding tip's acceleration. `None` for a guard on a
    /// contact force (lift-off, slip), whose rate needs the forces' own.
    #[inline]
    fn kinematic_guard_rate(
        &self,
        kind: GuardKind,
        dy: &[f64; N],
        frames: &[RodFrame; 3],
    ) -> Option<f64> {
        let tip_rate =
            |rod: usize, tip: Tip| frames[rod].point(tip.sign() * self.body.half_length).1[1];
        match kind {
            GuardKind::Touchdown { rod, tip } => Some(tip_rate(rod, tip)),
            GuardKind::RodDown { rod } => {
                let tip = self.modes[rod].tip().expect("grounded rod");
                Some(tip_rate(rod, tip.other()))
            }
            GuardKind::Restick { rod } => {
                let RodMode::Slide { dir, .. } = self.modes[rod] else {
                    unreachable!("restick guard on a sliding rod")
                };
                Some(dy[slots::at(rod, VX)] * dir)
            }
            GuardKind::ComLow => Some((frames[0].v[1] + frames[1].v[1] + frames[2].v[1]) / 3.0),
            GuardKind::LiftOff { .. } | GuardKind::Slip { .. } => None,
        }
    }

    /// The guard of index `index` in the current modes.
    pub fn guard_kind(&self, index: usize) -> GuardKind {
        let mut k = 0;
        let found = self.try_guard_kinds(|kind| {
            if k == index {
                return ControlFlow::Break(kind);
            }
            k += 1;
            ControlFlow::Continue(())
        });
        match found {
            ControlFlow::Break(kind) => kind,
            ControlFlow::Continue(()) => panic!("guard index {index} out of range"),
        }
    }

    /// Re-applies the mode-choice rule to a grounded rod; `leaving`: the mode
    /// whose condition the event found violated, which the rod must leave.
    fn rechoose(
        &mut self,
        y: &mut [f64; N],
        rod: usize,
        tip: Tip,
        at_rest: bool,
        leaving: Option<RodMode>,
    ) {
        let frames = self.frames(y);
        let rods = Self::rods_of(y, &frames);
        self.modes[rod] = match self.replay {
            Some(choice) => choice.mode,
            None => {
                let (loads, _) = self.loads(&frames);
                let (r, load) = (&rods[rod], &loads[rod]);
                match leaving {
                    Some(mode) => self
                        .body
                        .choose_mode_leaving(r, tip, at_rest, load, self.mu, mode),
                    None => self.body.choose_mode(r, tip, at_rest, load, self.mu),
                }
            }
        };
        self.last_choice = Some(Choice {
            mode: self.modes[rod],
            impact: None,
        });
        self.body
            .slots(self.modes[rod], &rods[rod], slots::rod_mut(y, rod));
    }

    /// Touchdown of a free rod's tip: the impact, then the mode choice.
    pub fn touchdown(&mut self, y: &mut [f64; N], rod: usize, tip: Tip) -> Transition {
        let rods = self.rods(y);
        let impact = match self.replay.and_then(|c| c.impact) {
            Some(kind) => self.body.impact(&rods[rod], tip, kind),
            None => self.body.touchdown(&rods[rod], tip, self.mu),
        };
        let mut after = impact.after;
        // Put the tip exactly on the ground (it was declared a hair below).
        let (p, _) = self.body.tip_point(&after, tip);
        after.c[1] -= p[1];
        let mut rods = rods;
        rods[rod] = after;
        // Mode choice needs the loads with the rod in its new place.
        let frames: [RodFrame; 3] = std::array::from_fn(|i| RodFrame::new(&rods[i]));
        self.modes[rod] = match self.replay {
            Some(choice) => choice.mode,
            None => {
                let (loads, _) = self.loads(&frames);
                self.body
                    .choose_mode(&after, tip, impact.sticks(), &loads[rod], self.mu)
            }
        };
        self.last_choice = Some(Choice {
            mode: self.modes[rod],
            impact: Some(impact.kind),
        });
        self.body
            .slots(self.modes[rod], &after, slots::rod_mut(y, rod));
        Transition::Touchdown {
            rod,
            tip,
            omega_after: y[slots::at(rod, OMEGA)],
        }
    }

    /// The largest friction ratio |λ_x|/λ_y over the sticking rods whose
    /// normal force exceeds 5 % of a rod's weight (docs/model.md §4's
    /// `mu_required`; the raw ratio is infinite at every lift-off), or 0.
    pub fn friction_ratio(&self, y: &[f64; N]) -> f64 {
        // Only sticking rods count: without one, no contact force is needed.
        if !self.any_sticks() {
            return 0.0;
        }
        self.friction_ratio_of(&self.contact_forces(y))
    }

    /// [`friction_ratio`](Self::friction_ratio) at the state whose frames
    /// are `frames`.
    pub fn friction_ratio_at(&self, frames: &[RodFrame; 3]) -> f64 {
        if !self.any_sticks() {
            return 0.0;
        }
        self.friction_ratio_of(&self.contact_forces_of(frames))
    }

    /// Whether a rod sticks.
    fn any_sticks(&self) -> bool {
        self.modes
            .iter()
            .any(|m| matches!(m, RodMode::Stick { .. }))
    }

    /// [`friction_ratio`](Self::friction_ratio) from the contact forces.
    pub fn friction_ratio_of(&self, lambda: &[V2; 3]) -> f64 {
        let floor = self.mu_floor;
        (0..3)
            .filter(|&i| matches!(self.modes[i], RodMode::Stick { .. }))
            .map(|i| lambda[i])
            .filter(|l| l[1] > floor)
            .map(|l| l[0].abs() / l[1])
            .fold(0.0, f64::max)
    }

    /// Kinetic, gravitational and elastic energy of state `y`.
    pub fn energy(&self, y: &[f64; N]) -> (f64, f64, f64) {
        self.energy_at(y, &self.frames(y))
    }

    /// [`energy`](Self::energy) of `y`, whose frames are `frames`.
    pub fn energy_at(&self, y: &[f64; N], frames: &[RodFrame; 3]) -> (f64, f64, f64) {
        let rods = Self::rods_of(y, frames);
        let kinetic = rods.iter().map(|r| self.body.kinetic(r)).sum();
        let gravity = -self.body.m
            * rods
                .iter()
                .map(|r| r.c[0] * self.gravity[0] + r.c[1] * self.gravity[1])
                .sum::<f64>();
        (kinetic, gravity, self.strings.potential(frames))
    }

    /// Total mechanical energy (kinetic + gravity + strings).
    pub fn total_energy(&self, y: &[f64; N]) -> f64 {
        self.total_energy_at(y, &self.frames(y))
    }

    /// [`total_energy`](Self::total_energy) of `y`, whose frames are `frames`.
    pub fn total_energy_at(&self, y: &[f64; N], frames: &[RodFrame; 3]) -> f64 {
        let (k, g, s) = self.energy_at(y, frames);
        k + g + s
    }

    /// Centre of mass of the three rods.
    pub fn centre_of_mass(&self, y: &[f64; N]) -> V2 {
        Self::centre_of_mass_at(&self.frames(y))
    }

    /// Centre of mass of the rods with frames `f`.
    pub fn centre_of_mass_at(f: &[RodFrame; 3]) -> V2 {
        [
            (f[0].c[0] + f[1].c[0] + f[2].c[0]) / 3.0,
            (f[0].c[1] + f[1].c[1] + f[2].c[1]) / 3.0,
        ]
    }

    /// Number of rods with a tip on the ground (0 NLSP … 3 TLSP).
    pub fn contact_state(&self) -> usize {
        self.modes.iter().filter(|m| m.tip().is_some()).count()
    }

    /// Number of rods sliding.
    pub fn sliding(&self) -> usize {
        self.modes
            .iter()
            .filter(|m| matches!(m, RodMode::Slide { .. }))
            .count()
    }
}

impl Rtw {
    /// The rods' inertial constants.
    pub fn body(&self) -> &RodBody {
        &self.body
    }

    /// Gravity in the slope frame, g (sin φ, −cos φ).
    pub fn gravity(&self) -> V2 {
        self.gravity
    }

    /// The friction coefficient μ (infinite: no slip, frictionless slide).
    pub fn mu(&self) -> f64 {
        self.mu
    }

    /// The rods' contact modes.
    pub fn modes(&self) -> [RodMode; 3] {
        self.modes
    }

    /// Puts the rods in `modes` (the state's slots must be read in them).
    pub fn set_modes(&mut self, modes: [RodMode; 3]) {
        self.modes = modes;
    }
}

/// The RTW as a hybrid system: the dynamics of its modes, every guard firing
/// on a falling crossing of zero, and the resets of [`GuardKind`]. It is
/// autonomous (`t` is not used).
impl HybridSystem<N> for Rtw {
    /// Frames and contact forces λ of the rods.
    type Aux = AtState;
    type Transition = Transition;

    #[inline]
    fn rhs(&self, _t: f64, y: &[f64; N], dy: &mut [f64; N]) {
        self.dynamics(y, dy);
    }

    #[inline]
    fn rhs_aux(&self, _t: f64, y: &[f64; N], dy: &mut [f64; N], at: &mut AtState) {
        *at = self.dynamics(y, dy);
    }

    #[inline]
    fn guards(&self, _t: f64, y: &[f64; N], out: &mut Guards) {
        let frames = self.frames(y);
        let lambda = self.contact_forces_of(&frames);
        self.guards_of(y, &frames, &lambda, out);
    }

    /// Guard `index` alone at `y`, computing only what it needs: a tip height
    /// needs one rod's frame (one `sin_cos`), a contact force the string
    /// loads and that rod's constraint equations.
    #[inline]
    fn guard(&self, _t: f64, y: &[f64; N], index: usize) -> f64 {
        let frame = |rod: usize| self.body.frame(self.modes[rod], slots::rod(y, rod));
        let lambda = |rod: usize| {
            let frames = self.frames(y);
            let (loads, _) = self.loads(&frames);
            self.body
                .accel(self.modes[rod], &frames[rod], &loads[rod], self.mu)
                .lambda
        };
        self.guard_value(self.guard_kind(index), y, frame, lambda)
    }

    /// The guards' rates at a step end: the kinematic ones in closed form
    /// from the frames the right-hand side made there; those on a contact
    /// force by a forward difference along `ẏ`, from one evaluation of the
    /// contact forces (none while every rod is free).
    fn guard_rates(
        &self,
        _t: f64,
        y: &[f64; N],
        dy: &[f64; N],
        at: &AtState,
        g: &Guards,
        out: &mut [f64; MAX_GUARDS],
    ) {
        // The contact forces a small time `d` ahead, if a rod is on the
        // ground (only its guards read them). Its frames turn each rod's `e`
        // by dθ = d ω to first order: the error, (d ω)²/2 ≈ 1e-18, is below
        // rounding, and it saves three `sin_cos`.
        let grounded = self.modes.iter().any(|m| *m != RodMode::Free);
        let d = if grounded { fd_delta(y, dy) } else { 0.0 };
        let mut yd = *y;
        let mut ahead = AtState::default();
        if d != 0.0 {
            for (a, b) in yd.iter_mut().zip(dy) {
                *a += d * b;
            }
            ahead.frames = std::array::from_fn(|i| {
                let e = at.frames[i].e;
                let turn = d * dy[slots::at(i, THETA)];
                let e = [e[0] - turn * e[1], e[1] + turn * e[0]];
                self.body.frame_with(self.modes[i], slots::rod(&yd, i), e)
            });
            ahead.lambda = self.contact_forces_of(&ahead.frames);
        }
        let mut k = 0;
        self.guard_kinds(|kind| {
            out[k] = match self.kinematic_guard_rate(kind, dy, &at.frames) {
                Some(rate) => rate,
                None if d == 0.0 => 0.0,
                None => {
                    let v = self.guard_value(
                        kind,
                        &yd,
                        |rod| ahead.frames[rod],
                        |rod| ahead.lambda[rod],
                    );
                    (v - g.value[k]) / d
                }
            };
            k += 1;
        });
    }

    /// The guards at `y` from what [`dynamics`](Rtw::dynamics) returned there.
    #[inline]
    fn guards_aux(&self, _t: f64, y: &[f64; N], at: &AtState, out: &mut Guards) {
        self.guards_of(y, &at.frames, &at.lambda, out);
    }

    fn reset(&mut self, _t: f64, y: &mut [f64; N], index: usize) -> Transition {
        match self.guard_kind(index) {
            GuardKind::Touchdown { rod, tip } => self.touchdown(y, rod, tip),
            GuardKind::LiftOff { rod } => {
                let tip = self.modes[rod].tip().expect("grounded rod");
                let at_rest = matches!(self.modes[rod], RodMode::Stick { .. });
                self.rechoose(y, rod, tip, at_rest, Some(self.modes[rod]));
                Transition::ModeChange { rod }
            }
            GuardKind::Restick { rod } => {
                let tip = self.modes[rod].tip().expect("grounded rod");
                // The tip's velocity has just reversed: it is at rest up to
                // `restick_speed`, which the reset drops.
                y[slots::at(rod, VX)] = 0.0;
                self.rechoose(y, rod, tip, true, None);
                Transition::ModeChange { rod }
            }
            GuardKind::Slip { rod } => {
                let tip = self.modes[rod].tip().expect("grounded rod");
                self.rechoose(y, rod, tip, true, Some(self.modes[rod]));
                Transition::ModeChange { rod }
            }
            GuardKind::RodDown { .. } => Transition::Failure(FailureDetail::RodDown),
            GuardKind::ComLow => Transition::Failure(FailureDetail::CentreOfMassLow),
        }
    }

    /// The reset with the new mode and the kind of impact `nominal` chose.
    fn reset_replaying(
        &mut self,
        t: f64,
        y: &mut [f64; N],
        index: usize,
        nominal: &Self,
    ) -> Transition {
        self.replay = nominal.last_choice;
        let transition = self.reset(t, y, index);
        self.replay = None;
        transition
    }
}
