//! The summary of a finished scan: outcome shares with 95 % Wilson intervals,
//! the article's numbers beside them for the paper scan, failure clusters,
//! timing and the model variant — as `summary.json`, `summary.md` and the
//! printed table.
//!
//! Everything is computed from `samples.parquet` alone (its rows and the
//! config stored in its metadata), so `rtw-scan summary FILE` and the end of
//! `rtw-scan run` are the same code.

use crate::analysis::clusters::{
    CLUSTER_MAX_POINTS, ClusterTally, Failure, FailureClusters, FailureSample, cluster_failures,
};
use crate::config::variant::ModelChoices;
use crate::config::{self, ScanConfig};
use crate::files::{self, FileSet};
use crate::io::destination::SUMMARY_MAX_BYTES;
use crate::io::metadata::{
    META_CONFIG, META_CONTENT_HASH, META_REFINE, META_VERSION, META_WALL_TIME,
};
use crate::io::parquet::{self, READ_BATCH_ROWS};
use crate::io::scan_files;
use crate::io::scan_rows::label_index;
use crate::io::table::{f64_column, i64_column, label_column};
use anyhow::{Context, Result, anyhow, bail};
use arrow_array::RecordBatch;
use rtw_model::Label;
use serde::Serialize;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// z for a two-sided 95 % interval.
pub const Z95: f64 = 1.959_963_984_540_054;

/// The article's shares for the 1000-sample scan (supplementary, Section 2),
/// in % of all samples.
pub(crate) const PAPER_STABLE: f64 = 73.7;
pub(crate) const PAPER_SKIP: f64 = 35.9;
pub(crate) const PAPER_WALK: f64 = 32.0;
pub(crate) const PAPER_CRAWL: f64 = 5.8;

/// Wilson score interval of a binomial proportion `k / n`, as fractions,
/// at the normal quantile `z` ([`Z95`]: 95 %); `(0, 1)` when `n` is 0.
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
pub(crate) struct Share {
    pub(crate) outcome: String,
    pub(crate) count: u64,
    /// % of all samples.
    pub(crate) percent: f64,
    /// 95 % Wilson score interval, in %.
    pub(crate) ci95: [f64; 2],
    /// The article's value, in % (paper scan only).
    pub(crate) paper_percent: Option<f64>,
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

/// What a summary is made from: the stored config and one pass over the
/// rows. Its size does not grow with the scan: the failures are kept as a
/// bounded sample ([`FailureSample`], at most [`CLUSTER_MAX_POINTS`]), and a
/// clustering of a sample counts every failure in a second pass over the file.
pub(crate) struct ScanData {
    pub(crate) path: PathBuf,
    pub(crate) config: ScanConfig,
    pub(crate) version: String,
    /// Its `rtw.content_hash`: what an assignments file records of its scan.
    pub(crate) content_hash: String,
    pub(crate) rows: u64,
    /// Rows per label, in [`Label::ALL`] order.
    pub(crate) counts: [u64; 6],
    /// The failures k-means runs on: all of them when they fit, else a
    /// seeded random sample (seeded with the scan seed).
    pub(crate) failures: FailureSample,
    /// Sum of the per-sample wall times.
    pub(crate) sample_time_s: f64,
    /// Elapsed time of the run (summed over resumed sessions), when recorded.
    pub(crate) wall_time_s: Option<f64>,
    /// A refine's combined file: its added samples are not draws from the
    /// inputs' distribution.
    pub(crate) refined: bool,
}

/// The failures (collapse, stall) among a batch's rows; `labels` is its
/// decoded `outcome` column.
fn batch_failures(batch: &RecordBatch, labels: &[Label]) -> Result<Vec<Failure>> {
    let sample_id = i64_column(batch, "sample_id")?;
    let alpha = f64_column(batch, "alpha")?;
    let f_n = f64_column(batch, "fn")?;
    let phi = f64_column(batch, "phi")?;
    Ok(labels
        .iter()
        .enumerate()
        .filter(|(_, l)| l.is_failure())
        .map(|(i, label)| Failure {
            sample_id: sample_id.value(i) as u64,
            alpha: alpha.value(i),
            f_n: f_n.value(i),
            phi: phi.value(i),
            label: *label,
        })
        .collect())
}

/// Whether a scan's rows (its metadata's `keys` and its stored config) are
/// a refinement's: a refine's combined file (`rtw.refine`) or one of its
/// rounds (whose config stores the points chosen near the label changes).
/// Their shares are not the box's, and they are not draws for Sobol indices.
pub fn holds_refined_rows<'a>(
    mut keys: impl Iterator<Item = &'a String>,
    config: &ScanConfig,
) -> bool {
    keys.any(|k| k == META_REFINE) || config.points.is_some()
}

/// Opens a scan's Parquet file and parses the config stored in it.
pub fn open_scan(path: &Path) -> Result<(parquet::ParquetInput, ScanConfig)> {
    let input = parquet::open(path, READ_BATCH_ROWS)?;
    let text = input.metadata.get(META_CONFIG).ok_or_else(|| {
        anyhow!(
            "{} has no `{META_CONFIG}` metadata: not written by rtw-scan run",
            path.display()
        )
    })?;
    let config =
        config::parse(text).with_context(|| format!("the config stored in {}", path.display()))?;
    Ok((input, config))
}

/// Reads a scan's Parquet file: stored config, label counts, failures.
pub(crate) fn read_scan(path: &Path) -> Result<ScanData> {
    let (input, config) = open_scan(path)?;
    let refined = holds_refined_rows(input.metadata.keys(), &config);
    let mut data = ScanData {
        path: path.to_path_buf(),
        failures: FailureSample::new(CLUSTER_MAX_POINTS, config.seed),
        config,
        version: input
            .metadata
            .get(META_VERSION)
            .cloned()
            .unwrap_or_default(),
        content_hash: input
            .metadata
            .get(META_CONTENT_HASH)
            .cloned()
            .unwrap_or_default(),
        rows: 0,
        counts: [0; 6],
        sample_time_s: 0.0,
        wall_time_s: input
            .metadata
            .get(META_WALL_TIME)
            .and_then(|v| v.parse().ok()),
        refined,
    };
    let mut next_id = None;
    for batch in input.reader {
        let batch = batch.with_context(|| format!("reading {}", path.display()))?;
        let ctx = || format!("{}", path.display());
        scan_files::check_scan_values(&batch, path, data.rows)?;
        next_id = scan_files::check_ids(&batch, path, data.rows, next_id)?;
        let labels = label_column(&batch).with_context(ctx)?;
        let wall = f64_column(&batch, "wall_time_s").with_context(ctx)?;
        for (i, label) in labels.iter().enumerate() {
            data.counts[label_index(*label)] += 1;
            data.sample_time_s += wall.value(i);
        }
        for f in batch_failures(&batch, &labels).with_context(ctx)? {
            data.failures.push(f);
        }
        data.rows += batch.num_rows() as u64;
    }
    Ok(data)
}

impl ScanData {
    /// k-means of the failures with `k` (default: the config's); sizes and
    /// cross-table count every failure, also when k-means ran on a sample.
    pub(crate) fn clusters(&self, k: Option<usize>) -> Result<Option<FailureClusters>> {
        let k = k.unwrap_or(self.config.cluster.k as usize);
        let points = self.failures.points();
        if self.failures.is_subset() && k > points.len() {
            bail!(
                "k = {k} clusters is more than the {} failures k-means is run on (a random sample of the {}); \
                 use k <= {}",
                points.len(),
                self.failures.seen(),
                points.len()
            );
        }
        let Some(mut fc) = cluster_failures(
            &points,
            k,
            self.config.seed,
            self.config.cluster.restarts as usize,
        ) else {
            return Ok(None);
        };
        if self.failures.is_subset() {
            let mut tally = ClusterTally::new(k);
            self.for_each_assigned(&fc, |failures, clusters| {
                for (f, c) in failures.iter().zip(clusters) {
                    tally.add(*c, f.label);
                }
                Ok(())
            })?;
            fc.set_counts(&tally, self.failures.seen(), points.len());
        }
        Ok(Some(fc))
    }

    /// Calls `visit` with every failure of the scan and its cluster in `fc`
    /// (made by [`ScanData::clusters`]), batch by batch in `sample_id`
    /// order: k-means' own assignment when it saw every failure, else each
    /// failure's nearest centre, in a second pass over the file.
    pub(crate) fn for_each_assigned(
        &self,
        fc: &FailureClusters,
        mut visit: impl FnMut(&[Failure], &[usize]) -> Result<()>,
    ) -> Result<()> {
        if !self.failures.is_subset() {
            return visit(&self.failures.points(), &fc.assignment);
        }
        let input = parquet::open(&self.path, READ_BATCH_ROWS)?;
        for batch in input.reader {
            let ctx = || format!("{}", self.path.display());
            let batch = batch.with_context(ctx)?;
            let labels = label_column(&batch).with_context(ctx)?;
            let failures = batch_failures(&batch, &labels).with_context(ctx)?;
            let clusters: Vec<usize> = failures.iter().map(|f| fc.cluster_of(f)).collect();
            visit(&failures, &clusters)?;
        }
        Ok(())
    }
}

/// Every failure of the scan file at `path` with its cluster (an index into
/// its summary's `clusters`), in `sample_id` order, as `rtw-scan cluster
/// --assignments` writes them: the config's k, seed and restarts. `None`
/// when there are fewer failures than k.
pub fn failure_clusters(path: &Path) -> Result<Option<Vec<(u64, usize)>>> {
    let data = read_scan(path)?;
    let Some(fc) = data.clusters(None)? else {
        return Ok(None);
    };
    let mut out = Vec::new();
    data.for_each_assigned(&fc, |failures, clusters| {
        out.extend(
            failures
                .iter()
                .zip(clusters)
                .map(|(f, c)| (f.sample_id, *c)),
        );
        Ok(())
    })?;
    Ok(Some(out))
}

/// The summary of one scan.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Summary {
    pub(crate) name: Option<String>,
    pub(crate) file: String,
    pub(crate) version: String,
    pub(crate) seed: u64,
    pub(crate) samples: u64,
    pub(crate) variant: ModelChoices,
    /// Whether this is the article's scan (its numbers are then given beside ours).
    pub(crate) paper_scan: bool,
    /// Per label: skip, walk, crawl, collapse, stall, diverged.
    pub(crate) outcomes: Vec<Share>,
    /// skip + walk + crawl.
    pub(crate) stable: Share,
    /// collapse + stall.
    pub(crate) failed: Share,
    pub(crate) cluster_k: usize,
    /// `None` when there are fewer failures than clusters.
    pub(crate) clusters: Option<FailureClusters>,
    pub(crate) wall_time_s: Option<f64>,
    pub(crate) samples_per_s: Option<f64>,
    pub(crate) sample_time_s: f64,
    /// A refine's combined file or one of its rounds (written only then):
    /// its shares are the refined sample's, not the box's.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub(crate) refined: bool,
}

/// Summarizes a scan file (`k` overrides the config's cluster count).
pub(crate) fn summarize(path: &Path, k: Option<usize>) -> Result<Summary> {
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
        variant: ModelChoices::of(&data.config.simulation),
        paper_scan: paper,
        outcomes,
        stable,
        failed,
        cluster_k,
        clusters: data.clusters(Some(cluster_k))?,
        wall_time_s: data.wall_time_s,
        samples_per_s: data.wall_time_s.filter(|w| *w > 0.0).map(|w| n as f64 / w),
        sample_time_s: data.sample_time_s,
        refined: data.refined,
    })
}

/// The scan file a summary names, if rtw-scan wrote it: `summary.json`'s
/// `file` (in an object that also has `version` and `outcomes`), or
/// `summary.md`'s `- file: `...`` line under its `# rtw-scan summary:`
/// title. These are what every summary rtw-scan writes carries; a file
/// without them is not one of its summaries.
pub(crate) fn summary_of(name: &str, text: &str) -> Option<String> {
    if name.ends_with(".json") {
        let v = serde_json::from_str::<serde_json::Value>(text).ok()?;
        (v.get("version").is_some() && v.get("outcomes").is_some())
            .then(|| v.get("file")?.as_str().map(str::to_string))
            .flatten()
    } else {
        let mut lines = text.lines();
        lines.next()?.strip_prefix("# rtw-scan summary: ")?;
        lines.find_map(|l| {
            l.strip_prefix("- file: `")?
                .strip_suffix('`')
                .map(str::to_string)
        })
    }
}

/// Refuses to let the summary of `samples` replace `dir/summary.json` or
/// `dir/summary.md`: always when one is a symlink or not a regular file;
/// unless `force`, when one is the summary of another file (the summary of
/// a part beside the merged scan's, say) or is not an rtw-scan summary
/// ([`summary_of`]: a file a person put there).
pub(crate) fn check_summary_target(dir: &Path, samples: &Path, force: bool) -> Result<()> {
    for name in ["summary.json", "summary.md"] {
        let path = dir.join(name);
        files::refuse_special(&path, "")?;
        if force || !path.exists() {
            continue;
        }
        let of = files::read_limited(&path, "summary", SUMMARY_MAX_BYTES)
            .ok()
            .and_then(|b| String::from_utf8(b).ok())
            .and_then(|t| summary_of(name, &t));
        let file_name = |p: &Path| p.file_name().map(|n| n.to_os_string());
        match of {
            Some(f) if file_name(Path::new(&f)) == file_name(samples) => {}
            Some(f) => bail!(
                "{} is the summary of {f}, not of {}: writing this one would replace it; pass \
                 --force to replace it",
                path.display(),
                samples.display()
            ),
            None => bail!(
                "{} is not an rtw-scan summary (rtw-scan did not write it): refusing to replace \
                 it; move it away, or pass --force to replace it",
                path.display()
            ),
        }
    }
    Ok(())
}

/// Writes `summary.json` and `summary.md` into `dir`, moved into place
/// together: a reader never meets the JSON of one summary beside the
/// Markdown of another.
pub(crate) fn write_summary(dir: &Path, summary: &Summary) -> Result<()> {
    let mut set = FileSet::default();
    set.add_bytes(
        &dir.join("summary.json"),
        serde_json::to_string_pretty(summary)?.as_bytes(),
    )?;
    set.add_bytes(&dir.join("summary.md"), summary.to_markdown().as_bytes())?;
    set.commit()
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
    let of = match fc.clustered {
        None => format!("the {} failed samples", fc.failures),
        Some(n) => format!(
            "a seeded random sample of {n} of the {} failed samples (sizes and kinds count every \
             failure, in the cluster of its nearest centre)",
            fc.failures
        ),
    };
    let mut md = format!(
        "## Failure clusters\n\nk-means (k = {}) on standardized (α, f_n, φ) of {of}; silhouette {sil}.\n\n\
         | cluster | name | size | α | f_n [Hz] | φ [rad] | collapse | stall |\n|---:|---|---:|---:|---:|---:|---:|---:|\n",
        fc.k
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
        // A `--set` run's directory is `NAME+set-HASH` (cli/run.rs): its
        // name says which run this is, the config's name alone does not.
        let title = match (&self.name, dir_name) {
            (Some(n), Some(d)) if d.starts_with(&format!("{n}+set-")) => d,
            (Some(n), _) => n.clone(),
            (None, Some(d)) => d,
            (None, None) => "scan".into(),
        };
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
        if self.refined {
            md.push_str(
                "Refined scan (rtw-scan refine): its added samples crowd where the labels change, \
                 so these shares are the refined sample's, not the box's.\n",
            );
        }
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
    use crate::scan::Run;
    use crate::scan::progress::Silent;
    use crate::scan::run::{RunSettings, run_scan};
    use std::num::NonZeroUsize;
    use std::sync::atomic::AtomicBool;

    /// `cfg` scanned into `dir` by the fake simulator, in chunks of
    /// `chunk` rows on `threads` workers.
    fn fake_scan(cfg: &ScanConfig, dir: &std::path::Path, chunk: usize, threads: usize) {
        let settings = RunSettings {
            out_dir: dir.to_path_buf(),
            resume: false,
            chunk_size: NonZeroUsize::new(chunk).unwrap(),
            shard: None,
            force: false,
        };
        let sim = |p: &rtw_model::Params, o: &rtw_model::Options| {
            crate::fake::simulate(p, o, std::time::Duration::ZERO)
        };
        let stop = AtomicBool::new(false);
        let run = Run::new(&Silent, &stop).on(NonZeroUsize::new(threads));
        run_scan(cfg, &settings, &sim, &run).unwrap();
    }

    /// A summary whose Markdown cannot be written where it goes (a symlink
    /// stands there) leaves the earlier JSON as it was: the two files are
    /// one set.
    #[cfg(unix)]
    #[test]
    fn a_summary_refused_at_its_markdown_leaves_the_earlier_json() {
        let cfg = config::parse(
            "seed = 3\nsamples = 8\n[params]\nlength = 0.8\nrho = 2.5\n\
             alpha = { uniform = [0, 0.4] }\nfn = 3.0\nzeta = 0.05\nphi = 0.15\n",
        )
        .unwrap();
        let dir = tempfile::tempdir().unwrap();
        fake_scan(&cfg, dir.path(), 8, 1);
        let json = dir.path().join("summary.json");
        std::fs::write(&json, "{\"earlier\": true}").unwrap();
        std::os::unix::fs::symlink("/dev/null", dir.path().join("summary.md")).unwrap();
        let summary = summarize(&dir.path().join("samples.parquet"), None).unwrap();
        let e = write_summary(dir.path(), &summary).unwrap_err().to_string();
        assert!(e.contains("summary.md") && e.contains("symlink"), "{e}");
        assert_eq!(
            std::fs::read_to_string(&json).unwrap(),
            "{\"earlier\": true}"
        );
    }

    /// `run --set …` writes to `runs/NAME+set-HASH/` so that its rows never
    /// mix with the plain scan's; its summary must be headed by that name
    /// too, or the two summaries read alike.
    #[test]
    fn a_set_runs_summary_is_headed_by_its_directory_not_the_plain_scans_name() {
        let cfg = config::parse(
            "name = \"paper\"\nseed = 3\nsamples = 8\n[params]\nlength = 0.8\nrho = 2.5\n\
             alpha = { uniform = [0, 0.4] }\nfn = 3.0\nzeta = 0.05\nphi = 0.15\n",
        )
        .unwrap();
        let root = tempfile::tempdir().unwrap();
        let mut titles = Vec::new();
        for name in ["paper", "paper+set-0123abcd"] {
            let dir = root.path().join(name);
            fake_scan(&cfg, &dir, 8, 1);
            let md = summarize(&dir.join("samples.parquet"), None)
                .unwrap()
                .to_markdown();
            titles.push(md.lines().next().unwrap().to_string());
        }
        assert_eq!(titles[0], "# rtw-scan summary: paper");
        assert_eq!(titles[1], "# rtw-scan summary: paper+set-0123abcd");
    }

    #[test]
    fn more_failures_than_the_cap_are_clustered_from_a_sample_and_counted_exactly() {
        // The fake simulator fails (stall) every φ < 0.1 and collapses small
        // α with low f_n: about 3/4 of these 32000 samples fail, more than
        // the CLUSTER_MAX_POINTS that k-means sees.
        let cfg = config::parse(
            r#"
seed = 3
samples = 32000
[params]
length = 0.8
rho = { uniform = [1.2, 4.5] }
alpha = { uniform = [0, 0.4] }
fn = { uniform = [1.5, 5] }
zeta = 0.05
phi = { uniform = [0.05, 0.12] }
"#,
        )
        .unwrap();
        let dir = tempfile::tempdir().unwrap();
        fake_scan(&cfg, dir.path(), 4000, 2);
        let data = read_scan(&dir.path().join("samples.parquet")).unwrap();
        let collapses = data.counts[label_index(Label::Collapse)] as usize;
        let stalls = data.counts[label_index(Label::Stall)] as usize;
        assert_eq!(data.failures.seen(), collapses + stalls);
        assert!(
            data.failures.seen() > CLUSTER_MAX_POINTS,
            "{}",
            data.failures.seen()
        );
        assert_eq!(data.failures.points().len(), CLUSTER_MAX_POINTS);

        let fc = data.clusters(None).unwrap().unwrap();
        assert_eq!(data.clusters(None).unwrap().unwrap(), fc, "deterministic");
        assert_eq!(
            (fc.failures, fc.clustered),
            (collapses + stalls, Some(CLUSTER_MAX_POINTS))
        );
        // The cross-table adds up to the label counts: every failure is
        // counted once, not only the clustered ones.
        let sum = |g: fn(&crate::analysis::clusters::FailureCluster) -> usize| -> usize {
            fc.clusters.iter().map(g).sum()
        };
        assert_eq!((sum(|c| c.collapse), sum(|c| c.stall)), (collapses, stalls));
        assert_eq!(sum(|c| c.size), collapses + stalls);
        // The assignments (what `cluster --assignments` writes) visit every
        // failure once, in id order, and agree with the cluster sizes.
        let mut sizes = vec![0; fc.k];
        let (mut visited, mut last) = (0, None);
        data.for_each_assigned(&fc, |failures, clusters| {
            for (f, c) in failures.iter().zip(clusters) {
                assert!(f.label.is_failure());
                assert!(last < Some(f.sample_id));
                last = Some(f.sample_id);
                sizes[*c] += 1;
                visited += 1;
            }
            Ok(())
        })
        .unwrap();
        assert_eq!(visited, collapses + stalls);
        assert_eq!(
            sizes,
            fc.clusters.iter().map(|c| c.size).collect::<Vec<_>>()
        );
        let md = clusters_markdown(fc.k, Some(&fc), fc.failures);
        assert!(
            md.contains(&format!(
                "a seeded random sample of {CLUSTER_MAX_POINTS} of the {} failed samples",
                fc.failures
            )),
            "{md}"
        );
        // k-means cannot make more clusters than it has points.
        let e = data.clusters(Some(CLUSTER_MAX_POINTS + 1)).unwrap_err();
        assert!(e.to_string().contains("use k <= 20000"), "{e}");
    }

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
