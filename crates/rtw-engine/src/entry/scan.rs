//! A scan as a study: its outputs checked before any work
//! ([`check_outputs`]), its rows run or resumed ([`run_scan`]), a sharded
//! scan's parts joined ([`merge`]), and then a whole scan's summary
//! written beside it ([`write_summary`]).

use crate::analysis::report::{self, Summary};
use crate::config::ScanConfig;
use crate::files;
use crate::scan::checkpoint::Layout;
use crate::scan::shard::merge_parts;
use crate::scan::space;
use anyhow::Result;
use std::path::Path;

pub use crate::scan::run::{DEFAULT_CHUNK_SIZE, RunSettings, RunStatus, run_scan};
pub use crate::scan::shard::{Merged, Shard};

/// Before any work: the files a run writes (its rows, and for a whole scan
/// `summary.json` and `summary.md`) are not symlinks or special files, the
/// summaries there are rtw-scan's own, and the output fits on the disk
/// (these two unless `force`).
pub fn check_outputs(
    cfg: &ScanConfig,
    out: &Path,
    shard: Option<Shard>,
    force: bool,
) -> Result<()> {
    let layout = Layout::new(out, shard);
    files::refuse_special(&layout.samples, "--out")?;
    if shard.is_none() {
        report::check_summary_target(out, &layout.samples, force)?;
    }
    if !force {
        let total = cfg.total_rows()?;
        let ids = shard.map_or(Ok(0..total), |s| s.ids(total))?;
        space::check_free_space(ids.end - ids.start, out, &layout.partial)?;
    }
    Ok(())
}

/// The end of a whole scan (a run, a merge): `summary.json` and
/// `summary.md` written into `dir`, beside the scan file `samples`; returns
/// the summary.
pub fn write_summary(dir: &Path, samples: &Path) -> Result<Summary> {
    let summary = report::summarize(samples, None)?;
    report::write_summary(dir, &summary)?;
    Ok(summary)
}

/// Joins the shards `dir/part-K.parquet` into `dir/samples.parquet`
/// (checked as one scan's every shard, refused otherwise, see
/// `rtw-scan merge --help`); refuses first, unless `force`, summaries in
/// `dir` that are not this scan's, so that [`write_summary`] can follow.
pub fn merge(dir: &Path, force: bool) -> Result<Merged> {
    let samples = dir.join("samples.parquet");
    files::refuse_special(&samples, "")?;
    report::check_summary_target(dir, &samples, force)?;
    merge_parts(dir, force)
}
