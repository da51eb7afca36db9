//! A scan's folder read for a report: the scan verified ([`read_scan_table`]),
//! and the files beside it taken only when they are that scan's:
//! `summary.json` when the rows it counts are the scan's rows, and the
//! assignments file of `cluster --assignments` when its rows hash to the
//! content hash written with them and it records this scan's content hash.

use crate::analysis::report::summary_of;
use crate::analysis::scan_table::{ScanTable, read_scan_table};
use crate::files;
use crate::io::destination::SUMMARY_MAX_BYTES;
use crate::io::metadata::{FileKind, META_CONTENT_HASH, META_SCAN_HASH, META_SEED};
use crate::io::parquet::{self, READ_BATCH_ROWS};
use crate::io::scan_rows::label_index;
use crate::io::table::{i64_column, label_column};
use anyhow::{Context, Result, anyhow, bail};
use rtw_model::Label;
use std::path::{Path, PathBuf};

/// A scan and the files beside it that are its own ([`read_scan_folder`]).
pub struct ScanFolder {
    /// The scan's rows, verified.
    pub scan: ScanTable,
    /// `summary.json` as written, when the folder has one.
    pub summary: Option<String>,
    /// The assignments file of `cluster --assignments`, when the folder has one.
    pub assignments: Option<Assignments>,
}

/// Each failure's cluster, read from an assignments file.
pub struct Assignments {
    /// The file.
    pub path: PathBuf,
    /// `(sample_id, cluster)`, the cluster 0-based (its row in the cluster
    /// table), in the file's order: what [`crate::failure_clusters`] gives.
    pub clusters: Vec<(u64, usize)>,
}

/// Reads a scan as [`read_scan_table`] does, then from its folder (`path`,
/// or the folder of the scan file `path`) its `summary.json`
/// ([`read_summary`]) and its assignments file ([`read_assignments`]).
/// Each file beside it that is not the scan's own is an error naming it.
pub fn read_scan_folder(path: &Path) -> Result<ScanFolder> {
    let scan = read_scan_table(path)?;
    let dir = if path.is_dir() {
        path
    } else {
        path.parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."))
    };
    let summary = read_summary(&dir.join("summary.json"), &scan)?;
    let assignments = read_assignments(dir, &scan)?;
    Ok(ScanFolder {
        scan,
        summary,
        assignments,
    })
}

/// `summary.json` (its text, `None` when there is no such file), refused
/// unless it is rtw-scan's summary of `scan`: it names the scan's file, and
/// its seed, its row count and its count of every outcome are the scan's.
/// A summary records no hash of its scan (the rows hold none of the
/// summary), so these counts are what ties it to the rows.
pub fn read_summary(path: &Path, scan: &ScanTable) -> Result<Option<String>> {
    if std::fs::symlink_metadata(path).is_err() {
        return Ok(None);
    }
    files::refuse_special(path, "")?;
    let text = String::from_utf8(files::read_limited(path, "summary", SUMMARY_MAX_BYTES)?)
        .map_err(|_| anyhow!("{} is not UTF-8: not an rtw-scan summary", path.display()))?;
    let refuse = |why: String| {
        anyhow!(
            "{} is not the summary of this scan ({}): {why}; rerun `rtw-scan summary` on the scan, \
             or move the file",
            path.display(),
            scan_name(scan)
        )
    };
    let named = summary_of("summary.json", &text)
        .ok_or_else(|| refuse("rtw-scan did not write it".into()))?;
    let file_name = |p: &Path| p.file_name().map(|n| n.to_string_lossy().into_owned());
    let ours = match scan.files.as_slice() {
        [one] => file_name(one),
        _ => Some("samples.parquet".into()), // a shard set's merged file
    };
    if file_name(Path::new(&named)) != ours {
        return Err(refuse(format!("it is the summary of {named}")));
    }
    let value: serde_json::Value =
        serde_json::from_str(&text).with_context(|| path.display().to_string())?;
    let rows: u64 = scan.batches.iter().map(|b| b.num_rows() as u64).sum();
    let mut counts = [0u64; Label::ALL.len()];
    for batch in &scan.batches {
        for label in label_column(batch)? {
            counts[label_index(label)] += 1;
        }
    }
    let seed = scan.schema.metadata().get(META_SEED).cloned();
    let stated = |k: &str| value.get(k).map(|v| v.to_string());
    if stated("seed") != seed {
        return Err(refuse(format!(
            "it states seed {}, the scan's is {}",
            stated("seed").as_deref().unwrap_or("(none)"),
            seed.as_deref().unwrap_or("(none)")
        )));
    }
    if value.get("samples").and_then(|v| v.as_u64()) != Some(rows) {
        return Err(refuse(format!(
            "it counts {} rows, the scan has {rows}",
            stated("samples").as_deref().unwrap_or("(none)")
        )));
    }
    let outcomes = value.get("outcomes").and_then(|v| v.as_array());
    for (label, count) in Label::ALL.iter().zip(counts) {
        let said = outcomes
            .into_iter()
            .flatten()
            .find(|o| o.get("outcome").and_then(|v| v.as_str()) == Some(label.as_str()))
            .and_then(|o| o.get("count").and_then(|v| v.as_u64()));
        if said != Some(count) {
            return Err(refuse(format!(
                "it counts {} {label} rows, the scan has {count}",
                said.map_or("(none)".into(), |s| s.to_string()),
            )));
        }
    }
    Ok(Some(text))
}

/// The assignments file in `dir` (the first `*.parquet`, by name, whose
/// metadata has `rtw.clusters`), `None` when there is none. It is read
/// verified (its metadata and rows against their hashes) and must record
/// `scan`'s content hash; another scan's, or one that records none, is
/// refused naming the file.
pub fn read_assignments(dir: &Path, scan: &ScanTable) -> Result<Option<Assignments>> {
    let Some(path) = assignments_file(dir)? else {
        return Ok(None);
    };
    let input = parquet::open(&path, READ_BATCH_ROWS)?;
    let ours = scan
        .schema
        .metadata()
        .get(META_CONTENT_HASH)
        .map_or("(none)", String::as_str);
    match input.metadata.get(META_SCAN_HASH) {
        Some(theirs) if theirs == ours => {}
        theirs => bail!(
            "{} holds another scan's failure clusters: they were computed from the scan with \
             content hash {}, this one's ({}) is {ours}; rerun `rtw-scan cluster SCAN --assignments \
             FILE` on this scan, or move the file",
            path.display(),
            theirs.map_or("(none recorded)", String::as_str),
            scan_name(scan)
        ),
    }
    let mut clusters = Vec::new();
    for batch in input.reader {
        let batch = batch?;
        let ctx = || path.display().to_string();
        let ids = i64_column(&batch, "sample_id").with_context(ctx)?;
        let cluster = i64_column(&batch, "cluster").with_context(ctx)?;
        for (s, c) in ids.values().iter().zip(cluster.values()) {
            let (Ok(s), Some(c)) = (
                u64::try_from(*s),
                usize::try_from(*c).ok().and_then(|c| c.checked_sub(1)),
            ) else {
                bail!(
                    "{}: sample {s} has cluster {c}: not a sample id and a cluster >= 1",
                    path.display()
                );
            };
            clusters.push((s, c));
        }
    }
    Ok(Some(Assignments { path, clusters }))
}

/// The first `*.parquet` in `dir`, by name, that is an assignments file by
/// its metadata ([`FileKind::of`]); a file that is not Parquet is not one.
fn assignments_file(dir: &Path) -> Result<Option<PathBuf>> {
    Ok(files::parquet_files(dir)?.into_iter().find(|p| {
        parquet::open(p, 1).is_ok_and(|i| FileKind::of(&i.metadata) == Some(FileKind::Assignments))
    }))
}

/// The scan's file, or its first part, for messages.
fn scan_name(scan: &ScanTable) -> String {
    scan.files
        .first()
        .map_or_else(|| "(no file)".into(), |f| f.display().to_string())
}
