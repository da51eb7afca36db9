//! The hexagon of six massless Kelvin–Voigt strings (docs/model.md §3, §9).
//!
//! String `j` joins the spokes [`STRINGS`] pairs, `j` and `j+1` of [`SPOKES`] (a+–b+, b+–c+,
//! c+–a−, a−–b−, b−–c−, c−–a+), between the connection points `c ± r e`.
//! Tension `T = k (ℓ − ℓ₀) + c ℓ̇` (damping `along`), or spring along the
//! string plus the isotropic damper `−c (Ṗ − Q̇)` (damping `relative`); with
//! `slack` a string cannot push.

use crate::options::{Damping, Options};
use crate::params::Physical;
use crate::plant::geometry::{
    RodFrame, SPOKES, STRINGS, Vec2, add, cross, dot, next_spoke, scale, sub,
};

/// The number of strings.
pub const STRING_COUNT: usize = 6;

/// String constants of one RTW.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StringSet {
    /// Stiffness k.
    pub k: f64,
    /// Damping c.
    pub c: f64,
    /// Connection radius r (centre to connection point).
    pub r: f64,
    /// Natural length ℓ₀ = s r.
    pub rest_length: f64,
    /// A slack string cannot push.
    pub slack: bool,
    /// How the damper acts.
    pub damping: Damping,
}

impl StringSet {
    /// The strings of the RTW of `phys` with the string model of `options`
    /// (rest length `s r`, slack, damping): the plant's own, and what
    /// [`crate::modal`] linearizes.
    pub fn new(phys: &Physical, options: &Options) -> Self {
        Self {
            k: phys.k,
            c: phys.c,
            r: phys.r,
            rest_length: options.strings.rest_length_ratio * phys.r,
            slack: options.strings.slack,
            damping: options.strings.damping,
        }
    }
}

/// Net string force and torque (about its centre) on each rod, and the power
/// the strings dissipate.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StringLoads {
    /// Net string force on each rod.
    pub force: [Vec2; 3],
    /// Net string torque on each rod, about its centre.
    pub torque: [f64; 3],
    /// Rate of energy dissipation by the dampers (≥ 0 without slack).
    pub dissipation: f64,
}

impl StringSet {
    /// The force on end `p` of a string from `q` to `p`, the power
    /// dissipated, and the two values whose signs pick the branch of a slack
    /// string's law: its stretch (its spring pulls only when stretched) and
    /// the pull of spring and damper along it (it cannot push). The force
    /// has a kink where either changes sign.
    #[inline]
    fn string_law(&self, p: Vec2, vp: Vec2, q: Vec2, vq: Vec2) -> (Vec2, f64, [f64; 2]) {
        let d = sub(p, q);
        let dv = sub(vp, vq);
        let len = dot(d, d).sqrt();
        // A string of zero length has no direction; its force −k d vanishes there.
        let u = if len > 0.0 {
            scale(1.0 / len, d)
        } else {
            [0.0, 0.0]
        };
        let stretch = len - self.rest_length;
        let len_rate = dot(u, dv);
        let spring = if self.slack && stretch < 0.0 {
            0.0
        } else {
            self.k * stretch
        };
        let (force, pull) = match self.damping {
            Damping::Along => {
                let pull = spring + self.c * len_rate;
                let t = if self.slack { pull.max(0.0) } else { pull };
                (scale(-t, u), pull)
            }
            Damping::Relative => {
                let f = add(scale(-spring, u), scale(-self.c, dv));
                let pull = -dot(f, u);
                // Slack: the string can pull only.
                if self.slack && pull < 0.0 {
                    ([0.0, 0.0], pull)
                } else {
                    (f, pull)
                }
            }
        };
        // Power absorbed by the string minus the rate of its stored energy.
        let absorbed = -dot(force, dv);
        (force, absorbed - spring * len_rate, [stretch, pull])
    }

    /// Where the strings' force law has kinks: for each string `j`, its
    /// stretch at `2j` and its pull at `2j + 1` (see
    /// [`string_law`](Self::string_law)); `None` for strings that cannot go
    /// slack, whose law is smooth.
    pub fn kinks(&self, rods: &[RodFrame; 3]) -> Option<[f64; 2 * STRING_COUNT]> {
        if !self.slack {
            return None;
        }
        let mut out = [0.0; 2 * STRING_COUNT];
        for j in 0..STRING_COUNT {
            let (ip, iq) = Self::rods_of(j);
            [out[2 * j], out[2 * j + 1]] = self.kinks_of(j, &rods[ip], &rods[iq]);
        }
        Some(out)
    }

    /// The rods string `j` joins: the rods of spokes `j` and `j + 1`.
    #[inline]
    pub fn rods_of(j: usize) -> (usize, usize) {
        (SPOKES[j].0, SPOKES[next_spoke(j)].0)
    }

    /// String `j`'s two kinks ([`kinks`](Self::kinks)) from the frames of
    /// the rods it joins ([`rods_of`](Self::rods_of)), `p` and `q`.
    #[inline]
    pub fn kinks_of(&self, j: usize, p: &RodFrame, q: &RodFrame) -> [f64; 2] {
        let n = next_spoke(j);
        let (p, vp) = p.point(SPOKES[j].1.sign() * self.r);
        let (q, vq) = q.point(SPOKES[n].1.sign() * self.r);
        self.string_law(p, vp, q, vq).2
    }

    /// The sides of the strings' kinks ([`kinks`](Self::kinks)), bit `i`
    /// set where kink `i` is below zero; 0 for strings that cannot go slack.
    pub fn kink_sides(&self, rods: &[RodFrame; 3]) -> u32 {
        self.kinks(rods).map_or(0, |k| {
            k.iter()
                .enumerate()
                .fold(0, |bits, (i, v)| bits | (u32::from(*v < 0.0) << i))
        })
    }

    /// Forces and torques of the six strings on the three rods.
    #[inline]
    pub fn loads(&self, rods: &[RodFrame; 3]) -> StringLoads {
        let mut out = StringLoads::default();
        let mut ends = [([0.0; 2], [0.0; 2], [0.0; 2]); 6];
        for (j, &(i, tip)) in SPOKES.iter().enumerate() {
            let a = tip.sign() * self.r;
            let (p, v) = rods[i].point(a);
            ends[j] = (p, v, sub(p, rods[i].c));
        }
        // The pairs by index arithmetic, not read from `STRINGS`: from the
        // table the indices are loads and every `ends[..]` a bounds check,
        // and a scan spent about 4 % more instructions.
        for j in 0..6 {
            let n = next_spoke(j);
            let (p, vp, arm_p) = ends[j];
            let (q, vq, arm_q) = ends[n];
            let (f, diss, _) = self.string_law(p, vp, q, vq);
            let (ip, iq) = Self::rods_of(j);
            out.force[ip] = add(out.force[ip], f);
            out.force[iq] = sub(out.force[iq], f);
            out.torque[ip] += cross(arm_p, f);
            out.torque[iq] -= cross(arm_q, f);
            out.dissipation += diss;
        }
        out
    }

    /// Elastic energy stored in the strings.
    pub fn potential(&self, rods: &[RodFrame; 3]) -> f64 {
        let mut ends = [[0.0; 2]; 6];
        for (j, &(i, tip)) in SPOKES.iter().enumerate() {
            ends[j] = rods[i].point(tip.sign() * self.r).0;
        }
        STRINGS
            .iter()
            .map(|&(j, n)| {
                let d = sub(ends[j], ends[n]);
                let stretch = dot(d, d).sqrt() - self.rest_length;
                if self.slack && stretch < 0.0 {
                    0.0
                } else {
                    0.5 * self.k * stretch * stretch
                }
            })
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plant::geometry::RodState;

    fn frames(c: [Vec2; 3], th: [f64; 3], v: [Vec2; 3], w: [f64; 3]) -> [RodFrame; 3] {
        std::array::from_fn(|i| {
            RodFrame::new(&RodState {
                c: c[i],
                theta: th[i],
                v: v[i],
                omega: w[i],
            })
        })
    }

    /// Generalized forces of the approximate model (common fixed centre),
    /// S5–S6 with the sign of docs/model.md §3 (M q̈ = −F).
    fn s5_s6(k: f64, c: f64, r: f64, th: [f64; 3], w: [f64; 3]) -> [f64; 3] {
        let [a, b, cc] = th;
        let [da, db, dc] = w;
        let r2 = r * r;
        let fk = [
            2.0 * k * r2 * ((a - b).sin() - (a - cc).sin()),
            2.0 * k * r2 * (-(a - b).sin() + (b - cc).sin()),
            2.0 * k * r2 * ((a - cc).sin() - (b - cc).sin()),
        ];
        let fc = [
            -c * r2
                * (-2.0 * da + db + dc + (-da + db) * (a - b).cos() + (da - dc) * (a - cc).cos()),
            -c * r2
                * (da - 2.0 * db + dc + (da - db) * (a - b).cos() + (-db + dc) * (b - cc).cos()),
            c * r2
                * (-da - db + 2.0 * dc + (da - dc) * (a - cc).cos() + (-db + dc) * (b - cc).cos()),
        ];
        std::array::from_fn(|i| -(fk[i] + fc[i]))
    }

    #[test]
    fn torques_match_s5_s6_on_the_approximate_model() {
        // Independent reference: the supplementary's closed forms S5 and S6.
        let set = StringSet {
            k: 500.0,
            c: 1.0,
            r: 0.3,
            rest_length: 0.0,
            slack: false,
            damping: Damping::Along,
        };
        let mut seed = 12345u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        for _ in 0..200 {
            let base = rnd() * 3.0;
            let th = [
                base + 0.4 * rnd(),
                base + std::f64::consts::FRAC_PI_3 + 0.4 * rnd(),
                base + 2.0 * std::f64::consts::FRAC_PI_3 + 0.4 * rnd(),
            ];
            let w = [3.0 * rnd(), 3.0 * rnd(), 3.0 * rnd()];
            let rods = frames([[0.0; 2]; 3], th, [[0.0; 2]; 3], w);
            let got = set.loads(&rods).torque;
            let want = s5_s6(set.k, set.c, set.r, th, w);
            for i in 0..3 {
                assert!(
                    (got[i] - want[i]).abs() < 1e-9 * (1.0 + want[i].abs()),
                    "{got:?} vs {want:?}"
                );
            }
        }
    }

    #[test]
    fn forces_are_the_gradient_of_the_potential_and_balance() {
        for (s, slack) in [(0.0, false), (0.85, false), (0.85, true)] {
            let set = StringSet {
                k: 300.0,
                c: 0.0,
                r: 0.3,
                rest_length: s * 0.3,
                slack,
                damping: Damping::Along,
            };
            let c = [[0.01, 0.02], [-0.03, 0.015], [0.02, -0.01]];
            let th = [0.1, 1.2, 2.0];
            let z = [[0.0; 2]; 3];
            let rods = frames(c, th, z, [0.0; 3]);
            let l = set.loads(&rods);
            let h = 1e-6;
            for i in 0..3 {
                for dof in 0..3 {
                    let shift = |d: f64| {
                        let mut c2 = c;
                        let mut t2 = th;
                        if dof < 2 {
                            c2[i][dof] += d;
                        } else {
                            t2[i] += d;
                        }
                        set.potential(&frames(c2, t2, z, [0.0; 3]))
                    };
                    let grad = (shift(h) - shift(-h)) / (2.0 * h);
                    let generalized = if dof < 2 {
                        l.force[i][dof]
                    } else {
                        l.torque[i]
                    };
                    assert!(
                        (generalized + grad).abs() < 1e-5,
                        "rod {i} dof {dof}: {generalized} vs {}",
                        -grad
                    );
                }
            }
            // Internal forces: net force and net moment about the origin vanish.
            let fx: f64 = l.force.iter().map(|f| f[0]).sum();
            let fy: f64 = l.force.iter().map(|f| f[1]).sum();
            let m: f64 = (0..3).map(|i| l.torque[i] + cross(c[i], l.force[i])).sum();
            assert!(fx.abs() < 1e-9 && fy.abs() < 1e-9 && m.abs() < 1e-9);
        }
    }

    #[test]
    fn dampers_dissipate_what_they_absorb() {
        for damping in [Damping::Along, Damping::Relative] {
            let set = StringSet {
                k: 200.0,
                c: 2.0,
                r: 0.3,
                rest_length: 0.2,
                slack: false,
                damping,
            };
            let rods = frames(
                [[0.0, 0.0], [0.02, 0.01], [-0.01, 0.03]],
                [0.0, 1.1, 2.2],
                [[0.1, -0.3], [0.4, 0.2], [-0.2, 0.1]],
                [1.0, -2.0, 0.5],
            );
            let l = set.loads(&rods);
            assert!(l.dissipation > 0.0);
            // Power of all string forces on the rods = −(dV/dt + dissipation).
            let power: f64 = (0..3)
                .map(|i| dot(l.force[i], rods[i].v) + l.torque[i] * rods[i].omega)
                .sum();
            let h = 1e-7;
            let moved: [RodFrame; 3] = std::array::from_fn(|i| {
                RodFrame::new(&RodState {
                    c: add(rods[i].c, scale(h, rods[i].v)),
                    theta: rods[i].e[1].atan2(rods[i].e[0]) + h * rods[i].omega,
                    v: rods[i].v,
                    omega: rods[i].omega,
                })
            });
            let dv = (set.potential(&moved) - set.potential(&rods)) / h;
            assert!((power + dv + l.dissipation).abs() < 1e-4, "{damping:?}");
        }
    }
}
