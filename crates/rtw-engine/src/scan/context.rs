//! What every study is run with, whatever it computes: the observer that
//! hears of its progress, the flag that stops it, and its threads.

use crate::scan::progress::{Progress, Silent};
use crate::scan::workers::Stopped;
use std::num::NonZeroUsize;
use std::sync::atomic::{AtomicBool, Ordering};

/// How a study runs: what watches it, what stops it, on how many threads.
/// Every study entry takes one (`&Run`) beside its checked settings, so
/// that the command line and Python hand these three to each study the same
/// way (the command line: its progress on stderr and the flag its Ctrl-C
/// handler sets; Python: a callback and the flag KeyboardInterrupt sets).
#[derive(Clone, Copy)]
pub struct Run<'a> {
    /// Hears of the study's stages and units of work.
    pub progress: &'a dyn Progress,
    /// Set from outside to stop the study: the model's runs end at their
    /// next step, and the study returns [`Stopped`] with nothing written.
    pub stop: &'a AtomicBool,
    /// Worker threads (`None`: one per core); a sequential study has none
    /// to set.
    pub threads: Option<NonZeroUsize>,
}

impl<'a> Run<'a> {
    /// A run watched by `progress` and stopped by `stop`, one thread per core.
    pub fn new(progress: &'a dyn Progress, stop: &'a AtomicBool) -> Self {
        Self {
            progress,
            stop,
            threads: None,
        }
    }

    /// The same run on `threads` worker threads.
    pub fn on(self, threads: Option<NonZeroUsize>) -> Self {
        Self { threads, ..self }
    }

    /// A run nobody watches, stopped by `stop`.
    pub fn silent(stop: &'a AtomicBool) -> Self {
        Self::new(&Silent, stop)
    }

    /// [`Stopped`] once the stop flag is set: a study calls it between its
    /// units of work.
    pub fn check(&self) -> anyhow::Result<()> {
        if self.stop.load(Ordering::SeqCst) {
            return Err(Stopped.into());
        }
        Ok(())
    }

    /// Runs `f` so that every run of the model it makes on this thread ends
    /// at its next step once the flag is set ([`rtw_model::cancellable`]);
    /// [`Stopped`] if it was set.
    pub fn cancellable<T>(&self, f: impl FnOnce() -> T) -> anyhow::Result<T> {
        rtw_model::cancellable(self.stop, f).ok_or_else(|| Stopped.into())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_set_flag_stops_the_run_and_a_clear_one_does_not() {
        let stop = AtomicBool::new(false);
        let run = Run::silent(&stop);
        assert!(run.check().is_ok());
        assert_eq!(run.cancellable(|| 7).unwrap(), 7);
        stop.store(true, Ordering::SeqCst);
        assert!(run.check().unwrap_err().downcast_ref::<Stopped>().is_some());
        let e = run.cancellable(|| 7).unwrap_err();
        assert!(e.downcast_ref::<Stopped>().is_some(), "{e:#}");
        let threads = NonZeroUsize::new(3);
        assert_eq!(run.on(threads).threads, threads);
    }
}
