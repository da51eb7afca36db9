//! Scan files read back: typed columns, the values every reader relies on,
//! and the concatenation of a run's chunks or a scan's shard parts into one
//! file.

use crate::io::metadata::META_WALL_TIME;
use crate::io::parquet::{self, ParquetFile, READ_BATCH_ROWS};
use crate::io::scan_rows::{COLUMNS, schema, schema_of_files};
use crate::io::table::{f64_column, i64_column};
use ::parquet::file::metadata::KeyValue;
use anyhow::{Context, Result, anyhow, bail};
use arrow_array::RecordBatch;
use arrow_array::cast::AsArray;
use arrow_array::types::Int64Type;
use rtw_model::Param;
use std::path::{Path, PathBuf};

/// Checks the values of a batch of scan rows that every reader relies on:
/// each `sample_id` a number >= 0, each input parameter inside its range
/// (docs/model.md §1), the derived parameters finite, each `wall_time_s`
/// finite and >= 0 (summed into the summary's timing). `first_row` is the
/// batch's first row in the file; an error names the file, the column and
/// the row. That the ids run in order, once each, is the caller's check
/// ([`check_ids`]): it spans batches.
pub fn check_scan_values(batch: &RecordBatch, path: &Path, first_row: u64) -> Result<()> {
    let ids = i64_column(batch, "sample_id").with_context(|| path.display().to_string())?;
    if let Some(r) = ids.iter().position(|v| v.is_none_or(|v| v < 0)) {
        bail!(
            "{}: column `sample_id`, row {}: {} is invalid: must be an integer >= 0; the file is corrupt \
             or was not written by rtw-scan",
            path.display(),
            first_row + r as u64,
            ids.iter()
                .nth(r)
                .flatten()
                .map_or("null".into(), |v| v.to_string())
        );
    }
    let wall = f64_column(batch, "wall_time_s").with_context(|| path.display().to_string())?;
    if let Some(r) = wall
        .iter()
        .position(|v| !v.is_some_and(|v| v.is_finite() && v >= 0.0))
    {
        bail!(
            "{}: column `wall_time_s`, row {}: {} is invalid: must be a finite number >= 0; the file \
             is corrupt or was not written by rtw-scan",
            path.display(),
            first_row + r as u64,
            wall.iter()
                .nth(r)
                .flatten()
                .map_or("null".into(), |v| v.to_string())
        );
    }
    for input in Param::ALL {
        let key = input.name();
        let col = f64_column(batch, key).with_context(|| path.display().to_string())?;
        for (r, v) in col.iter().enumerate() {
            let bad = match v {
                None => Some("null: must be a number".to_string()),
                Some(v) => input.check(v).err().map(|e| {
                    // Corrupt bits are often huge or tiny: keep them readable.
                    let shown = if v != 0.0 && !(1e-6..1e6).contains(&v.abs()) {
                        format!("{v:e}")
                    } else {
                        v.to_string()
                    };
                    format!("{shown} is invalid: must be {}", e.range)
                }),
            };
            if let Some(why) = bad {
                bail!(
                    "{}: column `{key}`, row {}: {why}; the file is corrupt or was not written by rtw-scan",
                    path.display(),
                    first_row + r as u64
                );
            }
        }
    }
    for c in COLUMNS.iter().filter(|c| c.group == "derived") {
        let col = f64_column(batch, c.name).with_context(|| path.display().to_string())?;
        if let Some(r) = col.iter().position(|v| !v.is_some_and(f64::is_finite)) {
            bail!(
                "{}: column `{}`, row {}: {:?} is invalid: must be a finite number; the file is corrupt",
                path.display(),
                c.name,
                first_row + r as u64,
                col.iter().nth(r).flatten()
            );
        }
    }
    Ok(())
}

/// Checks that the `sample_id`s of a batch (already checked >= 0 by
/// [`check_scan_values`]) go on from `next` (the id expected after the
/// previous batch's last; `None` at the file's first row) one by one: no id
/// twice, none skipped, in order. Returns the id expected next. `first_row`
/// is the batch's first row in the file.
pub fn check_ids(
    batch: &RecordBatch,
    path: &Path,
    first_row: u64,
    mut next: Option<i64>,
) -> Result<Option<i64>> {
    let ids = i64_column(batch, "sample_id").with_context(|| path.display().to_string())?;
    for (r, id) in ids.iter().enumerate() {
        let id = id.unwrap_or(-1);
        if let Some(want) = next.filter(|want| *want != id) {
            bail!(
                "{}: column `sample_id`, row {}: {id} is invalid: must be {want} (each id once, in \
                 order); the file is corrupt or was not written by rtw-scan",
                path.display(),
                first_row + r as u64
            );
        }
        // Past the largest id, the expected one wraps to a negative number
        // that no valid id equals: a row after it is refused.
        next = Some(id.wrapping_add(1));
    }
    Ok(next)
}

/// Concatenates scan files (a run's chunks, or a scan's shard parts), in
/// order, into `dest` with `metadata` and [`META_WALL_TIME`] = the sum of the
/// inputs' `wall_key` values. The rows are cut into row groups of
/// `row_group_rows` regardless of where one input ends and the next begins,
/// so the result does not depend on the chunk size or the shard count.
/// Streams [`READ_BATCH_ROWS`] rows at a time (memory stays flat in the row
/// count: at most one row group is buffered) and checks on the way that the
/// `sample_id`s run through `ids` exactly once, in order; on any error `dest`
/// is left as it was.
pub(crate) fn concat_scan_files(
    inputs: &[PathBuf],
    ids: std::ops::Range<u64>,
    dest: &Path,
    row_group_rows: usize,
    metadata: Vec<KeyValue>,
    wall_key: &str,
) -> Result<()> {
    // The scan schema, with the robustness columns the files carry (all
    // files of a scan were made with its options).
    let schema = match inputs.first() {
        Some(first) => schema_of_files(&parquet::open(first, READ_BATCH_ROWS)?.reader.schema()),
        None => schema(),
    };
    let props = parquet::writer_properties(&schema, row_group_rows, metadata);
    let mut file = ParquetFile::create(dest, schema.clone(), props)?;
    let mut wall = 0.0;
    let mut next = ids.start;
    for path in inputs {
        let input = parquet::open(path, READ_BATCH_ROWS)?;
        let first_row = next;
        wall += input
            .metadata
            .get(wall_key)
            .and_then(|v| v.parse::<f64>().ok())
            .unwrap_or(0.0);
        for batch in input.reader {
            let batch = batch.with_context(|| format!("reading {}", path.display()))?;
            let col = batch
                .column_by_name("sample_id")
                .and_then(|c| c.as_primitive_opt::<Int64Type>())
                .ok_or_else(|| anyhow!("{}: no Int64 sample_id column", path.display()))?;
            for id in col.iter() {
                let id = id.ok_or_else(|| anyhow!("{}: null sample_id", path.display()))? as u64;
                if id < next {
                    bail!(
                        "{}: sample_id {id} is already in an earlier file (or twice in this one): \
                         the files overlap",
                        path.display()
                    );
                }
                if id > next {
                    bail!(
                        "{}: sample_id {id} where {next} was expected: sample_ids {next}..{} are in no file",
                        path.display(),
                        id - 1
                    );
                }
                next += 1;
            }
            if next > ids.end {
                bail!(
                    "{}: sample_id {} is beyond the scan's last id {}",
                    path.display(),
                    next - 1,
                    ids.end.saturating_sub(1)
                );
            }
            check_scan_values(&batch, path, next - batch.num_rows() as u64 - first_row)?;
            file.write(
                &RecordBatch::try_new(schema.clone(), batch.columns().to_vec())
                    .with_context(|| format!("{}: not this scan's columns", path.display()))?,
            )?;
        }
        crate::pause_at("merge");
    }
    if next != ids.end {
        bail!(
            "sample_ids {next}..{} are in no file",
            ids.end.saturating_sub(1)
        );
    }
    file.append_metadata(META_WALL_TIME, wall.to_string());
    file.finish()
}
