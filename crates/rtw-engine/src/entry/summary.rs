//! A finished scan's summary ([`summary_to_files`]) and its failure
//! clusters ([`cluster`], with each failure's cluster written to a file).

use crate::analysis::assignments::AssignmentsWriter;
use crate::analysis::clusters::FailureClusters;
use crate::analysis::report;
use crate::files;
use crate::io::destination;
use crate::io::metadata::{FileKind, META_SCAN_HASH, META_SEED, META_VERSION, kv};
use crate::scan::lock::Lock;
use anyhow::{Context, Result, anyhow};
use std::path::Path;

pub use crate::analysis::report::{Summary, clusters_markdown};

/// Recomputes the summary of the scan file `samples` (`k` failure clusters,
/// default the config's `cluster.k`) and writes `summary.json` and
/// `summary.md` beside it; refuses, unless `force`, summaries there that are
/// another file's or not rtw-scan's (never a symlink or a special file).
pub fn summary_to_files(samples: &Path, k: Option<usize>, force: bool) -> Result<Summary> {
    let dir = samples
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    // The scan's own lock: no summary is written beside a scan being
    // written, and two summaries of one scan do not race.
    let _lock = Lock::for_result(samples, &format!("writing beside {}", samples.display()))?;
    report::check_summary_target(dir, samples, force)?;
    let summary = report::summarize(samples, k)?;
    report::write_summary(dir, &summary)?;
    Ok(summary)
}

/// A scan's failure clusters.
#[derive(Clone, Debug)]
pub struct Clusters {
    /// The number of clusters asked for.
    pub k: usize,
    /// The clustering; `None` when there are fewer failures than `k`.
    pub clusters: Option<FailureClusters>,
    /// The failed samples (collapse or stall).
    pub failures: usize,
}

/// Clusters the failed samples of the scan file `samples` (`k` clusters,
/// default the config's `cluster.k`); with `assignments`, also writes each
/// failure's cluster there (refused, unless `force`, over a file that is not
/// an assignments file or over the input; an error when there are fewer
/// failures than `k`).
pub fn cluster(
    samples: &Path,
    k: Option<usize>,
    assignments: Option<&Path>,
    force: bool,
) -> Result<Clusters> {
    let data = report::read_scan(samples)?;
    let k = k.unwrap_or(data.config.cluster.k as usize);
    let clusters = data.clusters(Some(k))?;
    let failures = data.failures.seen();
    if let Some(path) = assignments {
        let _lock = Lock::for_result(path, &format!("writing {}", path.display()))?;
        destination::check_destination(
            path,
            FileKind::Assignments,
            &[samples],
            "--assignments",
            force,
        )?;
        let fc = clusters.as_ref().ok_or_else(|| {
            anyhow!(
                "--assignments: {failures} failed samples (collapse or stall) in {}, fewer than k = {k}: nothing to cluster",
                samples.display()
            )
        })?;
        let meta = vec![
            kv(META_VERSION, crate::io::metadata::VERSION.into()),
            kv(META_SEED, data.config.seed.to_string()),
            kv(META_SCAN_HASH, data.content_hash.clone()),
        ];
        files::remove_stray_temps(path)?;
        let written = || -> Result<()> {
            let mut w = AssignmentsWriter::create(path, fc, meta)?;
            data.for_each_assigned(fc, |f, c| w.write(f, c))?;
            w.finish()
        };
        written().with_context(|| format!("--assignments {}", path.display()))?;
    }
    Ok(Clusters {
        k,
        clusters,
        failures,
    })
}
