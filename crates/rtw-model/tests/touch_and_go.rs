//! The step map's section for skipping gaits whose feet touch and lift
//! again (`Section::TouchAndGo`): at s = 0 on a steep slope every new foot
//! lifts at once, so the walk's section (a foot that stays) is never
//! crossed; the touch-and-go section finds the skip that a simulation of the
//! same robot keeps doing.

use rtw_model::RodMode;
use rtw_model::cycles::Section;
use rtw_model::cycles::{CycleOptions, StepError, StepMap};
use rtw_model::{Label, Options, Params, simulate};

fn steep_s0() -> (Params, Options) {
    let mut options = Options::default();
    options.strings.rest_length_ratio = 0.0;
    (
        Params {
            phi: 0.34,
            ..Params::fig7a()
        },
        options,
    )
}

#[test]
fn a_skip_whose_feet_touch_and_go_never_crosses_the_walks_section() {
    let (params, options) = steep_s0();
    let run = simulate(&params, &options);
    assert_eq!(run.label, Label::Skip, "{run:?}");
    let cycle = CycleOptions::default();
    let map = StepMap::new(&params, &options, &cycle);
    // The walk's section: no foot stays down, so no step ends.
    let err = map.limit_cycle(&options, &cycle).unwrap_err();
    assert!(
        err.to_string().contains(&StepError::NoNewFoot.to_string()),
        "{err}"
    );
}

/// The post-impact ω of the new stance rod (a+ in canonical labels).
const OMEGA_A: usize = 5;

#[test]
fn the_touch_and_go_section_finds_the_skip_the_simulation_keeps_doing() {
    let (params, options) = steep_s0();
    let run = simulate(&params, &options);
    let cycle = CycleOptions {
        section: Section::TouchAndGo,
        ..CycleOptions::default()
    };
    let map = StepMap::new(&params, &options, &cycle);
    let mut p = map.first(&options).expect("a first landing").to;
    let mut omega = Vec::new();
    for _ in 0..600 {
        p = map.step(&p).expect("a touch-and-go step").to;
        omega.push(p.y[OMEGA_A]);
    }
    // The iterates circle slowly about the cycle (`limit_cycle` sees no
    // period ≤ 12 after its settling steps), so Newton starts from where
    // they are.
    let lc = map
        .solve(&p, 1, &cycle)
        .expect("Newton on the touch-and-go section");
    // Every rod is in the air just after the landing: the foot touched and went.
    assert_eq!(lc.orbit[0].modes, [RodMode::Free; 3]);
    // The same skip as the simulation's: its new-foot rate to one step in the
    // run's analysis window.
    let rate = 1.0 / lc.steps[0].time;
    assert!(
        (rate - run.f_w_newfoot).abs() <= 1.0 / options.analysis_window,
        "map {rate} Hz, run {} Hz",
        run.f_w_newfoot
    );
    // Its leading multipliers: a complex pair on the unit circle to 1 %
    // (a Neimark–Sacker point close by: the simulated skip is quasi-periodic
    // about this cycle).
    let mu = lc.multipliers[0];
    assert!(mu.im.abs() > 1e-3 && (mu.norm() - 1.0).abs() < 0.01, "{mu}");
    // The linearization's rotation per step, 2π / arg μ steps per turn, is
    // the period of the iterates' slow oscillation about the fixed point
    // (counted from their crossings of the fixed point's ω over steps
    // 100–600, an independent measure), to 15 %.
    let w = lc.orbit[0].y[OMEGA_A];
    let late = &omega[100..];
    let ups: Vec<usize> = (1..late.len())
        .filter(|&k| late[k - 1] < w && late[k] >= w)
        .collect();
    assert!(ups.len() >= 3, "{} upward crossings", ups.len());
    let observed = (ups[ups.len() - 1] - ups[0]) as f64 / (ups.len() - 1) as f64;
    let predicted = 2.0 * std::f64::consts::PI / mu.arg().abs();
    assert!(
        (observed / predicted - 1.0).abs() < 0.15,
        "iterates turn every {observed} steps, the multiplier says {predicted}"
    );
}
