//! The ground under the walker (docs/model.md §4, "Terrain"): the flat slope
//! by default, the slope with a single step down, or the rough slope.
//!
//! In slope coordinates the ground is piecewise constant: `y = 0` for
//! `x < step_at`, and from there `y = −step_height` (the step) or, with a
//! roughness σ, patches `[step_at + k p, step_at + (k+1) p)` of length
//! `p = terrain.patch`, patch `k` at `y = −step_height + σ z_k` with `z_k`
//! standard normal, a pure function of `(terrain.seed, k)`
//! ([`TerrainOptions`](crate::options::TerrainOptions)). Every guard that
//! measures a height above the ground (a touchdown, a rod lying down, the
//! centre of mass sinking) is as smooth as on the flat slope inside each
//! patch. What happens at an edge (the same at every edge, up or down):
//!
//! * **A tip touches down on the patch under it.** Its touchdown guard is
//!   its height minus the ground's height at its own `x`. A tip passing over
//!   an edge down sees that guard jump *up*, which is never a falling
//!   crossing, so it lands on the lower patch where it meets it.
//! * **A stance tip that slides onto a lower patch leaves the ground.** A
//!   sliding tip watches the edges of its own patch as its own guard
//!   ([`GuardKind::Edge`](crate::plant::rtw::GuardKind::Edge)); at a down
//!   edge the rod becomes free (the tip has nothing under it any more) and
//!   falls. A sticking tip does not move, so it never reaches an edge.
//! * **A tip that meets a riser trips the walker.** A free tip below a
//!   higher patch moving across its edge would pass through the riser: its
//!   touchdown guard jumps *down* there, the event is located at the face,
//!   and the touchdown reset, finding the tip far below the ground it was
//!   declared on, ends the run as a `collapse` with detail `riser`. A tip
//!   sliding into a higher patch does the same through its edge guard. A tip
//!   *above* the higher patch crosses its edge freely and lands on it. On a
//!   step this happens when the step lies just ahead of the landing foot (a
//!   falling foot moves downhill until it is level with the stance foot and
//!   uphill below that level): the walker catches its foot on the step
//!   instead of stepping down, which is a fall of a real walker too. Strings
//!   and rods other than their tips never touch the ground or an edge (as on
//!   the flat slope).

use crate::outcome::FailureDetail;
use crate::plant::contact::RodMode;
use crate::plant::geometry::SPOKES;
use crate::plant::rtw::{Rtw, Transition};
use crate::plant::slots::{self, N, VX, X, Y};

/// The hooks of the RTW's guards and resets into the terrain.
impl Rtw {
    /// The ground's height under `x`.
    #[inline]
    pub(crate) fn ground(&self, x: f64) -> f64 {
        self.terrain.ground(x)
    }

    /// The front-most (furthest downhill) grounded tip of state `y`: its
    /// spoke ([`SPOKES`]) and its `x`; `None` when every rod is free. A
    /// step met by the gait has its edge ahead of it.
    pub(crate) fn front_foot(&self, y: &[f64; N]) -> Option<(usize, f64)> {
        let rods = self.rods(y);
        SPOKES
            .iter()
            .enumerate()
            .filter(|(_, (rod, tip))| self.modes[*rod].tip() == Some(*tip))
            .map(|(j, &(rod, tip))| (j, self.body.tip_point(&rods[rod], tip).0[0]))
            .max_by(|a, b| a.1.total_cmp(&b.1))
    }

    /// Puts a grounded rod's height slot at the ground under its tip (the
    /// slots of a contact mode hold the tip's `x` and the ground's height).
    #[inline]
    pub(crate) fn set_level(&self, y: &mut [f64; N], rod: usize) {
        if self.modes[rod] != RodMode::Free {
            y[slots::at(rod, Y)] = self.terrain.ground(y[slots::at(rod, X)]);
        }
    }

    /// The value of a sliding rod's edge guard at `y`.
    #[inline]
    pub(crate) fn edge_guard(&self, y: &[f64; N], rod: usize) -> f64 {
        self.terrain
            .edge_distance(y[slots::at(rod, X)], y[slots::at(rod, Y)])
    }

    /// Its rate, from `ẏ`.
    #[inline]
    pub(crate) fn edge_guard_rate(&self, y: &[f64; N], dy: &[f64; N], rod: usize) -> f64 {
        self.terrain.edge_rate(
            y[slots::at(rod, X)],
            dy[slots::at(rod, X)],
            y[slots::at(rod, Y)],
        )
    }

    /// The reset of a sliding tip at the edge of its patch: onto a lower
    /// patch the rod is released (nothing is under its tip any more); into a
    /// higher one the tip slid into the riser, and the walker trips.
    pub(crate) fn leave_edge(&mut self, y: &mut [f64; N], rod: usize) -> Transition {
        let (x, vx, level) = (
            y[slots::at(rod, X)],
            y[slots::at(rod, VX)],
            y[slots::at(rod, Y)],
        );
        if self.terrain.level_beyond(x, vx, level) > level {
            return Transition::Failure(FailureDetail::Riser);
        }
        let rods = self.rods(y);
        self.modes[rod] = RodMode::Free;
        self.body
            .slots(RodMode::Free, &rods[rod], slots::rod_mut(y, rod));
        Transition::ModeChange { rod }
    }
}

#[cfg(test)]
mod tests {
    use crate::options::{Options, TerrainOptions};
    use crate::outcome::FailureDetail;
    use crate::params::{Params, Physical};
    use crate::plant::contact::RodMode;
    use crate::plant::geometry::{Tip, rest_star};
    use crate::plant::rtw::{Rtw, Transition};
    use crate::plant::slots::{self, N, VX, X, Y};

    /// A rough ground from `at` whose first patch lies above level 0 (`up`)
    /// or below it: the first seed that gives one.
    fn first_patch(up: bool, at: f64) -> TerrainOptions {
        (0..)
            .map(|seed| TerrainOptions::rough(0.01, seed, at, 0.2))
            .find(|t| (t.ground(at + 0.1) > 0.0) == up)
            .unwrap()
    }

    /// The star standing on the Plus tip of rod a at the origin in `mode`
    /// (the others free) on `terrain`.
    fn on_front_foot(mode: RodMode, terrain: TerrainOptions) -> (Rtw, [f64; N]) {
        let o = Options {
            terrain,
            ..Options::default()
        };
        let phys = Physical::new(&Params::fig7a(), o.normalization, o.g);
        let mut sys = Rtw::new(&phys, &o);
        let th = -std::f64::consts::FRAC_PI_3;
        let half = phys.length / 2.0;
        let rods = rest_star([-half * th.cos(), -half * th.sin()], th);
        sys.set_modes([mode, RodMode::Free, RodMode::Free]);
        let mut y = [0.0; N];
        sys.store(&rods, &mut y);
        (sys, y)
    }

    #[test]
    fn a_tip_sliding_onto_a_lower_patch_leaves_the_ground_and_into_a_higher_one_trips() {
        let slide = RodMode::Slide {
            tip: Tip::Plus,
            dir: 1.0,
        };
        for up in [false, true] {
            // The tip at the origin, 0.05 m before the patch's edge.
            let (mut sys, mut y) = on_front_foot(slide, first_patch(up, 0.05));
            assert_eq!((y[slots::at(0, X)], y[slots::at(0, Y)]), (0.0, 0.0));
            y[slots::at(0, VX)] = 0.3;
            assert!((sys.edge_guard(&y, 0) - 0.05).abs() < 1e-15);
            let mut dy = [0.0; N];
            dy[slots::at(0, X)] = 0.3;
            assert_eq!(sys.edge_guard_rate(&y, &dy, 0), -0.3);
            let t = sys.leave_edge(&mut y, 0);
            if up {
                assert_eq!(t, Transition::Failure(FailureDetail::Riser));
            } else {
                assert_eq!(t, Transition::ModeChange { rod: 0 });
                assert_eq!(sys.modes()[0], RodMode::Free);
            }
        }
    }

    #[test]
    fn a_free_tip_below_a_higher_patch_meets_its_riser_and_lands_on_a_lower_one() {
        for up in [false, true] {
            // The patch's edge just behind the tip at the origin (a
            // constructed ground: the options refuse a start at x ≤ 0).
            let terrain = TerrainOptions {
                step_at: -0.01,
                ..first_patch(up, 0.05)
            };
            let (mut sys, mut y) = on_front_foot(RodMode::Free, terrain);
            let level = terrain.ground(0.0);
            assert_eq!(level > 0.0, up);
            let t = sys.touchdown(&mut y, 0, Tip::Plus);
            if up {
                assert_eq!(t, Transition::Failure(FailureDetail::Riser));
            } else {
                assert!(matches!(t, Transition::Touchdown { rod: 0, .. }), "{t:?}");
                // The tip is put on the patch under it.
                assert_eq!(y[slots::at(0, Y)], level);
            }
        }
    }
}

#[cfg(test)]
mod step_tests {
    use crate::options::TerrainOptions;

    #[test]
    fn flat_by_default_and_a_step_drops_the_ground_from_its_edge_on() {
        let flat = TerrainOptions::default();
        assert!(flat.is_flat());
        flat.validate().unwrap();
        for x in [-1.0, 0.0, 1.0, 1e6] {
            assert_eq!(flat.ground(x).to_bits(), 0.0f64.to_bits());
        }
        let step = TerrainOptions::step(0.02, 1.5);
        step.validate().unwrap();
        assert_eq!(step.ground(1.4999), 0.0);
        assert_eq!(step.ground(1.5), -0.02);
        assert_eq!(step.ground(9.0), -0.02);
        assert_eq!(step.edge_distance(1.0, 0.0), 0.5);
        assert_eq!(step.edge_distance(2.0, -0.02), 0.5);
    }

    #[test]
    fn out_of_range_steps_are_refused_naming_the_field() {
        for (t, field) in [
            (TerrainOptions::step(-0.01, 1.0), "terrain.step_height"),
            (TerrainOptions::step(f64::NAN, 1.0), "terrain.step_height"),
            (TerrainOptions::step(2e3, 1.0), "terrain.step_height"),
            (TerrainOptions::step(0.01, 0.0), "terrain.step_at"),
            (TerrainOptions::step(0.01, f64::INFINITY), "terrain.step_at"),
        ] {
            let e = t.validate().unwrap_err().to_string();
            assert!(e.starts_with(field), "{e}");
            assert!(e.contains("must be in"), "{e}");
        }
    }
}
