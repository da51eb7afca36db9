//! What the run's observers read off a state: the friction ratio, the
//! energies, the centre of mass, and how many rods touch or slide.

use super::model::Rtw;
use crate::plant::contact::RodMode;
use crate::plant::geometry::{RodFrame, Vec2};
use crate::plant::slots::N;

impl Rtw {
    #[cfg(test)]
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
    pub fn friction_ratio_of(&self, lambda: &[Vec2; 3]) -> f64 {
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
    pub fn centre_of_mass(&self, y: &[f64; N]) -> Vec2 {
        Self::centre_of_mass_at(&self.frames(y))
    }

    /// Centre of mass of the rods with frames `f`.
    pub fn centre_of_mass_at(f: &[RodFrame; 3]) -> Vec2 {
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
