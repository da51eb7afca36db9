//! McGeer's rimless wheel over a step down, on the hybrid engine with the
//! RTW's terrain ([`TerrainOptions`]), against the closed form derived in
//! docs/robustness-step-down.md ("The rimless wheel on a step down").
//!
//! The wheel: a point-mass hub on spokes of length `l`, `2α` apart, on a
//! slope `γ`. State `[θ, θ̇]`, `θ` the stance spoke's angle from the vertical
//! (positive with the hub downhill of its foot), stance `θ̈ = (g/l) sin θ`.
//! Unlike the flat-slope fixture (`hybrid_ode::rimless`), the touchdown is
//! not an angle: the leading spoke's tip is followed in slope coordinates and
//! lands where its height reaches the ground under it, so the engine finds
//! the impact on the lower segment from the terrain alone. A second guard
//! watches the stance foot's normal force, `m (g cos θ − l θ̇²)`: at zero the
//! wheel leaves the ground and no longer rolls on.

use crate::options::TerrainOptions;
use hybrid_ode::{
    Crossing, EndReason, EndsRun, EngineOptions, Flow, Guards, HybridSystem, Method, Observer, run,
};
use std::f64::consts::PI;

const G: f64 = 9.81;

/// The wheel on a terrain, with its stance foot's place (slope coordinates).
#[derive(Clone, Copy, Debug)]
struct Wheel {
    l: f64,
    alpha: f64,
    gamma: f64,
    terrain: TerrainOptions,
    foot: [f64; 2],
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Event {
    /// The leading spoke landed: the state just after the impact.
    Touchdown { theta: f64, rate: f64 },
    /// The stance foot's normal force reached zero.
    Flies,
    /// The wheel rolled back over its stance foot.
    RolledBack,
    /// The leading tip met the riser.
    Riser,
}

impl EndsRun for Event {
    fn ends_run(&self) -> bool {
        !matches!(self, Event::Touchdown { .. })
    }
}

impl Wheel {
    /// The leading spoke's tip at stance angle `theta`.
    fn leading_tip(&self, theta: f64) -> [f64; 2] {
        let psi = theta - self.gamma; // from the slope normal
        let hub = [
            self.foot[0] + self.l * psi.sin(),
            self.foot[1] + self.l * psi.cos(),
        ];
        let lead = psi - 2.0 * self.alpha;
        [hub[0] - self.l * lead.sin(), hub[1] - self.l * lead.cos()]
    }
}

impl HybridSystem<2> for Wheel {
    type Aux = ();
    type Transition = Event;

    fn rhs(&self, _t: f64, y: &[f64; 2], dy: &mut [f64; 2]) {
        dy[0] = y[1];
        dy[1] = (G / self.l) * y[0].sin();
    }

    fn guards(&self, _t: f64, y: &[f64; 2], out: &mut Guards) {
        out.clear();
        let tip = self.leading_tip(y[0]);
        out.push(tip[1] - self.terrain.ground(tip[0]), Crossing::Falling);
        out.push(G * y[0].cos() - self.l * y[1] * y[1], Crossing::Falling);
        // Back over the stance foot: the hub upstream of the normal by α.
        out.push(y[0] - self.gamma + self.alpha, Crossing::Falling);
    }

    fn reset(&mut self, _t: f64, y: &mut [f64; 2], index: usize) -> Event {
        match index {
            0 => {
                let tip = self.leading_tip(y[0]);
                let ground = self.terrain.ground(tip[0]);
                if tip[1] - ground < -1e-6 * self.l {
                    return Event::Riser;
                }
                self.foot = [tip[0], ground];
                y[0] -= 2.0 * self.alpha;
                y[1] *= (2.0 * self.alpha).cos();
                Event::Touchdown {
                    theta: y[0],
                    rate: y[1],
                }
            }
            1 => Event::Flies,
            _ => Event::RolledBack,
        }
    }
}

/// Records the touchdowns; stops after `steps` of them.
struct Steps {
    steps: usize,
    seen: Vec<(f64, f64)>,
    end: Option<Event>,
}

impl Observer<2, Wheel> for Steps {
    fn on_transition(&mut self, _: &Wheel, _t: f64, _: &[f64; 2], e: &Event) -> Flow {
        match *e {
            Event::Touchdown { theta, rate } => {
                self.seen.push((theta, rate));
                if self.seen.len() >= self.steps {
                    return Flow::Stop;
                }
                Flow::Continue
            }
            other => {
                self.end = Some(other);
                Flow::Stop
            }
        }
    }

    fn reads_interior(&self, _: &Wheel, _t0: f64, _t1: f64) -> bool {
        false
    }
}

fn opts() -> EngineOptions {
    EngineOptions {
        method: Method::Dop853,
        rtol: 1e-12,
        atol: 1e-14,
        h_max: 0.05,
        ..EngineOptions::default()
    }
}

/// An 8-spoke wheel (α = π/8) of unit spokes on γ = 0.08, its stance foot at
/// the origin, a step of `h` a twentieth of a spoke ahead of it.
fn wheel(h: f64) -> Wheel {
    Wheel {
        l: 1.0,
        alpha: PI / 8.0,
        gamma: 0.08,
        terrain: TerrainOptions::step(h, 0.05),
        foot: [0.0, 0.0],
    }
}

/// The closed forms of docs/robustness-step-down.md for wheel `w` on a step `h`.
struct ClosedForm {
    /// McGeer's fixed point on the flat slope.
    omega_star: f64,
    /// The extra stance angle of the fall, `sin δ = h / (2 l sin α)`.
    delta: f64,
    /// The rate just after landing on the lower segment.
    rate_1: f64,
    /// The rate after the next (flat) impact, back on the flat section.
    rate_2: f64,
}

fn closed_form(w: &Wheel, h: f64) -> ClosedForm {
    let (l, a, gm) = (w.l, w.alpha, w.gamma);
    let c2a = (2.0 * a).cos();
    let omega_star = (4.0 * (G / l) * a.sin() * gm.sin()).sqrt() / (2.0 * a).tan();
    let delta = (h / (2.0 * l * a.sin())).asin();
    let th0 = gm - a;
    let th1 = gm + a + delta;
    let rate_1 = c2a * (omega_star.powi(2) + 2.0 * (G / l) * (th0.cos() - th1.cos())).sqrt();
    let rate_2 =
        c2a * (rate_1.powi(2) + 2.0 * (G / l) * ((gm - a + delta).cos() - (gm + a).cos())).sqrt();
    ClosedForm {
        omega_star,
        delta,
        rate_1,
        rate_2,
    }
}

/// Walks wheel `w` from the start of a stance at `omega` for `steps`
/// touchdowns.
fn walk(w: Wheel, omega: f64, steps: usize) -> Steps {
    let mut sys = w;
    let mut obs = Steps {
        steps,
        seen: Vec::new(),
        end: None,
    };
    let mut y = [w.gamma - w.alpha, omega];
    let end = run(&mut sys, &mut obs, 0.0, &mut y, 1e3, &opts());
    assert_eq!(end.reason, EndReason::Stopped, "{end:?}");
    obs
}

#[test]
fn the_step_down_map_is_the_closed_form() {
    for h in [0.0, 0.02, 0.1, 0.2] {
        let w = wheel(h);
        let cf = closed_form(&w, h);
        let s = walk(w, cf.omega_star, 2);
        assert_eq!(s.end, None, "h = {h}");
        let (theta_1, rate_1) = s.seen[0];
        let (theta_2, rate_2) = s.seen[1];
        // Landing lower, the wheel turns δ further: the new stance spoke
        // starts δ ahead of the flat section, and the cos 2α loss applies to
        // the larger rate the fall gave it.
        let want_theta_1 = w.gamma - w.alpha + cf.delta;
        assert!(
            (theta_1 - want_theta_1).abs() < 1e-9,
            "h = {h}: θ₁ {theta_1} vs {want_theta_1}"
        );
        assert!(
            (rate_1 - cf.rate_1).abs() < 1e-9,
            "h = {h}: ω₁ {rate_1} vs {}",
            cf.rate_1
        );
        assert!((theta_2 - (w.gamma - w.alpha)).abs() < 1e-9, "h = {h}");
        assert!(
            (rate_2 - cf.rate_2).abs() < 1e-9,
            "h = {h}: ω₂ {rate_2} vs {}",
            cf.rate_2
        );
        if h == 0.0 {
            assert!(
                (rate_1 - cf.omega_star).abs() < 1e-9,
                "flat: the fixed point"
            );
        } else {
            // Energy: the kinetic energy per mass just before the second
            // impact exceeds the flat stance's by the hub's extra drop (the
            // new foot is h lower along the normal and x_f further downhill:
            // g (h cos γ + x_f sin γ)) less the first impact's loss,
            // (1 − cos² 2α) of the kinetic energy it met.
            let c = (2.0 * w.alpha).cos();
            let (before_1, before_2) = (rate_1 / c, rate_2 / c);
            let flat_before = cf.omega_star / c;
            let gained = 0.5 * w.l * w.l * (before_2.powi(2) - flat_before.powi(2));
            let lost = 0.5 * w.l * w.l * (1.0 - c * c) * before_1.powi(2);
            let x_f = 2.0 * w.l * w.alpha.sin() * cf.delta.cos();
            let drop = G * (h * w.gamma.cos() + x_f * w.gamma.sin());
            assert!(
                (gained + lost - drop).abs() < 1e-8,
                "h = {h}: kinetic energy per mass {gained} + impact loss {lost} vs drop {drop}"
            );
        }
    }
}

/// The largest step down after which the wheel still rolls on: the stance
/// foot's normal force `m (g cos θ − l θ̇²)` stays positive through the fall
/// (docs/robustness-step-down.md). With energy conserved in stance,
/// `θ̇² = ω*² + 2 (g/l)(cos θ₀ − cos θ)`, it is least at the landing angle
/// `θ₁ = γ + α + δ`, so the wheel flies off a step with
/// `cos θ₁ < (ω*² l/g + 2 cos θ₀) / 3`.
fn largest_step_closed_form(w: &Wheel) -> f64 {
    let omega_star = closed_form(w, 0.0).omega_star;
    let th0 = w.gamma - w.alpha;
    let th1 = ((omega_star.powi(2) * w.l / G + 2.0 * th0.cos()) / 3.0).acos();
    let delta = th1 - w.gamma - w.alpha;
    2.0 * w.l * w.alpha.sin() * delta.sin()
}

#[test]
fn the_largest_step_down_the_wheel_rolls_on_from_is_the_closed_form() {
    let h_max = largest_step_closed_form(&wheel(0.0));
    // The next stance, faster but starting δ ahead, keeps its foot loaded
    // too: the fall's landing is the binding point.
    {
        let w = wheel(h_max);
        let cf = closed_form(&w, h_max);
        let th_end = w.gamma + w.alpha;
        let th_start = w.gamma - w.alpha + cf.delta;
        assert!(
            th_end.cos() > (cf.rate_1.powi(2) * w.l / G + 2.0 * th_start.cos()) / 3.0,
            "the second stance binds first"
        );
    }
    let omega_star = closed_form(&wheel(0.0), 0.0).omega_star;
    let rolls_on = |h: f64| {
        let s = walk(wheel(h), omega_star, 10);
        s.end.is_none() && s.seen.len() == 10
    };
    let (mut lo, mut hi) = (0.0, 0.5);
    assert!(rolls_on(lo) && !rolls_on(hi));
    while hi - lo > 1e-9 {
        let mid = 0.5 * (lo + hi);
        if rolls_on(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    println!("largest step down: simulated {lo:.9} m, closed form {h_max:.9} m");
    assert!((lo - h_max).abs() < 1e-7, "{lo} vs {h_max}");
    // And it fails the way the closed form says: the wheel flies.
    assert_eq!(
        walk(wheel(1.01 * h_max), omega_star, 10).end,
        Some(Event::Flies)
    );
}

#[test]
fn a_step_just_ahead_of_the_landing_foot_is_a_riser_hit() {
    // The falling tip moves uphill below its stance foot's level: with the
    // edge between where it lands on the lower segment
    // (`2 l sin α cos δ` ahead) and where it passes the upper level
    // (`2 l sin α` ahead), it meets the riser.
    let mut w = wheel(0.2);
    let cf = closed_form(&w, 0.2);
    let land = 2.0 * w.l * w.alpha.sin() * cf.delta.cos();
    let level = 2.0 * w.l * w.alpha.sin();
    w.terrain.step_at = 0.5 * (land + level);
    let s = walk(w, cf.omega_star, 2);
    assert_eq!(s.end, Some(Event::Riser));
}

/// The wheel's gait sensitivity norm in closed form (docs/robustness-gsn.md,
/// "The gait sensitivity norm"), indicator the post-impact rate (the wheel's
/// speed), input the drop met by the next landing: `y_0 = b`,
/// `y_k = c^{2(k−1)} r`, `GSN² = b² + r² / (1 − c⁴)`.
fn gsn_closed_form(w: &Wheel) -> f64 {
    let (l, a, gm) = (w.l, w.alpha, w.gamma);
    let c2 = (2.0 * a).cos().powi(2);
    let omega = closed_form(w, 0.0).omega_star;
    let d_delta = 1.0 / (2.0 * l * a.sin());
    let a_theta = -c2 * (G / l) * (gm - a).sin() / omega;
    let b = c2 * (G / l) * (gm + a).sin() * d_delta / omega;
    let r = a_theta * d_delta + c2 * b;
    (b * b + r * r / (1.0 - c2 * c2)).sqrt()
}

#[test]
fn the_engines_response_to_a_small_step_is_the_closed_form_gsn() {
    // The engine's wheel met by a real step of ε at the fixed point, its
    // post-impact rates against the flat walk's, divided by ε and summed in
    // squares over 60 steps (c⁴ = 1/4: the response is below 1e-30 by
    // then). What is left is the map's curvature, of order ε.
    let closed = gsn_closed_form(&wheel(0.0));
    let omega = closed_form(&wheel(0.0), 0.0).omega_star;
    let flat = walk(wheel(0.0), omega, 60).seen;
    let rel: Vec<f64> = [1e-4, 1e-5]
        .iter()
        .map(|&eps| {
            let over = walk(wheel(eps), omega, 60).seen;
            let simulated = over
                .iter()
                .zip(&flat)
                .map(|(a, b)| ((a.1 - b.1) / eps).powi(2))
                .sum::<f64>()
                .sqrt();
            eprintln!("rimless wheel: GSN {closed:.9}, simulated over {eps} m {simulated:.9}");
            (simulated - closed).abs() / closed
        })
        .collect();
    assert!(rel[1] < 1e-4 && rel[1] < rel[0] / 3.0, "{rel:?}");
}
