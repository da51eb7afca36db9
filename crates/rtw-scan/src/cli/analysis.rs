//! `cluster` and `summary`: a finished scan's failure clusters and summary.

use crate::analysis::assignments::AssignmentsWriter;
use crate::analysis::report::{self, clusters_markdown};
use crate::files;
use crate::io::destination;
use crate::io::metadata::{FileKind, META_SCAN_HASH, META_SEED, META_VERSION, kv};
use anyhow::{Context, Result, anyhow};
use clap::Args;
use std::num::NonZeroUsize;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(Args, Debug)]
pub(super) struct ClusterArgs {
    /// A samples.parquet written by `rtw-scan run`.
    samples: PathBuf,
    /// Number of clusters [default: the config's cluster.k].
    #[arg(long, value_parser = super::values::positive)]
    k: Option<NonZeroUsize>,
    /// Print JSON instead of a table.
    #[arg(long)]
    json: bool,
    /// Also write each failed sample's cluster to this Parquet file (sample_id, cluster, cluster_name,
    /// outcome, alpha, fn, phi; the clustering as JSON in its `rtw.clusters` metadata).
    #[arg(long, value_name = "FILE.parquet")]
    assignments: Option<PathBuf>,
    /// Write the assignments even over a file that is not an assignments file (or over the input).
    #[arg(long)]
    force: bool,
}

#[derive(Args, Debug)]
pub(super) struct SummaryArgs {
    /// A samples.parquet written by `rtw-scan run`.
    samples: PathBuf,
    /// Number of failure clusters [default: the config's cluster.k].
    #[arg(long, value_parser = super::values::positive)]
    k: Option<NonZeroUsize>,
    /// Print the summary as JSON (what summary.json holds) instead of Markdown.
    #[arg(long)]
    json: bool,
    /// Write summary.json and summary.md even when they are another file's summary or not rtw-scan's
    /// (never over a symlink or a special file).
    #[arg(long)]
    force: bool,
}

pub(super) fn cmd_cluster(a: ClusterArgs) -> Result<ExitCode> {
    let data = report::read_scan(&a.samples)?;
    let k =
        a.k.map_or(data.config.cluster.k as usize, NonZeroUsize::get);
    let clusters = data.clusters(Some(k))?;
    let failures = data.failures.seen();
    if let Some(path) = &a.assignments {
        destination::check_destination(
            path,
            FileKind::Assignments,
            &[&a.samples],
            "--assignments",
            a.force,
        )?;
        let fc = clusters.as_ref().ok_or_else(|| {
            anyhow!(
                "--assignments: {failures} failed samples (collapse or stall) in {}, fewer than k = {k}: nothing to cluster",
                a.samples.display()
            )
        })?;
        let meta = vec![
            kv(META_VERSION, env!("CARGO_PKG_VERSION").into()),
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
    if a.json {
        println!("{}", serde_json::to_string_pretty(&clusters)?);
    } else {
        print!("{}", clusters_markdown(k, clusters.as_ref(), failures));
    }
    Ok(ExitCode::SUCCESS)
}

pub(super) fn cmd_summary(a: SummaryArgs) -> Result<ExitCode> {
    let dir = a
        .samples
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    report::check_summary_target(dir, &a.samples, a.force)?;
    let summary = report::summarize(&a.samples, a.k.map(NonZeroUsize::get))?;
    report::write_summary(dir, &summary)?;
    if a.json {
        println!("{}", serde_json::to_string_pretty(&summary)?);
    } else {
        print!("{}", summary.to_markdown());
    }
    Ok(ExitCode::SUCCESS)
}
