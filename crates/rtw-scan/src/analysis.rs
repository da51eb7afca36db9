//! `cluster` and `summary`: a finished scan's failure clusters and summary.
//! The studies are the library's ([`rtw_engine::entry::summary`]); this parses
//! and prints.

use anyhow::Result;
use clap::Args;
use rtw_engine::entry::summary;
use std::num::NonZeroUsize;
use std::path::PathBuf;
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
    let c = summary::cluster(
        &a.samples,
        a.k.map(NonZeroUsize::get),
        a.assignments.as_deref(),
        a.force,
    )?;
    if a.json {
        outln!("{}", serde_json::to_string_pretty(&c.clusters)?);
    } else {
        out!(
            "{}",
            summary::clusters_markdown(c.k, c.clusters.as_ref(), c.failures)
        );
    }
    Ok(ExitCode::SUCCESS)
}

pub(super) fn cmd_summary(a: SummaryArgs) -> Result<ExitCode> {
    let summary = summary::summary_to_files(&a.samples, a.k.map(NonZeroUsize::get), a.force)?;
    if a.json {
        outln!("{}", serde_json::to_string_pretty(&summary)?);
    } else {
        out!("{}", summary.to_markdown());
    }
    Ok(ExitCode::SUCCESS)
}
