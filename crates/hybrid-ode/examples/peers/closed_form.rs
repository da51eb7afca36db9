//! The two smallest hybrid systems with closed-form answers, shared by the
//! peer benchmark (`examples/peers`) and its test (`tests/peers_closed_form.rs`).
//! `scripts/peers_bench.py` holds the same formulas in NumPy for the peers,
//! and checks that the parameters printed here are its own.
#![allow(dead_code)]

use hybrid_ode::rimless::{RimlessWheel, Stride};
use hybrid_ode::{Crossing, Flow, Guards, HybridSystem, Observer};

/// Gravity (m/s²), both models.
pub const G: f64 = 9.81;
/// The ball's coefficient of restitution.
pub const RESTITUTION: f64 = 0.8;
/// Impacts per trajectory, both models.
pub const IMPACTS: usize = 10;
/// The wheel: spoke length (m), slope (rad), spokes.
pub const WHEEL_L: f64 = 1.0;
pub const WHEEL_GAMMA: f64 = 0.08;
pub const WHEEL_SPOKES: u32 = 12;

/// Drop height of ball trajectory `i` of `n`: spread over [1, 2) m so the
/// impact times differ from one trajectory to the next.
pub fn ball_height(i: usize, n: usize) -> f64 {
    1.0 + i as f64 / n as f64
}

/// Post-impact rate the wheel starts with in trajectory `i` of `n`: spread
/// over [1.2, 2.0) rad/s, all far above the apex rate (0.57 rad/s), around
/// the fixed point ω* = 1.56 rad/s.
pub fn wheel_rate(i: usize, n: usize) -> f64 {
    1.2 + 0.8 * i as f64 / n as f64
}

pub fn wheel() -> RimlessWheel {
    RimlessWheel::with_spokes(WHEEL_SPOKES, WHEEL_L, WHEEL_GAMMA, G)
}

/// A ball dropped from rest at height `h0`: the impact times
/// `t_1 = sqrt(2 h0 / g)`, `t_{k+1} = t_k + 2 e^k v_1 / g` with
/// `v_1 = sqrt(2 g h0)`, and the state just after impact `k`, `[0, e^k v_1]`.
pub fn ball_reference(h0: f64, times: &mut [f64; IMPACTS]) -> [f64; 2] {
    let v1 = (2.0 * G * h0).sqrt();
    let mut t = (2.0 * h0 / G).sqrt();
    let mut v = v1;
    for (k, slot) in times.iter_mut().enumerate() {
        if k > 0 {
            t += 2.0 * v / G;
        }
        *slot = t;
        v *= RESTITUTION;
    }
    [0.0, v]
}

/// The wheel started at `[γ − α, ω0]`: the touchdown times and the state
/// just after the last touchdown, `[γ − α, P^K(ω0)]`. The rates are
/// McGeer's closed-form step map; a stance's duration is
/// `∫ dθ / sqrt(ω² + 2 (g/l)(cos(γ − α) − cos θ))` over `[γ − α, γ + α]`, an
/// elliptic integral with no elementary form, taken by Gauss–Legendre
/// quadrature: its integrand is analytic on the interval (the wheel never
/// comes near the apex rate here), so 40 nodes are exact to rounding.
pub fn wheel_reference(w: &RimlessWheel, omega0: f64, times: &mut [f64; IMPACTS]) -> [f64; 2] {
    let (nodes, weights) = gauss_legendre::<40>();
    let (a, b) = (w.stance_start(), w.touchdown_angle());
    let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
    let k = 2.0 * w.g / w.l;
    let mut t = 0.0;
    let mut omega = omega0;
    for slot in times.iter_mut() {
        let mut stance = 0.0;
        for (x, wt) in nodes.iter().zip(&weights) {
            let theta = mid + half * x;
            stance += wt / (omega * omega + k * (a.cos() - theta.cos())).sqrt();
        }
        t += half * stance;
        *slot = t;
        omega = w
            .step_map_closed_form(omega)
            .expect("the wheel passes the apex from every benchmark rate");
    }
    [a, omega]
}

/// Gauss–Legendre nodes and weights on [−1, 1], by Newton on `P_M` from
/// Chebyshev guesses (Numerical Recipes' `gauleg`): converged to rounding.
pub fn gauss_legendre<const M: usize>() -> ([f64; M], [f64; M]) {
    let (mut x, mut w) = ([0.0; M], [0.0; M]);
    let m = M as f64;
    for i in 0..M.div_ceil(2) {
        let mut z = (std::f64::consts::PI * (i as f64 + 0.75) / (m + 0.5)).cos();
        let mut dp = 0.0;
        for _ in 0..100 {
            let (mut p1, mut p2) = (1.0, 0.0);
            for j in 0..M {
                let p3 = p2;
                p2 = p1;
                let jf = j as f64;
                p1 = ((2.0 * jf + 1.0) * z * p2 - jf * p3) / (jf + 1.0);
            }
            dp = m * (z * p1 - p2) / (z * z - 1.0);
            let dz = p1 / dp;
            z -= dz;
            if dz.abs() < 1e-16 {
                break;
            }
        }
        x[i] = -z;
        x[M - 1 - i] = z;
        w[i] = 2.0 / ((1.0 - z * z) * dp * dp);
        w[M - 1 - i] = w[i];
    }
    (x, w)
}

/// The impact oscillator of `tests/grazing.rs` (Nordmark 1991):
/// `ẍ + 2ζẋ + x = A cos Ωt`, impact at `x = σ` with `ẋ ← −r ẋ`. Its free
/// periodic orbit `x = X cos(Ωt − θ)`, `X = A / √((1 − Ω²)² + (2ζΩ)²)`,
/// `θ = atan2(2ζΩ, 1 − Ω²)`, grazes the stop at `X = σ`.
pub const OSC_ZETA: f64 = 0.05;
pub const OSC_OMEGA: f64 = 0.8;
pub const OSC_SIGMA: f64 = 1.0;
pub const OSC_R: f64 = 0.8;

/// Trajectory `i` of `n` of the oscillator is `ε = 10^(−4 + 3 i/n)` past
/// grazing, `A = A_g (1 + ε)`: from an excursion past the stop of 1e-4 σ
/// (the orbit is beyond the stop for 0.035 s of its 7.85 s period, inside
/// one step of every method here) to 0.1 σ.
pub fn osc_epsilon(i: usize, n: usize) -> f64 {
    10f64.powf(-4.0 + 3.0 * i as f64 / n as f64)
}

#[derive(Clone, Copy, Debug)]
pub struct Oscillator {
    /// Forcing amplitude.
    pub a: f64,
}

fn osc_denominator() -> f64 {
    ((1.0 - OSC_OMEGA * OSC_OMEGA).powi(2) + (2.0 * OSC_ZETA * OSC_OMEGA).powi(2)).sqrt()
}

fn osc_theta() -> f64 {
    (2.0 * OSC_ZETA * OSC_OMEGA).atan2(1.0 - OSC_OMEGA * OSC_OMEGA)
}

impl Oscillator {
    pub fn past_grazing(eps: f64) -> Self {
        Self {
            a: OSC_SIGMA * osc_denominator() * (1.0 + eps),
        }
    }

    /// The start: the free orbit's minimum, `t0 = (θ + π)/Ω`, `[−X, 0]`.
    pub fn start(&self) -> (f64, [f64; 2]) {
        let x = self.a / osc_denominator();
        ((osc_theta() + std::f64::consts::PI) / OSC_OMEGA, [-x, 0.0])
    }

    /// The first impact in closed form: the free orbit reaches the stop at
    /// `Ωt − θ = 2π − acos(σ/X)` with speed `Ω √(X² − σ²)`; the state
    /// after it is `[σ, −r Ω √(X² − σ²)]`.
    pub fn reference(&self) -> (f64, [f64; 2]) {
        let x = self.a / osc_denominator();
        let t = (osc_theta() + 2.0 * std::f64::consts::PI - (OSC_SIGMA / x).acos()) / OSC_OMEGA;
        let v = OSC_OMEGA * (x * x - OSC_SIGMA * OSC_SIGMA).sqrt();
        (t, [OSC_SIGMA, -OSC_R * v])
    }
}

impl HybridSystem<2> for Oscillator {
    type Aux = ();
    type Transition = Flow;

    #[inline]
    fn rhs(&self, t: f64, y: &[f64; 2], dy: &mut [f64; 2]) {
        dy[0] = y[1];
        dy[1] = self.a * (OSC_OMEGA * t).cos() - 2.0 * OSC_ZETA * y[1] - y[0];
    }

    #[inline]
    fn guards(&self, _t: f64, y: &[f64; 2], out: &mut Guards) {
        out.clear();
        out.push(OSC_SIGMA - y[0], Crossing::Falling);
    }

    fn reset(&mut self, _t: f64, y: &mut [f64; 2], _index: usize) -> Flow {
        y[1] *= -OSC_R;
        Flow::Continue
    }
}

/// The bouncing ball, `[height, velocity]`: `ÿ = −g`, impact where the
/// height falls through 0, `v ← −e v`.
#[derive(Clone, Copy, Debug)]
pub struct Ball;

impl HybridSystem<2> for Ball {
    type Aux = ();
    type Transition = Flow;

    #[inline]
    fn rhs(&self, _t: f64, y: &[f64; 2], dy: &mut [f64; 2]) {
        dy[0] = y[1];
        dy[1] = -G;
    }

    #[inline]
    fn guards(&self, _t: f64, y: &[f64; 2], out: &mut Guards) {
        out.clear();
        out.push(y[0], Crossing::Falling);
    }

    fn reset(&mut self, _t: f64, y: &mut [f64; 2], _index: usize) -> Flow {
        // The engine hands over the event state on the guard's crossed
        // side or on it (a hair below the floor, or exactly 0). A step that
        // starts there and flies a whole bounce ends below the floor again,
        // which is neither a sign change from the uncrossed side nor a dip
        // (both ends above): the bounce would be missed. So the flight
        // starts strictly above the floor, at the event state's mirror image
        // or the smallest positive double, and the next landing is a sign
        // change. Neither moves the state by more than rounding.
        y[0] = y[0].abs().max(f64::MIN_POSITIVE);
        y[1] *= -RESTITUTION;
        Flow::Continue
    }
}

/// Records the impact times and stops after `stop_after` of them (at most
/// [`IMPACTS`]).
#[derive(Clone, Copy, Debug)]
pub struct Impacts {
    pub times: [f64; IMPACTS],
    pub count: usize,
    pub stop_after: usize,
}

impl Default for Impacts {
    fn default() -> Self {
        Self::stopping_after(IMPACTS)
    }
}

impl Impacts {
    pub fn stopping_after(stop_after: usize) -> Self {
        Self {
            times: [f64::NAN; IMPACTS],
            count: 0,
            stop_after: stop_after.min(IMPACTS),
        }
    }

    fn record(&mut self, t: f64) -> Flow {
        if self.count < IMPACTS {
            self.times[self.count] = t;
        }
        self.count += 1;
        if self.count >= self.stop_after {
            Flow::Stop
        } else {
            Flow::Continue
        }
    }
}

impl Observer<2, Ball> for Impacts {
    fn on_transition(&mut self, _: &Ball, t: f64, _: &[f64; 2], _: &Flow) -> Flow {
        self.record(t)
    }

    // Only the event times are read: the cheap interpolant is enough.
    fn reads_interior(&self, _: &Ball, _t0: f64, _t1: f64) -> bool {
        false
    }
}

impl Observer<2, Oscillator> for Impacts {
    fn on_transition(&mut self, _: &Oscillator, t: f64, _: &[f64; 2], _: &Flow) -> Flow {
        self.record(t)
    }

    fn reads_interior(&self, _: &Oscillator, _t0: f64, _t1: f64) -> bool {
        false
    }
}

impl Observer<2, RimlessWheel> for Impacts {
    fn on_transition(&mut self, _: &RimlessWheel, t: f64, _: &[f64; 2], s: &Stride) -> Flow {
        match s {
            Stride::Touchdown { .. } => self.record(t),
            Stride::RolledBack => Flow::Stop,
        }
    }

    fn reads_interior(&self, _: &RimlessWheel, _t0: f64, _t1: f64) -> bool {
        false
    }
}
