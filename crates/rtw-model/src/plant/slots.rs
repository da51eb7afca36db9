//! The layout of the RTW's state vector: three rods of [`ROD_SLOTS`] slots
//! each, then the energies dissipated by the string dampers and by sliding
//! friction, integrated alongside the motion for the energy balance.
//!
//! A rod's slots mean what its contact mode says ([`crate::plant::contact`]):
//!
//! | slot | free | stick | slide |
//! |---|---|---|---|
//! | [`X`] | centre x | contact point x | tip x |
//! | [`Y`] | centre y | ground height (0 on the flat slope) | ground height |
//! | [`THETA`] | θ | θ | θ |
//! | [`VX`] | ẋ | 0 | tip ẋ |
//! | [`VY`] | ẏ | 0 | 0 |
//! | [`OMEGA`] | ω | ω | ω |

use crate::plant::contact::RodMode;

/// State dimension: 3 rods × 6 slots + two dissipated energies.
pub const N: usize = 20;
/// Slots per rod.
pub const ROD_SLOTS: usize = 6;
/// Slot of the energy dissipated by the string dampers.
pub const DISSIPATED: usize = 18;
/// Slot of the energy dissipated by sliding friction (finite μ).
pub const FRICTION: usize = 19;

/// A rod's x slot: its centre's (free), contact point's (stick) or tip's (slide) x.
pub const X: usize = 0;
/// A rod's y slot: its centre's y when free, 0 on the ground.
pub const Y: usize = 1;
/// A rod's angle θ.
pub const THETA: usize = 2;
/// A rod's x velocity: its centre's (free), 0 (stick) or its tip's (slide).
pub const VX: usize = 3;
/// A rod's y velocity: its centre's when free, 0 on the ground.
pub const VY: usize = 4;
/// A rod's angular velocity ω.
pub const OMEGA: usize = 5;

/// Index in the state of slot `k` of rod `rod`.
#[inline]
pub const fn at(rod: usize, k: usize) -> usize {
    ROD_SLOTS * rod + k
}

/// The slots of rod `rod`.
#[inline]
pub fn rod(y: &[f64; N], rod: usize) -> &[f64] {
    &y[at(rod, 0)..at(rod + 1, 0)]
}

/// The slots of rod `rod`, to write.
#[inline]
pub fn rod_mut(y: &mut [f64; N], rod: usize) -> &mut [f64] {
    &mut y[at(rod, 0)..at(rod + 1, 0)]
}

/// The slots that are a rod's minimal coordinates in `mode` (the others are
/// fixed by its contact): all six when free, (x, θ, ω) sticking,
/// (x, θ, ẋ, ω) sliding.
pub fn coordinates(mode: RodMode) -> &'static [usize] {
    match mode {
        RodMode::Free => &[X, Y, THETA, VX, VY, OMEGA],
        RodMode::Stick { .. } => &[X, THETA, OMEGA],
        RodMode::Slide { .. } => &[X, THETA, VX, OMEGA],
        RodMode::Corner { .. } => &[THETA, OMEGA],
        RodMode::Wall { .. } => &[Y, THETA, VY, OMEGA],
    }
}

/// The velocity slots of a rod.
pub const VELOCITIES: [usize; 3] = [VX, VY, OMEGA];
