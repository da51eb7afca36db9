//! The resets: what a guard's crossing does to the modes and the state
//! (touchdown, lift-off, re-stick, slip, failure).

use super::model::{Choice, GuardKind, Rtw, Transition};
use crate::outcome::FailureDetail;
use crate::plant::contact::RodMode;
use crate::plant::geometry::{RodFrame, Tip};
use crate::plant::slots::{self, N, OMEGA, VX};

impl Rtw {
    /// The reset of guard `kind`, which has just fired at `y`; then every
    /// free rod's tips are put back where their guards watch them
    /// ([`free_tips_out`](Self::free_tips_out)).
    pub(crate) fn reset_kind(&mut self, y: &mut [f64; N], kind: GuardKind) -> Transition {
        let transition = self.reset_only(y, kind);
        if !matches!(transition, Transition::Failure(_)) {
            self.free_tips_out(y);
        }
        transition
    }

    /// The reset of guard `kind` alone.
    fn reset_only(&mut self, y: &mut [f64; N], kind: GuardKind) -> Transition {
        match kind {
            GuardKind::Touchdown { rod, tip } => self.touchdown(y, rod, tip),
            GuardKind::LiftOff { rod } | GuardKind::Slip { rod }
                if matches!(
                    self.modes[rod],
                    RodMode::Corner { .. } | RodMode::Wall { .. }
                ) =>
            {
                self.leave_face_mode(y, rod)
            }
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
            GuardKind::Edge { rod } => self.edge_reset(y, rod),
            GuardKind::FaceTop { rod } => self.leave_face_over_top(y, rod),
            GuardKind::EdgePass { rod, tip } => self.pass_edge(y, rod, tip),
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
        self.set_level(y, rod);
    }

    /// Touchdown of a free rod's tip: the impact, then the mode choice.
    pub fn touchdown(&mut self, y: &mut [f64; N], rod: usize, tip: Tip) -> Transition {
        let rods = self.rods(y);
        if !self.terrain.is_flat() {
            let (p, _) = self.body.tip_point(&rods[rod], tip);
            if self
                .terrain
                .met_riser(p[1] - self.ground(p[0]), self.touchdown_height)
            {
                return self.meet_face(y, rod, tip);
            }
        }
        let impact = match self.replay.and_then(|c| c.impact) {
            Some(kind) => self.body.impact(&rods[rod], tip, kind),
            None => self.body.touchdown(&rods[rod], tip, self.mu),
        };
        let mut after = impact.after;
        // Put the tip exactly on the ground (it was declared a hair below).
        let (p, _) = self.body.tip_point(&after, tip);
        after.c[1] -= p[1] - self.ground(p[0]);
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
        self.set_level(y, rod);
        Transition::Touchdown {
            rod,
            tip,
            omega_after: y[slots::at(rod, OMEGA)],
        }
    }
}

#[cfg(test)]
mod tests {
    //! One reset at a time on a constructed state (as Drake tests a hybrid
    //! system's resets): the modes after it, and the state it leaves.

    use super::super::model::{GuardKind, Rtw, Transition};
    use crate::options::Options;
    use crate::outcome::FailureDetail;
    use crate::params::{Params, Physical};
    use crate::plant::contact::RodMode;
    use crate::plant::geometry::{RodState, Tip, rest_star};
    use crate::plant::slots::{self, N, VX};

    /// The star turning at ω = −2 on the Plus tip of rod a in `mode`, the others
    /// free, its centre at rest at first; rod a's tip moves along the ground at `tip_vx` when sliding.
    fn on_front_foot(mode: RodMode, tip_vx: f64, mu: f64) -> (Rtw, [f64; N]) {
        let mut o = Options::literal();
        o.contact.mu = mu;
        let phys = Physical::new(&Params::fig7a(), o.normalization, o.g);
        let mut sys = Rtw::new(&phys, &o);
        let th = -std::f64::consts::FRAC_PI_3;
        let half = sys.body().half_length;
        let mut rods = rest_star([-half * th.cos(), -half * th.sin()], th);
        for r in rods.iter_mut() {
            r.omega = -2.0;
        }
        sys.set_modes([mode, RodMode::Free, RodMode::Free]);
        let mut y = [0.0; N];
        sys.store(&rods, &mut y);
        if let RodMode::Slide { .. } = mode {
            y[slots::at(0, VX)] = tip_vx;
        }
        (sys, y)
    }

    /// Rods b and c, and the dissipated energies, are not the reset's business.
    fn assert_others_untouched(before: &[f64; N], after: &[f64; N]) {
        assert_eq!(before[slots::at(1, 0)..], after[slots::at(1, 0)..]);
    }

    /// The rod's place and velocity are the same up to rounding.
    fn assert_unmoved(before: &RodState, after: &RodState) {
        for (a, b) in [
            (before.c[0], after.c[0]),
            (before.c[1], after.c[1]),
            (before.theta, after.theta),
            (before.v[0], after.v[0]),
            (before.v[1], after.v[1]),
            (before.omega, after.omega),
        ] {
            assert!((a - b).abs() < 1e-12, "{a} vs {b}");
        }
    }

    #[test]
    fn lift_off_leaves_the_stick_and_keeps_the_rod_where_it_was() {
        let (mut sys, mut y) = on_front_foot(RodMode::Stick { tip: Tip::Plus }, 0.0, f64::INFINITY);
        let before = y;
        let rod_before = sys.rods(&y)[0];
        let t = sys.reset_kind(&mut y, GuardKind::LiftOff { rod: 0 });
        assert_eq!(t, Transition::ModeChange { rod: 0 });
        let modes = sys.modes();
        // The guard found the stick's condition violated: the rod must leave it.
        assert_ne!(modes[0], RodMode::Stick { tip: Tip::Plus });
        assert_eq!(modes[1..], [RodMode::Free; 2]);
        assert_eq!(sys.last_choice.map(|c| c.mode), Some(modes[0]));
        assert_others_untouched(&before, &y);
        // A change of mode re-expresses the rod; it does not move it.
        assert_unmoved(&rod_before, &sys.rods(&y)[0]);
    }

    #[test]
    fn restick_stops_the_sliding_tip_on_the_ground() {
        // Infinite μ: the stopped tip sticks. μ = 0.01, far inside the
        // star's friction need: it slides on from rest, so the reversed
        // speed the guard tolerated must have been dropped.
        for (mu, sticks) in [(f64::INFINITY, true), (0.01, false)] {
            let slide = RodMode::Slide {
                tip: Tip::Plus,
                dir: 1.0,
            };
            // The guard fires once the reversed speed exceeds `restick_speed`.
            let (mut sys, mut y) = on_front_foot(slide, -2e-9, mu);
            let before = y;
            let t = sys.reset_kind(&mut y, GuardKind::Restick { rod: 0 });
            assert_eq!(t, Transition::ModeChange { rod: 0 });
            let mode = sys.modes()[0];
            assert_eq!(mode.tip(), Some(Tip::Plus), "μ = {mu}");
            assert_eq!(
                matches!(mode, RodMode::Stick { .. }),
                sticks,
                "μ = {mu}: {mode:?}"
            );
            assert_eq!(
                y[slots::at(0, VX)],
                0.0,
                "μ = {mu}: the tip's speed is dropped"
            );
            let (p, v) = sys.body().tip_point(&sys.rods(&y)[0], Tip::Plus);
            assert_eq!(p[1], 0.0, "μ = {mu}: the tip stays on the ground");
            assert!(
                v[0].abs() < 1e-15 && v[1].abs() < 1e-15,
                "μ = {mu}: tip at rest: {v:?}"
            );
            assert_others_untouched(&before, &y);
        }
    }

    #[test]
    fn slip_turns_the_stick_into_a_slide_from_rest_and_keeps_the_rod_where_it_was() {
        // μ = 0.01, far inside the star's friction need: the stuck tip's
        // friction cone is left and the slip guard has fired.
        let (mut sys, mut y) = on_front_foot(RodMode::Stick { tip: Tip::Plus }, 0.0, 0.01);
        let before = y;
        let rod_before = sys.rods(&y)[0];
        let t = sys.reset_kind(&mut y, GuardKind::Slip { rod: 0 });
        assert_eq!(t, Transition::ModeChange { rod: 0 });
        let modes = sys.modes();
        assert!(
            matches!(modes[0], RodMode::Slide { tip: Tip::Plus, .. }),
            "{:?}",
            modes[0]
        );
        assert_eq!(modes[1..], [RodMode::Free; 2]);
        assert_eq!(sys.last_choice.map(|c| c.mode), Some(modes[0]));
        assert_others_untouched(&before, &y);
        // The slide starts from rest on the ground: the tip neither moves nor
        // leaves the ground, and the rod is re-expressed, not moved.
        let rod_after = sys.rods(&y)[0];
        assert_unmoved(&rod_before, &rod_after);
        let (p, v) = sys.body().tip_point(&rod_after, Tip::Plus);
        assert!(p[1].abs() < 1e-12, "the tip stays on the ground: {}", p[1]);
        assert!(
            v[0].abs() < 1e-12 && v[1].abs() < 1e-12,
            "tip at rest: {v:?}"
        );
    }

    #[test]
    fn rod_down_and_low_centre_of_mass_end_the_run_and_change_nothing() {
        for (kind, detail) in [
            (GuardKind::RodDown { rod: 0 }, FailureDetail::RodDown),
            (GuardKind::ComLow, FailureDetail::CentreOfMassLow),
        ] {
            let (mut sys, mut y) =
                on_front_foot(RodMode::Stick { tip: Tip::Plus }, 0.0, f64::INFINITY);
            let (before, modes) = (y, sys.modes());
            assert_eq!(sys.reset_kind(&mut y, kind), Transition::Failure(detail));
            assert_eq!(y, before, "{kind:?}");
            assert_eq!(sys.modes(), modes, "{kind:?}");
        }
    }
}
