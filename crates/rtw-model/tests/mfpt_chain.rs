//! The RTW's MFPT by the chain (`robustness.mfpt_method = "chain"`,
//! docs/robustness-estimators.md, "The chain method") at Fig. 7(a), against the
//! counted estimator's measurements there (results/robustness/mfpt_chain.md
//! says where the numbers and the references are).

use rtw_model::options::{MfptMethod, RobustnessOptions};
use rtw_model::{Options, Params, cancellable, simulate};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// Fig. 7(a) with the chain's MFPT at roughness `sigma`.
fn options(sigma: f64) -> Options {
    Options {
        robustness: RobustnessOptions {
            mfpt: true,
            sigma,
            mfpt_method: MfptMethod::Chain,
            ..RobustnessOptions::default()
        },
        ..Options::default()
    }
}

/// Where the chain works on the RTW (σ = 5 and 3 cm) its range overlaps
/// the counted estimator's interval (5 cm: 153 [119, 215]; 3 cm: 8 056
/// [6 839, 9 558]), and it says how it was made (the values measured are
/// in results/robustness/mfpt_chain-cli.md). Below 3 cm it does not (2 cm:
/// about ten times too high), so no test claims it.
#[test]
#[ignore = "minutes: the chain's 4 x 10^5 steps at each roughness"]
fn the_chain_overlaps_the_counted_estimate_at_5_and_3_cm() {
    for (sigma, lo, hi) in [(0.05, 119.0, 215.0), (0.03, 6_839.0, 9_558.0)] {
        let t = Instant::now();
        let out = simulate(&Params::fig7a(), &options(sigma));
        assert!(out.label.is_stable(), "{out:?}");
        let r = out.robustness.unwrap();
        let (m, d) = (r.mfpt.unwrap(), r.mfpt_chain.unwrap());
        eprintln!("sigma {sigma}: {m:?} {d:?} in {:?}", t.elapsed());
        assert!(m.lo <= hi && lo <= m.hi, "sigma {sigma}: {m:?}");
        assert!(m.lo <= m.mfpt && m.mfpt <= m.hi, "{m:?}");
        assert!(d.cells >= 20 && d.members == 1500 && d.nodes == 80, "{d:?}");
        assert!(d.dimension >= 1 && d.dimension <= d.features, "{d:?}");
    }
}

/// The chain reads the stop flag (Ctrl-C): set a moment into its cloud,
/// the computation ends within seconds and its result is refused.
#[test]
fn a_flag_set_during_the_chain_ends_it() {
    let p = Params::fig7a();
    let o = options(0.05);
    let stop = AtomicBool::new(false);
    let (out, stopped_after) = std::thread::scope(|s| {
        let flag = &stop;
        let setter = s.spawn(move || {
            // Past the flat run (well under a second): inside the chain.
            std::thread::sleep(Duration::from_secs(2));
            flag.store(true, Ordering::SeqCst);
            Instant::now()
        });
        let out = cancellable(&stop, || simulate(&p, &o));
        let done = Instant::now();
        (out, done.duration_since(setter.join().unwrap()))
    });
    assert!(out.is_none(), "the chain finished before the flag: {out:?}");
    eprintln!("flag to return: {stopped_after:?}");
    // 2 s promised; 5 s allowed on a loaded machine.
    assert!(stopped_after < Duration::from_secs(5), "{stopped_after:?}");
}
