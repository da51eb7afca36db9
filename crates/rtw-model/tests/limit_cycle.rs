//! Limit cycles: fixed points of step maps by Newton, Floquet multipliers by
//! the variational equations, checked against closed forms (McGeer's rimless
//! wheel) and against finite differences of the map (the RTW).

use rtw_model::hybrid::EngineOptions;
use rtw_model::integrate::Method;
use rtw_model::limit::{self, newton, nontrivial_multipliers};
use rtw_model::rimless::RimlessWheel;
use rtw_model::stepmap::{CycleOptions, StepMap};
use rtw_model::{Options, Params};

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

fn fig7a_walk() -> (StepMap, Options, CycleOptions) {
    let options = Options::default();
    let cycle = CycleOptions::default();
    (
        StepMap::new(&Params::fig7a(), &options, &cycle),
        options,
        cycle,
    )
}

/// The Fig. 7(a) walk of the default model is a period-1 cycle whose
/// multipliers by the variational equations (through slips, re-sticks,
/// lift-offs and the touchdown) equal those of central differences of the
/// map, at two step sizes, to 6 significant digits.
#[test]
fn rtw_walk_multipliers_variational_equal_finite_differences() {
    let (map, options, cycle) = fig7a_walk();
    let lc = map.limit_cycle(&options, &cycle).expect("a limit cycle");
    assert_eq!(lc.period, 1);
    assert!(lc.is_stable(), "max |μ| = {}", lc.floquet_max());
    let var = &lc.multipliers;
    assert!(var.len() >= 8, "{} multipliers", var.len());
    let p = lc.orbit[0];
    for rel in [1e-5, 1e-6] {
        let j = map.fd_jacobian(&p, rel).expect("the map is smooth there");
        let fd = nontrivial_multipliers(&j);
        assert_eq!(fd.len(), var.len(), "step {rel:e}");
        for (a, b) in var.iter().zip(&fd) {
            assert!(
                (a - b).norm() <= 1e-6 * a.norm(),
                "step {rel:e}: variational {a} vs differences {b}"
            );
        }
    }
}

/// Newton's fixed point, stepped once more by the map (and by an independent
/// integrator, DP5(4) at rtol 1e-10), comes back to itself within the
/// integration tolerance.
#[test]
fn newton_fixed_point_returns_to_itself() {
    let (map, options, cycle) = fig7a_walk();
    let lc = map.limit_cycle(&options, &cycle).expect("a limit cycle");
    let p = lc.orbit[0];
    let scale = map.coord_scale(&p);
    assert!(lc.fixed_point.residual <= cycle.newton_tol);
    let again = map.step(&p).expect("a step").to;
    assert_eq!(again.modes, p.modes);
    let d = limit::scaled_max(&again.coords(), &p.coords(), &scale);
    assert!(d <= 1e-9, "same map: scaled distance {d:.3e}");

    let other = CycleOptions {
        method: Method::Dp54,
        rtol: 1e-10,
        atol: 1e-12,
        ..cycle
    };
    let map5 = StepMap::new(&Params::fig7a(), &options, &other);
    let again = map5.step(&p).expect("a step").to;
    let d = limit::scaled_max(&again.coords(), &p.coords(), &scale);
    assert!(d <= 1e-7, "DP5(4) at 1e-10: scaled distance {d:.3e}");
}
