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
                    // A measure that could not be computed (NaN) is null;
                    // an infinite one is measured (an MFPT whose interval
                    // is open above) and stays infinite.
                    .filter(|v| !v.is_nan())
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::scan_rows::tests::{outcome, row};
    use crate::io::scan_rows::to_batch;
    use arrow_array::Array;
    use rtw_model::Label;
    use rtw_model::outcome::{MeanFirstPassage, Robustness};

    fn column(b: &RecordBatch, name: &str) -> Float64Array {
        b.column_by_name(name)
            .unwrap()
            .as_any()
            .downcast_ref::<Float64Array>()
            .unwrap()
            .clone()
    }

    #[test]
    fn an_mfpt_open_above_keeps_its_infinite_upper_end_and_nan_is_null() {
        // A gait whose fall rate's interval reaches 0 has mfpt_hi = ∞, and
        // one whose splitting saw no fall has mfpt = mfpt_lo = ∞: both are
        // measured, unlike a measure that could not be computed (NaN), and a
        // reader must tell them apart.
        let mut options = Options::default();
        options.robustness.mfpt = true;
        options.robustness.gsn = true;
        let with = |mfpt, lo, hi, fall_rate, gsn| {
            let mut o = outcome(Label::Walk);
            o.robustness = Some(Robustness {
                gsn: Some(gsn),
                mfpt: Some(MeanFirstPassage {
                    mfpt,
                    lo,
                    hi,
                    fall_rate,
                    steps: 1000,
                }),
                ..Robustness::default()
            });
            o
        };
        let inf = f64::INFINITY;
        let rows = vec![
            row(0, Some(with(5171.0, 2537.0, inf, 1.9e-4, 4.6))),
            row(1, Some(with(inf, inf, inf, 0.0, f64::NAN))),
            row(2, Some(with(146.1, 85.3, 1174.3, 0.0074, 4.6))),
        ];
        let b = with_robustness(to_batch(&rows), &rows, &options);
        let (mfpt, lo, hi, rate, gsn) = (
            column(&b, "mfpt"),
            column(&b, "mfpt_lo"),
            column(&b, "mfpt_hi"),
            column(&b, "fall_rate"),
            column(&b, "gsn"),
        );
        assert_eq!(hi.null_count(), 0, "mfpt_hi: {hi:?}");
        assert_eq!(hi.value(0), inf);
        assert_eq!((mfpt.value(1), lo.value(1), hi.value(1)), (inf, inf, inf));
        assert_eq!(rate.value(1), 0.0);
        assert_eq!(hi.value(2), 1174.3);
        assert!(gsn.is_null(1), "a NaN measure is null: {gsn:?}");
        assert_eq!(gsn.value(0), 4.6);
    }
}
