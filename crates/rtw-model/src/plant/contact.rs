//! Ground contact of one rod (docs/model.md §4): the three modes in reduced
//! coordinates, the contact force λ, the touchdown impact and the one
//! mode-choice rule used at every touchdown, lift-off and re-stick.
//!
//! Each rod owns six state slots. Their meaning depends on its mode, so that
//! constraints hold exactly (no drift, no stabilization):
//!
//! | mode | slots 0..3 (position) | slots 3..6 (velocity) |
//! |---|---|---|
//! | free  | centre x, centre y, θ | ẋ, ẏ, ω |
//! | stick | contact point x, ground height, θ | 0, 0, ω |
//! | slide | tip x, ground height, θ | tip ẋ, 0, ω |
//!
//! Stick and slide share a layout: a stick is a slide whose tip does not move.
//! Contacts of different rods never couple (strings carry no impulse), so
//! every decision here is per rod.

use crate::plant::geometry::{RodFrame, RodState, Tip, Vec2, add, cross, perp, scale, sub};

/// A rod's contact mode.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RodMode {
    /// 3 DOF (x, y, θ).
    Free,
    /// 1 DOF θ: tip pinned at a ground point.
    Stick {
        /// The tip on the ground.
        tip: Tip,
    },
    /// 2 DOF (x_tip, θ): tip on `y = 0`, moving along it. `dir` is the slip
    /// direction (±1) that friction opposes and that a re-stick must reverse.
    Slide {
        /// The tip on the ground.
        tip: Tip,
        /// The slip direction, ±1.
        dir: f64,
    },
    /// 1 DOF θ: tip pinned in the inside corner at the foot of a face of the
    /// ground, held by the lower patch and the face together
    /// (`plant::face`).
    Corner {
        /// The tip in the corner.
        tip: Tip,
        /// The side of the lower patch (±1 along x): the face's normal.
        side: f64,
    },
    /// 2 DOF (y_tip, θ): tip on a face of the ground, sliding along it
    /// without friction (`plant::face`).
    Wall {
        /// The tip on the face.
        tip: Tip,
        /// The side of the lower patch (±1 along x): the face's normal.
        side: f64,
    },
}

impl RodMode {
    /// The tip on the ground, if any.
    #[inline]
    pub(crate) fn tip(self) -> Option<Tip> {
        match self {
            RodMode::Free => None,
            RodMode::Stick { tip }
            | RodMode::Slide { tip, .. }
            | RodMode::Corner { tip, .. }
            | RodMode::Wall { tip, .. } => Some(tip),
        }
    }

    /// Trace code: 0 free, ±1 stick on tip ±, ±2 slide on tip ±, ±3 in
    /// the corner at a face's foot, ±4 sliding on a face.
    pub(crate) fn code(self) -> i8 {
        match self {
            RodMode::Free => 0,
            RodMode::Stick { tip } => tip.sign() as i8,
            RodMode::Slide { tip, .. } => 2 * tip.sign() as i8,
            RodMode::Corner { tip, .. } => 3 * tip.sign() as i8,
            RodMode::Wall { tip, .. } => 4 * tip.sign() as i8,
        }
    }
}

/// Inertial constants of a rod.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RodBody {
    /// Mass.
    pub m: f64,
    /// Inertia about the centre.
    pub inertia: f64,
    /// L / 2.
    pub half_length: f64,
}

/// External (non-contact) load on a rod: net force and torque about its centre.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Load {
    /// Net force.
    pub force: Vec2,
    /// Torque about the rod's centre.
    pub torque: f64,
}

/// Accelerations of a rod in its mode, and the ground's force on it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RodAccel {
    /// Time derivative of the rod's six slots.
    pub deriv: [f64; 6],
    /// Contact force λ on the tip (zero when free).
    pub lambda: Vec2,
}

impl RodBody {
    /// The vector from the centre to tip `tip`.
    #[inline]
    pub fn arm(&self, theta_e: Vec2, tip: Tip) -> Vec2 {
        scale(tip.sign() * self.half_length, theta_e)
    }

    /// Full coordinates of a rod from its slots.
    #[inline]
    pub fn rod_state(&self, mode: RodMode, s: &[f64]) -> RodState {
        self.frame(mode, s).state(s[2])
    }

    /// Slots of a rod in `mode` from full coordinates. For a contact mode the
    /// tip is taken to be on the ground (its height is dropped) and, in stick,
    /// at rest (its velocity is dropped): callers put it there first.
    #[inline]
    pub fn slots(&self, mode: RodMode, r: &RodState, s: &mut [f64]) {
        match mode {
            RodMode::Free => {
                s[..6].copy_from_slice(&[r.c[0], r.c[1], r.theta, r.v[0], r.v[1], r.omega]);
            }
            RodMode::Stick { tip } | RodMode::Slide { tip, .. } => {
                let (p, vp) = self.tip_point(r, tip);
                let vx = if matches!(mode, RodMode::Stick { .. }) {
                    0.0
                } else {
                    vp[0]
                };
                s[..6].copy_from_slice(&[p[0], 0.0, r.theta, vx, 0.0, r.omega]);
            }
            // At a face the tip's height is its own, not a patch's level.
            RodMode::Corner { tip, .. } => {
                let (p, _) = self.tip_point(r, tip);
                s[..6].copy_from_slice(&[p[0], p[1], r.theta, 0.0, 0.0, r.omega]);
            }
            RodMode::Wall { tip, .. } => {
                let (p, vp) = self.tip_point(r, tip);
                s[..6].copy_from_slice(&[p[0], p[1], r.theta, 0.0, vp[1], r.omega]);
            }
        }
    }

    /// Position and velocity of a tip.
    #[inline]
    pub fn tip_point(&self, r: &RodState, tip: Tip) -> (Vec2, Vec2) {
        let (sin, cos) = r.theta.sin_cos();
        let d = self.arm([cos, sin], tip);
        (add(r.c, d), add(r.v, scale(r.omega, perp(d))))
    }

    /// Full coordinates and unit vector of a rod from its slots, with one
    /// `sin_cos` (the hot path's only trigonometry).
    #[inline]
    pub fn frame(&self, mode: RodMode, s: &[f64]) -> RodFrame {
        let (sin, cos) = s[2].sin_cos();
        self.frame_with(mode, s, [cos, sin])
    }

    /// [`frame`](Self::frame) given the unit vector `e` of the angle `s[2]`.
    #[inline]
    pub fn frame_with(&self, mode: RodMode, s: &[f64], e: Vec2) -> RodFrame {
        match mode {
            RodMode::Free => RodFrame {
                c: [s[0], s[1]],
                v: [s[3], s[4]],
                omega: s[5],
                e,
            },
            RodMode::Stick { tip } | RodMode::Slide { tip, .. } | RodMode::Corner { tip, .. } => {
                let d = self.arm(e, tip);
                RodFrame {
                    c: sub([s[0], s[1]], d),
                    v: sub([s[3], 0.0], scale(s[5], perp(d))),
                    omega: s[5],
                    e,
                }
            }
            RodMode::Wall { tip, .. } => {
                let d = self.arm(e, tip);
                RodFrame {
                    c: sub([s[0], s[1]], d),
                    v: sub([0.0, s[4]], scale(s[5], perp(d))),
                    omega: s[5],
                    e,
                }
            }
        }
    }

    /// Accelerations in `mode` under `load`. `mu` is the friction coefficient
    /// (infinite: slide is frictionless).
    #[inline]
    pub fn accel(&self, mode: RodMode, r: &RodFrame, load: &Load, mu: f64) -> RodAccel {
        let m = self.m;
        let f = load.force;
        match mode {
            RodMode::Free => RodAccel {
                deriv: [
                    r.v[0],
                    r.v[1],
                    r.omega,
                    f[0] / m,
                    f[1] / m,
                    load.torque / self.inertia,
                ],
                lambda: [0.0, 0.0],
            },
            // In the corner the tip is pinned as in stick. One arm for both,
            // not a call of `accel` again: a recursive `accel` is not inlined
            // into the right-hand side, and the flat slope paid for it.
            RodMode::Stick { tip } | RodMode::Corner { tip, .. } => {
                let d = self.arm(r.e, tip);
                let w2 = r.omega * r.omega;
                // I_P θ̈ = τ_P, the moment about the contact point P = c + d.
                let tau_p = load.torque - cross(d, f);
                let i_p = self.inertia + m * self.half_length * self.half_length;
                let beta = tau_p / i_p;
                // c = P − d: c̈ = −(β d⊥ − ω² d); λ = m c̈ − F.
                let cdd = scale(-1.0, sub(scale(beta, perp(d)), scale(w2, d)));
                RodAccel {
                    deriv: [0.0, 0.0, r.omega, 0.0, 0.0, beta],
                    lambda: sub(scale(m, cdd), f),
                }
            }
            RodMode::Wall { tip, .. } => self.wall_accel(tip, r, load),
            RodMode::Slide { tip, dir } => {
                let kappa = if mu.is_finite() { -mu * dir } else { 0.0 };
                let d = self.arm(r.e, tip);
                let w2 = r.omega * r.omega;
                let i = self.inertia;
                // Unknowns: tip acceleration a, θ̈ = β, normal force λ_y
                // (λ_x = κ λ_y). With c = (x_t, 0) − d:
                //   m (a + β d_y + ω² d_x) = F_x + κ λ_y
                //   m (−β d_x + ω² d_y)    = F_y + λ_y
                //   I β = τ + λ_y (d_x − κ d_y)
                let lam_y = (m * w2 * d[1] - f[1] - m * d[0] * load.torque / i)
                    / (1.0 + m * d[0] * (d[0] - kappa * d[1]) / i);
                let beta = (load.torque + lam_y * (d[0] - kappa * d[1])) / i;
                let a = (f[0] + kappa * lam_y) / m - beta * d[1] - w2 * d[0];
                // Slots: (x_t, 0, θ, ẋ_t, 0, ω).
                RodAccel {
                    // ẋ_t: the tip's velocity, v + ω d⊥.
                    deriv: [r.v[0] - r.omega * d[1], 0.0, r.omega, a, 0.0, beta],
                    lambda: [kappa * lam_y, lam_y],
                }
            }
        }
    }

    /// Acceleration of a tip if the rod were free.
    #[inline]
    pub fn free_tip_accel(&self, r: &RodState, tip: Tip, load: &Load) -> Vec2 {
        let (sin, cos) = r.theta.sin_cos();
        let d = self.arm([cos, sin], tip);
        let beta = load.torque / self.inertia;
        let a = scale(1.0 / self.m, load.force);
        add(a, sub(scale(beta, perp(d)), scale(r.omega * r.omega, d)))
    }

    /// Kinetic energy.
    #[inline]
    pub fn kinetic(&self, r: &RodState) -> f64 {
        0.5 * self.m * (r.v[0] * r.v[0] + r.v[1] * r.v[1]) + 0.5 * self.inertia * r.omega * r.omega
    }

    #[cfg(test)]
    /// Angular momentum about a point `p` (z-component).
    pub fn angular_momentum_about(&self, r: &RodState, p: Vec2) -> f64 {
        self.inertia * r.omega + self.m * cross(sub(r.c, p), r.v)
    }

    /// The perfectly inelastic touchdown of `tip` (docs/model.md §4).
    ///
    /// Sticking impact: the tip stops, angular momentum about it is conserved,
    /// `I_P ω⁺ = I ω⁻ + m (c − P) × v⁻`. If that would need a pulling normal
    /// impulse the impact is frictionless instead (normal tip velocity to zero,
    /// no tangential impulse); with finite `mu`, if the sticking impulse leaves
    /// the friction cone the impact slides with `|Π_x| = μ Π_y`.
    pub fn touchdown(&self, r: &RodState, tip: Tip, mu: f64) -> Impact {
        let stick = self.impact(r, tip, ImpactKind::Stick);
        let impulse = stick.impulse;
        let in_cone = mu.is_infinite() || impulse[0].abs() <= mu * impulse[1];
        if impulse[1] >= 0.0 && in_cone {
            return stick;
        }
        // Frictionless (pulling) or sliding (outside the cone) impact.
        let kappa = if impulse[1] >= 0.0 {
            mu * impulse[0].signum()
        } else {
            0.0
        };
        self.impact(r, tip, ImpactKind::Slide { kappa })
    }

    /// The impact of `kind` on `tip` (the choice among the kinds is
    /// [`touchdown`](Self::touchdown)'s).
    pub fn impact(&self, r: &RodState, tip: Tip, kind: ImpactKind) -> Impact {
        let (sin, cos) = r.theta.sin_cos();
        let d = self.arm([cos, sin], tip);
        match kind {
            ImpactKind::Stick => {
                let i_p = self.inertia + self.m * self.half_length * self.half_length;
                // Angular momentum about P = c + d: I ω + m (−d) × v.
                let omega = (self.inertia * r.omega - self.m * cross(d, r.v)) / i_p;
                let v = scale(-omega, perp(d));
                Impact {
                    after: RodState { v, omega, ..*r },
                    impulse: scale(self.m, sub(v, r.v)),
                    kind,
                }
            }
            ImpactKind::Face => self.face_impact(r, tip),
            ImpactKind::Slide { kappa } => {
                // Π = (κ Π_y, Π_y) with the tip's normal velocity brought to zero.
                let v_tip_y = r.v[1] + r.omega * d[0];
                let p_y = -v_tip_y / (1.0 / self.m + d[0] * (d[0] - kappa * d[1]) / self.inertia);
                let impulse = [kappa * p_y, p_y];
                Impact {
                    after: RodState {
                        v: add(r.v, scale(1.0 / self.m, impulse)),
                        omega: r.omega + cross(d, impulse) / self.inertia,
                        ..*r
                    },
                    impulse,
                    kind,
                }
            }
        }
    }

    /// The one mode-choice rule (docs/model.md §4), for a rod whose `tip` is on the
    /// ground with zero normal velocity: *stick* if its normal force λ_y > 0
    /// (and, with finite μ, |λ_x| ≤ μ λ_y) and the tip is at rest; else *free*
    /// if the free tip would not accelerate into the ground; else *slide*. If
    /// even the slide would need a pulling normal force (no consistent mode,
    /// which a frictionless or Painlevé-free contact never meets) it is free.
    ///
    /// `at_rest` says the tip has no tangential velocity (after a sticking
    /// impact, while sticking, at a re-stick); only then can it stick.
    pub fn choose_mode(
        &self,
        r: &RodState,
        tip: Tip,
        at_rest: bool,
        load: &Load,
        mu: f64,
    ) -> RodMode {
        self.choose(r, tip, at_rest, true, load, mu)
    }

    /// [`choose_mode`](Self::choose_mode) when a guard has just found the
    /// condition of the rod's mode `leaving` violated (a lift-off: λ_y ≤ 0; a
    /// slip: |λ_x| ≥ μ λ_y). The rule's own evaluation of that condition, at
    /// the same state by another rounding path, can still pass; the rod would
    /// then stay in a mode whose guard, now on its crossed side, never fires
    /// again (a stick outside the friction cone). So the mode it leaves is
    /// excluded: stick first, then free.
    pub fn choose_mode_leaving(
        &self,
        r: &RodState,
        tip: Tip,
        at_rest: bool,
        load: &Load,
        mu: f64,
        leaving: RodMode,
    ) -> RodMode {
        let mode = self.choose(r, tip, at_rest, true, load, mu);
        if mode != leaving {
            return mode;
        }
        let mode = self.choose(r, tip, at_rest, false, load, mu);
        if mode != leaving { mode } else { RodMode::Free }
    }

    fn choose(
        &self,
        r: &RodState,
        tip: Tip,
        at_rest: bool,
        may_stick: bool,
        load: &Load,
        mu: f64,
    ) -> RodMode {
        let (_, v_tip) = self.tip_point(r, tip);
        let frame = RodFrame::new(r);
        let stick = RodMode::Stick { tip };
        let lam = self.accel(stick, &frame, load, mu).lambda;
        if may_stick && at_rest && lam[1] > 0.0 && (mu.is_infinite() || lam[0].abs() <= mu * lam[1])
        {
            return stick;
        }
        if self.free_tip_accel(r, tip, load)[1] >= 0.0 {
            return RodMode::Free;
        }
        let dir = if !at_rest {
            v_tip[0].signum()
        } else if mu.is_finite() && lam[1] > 0.0 {
            // The tip slips against the friction it could not get.
            -lam[0].signum()
        } else {
            // Frictionless: it slides the way it accelerates.
            let probe = self.accel(
                RodMode::Slide { tip, dir: 1.0 },
                &frame,
                load,
                f64::INFINITY,
            );
            if probe.deriv[3] < 0.0 { -1.0 } else { 1.0 }
        };
        let slide = RodMode::Slide { tip, dir };
        if self.accel(slide, &frame, load, mu).lambda[1] > 0.0 {
            slide
        } else {
            RodMode::Free
        }
    }
}

/// Which impact a touchdown is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ImpactKind {
    /// The tip stops (it is at rest afterwards).
    Stick,
    /// The tip's normal velocity stops; the tangential impulse is `κ` times
    /// the normal one (`κ = ±μ` sliding, 0 frictionless).
    Slide {
        /// Tangential over normal impulse.
        kappa: f64,
    },
    /// A face of the ground stops the tip's velocity across it, without
    /// friction (`plant::face`).
    Face,
}

/// Result of a touchdown impact.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Impact {
    /// The rod just after the impact (same position).
    pub after: RodState,
    /// Impulse of the ground on the tip.
    pub impulse: Vec2,
    /// Which impact it was.
    pub kind: ImpactKind,
}

impl Impact {
    /// A sticking impact: the tip is at rest afterwards.
    #[inline]
    pub fn sticks(&self) -> bool {
        self.kind == ImpactKind::Stick
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn body() -> RodBody {
        RodBody {
            m: 2.0,
            inertia: 2.0 * 0.64 / 12.0,
            half_length: 0.4,
        }
    }

    fn rod(theta: f64, v: Vec2, omega: f64) -> RodState {
        RodState {
            c: [0.3, 0.4 * theta.sin().abs()],
            theta,
            v,
            omega,
        }
    }

    #[test]
    fn slots_round_trip_in_every_mode() {
        let b = body();
        let r = rod(-1.0, [0.2, -0.1], 0.7);
        for mode in [
            RodMode::Free,
            RodMode::Slide {
                tip: Tip::Plus,
                dir: 1.0,
            },
        ] {
            let mut s = [0.0; 6];
            // Put the tip on the ground first (θ = −1 puts tip + below the centre).
            let mut r = r;
            if mode != RodMode::Free {
                let (p, vp) = b.tip_point(&r, Tip::Plus);
                r.c[1] -= p[1];
                r.v[1] -= vp[1];
            }
            b.slots(mode, &r, &mut s);
            let back = b.rod_state(mode, &s);
            for k in 0..2 {
                assert!((back.c[k] - r.c[k]).abs() < 1e-15);
                assert!((back.v[k] - r.v[k]).abs() < 1e-15);
            }
        }
    }

    #[test]
    fn impact_conserves_angular_momentum_about_tip_and_loses_energy() {
        let b = body();
        for (theta, v, w) in [
            (-1.2, [0.5, -0.8], -1.5),
            (-2.0, [0.9, -0.3], -3.0),
            (-0.6, [0.1, -1.0], 2.0),
        ] {
            let r = rod(theta, v, w);
            let (p, _) = b.tip_point(&r, Tip::Plus);
            let imp = b.touchdown(&r, Tip::Plus, f64::INFINITY);
            let h0 = b.angular_momentum_about(&r, p);
            let h1 = b.angular_momentum_about(&imp.after, p);
            // An impulse at P has no moment about P.
            assert!((h0 - h1).abs() < 1e-13, "{h0} {h1}");
            assert!(b.kinetic(&imp.after) <= b.kinetic(&r) + 1e-15);
            let (_, vt) = b.tip_point(&imp.after, Tip::Plus);
            assert!(vt[1].abs() < 1e-13);
            if imp.sticks() {
                assert!(vt[0].abs() < 1e-13);
                assert!(imp.impulse[1] >= 0.0);
            }
        }
    }

    #[test]
    fn pulling_impact_falls_back_to_frictionless() {
        let b = body();
        // A rod flying uphill, tip slightly below its centre and descending:
        // stopping the tip dead would swing the centre up faster than it
        // moves, i.e. need the ground to pull (hand check: ω⁺ ≈ 1.6 rad/s,
        // Π_y ≈ 2 (−0.62 + 0.05) < 0).
        let r = rod(-0.3, [-3.0, -0.05], -0.5);
        let (_, vt) = b.tip_point(&r, Tip::Plus);
        assert!(vt[1] < 0.0);
        let imp = b.touchdown(&r, Tip::Plus, f64::INFINITY);
        assert!(!imp.sticks());
        assert_eq!(imp.impulse[0], 0.0);
        assert!(imp.impulse[1] > 0.0);
        let (_, vt2) = b.tip_point(&imp.after, Tip::Plus);
        assert!(vt2[1].abs() < 1e-14);
        assert!(b.kinetic(&imp.after) <= b.kinetic(&r));
    }

    #[test]
    fn stick_lambda_is_newton_for_the_centre() {
        // λ = m c̈ − F, with c̈ from finite differences of the stick motion.
        let b = body();
        let load = Load {
            force: [3.0, -25.0],
            torque: 1.5,
        };
        let mode = RodMode::Stick { tip: Tip::Minus };
        let s0 = [0.1, 0.0, 0.9, 0.0, 0.0, 1.3];
        let acc = b.accel(mode, &b.frame(mode, &s0), &load, f64::INFINITY);
        let h = 1e-5;
        let at = |t: f64| {
            let th = s0[2] + s0[5] * t + 0.5 * acc.deriv[5] * t * t;
            let s = [s0[0], 0.0, th, 0.0, 0.0, s0[5] + acc.deriv[5] * t];
            b.rod_state(mode, &s).c
        };
        let (cm, c0, cp) = (at(-h), at(0.0), at(h));
        for k in 0..2 {
            let cdd = (cp[k] - 2.0 * c0[k] + cm[k]) / (h * h);
            assert!((b.m * cdd - load.force[k] - acc.lambda[k]).abs() < 1e-4);
        }
    }

    #[test]
    fn slide_keeps_tip_on_ground_and_obeys_newton() {
        let b = body();
        let load = Load {
            force: [3.0, -25.0],
            torque: 1.5,
        };
        for mu in [f64::INFINITY, 0.6] {
            let mode = RodMode::Slide {
                tip: Tip::Plus,
                dir: 1.0,
            };
            let s = [0.1, 0.0, -1.0, 0.4, 0.0, -0.8];
            let r = b.rod_state(mode, &s);
            let acc = b.accel(mode, &b.frame(mode, &s), &load, mu);
            // Rebuild c̈ from the slot accelerations and check m c̈ = F + λ, I θ̈ = τ + d × λ.
            let h = 1e-5;
            let at = |t: f64| {
                let st = [
                    s[0] + s[3] * t + 0.5 * acc.deriv[3] * t * t,
                    0.0,
                    s[2] + s[5] * t + 0.5 * acc.deriv[5] * t * t,
                    s[3] + acc.deriv[3] * t,
                    0.0,
                    s[5] + acc.deriv[5] * t,
                ];
                b.rod_state(mode, &st).c
            };
            let (cm, c0, cp) = (at(-h), at(0.0), at(h));
            for k in 0..2 {
                let cdd = (cp[k] - 2.0 * c0[k] + cm[k]) / (h * h);
                assert!(
                    (b.m * cdd - load.force[k] - acc.lambda[k]).abs() < 1e-4,
                    "mu {mu}"
                );
            }
            let d = b.arm([r.theta.cos(), r.theta.sin()], Tip::Plus);
            // ẋ_t is the tip's own velocity, which the slots also carry.
            assert!(
                (acc.deriv[0] - s[3]).abs() < 1e-12,
                "{} vs {}",
                acc.deriv[0],
                s[3]
            );
            let res = b.inertia * acc.deriv[5] - load.torque - cross(d, acc.lambda);
            assert!(res.abs() < 1e-12);
            if mu.is_finite() {
                assert!((acc.lambda[0] + mu * acc.lambda[1]).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn mode_choice_covers_stick_free_and_slide() {
        let b = body();
        let mu = f64::INFINITY;
        let tip = Tip::Plus;
        // Standing, pressed down by gravity: stick.
        let r = rod(-1.2, [0.0, 0.0], 0.0);
        let (p, _) = b.tip_point(&r, tip);
        let r = RodState {
            c: [r.c[0], r.c[1] - p[1]],
            ..r
        };
        let gravity = Load {
            force: [0.0, -19.62],
            torque: 0.0,
        };
        assert_eq!(
            b.choose_mode(&r, tip, true, &gravity, mu),
            RodMode::Stick { tip }
        );
        // Pulled up hard: free.
        let up = Load {
            force: [0.0, 60.0],
            torque: 0.0,
        };
        assert_eq!(b.choose_mode(&r, tip, true, &up, mu), RodMode::Free);
        // The Painlevé-type gap of docs/model.md §4: a large uphill pull F_x that
        // the pinned tip resists makes stick need λ_y < 0, while released the
        // torque drives the free tip into the ground: slide. (With ω = 0,
        // λ_y = −m d_x (τ − d × F)/I_P − F_y < 0 needs F_x < −115 N here.)
        let r = rod(-0.35, [0.0, 0.0], 0.0);
        let (p, _) = b.tip_point(&r, tip);
        let r = RodState {
            c: [r.c[0], r.c[1] - p[1]],
            ..r
        };
        let load = Load {
            force: [-150.0, -19.62],
            torque: -12.0,
        };
        let f = RodFrame::new(&r);
        let stick = b.accel(RodMode::Stick { tip }, &f, &load, mu).lambda;
        let free = b.free_tip_accel(&r, tip, &load);
        assert!(
            stick[1] < 0.0 && free[1] < 0.0,
            "constructed gap: {stick:?} {free:?}"
        );
        let mode = b.choose_mode(&r, tip, true, &load, mu);
        assert!(matches!(mode, RodMode::Slide { .. }), "{mode:?}");
        assert!(b.accel(mode, &f, &load, mu).lambda[1] > 0.0);
    }
}
