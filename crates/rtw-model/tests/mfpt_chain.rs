//! The RTW's MFPT by the chain (`robustness.mfpt_method = "chain"`,
//! docs/robustness-rough.md, "The chain method") at Fig. 7(a), against the
//! counted estimator's measurements there (run with many batches:
//! results/robustness/mfpt_chain.md lists the commands).

use rtw_model::options::{MfptMethod, RobustnessOptions};
use rtw_model::{Options, Params, simulate};
use std::time::Instant;

/// The chain's MFPT of Fig. 7(a)'s stable gait at roughness `sigma`.
fn chain_at(sigma: f64) -> rtw_model::outcome::Robustness {
    let o = Options {
        robustness: RobustnessOptions {
            mfpt: true,
            sigma,
            mfpt_method: MfptMethod::Chain,
            ..RobustnessOptions::default()
        },
        ..Options::default()
    };
    let t = Instant::now();
    let out = simulate(&Params::fig7a(), &o);
    assert!(out.label.is_stable(), "{out:?}");
    let r = out.robustness.unwrap();
    eprintln!(
        "sigma {sigma}: {:?} {:?} in {:.1} s",
        r.mfpt,
        r.mfpt_chain,
        t.elapsed().as_secs_f64()
    );
    r
}

#[test]
#[ignore = "a measurement (minutes): scripts/mfpt_chain_check.sh"]
fn measure() {
    for sigma in [0.05, 0.02, 0.015, 0.01] {
        chain_at(sigma);
    }
}
