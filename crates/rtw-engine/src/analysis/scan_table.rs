//! A scan read whole, with every check that `summary` and `sensitivity`
//! make, for readers that want its rows as one table (rtw-py's `read_scan`,
//! the HTML report): the footer and content hash of each file, the row
//! values, the `sample_id`s once each and in order, and for an unmerged
//! shard set that every shard of one scan is there. And a scan's
//! sensitivity indices, read only when they were computed from that scan.

use crate::analysis::report::open_scan;
use crate::io::content_hash::ContentHash;
use crate::io::metadata::{
    META_CONFIG_HASH, META_CONTENT_HASH, META_METADATA_HASH, META_SENSITIVITY, META_SHARD,
    META_SHARDS, META_TOTAL_ROWS, META_WALL_TIME,
};
use crate::io::parquet::{self, READ_BATCH_ROWS};
use crate::io::scan_files::{check_ids, check_scan_values};
use crate::scan::shard::{Shard, complete_parts, part_index};
use anyhow::{Context, Result, anyhow, bail};
use arrow_array::RecordBatch;
use arrow_schema::SchemaRef;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Key of the field in `rtw.sensitivity`'s JSON that names the scan the
/// indices were computed from by its `rtw.content_hash`: the identity
/// [`read_indices`] checks.
pub const SENSITIVITY_SCAN_HASH: &str = "scan_content_hash";

/// A scan's rows, read and checked by [`read_scan_table`].
pub struct ScanTable {
    /// The rows, in `sample_id` order.
    pub batches: Vec<RecordBatch>,
    /// Their schema, with the scan's metadata (`rtw.config`, `rtw.seed`,
    /// `rtw.content_hash`, ...). An unmerged shard set carries what its
    /// merged file would: no `rtw.shard`, `rtw.shards` = N, the parts'
    /// summed wall time and the content hash of all its rows.
    pub schema: SchemaRef,
    /// The files read: one, or the parts of a shard set in shard order.
    pub files: Vec<PathBuf>,
}

/// Reads a scan whole, checked: `path` is a scan file, or a directory
/// holding `samples.parquet` (a plain or merged scan) or else the
/// `part-K.parquet` of a shard set, which must be every shard of one scan.
/// Every file's footer and rows are verified against its hashes, the row
/// values as `summary` checks them, and the `sample_id`s must run from the
/// first of the file (0, or a part's first id) one by one. Errors name the
/// file and, for a row, the column and the row.
pub fn read_scan_table(path: &Path) -> Result<ScanTable> {
    if !path.is_dir() {
        return read_files(&[path.to_path_buf()], None);
    }
    let merged = path.join("samples.parquet");
    if merged.exists() {
        return read_files(&[merged], None);
    }
    let has_parts = std::fs::read_dir(path)
        .with_context(|| format!("cannot read directory {}", path.display()))?
        .filter_map(|e| e.ok())
        .any(|e| e.file_name().to_str().and_then(part_index).is_some());
    if !has_parts {
        bail!(
            "{} holds no samples.parquet and no part-K.parquet: not a scan directory (one written \
             by `rtw-scan run --out DIR` or `rtw-scan merge DIR`)",
            path.display()
        );
    }
    let set = complete_parts(path)?;
    read_files(&set.paths, Some(set.total))
}

/// Reads `files` in order, their ids running on from one file to the next;
/// `set_total` is the row count of a shard set whose parts they are.
fn read_files(files: &[PathBuf], set_total: Option<u64>) -> Result<ScanTable> {
    let mut batches = Vec::new();
    let mut schema: Option<SchemaRef> = None;
    let mut metadata = BTreeMap::new();
    let mut hash = None;
    let mut wall = 0.0;
    let mut next = None;
    for (k, file) in files.iter().enumerate() {
        let (input, cfg) = open_scan(file)?;
        if k == 0 {
            metadata = input.metadata.clone();
            // The first id: 0, or a part's own first id when a part is read alone.
            let first = match (set_total, metadata.get(META_SHARD)) {
                (None, Some(shard)) => {
                    let shard: Shard = shard
                        .parse()
                        .map_err(|e| anyhow!("{}: `{META_SHARD}` {e}", file.display()))?;
                    shard.ids(cfg.total_rows()?)?.start
                }
                _ => 0,
            };
            next = Some(first as i64);
            let s = input.reader.schema();
            hash = Some(ContentHash::new(s.fields().len()));
            schema = Some(s);
        }
        wall += input
            .metadata
            .get(META_WALL_TIME)
            .and_then(|v| v.parse::<f64>().ok())
            .unwrap_or(0.0);
        let schema = schema.as_ref().expect("set by the first file");
        let mut rows = 0u64;
        for batch in input.reader {
            let batch = batch.with_context(|| format!("reading {}", file.display()))?;
            let batch = RecordBatch::try_new(Arc::clone(schema), batch.columns().to_vec())
                .with_context(|| {
                    format!(
                        "{}: not the columns of {}",
                        file.display(),
                        files[0].display()
                    )
                })?;
            check_scan_values(&batch, file, rows)?;
            next = check_ids(&batch, file, rows, next)?;
            rows += batch.num_rows() as u64;
            if let Some(h) = hash.as_mut() {
                h.update(&batch)?;
            }
            batches.push(batch);
        }
    }
    if let Some(total) = set_total {
        // Each part's rows are its own hash's; that they are the set's
        // rows, all of them, is checked here.
        let got = next.unwrap_or(0);
        if got != total as i64 {
            bail!(
                "the parts {} … {} hold sample_ids 0..{} where the scan has {total}: a part is \
                 short; rerun it with `rtw-scan run CONFIG --shard K/N --resume`",
                files[0].display(),
                files[files.len() - 1].display(),
                got - 1
            );
        }
        for key in [META_SHARD, META_TOTAL_ROWS, META_METADATA_HASH] {
            metadata.remove(key);
        }
        metadata.insert(META_SHARDS.into(), files.len().to_string());
        metadata.insert(META_WALL_TIME.into(), wall.to_string());
        let hash = hash.as_ref().map(ContentHash::value).unwrap_or_default();
        metadata.insert(META_CONTENT_HASH.into(), hash);
    }
    let fields = schema.expect("at least one file").fields().clone();
    let (batches, schema) = parquet::with_metadata(batches, fields, metadata)?;
    Ok(ScanTable {
        batches,
        schema,
        files: files.to_vec(),
    })
}

/// Reads the sensitivity indices at `path` (`rtw-scan sensitivity`'s
/// file, verified as every read is) and checks that they are of the scan
/// whose metadata is `scan` and which has `rows` rows: by the scan's
/// content hash when the indices record it (`SENSITIVITY_SCAN_HASH`),
/// else by its config hash and row count. A file of other indices, or of
/// none, is refused, naming it.
pub fn read_indices(
    path: &Path,
    scan: &BTreeMap<String, String>,
    rows: u64,
) -> Result<(Vec<RecordBatch>, SchemaRef)> {
    let input = parquet::open(path, READ_BATCH_ROWS)?;
    let about = input.metadata.get(META_SENSITIVITY).ok_or_else(|| {
        anyhow!(
            "{}: not sensitivity indices written by `rtw-scan sensitivity` (no `{META_SENSITIVITY}` \
             metadata): rerun `rtw-scan sensitivity` on this scan, or move the file",
            path.display()
        )
    })?;
    let about: serde_json::Value = serde_json::from_str(about)
        .with_context(|| format!("{}: `{META_SENSITIVITY}` is not JSON", path.display()))?;
    let field = |k: &str| {
        about
            .get(k)
            .map(|v| v.as_str().map_or(v.to_string(), String::from))
    };
    let ours = |k: &str| scan.get(k).cloned().unwrap_or_else(|| "(none)".into());
    let differs = match field(SENSITIVITY_SCAN_HASH) {
        Some(theirs) => (theirs != ours(META_CONTENT_HASH)).then(|| {
            format!(
                "they were computed from the scan with content hash {theirs}, this one's is {}",
                ours(META_CONTENT_HASH)
            )
        }),
        None => {
            let (hash, n) = (field("config_hash"), field("rows"));
            if hash.as_deref() != Some(&ours(META_CONFIG_HASH)) {
                Some(format!(
                    "they were computed from a scan with config hash {}, this one's is {}",
                    hash.as_deref().unwrap_or("(none)"),
                    ours(META_CONFIG_HASH)
                ))
            } else if n != Some(rows.to_string()) {
                Some(format!(
                    "they were computed from {} rows, this scan has {rows}",
                    n.as_deref().unwrap_or("(none)")
                ))
            } else {
                None
            }
        }
    };
    if let Some(why) = differs {
        bail!(
            "{} holds another scan's sensitivity indices: {why}; rerun `rtw-scan sensitivity` on \
             this scan, or move the file",
            path.display()
        );
    }
    let schema = input.reader.schema();
    let batches = input
        .reader
        .collect::<Result<Vec<_>>>()
        .with_context(|| format!("reading {}", path.display()))?;
    Ok((batches, schema))
}
