//! The optional robustness columns of a scan (docs/robustness.md): written
//! only when the scan's options ask for the measure, after the columns of
//! [`COLUMNS`](super::scan_rows::COLUMNS) and in [`MEASURES`]' order (io/measures.rs), so a
//! scan without them has exactly the scan schema.

use super::measures::{MEASURES, Measure, asked};
use super::scan_rows::{Row, schema};
use super::table;
use arrow_array::{ArrayRef, Float64Array, RecordBatch};
use arrow_schema::{DataType, Schema, SchemaRef};
use rtw_model::Options;
use std::sync::Arc;

/// The scan schema, with the columns of `measures`.
fn scan_schema<'a>(measures: impl Iterator<Item = &'a Measure>) -> SchemaRef {
    let mut fields: Vec<_> = schema()
        .fields()
        .iter()
        .map(|f| f.as_ref().clone())
        .collect();
    fields.extend(measures.map(|m| table::field(m.name, DataType::Float64, true, m.unit, m.doc)));
    Arc::new(Schema::new(fields))
}

/// `batch` (scan rows in the scan schema) with the robustness columns the
/// scan's `options` ask for, read from `rows`.
pub(crate) fn with_robustness(batch: RecordBatch, rows: &[Row], options: &Options) -> RecordBatch {
    if asked(&options.robustness).next().is_none() {
        return batch;
    }
    let mut columns: Vec<ArrayRef> = batch.columns().to_vec();
    for m in asked(&options.robustness) {
        let values: Float64Array = rows
            .iter()
            .map(|r| {
                r.outcome
                    .and_then(|o| o.robustness)
                    .and_then(|x| (m.value)(&x))
                    .filter(|v| v.is_finite())
            })
            .collect();
        columns.push(Arc::new(values));
    }
    RecordBatch::try_new(scan_schema(asked(&options.robustness)), columns)
        .expect("one value per row")
}

/// The schema of scan files whose first file has `schema`: the scan schema,
/// with the robustness columns it carries.
pub(crate) fn schema_of_files(first: &Schema) -> SchemaRef {
    scan_schema(
        MEASURES
            .iter()
            .filter(|m| first.column_with_name(m.name).is_some()),
    )
}
