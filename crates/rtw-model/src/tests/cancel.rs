//! The stop flag of [`cancellable`]: a set flag ends a run at its first
//! step end, an unset one changes nothing.

use crate::{Options, Params, cancellable, simulate};
use std::sync::atomic::AtomicBool;

/// A stop flag set before the run ends it at its first step: the run
/// comes back at once and the result is refused; without the flag, the
/// same run is the plain `simulate`'s, bit for bit.
#[test]
fn a_set_flag_stops_the_run_and_an_unset_one_changes_nothing() {
    let p = Params::fig7a();
    let o = Options::default();
    let clear = AtomicBool::new(false);
    let plain = simulate(&p, &o);
    let kept = cancellable(&clear, || simulate(&p, &o)).unwrap();
    assert_eq!(format!("{kept:?}"), format!("{plain:?}"));
    let set = AtomicBool::new(true);
    let mut t_end = f64::NAN;
    assert!(cancellable(&set, || t_end = simulate(&p, &o).t_end).is_none());
    // Ended at its first step end, not at t_max (the plain run's end).
    assert!(t_end < 0.05 && plain.t_end > 1.0, "{t_end} {}", plain.t_end);
    let cut = cancellable(&clear, || cancellable(&set, || simulate(&p, &o)));
    assert_eq!(cut, Some(None));
    // Each call's flag is gone after it: the same run again, whole.
    let again = simulate(&p, &o);
    assert_eq!(format!("{again:?}"), format!("{plain:?}"));
}

/// The MFPT's batches read the flag too: at Fig. 7(a), σ = 5 cm and its
/// most batches (3000, minutes of one-step runs), a flag set a moment after
/// the start ends the computation within seconds and its result is refused.
#[test]
fn a_flag_set_during_the_mfpt_s_batches_ends_them() {
    use crate::options::RobustnessOptions;
    use std::sync::atomic::Ordering;
    use std::time::{Duration, Instant};
    let p = Params::fig7a();
    let o = Options {
        robustness: RobustnessOptions {
            mfpt: true,
            sigma: 0.05,
            mfpt_batches: 3000,
            ..RobustnessOptions::default()
        },
        ..Options::default()
    };
    let stop = AtomicBool::new(false);
    let (out, stopped_after) = std::thread::scope(|s| {
        let flag = &stop;
        let setter = s.spawn(move || {
            // Past the flat run (well under a second): inside the batches.
            std::thread::sleep(Duration::from_secs(2));
            flag.store(true, Ordering::SeqCst);
            Instant::now()
        });
        let out = cancellable(&stop, || simulate(&p, &o));
        let done = Instant::now();
        (out, done.duration_since(setter.join().unwrap()))
    });
    assert!(out.is_none(), "the MFPT finished before the flag: {out:?}");
    eprintln!("flag to return: {stopped_after:?}");
    // 2 s promised; 5 s allowed on a loaded machine.
    assert!(stopped_after < Duration::from_secs(5), "{stopped_after:?}");
}
