//! A whole scan in memory ([`scan_batch`], Python's `rtw.scan`): the rows
//! `rtw-scan run` writes, computed in parallel and returned as one batch.

use crate::config::ScanConfig;
use crate::io::metadata::{self, META_WALL_TIME};
use crate::io::scan_rows::{self, Row};
use crate::scan::one::Simulator;
use crate::scan::progress::Progress;
use crate::scan::sample::Sampler;
use crate::scan::workers::{Jobs, worker_pool};
use anyhow::{Result, anyhow, bail};
use arrow_array::RecordBatch;
use rayon::prelude::*;
use std::num::NonZeroUsize;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

/// The rows of the first `n` sample ids, computed in parallel on `pool`, in
/// id order, each reported to `jobs.progress` as it comes in; `None` once `stop` is
/// set (the rows in flight stop at their runs' next step, the rest are skipped). The rows' memory
/// is reserved first: an allocation that cannot be made is an error
/// ([`std::collections::TryReserveError`] in its chain), not an abort.
fn compute_rows(pool: &rayon::ThreadPool, n: usize, jobs: &Jobs<'_>) -> Result<Option<Vec<Row>>> {
    let mut results: Vec<Option<Row>> = Vec::new();
    results
        .try_reserve_exact(n)
        .map_err(|e| anyhow!(e).context(format!("cannot hold the scan's {n} rows in memory")))?;
    pool.install(|| {
        (0..n)
            .into_par_iter()
            .map(|i| {
                if jobs.stop.load(Ordering::SeqCst) {
                    None
                } else {
                    jobs.row(i as u64)
                }
            })
            .collect_into_vec(&mut results)
    });
    Ok(results.into_iter().collect())
}

/// Most rows [`scan_batch`] holds in memory (about 1 kB each with their
/// table): `rtw.scan` of more is refused, up front, with the way to run it
/// (`rtw-scan run`, which streams the rows to a file), rather than fail
/// part way or abort the interpreter when memory runs out.
pub const MAX_BATCH_ROWS: u64 = 1_000_000;

/// A whole scan computed in memory, as `rtw.scan` does from Python: the
/// rows `rtw-scan run` writes to `samples.parquet` (same per-sample code,
/// same values but `wall_time_s`), as one batch whose schema carries the
/// file's metadata (config, its hash, version, seed, variant, wall time).
/// `progress` watches the rows come in (an [`std::sync::atomic::AtomicU64`]
/// counts them, for a progress display).
/// `Ok(None)` when `stop` was set before the last row was computed. A scan
/// of more than `MAX_BATCH_ROWS` (10⁶) rows is refused.
pub fn scan_batch(
    cfg: &ScanConfig,
    threads: Option<NonZeroUsize>,
    stop: &AtomicBool,
    progress: &dyn Progress,
) -> Result<Option<RecordBatch>> {
    let total = cfg.total_rows()?;
    if total > MAX_BATCH_ROWS {
        bail!(
            "samples: {total} rows is more than a scan in memory may have: at most {MAX_BATCH_ROWS} \
             (about 1 GB); run a larger scan with `rtw-scan run CONFIG --out DIR`, which streams its \
             rows to DIR/samples.parquet, and read that file (polars.scan_parquet reads it lazily)"
        );
    }
    let pool = worker_pool(threads)?;
    let started = Instant::now();
    progress.start(total);
    let sim: Simulator = &rtw_model::simulate;
    let jobs = Jobs {
        sampler: &Sampler::new(cfg),
        options: &cfg.simulation,
        sim,
        stop,
        progress,
    };
    let Some(rows) = compute_rows(&pool, total as usize, &jobs)? else {
        progress.finish(false);
        return Ok(None);
    };
    progress.finish(true);
    let mut meta = metadata::scan_metadata(cfg);
    meta.push(metadata::kv(
        META_WALL_TIME,
        started.elapsed().as_secs_f64().to_string(),
    ));
    let batch = scan_rows::to_batch(&rows, &cfg.simulation.robustness);
    Ok(Some(metadata::with_metadata(batch, meta)?))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::parse;
    use crate::scan::fixtures::CFG;
    use std::sync::atomic::AtomicU64;

    #[test]
    fn scan_batch_refuses_more_rows_than_memory_holds_naming_the_cli() {
        let n = MAX_BATCH_ROWS + 1;
        let cfg = parse(&CFG.replace("samples = 37", &format!("samples = {n}"))).unwrap();
        let never = AtomicBool::new(false);
        let done = AtomicU64::new(0);
        let e = scan_batch(&cfg, None, &never, &done)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains(&format!("{n} rows")) && e.contains("rtw-scan run"),
            "{e}"
        );
        assert_eq!(done.load(Ordering::SeqCst), 0);
    }
}
