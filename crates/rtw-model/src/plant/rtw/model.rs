//! [`Rtw`]: its constants, its contact modes, its state's rods; and the
//! types its dynamics, guards and resets speak.

use crate::options::Options;
use crate::options::{Over, TerrainOptions};
use crate::outcome::FailureDetail;
use crate::params::Physical;
use crate::plant::contact::{ImpactKind, RodBody, RodMode};
use crate::plant::geometry::{RodFrame, RodState, Tip, Vec2};
use crate::plant::slots::{self, N, THETA};
use crate::plant::strings::StringSet;
use hybrid_ode::EndsRun;

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
    /// A sliding tip reaches the edge of its patch, or a tip on a face the
    /// face's foot (`plant::terrain`); watched only off the flat slope.
    Edge { rod: usize },
    /// A tip on a face reaches the face's top, where it leaves the face.
    FaceTop { rod: usize },
    /// A free rod's tip passes an edge of the patch under it: onto the next
    /// patch if above its level, else into the face of that patch
    /// (`plant::terrain`); watched only off the flat slope.
    EdgePass { rod: usize, tip: Tip },
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
    pub lambda: [Vec2; 3],
}

/// The discrete choices a reset made: the rod's new mode and, at a
/// touchdown, the kind of impact.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Choice {
    pub(crate) mode: RodMode,
    pub(crate) impact: Option<ImpactKind>,
}

/// The RTW: its constants and its current contact modes.
#[derive(Clone, Debug)]
pub struct Rtw {
    /// The rods' inertial constants.
    pub(crate) body: RodBody,
    /// The strings.
    pub(crate) strings: StringSet,
    /// Gravity in the slope frame, g (sin φ, −cos φ).
    pub(crate) gravity: Vec2,
    /// Friction coefficient (infinite: no slip, frictionless slide).
    pub(crate) mu: f64,
    /// The rods' contact modes.
    pub(crate) modes: [RodMode; 3],
    /// The level of the patch under each tip ([`Tip::index`]) of a free
    /// rod, off the flat slope: a free tip's touchdown guard is its height
    /// above this level, which changes only where the tip passes an edge
    /// ([`GuardKind::EdgePass`]), so that guard is smooth (`plant::terrain`).
    pub(crate) over: [[Over; 2]; 3],
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
    /// The ground ([`crate::plant::terrain`]).
    pub(crate) terrain: TerrainOptions,
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
            over: [[Over::level(0.0); 2]; 3],
            touchdown_height: -opts.touchdown_offset * phys.length,
            restick_speed: 1e-9 * phys.length,
            collapse_height: opts.collapse_height_ratio * phys.standing_height(),
            mu_floor: 0.05 * phys.m * gravity[0].hypot(gravity[1]),
            last_choice: None,
            replay: None,
            relax: 0.0,
            terrain: opts.terrain,
        }
    }

    /// Per-rod frames (full coordinates plus unit vectors) of state `y`.
    #[inline]
    pub fn frames(&self, y: &[f64; N]) -> [RodFrame; 3] {
        // Written out, not `array::from_fn`: its closure was left out of line
        // in the right-hand side once the contact modes grew.
        let frame = |i: usize| self.body.frame(self.modes[i], slots::rod(y, i));
        [frame(0), frame(1), frame(2)]
    }

    /// Full coordinates of the rods.
    pub fn rods(&self, y: &[f64; N]) -> [RodState; 3] {
        std::array::from_fn(|i| self.rod(y, i))
    }

    /// Full coordinates of rod `rod` alone (one `sin_cos`, not three).
    #[inline]
    pub(crate) fn rod(&self, y: &[f64; N], rod: usize) -> RodState {
        self.body.rod_state(self.modes[rod], slots::rod(y, rod))
    }

    /// [`rods`](Self::rods) from the frames of `y` (no trigonometry again).
    pub(crate) fn rods_of(y: &[f64; N], frames: &[RodFrame; 3]) -> [RodState; 3] {
        std::array::from_fn(|i| frames[i].state(y[slots::at(i, THETA)]))
    }

    /// Writes the rods back into `y` in the current modes.
    pub fn store(&mut self, rods: &[RodState; 3], y: &mut [f64; N]) {
        for (i, r) in rods.iter().enumerate() {
            self.body.slots(self.modes[i], r, slots::rod_mut(y, i));
            self.set_level(y, i);
        }
    }

    #[cfg(test)]
    /// The rods' inertial constants.
    pub fn body(&self) -> &RodBody {
        &self.body
    }

    #[cfg(test)]
    /// Gravity in the slope frame, g (sin φ, −cos φ).
    pub fn gravity(&self) -> Vec2 {
        self.gravity
    }

    #[cfg(test)]
    /// The friction coefficient μ (infinite: no slip, frictionless slide).
    pub fn mu(&self) -> f64 {
        self.mu
    }

    /// The rods' contact modes.
    pub fn modes(&self) -> [RodMode; 3] {
        self.modes
    }

    #[cfg(test)]
    /// Puts the rods in `modes` (the state's slots must be read in them).
    pub fn set_modes(&mut self, modes: [RodMode; 3]) {
        self.modes = modes;
    }

    /// Puts the RTW in `modes` at the state `y` (a section point's, or a
    /// perturbed one): the modes, and the patch under each free tip.
    pub(crate) fn enter(&mut self, modes: [RodMode; 3], y: &[f64; N]) {
        self.modes = modes;
        self.note_patches(y);
    }
}
