//! The summary of a finished scan: outcome shares with 95 % Wilson intervals,
//! the article's numbers beside them for the paper scan, failure clusters,
//! timing and the model variant — as `summary.json`, `summary.md` and the
//! printed table.
//!
//! Everything is computed from `samples.parquet` alone (its rows and the
//! config stored in its metadata), so `rtw-scan summary FILE` and the end of
//! `rtw-scan run` are the same code.

use crate::cluster::{Failure, FailureClusters, cluster_failures};
use crate::config::{self, ScanConfig, Variant};
use crate::output::{self, META_CONFIG, META_VERSION, META_WALL_TIME, write_atomic};
use anyhow::{Context, Result, anyhow};
use rtw_model::Label;
use serde::Serialize;
use std::fmt::Write as _;
use std::path::Path;

/// z for a two-sided 95 % interval.
const Z95: f64 = 1.959_963_984_540_054;

/// The article's shares for the 1000-sample scan (supplementary, Section 2),
/// in % of all samples.
pub const PAPER_STABLE: f64 = 73.7;
pub const PAPER_SKIP: f64 = 35.9;
pub const PAPER_WALK: f64 = 32.0;
pub const PAPER_CRAWL: f64 = 5.8;

/// Wilson score interval of a binomial proportion `k / n`, as fractions.
pub fn wilson(k: u64, n: u64, z: f64) -> (f64, f64) {
    if n == 0 {
        return (0.0, 1.0);
    }
    let n = n as f64;
    let p = k as f64 / n;
    let z2 = z * z;
    let denom = 1.0 + z2 / n;
    let centre = (p + z2 / (2.0 * n)) / denom;
    let half = z / denom * (p * (1.0 - p) / n + z2 / (4.0 * n * n)).sqrt();
    ((centre - half).max(0.0), (centre + half).min(1.0))
}

/// A share of all samples.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Share {
    pub outcome: String,
    pub count: u64,
    /// % of all samples.
    pub percent: f64,
    /// 95 % Wilson score interval, in %.
    pub ci95: [f64; 2],
    /// The article's value, in % (paper scan only).
    pub paper_percent: Option<f64>,
}

impl Share {
    fn new(outcome: &str, count: u64, n: u64, paper: Option<f64>) -> Self {
        let (lo, hi) = wilson(count, n, Z95);
        Self {
            outcome: outcome.into(),
            count,
            percent: 100.0 * count as f64 / n.max(1) as f64,
            ci95: [100.0 * lo, 100.0 * hi],
            paper_percent: paper,
        }
    }
}

/// What a summary is made from: the stored config and one pass over the rows.
pub struct ScanData {
    pub config: ScanConfig,
    pub version: String,
    pub rows: u64,
    /// Rows per label, in [`Label::ALL`] order.
    pub counts: [u64; 6],
    pub failures: Vec<Failure>,
    /// Sum of the per-sample wall times.
    pub sample_time_s: f64,
    /// Elapsed time of the run (summed over resumed sessions), when recorded.
    pub wall_time_s: Option<f64>,
}

/// Reads a scan's Parquet file: stored config, label counts, failures.
pub fn read_scan(path: &Path) -> Result<ScanData> {
    let input = output::open(path, 4096)?;
    let text = input.metadata.get(META_CONFIG).ok_or_else(|| {
        anyhow!(
            "{} has no `{META_CONFIG}` metadata: not written by rtw-scan run",
            path.display()
        )
    })?;
    let config =
        config::parse(text).with_context(|| format!("the config stored in {}", path.display()))?;
    let mut data = ScanData {
        config,
        version: input
            .metadata
            .get(META_VERSION)
            .cloned()
            .unwrap_or_default(),
        rows: 0,
        counts: [0; 6],
        failures: Vec::new(),
        sample_time_s: 0.0,
        wall_time_s: input
            .metadata
            .get(META_WALL_TIME)
            .and_then(|v| v.parse().ok()),
    };
    for batch in input.reader {
        let batch = batch.with_context(|| format!("reading {}", path.display()))?;
        let ctx = || format!("{}", path.display());
        let labels = output::label_column(&batch).with_context(ctx)?;
        let sample_id = output::i64_column(&batch, "sample_id").with_context(ctx)?;
        let alpha = output::f64_column(&batch, "alpha").with_context(ctx)?;
        let f_n = output::f64_column(&batch, "fn").with_context(ctx)?;
        let phi = output::f64_column(&batch, "phi").with_context(ctx)?;
        let wall = output::f64_column(&batch, "wall_time_s").with_context(ctx)?;
        for (i, label) in labels.into_iter().enumerate() {
            let li = output::label_index(label);
            data.counts[li] += 1;
            if label.is_failure() {
                data.failures.push(Failure {
                    sample_id: sample_id.value(i) as u64,
                    alpha: alpha.value(i),
                    f_n: f_n.value(i),
                    phi: phi.value(i),
                    label,
                });
            }
            data.sample_time_s += wall.value(i);
        }
        data.rows += batch.num_rows() as u64;
    }
    Ok(data)
}

impl ScanData {
    /// k-means of the failures with `k` (default: the config's).
    pub fn clusters(&self, k: Option<usize>) -> Option<FailureClusters> {
        let k = k.unwrap_or(self.config.cluster.k as usize);
        cluster_failures(
            &self.failures,
            k,
            self.config.seed,
            self.config.cluster.restarts as usize,
        )
    }
}

/// The summary of one scan.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Summary {
    pub name: Option<String>,
    pub file: String,
    pub version: String,
    pub seed: u64,
    pub samples: u64,
    pub variant: Variant,
    /// Whether this is the article's scan (its numbers are then given beside ours).
    pub paper_scan: bool,
    /// Per label: skip, walk, crawl, collapse, stall, diverged.
    pub outcomes: Vec<Share>,
    /// skip + walk + crawl.
    pub stable: Share,
    /// collapse + stall.
    pub failed: Share,
    pub cluster_k: usize,
    /// `None` when there are fewer failures than clusters.
    pub clusters: Option<FailureClusters>,
    pub wall_time_s: Option<f64>,
    pub samples_per_s: Option<f64>,
    pub sample_time_s: f64,
}

/// Summarizes a scan file (`k` overrides the config's cluster count).
pub fn summarize(path: &Path, k: Option<usize>) -> Result<Summary> {
    let data = read_scan(path)?;
    let n = data.rows;
    let paper = data.config.is_paper_scan();
    let paper_value = |v: f64| paper.then_some(v);
    let outcomes = Label::ALL
        .iter()
        .zip(data.counts)
        .map(|(l, c)| {
            let p = match l {
                Label::Skip => paper_value(PAPER_SKIP),
                Label::Walk => paper_value(PAPER_WALK),
                Label::Crawl => paper_value(PAPER_CRAWL),
                _ => None,
            };
            Share::new(l.as_str(), c, n, p)
        })
        .collect();
    let count = |f: fn(Label) -> bool| -> u64 {
        Label::ALL
            .iter()
            .zip(data.counts)
            .filter(|(l, _)| f(**l))
            .map(|(_, c)| c)
            .sum()
    };
    let stable = Share::new(
        "stable",
        count(Label::is_stable),
        n,
        paper_value(PAPER_STABLE),
    );
    let failed = Share::new(
        "failed",
        count(Label::is_failure),
        n,
        paper_value(100.0 - PAPER_STABLE),
    );
    let cluster_k = k.unwrap_or(data.config.cluster.k as usize);
    Ok(Summary {
        name: data.config.name.clone(),
        file: path.display().to_string(),
        version: data.version.clone(),
        seed: data.config.seed,
        samples: n,
        variant: Variant::of(&data.config.simulation),
        paper_scan: paper,
        outcomes,
        stable,
        failed,
        cluster_k,
        clusters: data.clusters(Some(cluster_k)),
        wall_time_s: data.wall_time_s,
        samples_per_s: data.wall_time_s.filter(|w| *w > 0.0).map(|w| n as f64 / w),
        sample_time_s: data.sample_time_s,
    })
}

/// Writes `summary.json` and `summary.md` into `dir`.
pub fn write_summary(dir: &Path, summary: &Summary) -> Result<()> {
    write_atomic(
        &dir.join("summary.json"),
        serde_json::to_string_pretty(summary)?.as_bytes(),
    )?;
    write_atomic(&dir.join("summary.md"), summary.to_markdown().as_bytes())
}

fn share_row(s: &Share, paper: bool, bold: bool) -> String {
    let name = if bold {
        format!("**{}**", s.outcome)
    } else {
        s.outcome.clone()
    };
    let mut row = format!(
        "| {name} | {} | {:.1} | {:.1}–{:.1} |",
        s.count, s.percent, s.ci95[0], s.ci95[1]
    );
    if paper {
        match s.paper_percent {
            Some(p) => write!(row, " {p:.1} |").unwrap(),
            None => row.push_str(" – |"),
        }
    }
    row
}

/// The cluster table in Markdown.
pub fn clusters_markdown(k: usize, clusters: Option<&FailureClusters>, failures: usize) -> String {
    let Some(fc) = clusters else {
        return format!(
            "## Failure clusters\n\nNot computed: {failures} failed samples (collapse or stall), fewer than k = {k}.\n"
        );
    };
    let sil = fc.silhouette.map_or("–".into(), |s| format!("{s:.3}"));
    let mut md = format!(
        "## Failure clusters\n\nk-means (k = {}) on standardized (α, f_n, φ) of the {} failed samples; silhouette {sil}.\n\n\
         | cluster | name | size | α | f_n [Hz] | φ [rad] | collapse | stall |\n|---:|---|---:|---:|---:|---:|---:|---:|\n",
        fc.k, fc.failures
    );
    for (i, c) in fc.clusters.iter().enumerate() {
        writeln!(
            md,
            "| {} | {} | {} | {:.3} | {:.3} | {:.3} | {} | {} |",
            i + 1,
            c.name,
            c.size,
            c.alpha,
            c.f_n,
            c.phi,
            c.collapse,
            c.stall
        )
        .unwrap();
    }
    md
}

impl Summary {
    /// The summary as Markdown (also what `run` and `summary` print).
    pub fn to_markdown(&self) -> String {
        let mut md = String::new();
        let dir_name = Path::new(&self.file)
            .parent()
            .and_then(|d| d.file_name())
            .map(|d| d.to_string_lossy().into_owned());
        let title = self
            .name
            .clone()
            .or(dir_name)
            .unwrap_or_else(|| "scan".into());
        writeln!(md, "# rtw-scan summary: {title}\n").unwrap();
        writeln!(md, "- file: `{}`", self.file).unwrap();
        writeln!(
            md,
            "- samples: {} (seed {}), rtw-scan {}",
            self.samples, self.seed, self.version
        )
        .unwrap();
        writeln!(md, "- model variant: {}", self.variant).unwrap();
        match (self.wall_time_s, self.samples_per_s) {
            (Some(w), Some(r)) => writeln!(
                md,
                "- wall time: {w:.1} s ({r:.2} samples/s); summed sample time {:.1} s",
                self.sample_time_s
            ),
            _ => writeln!(md, "- summed sample time {:.1} s", self.sample_time_s),
        }
        .unwrap();
        md.push('\n');
        md.push_str("| outcome | count | % of all | 95 % CI |");
        if self.paper_scan {
            md.push_str(" paper % |");
        }
        md.push_str("\n|---|---:|---:|---|");
        if self.paper_scan {
            md.push_str("---:|");
        }
        md.push('\n');
        for s in &self.outcomes {
            writeln!(md, "{}", share_row(s, self.paper_scan, false)).unwrap();
        }
        writeln!(md, "{}", share_row(&self.stable, self.paper_scan, true)).unwrap();
        writeln!(md, "{}", share_row(&self.failed, self.paper_scan, true)).unwrap();
        md.push('\n');
        md.push_str("95 % CI: Wilson score interval. Stable = skip + walk + crawl; failed = collapse + stall.\n");
        if self.paper_scan {
            writeln!(
                md,
                "Paper: supplementary Section 2 ({PAPER_STABLE} % stable; skip {PAPER_SKIP}, walk {PAPER_WALK}, \
                 crawl {PAPER_CRAWL} % of all samples; failed = 100 − {PAPER_STABLE})."
            )
            .unwrap();
        }
        let diverged = self
            .outcomes
            .iter()
            .find(|s| s.outcome == "diverged")
            .map_or(0, |s| s.count);
        if diverged > 0 {
            writeln!(
                md,
                "**{diverged} diverged** sample(s): numerical failures or panics (see the `failure` and `message` \
                 columns). They count in the denominator and are defects, not outcomes."
            )
            .unwrap();
        }
        md.push('\n');
        let failures = self.failed.count as usize;
        md.push_str(&clusters_markdown(
            self.cluster_k,
            self.clusters.as_ref(),
            failures,
        ));
        md
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wilson_known_values() {
        let (lo, hi) = wilson(5, 10, Z95);
        assert!(
            (lo - 0.236_593).abs() < 1e-5 && (hi - 0.763_407).abs() < 1e-5,
            "{lo} {hi}"
        );
        let (lo, hi) = wilson(0, 10, Z95);
        assert_eq!(lo, 0.0);
        assert!((hi - 0.277_533).abs() < 1e-5, "{hi}");
        let (lo, hi) = wilson(737, 1000, Z95);
        assert!(
            (lo - 0.708_8).abs() < 1e-3 && (hi - 0.763_8).abs() < 1e-3,
            "{lo} {hi}"
        );
    }
}
