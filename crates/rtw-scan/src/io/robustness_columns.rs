//! The optional robustness columns of a scan (docs/robustness.md): written
//! only when the scan's options ask for their measure, after the columns of
//! `scan_rows::COLUMNS`, so a scan without them has exactly the scan schema.
//! The same names, in the same order, follow the columns in a row's JSON and
//! text forms. `scan_rows` makes every batch and schema of scan rows through
//! the two functions here, so no writer of scan rows can leave the columns
//! out; they know a row only by its measures, so they sit below `scan_rows`.

use super::robustness_measures::{RobustnessColumn, picked};
use super::table;
use arrow_array::{ArrayRef, Float64Array, RecordBatch};
use arrow_schema::{DataType, Schema, SchemaRef};
use rtw_model::options::RobustnessOptions;
use rtw_model::outcome::Robustness;
use std::sync::Arc;

/// `base` (the scan schema) followed by `columns`; `base` itself when there
/// are none.
pub(crate) fn extend_schema<'a>(
    base: SchemaRef,
    columns: impl Iterator<Item = &'a RobustnessColumn>,
) -> SchemaRef {
    let mut fields: Vec<_> = base.fields().iter().map(|f| f.as_ref().clone()).collect();
    let n = fields.len();
    fields.extend(
        columns.map(|c| table::field(c.name, DataType::Float64, true, c.unit, c.description)),
    );
    if fields.len() == n {
        return base;
    }
    Arc::new(Schema::new(fields))
}

/// `batch` (`rows` in the scan schema) with the robustness columns `asked`
/// switches on, each row's values read from its `measured` robustness.
pub(crate) fn append<R>(
    batch: RecordBatch,
    rows: &[R],
    measured: impl Fn(&R) -> Option<Robustness>,
    asked: &RobustnessOptions,
) -> RecordBatch {
    let on = || picked(|c| (c.on)(asked));
    if on().next().is_none() {
        return batch;
    }
    let mut columns: Vec<ArrayRef> = batch.columns().to_vec();
    for c in on() {
        let values: Float64Array = rows
            .iter()
            .map(|r| {
                measured(r)
                    .and_then(|m| c.value(&m))
                    // A measure that could not be computed (NaN) is null;
                    // an infinite one is measured (an MFPT whose interval
                    // is open above) and stays infinite.
                    .filter(|v| !v.is_nan())
            })
            .collect();
        columns.push(Arc::new(values));
    }
    RecordBatch::try_new(extend_schema(batch.schema(), on()), columns).expect("one value per row")
}
