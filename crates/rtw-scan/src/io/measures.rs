//! The robustness measures a run can be asked for (`robustness.*`,
//! docs/robustness.md), as they appear after a scan row's columns: in the
//! JSON row, the text form and the optional Parquet columns, in this order.

use rtw_model::options::RobustnessOptions;
use rtw_model::outcome::Robustness;

/// One robustness measure's column.
pub(crate) struct Measure {
    /// Its name (the column, the JSON key, the Python attribute).
    pub(crate) name: &'static str,
    /// Its unit (Parquet field metadata).
    pub(crate) unit: &'static str,
    /// Its description (Parquet field metadata).
    pub(crate) doc: &'static str,
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
