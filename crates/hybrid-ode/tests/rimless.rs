//! McGeer's rigid rimless wheel through the hybrid engine against its closed
//! forms (McGeer 1990; derivation in `src/rimless.rs`):
//! `P(ω) = cos 2α · sqrt(ω² + 4 (g/l) sin α sin γ)`,
//! `ω* = cot 2α · sqrt(4 (g/l) sin α sin γ)`, `P'(ω*) = cos² 2α`, and the
//! impact `θ̇⁺ = θ̇⁻ cos 2α`.

use hybrid_ode::rimless::{GUARD_ROLLBACK, GUARD_TOUCHDOWN, RimlessWheel, Stride};
use hybrid_ode::{EndReason, EngineOptions, HybridSystem, Method};

/// An 8-spoke wheel (2α = 2π/8, α = π/8) on γ = 0.08, l = 1, g = 9.81.
fn wheel() -> RimlessWheel {
    RimlessWheel::with_spokes(8, 1.0, 0.08, 9.81)
}

fn opts(method: Method, rtol: f64) -> EngineOptions {
    EngineOptions {
        method,
        rtol,
        atol: rtol * 1e-2,
        h_max: 0.05,
        ..EngineOptions::default()
    }
}

#[test]
fn omega_star_is_the_closed_form_fixed_point() {
    let w = wheel();
    let alpha = std::f64::consts::PI / 8.0;
    assert_eq!(w.alpha, alpha);
    // cot(π/4) = 1, so ω* = sqrt(4 g sin(π/8) sin(0.08)).
    let want = (4.0 * 9.81 * alpha.sin() * 0.08f64.sin()).sqrt();
    assert!((w.omega_star() - want).abs() <= 1e-15 * want);
    let p = w.step_map_closed_form(w.omega_star()).unwrap();
    assert!((p - w.omega_star()).abs() <= 1e-14 * want);
    let slope = w.step_map_slope(w.omega_star());
    assert!((slope - (2.0 * alpha).cos().powi(2)).abs() < 1e-14);
}

#[test]
fn simulated_step_map_matches_the_closed_form() {
    let w = wheel();
    let ws = w.omega_star();
    for method in [Method::Dp54, Method::Dop853] {
        for omega in [0.99 * ws, ws, 1.3 * ws, 3.0 * ws] {
            let p = w.step_map(omega, &opts(method, 1e-12)).unwrap();
            let want = w.step_map_closed_form(omega).unwrap();
            assert!(
                (p - want).abs() <= 1e-10 * want,
                "{method:?} ω = {omega}: {p} vs {want}"
            );
        }
    }
}

#[test]
fn iterated_step_map_converges_to_omega_star() {
    let w = wheel();
    let ws = w.omega_star();
    for method in [Method::Dp54, Method::Dop853] {
        let o = opts(method, 1e-12);
        let mut omega = 1.3 * ws;
        for _ in 0..200 {
            omega = w.step_map(omega, &o).unwrap();
        }
        let rel = (omega - ws).abs() / ws;
        println!("{method:?}: ω after 200 steps = {omega}, ω* = {ws}, relative error {rel:.3e}");
        assert!(rel <= 1e-8, "{method:?}: {rel}");
    }
}

#[test]
fn a_200_step_walk_in_one_run_converges_to_omega_star() {
    // The same, but all 200 stance phases and impacts in a single run: this
    // exercises the engine's restart after each reset.
    let ws = wheel().omega_star();
    for method in [Method::Dp54, Method::Dop853] {
        let w = wheel();
        let mut y = [0.0; 2];
        let (end, walk) = w.walk(1.3 * ws, 200, 1e4, &opts(method, 1e-12), &mut y);
        assert_eq!(end.reason, EndReason::Stopped);
        assert_eq!(walk.impacts, 200);
        assert_eq!(end.work.events, 200);
        let rel = (walk.last_rate_plus - ws).abs() / ws;
        println!(
            "{method:?}: 200-step walk, relative error {rel:.3e}, {:?}",
            end.work
        );
        assert!(rel <= 1e-8, "{method:?}: {rel}");
        // Each stance starts at γ − α: the state right after the reset.
        assert!((y[0] - w.stance_start()).abs() < 1e-12);
    }
}

#[test]
fn step_map_slope_at_the_fixed_point_is_cos2_2alpha() {
    let w = wheel();
    let ws = w.omega_star();
    let want = (2.0 * w.alpha).cos().powi(2);
    let d = 1e-5 * ws;
    for method in [Method::Dp54, Method::Dop853] {
        let o = opts(method, 1e-12);
        let slope = (w.step_map(ws + d, &o).unwrap() - w.step_map(ws - d, &o).unwrap()) / (2.0 * d);
        println!(
            "{method:?}: dP/dω(ω*) = {slope}, cos² 2α = {want}, diff {:.3e}",
            slope - want
        );
        assert!(
            (slope - want).abs() <= 1e-6,
            "{method:?}: {slope} vs {want}"
        );
    }
}

#[test]
fn the_impact_reset_scales_the_rate_by_cos_2alpha() {
    let mut w = wheel();
    let c = (2.0 * w.alpha).cos();
    // The reset itself.
    let mut y = [w.touchdown_angle(), 1.7];
    let stride = w.reset(0.3, &mut y, GUARD_TOUCHDOWN);
    assert_eq!(y[1], 1.7 * c);
    assert!((y[0] - w.stance_start()).abs() < 1e-15);
    assert_eq!(
        stride,
        Stride::Touchdown {
            rate_minus: 1.7,
            rate_plus: 1.7 * c
        }
    );
    // And at a located event inside a run.
    let w = wheel();
    let mut y = [0.0; 2];
    let (_, walk) = w.walk(
        1.3 * w.omega_star(),
        3,
        100.0,
        &opts(Method::Dop853, 1e-10),
        &mut y,
    );
    assert_eq!(walk.impacts, 3);
    assert_eq!(walk.last_rate_plus, walk.last_rate_minus * c);
    assert_eq!(y[1], walk.last_rate_plus);
}

#[test]
fn a_slow_wheel_rolls_back() {
    // Below the apex rate sqrt(2 (g/l)(1 − cos(α − γ))) the hub does not pass
    // over the contact and the wheel falls back onto its previous spoke.
    let w = wheel();
    let apex = w.apex_rate_sq().sqrt();
    assert!(w.step_map_closed_form(0.9 * apex).is_none());
    for method in [Method::Dp54, Method::Dop853, Method::Rk4] {
        let o = opts(method, 1e-10);
        assert_eq!(w.step_map(0.9 * apex, &o), None, "{method:?}");
        let mut y = [0.0; 2];
        let (end, walk) = w.walk(0.9 * apex, 1, 100.0, &o, &mut y);
        assert_eq!(end.reason, EndReason::Stopped);
        assert!(walk.rolled_back);
        assert_eq!(walk.impacts, 0);
        // Rolled back to θ = γ − α with the energy it started with: θ̇ = −ω.
        assert!((y[0] - w.stance_start()).abs() < 1e-9);
        assert!((y[1] + 0.9 * apex).abs() < 1e-6, "{method:?}: {}", y[1]);
        let _ = GUARD_ROLLBACK;
        // And just above the apex rate it passes.
        assert!(w.step_map(1.1 * apex, &o).is_some());
    }
}

#[test]
fn rk4_walks_to_omega_star_too() {
    // Fixed-step RK4 (h = 1 ms), events located on its cubic Hermite
    // interpolant: global error O(h^4) and interpolation error O(h^4), both
    // ~1e-12 here (measured 2e-13); asserted with margin.
    let w = wheel();
    let ws = w.omega_star();
    let o = EngineOptions {
        method: Method::Rk4,
        ..EngineOptions::default()
    };
    let mut omega = 1.3 * ws;
    for _ in 0..100 {
        omega = w.step_map(omega, &o).unwrap();
    }
    let rel = (omega - ws).abs() / ws;
    println!("RK4: relative error {rel:.3e}");
    assert!(rel <= 1e-9, "{rel}");
}
