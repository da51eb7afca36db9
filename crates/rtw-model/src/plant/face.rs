//! A tip against a face of the ground (docs/model.md §4, "Faces"): the
//! vertical surface at the edge between two patches of a step or a rough
//! slope. Faces are frictionless; the lower patch's ground keeps its
//! friction μ.
//!
//! * **The face's impact** ([`ImpactKind::Face`]) stops the tip's velocity
//!   across the face with an impulse along its normal `(side, 0)`: perfectly
//!   inelastic like a touchdown, and like it it only loses energy.
//! * **Wall** ([`RodMode::Wall`]): the tip slides along the face. Its one
//!   constraint force is the face's normal force `λ = (λ_x, 0)`, which does no
//!   work (the tip moves along the face), so no energy is made or lost.
//! * **Corner** ([`RodMode::Corner`]): the tip rests in the inside corner at
//!   the face's foot, pinned as a stick. The ground and the face together
//!   hold it against any force `λ` with `λ_y ≥ 0` whose pull towards the
//!   face stays within the ground's friction, `side λ_x ≥ −μ λ_y`: the
//!   face's normal force takes any push away from it.
//!
//! A tip arriving in the corner (sliding into the face, or sliding down it)
//! takes the first admissible of three impacts: it stops there, if the
//! impulse that stops it is one the corner can give; else the ground's own
//! impact, if it leaves the tip moving away from the face; else the face's,
//! if it leaves the tip moving up the face. (If none is admissible, which
//! the three cover for any tip moving into the corner, it stops.)

use crate::plant::contact::{Impact, ImpactKind, Load, RodAccel, RodBody, RodMode};
use crate::plant::geometry::{RodFrame, RodState, Tip, cross};

impl RodBody {
    /// The accelerations of a rod whose `tip` slides along a face without
    /// friction. With `d` the centre-to-tip arm, the tip at `(x_f, y_t)` and
    /// `c = (x_f, y_t) − d`:
    ///
    /// ```text
    /// m (β d_y + ω² d_x)     = F_x + λ_x
    /// m (ÿ_t − β d_x + ω² d_y) = F_y
    /// I β = τ − d_y λ_x
    /// ```
    pub(crate) fn wall_accel(&self, tip: Tip, r: &RodFrame, load: &Load) -> RodAccel {
        let (m, f) = (self.m, load.force);
        let d = self.arm(r.e, tip);
        let w2 = r.omega * r.omega;
        let beta =
            (load.torque + d[1] * f[0] - m * w2 * d[0] * d[1]) / (self.inertia + m * d[1] * d[1]);
        let lam_x = m * (beta * d[1] + w2 * d[0]) - f[0];
        let a = f[1] / m + beta * d[0] - w2 * d[1];
        RodAccel {
            // ẏ_t: the tip's vertical velocity, v_y + ω d_x.
            deriv: [0.0, r.v[1] + r.omega * d[0], r.omega, 0.0, a, beta],
            lambda: [lam_x, 0.0],
        }
    }

    /// The face's impact: the impulse `(Π_x, 0)` at the tip that stops its
    /// velocity across the face, `Π_x = −v_tx / (1/m + d_y²/I)`.
    pub(crate) fn face_impact(&self, r: &RodState, tip: Tip) -> Impact {
        let (sin, cos) = r.theta.sin_cos();
        let d = self.arm([cos, sin], tip);
        let v_tip_x = r.v[0] - r.omega * d[1];
        let p_x = -v_tip_x / (1.0 / self.m + d[1] * d[1] / self.inertia);
        let impulse = [p_x, 0.0];
        Impact {
            after: RodState {
                v: [r.v[0] + p_x / self.m, r.v[1]],
                omega: r.omega + cross(d, impulse) / self.inertia,
                ..*r
            },
            impulse,
            kind: ImpactKind::Face,
        }
    }

    /// The impact of a tip arriving in the corner at the foot of a face on
    /// `side` (module docs): the first admissible of stopping, the ground's
    /// impact and the face's.
    pub(crate) fn corner_impact(&self, r: &RodState, tip: Tip, side: f64, mu: f64) -> Impact {
        let stop = self.impact(r, tip, ImpactKind::Stick);
        if corner_holds(stop.impulse, side, mu) {
            return stop;
        }
        let (_, v) = self.tip_point(r, tip);
        if v[1] < 0.0 {
            let ground = self.touchdown(r, tip, mu);
            if side * self.tip_point(&ground.after, tip).1[0] >= 0.0 {
                return ground;
            }
        }
        if side * v[0] < 0.0 {
            let face = self.face_impact(r, tip);
            if self.tip_point(&face.after, tip).1[1] >= 0.0 {
                return face;
            }
        }
        stop
    }

    /// The mode of a rod whose `tip` has just arrived at the corner of a
    /// face on `side`, or has left a mode there (`may_stay` false: the
    /// corner's guard found its condition violated). By the tip's velocity:
    /// moving away from the face along the ground, the ground's rule; moving
    /// up the face, [`choose_at_wall`](Self::choose_at_wall); at rest, the
    /// corner if it holds, else free if the free tip accelerates away from
    /// both surfaces, else a slide up the face or away from it along the
    /// ground, whichever is consistent (the one the lost condition points
    /// to first), else free.
    pub(crate) fn choose_at_corner(
        &self,
        r: &RodState,
        tip: Tip,
        load: &Load,
        mu: f64,
        side: f64,
        may_stay: bool,
    ) -> RodMode {
        let (_, v) = self.tip_point(r, tip);
        if side * v[0] > 0.0 && v[1] <= 0.0 {
            return self.choose_mode(r, tip, false, load, mu);
        }
        if v[1] > 0.0 {
            return self.choose_at_wall(r, tip, load, side, true);
        }
        let frame = RodFrame::new(r);
        let lam = self.accel(RodMode::Stick { tip }, &frame, load, mu).lambda;
        if may_stay && lam[1] > 0.0 && corner_holds(lam, side, mu) {
            return RodMode::Corner { tip, side };
        }
        let a = self.free_tip_accel(r, tip, load);
        if a[1] >= 0.0 && side * a[0] >= 0.0 {
            return RodMode::Free;
        }
        let wall = RodMode::Wall { tip, side };
        let up = self.accel(wall, &frame, load, mu);
        let wall_ok = side * up.lambda[0] > 0.0 && up.deriv[4] >= 0.0;
        let slide = RodMode::Slide { tip, dir: side };
        let away = self.accel(slide, &frame, load, mu);
        let slide_ok = away.lambda[1] > 0.0 && side * away.deriv[3] >= 0.0;
        match (lam[1] > 0.0, wall_ok, slide_ok) {
            (true, _, true) | (false, false, true) => slide,
            (_, true, _) => wall,
            _ => RodMode::Free,
        }
    }

    /// The mode of a rod whose `tip` is on a face on `side` and not moving
    /// across it: the wall if the face must push to keep the tip out of it
    /// (`may_stay` false: its lift-off guard has just fired), else free.
    pub(crate) fn choose_at_wall(
        &self,
        r: &RodState,
        tip: Tip,
        load: &Load,
        side: f64,
        may_stay: bool,
    ) -> RodMode {
        let wall = RodMode::Wall { tip, side };
        let lam = self.wall_accel(tip, &RodFrame::new(r), load).lambda;
        if may_stay && side * lam[0] > 0.0 {
            wall
        } else {
            RodMode::Free
        }
    }
}

/// Can the corner at the foot of a face on `side` give the force or
/// impulse `p`: pushing up off the ground (`p_y ≥ 0`), and pulling towards
/// the face no more than the ground's friction allows?
pub(crate) fn corner_holds(p: [f64; 2], side: f64, mu: f64) -> bool {
    p[1] >= 0.0 && (mu.is_infinite() || side * p[0] >= -mu * p[1])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plant::geometry::sub;

    fn body() -> RodBody {
        RodBody {
            m: 2.0,
            inertia: 2.0 * 0.64 / 12.0,
            half_length: 0.4,
        }
    }

    #[test]
    fn wall_slide_keeps_the_tip_on_the_face_and_obeys_newton() {
        // Finite differences of the constrained motion give c̈; then
        // m c̈ = F + λ and I θ̈ = τ + d × λ, with λ normal to the face and
        // the tip's x fixed.
        let b = body();
        let load = Load {
            force: [3.0, -25.0],
            torque: 1.5,
        };
        for side in [1.0, -1.0] {
            let mode = RodMode::Wall {
                tip: Tip::Plus,
                side,
            };
            let s = [1.0, 0.05, -1.0, 0.0, 0.3, -0.8];
            let acc = b.accel(mode, &b.frame(mode, &s), &load, 0.8);
            assert_eq!(acc.lambda[1], 0.0);
            let h = 1e-5;
            let at = |t: f64| {
                let st = [
                    s[0],
                    s[1] + s[4] * t + 0.5 * acc.deriv[4] * t * t,
                    s[2] + s[5] * t + 0.5 * acc.deriv[5] * t * t,
                    0.0,
                    s[4] + acc.deriv[4] * t,
                    s[5] + acc.deriv[5] * t,
                ];
                b.rod_state(mode, &st)
            };
            let (cm, c0, cp) = (at(-h).c, at(0.0), at(h).c);
            for k in 0..2 {
                let cdd = (cp[k] - 2.0 * c0.c[k] + cm[k]) / (h * h);
                assert!((b.m * cdd - load.force[k] - acc.lambda[k]).abs() < 1e-4);
            }
            let d = b.arm([c0.theta.cos(), c0.theta.sin()], Tip::Plus);
            let res = b.inertia * acc.deriv[5] - load.torque - cross(d, acc.lambda);
            assert!(res.abs() < 1e-12, "{res}");
            // The slots carry the tip's own vertical velocity; the tip does
            // not move across the face.
            let (_, vt) = b.tip_point(&c0, Tip::Plus);
            assert!(vt[0].abs() < 1e-15 && (vt[1] - s[4]).abs() < 1e-15);
            assert_eq!(acc.deriv[1], s[4]);
        }
    }

    #[test]
    fn the_face_stops_the_tip_across_it_and_only_takes_energy() {
        let b = body();
        for (theta, v, w) in [
            (-1.2, [0.5, -0.8], -1.5),
            (-2.0, [0.9, -0.3], -3.0),
            (-0.6, [-0.4, -1.0], 2.0),
        ] {
            let r = RodState {
                c: [0.3, 0.4],
                theta,
                v,
                omega: w,
            };
            let imp = b.face_impact(&r, Tip::Plus);
            let (_, before) = b.tip_point(&r, Tip::Plus);
            let (_, after) = b.tip_point(&imp.after, Tip::Plus);
            assert!(after[0].abs() < 1e-14, "{after:?}");
            // The impulse is along the face's normal and opposes the tip.
            assert_eq!(imp.impulse[1], 0.0);
            assert!(imp.impulse[0] * before[0] <= 0.0);
            // Linear momentum changes by the impulse; the energy lost is
            // ½ v_tx² / (1/m + d_y²/I) (an impulse at the tip, closed form).
            let dp = sub(imp.after.v, r.v);
            assert!((b.m * dp[0] - imp.impulse[0]).abs() < 1e-14);
            let d = b.arm([theta.cos(), theta.sin()], Tip::Plus);
            let lost = 0.5 * before[0] * before[0] / (1.0 / b.m + d[1] * d[1] / b.inertia);
            let de = b.kinetic(&r) - b.kinetic(&imp.after);
            assert!((de - lost).abs() < 1e-13 && de >= 0.0, "{de} {lost}");
        }
    }

    #[test]
    fn a_tip_arriving_in_the_corner_stops_there_or_leaves_it_without_entering_a_surface() {
        // Every impact at the corner leaves the tip neither in the ground
        // nor in the face, takes energy, and its impulse is one the corner
        // can give.
        let b = body();
        let mut kinds = Vec::new();
        for side in [1.0, -1.0] {
            for mu in [0.3, 0.8, f64::INFINITY] {
                for (theta, v, w) in [
                    (-1.2, [-0.5, 0.0], -1.5),
                    (-2.0, [-0.9, -0.3], 3.0),
                    (-0.6, [-0.1, -1.0], 2.0),
                    (-1.0, [-2.0, 0.2], -4.0),
                    (-0.3, [-1.5, -0.1], 6.0),
                ] {
                    let v = [side * v[0], v[1]];
                    let r = RodState {
                        c: [0.0, 0.4],
                        theta: if side > 0.0 {
                            theta
                        } else {
                            std::f64::consts::PI - theta
                        },
                        v,
                        omega: side * w,
                    };
                    let (_, before) = b.tip_point(&r, Tip::Plus);
                    if side * before[0] >= 0.0 && before[1] >= 0.0 {
                        continue; // not moving into the corner
                    }
                    let imp = b.corner_impact(&r, Tip::Plus, side, mu);
                    let (_, after) = b.tip_point(&imp.after, Tip::Plus);
                    assert!(after[1] >= -1e-14, "into the ground: {after:?}");
                    assert!(side * after[0] >= -1e-14, "into the face: {after:?}");
                    assert!(b.kinetic(&imp.after) <= b.kinetic(&r) + 1e-15);
                    let p = imp.impulse;
                    match imp.kind {
                        ImpactKind::Face => assert!(side * p[0] > 0.0 && p[1] == 0.0),
                        ImpactKind::Stick => assert!(corner_holds(p, side, mu), "{p:?}"),
                        ImpactKind::Slide { .. } => {
                            assert!(
                                p[1] >= 0.0
                                    && (mu.is_infinite()
                                        || p[0].abs() <= mu * p[1] * (1.0 + 1e-12))
                            )
                        }
                    }
                    kinds.push(imp.kind);
                }
            }
        }
        // The cases reach all three impacts.
        assert!(kinds.contains(&ImpactKind::Stick));
        assert!(kinds.contains(&ImpactKind::Face));
        assert!(kinds.iter().any(|k| matches!(k, ImpactKind::Slide { .. })));
    }

    #[test]
    fn the_corner_holds_pushes_away_from_the_face_and_friction_towards_it() {
        for side in [1.0, -1.0] {
            // Straight up, and a push away from the face of any size.
            assert!(corner_holds([0.0, 1.0], side, 0.5));
            assert!(corner_holds([side * 50.0, 1.0], side, 0.5));
            // Towards the face: only within friction.
            assert!(corner_holds([-side * 0.4, 1.0], side, 0.5));
            assert!(!corner_holds([-side * 0.6, 1.0], side, 0.5));
            assert!(corner_holds([-side * 1e9, 1.0], side, f64::INFINITY));
            // Never pulling the tip down.
            assert!(!corner_holds([side, -1e-9], side, f64::INFINITY));
        }
    }
}
