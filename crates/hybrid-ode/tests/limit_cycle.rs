//! Limit cycles of McGeer's rimless wheel: the fixed point of its step map
//! by Newton, and its Floquet multiplier by the variational equations with
//! saltation, against the closed forms.

use hybrid_ode::limit::{newton, nontrivial_multipliers};
use hybrid_ode::rimless::RimlessWheel;
use hybrid_ode::{EngineOptions, Method};

fn tight() -> EngineOptions {
    EngineOptions {
        method: Method::Dop853,
        rtol: 1e-12,
        atol: 1e-12,
        ..EngineOptions::default()
    }
}

/// McGeer's wheel through the same Newton and variational code as the RTW:
/// ω* = cot 2α · sqrt(4 (g/l) sin α sin γ), dP/dω(ω*) = cos² 2α.
#[test]
fn rimless_wheel_fixed_point_and_multiplier_match_the_closed_form() {
    // Slopes steep enough that the fixed point passes the apex
    // (ω*² > 2 (g/l)(1 − cos(α − γ))).
    for (n, gamma) in [(6u32, 0.3), (8, 0.2), (12, 0.06)] {
        let w = RimlessWheel::with_spokes(n, 1.0, gamma, 9.81);
        assert!(w.omega_star().powi(2) > w.apex_rate_sq());
        let opts = tight();
        let start = 1.3 * w.omega_star();
        let fp = newton(&[start], &[1.0], 1e-11, 20, |z| {
            let (p, slope) = w.step_map_with_slope(z[0], &opts)?;
            Some((vec![p], nalgebra::DMatrix::from_element(1, 1, slope)))
        })
        .expect("Newton converges");
        let omega = fp.z[0];
        assert!(
            (omega - w.omega_star()).abs() < 1e-9 * w.omega_star(),
            "n = {n}: ω = {omega}, ω* = {}",
            w.omega_star()
        );
        let mu = nontrivial_multipliers(&fp.jacobian);
        let cos2 = (2.0 * w.alpha).cos().powi(2);
        assert_eq!(mu.len(), 1);
        assert!(
            (mu[0].re - cos2).abs() < 1e-8 && mu[0].im == 0.0,
            "n = {n}: multiplier {} vs cos² 2α = {cos2}",
            mu[0]
        );
    }
}
