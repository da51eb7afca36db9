//! The worker threads of a scan and what each of them needs: the pool (at
//! most [`MAX_THREADS_PER_CORE`] a core) and a sample's row, counted in the
//! progress.

use crate::io::scan_rows::Row;
use crate::scan::one::{Simulator, run_one};
use crate::scan::progress::Progress;
use crate::scan::sample::Sampler;
use anyhow::{Context, Result, bail};
use rtw_model::Options;
use std::num::NonZeroUsize;
use std::sync::atomic::AtomicBool;

/// Most worker threads per core accepted by `--threads`: more only adds
/// switching (10 000 threads took 98 s for 6 samples), and a huge count
/// would start threads until the system stops it.
pub(crate) const MAX_THREADS_PER_CORE: usize = 4;

/// Refuses a thread count above [`MAX_THREADS_PER_CORE`] × the cores,
/// naming it as the caller spells it (`--threads`, Python's `threads`).
pub(crate) fn check_threads(threads: Option<NonZeroUsize>, name: &str) -> Result<()> {
    let cores = std::thread::available_parallelism().map_or(1, NonZeroUsize::get);
    let cap = MAX_THREADS_PER_CORE * cores;
    match threads {
        Some(n) if n.get() > cap => bail!(
            "{name}: {n} is invalid: must be at most {cap} ({MAX_THREADS_PER_CORE} per core, {cores} cores)"
        ),
        _ => Ok(()),
    }
}

/// A pool of `threads` workers (`None`: one per core).
pub(crate) fn worker_pool(threads: Option<NonZeroUsize>) -> Result<rayon::ThreadPool> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads.map_or(0, NonZeroUsize::get))
        .build()
        .context("cannot start the worker threads")
}

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
