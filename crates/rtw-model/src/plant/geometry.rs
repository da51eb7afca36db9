//! Rods, tips and connection points in the slope frame (docs/model.md §2–§3).
//!
//! `x` runs down the slope, `y` along its normal; the ground is `y = 0`.
//! A rod has centre `c`, angle `θ` and unit vector `e = (cos θ, sin θ)`; its
//! tips (feet) are `c ± (L/2) e` and its connection points `c ± r e`.

use std::f64::consts::PI;

/// A plain 2-vector (the hot path wants no more than this).
pub type Vec2 = [f64; 2];

/// `a + b`.
#[inline]
pub fn add(a: Vec2, b: Vec2) -> Vec2 {
    [a[0] + b[0], a[1] + b[1]]
}
/// `a − b`.
#[inline]
pub fn sub(a: Vec2, b: Vec2) -> Vec2 {
    [a[0] - b[0], a[1] - b[1]]
}
/// `s a`.
#[inline]
pub fn scale(s: f64, a: Vec2) -> Vec2 {
    [s * a[0], s * a[1]]
}
/// `a · b`.
#[inline]
pub fn dot(a: Vec2, b: Vec2) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}
/// z-component of the planar cross product `a × b`.
#[inline]
pub fn cross(a: Vec2, b: Vec2) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}
/// `a` turned by +90°: the velocity of a point at `a` on a body spinning at unit rate.
#[inline]
pub fn perp(a: Vec2) -> Vec2 {
    [-a[1], a[0]]
}

/// One end of a rod: `+` at `c + (L/2) e`, `−` at `c − (L/2) e`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Tip {
    /// The tip at `c + (L/2) e`.
    Plus,
    /// The tip at `c − (L/2) e`.
    Minus,
}

impl Tip {
    /// ±1.
    #[inline]
    pub(crate) fn sign(self) -> f64 {
        match self {
            Tip::Plus => 1.0,
            Tip::Minus => -1.0,
        }
    }

    /// 0 for Plus, 1 for Minus: the tip's place in per-tip arrays.
    #[inline]
    pub(crate) fn index(self) -> usize {
        match self {
            Tip::Plus => 0,
            Tip::Minus => 1,
        }
    }

    /// The rod's other tip.
    #[inline]
    pub(crate) fn other(self) -> Tip {
        match self {
            Tip::Plus => Tip::Minus,
            Tip::Minus => Tip::Plus,
        }
    }
}

/// Position and velocity of one rod in full coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RodState {
    /// Centre.
    pub c: Vec2,
    /// Angle θ.
    pub theta: f64,
    /// Centre velocity.
    pub v: Vec2,
    /// Angular velocity ω.
    pub omega: f64,
}

/// A rod's kinematic quantities that every force evaluation needs once.
#[derive(Clone, Copy, Debug, Default)]
pub struct RodFrame {
    /// Centre.
    pub c: Vec2,
    /// Centre velocity.
    pub v: Vec2,
    /// Angular velocity ω.
    pub omega: f64,
    /// Unit vector along the rod.
    pub e: Vec2,
}

impl RodFrame {
    /// The frame of `s` (one `sin_cos`).
    #[inline]
    pub fn new(s: &RodState) -> Self {
        let (sin, cos) = s.theta.sin_cos();
        Self {
            c: s.c,
            v: s.v,
            omega: s.omega,
            e: [cos, sin],
        }
    }

    /// The rod's full coordinates, given the angle `theta` that `e` was made of.
    #[inline]
    pub fn state(&self, theta: f64) -> RodState {
        RodState {
            c: self.c,
            theta,
            v: self.v,
            omega: self.omega,
        }
    }

    /// The point at signed distance `a` from the centre along the rod, and its velocity.
    #[inline]
    pub fn point(&self, a: f64) -> (Vec2, Vec2) {
        let arm = scale(a, self.e);
        (add(self.c, arm), add(self.v, scale(self.omega, perp(arm))))
    }
}

/// The rest shape (docs/model.md §3): a regular six-spoked star, all centres at
/// `hub`, with rod angles `θ_a`, `θ_a + π/3`, `θ_a + 2π/3`, so that the spokes
/// a+, b+, c+, a−, b−, c− go round in that angular order.
pub fn rest_star(hub: Vec2, theta_a: f64) -> [RodState; 3] {
    std::array::from_fn(|i| RodState {
        c: hub,
        theta: theta_a + i as f64 * PI / 3.0,
        v: [0.0, 0.0],
        omega: 0.0,
    })
}

/// The spokes in angular order: (rod index, tip) of a+, b+, c+, a−, b−, c−.
pub const SPOKES: [(usize, Tip); 6] = [
    (0, Tip::Plus),
    (1, Tip::Plus),
    (2, Tip::Plus),
    (0, Tip::Minus),
    (1, Tip::Minus),
    (2, Tip::Minus),
];

/// The six strings as pairs of spokes (indices into [`SPOKES`]): string `j`
/// joins the connection points of spoke `j` and spoke `j + 1`, round the
/// star (a+–b+, b+–c+, c+–a−, a−–b−, b−–c−, c−–a+).
pub const STRINGS: [(usize, usize); 6] = {
    let mut strings = [(0, 0); 6];
    let mut j = 0;
    while j < 6 {
        strings[j] = (j, next_spoke(j));
        j += 1;
    }
    strings
};

/// The spoke after spoke `j` round the star, which string `j` joins it to.
#[inline]
pub(crate) const fn next_spoke(j: usize) -> usize {
    (j + 1) % 6
}

/// The tip and the connection point of every spoke, in [`SPOKES`] order, of
/// rods with centres `c` and angles `theta` (`rods[i] = (c, theta)`): tip
/// `c ± (L/2) e`, connection point `c ± r e`. What a drawing of the star
/// needs; the strings join the connection points as [`STRINGS`] pairs them.
pub fn spoke_points(rods: &[(Vec2, f64); 3], length: f64, r: f64) -> ([Vec2; 6], [Vec2; 6]) {
    let frames = rods.map(|(c, theta)| {
        RodFrame::new(&RodState {
            c,
            theta,
            v: [0.0, 0.0],
            omega: 0.0,
        })
    });
    let at = |a: f64| -> [Vec2; 6] {
        std::array::from_fn(|j| {
            let (i, tip) = SPOKES[j];
            frames[i].point(tip.sign() * a).0
        })
    };
    (at(0.5 * length), at(r))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rest_star_spokes_go_round_at_sixty_degrees() {
        let rods = rest_star([0.0, 0.0], 0.3);
        for (j, &(i, tip)) in SPOKES.iter().enumerate() {
            let f = RodFrame::new(&rods[i]);
            let (p, _) = f.point(tip.sign());
            let ang = p[1].atan2(p[0]);
            let want = 0.3 + j as f64 * PI / 3.0;
            let d = (ang - want).rem_euclid(2.0 * PI);
            assert!(
                d < 1e-12 || 2.0 * PI - d < 1e-12,
                "spoke {j}: {ang} vs {want}"
            );
        }
    }

    #[test]
    fn point_velocity_is_rigid_body() {
        let s = RodState {
            c: [1.0, 2.0],
            theta: 0.7,
            v: [0.3, -0.2],
            omega: 1.9,
        };
        let f = RodFrame::new(&s);
        // Finite difference of the point position along the motion.
        let h = 1e-6;
        let s2 = RodState {
            c: add(s.c, scale(h, s.v)),
            theta: s.theta + h * s.omega,
            ..s
        };
        let (p0, v0) = f.point(0.25);
        let (p1, _) = RodFrame::new(&s2).point(0.25);
        for k in 0..2 {
            assert!(((p1[k] - p0[k]) / h - v0[k]).abs() < 1e-5);
        }
    }
}
