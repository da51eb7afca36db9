//! The continuous dynamics of the RTW in its current modes: the external
//! loads, `ẏ = f(y)`, and the contact forces λ.

use super::model::{AtState, Rtw};
use crate::plant::contact::{Load, RodMode};
use crate::plant::geometry::{RodFrame, Vec2, add, scale};
use crate::plant::slots::{self, DISSIPATED, FRICTION, N, VX};
#[cfg(test)]
use crate::plant::strings::STRING_COUNT;

impl Rtw {
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
        let mut at = AtState::default();
        self.dynamics_into(y, dy, &mut at);
        at
    }

    /// [`dynamics`](Self::dynamics) with the frames and λ written into `at`
    /// in place: the engine keeps them at every stage, and a returned
    /// `AtState` (216 bytes) was copied into its place at each evaluation.
    #[inline]
    pub(super) fn dynamics_into(&self, y: &[f64; N], dy: &mut [f64; N], at: &mut AtState) {
        at.frames = self.frames(y);
        let frames = &at.frames;
        let (loads, dissipation) = self.loads(frames);
        let mut friction = 0.0;
        let lambda = &mut at.lambda;
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
    }

    #[cfg(test)]
    /// The strings' kinks at `y` ([`StringSet::kinks`](crate::plant::strings::StringSet::kinks)).
    pub(crate) fn string_kinks(&self, y: &[f64; N]) -> Option<[f64; 2 * STRING_COUNT]> {
        self.strings.kinks(&self.frames(y))
    }

    #[cfg(test)]
    /// Contact forces λ of the rods at `y` (zero when free).
    pub fn contact_forces(&self, y: &[f64; N]) -> [Vec2; 3] {
        self.contact_forces_of(&self.frames(y))
    }

    /// Contact forces λ of the rods with frames `frames` (zero when free).
    pub(super) fn contact_forces_of(&self, frames: &[RodFrame; 3]) -> [Vec2; 3] {
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
}
