//! The worker threads of a scan and what each of them needs: the pool (at
//! most `MAX_THREADS_PER_CORE` a core) and a sample's row, counted in the
//! progress.

use crate::config::count::count_usize;
use crate::io::scan_rows::Row;
use crate::scan::one::{Simulator, run_one};
use crate::scan::progress::Progress;
use crate::scan::sample::Sampler;
use anyhow::{Context, Result};
use rtw_model::Options;
use std::num::NonZeroUsize;
use std::sync::atomic::AtomicBool;

/// Most worker threads per core: more only adds switching (10 000 threads
/// took 98 s for 6 samples), and a huge count would start threads until the
/// system stops it.
pub(crate) const MAX_THREADS_PER_CORE: usize = 4;

/// The thread counts a pool accepts, `[1, MAX_THREADS_PER_CORE × cores]`,
/// and the note that says where the upper bound comes from.
fn thread_range() -> (std::ops::RangeInclusive<usize>, String) {
    let cores = std::thread::available_parallelism().map_or(1, NonZeroUsize::get);
    (
        1..=MAX_THREADS_PER_CORE * cores,
        format!(" ({MAX_THREADS_PER_CORE} per core, {cores} cores)"),
    )
}

/// A thread count given as text (`--threads`, Python's `threads`), in the
/// range every worker pool accepts; the error names it as `name`.
pub fn parse_threads(text: &str, name: &str) -> Result<NonZeroUsize> {
    let (range, note) = thread_range();
    let n = count_usize(name, text, range, &note)?;
    Ok(NonZeroUsize::new(n).expect("the range starts at 1"))
}

/// Refuses a thread count above `MAX_THREADS_PER_CORE` × the cores,
/// naming it as the caller spells it (`--threads`, Python's `threads`).
pub fn check_threads(threads: Option<NonZeroUsize>, name: &str) -> Result<()> {
    match threads {
        Some(n) => parse_threads(&n.to_string(), name).map(drop),
        None => Ok(()),
    }
}

/// A pool of `threads` workers (`None`: one per core). The cap of
/// [`check_threads`] is checked here, so that no caller can start more.
pub fn worker_pool(threads: Option<NonZeroUsize>) -> Result<rayon::ThreadPool> {
    check_threads(threads, "threads")?;
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads.map_or(0, NonZeroUsize::get))
        .build()
        .context("cannot start the worker threads")
}

/// Why a study (a basin slice, sensitivity indices) ended before its
/// result: its cancel flag was set (Ctrl-C in Python). Nothing was written.
#[derive(Debug)]
pub struct Stopped;

impl std::fmt::Display for Stopped {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("stopped before its end (its cancel flag was set): nothing was written")
    }
}

impl std::error::Error for Stopped {}

/// What every sample of a scan needs: its parameters, the options and the
/// simulator, the stop flag and the progress counts.
pub(crate) struct Jobs<'a> {
    pub(crate) sampler: &'a Sampler,
    pub(crate) options: &'a Options,
    pub(crate) sim: Simulator<'a>,
    pub(crate) stop: &'a AtomicBool,
    pub(crate) progress: &'a dyn Progress,
}

impl Jobs<'_> {
    /// The row of sample `id`, counted in the progress; `None` when `stop`
    /// was set while it ran: the stop reaches every run of the sample (the
    /// flat run and the robustness measures' many runs,
    /// [`rtw_model::cancellable`]), which ends at its next step, so a sample
    /// in flight stops within moments, and what it computed is dropped.
    pub(crate) fn row(&self, id: u64) -> Option<Row> {
        let row = rtw_model::cancellable(self.stop, || {
            run_one(id, self.sampler.params(id), self.options, self.sim)
        })?;
        self.progress.computed(row.label());
        Some(row)
    }
}
