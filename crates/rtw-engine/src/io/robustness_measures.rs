//! The robustness measures a scan row can carry (docs/robustness.md), by
//! name: which option switches each on and where its value is. The scan's
//! optional columns (`robustness_columns`) and a row's JSON and text forms
//! (`scan_rows`) both list them from here, in this order.

use rtw_model::options::RobustnessOptions;
use rtw_model::outcome::{PhaseSurvival, Robustness};

/// One optional column: the measure that switches it on and its value.
pub(crate) struct RobustnessColumn {
    pub(crate) name: &'static str,
    pub(crate) unit: &'static str,
    pub(crate) description: &'static str,
    pub(crate) on: fn(&RobustnessOptions) -> bool,
    get: Get,
}

/// Where a column's value is.
enum Get {
    /// A measure of the gait.
    Measure(fn(&Robustness) -> Option<f64>),
    /// A share of the survival curve's point, `robustness.step_down_at`.
    Phase(fn(&PhaseSurvival) -> f64),
}

impl RobustnessColumn {
    /// The column's value in `m`, if measured.
    pub(crate) fn value(&self, m: &Robustness) -> Option<f64> {
        match self.get {
            Get::Measure(get) => get(m),
            Get::Phase(share) => m.step_down_at.as_ref().map(share),
        }
    }
}

/// Every optional column, in the order they follow the scan's columns.
const ROBUSTNESS_COLUMNS: &[RobustnessColumn] = &[
    RobustnessColumn {
        name: "step_down_max",
        unit: "m",
        description: "largest survivable step down of the gait at its best phase, the edge 0.05 L \
                      ahead of its front-most grounded tip (docs/robustness.md); null unless \
                      stable; only with robustness.step_down = true",
        on: |r| r.step_down,
        get: Get::Measure(|m| m.step_down_max),
    },
    RobustnessColumn {
        name: "step_down_h50",
        unit: "m",
        description: "step down over every phase: the height at which half of 20 edge positions \
                      spread over one step of the gait survive (docs/robustness.md); null unless \
                      stable; only with robustness.step_down_h50 = true",
        on: |r| r.step_down_h50,
        get: Get::Measure(|m| m.step_down_h50),
    },
    phase_share(
        "step_down_survival",
        "share of 20 edge positions spread over one step of the gait at which it survives a step \
         down of robustness.step_down_at m (a point of its survival curve, docs/robustness.md); \
         null unless stable; only with robustness.step_down_at > 0",
        |p| p.survived,
    ),
    phase_share(
        "step_down_collapse",
        "share of the 20 edge positions at which that step down ends in a collapse",
        |p| p.collapse,
    ),
    phase_share(
        "step_down_stall",
        "share of the 20 edge positions at which that step down ends in a stall",
        |p| p.stall,
    ),
    phase_share(
        "step_down_other_gait",
        "share of the 20 edge positions from which the gait walks on in another gait",
        |p| p.other_gait,
    ),
    phase_share(
        "step_down_diverged",
        "share of the 20 edge positions at which the run over that step down fails numerically",
        |p| p.diverged,
    ),
    RobustnessColumn {
        name: "gsn",
        unit: "1",
        description: "gait sensitivity norm: H2 norm of the step time and length's response to a \
                      floor drop (docs/robustness.md); null unless stable or where it cannot be \
                      computed; only with robustness.gsn = true",
        on: |r| r.gsn,
        get: Get::Measure(|m| m.gsn),
    },
    RobustnessColumn {
        name: "steps_to_fall",
        unit: "steps",
        description: "mean steps to fall on seeded rough slopes of roughness robustness.sigma, \
                      censored at robustness.max_steps (a lower bound when \
                      steps_to_fall_censored > 0; docs/robustness.md); null unless stable; only \
                      with robustness.steps_to_fall = true",
        on: |r| r.steps_to_fall,
        get: Get::Measure(|m| m.steps_to_fall.map(|s| s.mean)),
    },
    RobustnessColumn {
        name: "steps_to_fall_lo",
        unit: "steps",
        description: "lower end of the 95 % interval of steps_to_fall (normal, mean - 1.96 \
                      standard errors, cut at 0)",
        on: |r| r.steps_to_fall,
        get: Get::Measure(|m| m.steps_to_fall.map(|s| s.lo)),
    },
    RobustnessColumn {
        name: "steps_to_fall_hi",
        unit: "steps",
        description: "upper end of the 95 % interval of steps_to_fall",
        on: |r| r.steps_to_fall,
        get: Get::Measure(|m| m.steps_to_fall.map(|s| s.hi)),
    },
    RobustnessColumn {
        name: "steps_to_fall_censored",
        unit: "trials",
        description: "how many of the robustness.trials Monte Carlo trials never fell",
        on: |r| r.steps_to_fall,
        get: Get::Measure(|m| m.steps_to_fall.map(|s| f64::from(s.censored))),
    },
    RobustnessColumn {
        name: "mfpt",
        unit: "steps",
        description: "mean first-passage time: expected steps of the flat gait to the fall from \
                      the quasi-stationary regime on seeded rough slopes of roughness \
                      robustness.sigma, uncensored (the falls of a Fleming–Viot cloud, \
                      counted; docs/robustness.md); inf (JSON \"inf\") when no fall was \
                      counted; null unless stable; only with robustness.mfpt = true",
        on: |r| r.mfpt,
        get: Get::Measure(|m| m.mfpt.map(|s| s.mfpt)),
    },
    RobustnessColumn {
        name: "mfpt_lo",
        unit: "steps",
        description: "lower end of the 95 % interval of mfpt",
        on: |r| r.mfpt,
        get: Get::Measure(|m| m.mfpt.map(|s| s.lo)),
    },
    RobustnessColumn {
        name: "mfpt_hi",
        unit: "steps",
        description: "upper end of the 95 % interval of mfpt (inf, JSON \"inf\", when the fall \
                      rate's interval reaches 0: the interval is open above)",
        on: |r| r.mfpt,
        get: Get::Measure(|m| m.mfpt.map(|s| s.hi)),
    },
    RobustnessColumn {
        name: "fall_rate",
        unit: "1/step",
        description: "per-step fall probability in the quasi-stationary regime on the rough \
                      slope, 1 / mfpt",
        on: |r| r.mfpt,
        get: Get::Measure(|m| m.mfpt.map(|s| s.fall_rate)),
    },
];

/// A column of the survival curve's point (`robustness.step_down_at`): one
/// share of its [`PhaseSurvival`], picked by `share`.
const fn phase_share(
    name: &'static str,
    description: &'static str,
    share: fn(&PhaseSurvival) -> f64,
) -> RobustnessColumn {
    RobustnessColumn {
        name,
        unit: "1",
        description,
        on: |r| r.step_down_at > 0.0,
        get: Get::Phase(share),
    }
}

/// The optional columns `on` picks.
pub(crate) fn picked(
    on: impl Fn(&RobustnessColumn) -> bool,
) -> impl Iterator<Item = &'static RobustnessColumn> {
    ROBUSTNESS_COLUMNS.iter().filter(move |c| on(c))
}
