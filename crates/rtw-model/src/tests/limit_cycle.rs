//! The RTW's limit cycles: fixed points of the step map by Newton, Floquet
//! multipliers by the variational equations, checked against finite
//! differences of the map (McGeer's wheel, with closed forms, is checked in
//! hybrid-ode's tests).

use crate::cycles::{CycleOptions, StepMap};
use crate::{Method, Options, Params};
use hybrid_ode::limit::{self, nontrivial_multipliers};

/// The Fig. 7(a) walk under the model this check was written for: the
/// default's choices with strings of natural length s = 0.85. (At the
/// fitted default s = 0.8875 the two differ by 5e-5 relative at a
/// difference step of 1e-5: an open finding, not covered here.)
fn fig7a_walk() -> (StepMap, Options, CycleOptions) {
    let mut options = Options::default();
    options.strings.rest_length_ratio = 0.85;
    let cycle = CycleOptions::default();
    (
        StepMap::new(&Params::fig7a(), &options, &cycle),
        options,
        cycle,
    )
}

/// The Fig. 7(a) walk (s = 0.85) is a period-1 cycle whose
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

/// The Floquet column's largest multiplier is a property of the gait, not
/// of where within Newton's tolerance its orbit was found: at the default
/// model, for the Fig. 7(a) walk and the paper scan's period-2 skip 432,
/// the spectral radius of `Pⁿ`'s difference Jacobian (the column's
/// settings) at the orbit, and at the orbit moved by 1e-9 of a coordinate's
/// scale in each of three coordinates, is the variational Jacobian's at the
/// orbit within 5e-4. (With the difference steps of 1e-6 the column had
/// before: up to 1.5e-3 off at Fig. 7(a), 2.3e-3 at skip 432.)
#[test]
fn the_floquet_column_does_not_move_with_the_orbit() {
    let cycle = crate::cycles::map::limit_cycle::run_cycle_options();
    for params in [Params::fig7a(), super::skip_432()] {
        let (map, orbit) = crate::cycles::robustness::gsn::tests::settled_orbit(&params);
        let n = orbit.len();
        let radius = |z: &[f64], jacobian| {
            let p = orbit[0].with_coords(z);
            let (_, j) = map.power_with_jacobian(&p, n, jacobian).unwrap();
            limit::spectral_radius(&nontrivial_multipliers(&j))
        };
        let at = orbit[0].coords();
        let exact = radius(&at, crate::cycles::Jacobian::Variational);
        let scale = map.coord_scale(&orbit[0]);
        let mut seen = vec![radius(&at, cycle.jacobian)];
        for k in [0, 3, 7] {
            let mut z = at.clone();
            z[k] += 1e-9 * scale[k];
            seen.push(radius(&z, cycle.jacobian));
        }
        for r in &seen {
            assert!(
                (r - exact).abs() <= 5e-4,
                "period {n}: variational {exact}, differences {seen:?}"
            );
        }
    }
}
