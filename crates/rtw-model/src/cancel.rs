//! Stopping a run part way: [`cancellable`] runs a computation with a stop
//! flag that every run of the RTW it makes (the flat run and each run of the
//! robustness measures: the step-down ladder, the rough-slope trials, the
//! MFPT's batches of one-step runs, whose loops read it too) reads
//! at each step end, and ends at once when it is set. A measure of 10⁵
//! trials of 10⁶ steps would otherwise finish, hours after a Ctrl-C.
//!
//! The flag is reached through the thread the computation runs on, so the
//! many functions between `simulate` and a run's observer need not carry it.

use std::cell::Cell;
use std::sync::atomic::{AtomicBool, Ordering};

thread_local! {
    /// The stop flag of the [`cancellable`] computation running on this
    /// thread (null: none).
    static STOP: Cell<*const AtomicBool> = const { Cell::new(std::ptr::null()) };
}

/// Runs `f` on this thread with `stop` as its stop flag: every run of the
/// RTW that `f` makes ends at its next step end once `stop` is set, so `f`
/// returns soon after. Its result is `None` when `stop` was set by the time
/// `f` returned (a run may have been cut short: the result is not the
/// computation's), and `Some` otherwise (no run was cut: `stop` is only ever
/// set, never cleared, while `f` runs). Calls nest: the inner flag holds
/// inside the inner call.
pub fn cancellable<T>(stop: &AtomicBool, f: impl FnOnce() -> T) -> Option<T> {
    /// Puts the outer flag back, also when `f` panics.
    struct Restore(*const AtomicBool);
    impl Drop for Restore {
        fn drop(&mut self) {
            STOP.with(|s| s.set(self.0));
        }
    }
    let _restore = Restore(STOP.with(|s| s.replace(stop)));
    let out = f();
    (!stop.load(Ordering::SeqCst)).then_some(out)
}

/// Whether the stop flag of the computation on this thread is set.
pub(crate) fn requested() -> bool {
    STOP.with(|s| {
        let p = s.get();
        // SAFETY: a non-null pointer was set by `cancellable` from a
        // reference that outlives its call, and `Restore` puts the previous
        // value back before that call returns (or unwinds); the pointer is
        // only read on this thread, inside that call.
        !p.is_null() && unsafe { (*p).load(Ordering::Relaxed) }
    })
}
