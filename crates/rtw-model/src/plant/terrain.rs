//! The ground under the walker (docs/model.md §2, "Terrain"): the flat slope
//! by default, or the slope with a single step down.
//!
//! In slope coordinates the ground is the line `y = 0` for `x < step_at` and
//! `y = −step_height` from `x = step_at` on: piecewise constant, so every
//! guard that measures a height above the ground (a touchdown, a rod lying
//! down, the centre of mass sinking) stays as smooth as on the flat slope
//! inside each piece. What happens at the edge:
//!
//! * **A tip touches down on the segment under it.** Its touchdown guard is
//!   its height minus the ground's height at its own `x`. A tip passing over
//!   the edge downhill sees that guard jump *up* by `step_height`, which is
//!   never a falling crossing, so it lands on the lower segment where it
//!   meets it.
//! * **A stance tip that passes the edge leaves the ground.** A sliding tip
//!   on the upper segment watches the edge as its own guard
//!   ([`GuardKind::Edge`](crate::plant::rtw::GuardKind::Edge)); at it the rod
//!   becomes free (the tip has nothing under it any more) and falls. A
//!   sticking tip does not move, so it never reaches the edge.
//! * **A tip that meets the riser trips the walker.** A free tip below the
//!   upper segment moving uphill across `x = step_at` would pass through the
//!   step's face: its touchdown guard jumps *down* there, the event is
//!   located at the face, and the touchdown reset, finding the tip far below
//!   the ground it was declared on, ends the run as a `collapse` with detail
//!   `riser`. A sliding tip on the lower segment that slides back into the
//!   face does the same through its edge guard. A falling foot moves downhill
//!   until it is level with the stance foot and uphill below that level, so
//!   this happens when the step lies just ahead of the landing foot: the
//!   walker catches its foot on the step instead of stepping down, which is
//!   a fall of a real walker too. Strings and rods other than their tips
//!   never touch the ground or the edge (as on the flat slope).

use crate::outcome::FailureDetail;
use crate::plant::contact::RodMode;
use crate::plant::geometry::SPOKES;
use crate::plant::rtw::{Rtw, Transition};
use crate::plant::slots::{self, N, X, Y};

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
        self.terrain
            .edge_rate(dy[slots::at(rod, X)], y[slots::at(rod, Y)])
    }

    /// The reset of a sliding tip at the edge: on the upper segment the rod
    /// is released (nothing is under its tip any more); on the lower one the
    /// tip slid back into the riser, and the walker trips.
    pub(crate) fn leave_edge(&mut self, y: &mut [f64; N], rod: usize) -> Transition {
        if y[slots::at(rod, Y)] != 0.0 {
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
