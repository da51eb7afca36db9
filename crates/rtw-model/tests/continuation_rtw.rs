//! The Fig. 7(a) walk's branch in the slope φ by continuation on the step
//! map: the period doubling where the attractor sweep of
//! `rtw-scan bifurcation` (an independent computation: simulation and
//! Newton at fixed φ, results/bifurcation/summary.md) saw the leading
//! multiplier pass −1, between φ = 0.2035 (−0.9975) and 0.2040 (−1.0091).

use hybrid_ode::continuation::{self, Kind, Options as Cont};
use hybrid_ode::limit;
use rtw_model::cycles::continuation::StepMapFamily;
use rtw_model::cycles::stepmap::{CycleOptions, StepMap};
use rtw_model::{Options, Param, Params};

#[test]
fn the_walks_period_doubling_is_located_where_the_attractor_sweep_brackets_it() {
    let options = Options::default();
    let base = Params {
        phi: 0.2,
        ..Params::fig7a()
    };
    // Near the period doubling the walk converges slowly (|μ| ≈ 0.85 per
    // step): settle longer than the default before looking for its period.
    let cycle = CycleOptions {
        settle_steps: 300,
        ..CycleOptions::default()
    };
    let map = StepMap::new(&base, &options, &cycle);
    let lc = map
        .limit_cycle(&options, &cycle)
        .expect("the period-1 walk at φ = 0.2");
    assert_eq!(lc.period, 1);
    let template = lc.orbit[0];
    let mut family = StepMapFamily::new(&base, &options, &cycle, Param::Phi, template, 1);
    let opts = Cont {
        ds: 0.02,
        ds_max: 0.05,
        ds_min: 1e-6,
        p_min: 0.19,
        p_max: 0.21,
        tol: 1e-8,
        locate_tol: 1e-6,
        z_scale: map.coord_scale(&template),
        p_scale: 0.1,
        ..Cont::default()
    };
    let b = continuation::continue_branch(
        &mut family,
        &lc.fixed_point.z,
        base.phi,
        1.0,
        &opts,
        &limit::nontrivial_multipliers,
    )
    .expect("a start");
    let pd: Vec<_> = b
        .bifurcations
        .iter()
        .filter(|b| b.kind == Kind::PeriodDoubling)
        .collect();
    assert_eq!(pd.len(), 1, "{:?}", b.bifurcations);
    let phi = pd[0].point.p;
    assert!(
        (0.2035..0.2040).contains(&phi),
        "period doubling at φ = {phi}"
    );
    let nearest = pd[0]
        .point
        .multipliers
        .iter()
        .map(|m| (m.re + 1.0).hypot(m.im))
        .fold(f64::INFINITY, f64::min);
    assert!(nearest < 1e-3, "a multiplier within 1e-3 of −1: {nearest}");
    // Stable before it, unstable after it: the branch goes on past it.
    assert!(
        b.points
            .iter()
            .filter(|p| p.p < phi - 1e-4)
            .all(|p| p.stable)
    );
    assert!(b.points.iter().any(|p| p.p > phi + 1e-4 && !p.stable));
}
