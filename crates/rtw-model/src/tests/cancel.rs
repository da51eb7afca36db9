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
