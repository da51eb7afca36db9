//! The RTW's mean first-passage time (docs/robustness-rough.md, "Mean
//! first-passage time") against plain Monte Carlo run to the fall where
//! that is affordable: the same rough slopes, the Monte Carlo trials
//! (`steps_to_fall`) capped far beyond any of them, so uncensored.

use rtw_model::options::RobustnessOptions;
use rtw_model::outcome::{MeanFirstPassage, Robustness, StepsToFall};
use rtw_model::{Options, Params, simulate};

/// The robustness measures `robustness` asks for, of Fig. 7(a)'s stable
/// gait.
fn fig7a(robustness: RobustnessOptions) -> Robustness {
    let o = Options {
        robustness,
        ..Options::default()
    };
    let out = simulate(&Params::fig7a(), &o);
    assert!(out.label.is_stable(), "{out:?}");
    out.robustness.unwrap()
}

/// Fig. 7(a)'s stable gait on the rough slope of `sigma`: plain Monte
/// Carlo of `trials` runs capped at `max_steps`, and the MFPT (its cloud
/// in `mfpt_batches` batches).
fn monte_carlo_and_mfpt(
    sigma: f64,
    trials: u32,
    max_steps: u32,
    mfpt_batches: u32,
) -> (StepsToFall, MeanFirstPassage) {
    let r = fig7a(RobustnessOptions {
        mfpt: true,
        steps_to_fall: true,
        sigma,
        trials,
        max_steps,
        mfpt_batches,
        ..RobustnessOptions::default()
    });
    let (mc, m) = (r.steps_to_fall.unwrap(), r.mfpt.unwrap());
    eprintln!("Monte Carlo {mc:?}\nMFPT {m:?}");
    (mc, m)
}

/// The MFPT of Fig. 7(a)'s gait on the rough slope of `sigma`, its cloud
/// in `mfpt_batches` batches.
fn mfpt_alone(sigma: f64, mfpt_batches: u32) -> MeanFirstPassage {
    let m = fig7a(RobustnessOptions {
        mfpt: true,
        sigma,
        mfpt_batches,
        ..RobustnessOptions::default()
    })
    .mfpt
    .unwrap();
    eprintln!("MFPT ({mfpt_batches} batches) {m:?}");
    m
}

#[test]
fn the_mfpt_agrees_with_uncensored_monte_carlo_where_falls_are_frequent() {
    let (mc, m) = monte_carlo_and_mfpt(0.05, 200, 20_000, 6);
    assert_eq!(mc.censored, 0, "{mc:?}");
    assert!(m.mfpt <= 200.0, "{m:?}");
    // The two 95 % intervals overlap.
    assert!(
        m.lo <= mc.hi && mc.lo <= m.hi,
        "Monte Carlo {mc:?} vs MFPT {m:?}"
    );
    assert!(m.fall_rate > 0.0 && m.fall_rate < 1.0, "{m:?}");
}

#[test]
fn the_mfpt_is_a_function_of_the_seed_and_refused_on_the_flat_slope() {
    let mut o = Options {
        robustness: RobustnessOptions {
            mfpt: true,
            sigma: 0.05,
            ..RobustnessOptions::default()
        },
        ..Options::default()
    };
    let p = Params::fig7a();
    let a = simulate(&p, &o).robustness.unwrap().mfpt.unwrap();
    assert_eq!(a, simulate(&p, &o).robustness.unwrap().mfpt.unwrap());
    o.terrain.seed = 1;
    assert_ne!(a, simulate(&p, &o).robustness.unwrap().mfpt.unwrap());
    o.robustness.sigma = 0.0;
    assert_eq!(o.validate().unwrap_err().field, "robustness.sigma");
}

/// Where falls are rare (σ = 3 cm: thousands of steps) plain Monte Carlo
/// run to the fall is still affordable for a test, and the MFPT's interval
/// (open above when the cloud counts few falls) must hold it. Ten times the
/// batches (`robustness.mfpt_batches`, ten times the walker-steps) close
/// the interval there, and it still holds the Monte Carlo. At the default
/// roughness (σ = 1 cm) Fig. 7(a)'s walk falls too rarely for either: none
/// of 100 trials falls within 20 000 steps, and the MFPT is a lower bound
/// of about 3 200 steps. (Before a tip put on a face at its foot was
/// watched for its return there, such tips slid through the lower patch,
/// and the walk "collapsed" within about 500 steps at σ = 1 cm.)
#[test]
fn the_mfpt_holds_uncensored_monte_carlo_where_falls_are_rare() {
    let (mc, m) = monte_carlo_and_mfpt(0.03, 50, 200_000, 6);
    assert_eq!(mc.censored, 0, "{mc:?}");
    assert!(mc.mean > 1000.0, "{mc:?}");
    assert!(
        m.lo <= mc.hi && mc.lo <= m.hi,
        "Monte Carlo {mc:?} vs MFPT {m:?}"
    );
    let deep = mfpt_alone(0.03, 60);
    // Each batch is 2 880 steps of the walker: 16 walkers through 60 steps
    // of burn-in, then their 32 copies through the 60 counted steps.
    assert_eq!(deep.steps, 60 * (16 * 60 + 32 * 60), "{deep:?}");
    assert!(deep.hi.is_finite(), "{deep:?}");
    assert!(
        deep.lo <= mc.hi && mc.lo <= deep.hi,
        "Monte Carlo {mc:?} vs MFPT of 60 batches {deep:?}"
    );
}
