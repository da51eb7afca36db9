//! The optional robustness columns of a scan (docs/robustness.md): written
//! only when the scan's options ask for the measure, after the columns of
//! [`COLUMNS`](super::scan_rows::COLUMNS), so a scan without them has
//! exactly the scan schema.

use super::scan_rows::{Row, schema};
use super::table;
use arrow_array::{ArrayRef, Float64Array, RecordBatch};
use arrow_schema::{DataType, Schema, SchemaRef};
use rtw_model::Options;
use std::sync::Arc;

/// The largest survivable step down's column.
pub(crate) const STEP_DOWN_MAX: &str = "step_down_max";

/// The scan schema, with the `step_down_max` column when `step_down`.
pub(crate) fn scan_schema(step_down: bool) -> SchemaRef {
    if !step_down {
        return schema();
    }
    let mut fields: Vec<_> = schema()
        .fields()
        .iter()
        .map(|f| f.as_ref().clone())
        .collect();
    fields.push(table::field(
        STEP_DOWN_MAX,
        DataType::Float64,
        true,
        "m",
        "largest survivable step down of the gait (docs/robustness.md); null unless stable; \
         only with robustness.step_down = true",
    ));
    Arc::new(Schema::new(fields))
}

/// `batch` (scan rows in the scan schema) with the robustness columns the
/// scan's `options` ask for, read from `rows`.
pub(crate) fn with_robustness(batch: RecordBatch, rows: &[Row], options: &Options) -> RecordBatch {
    if !options.robustness.step_down {
        return batch;
    }
    let values: Float64Array = rows
        .iter()
        .map(|r| {
            r.outcome
                .and_then(|o| o.robustness)
                .and_then(|m| m.step_down_max)
        })
        .collect();
    let mut columns: Vec<ArrayRef> = batch.columns().to_vec();
    columns.push(Arc::new(values));
    RecordBatch::try_new(scan_schema(true), columns).expect("one value per row")
}

/// The schema of scan files whose first file has `schema`: the scan schema,
/// with the robustness columns it carries.
pub(crate) fn schema_of_files(first: &Schema) -> SchemaRef {
    scan_schema(first.column_with_name(STEP_DOWN_MAX).is_some())
}
