//! A grazing bifurcation known in closed form: the harmonically forced,
//! damped linear oscillator with a rigid stop (the impact oscillator of
//! Nordmark 1991 and di Bernardo et al. §4.2),
//!
//! `ẍ + 2ζẋ + x = A cos Ωt`, impact at `x = σ` with `ẋ ↦ −r ẋ`.
//!
//! Without impacts its periodic orbit is `x = X cos(Ωt − θ)` with amplitude
//! `X = A / √((1 − Ω²)² + (2ζΩ)²)`: it grazes the stop where `X = σ`, at
//! `A_g = σ √((1 − Ω²)² + (2ζΩ)²)`, at the time `θ/Ω` of its maximum. Past
//! grazing, `A = A_g (1 + ε)`, the orbit started on the free periodic orbit
//! reaches the stop with the velocity of a parabola's chord,
//! `v = √(2 |ẍ| (X − σ)) = Ω σ √(2 ε (1 + ε))`: the square-root singularity.

use hybrid_ode::limit::{fd_jacobian, newton};
use hybrid_ode::nonsmooth::{GuardMinima, Kind, classify, locate_change};
use hybrid_ode::{Crossing, EndReason, EngineOptions, Flow, Guards, HybridSystem, Method, run};
use std::f64::consts::PI;

const ZETA: f64 = 0.05;
const OMEGA: f64 = 0.8;
const SIGMA: f64 = 1.0;
const R: f64 = 0.8;

struct Impact {
    a: f64,
}

impl HybridSystem<2> for Impact {
    type Aux = ();
    type Transition = Flow;

    fn rhs(&self, t: f64, y: &[f64; 2], dy: &mut [f64; 2]) {
        dy[0] = y[1];
        dy[1] = self.a * (OMEGA * t).cos() - 2.0 * ZETA * y[1] - y[0];
    }

    fn guards(&self, _t: f64, y: &[f64; 2], out: &mut Guards) {
        out.clear();
        out.push(SIGMA - y[0], Crossing::Falling);
    }

    fn reset(&mut self, _t: f64, y: &mut [f64; 2], _index: usize) -> Flow {
        y[1] *= -R;
        Flow::Continue
    }
}

fn denominator() -> f64 {
    ((1.0 - OMEGA * OMEGA).powi(2) + (2.0 * ZETA * OMEGA).powi(2)).sqrt()
}

/// The grazing forcing amplitude, in closed form.
fn a_graze() -> f64 {
    SIGMA * denominator()
}

/// Phase lag θ of the free periodic orbit.
fn theta() -> f64 {
    (2.0 * ZETA * OMEGA).atan2(1.0 - OMEGA * OMEGA)
}

/// The free periodic orbit's state at t = 0 (the stroboscopic section).
fn free_state(a: f64) -> [f64; 2] {
    let x = a / denominator();
    [x * theta().cos(), x * OMEGA * theta().sin()]
}

fn period() -> f64 {
    2.0 * PI / OMEGA
}

fn opts() -> EngineOptions {
    EngineOptions {
        method: Method::Dop853,
        rtol: 1e-12,
        atol: 1e-13,
        h_max: 0.0,
        ..EngineOptions::default()
    }
}

/// One forcing period from `y0` at t = 0 (the stroboscopic map), with its
/// events and guard minima.
fn period_map(a: f64, y0: &[f64; 2]) -> Option<([f64; 2], GuardMinima)> {
    let mut y = *y0;
    let mut obs = GuardMinima::default();
    let end = run(&mut Impact { a }, &mut obs, 0.0, &mut y, period(), &opts());
    (end.reason == EndReason::TimeUp).then_some((y, obs))
}

/// The number of impacts per period of the period-1 orbit at `a` (Newton on
/// the stroboscopic map from the free orbit), `usize::MAX` where Newton finds
/// none: the orbit's signature, whose change the bisection locates.
fn signature(a: f64) -> (usize, Option<GuardMinima>) {
    let map = |z: &[f64]| period_map(a, &[z[0], z[1]]).map(|(y, _)| y.to_vec());
    // The free map is linear: small difference steps, and a tolerance above
    // a period's integration error (≈ 1e-12), so that an orbit that passes
    // within 1e-9 of the stop is found without perturbations that hit it.
    let fp = newton(&free_state(a), &[1.0, 1.0], 1e-10, 20, |z| {
        let p = map(z)?;
        Some((p, fd_jacobian(z, &[1e-10, 1e-10], map)?))
    });
    match fp {
        Ok(fp) => {
            let (_, obs) = period_map(a, &[fp.z[0], fp.z[1]]).expect("a period runs");
            (obs.events.len(), Some(obs))
        }
        Err(_) => (usize::MAX, None),
    }
}

/// The located grazing is the closed form's, and named a grazing at the
/// orbit's maximum: bisection on A between a non-impacting orbit (A_g/2) and
/// an impacting one (2 A_g), on the period-1 orbit's number of impacts.
#[test]
fn the_located_grazing_of_the_impact_oscillator_is_the_closed_forms() {
    let ag = a_graze();
    let change = locate_change(0.5 * ag, 2.0 * ag, 1e-13, |a| signature(a).0)
        .expect("the signatures at A_g/2 and 2 A_g differ");
    assert_eq!(change.old_signature, 0);
    assert_ne!(change.new_signature, 0);
    // The engine fires a dip deeper than a step's error estimate
    // (rtol 1e-12): the change is found within a few 1e-12 of A_g.
    let rel = (change.old - ag).abs() / ag;
    assert!(
        rel < 1e-9,
        "located A = {} vs closed form A_g = {ag} (relative {rel:.2e})",
        change.old
    );
    let old = signature(change.old).1.expect("an orbit on the old side");
    let new = period_map(change.new, &free_state(change.new)).unwrap().1;
    match classify(&old, &new, 1e-8, 1e-9) {
        Kind::Grazing { guard, t, value } => {
            assert_eq!(guard, 0);
            assert!(value.abs() < 1e-8, "distance to the stop {value}");
            // At the orbit's maximum, Ωt = θ.
            assert!((t - theta() / OMEGA).abs() < 1e-5, "t = {t}");
        }
        other => panic!("named {other:?}, not a grazing"),
    }
    // Tangential: the new side's impact has almost no velocity.
    let v = -new.events[0].rate;
    assert!((0.0..1e-4).contains(&v), "impact velocity {v}");
}

/// Least-squares slope of `ln y` on `ln x`.
fn log_slope(x: &[f64], y: &[f64]) -> f64 {
    let lx: Vec<f64> = x.iter().map(|v| v.ln()).collect();
    let ly: Vec<f64> = y.iter().map(|v| v.ln()).collect();
    let n = lx.len() as f64;
    let (mx, my) = (lx.iter().sum::<f64>() / n, ly.iter().sum::<f64>() / n);
    let sxy: f64 = lx.iter().zip(&ly).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = lx.iter().map(|a| (a - mx).powi(2)).sum();
    sxy / sxx
}

/// Past grazing, the impact velocity of the orbit from the free periodic
/// orbit is `Ω σ √(2ε(1 + ε))`, and so grows as `(A − A_g)^½`; the
/// stroboscopic map's jump off the free orbit (Nordmark's discontinuity map)
/// grows with the same exponent.
#[test]
fn past_grazing_the_impact_velocity_and_the_maps_jump_follow_the_square_root_law() {
    let ag = a_graze();
    let eps: Vec<f64> = (0..11).map(|k| 1e-8 * 10f64.powf(0.5 * k as f64)).collect();
    let mut v = Vec::new();
    let mut jump = Vec::new();
    for &e in &eps {
        let a = ag * (1.0 + e);
        let z = free_state(a);
        let (p, obs) = period_map(a, &z).expect("a period runs");
        assert_eq!(obs.events.len(), 1, "ε = {e}: one impact per period");
        let vi = -obs.events[0].rate;
        let closed = OMEGA * SIGMA * (2.0 * e * (1.0 + e)).sqrt();
        assert!(
            (vi - closed).abs() < 2e-3 * closed + 1e-9,
            "ε = {e}: impact velocity {vi} vs closed form {closed}"
        );
        v.push(vi);
        jump.push(((p[0] - z[0]).powi(2) + (p[1] - z[1]).powi(2)).sqrt());
    }
    let (sv, sj) = (log_slope(&eps, &v), log_slope(&eps, &jump));
    assert!((sv - 0.5).abs() < 0.01, "impact velocity exponent {sv}");
    assert!((sj - 0.5).abs() < 0.01, "map jump exponent {sj}");
}
