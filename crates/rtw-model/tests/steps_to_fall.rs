//! Mean steps to fall on seeded rough slopes (docs/robustness-rough.md): a pure
//! function of the seed, censored on the flat slope, short on rough ground.

use rtw_model::options::RobustnessOptions;
use rtw_model::outcome::StepsToFall;
use rtw_model::{Options, Params, simulate};

fn steps_to_fall(sigma: f64, seed: u64) -> StepsToFall {
    let mut o = Options::default();
    o.terrain.seed = seed;
    o.robustness = RobustnessOptions {
        steps_to_fall: true,
        sigma,
        trials: 10,
        max_steps: 60,
        ..RobustnessOptions::default()
    };
    let out = simulate(&Params::fig7a(), &o);
    assert!(out.label.is_stable(), "{out:?}");
    out.robustness.unwrap().steps_to_fall.unwrap()
}

#[test]
fn steps_to_fall_is_a_function_of_the_seed() {
    // σ = 5 cm, where some trials fall within 60 steps (at 1 cm every
    // trial walks them, so any two seeds agree on 60 censored steps); the
    // seeds far apart, as trial i draws its ground from seed + i.
    let (a, b, c) = (
        steps_to_fall(0.05, 3),
        steps_to_fall(0.05, 3),
        steps_to_fall(0.05, 1000),
    );
    assert_eq!(a, b);
    assert_ne!(a, c);
    assert_eq!(a.trials, 10);
    assert!(a.lo <= a.mean && a.mean <= a.hi, "{a:?}");
}

#[test]
fn the_flat_slope_never_trips_the_fig7a_walk_and_a_rough_one_does_quickly() {
    // σ = 0 is the flat slope: every trial walks to the censoring count.
    let flat = steps_to_fall(0.0, 0);
    assert_eq!((flat.mean, flat.censored), (60.0, 10), "{flat:?}");
    // A rough slope does fell it: at σ = 30 cm (37 % of a rod) every trial
    // falls before the censoring count. (When a foot meeting a face tripped
    // the walker, σ = 5 cm felled every trial within 15 steps; with faces as
    // contacts, docs/model.md §4, σ = 5 cm leaves most trials walking.)
    let rough = steps_to_fall(0.3, 0);
    assert_eq!(rough.censored, 0, "{rough:?}");
    assert!(rough.hi < 60.0, "{rough:?}");
}

/// The work budget (`max_steps`, integrator steps before a run is declared
/// diverged) is sized for the flat run; a trial of many more steps must not
/// run out of it and count as a fall. With the default budget (5 × 10⁶)
/// every trial of Fig. 7(a) longer than about 2.4 × 10⁵ steps of the gait
/// "fell" there (`simulate` of Fig. 7(a) with `--set terrain.roughness=0.02
/// --set t_max=250000 --set stop_when_settled=false` ends `work_budget` at
/// 60 234 s, 2.4 × 10⁵ steps). Here the budget is cut to
/// 20 000 integrator steps, which the flat run needs a fraction of, and the
/// trials of 2 000 gait steps need about twice.
#[test]
fn a_long_trial_is_not_felled_by_the_work_budget_of_the_flat_run() {
    let mut o = Options {
        max_steps: 20_000,
        ..Options::default()
    };
    o.robustness = RobustnessOptions {
        steps_to_fall: true,
        sigma: 0.0,
        trials: 2,
        max_steps: 2_000,
        ..RobustnessOptions::default()
    };
    let out = simulate(&Params::fig7a(), &o);
    assert!(out.label.is_stable(), "{out:?}");
    let s = out.robustness.unwrap().steps_to_fall.unwrap();
    assert_eq!((s.mean, s.censored), (2_000.0, 2), "{s:?}");
}

#[test]
fn bad_monte_carlo_settings_are_refused_naming_the_field() {
    let bad = |f: fn(&mut RobustnessOptions)| {
        let mut o = Options::default();
        f(&mut o.robustness);
        o.validate().unwrap_err().to_string()
    };
    for (e, field) in [
        (bad(|r| r.sigma = -0.01), "robustness.sigma"),
        (bad(|r| r.sigma = f64::NAN), "robustness.sigma"),
        (bad(|r| r.trials = 1), "robustness.trials"),
        (bad(|r| r.max_steps = 0), "robustness.max_steps"),
    ] {
        assert!(e.starts_with(field) && e.contains("must be in"), "{e}");
    }
    Options::default().validate().unwrap();
}
