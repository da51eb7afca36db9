//! [`Rtw`] as a [`HybridSystem`]: the dynamics, guards and resets of the
//! sibling files behind the engine's interface.

use super::model::{AtState, Rtw, Transition};
use crate::plant::contact::RodMode;
use crate::plant::slots::{self, N, THETA};
use crate::plant::strings::{STRING_COUNT, StringSet};
use hybrid_ode::system::{MAX_GUARDS, fd_delta};
use hybrid_ode::{Guards, HybridSystem};

/// The RTW as a hybrid system: the dynamics of its modes, every guard firing
/// on a falling crossing of zero, and the resets of [`GuardKind`](super::GuardKind). It is
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
        self.dynamics_into(y, dy, at);
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
            let frame = |i: usize| {
                let e = at.frames[i].e;
                let turn = d * dy[slots::at(i, THETA)];
                let e = [e[0] - turn * e[1], e[1] + turn * e[0]];
                self.body.frame_with(self.modes[i], slots::rod(&yd, i), e)
            };
            // Written out: `array::from_fn`'s closure was left out of line.
            ahead.frames = [frame(0), frame(1), frame(2)];
            ahead.lambda = self.contact_forces_of(&ahead.frames);
        }
        let mut k = 0;
        self.guard_kinds(|kind| {
            out[k] = match self.kinematic_guard_rate(kind, y, dy, &at.frames) {
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

    /// The strings' kinks that move a contact force: a slack string's
    /// stretch and pull changing sign, for each string that pulls on a rod on
    /// the ground (a rod's contact force depends on its own loads alone),
    /// from the frames the right-hand side made at the step's end. A free
    /// rod's tip height is C² across a kink (its acceleration kinks, its
    /// velocity does not), and every miss a kink caused was of a contact
    /// force (`tests/crossings_inside_a_step.rs`).
    #[inline]
    fn kink_sides(&self, _t: f64, _y: &[f64; N], at: &AtState) -> u32 {
        let grounded = |rod: usize| self.modes[rod] != RodMode::Free;
        let mask = (0..STRING_COUNT)
            .filter(|&j| {
                let (ip, iq) = StringSet::rods_of(j);
                grounded(ip) || grounded(iq)
            })
            .fold(0u32, |m, j| m | (0b11 << (2 * j)));
        if mask == 0 {
            return 0;
        }
        self.strings.kink_sides(&at.frames) & mask
    }

    /// Kink `index` alone at `y`, from the frames of the two rods its string
    /// joins (two `sin_cos`, not three, and one string): the root finder
    /// calls it at every iterate.
    fn kink(&self, _t: f64, y: &[f64; N], index: usize) -> f64 {
        let j = index / 2;
        let (ip, iq) = StringSet::rods_of(j);
        let frame = |rod: usize| self.body.frame(self.modes[rod], slots::rod(y, rod));
        self.strings.kinks_of(j, &frame(ip), &frame(iq))[index % 2]
    }

    fn reset(&mut self, _t: f64, y: &mut [f64; N], index: usize) -> Transition {
        self.reset_kind(y, self.guard_kind(index))
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
