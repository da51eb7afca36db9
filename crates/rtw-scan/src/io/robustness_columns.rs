//! The optional robustness columns of a scan (docs/robustness.md): written
//! only when the scan's options ask for the measure, after the columns of
//! [`COLUMNS`](super::scan_rows::COLUMNS) and in [`MEASURES`]' order, so a
//! scan without them has exactly the scan schema.

use super::scan_rows::{Row, schema};
use super::table;
use arrow_array::{ArrayRef, Float64Array, RecordBatch};
use arrow_schema::{DataType, Schema, SchemaRef};
use rtw_model::Options;
use rtw_model::options::RobustnessOptions;
use rtw_model::outcome::Robustness;
use std::sync::Arc;

/// One robustness measure's column.
pub(crate) struct Measure {
    /// Its name (the column, the JSON key, the Python attribute).
    pub(crate) name: &'static str,
    unit: &'static str,
    doc: &'static str,
    /// Whether the options ask for it.
    pub(crate) asked: fn(&RobustnessOptions) -> bool,
    /// Its value (`None` unless the gait is stable).
    pub(crate) value: fn(&Robustness) -> Option<f64>,
}

/// The robustness measures, in column order.
pub(crate) const MEASURES: [Measure; 2] = [
    Measure {
        name: "step_down_max",
        unit: "m",
        doc: "largest survivable step down of the gait (docs/robustness.md); null unless stable; \
              only with robustness.step_down = true",
        asked: |o| o.step_down,
        value: |r| r.step_down_max,
    },
    Measure {
        name: "gsn",
        unit: "1",
        doc: "gait sensitivity norm: H2 norm of the step time and length's response to a floor \
              drop (docs/robustness.md); null unless stable or where it cannot be computed; \
              only with robustness.gsn = true",
        asked: |o| o.gsn,
        value: |r| r.gsn,
    },
];

/// The measures `asked` asks for, in column order.
pub(crate) fn asked(asked: &RobustnessOptions) -> impl Iterator<Item = &'static Measure> + '_ {
    MEASURES.iter().filter(move |m| (m.asked)(asked))
}

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
    if options.robustness.is_off() {
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
