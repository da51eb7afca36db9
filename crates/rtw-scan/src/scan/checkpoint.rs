//! What makes an interrupted scan resumable: where its files go
//! ([`Layout`]), the manifest that ties its unfinished chunks to one config,
//! the checks that keep a chunk, and the refusal to mix another scan's
//! results into a directory.

use crate::config::ScanConfig;
use crate::io::metadata::{self, META_CONFIG, META_CONFIG_HASH, META_SHARD};
use crate::io::scan_files;
use crate::io::{files, parquet};
use crate::scan::shard::{self, Shard};
use anyhow::{Context, Result, anyhow, bail};
use arrow_array::cast::AsArray;
use arrow_array::types::Int64Type;
use rtw_model::Label;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// What `.partial/manifest.json` records to make a resume safe.
#[derive(Debug, PartialEq, Serialize, Deserialize)]
pub(crate) struct Manifest {
    pub(crate) version: String,
    pub(crate) config: String,
    pub(crate) chunk_size: usize,
    pub(crate) rows: u64,
    /// The shard (`K/N`) this run computes; absent for a whole scan.
    #[serde(default)]
    pub(crate) shard: Option<String>,
}

/// Where a scan (or one shard of it) writes.
pub(crate) struct Layout {
    /// `samples.parquet`, or `part-K.parquet` for shard K.
    pub(crate) samples: PathBuf,
    /// `.partial`, or `.partial-K` for shard K (shards share a directory).
    pub(crate) partial: PathBuf,
}

impl Layout {
    pub(crate) fn new(out_dir: &Path, shard: Option<Shard>) -> Self {
        match shard {
            None => Self {
                samples: out_dir.join("samples.parquet"),
                partial: out_dir.join(".partial"),
            },
            Some(s) => Self {
                samples: out_dir.join(s.part_name()),
                partial: out_dir.join(s.partial_name()),
            },
        }
    }
    pub(crate) fn manifest(&self) -> PathBuf {
        self.partial.join("manifest.json")
    }
    pub(crate) fn chunk(&self, c: u64) -> PathBuf {
        self.partial.join(format!("chunk-{c:05}.parquet"))
    }
}

/// Checks a chunk file (config, row count, ids) and returns its labels.
pub(crate) fn chunk_labels(
    path: &Path,
    ids: std::ops::Range<u64>,
    config: &str,
) -> Result<Vec<Label>> {
    let input = parquet::open(path, ids.end.saturating_sub(ids.start) as usize)?;
    if input.metadata.get(META_CONFIG).map(String::as_str) != Some(config) {
        bail!("written for another config");
    }
    if input.rows as u64 != ids.end - ids.start {
        bail!("{} rows, expected {}", input.rows, ids.end - ids.start);
    }
    let mut labels = Vec::new();
    let mut next = ids.start;
    for batch in input.reader {
        let batch = batch?;
        let col = batch
            .column_by_name("sample_id")
            .and_then(|c| c.as_primitive_opt::<Int64Type>())
            .ok_or_else(|| anyhow!("no Int64 sample_id column"))?;
        for id in col.iter() {
            if id != Some(next as i64) {
                bail!("sample_id {id:?} where {next} was expected");
            }
            next += 1;
        }
        scan_files::check_scan_values(&batch, path, labels.len() as u64)?;
        labels.extend(scan_files::label_column(&batch)?);
    }
    Ok(labels)
}

/// The chunk numbers of the `chunk-NNNNN.parquet` files in `partial`.
pub(crate) fn chunks_on_disk(partial: &Path) -> Result<Vec<u64>> {
    let mut found = Vec::new();
    for entry in
        std::fs::read_dir(partial).with_context(|| format!("cannot read {}", partial.display()))?
    {
        let name = entry?.file_name();
        let name = name.to_string_lossy();
        if let Some(c) = name
            .strip_prefix("chunk-")
            .and_then(|n| n.strip_suffix(".parquet"))
            .filter(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()))
            .and_then(|n| n.parse().ok())
        {
            found.push(c);
        }
    }
    found.sort_unstable();
    Ok(found)
}

/// Refuses to run into a directory that holds another scan's results: a
/// `samples.parquet` or `part-K.parquet` of another config (hash), or, for a
/// shard, the parts of another split of this scan.
pub(crate) fn refuse_other_results(
    out: &Path,
    cfg: &ScanConfig,
    shard: Option<Shard>,
) -> Result<()> {
    let hash = cfg.hash();
    let ours = metadata::scan_label(&hash, cfg.name.as_deref(), cfg.seed);
    let mut names: Vec<String> = std::fs::read_dir(out)
        .with_context(|| format!("cannot read {}", out.display()))?
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n == "samples.parquet" || shard::part_index(n).is_some())
        .collect();
    names.sort();
    for name in names {
        let path = out.join(&name);
        let meta = match parquet::open(&path, 1) {
            Ok(i) => i.metadata,
            Err(e) => bail!(
                "{} holds {name}, which is not a scan rtw-scan can read ({e:#}); this run is {ours}: \
                 choose another --out, or pass --force to replace it",
                out.display()
            ),
        };
        if meta.get(META_CONFIG_HASH) != Some(&hash) {
            bail!(
                "{} holds another scan's results: {name} is {}; this run is {ours}. Choose another \
                 --out, or pass --force to replace them",
                out.display(),
                metadata::scan_label_of(&meta)
            );
        }
        let theirs = meta.get(META_SHARD).and_then(|t| t.parse::<Shard>().ok());
        if let (Some(s), Some(t)) = (shard, theirs)
            && s.count != t.count
        {
            bail!(
                "{} holds the parts of a {}-shard split of this scan ({name} is shard {t}); this run \
                 is shard {s}, and merge joins the parts of one split only. Use --shard K/{}, another \
                 --out, or pass --force",
                out.display(),
                t.count,
                t.count
            );
        }
    }
    Ok(())
}

pub(crate) fn read_manifest(path: &Path) -> Result<Manifest> {
    // The manifest holds the config and a few numbers.
    let text =
        files::read_limited(path, "manifest", 2 * files::CONFIG_MAX_BYTES).with_context(|| {
            format!(
                "cannot read {}: delete its directory to start over",
                path.display()
            )
        })?;
    serde_json::from_slice(&text).with_context(|| format!("{} is corrupt", path.display()))
}

/// Removes everything in `.partial` that is neither the manifest nor a chunk
/// (temporary files of a killed run).
pub(crate) fn remove_stray_files(partial: &Path) -> Result<()> {
    for entry in std::fs::read_dir(partial)? {
        let entry = entry?;
        let name = entry.file_name();
        let name = name.to_string_lossy();
        let keep =
            name == "manifest.json" || (name.starts_with("chunk-") && name.ends_with(".parquet"));
        if !keep {
            std::fs::remove_file(entry.path())
                .with_context(|| format!("cannot remove {}", entry.path().display()))?;
        }
    }
    Ok(())
}

/// Does `samples` exist, complete, for this very config (and shard)?
pub(crate) fn is_complete(samples: &Path, config: &str, shard: Option<&str>) -> bool {
    parquet::open(samples, 1)
        .map(|i| {
            i.metadata.get(META_CONFIG).map(String::as_str) == Some(config)
                && i.metadata.get(META_SHARD).map(String::as_str) == shard
        })
        .unwrap_or(false)
}
