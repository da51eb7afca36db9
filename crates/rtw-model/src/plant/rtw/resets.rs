//! The resets: what a guard's crossing does to the modes and the state
//! (touchdown, lift-off, re-stick, slip, failure).

use super::model::{Choice, GuardKind, Rtw, Transition};
use crate::outcome::FailureDetail;
use crate::plant::contact::RodMode;
use crate::plant::geometry::{RodFrame, Tip};
use crate::plant::slots::{self, N, OMEGA, VX};

impl Rtw {
    /// The reset of guard `kind`, which has just fired at `y`.
    pub(super) fn reset_kind(&mut self, y: &mut [f64; N], kind: GuardKind) -> Transition {
        match kind {
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
}
