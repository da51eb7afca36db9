//! Scan rows and their Parquet, JSON and text forms.
//!
//! One table, [`COLUMNS`], defines every column of a scan row: its name,
//! type, nullability, unit, meaning and how to read it from a [`Row`]. The
//! Parquet schema, the record batches, `simulate --json` and the `simulate`
//! text table are all generated from it, so they cannot drift apart.
//! `outcome` is a dictionary column with signed `Int32` keys over the fixed
//! label list [`Label::ALL`] (pandas and polars read it as categorical);
//! floats are `Float64`, counts `Int64`.

use crate::io::robustness_columns::{append, extend_schema};
use crate::io::robustness_measures::picked;
use crate::io::table::{self, Column, Get};
use arrow_array::RecordBatch;
use arrow_schema::{Schema, SchemaRef};
use rtw_model::options::RobustnessOptions;
use rtw_model::outcome::FailureDetail;
use rtw_model::{Label, Outcome, Params, Physical};
use serde::ser::{Serialize, SerializeMap, Serializer};
use std::sync::LazyLock;

/// One scan row: a sample's inputs, derived parameters and outcome.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// The sample's id in its scan.
    pub sample_id: u64,
    pub(crate) params: Params,
    pub(crate) physical: Physical,
    /// `None` when the simulation panicked (the row is then `diverged`).
    pub outcome: Option<Outcome>,
    /// Why a sample became `diverged` without an outcome (panic message).
    pub(crate) message: Option<String>,
    pub(crate) wall_time_s: f64,
}

impl Row {
    /// Why the sample became `diverged` without an outcome (its panic's
    /// message), if it did.
    pub fn message(&self) -> Option<&str> {
        self.message.as_deref()
    }

    /// The row's gait label, `diverged` when it has no outcome.
    pub fn label(&self) -> Label {
        self.outcome.map_or(Label::Diverged, |o| o.label)
    }
}

/// A float column of `group`.
const fn float(
    name: &'static str,
    group: &'static str,
    nullable: bool,
    unit: &'static str,
    description: &'static str,
    get: fn(&Row) -> Option<f64>,
) -> Column<Row> {
    Column {
        name,
        group,
        nullable,
        unit,
        description,
        get: Get::F64(get),
    }
}
const fn input(
    name: &'static str,
    unit: &'static str,
    description: &'static str,
    get: fn(&Row) -> Option<f64>,
) -> Column<Row> {
    float(name, "input", false, unit, description, get)
}
const fn derived(
    name: &'static str,
    unit: &'static str,
    description: &'static str,
    get: fn(&Row) -> Option<f64>,
) -> Column<Row> {
    float(name, "derived", false, unit, description, get)
}
/// Null when the sample panicked.
const fn metric(
    name: &'static str,
    unit: &'static str,
    description: &'static str,
    get: fn(&Row) -> Option<f64>,
) -> Column<Row> {
    float(name, "metric", true, unit, description, get)
}
const fn count(
    name: &'static str,
    group: &'static str,
    description: &'static str,
    get: fn(&Row) -> Option<i64>,
) -> Column<Row> {
    Column {
        name,
        group,
        nullable: true,
        unit: "1",
        description,
        get: Get::I64(get),
    }
}

/// Every column of a scan row, in file order. Metrics and counts are null in
/// a row whose sample panicked (its `message` says why).
pub static COLUMNS: &[Column<Row>] = &[
    Column {
        name: "sample_id",
        group: "id",
        nullable: false,
        unit: "-",
        description: "sample index; the row depends only on (seed, sample_id)",
        get: Get::I64(|r| Some(r.sample_id as i64)),
    },
    input("length", "m", "rod length L", |r| Some(r.params.length)),
    input("rho", "kg/m", "mass per length ρ of a rod", |r| {
        Some(r.params.rho)
    }),
    input(
        "alpha",
        "1",
        "connection ratio α: each string end sits α·L from a rod's tip",
        |r| Some(r.params.alpha),
    ),
    input(
        "fn",
        "Hz",
        "eigen-frequency f_n of the normalization (docs/model.md §1; the true mode is √3·f_n, §7)",
        |r| Some(r.params.f_n),
    ),
    input("zeta", "1", "damping ratio ζ of the normalization", |r| {
        Some(r.params.zeta)
    }),
    input("phi", "rad", "slope angle φ", |r| Some(r.params.phi)),
    derived("m", "kg", "rod mass m = ρ L", |r| Some(r.physical.m)),
    derived(
        "l_c",
        "m",
        "connection offset from each tip l_c = α L",
        |r| Some(r.physical.l_c),
    ),
    derived(
        "inertia",
        "kg·m²",
        "rod inertia about its centre I = m L²/12",
        |r| Some(r.physical.inertia),
    ),
    derived("r", "m", "connection radius r = L/2 − l_c", |r| {
        Some(r.physical.r)
    }),
    derived("k", "N/m", "string stiffness k", |r| Some(r.physical.k)),
    derived("c", "N·s/m", "string damping coefficient c", |r| {
        Some(r.physical.c)
    }),
    Column {
        name: "outcome",
        group: "outcome",
        nullable: false,
        unit: "-",
        description: "gait (skip, walk, crawl) or failure (collapse, stall, diverged), docs/model.md §5",
        get: Get::Label {
            index: |r| label_index(r.label()),
            names: label_names,
        },
    },
    Column {
        name: "failure",
        group: "outcome",
        nullable: true,
        unit: "-",
        description: "why the run failed (rod_down, com_low, no_standing_equilibrium, standing_rod_down, \
                      standing_com_low, standing_rolls_away, riser, no_touchdown, no_progress, non_finite, \
                      step_underflow, work_budget, zeno); null for a gait",
        get: Get::Str(|r| r.outcome.and_then(|o| o.failure).map(|f| f.as_str())),
    },
    Column {
        name: "message",
        group: "outcome",
        nullable: true,
        unit: "-",
        description: "the error message of a sample that panicked (outcome diverged), else what its \
                      failure means in words; null for a gait",
        // A panic's message, else what the failure means in words.
        get: Get::Str(|r| {
            r.message.as_deref().or_else(|| {
                r.outcome
                    .and_then(|o| o.failure)
                    .map(FailureDetail::describe)
            })
        }),
    },
    Column {
        name: "start",
        group: "outcome",
        nullable: true,
        unit: "-",
        description: "how the star stood before the push: two_feet, three_feet (static equilibrium), \
                      rest_shape (not in equilibrium), docs/model.md §6",
        get: Get::Str(|r| r.outcome.map(|o| o.start.as_str())),
    },
    metric(
        "t_end",
        "s",
        "simulated time at the end of the run (t_max unless it failed or settled early)",
        |r| r.outcome.map(|o| o.t_end),
    ),
    metric(
        "nlsp",
        "1",
        "fraction of the analysis window with no foot on the ground (flight)",
        |r| r.outcome.map(|o| o.fractions.nlsp),
    ),
    metric(
        "slsp",
        "1",
        "fraction of the analysis window with one rod on the ground",
        |r| r.outcome.map(|o| o.fractions.slsp),
    ),
    metric(
        "dlsp",
        "1",
        "fraction of the analysis window with two rods on the ground",
        |r| r.outcome.map(|o| o.fractions.dlsp),
    ),
    metric(
        "tlsp",
        "1",
        "fraction of the analysis window with three rods on the ground",
        |r| r.outcome.map(|o| o.fractions.tlsp),
    ),
    count(
        "window_steps",
        "metric",
        "whole steps (one new foot's touchdown to the next) in the analysis window",
        |r| r.outcome.map(|o| o.step_shares.steps as i64),
    ),
    metric(
        "flight_steps",
        "1",
        "share of the window's steps whose own flight fraction exceeds labels.flight (docs/model.md §5)",
        |r| r.outcome.map(|o| o.step_shares.flight),
    ),
    metric(
        "triple_steps",
        "1",
        "share of the window's steps whose own triple-support fraction exceeds labels.triple",
        |r| r.outcome.map(|o| o.step_shares.triple),
    ),
    count(
        "touchdowns",
        "metric",
        "touchdowns over the whole run",
        |r| r.outcome.map(|o| o.touchdowns as i64),
    ),
    metric(
        "f_w",
        "Hz",
        "step frequency: touchdowns per second over the analysis window",
        |r| r.outcome.map(|o| o.f_w),
    ),
    metric(
        "f_w_newfoot",
        "Hz",
        "touchdowns of a tip other than the one that rod last landed on, per second over the analysis window",
        |r| r.outcome.map(|o| o.f_w_newfoot),
    ),
    metric(
        "speed",
        "m/s",
        "mean downhill speed of the centre of mass over the analysis window",
        |r| r.outcome.map(|o| o.speed),
    ),
    metric(
        "mu_required",
        "1",
        "largest |λ_x|/λ_y while a rod sticks with λ_y > 0.05 m g, over the analysis window (docs/model.md §4)",
        |r| r.outcome.map(|o| o.mu_required),
    ),
    metric(
        "slide_time",
        "s",
        "rod-seconds spent sliding over the whole run",
        |r| r.outcome.map(|o| o.slide_time),
    ),
    metric(
        "energy_initial",
        "J",
        "total energy at the start (kinetic, string and gravity potential)",
        |r| r.outcome.map(|o| o.energy.initial),
    ),
    metric(
        "energy_last",
        "J",
        "total energy at the end of the run",
        |r| r.outcome.map(|o| o.energy.last),
    ),
    metric(
        "energy_gravity_released",
        "J",
        "potential energy of gravity released over the run",
        |r| r.outcome.map(|o| o.energy.gravity_released),
    ),
    metric(
        "energy_impact_loss",
        "J",
        "energy lost in touchdown impacts",
        |r| r.outcome.map(|o| o.energy.impact_loss),
    ),
    metric(
        "energy_damping_loss",
        "J",
        "energy dissipated by the string dampers",
        |r| r.outcome.map(|o| o.energy.damping_loss),
    ),
    metric(
        "energy_friction_loss",
        "J",
        "work of sliding friction (finite μ only)",
        |r| r.outcome.map(|o| o.energy.friction_loss),
    ),
    metric(
        "energy_balance_error",
        "J",
        "energy_last + the three losses − energy_initial: zero up to integration error",
        |r| r.outcome.map(|o| o.energy.balance_error),
    ),
    // From the step map's Newton solution when the run asked for its limit
    // cycle (`limit_cycle = true`) and one was found, else from the
    // touchdown return times.
    count(
        "period",
        "metric",
        "the gait's period, two ways (0: none found): with limit_cycle = true and a cycle found, in steps on \
         the step map (new-foot touchdowns, the star's 60° symmetry factored out; Newton at rtol 1e-11); \
         else in touchdowns on the touchdown return map (step time and the landing rod's ω repeating within 1e-3, \
         at the run's own tolerance), which can be a multiple: the Fig. 7(a) walk gives 3 at rtol 1e-4, 1 on the step map",
        |r| {
            r.outcome
                .map(|o| i64::from(o.cycle.map_or(o.period, |c| c.period)))
        },
    ),
    metric(
        "floquet_max",
        "1",
        "largest Floquet multiplier modulus of the gait's limit cycle (< 1: stable); null unless limit_cycle = true found one",
        |r| r.outcome.and_then(|o| o.cycle).map(|c| c.floquet_max),
    ),
    metric(
        "cycle_residual",
        "1",
        "scaled Newton residual |Pⁿ(z) − z| of the limit cycle's fixed point; null as floquet_max",
        |r| r.outcome.and_then(|o| o.cycle).map(|c| c.residual),
    ),
    count("steps", "work", "accepted integrator steps", |r| {
        r.outcome.map(|o| o.work.steps as i64)
    }),
    count("rejected", "work", "rejected integrator steps", |r| {
        r.outcome.map(|o| o.work.rejected as i64)
    }),
    count(
        "rhs_evals",
        "work",
        "right-hand-side evaluations (the machine-independent work)",
        |r| r.outcome.map(|o| o.work.rhs_evals as i64),
    ),
    count(
        "events",
        "work",
        "events located (touchdowns, lift-offs, mode switches)",
        |r| r.outcome.map(|o| o.work.events as i64),
    ),
    Column {
        name: "wall_time_s",
        group: "work",
        nullable: false,
        unit: "s",
        description: "wall-clock time of this sample's simulation (machine-dependent)",
        get: Get::F64(|r| Some(r.wall_time_s)),
    },
];

static SCHEMA: LazyLock<SchemaRef> = LazyLock::new(|| table::schema(COLUMNS));

/// The Arrow schema of scan rows.
pub fn schema() -> SchemaRef {
    SCHEMA.clone()
}

/// Position of a label in [`Label::ALL`]: its dictionary key in the
/// `outcome` column and its slot in per-label counts.
pub fn label_index(label: Label) -> usize {
    Label::ALL
        .iter()
        .position(|l| *l == label)
        .expect("every label is in Label::ALL")
}

/// The values of the `outcome` dictionary, in key order.
fn label_names() -> Vec<&'static str> {
    Label::ALL.iter().map(|l| l.as_str()).collect()
}

/// Rows → one record batch: the columns of [`COLUMNS`], then the
/// robustness columns `asked` switches on, in [`schema_for`]`(asked)`. The
/// one way scan rows become a batch (a scan's chunks, the in-memory scan, a
/// slope profile), so none can leave the robustness columns out.
pub fn to_batch(rows: &[Row], asked: &RobustnessOptions) -> RecordBatch {
    let batch = table::batch(COLUMNS, schema(), rows);
    append(batch, rows, |r| r.outcome.and_then(|o| o.robustness), asked)
}

/// The schema of scan rows under `asked`: [`schema`], then the robustness
/// columns it switches on.
pub fn schema_for(asked: &RobustnessOptions) -> SchemaRef {
    extend_schema(schema(), picked(|c| (c.on)(asked)))
}

/// The schema of scan files whose first file has schema `first`: [`schema`],
/// then the robustness columns it carries.
pub(crate) fn schema_of_files(first: &Schema) -> SchemaRef {
    extend_schema(
        schema(),
        picked(|c| first.column_with_name(c.name).is_some()),
    )
}

/// A row as one flat JSON object, keys in column order (`outcome` is the
/// label string; absent metrics and non-finite floats are `null`), then the
/// robustness measures its options asked for (the second field): one set
/// of keys for given options, however the run ended; an infinite measure
/// is `"inf"`, not null (`super::robustness_columns::json_value`).
pub struct JsonRow<'a>(pub &'a Row, pub &'a RobustnessOptions);

impl Serialize for JsonRow<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let r = self.0;
        let mut map = s.serialize_map(Some(COLUMNS.len()))?;
        for c in COLUMNS {
            match &c.get {
                Get::F64(g) => map.serialize_entry(c.name, &g(r).filter(|v| v.is_finite()))?,
                Get::I64(g) => map.serialize_entry(c.name, &g(r))?,
                Get::Bool(g) => map.serialize_entry(c.name, &g(r))?,
                Get::Str(g) => map.serialize_entry(c.name, &g(r))?,
                Get::Label { index, names } => map.serialize_entry(c.name, names()[index(r)])?,
            }
        }
        for (name, value) in robustness_entries(r, self.1) {
            map.serialize_entry(name, &super::robustness_columns::json_value(value))?;
        }
        map.end()
    }
}

/// The value of one column of a scan row as `simulate --json` has it: an
/// absent metric and a non-finite float are `None` (of the robustness
/// measures, only NaN: an infinite one, JSON's `"inf"`, stays infinite);
/// `outcome` is the label's name. What the Python package's `Outcome` holds, without going through
/// JSON text.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    /// A `Float64` column.
    Float(Option<f64>),
    /// An `Int64` column.
    Int(Option<i64>),
    /// A `Boolean` column.
    Bool(Option<bool>),
    /// A string or label column.
    Text(Option<String>),
}

/// The type of a scan row's column as [`Value`] has it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// [`Value::Float`].
    Float,
    /// [`Value::Int`].
    Int,
    /// [`Value::Bool`].
    Bool,
    /// [`Value::Text`].
    Text,
}

/// A scan row's column as a library user reads it: name, [`Kind`], and
/// whether it may be null (`None`). Listed by [`row_columns`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ColumnKind {
    /// The column's name (`speed`).
    pub name: &'static str,
    /// Its type.
    pub kind: Kind,
    /// Null when the sample panicked or the metric does not apply.
    pub nullable: bool,
}

/// Every column of a scan row in file order, from `COLUMNS`.
pub fn row_columns() -> impl ExactSizeIterator<Item = ColumnKind> {
    COLUMNS.iter().map(|c| ColumnKind {
        name: c.name,
        kind: match c.get {
            Get::F64(_) => Kind::Float,
            Get::I64(_) => Kind::Int,
            Get::Bool(_) => Kind::Bool,
            Get::Str(_) | Get::Label { .. } => Kind::Text,
        },
        nullable: c.nullable,
    })
}

/// A row's values in column order, as [`JsonRow`] writes them.
pub(crate) fn values(r: &Row) -> Vec<Value> {
    COLUMNS
        .iter()
        .map(|c| match &c.get {
            Get::F64(g) => Value::Float(g(r).filter(|v| v.is_finite())),
            Get::I64(g) => Value::Int(g(r)),
            Get::Bool(g) => Value::Bool(g(r)),
            Get::Str(g) => Value::Text(g(r).map(str::to_string)),
            Get::Label { index, names } => Value::Text(Some(names()[index(r)].to_string())),
        })
        .collect()
}

/// The robustness measures `asked` for (`robustness.*`,
/// docs/robustness.md), after the scan row's columns in its JSON and text
/// forms: none unless asked for, so a row's form is unchanged by default;
/// each asked for, with its value or `None`, whatever became of the run (a
/// star that could not stand, a panic, a gait that is not stable), so that
/// the keys depend on the options alone, as a scan file's columns do.
pub fn robustness_entries(r: &Row, asked: &RobustnessOptions) -> Vec<(&'static str, Option<f64>)> {
    let measured = r.outcome.and_then(|o| o.robustness);
    picked(|c| (c.on)(asked))
        .map(|c| (c.name, measured.as_ref().and_then(|m| c.value(m))))
        .collect()
}

/// A row as a readable two-column table, grouped by section.
pub fn row_text(r: &Row, asked: &RobustnessOptions) -> String {
    let mut out = String::new();
    let mut group = "";
    for c in COLUMNS {
        if c.group != group {
            group = c.group;
            out.push_str(&format!("[{group}]\n"));
        }
        let value = match &c.get {
            Get::F64(g) => g(r).map(|v| format!("{v:.6}")),
            Get::I64(g) => g(r).map(|v| v.to_string()),
            Get::Bool(g) => g(r).map(|v| v.to_string()),
            Get::Str(g) => g(r).map(str::to_string),
            Get::Label { index, names } => Some(names()[index(r)].to_string()),
        };
        out.push_str(&format!(
            "  {:<24} {}\n",
            c.name,
            value.as_deref().unwrap_or("-")
        ));
    }
    let robustness = robustness_entries(r, asked);
    if !robustness.is_empty() {
        out.push_str("[robustness]\n");
    }
    for (name, value) in robustness {
        let value = value.map_or("-".to_string(), |v| format!("{v:.6}"));
        out.push_str(&format!("  {name:<24} {value}\n"));
    }
    out
}

#[cfg(test)]
pub(crate) mod tests {
    #[test]
    fn text_form_groups_the_columns() {
        let r = row(4, Some(outcome(Label::Walk)));
        let text = row_text(&r, &Default::default());
        assert!(text.contains("[metric]") && text.contains("outcome") && text.contains("walk"));
    }

    #[test]
    fn the_failure_column_description_names_every_failure_detail() {
        // The description is a fixed string in the file's field metadata; a
        // failure kind added to rtw-model must be named there too.
        let col = COLUMNS.iter().find(|c| c.name == "failure").unwrap();
        for f in rtw_model::outcome::FailureDetail::ALL {
            assert!(
                col.description.contains(f.as_str()),
                "the failure column's description does not name {}",
                f.as_str()
            );
        }
    }

    use super::*;
    use crate::io::metadata::META_SEED;
    use crate::io::parquet::{open, write_file};
    use crate::io::table::{f64_column, label_column, label_type};
    use ::parquet::file::metadata::KeyValue;
    use arrow_array::Array;
    use arrow_array::cast::AsArray;
    use rtw_model::Normalization;
    use rtw_model::outcome::{
        ContactFractions, Energy, FailureDetail, IntegratorWork, MeanFirstPassage, Robustness,
    };

    pub(crate) fn outcome(label: Label) -> Outcome {
        Outcome {
            label,
            failure: (label == Label::Stall).then_some(FailureDetail::NoTouchdown),
            start: rtw_model::outcome::Stance::TwoFeet,
            t_end: 20.0,
            fractions: ContactFractions {
                nlsp: 0.1,
                slsp: 0.5,
                dlsp: 0.4,
                tlsp: 0.0,
            },
            step_shares: rtw_model::outcome::StepShares {
                steps: 30,
                flight: 0.4,
                triple: 0.0,
            },
            touchdowns: 40,
            f_w: 3.2,
            f_w_newfoot: 2.9,
            speed: 0.8,
            mu_required: 7.5,
            slide_time: 0.01,
            energy: Energy::default(),
            period: 1,
            cycle: Some(rtw_model::CycleSummary {
                period: 1,
                floquet_max: 0.8,
                residual: 1e-10,
            }),
            work: IntegratorWork {
                steps: 100,
                rejected: 3,
                rhs_evals: 700,
                events: 50,
            },
            robustness: None,
        }
    }

    pub(crate) fn row(id: u64, outcome: Option<Outcome>) -> Row {
        let params = Params::fig7a();
        Row {
            sample_id: id,
            params,
            physical: Physical::new(&params, Normalization::Supplementary, 9.81),
            outcome,
            message: outcome.is_none().then(|| "boom".to_string()),
            wall_time_s: 0.25,
        }
    }

    #[test]
    fn batch_has_every_column_and_signed_dictionary_keys() {
        let rows = vec![
            row(0, Some(outcome(Label::Walk))),
            row(1, None),
            row(2, Some(outcome(Label::Stall))),
        ];
        let b = to_batch(&rows, &Default::default());
        assert_eq!(b.num_rows(), 3);
        assert_eq!(b.num_columns(), COLUMNS.len());
        assert_eq!(
            b.schema().field_with_name("outcome").unwrap().data_type(),
            &label_type()
        );
        assert_eq!(
            label_column(&b).unwrap(),
            vec![Label::Walk, Label::Diverged, Label::Stall]
        );
        let t_end = f64_column(&b, "t_end").unwrap();
        assert!(t_end.is_valid(0) && t_end.is_null(1));
        let failure = b.column_by_name("failure").unwrap().as_string::<i32>();
        assert!(failure.is_null(0));
        assert_eq!(failure.value(2), "no_touchdown");
        let message = b.column_by_name("message").unwrap().as_string::<i32>();
        assert_eq!(message.value(1), "boom");
    }

    #[test]
    fn parquet_round_trip_keeps_types_and_metadata() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("x.parquet");
        let rows: Vec<Row> = (0..5).map(|i| row(i, Some(outcome(Label::Skip)))).collect();
        write_file(
            &path,
            &to_batch(&rows, &Default::default()),
            vec![KeyValue::new(META_SEED.into(), "7".to_string())],
        )
        .unwrap();
        let input = open(&path, 100).unwrap();
        assert_eq!(input.rows, 5);
        assert_eq!(input.metadata[META_SEED], "7");
        let batches: Vec<RecordBatch> = input.reader.collect::<Result<_, _>>().unwrap();
        assert_eq!(batches[0].schema().fields(), schema().fields());
        assert_eq!(batches[0], to_batch(&rows, &Default::default()));
        // Nothing but the file is left in the directory.
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn json_is_flat_and_ordered() {
        let r = row(4, Some(outcome(Label::Walk)));
        let s = serde_json::to_string(&JsonRow(&r, &Default::default())).unwrap();
        let v: serde_json::Value = serde_json::from_str(&s).unwrap();
        assert_eq!(v["outcome"], "walk");
        assert_eq!(v["slsp"], 0.5);
        assert_eq!(v["steps"], 100);
        assert_eq!(v["k"].as_f64().unwrap().round(), 500.0);
        assert!(v["failure"].is_null());
        assert!(s.starts_with("{\"sample_id\":4,\"length\":0.8"));
        let d = serde_json::to_value(JsonRow(&row(1, None), &Default::default())).unwrap();
        assert_eq!(d["outcome"], "diverged");
        assert_eq!(d["message"], "boom");
        assert!(d["t_end"].is_null());
        // Every field of Outcome has a column: nested structs flatten to
        // their field names (`energy` with an `energy_` prefix).
        let o = serde_json::to_value(r.outcome.unwrap()).unwrap();
        for (k, val) in o.as_object().unwrap() {
            let names: Vec<String> = match val.as_object() {
                Some(inner) if k == "energy" => {
                    inner.keys().map(|f| format!("energy_{f}")).collect()
                }
                Some(inner) if k == "step_shares" => inner
                    .keys()
                    .map(|f| match f.as_str() {
                        "steps" => "window_steps".into(),
                        _ => format!("{f}_steps"),
                    })
                    .collect(),
                Some(inner) if k == "cycle" => inner
                    .keys()
                    .map(|f| match f.as_str() {
                        "residual" => "cycle_residual".into(),
                        _ => f.clone(),
                    })
                    .collect(),
                Some(inner) => inner.keys().cloned().collect(),
                None if k == "label" => vec!["outcome".into()],
                None => vec![k.clone()],
            };
            for n in names {
                assert!(
                    COLUMNS.iter().any(|c| c.name == n),
                    "Outcome field {n} has no column"
                );
            }
        }
    }

    #[test]
    fn an_mfpt_open_above_keeps_its_infinite_upper_end_and_nan_is_null() {
        // A gait whose fall rate's interval reaches 0 has mfpt_hi = ∞, and
        // one whose estimator saw no fall has mfpt = mfpt_lo = ∞: both are
        // measured, unlike a measure that could not be computed (NaN), and a
        // reader must tell them apart.
        let asked = RobustnessOptions {
            mfpt: true,
            gsn: true,
            ..RobustnessOptions::default()
        };
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
        let b = to_batch(&rows, &asked);
        assert_eq!(b.schema(), schema_for(&asked));
        let column = |name| f64_column(&b, name).unwrap();
        let (mfpt, lo, hi, rate, gsn) = (
            column("mfpt"),
            column("mfpt_lo"),
            column("mfpt_hi"),
            column("fall_rate"),
            column("gsn"),
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
