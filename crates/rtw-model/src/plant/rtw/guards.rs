//! The guards that end a mode: which ones the current modes watch, in a
//! fixed order, their values, and the rates of the kinematic ones.

use super::model::{GuardKind, Rtw};
use crate::plant::contact::RodMode;
use crate::plant::geometry::{RodFrame, Tip, Vec2};
use crate::plant::slots::{self, N, VX};
use hybrid_ode::{Crossing, Guards};
use std::ops::ControlFlow;

impl Rtw {
    /// The guards of the current modes, in a fixed order that depends only
    /// on the modes (the engine compares the same index across a step).
    #[inline]
    pub fn guard_kinds(&self, mut visit: impl FnMut(GuardKind)) {
        let _: ControlFlow<()> = self.try_guard_kinds(|kind| {
            visit(kind);
            ControlFlow::Continue(())
        });
    }

    /// [`guard_kinds`](Self::guard_kinds) until `visit` breaks: the lookup
    /// of one guard stops at it (root finding asks at every iterate).
    #[inline]
    fn try_guard_kinds<B>(
        &self,
        mut visit: impl FnMut(GuardKind) -> ControlFlow<B>,
    ) -> ControlFlow<B> {
        for (rod, mode) in self.modes.iter().enumerate() {
            match *mode {
                RodMode::Free => {
                    visit(GuardKind::Touchdown {
                        rod,
                        tip: Tip::Plus,
                    })?;
                    visit(GuardKind::Touchdown {
                        rod,
                        tip: Tip::Minus,
                    })?;
                    if !self.terrain.is_flat() {
                        visit(GuardKind::EdgePass {
                            rod,
                            tip: Tip::Plus,
                        })?;
                        visit(GuardKind::EdgePass {
                            rod,
                            tip: Tip::Minus,
                        })?;
                    }
                }
                RodMode::Stick { .. } => {
                    visit(GuardKind::LiftOff { rod })?;
                    visit(GuardKind::RodDown { rod })?;
                    if self.mu.is_finite() {
                        visit(GuardKind::Slip { rod })?;
                    }
                }
                RodMode::Slide { .. } => {
                    visit(GuardKind::LiftOff { rod })?;
                    visit(GuardKind::RodDown { rod })?;
                    visit(GuardKind::Restick { rod })?;
                    if !self.terrain.is_flat() {
                        visit(GuardKind::Edge { rod })?;
                    }
                }
                // At a face (never on the flat slope).
                RodMode::Corner { .. } => {
                    visit(GuardKind::LiftOff { rod })?;
                    visit(GuardKind::RodDown { rod })?;
                    if self.mu.is_finite() {
                        visit(GuardKind::Slip { rod })?;
                    }
                }
                // The face's foot and top are two guards, each linear in the
                // tip's height: the nearer of the two as one guard was a tent
                // whose cubic model on a step missed a tip that went over the
                // whole of a low face and beyond its top within the step.
                RodMode::Wall { .. } => {
                    visit(GuardKind::LiftOff { rod })?;
                    visit(GuardKind::RodDown { rod })?;
                    visit(GuardKind::Edge { rod })?;
                    visit(GuardKind::FaceTop { rod })?;
                }
            }
        }
        visit(GuardKind::ComLow)
    }

    pub(super) fn guards_of(
        &self,
        y: &[f64; N],
        frames: &[RodFrame; 3],
        lambda: &[Vec2; 3],
        out: &mut Guards,
    ) {
        out.clear();
        self.guard_kinds(|kind| {
            let value = self.guard_value(kind, y, |rod| frames[rod], |rod| lambda[rod]);
            out.push(value, Crossing::Falling);
        });
    }

    /// The value of guard `kind` at `y`, given each rod's frame and contact
    /// force λ there (asked for only when this guard needs them).
    #[inline]
    pub(super) fn guard_value(
        &self,
        kind: GuardKind,
        y: &[f64; N],
        frame: impl Fn(usize) -> RodFrame,
        lambda: impl Fn(usize) -> Vec2,
    ) -> f64 {
        // The tip and its height are `#[inline(always)]` methods, the
        // closures only bind `frame`: with the arithmetic in closures (one
        // calling the other) they stayed calls once the faces' guards grew
        // this match, a call for every tip height of the flat slope.
        let tip = |rod: usize, t: Tip| self.tip_at(&frame(rod), t);
        let tip_height = |rod: usize, t: Tip| self.height_above_ground(self.tip_at(&frame(rod), t));
        match kind {
            // A free tip's height above the patch under it: smooth, as the
            // patch changes only at an edge pass.
            GuardKind::Touchdown { rod, tip: t } if !self.terrain.is_flat() => {
                tip(rod, t)[1] - self.over[rod][t.index()].level - self.touchdown_height
            }
            GuardKind::Touchdown { rod, tip: t } => tip_height(rod, t) - self.touchdown_height,
            GuardKind::LiftOff { rod } => match self.modes[rod] {
                // On a face: the face's normal force.
                RodMode::Wall { side, .. } => side * lambda(rod)[0],
                _ => lambda(rod)[1],
            },
            GuardKind::RodDown { rod } => {
                let tip = self.modes[rod].tip().expect("grounded rod");
                tip_height(rod, tip.other())
            }
            GuardKind::Restick { rod } => {
                let RodMode::Slide { dir, .. } = self.modes[rod] else {
                    unreachable!("restick guard on a sliding rod")
                };
                y[slots::at(rod, VX)] * dir + self.restick_speed
            }
            GuardKind::Slip { rod } => {
                let l = lambda(rod);
                match self.modes[rod] {
                    // In the corner only a pull towards the face can slip
                    // (crate::plant::face).
                    RodMode::Corner { side, .. } => side * l[0] + self.mu * l[1],
                    _ => self.mu * l[1] - l[0].abs(),
                }
            }
            GuardKind::ComLow => {
                let (a, b, c) = (frame(0).c, frame(1).c, frame(2).c);
                let ground = self.ground((a[0] + b[0] + c[0]) / 3.0);
                (a[1] + b[1] + c[1]) / 3.0 - ground - self.collapse_height
            }
            GuardKind::Edge { rod } => self.edge_guard(y, rod),
            GuardKind::FaceTop { rod } => self.face_top_guard(y, rod),
            GuardKind::EdgePass { rod, tip: t } => self.edge_pass_guard(tip(rod, t)[0], rod, t),
        }
    }

    /// The point of `tip` of the rod with frame `f`.
    #[inline(always)]
    fn tip_at(&self, f: &RodFrame, tip: Tip) -> Vec2 {
        f.point(tip.sign() * self.body.half_length).0
    }

    /// A point's height above the ground under it (crate::plant::terrain).
    #[inline(always)]
    fn height_above_ground(&self, p: Vec2) -> f64 {
        p[1] - self.ground(p[0])
    }

    /// The time derivative of guard `kind` at a state with frames `frames`
    /// and `ẏ = dy`, where it is kinematic: a tip height's is the tip's
    /// vertical velocity, the centre of mass's its mean vertical velocity, a
    /// re-stick's the sliding tip's acceleration. `None` for a guard on a
    /// contact force (lift-off, slip), whose rate needs the forces' own.
    #[inline]
    pub(super) fn kinematic_guard_rate(
        &self,
        kind: GuardKind,
        y: &[f64; N],
        dy: &[f64; N],
        frames: &[RodFrame; 3],
    ) -> Option<f64> {
        let tip_rate =
            |rod: usize, tip: Tip| frames[rod].point(tip.sign() * self.body.half_length).1[1];
        match kind {
            GuardKind::Touchdown { rod, tip } => Some(tip_rate(rod, tip)),
            GuardKind::RodDown { rod } => {
                let tip = self.modes[rod].tip().expect("grounded rod");
                Some(tip_rate(rod, tip.other()))
            }
            GuardKind::Restick { rod } => {
                let RodMode::Slide { dir, .. } = self.modes[rod] else {
                    unreachable!("restick guard on a sliding rod")
                };
                Some(dy[slots::at(rod, VX)] * dir)
            }
            GuardKind::ComLow => Some((frames[0].v[1] + frames[1].v[1] + frames[2].v[1]) / 3.0),
            GuardKind::Edge { rod } => Some(self.edge_guard_rate(y, dy, rod)),
            GuardKind::FaceTop { rod } => Some(-dy[slots::at(rod, slots::Y)]),
            GuardKind::EdgePass { rod, tip } => {
                let (p, v) = frames[rod].point(tip.sign() * self.body.half_length);
                Some(self.edge_pass_rate(p[0], v[0], rod, tip))
            }
            GuardKind::LiftOff { .. } | GuardKind::Slip { .. } => None,
        }
    }

    /// The guard of index `index` in the current modes.
    pub fn guard_kind(&self, index: usize) -> GuardKind {
        let mut k = 0;
        let found = self.try_guard_kinds(|kind| {
            if k == index {
                return ControlFlow::Break(kind);
            }
            k += 1;
            ControlFlow::Continue(())
        });
        match found {
            ControlFlow::Break(kind) => kind,
            ControlFlow::Continue(()) => panic!("guard index {index} out of range"),
        }
    }
}
