//! The optional robustness columns of a scan (docs/robustness.md): written
//! only when the scan's options ask for their measure, after the columns of
//! [`COLUMNS`](super::scan_rows::COLUMNS), so a scan without them has
//! exactly the scan schema. The same names, in the same order, follow the
//! columns in a row's JSON and text forms.

use super::robustness_measures::{RobustnessColumn, picked};
use super::scan_rows::{Row, schema};
use super::table;
use arrow_array::{ArrayRef, Float64Array, RecordBatch};
use arrow_schema::{DataType, Schema, SchemaRef};
use rtw_model::Options;
use std::sync::Arc;

/// The scan schema followed by `columns`.
fn scan_schema<'a>(columns: impl Iterator<Item = &'a RobustnessColumn>) -> SchemaRef {
    let mut fields: Vec<_> = schema()
        .fields()
        .iter()
        .map(|f| f.as_ref().clone())
        .collect();
    let n = fields.len();
    fields.extend(
        columns.map(|c| table::field(c.name, DataType::Float64, true, c.unit, c.description)),
    );
    if fields.len() == n {
        return schema();
    }
    Arc::new(Schema::new(fields))
}

/// The schema of scan rows under `options`: the scan schema, with the
/// robustness columns they ask for.
pub(crate) fn schema_for(options: &Options) -> SchemaRef {
    let asked = options.robustness;
    scan_schema(picked(|c| (c.on)(&asked)))
}

/// `batch` (scan rows in the scan schema) with the robustness columns the
/// scan's `options` ask for, read from `rows`.
pub(crate) fn with_robustness(batch: RecordBatch, rows: &[Row], options: &Options) -> RecordBatch {
    let asked = options.robustness;
    if picked(|c| (c.on)(&asked)).next().is_none() {
        return batch;
    }
    let mut columns: Vec<ArrayRef> = batch.columns().to_vec();
    for c in picked(|c| (c.on)(&asked)) {
        let values: Float64Array = rows
            .iter()
            .map(|r| {
                r.outcome
                    .and_then(|o| o.robustness)
                    .and_then(|m| (c.get)(&m))
                    // A measure that could not be computed (NaN) is null.
                    .filter(|v| v.is_finite())
            })
            .collect();
        columns.push(Arc::new(values));
    }
    RecordBatch::try_new(scan_schema(picked(|c| (c.on)(&asked))), columns)
        .expect("one value per row")
}

/// The schema of scan files whose first file has `schema`: the scan schema,
/// with the robustness columns it carries.
pub(crate) fn schema_of_files(first: &Schema) -> SchemaRef {
    scan_schema(picked(|c| first.column_with_name(c.name).is_some()))
}
