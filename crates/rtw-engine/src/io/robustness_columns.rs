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

/// Every robustness column, alone (the data dictionary's table of them).
pub fn all_columns_schema() -> SchemaRef {
    extend_schema(Arc::new(Schema::empty()), picked(|_| true))
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
                // A measure that could not be computed (NaN) is null; an
                // infinite one is measured (an MFPT whose interval is open
                // above) and stays infinite.
                kept(measured(r).and_then(|m| c.value(&m)))
            })
            .collect();
        columns.push(Arc::new(values));
    }
    RecordBatch::try_new(extend_schema(batch.schema(), on()), columns).expect("one value per row")
}

/// A robustness measure as a row's JSON has it: a number; `"inf"` (or
/// `"-inf"`) when it is measured infinite, which JSON has no number for (an
/// MFPT with no fall counted: `mfpt` and `mfpt_hi`), as Parquet holds inf;
/// null only when it was not computed (not asked for this row, no stable
/// gait, NaN), as Parquet holds null.
pub(crate) fn json_value(v: Option<f64>) -> serde_json::Value {
    match v {
        Some(v) if v.is_infinite() => (if v > 0.0 { "inf" } else { "-inf" }).into(),
        Some(v) => serde_json::Number::from_f64(v).map_or(serde_json::Value::Null, Into::into),
        None => serde_json::Value::Null,
    }
}

/// A robustness measure as a row's values hold it ([`super::scan_rows::Value`],
/// what Python's `Outcome` gives): NaN (not computed) is `None`, an infinite
/// measure stays infinite, as in Parquet.
pub(crate) fn kept(v: Option<f64>) -> Option<f64> {
    v.filter(|v| !v.is_nan())
}
