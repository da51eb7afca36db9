//! The RTW's Poincaré section at each touchdown of a new foot, reduced by
//! the star's symmetry: its points, and the log of a run's crossings.
//!
//! **Section.** The state just after the impact of a foot other than the
//! stance foot and the one behind it, when the foot stays on the ground (a
//! touch-and-go, or a foot that lands again after a bounce, is not a step).
//!
//! **Symmetry.** A 60° turn maps the spokes a+ → b+ → c+ → a− → b− → c− → a+
//! ([`SPOKES`]'s order): a relabelling of the rods, where a rod turned by π is
//! the same rod with its tips swapped. The gait is also invariant under a
//! shift along the slope. So every section point is stored *canonically*:
//! rods relabelled so that the landing foot is a+ (spoke `j` of the old labels
//! becomes spoke 0; the old rod of spoke `(i + j) mod 6` becomes rod `i`,
//! turned by π when that spoke is a − tip), shifted so that the landing foot
//! is at `x = 0`, angles wrapped to `(−π, π]`, dissipated energies zeroed.
//! A steady walk is then a fixed point of the map; the same physical posture
//! one step later has the same canonical coordinates.
//!
//! **Coordinates.** The state's slots are minimal coordinates in each rod's
//! mode ([`crate::plant::slots`]): a sticking rod has (contact x, θ, ω), a sliding
//! one (tip x, θ, tip ẋ, ω), a free one all six. The map's coordinates `z`
//! are those slots of the three rods in the section's modes, without a+'s
//! contact x (zero by the shift). The section's own constraints (the landing
//! foot on the ground, at rest after a sticking impact) are thus built in and
//! the map has no trivial multipliers. A map is smooth only between points of
//! the same *mode pattern* (which rods touch, how); the step map's `step`
//! reports the pattern it lands in, and a fixed point must keep its own.
//!

use crate::outcome::MAX_PERIOD;
use crate::plant::contact::RodMode;
use crate::plant::geometry::{SPOKES, Tip};
use crate::plant::slots::{self, DISSIPATED, FRICTION, N, OMEGA, THETA, X};
use std::f64::consts::PI;

/// Which touchdowns of a new foot cross the step map's section.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Section {
    /// Only a foot that stays on the ground (the walk's step; a
    /// touch-and-go landing is not a step).
    #[default]
    Stays,
    /// Every touchdown of a new foot, a touch-and-go too: the section of
    /// skipping gaits whose feet touch and lift again at once (s = 0 on
    /// steep slopes), which [`Section::Stays`] never crosses. The landing
    /// rod may then be free, with its tip on the ground: its coordinates
    /// keep the height and angle that this ties together, so the map has one
    /// trivial multiplier 0 more.
    TouchAndGo,
}

/// Canonical spoke of the stance foot, and of the foot behind it (c−).
pub(crate) const STANCE_SPOKE: usize = 0;
const BEHIND_SPOKE: usize = 5;

/// The spoke that landed if the touchdown of `tip` of `rod` crosses the
/// section of a walk whose stance foot is spoke `stance`: a new foot —
/// neither the stance foot nor the one behind it — that stays on the ground
/// (in `modes`, just after the impact), or with [`Section::TouchAndGo`] any
/// new foot. A foot that lands again after a bounce is not a step.
pub(crate) fn new_foot(
    stance: usize,
    modes: &[RodMode; 3],
    rod: usize,
    tip: Tip,
    section: Section,
) -> Option<usize> {
    let j = SPOKES.iter().position(|&s| s == (rod, tip))?;
    let behind = (stance + BEHIND_SPOKE) % 6;
    let down = modes[rod] != RodMode::Free || section == Section::TouchAndGo;
    (j != stance && j != behind && down).then_some(j)
}

/// A point on the section, in canonical labels (see the module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SectionPoint {
    /// The rods' contact modes.
    pub modes: [RodMode; 3],
    /// The state, in those modes.
    pub y: [f64; N],
}

impl SectionPoint {
    /// The state slots that are the map's coordinates in this point's modes.
    pub(crate) fn coordinate_slots(&self) -> Vec<usize> {
        let mut out = Vec::with_capacity(N);
        for (i, &mode) in self.modes.iter().enumerate() {
            let own = slots::coordinates(mode);
            // a+'s x slot (contact x, or the centre's of a free rod after a
            // touch-and-go) is zero by the shift.
            let skip = usize::from(i == 0);
            out.extend(own[skip..].iter().map(|&k| slots::at(i, k)));
        }
        out
    }

    /// The map's coordinates of this point.
    pub fn coords(&self) -> Vec<f64> {
        self.coordinate_slots().iter().map(|&s| self.y[s]).collect()
    }

    /// This point with its coordinates replaced by `z` (same modes).
    pub fn with_coords(&self, z: &[f64]) -> SectionPoint {
        let mut p = *self;
        for (&s, &v) in self.coordinate_slots().iter().zip(z) {
            p.y[s] = v;
        }
        p
    }

    /// The landing rod's angular velocity just after the impact.
    pub fn omega(&self) -> f64 {
        self.y[slots::at(0, OMEGA)]
    }
}

/// Old rod of new rod `i` when spoke `j` becomes a+, and whether it is turned by π.
#[inline]
pub(crate) fn source(j: usize, i: usize) -> (usize, bool) {
    let s = (i + j) % 6;
    (s % 3, s >= 3)
}

/// The turned rod's mode: the same contact on its other tip's label.
fn turned(mode: RodMode) -> RodMode {
    match mode {
        RodMode::Free => RodMode::Free,
        RodMode::Stick { tip } => RodMode::Stick { tip: tip.other() },
        RodMode::Slide { tip, dir } => RodMode::Slide {
            tip: tip.other(),
            dir,
        },
        RodMode::Corner { tip, side } => RodMode::Corner {
            tip: tip.other(),
            side,
        },
        RodMode::Wall { tip, side } => RodMode::Wall {
            tip: tip.other(),
            side,
        },
    }
}

/// `θ` wrapped to `(−π, π]`.
#[inline]
fn wrap(theta: f64) -> f64 {
    let w = theta.rem_euclid(2.0 * PI);
    if w > PI { w - 2.0 * PI } else { w }
}

/// The canonical section point of the state `y` (in modes `modes`) just after
/// spoke `j` landed; `None` if the landing rod is not on the ground, unless
/// the section counts touch-and-go landings.
pub(crate) fn canonical(
    modes: &[RodMode; 3],
    y: &[f64; N],
    j: usize,
    section: Section,
) -> Option<SectionPoint> {
    let (o0, _) = source(j, 0);
    if modes[o0] == RodMode::Free && section == Section::Stays {
        return None;
    }
    let x0 = y[slots::at(o0, X)];
    let mut p = SectionPoint {
        modes: [RodMode::Free; 3],
        y: [0.0; N],
    };
    for i in 0..3 {
        let (o, flip) = source(j, i);
        slots::rod_mut(&mut p.y, i).copy_from_slice(slots::rod(y, o));
        p.y[slots::at(i, X)] -= x0;
        let theta = slots::at(i, THETA);
        if flip {
            p.y[theta] += PI;
        }
        p.y[theta] = wrap(p.y[theta]);
        p.modes[i] = if flip { turned(modes[o]) } else { modes[o] };
    }
    p.y[DISSIPATED] = 0.0;
    p.y[FRICTION] = 0.0;
    Some(p)
}

/// `∂(canonical y)/∂y` for landing spoke `j`: a permutation of the rods' slots
/// minus the landing foot's x from every rod's x slot (the π turns and the
/// wrapping add constants).
pub(crate) fn canonical_jacobian(j: usize) -> [[f64; N]; N] {
    let mut c = [[0.0; N]; N];
    let (o0, _) = source(j, 0);
    for i in 0..3 {
        let (o, _) = source(j, i);
        for k in 0..slots::ROD_SLOTS {
            c[slots::at(i, k)][slots::at(o, k)] += 1.0;
        }
        c[slots::at(i, X)][slots::at(o0, X)] -= 1.0;
    }
    c
}

/// Longest history a [`SectionLog`] keeps: two of the longest periods, and one.
const LOG_LEN: usize = 2 * MAX_PERIOD + 1;

/// The latest section crossings of a simulation, in a fixed ring (no
/// allocation in the run): where the limit-cycle analysis of a run starts.
#[derive(Clone, Debug)]
pub struct SectionLog {
    ring: [SectionPoint; LOG_LEN],
    len: usize,
    /// Spoke of the stance foot, in the run's labels (a+ at the start).
    stance: usize,
}

impl Default for SectionLog {
    fn default() -> Self {
        Self {
            ring: [SectionPoint {
                modes: [RodMode::Free; 3],
                y: [0.0; N],
            }; LOG_LEN],
            len: 0,
            stance: STANCE_SPOKE,
        }
    }
}

impl SectionLog {
    /// An empty log of a run whose stance foot is spoke `stance` (in the
    /// run's labels) now.
    pub(crate) fn starting_at(stance: usize) -> Self {
        Self {
            stance,
            ..Self::default()
        }
    }

    /// How many crossings were recorded (more than it keeps).
    pub(crate) fn count(&self) -> usize {
        self.len
    }

    /// Records the touchdown of `tip` of `rod` (state `y` just after it, in
    /// `modes`) if it crosses the section (`new_foot`).
    pub fn on_touchdown(&mut self, modes: &[RodMode; 3], y: &[f64; N], rod: usize, tip: Tip) {
        let Some(j) = new_foot(self.stance, modes, rod, tip, Section::Stays) else {
            return;
        };
        if let Some(p) = canonical(modes, y, j, Section::Stays) {
            self.ring[self.len % LOG_LEN] = p;
            self.len += 1;
            self.stance = j;
        }
    }

    /// The recorded crossings, oldest first (at most the ring's length).
    pub fn latest(&self) -> Vec<SectionPoint> {
        let n = self.len.min(LOG_LEN);
        (self.len - n..self.len)
            .map(|k| self.ring[k % LOG_LEN])
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn relabelling_is_a_sixty_degree_turn() {
        // Landing spoke j becomes a+: new rod i is old spoke (i + j) mod 6.
        assert_eq!(source(0, 0), (0, false));
        assert_eq!(source(1, 0), (1, false));
        assert_eq!(source(1, 2), (0, true));
        assert_eq!(source(4, 0), (1, true));
        // Six turns come back to the start: j and j + 6 agree.
        for j in 0..6 {
            for i in 0..3 {
                assert_eq!(source(j, i), source(j + 6, i));
            }
        }
    }

    #[test]
    fn wrap_keeps_angles_in_the_half_open_circle() {
        for &t in &[0.0, 1.0, -1.0, PI, -PI, 3.0 * PI, 7.5, -7.5] {
            let w = wrap(t);
            assert!(w > -PI - 1e-12 && w <= PI + 1e-12, "{t} -> {w}");
            let k = (t - w) / (2.0 * PI);
            assert!((k - k.round()).abs() < 1e-12);
        }
    }
}
