//! Bifurcation diagrams: one parameter swept with continuation on the step
//! map ([`rtw_model::stepmap`]), a step quantity recorded after transients,
//! and the limit cycle's Floquet multipliers at every value.
//!
//! At each value, in sweep order, the map starts from the previous value's
//! last section point (continuation: the gait followed is the one the robot
//! was in, not the one a fresh start finds); the first value, and any value
//! where the map fails from the continued point, starts from the initial
//! state instead (`restarted`). After `transient` steps, `record` steps are
//! kept (post-impact angular velocity of the new stance rod, step time); the
//! period is detected on their section points, and a periodic gait is solved
//! for the fixed point of `Pⁿ` by Newton with variational Jacobians, giving
//! its multipliers. The gait label comes from the recorded steps' contact
//! fractions; a failed step gets the scan's failure label (collapse, stall,
//! diverged) or, when the map itself stopped, `failure` ([`PointLabel`]),
//! and its reason.
//!
//! Output: `FILE.parquet`, one row per parameter value ([`points_schema`]),
//! and `FILE.steps.parquet`, one row per recorded step ([`steps_schema`]),
//! with the resolved options, the swept parameter and the base point in the
//! metadata; and a markdown summary ([`summary_markdown`]).

use crate::config;
use crate::output::{self, kv};
use anyhow::{Result, bail};
use arrow_array::types::Int32Type;
use arrow_array::{
    ArrayRef, BooleanArray, DictionaryArray, Float64Array, Int32Array, Int64Array, RecordBatch,
    StringArray,
};
use arrow_schema::{DataType, Field, Schema, SchemaRef};
use parquet::file::metadata::KeyValue;
use rtw_model::limit;
use rtw_model::stepmap::{
    CycleError, CycleOptions, LimitCycle, SectionPoint, Step, StepError, StepMap,
};
use rtw_model::{Label, Options, ParamError, Params};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

/// The parameters a sweep can vary: the six inputs of docs/model.md §1 and `s`,
/// the strings' rest-length ratio (`strings.rest_length_ratio`).
pub const SWEEP_KEYS: [&str; 7] = ["length", "rho", "alpha", "fn", "zeta", "phi", "s"];

/// The swept parameter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SweepParam {
    /// Input `i` of [`config::PARAM_KEYS`].
    Input(usize),
    /// `strings.rest_length_ratio`.
    RestLengthRatio,
}

impl SweepParam {
    /// Parses a name of [`SWEEP_KEYS`]; the error names `--param` and the choices.
    pub fn parse(name: &str) -> Result<Self> {
        if name == "s" {
            return Ok(Self::RestLengthRatio);
        }
        match config::PARAM_KEYS.iter().position(|k| *k == name) {
            Some(i) => Ok(Self::Input(i)),
            None => bail!(
                "--param: unknown parameter `{name}`: must be one of {}",
                SWEEP_KEYS.join(", ")
            ),
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Self::Input(i) => config::PARAM_KEYS[i],
            Self::RestLengthRatio => "s",
        }
    }

    /// The parameters and options at value `v` of this parameter, the rest
    /// from `base` and `options`; an invalid `v` is named by `Params::validate`
    /// or `Options::validate`.
    pub fn at(
        self,
        base: &Params,
        options: &Options,
        v: f64,
    ) -> Result<(Params, Options), ParamError> {
        let (mut p, mut o) = (*base, *options);
        match self {
            Self::Input(i) => *config::param_mut(&mut p, i) = v,
            Self::RestLengthRatio => o.strings.rest_length_ratio = v,
        }
        p.validate()?;
        o.validate()?;
        Ok((p, o))
    }

    /// Checks a bound of the sweep given with `flag`.
    fn check(self, base: &Params, options: &Options, v: f64, flag: &str) -> Result<()> {
        match self.at(base, options, v) {
            Ok(_) => Ok(()),
            Err(e) => bail!(
                "{flag}: {v} is invalid for --param {}: {} must be {}",
                self.name(),
                e.field,
                e.range
            ),
        }
    }
}

/// A sweep: which parameter, its values in order, the base point and model,
/// and how many steps to settle and to record at each value.
#[derive(Clone, Debug)]
pub struct Sweep {
    pub param: SweepParam,
    pub values: Vec<f64>,
    pub base: Params,
    pub options: Options,
    pub transient: usize,
    pub record: usize,
    pub cycle: CycleOptions,
}

/// Most values of a sweep: its rows are held in memory until written.
pub const MAX_POINTS: usize = 1_000_000;
/// Most recorded steps per value (periods up to 12 are detected).
pub const MAX_RECORD: usize = 10_000;
/// Most transient steps per value.
pub const MAX_TRANSIENT: usize = 10_000_000;

impl Sweep {
    /// `points` values from `from` to `to` (inclusive, either direction),
    /// checked: both ends valid for the parameter, `points ≥ 2`, `record ≥ 2`
    /// (a period-1 gait needs two section points to be recognised).
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        param: SweepParam,
        from: f64,
        to: f64,
        points: usize,
        base: Params,
        options: Options,
        transient: usize,
        record: usize,
    ) -> Result<Self> {
        if let Err(e) = base.validate() {
            bail!("--{}: {} is invalid: must be {}", e.field, e.value, e.range);
        }
        config::validate_options(&options, "simulation")?;
        param.check(&base, &options, from, "--from")?;
        param.check(&base, &options, to, "--to")?;
        if !(2..=MAX_POINTS).contains(&points) {
            bail!(
                "--points: {points} is invalid: must be an integer >= 2 and at most {MAX_POINTS}"
            );
        }
        if !(2..=MAX_RECORD).contains(&record) {
            bail!(
                "--record: {record} is invalid: must be an integer >= 2 and at most {MAX_RECORD}"
            );
        }
        if transient > MAX_TRANSIENT {
            bail!("--transient: {transient} is invalid: must be at most {MAX_TRANSIENT}");
        }
        Ok(Self {
            param,
            values: config::linspace(from, to, points as u64),
            base,
            options,
            transient,
            record,
            cycle: CycleOptions::default(),
        })
    }
}

/// One parameter value of a sweep.
#[derive(Clone, Debug, PartialEq)]
pub struct PointRow {
    pub value: f64,
    pub label: PointLabel,
    /// Period of the solved cycle: the period of the recorded section points,
    /// or a divisor of it when the fixed point found has a shorter one
    /// (`None`: no period ≤ the longest looked for, e.g. quasi-periodic or
    /// chaotic iterates; or a failure).
    pub period: Option<usize>,
    /// Largest Floquet multiplier modulus of the solved cycle.
    pub floquet_max: Option<f64>,
    /// The largest multiplier itself (its sign and phase tell the type of a
    /// bifurcation: −1 period doubling, +1 fold, a complex pair Neimark–Sacker).
    pub mu_re: Option<f64>,
    pub mu_im: Option<f64>,
    pub stable: Option<bool>,
    /// The map failed from the continued point and this value started again
    /// from the initial state.
    pub restarted: bool,
    /// Newton's scaled residual `|Pⁿ(z) − z|` at the fixed point.
    pub residual: Option<f64>,
    pub newton_iterations: Option<u32>,
    /// Why Newton found no fixed point although the iterates were periodic.
    pub newton_error: Option<String>,
    /// Why the step map failed (then `label` is collapse, stall, diverged or failure).
    pub failure: Option<String>,
    pub wall_time_s: f64,
}

impl PointRow {
    /// A row with its label only (no period, cycle or failure yet).
    fn new(value: f64, label: PointLabel) -> Self {
        Self {
            value,
            label,
            period: None,
            floquet_max: None,
            mu_re: None,
            mu_im: None,
            stable: None,
            restarted: false,
            residual: None,
            newton_iterations: None,
            newton_error: None,
            failure: None,
            wall_time_s: 0.0,
        }
    }
}

/// One recorded step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StepRow {
    pub value: f64,
    /// Index among the recorded steps (0 … record − 1).
    pub k: usize,
    /// Post-impact angular velocity of the new stance rod (rad/s).
    pub omega: f64,
    pub step_time: f64,
    /// Downhill advance of the landing foot (m).
    pub advance: f64,
    pub label: PointLabel,
}

/// The label of a value: a gait or a run's failure label (the scan's
/// [`Label`]), or `failure` when the step map itself stopped (no new foot
/// within the step horizon, or the landing foot left at once): the map cannot
/// say whether the star stopped (a stall) or went on in a way that has no
/// step on its section.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PointLabel {
    Outcome(Label),
    Failure,
}

/// The values of the `label` dictionary column, in key order.
pub const LABELS: [&str; 7] = [
    "skip", "walk", "crawl", "collapse", "stall", "diverged", "failure",
];

impl PointLabel {
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Outcome(l) => l.as_str(),
            Self::Failure => "failure",
        }
    }

    fn key(self) -> i32 {
        LABELS
            .iter()
            .position(|l| *l == self.as_str())
            .expect("every label is in LABELS") as i32
    }
}

/// The label of a failed step: the scan's label of a run's failure, a
/// numerical end as `diverged`, the map's own stops as `failure`.
fn failure_label(e: &StepError) -> PointLabel {
    match e {
        StepError::Failure(detail) => PointLabel::Outcome(detail.label()),
        StepError::Numerical(_) => PointLabel::Outcome(Label::Diverged),
        StepError::NoNewFoot | StepError::LandingFootLeft => PointLabel::Failure,
    }
}

/// A dictionary column (signed `Int32` keys, like the scan's `outcome`) over
/// the fixed value list [`LABELS`].
fn label_array(labels: impl Iterator<Item = PointLabel>) -> ArrayRef {
    let keys: Int32Array = labels.map(PointLabel::key).collect();
    let values = StringArray::from_iter_values(LABELS);
    Arc::new(DictionaryArray::<Int32Type>::try_new(keys, Arc::new(values)).expect("keys in range"))
}

/// `transient` then `record` steps from `start`; the recorded ones.
fn settle_and_record(
    map: &StepMap,
    start: &SectionPoint,
    sweep: &Sweep,
) -> Result<Vec<Step>, StepError> {
    let settled = match sweep.transient {
        0 => *start,
        n => map.iterate(start, n)?.last().expect("n > 0").to,
    };
    map.iterate(&settled, sweep.record)
}

/// Newton on `Pⁿ` from `start`, then on `Pᵈ` if the fixed point found has a
/// shorter period `d | n`: slowly converging iterates near a period doubling
/// look period-2 to [`StepMap::period_of`], while Newton on `P²` may land on
/// the period-1 orbit (a fixed point of `P²` too), whose own multipliers are
/// the ones that tell the bifurcation.
fn solve_minimal(
    map: &StepMap,
    start: &SectionPoint,
    n: usize,
    cycle: &CycleOptions,
) -> Result<LimitCycle, CycleError> {
    let lc = map.solve(start, n, cycle)?;
    let p = &lc.orbit[0];
    let scale = map.coord_scale(p);
    let shorter = (1..n).filter(|d| n.is_multiple_of(*d)).find(|&d| {
        let q = &lc.orbit[d];
        q.modes == p.modes
            && limit::scaled_max(&q.coords(), &p.coords(), &scale) <= cycle.period_tol
    });
    match shorter {
        Some(d) => map.solve(p, d, cycle),
        None => Ok(lc),
    }
}

/// The analysis at one value from the recorded steps: period, cycle, label.
fn analyse(
    map: &StepMap,
    sweep: &Sweep,
    options: &Options,
    value: f64,
    steps: &[Step],
) -> PointRow {
    let hist: Vec<SectionPoint> = steps.iter().map(|s| s.to).collect();
    let max_period = sweep.cycle.max_period.min(hist.len() / 2);
    let period = map.period_of(&hist, max_period, sweep.cycle.period_tol);
    let label = Step::label(steps, &options.labels);
    let mut row = PointRow {
        period,
        ..PointRow::new(value, PointLabel::Outcome(label))
    };
    if let Some(n) = period {
        match solve_minimal(map, hist.last().expect("record >= 2"), n, &sweep.cycle) {
            Ok(lc) => {
                row.period = Some(lc.period);
                row.floquet_max = Some(lc.floquet_max());
                // `multipliers` is sorted by modulus, largest first.
                row.mu_re = lc.multipliers.first().map(|m| m.re);
                row.mu_im = lc.multipliers.first().map(|m| m.im);
                row.stable = Some(lc.is_stable());
                row.residual = Some(lc.fixed_point.residual);
                row.newton_iterations = Some(lc.fixed_point.iterations);
            }
            Err(e) => row.newton_error = Some(e.to_string()),
        }
    }
    row
}

/// The result of one value: its row, its recorded steps, and the section
/// point the next value continues from (`None` after a failure).
struct PointResult {
    row: PointRow,
    steps: Vec<Step>,
    next: Option<SectionPoint>,
}

/// One value of the sweep, continued from `from` (or from the initial state).
fn sweep_point(sweep: &Sweep, value: f64, from: Option<SectionPoint>) -> PointResult {
    let t0 = Instant::now();
    let (params, options) = sweep
        .param
        .at(&sweep.base, &sweep.options, value)
        .expect("the sweep's ends were checked, and the values lie between them");
    let map = StepMap::new(&params, &options, &sweep.cycle);
    let fresh = || -> Result<Vec<Step>, StepError> {
        let first = map.first(&options)?;
        settle_and_record(&map, &first.to, sweep)
    };
    let (recorded, restarted) = match from {
        Some(p) => match settle_and_record(&map, &p, sweep) {
            Ok(steps) => (Ok(steps), false),
            Err(_) => (fresh(), true),
        },
        None => (fresh(), false),
    };
    let (mut row, steps, next) = match recorded {
        Ok(steps) => {
            let row = analyse(&map, sweep, &options, value, &steps);
            let next = steps.last().map(|s| s.to);
            (row, steps, next)
        }
        Err(e) => {
            let row = PointRow {
                failure: Some(e.to_string()),
                ..PointRow::new(value, failure_label(&e))
            };
            (row, Vec::new(), None)
        }
    };
    row.restarted = restarted;
    row.wall_time_s = t0.elapsed().as_secs_f64();
    PointResult { row, steps, next }
}

/// The whole sweep, in order (continuation is sequential), calling
/// `progress(i, row)` after each value.
pub fn run_sweep(
    sweep: &Sweep,
    mut progress: impl FnMut(usize, &PointRow),
) -> (Vec<PointRow>, Vec<StepRow>) {
    let mut points = Vec::with_capacity(sweep.values.len());
    let mut step_rows = Vec::new();
    let mut carry = None;
    for (i, &value) in sweep.values.iter().enumerate() {
        let r = sweep_point(sweep, value, carry);
        step_rows.extend(r.steps.iter().enumerate().map(|(k, s)| StepRow {
            value,
            k,
            omega: s.to.omega(),
            step_time: s.time,
            advance: s.advance,
            label: r.row.label,
        }));
        progress(i, &r.row);
        points.push(r.row);
        carry = r.next;
    }
    (points, step_rows)
}

/// One column of a bifurcation file: name, Arrow type, nullable, unit,
/// description (the last two go to the field metadata, [`crate::dictionary`]).
type ColumnDef = (&'static str, DataType, bool, &'static str, &'static str);

const PARAM: &str = "the swept parameter's name (length, rho, alpha, fn, zeta, phi or s)";
const VALUE: &str =
    "the swept parameter's value, in its unit in samples.parquet (s = rest_length_ratio: 1)";
const VALUE_UNIT: &str = "as param";

/// The per-value file's columns (`FILE.parquet`), in file order.
fn point_columns() -> [ColumnDef; 16] {
    use DataType::{Boolean, Float64, Int64, Utf8};
    [
        ("param", Utf8, false, "-", PARAM),
        ("value", Float64, false, VALUE_UNIT, VALUE),
        (
            "label",
            output::label_type(),
            false,
            "-",
            "gait or failure at this value; failure: the step map stopped (no new foot landed)",
        ),
        (
            "period",
            Int64,
            true,
            "1",
            "period of the solved cycle in steps; null: no period found (chaotic or failure)",
        ),
        (
            "floquet_max",
            Float64,
            true,
            "1",
            "largest Floquet multiplier modulus of the solved cycle (< 1: stable)",
        ),
        (
            "mu_re",
            Float64,
            true,
            "1",
            "real part of the largest multiplier (−1: period doubling, +1: fold)",
        ),
        (
            "mu_im",
            Float64,
            true,
            "1",
            "imaginary part of the largest multiplier (a complex pair: Neimark–Sacker)",
        ),
        ("stable", Boolean, true, "-", "floquet_max < 1"),
        (
            "restarted",
            Boolean,
            false,
            "-",
            "the map failed from the continued point and this value started again from the initial state",
        ),
        (
            "residual",
            Float64,
            true,
            "1",
            "Newton's scaled residual |Pⁿ(z) − z| at the fixed point",
        ),
        (
            "newton_iterations",
            Int64,
            true,
            "1",
            "Newton iterations to the fixed point",
        ),
        (
            "newton_error",
            Utf8,
            true,
            "-",
            "why Newton found no fixed point although the iterates were periodic",
        ),
        (
            "failure",
            Utf8,
            true,
            "-",
            "why the step map failed at this value",
        ),
        (
            "transient",
            Int64,
            false,
            "1",
            "steps iterated before recording (--transient)",
        ),
        ("record", Int64, false, "1", "steps recorded (--record)"),
        (
            "wall_time_s",
            Float64,
            false,
            "s",
            "wall-clock time of this value (machine-dependent)",
        ),
    ]
}

/// The per-step file's columns (`FILE.steps.parquet`), in file order.
fn step_columns() -> [ColumnDef; 7] {
    use DataType::{Float64, Int64, Utf8};
    [
        ("param", Utf8, false, "-", PARAM),
        ("value", Float64, false, VALUE_UNIT, VALUE),
        (
            "k",
            Int64,
            false,
            "-",
            "index among the recorded steps (0 … record − 1)",
        ),
        (
            "omega",
            Float64,
            false,
            "rad/s",
            "post-impact angular velocity of the new stance rod",
        ),
        (
            "step_time",
            Float64,
            false,
            "s",
            "time from the previous section crossing",
        ),
        (
            "advance",
            Float64,
            false,
            "m",
            "downhill advance of the landing foot",
        ),
        (
            "label",
            output::label_type(),
            false,
            "-",
            "the value's label (as in FILE.parquet)",
        ),
    ]
}

fn schema_of(columns: impl IntoIterator<Item = ColumnDef>) -> SchemaRef {
    let fields: Vec<Field> = columns
        .into_iter()
        .map(|(n, t, null, unit, description)| {
            crate::dictionary::field(n, t, null, unit, description)
        })
        .collect();
    Arc::new(Schema::new(fields))
}

/// The schema of the per-value file `FILE.parquet`: one row per value.
pub fn points_schema() -> SchemaRef {
    schema_of(point_columns())
}

/// The schema of the per-step file `FILE.steps.parquet`: one row per
/// recorded step.
pub fn steps_schema() -> SchemaRef {
    schema_of(step_columns())
}

fn f64s(it: impl Iterator<Item = Option<f64>>) -> ArrayRef {
    Arc::new(it.collect::<Float64Array>())
}

fn i64s(it: impl Iterator<Item = Option<i64>>) -> ArrayRef {
    Arc::new(it.collect::<Int64Array>())
}

/// Per-value rows → a record batch of [`points_schema`].
pub fn points_batch(sweep: &Sweep, rows: &[PointRow]) -> RecordBatch {
    let name = sweep.param.name();
    let n = rows.len();
    let arrays: Vec<ArrayRef> = vec![
        Arc::new(StringArray::from_iter_values(std::iter::repeat_n(name, n))),
        f64s(rows.iter().map(|r| Some(r.value))),
        label_array(rows.iter().map(|r| r.label)),
        i64s(rows.iter().map(|r| r.period.map(|p| p as i64))),
        f64s(rows.iter().map(|r| r.floquet_max)),
        f64s(rows.iter().map(|r| r.mu_re)),
        f64s(rows.iter().map(|r| r.mu_im)),
        Arc::new(rows.iter().map(|r| r.stable).collect::<BooleanArray>()),
        Arc::new(
            rows.iter()
                .map(|r| Some(r.restarted))
                .collect::<BooleanArray>(),
        ),
        f64s(rows.iter().map(|r| r.residual)),
        i64s(rows.iter().map(|r| r.newton_iterations.map(i64::from))),
        Arc::new(
            rows.iter()
                .map(|r| r.newton_error.as_deref())
                .collect::<StringArray>(),
        ),
        Arc::new(
            rows.iter()
                .map(|r| r.failure.as_deref())
                .collect::<StringArray>(),
        ),
        i64s(rows.iter().map(|_| Some(sweep.transient as i64))),
        i64s(rows.iter().map(|_| Some(sweep.record as i64))),
        f64s(rows.iter().map(|r| Some(r.wall_time_s))),
    ];
    RecordBatch::try_new(points_schema(), arrays).expect("arrays match the schema")
}

/// Per-step rows → a record batch of [`steps_schema`].
pub fn steps_batch(sweep: &Sweep, rows: &[StepRow]) -> RecordBatch {
    let name = sweep.param.name();
    let arrays: Vec<ArrayRef> = vec![
        Arc::new(StringArray::from_iter_values(std::iter::repeat_n(
            name,
            rows.len(),
        ))),
        f64s(rows.iter().map(|r| Some(r.value))),
        i64s(rows.iter().map(|r| Some(r.k as i64))),
        f64s(rows.iter().map(|r| Some(r.omega))),
        f64s(rows.iter().map(|r| Some(r.step_time))),
        f64s(rows.iter().map(|r| Some(r.advance))),
        label_array(rows.iter().map(|r| r.label)),
    ];
    RecordBatch::try_new(steps_schema(), arrays).expect("arrays match the schema")
}

/// Metadata key: the swept parameter.
pub const META_PARAM: &str = "rtw.bifurcation.param";
/// Metadata key: the base point (JSON of the six inputs).
pub const META_BASE: &str = "rtw.params";
/// Metadata key: the resolved simulation options (TOML).
pub const META_OPTIONS: &str = "rtw.options";
/// Metadata key: the step map's settings (integrator, tolerances, periods).
pub const META_CYCLE: &str = "rtw.cycle";

/// The file metadata of both output files.
pub fn metadata(sweep: &Sweep, wall_time_s: f64) -> Result<Vec<KeyValue>> {
    Ok(vec![
        kv(output::META_VERSION, env!("CARGO_PKG_VERSION").into()),
        kv(META_PARAM, sweep.param.name().into()),
        kv(META_BASE, serde_json::to_string(&sweep.base)?),
        kv(META_OPTIONS, toml::to_string(&sweep.options)?),
        kv(
            output::META_VARIANT,
            config::Variant::of(&sweep.options).to_string(),
        ),
        kv(META_CYCLE, format!("{:?}", sweep.cycle)),
        kv("rtw.bifurcation.transient", sweep.transient.to_string()),
        kv("rtw.bifurcation.record", sweep.record.to_string()),
        kv(output::META_WALL_TIME, format!("{wall_time_s:.3}")),
    ])
}

/// The per-step file beside the per-value file `out`: `NAME.steps.parquet`.
pub fn steps_path(out: &Path) -> PathBuf {
    let stem = out
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    out.with_file_name(format!("{stem}.steps.parquet"))
}

/// Writes both files; returns the per-step file's path.
pub fn write(
    out: &Path,
    sweep: &Sweep,
    points: &[PointRow],
    steps: &[StepRow],
    wall_time_s: f64,
) -> Result<PathBuf> {
    if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)?;
    }
    let meta = metadata(sweep, wall_time_s)?;
    output::write_file(out, &points_batch(sweep, points), meta.clone())?;
    let sp = steps_path(out);
    output::write_file(&sp, &steps_batch(sweep, steps), meta)?;
    Ok(sp)
}

/// The summary beside the per-value file `out`: `NAME.md`.
pub fn summary_path(out: &Path) -> PathBuf {
    out.with_extension("md")
}

/// The `bifurcation` subcommand once its arguments are checked: runs the
/// sweep (progress on stderr), writes both Parquet files and the summary
/// (`FILE.md`), and prints the summary.
/// Refuses, unless `force`, to write the sweep's files (`out`, its
/// `.steps.parquet` and `.md`) over files that are not a sweep's: another
/// kind of Parquet file, or an `.md` that is not the summary of a sweep at
/// `out`.
pub fn check_outputs(out: &Path, force: bool) -> Result<()> {
    use output::FileKind::Bifurcation;
    output::check_destination(out, Bifurcation, &[], "--out", force)?;
    output::check_destination(
        &steps_path(out),
        Bifurcation,
        &[],
        "--out (steps file)",
        force,
    )?;
    let md = summary_path(out);
    if !force && md.exists() && !out.exists() {
        bail!(
            "--out {}: {} exists and is not the summary of a sweep there: refusing to replace it; \
             choose another file, or pass --force",
            out.display(),
            md.display()
        );
    }
    for f in [out.to_path_buf(), steps_path(out), md] {
        output::remove_stray_temps(&f)?;
    }
    Ok(())
}

pub fn cmd(sweep: &Sweep, out: &Path, quiet: bool) -> Result<std::process::ExitCode> {
    let t0 = Instant::now();
    let n = sweep.values.len();
    let (points, steps) = run_sweep(sweep, |i, r| {
        if quiet {
            return;
        }
        eprintln!(
            "rtw-scan: {} = {:.5} ({}/{n}): {} period {} max|mu| {}{} [{:.2} s]",
            sweep.param.name(),
            r.value,
            i + 1,
            r.label.as_str(),
            period_str(r.period),
            r.floquet_max.map_or("-".into(), |m| format!("{m:.4}")),
            if r.restarted { " (restarted)" } else { "" },
            r.wall_time_s,
        );
    });
    let wall = t0.elapsed().as_secs_f64();
    let sp = write(out, sweep, &points, &steps, wall)?;
    let md = summary_markdown(sweep, &points, wall);
    output::write_atomic(&summary_path(out), md.as_bytes())?;
    if !quiet {
        eprintln!(
            "rtw-scan: {} values in {}, {} recorded steps in {}",
            points.len(),
            out.display(),
            steps.len(),
            sp.display()
        );
    }
    print!("{md}");
    Ok(std::process::ExitCode::SUCCESS)
}

/// The bifurcation type a leading multiplier `μ` points to as it reaches the
/// unit circle.
pub fn crossing_type(re: f64, im: f64) -> &'static str {
    if im.abs() > 1e-9 * (re.hypot(im)).max(1.0) {
        "complex pair (Neimark–Sacker)"
    } else if re < 0.0 {
        "real, negative (period doubling)"
    } else {
        "real, positive (fold)"
    }
}

fn period_str(p: Option<usize>) -> String {
    p.map_or("none".into(), |p| p.to_string())
}

/// Within this distance of the unit circle the leading multiplier names the
/// bifurcation; farther inside, the change of gait is not a local
/// bifurcation of this cycle (another attractor took over, or the grid is
/// too coarse to tell) and the summary says so.
const NEAR_UNIT_CIRCLE: f64 = 0.05;

fn mu_str(r: &PointRow) -> String {
    match (r.mu_re, r.mu_im, r.floquet_max) {
        (Some(re), Some(im), Some(m)) if (m - 1.0).abs() <= NEAR_UNIT_CIRCLE => {
            format!("{re:.3}{im:+.3}i (|μ| = {m:.3}, {})", crossing_type(re, im))
        }
        (Some(re), Some(im), Some(m)) => {
            format!(
                "{re:.3}{im:+.3}i (|μ| = {m:.3}, inside the unit circle: not a local bifurcation at this resolution)"
            )
        }
        _ => "-".into(),
    }
}

/// The sweep summarized: contiguous ranges of (label, period, stable), where
/// the period changes (with the leading multiplier of the last cycle before
/// the change), where `floquet_max` crosses 1, and restarts and timing.
pub fn summary_markdown(sweep: &Sweep, rows: &[PointRow], wall_time_s: f64) -> String {
    let name = sweep.param.name();
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{} values of {name} from {} to {} (transient {}, record {} steps; step map {:?} rtol {:e}); model: {}",
        rows.len(),
        sweep.values.first().copied().unwrap_or(f64::NAN),
        sweep.values.last().copied().unwrap_or(f64::NAN),
        sweep.transient,
        sweep.record,
        sweep.cycle.method,
        sweep.cycle.rtol,
        config::Variant::of(&sweep.options),
    );
    let _ = writeln!(s);
    let _ = writeln!(
        s,
        "| {name} from | {name} to | values | label | period | stable | max |μ| range |"
    );
    let _ = writeln!(s, "|---:|---:|---:|---|---:|---|---|");
    let key = |r: &PointRow| (r.label, r.period, r.stable);
    let mut i = 0;
    while i < rows.len() {
        let mut j = i;
        while j + 1 < rows.len() && key(&rows[j + 1]) == key(&rows[i]) {
            j += 1;
        }
        let seg = &rows[i..=j];
        let mus: Vec<f64> = seg.iter().filter_map(|r| r.floquet_max).collect();
        let range = if mus.is_empty() {
            "-".to_string()
        } else {
            let lo = mus.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = mus.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            format!("{lo:.3} – {hi:.3}")
        };
        let stable = match rows[i].stable {
            Some(true) => "yes",
            Some(false) => "no",
            None => "-",
        };
        let _ = writeln!(
            s,
            "| {:.4} | {:.4} | {} | {} | {} | {stable} | {range} |",
            rows[i].value,
            rows[j].value,
            seg.len(),
            rows[i].label.as_str(),
            period_str(rows[i].period),
        );
        i = j + 1;
    }
    let _ = writeln!(s);
    for w in rows.windows(2) {
        let (a, b) = (&w[0], &w[1]);
        if a.period != b.period {
            let _ = writeln!(
                s,
                "- period {} → {} between {name} = {:.4} and {:.4}; leading multiplier at {:.4}: {}",
                period_str(a.period),
                period_str(b.period),
                a.value,
                b.value,
                a.value,
                mu_str(a),
            );
        }
        // A crossing on one branch: the same period on both sides.
        if let (Some(ma), Some(mb)) = (a.floquet_max, b.floquet_max)
            && a.period == b.period
            && (ma < 1.0) != (mb < 1.0)
        {
            let outside = if mb >= 1.0 { b } else { a };
            let _ = writeln!(
                s,
                "- max |μ| crosses 1 between {name} = {:.4} ({ma:.3}) and {:.4} ({mb:.3}); leading multiplier at {:.4}: {}",
                a.value,
                b.value,
                outside.value,
                mu_str(outside),
            );
        }
    }
    let restarts: Vec<String> = rows
        .iter()
        .filter(|r| r.restarted)
        .map(|r| format!("{:.4}", r.value))
        .collect();
    if !restarts.is_empty() {
        let _ = writeln!(
            s,
            "- restarted from the initial state (continuation failed) at {name} = {}",
            restarts.join(", ")
        );
    }
    let mut times: Vec<f64> = rows.iter().map(|r| r.wall_time_s).collect();
    times.sort_by(f64::total_cmp);
    let median = times.get(times.len() / 2).copied().unwrap_or(0.0);
    let _ = writeln!(
        s,
        "- wall time {wall_time_s:.1} s in all, median {median:.3} s per value"
    );
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sweep_params_parse_and_name_each_other() {
        for k in SWEEP_KEYS {
            assert_eq!(SweepParam::parse(k).unwrap().name(), k);
        }
        let e = SweepParam::parse("mu").unwrap_err().to_string();
        assert!(
            e.contains("--param") && e.contains("`mu`") && e.contains("phi, s"),
            "{e}"
        );
    }

    #[test]
    fn bad_bounds_name_the_flag_and_the_range() {
        let (p, o) = (Params::fig7a(), Options::default());
        let new = |param: &str, from: f64, to: f64, points: usize| {
            Sweep::new(
                SweepParam::parse(param).unwrap(),
                from,
                to,
                points,
                p,
                o,
                10,
                24,
            )
        };
        let e = new("phi", 0.1, 2.0, 5).unwrap_err().to_string();
        assert!(
            e.starts_with("--to: 2 is invalid for --param phi: phi must be"),
            "{e}"
        );
        let e = new("s", -0.1, 0.5, 5).unwrap_err().to_string();
        assert!(
            e.starts_with(
                "--from: -0.1 is invalid for --param s: strings.rest_length_ratio must be"
            ),
            "{e}"
        );
        let e = new("alpha", 0.1, 0.2, 1).unwrap_err().to_string();
        assert!(
            e.contains("--points: 1 is invalid: must be an integer >= 2"),
            "{e}"
        );
        let s = new("fn", 5.0, 2.0, 4).unwrap();
        assert_eq!(s.values, vec![5.0, 4.0, 3.0, 2.0]);
    }

    #[test]
    fn crossing_types_follow_the_multiplier() {
        assert_eq!(
            crossing_type(-1.01, 0.0),
            "real, negative (period doubling)"
        );
        assert_eq!(crossing_type(1.01, 0.0), "real, positive (fold)");
        assert_eq!(crossing_type(-0.7, 0.75), "complex pair (Neimark–Sacker)");
    }

    /// Continuation: the second value starts from the first value's last
    /// section point, so its rows equal a sweep of that one value started
    /// there by hand (an independent path through the same map calls).
    #[test]
    fn continuation_starts_from_the_previous_last_section_point() {
        let options = Options::default();
        let mut sweep = Sweep::new(
            SweepParam::parse("phi").unwrap(),
            0.15,
            0.16,
            2,
            Params::fig7a(),
            options,
            20,
            6,
        )
        .unwrap();
        sweep.cycle.newton_max_iter = 8;
        let (points, steps) = run_sweep(&sweep, |_, _| {});
        assert_eq!(points.len(), 2);
        assert!(!points[0].restarted && !points[1].restarted);
        // By hand: the first value from the initial state ...
        let (p0, o0) = sweep.param.at(&sweep.base, &options, 0.15).unwrap();
        let m0 = StepMap::new(&p0, &o0, &sweep.cycle);
        let first = m0.first(&o0).unwrap();
        let rec0 = settle_and_record(&m0, &first.to, &sweep).unwrap();
        // ... then the second from its last section point.
        let (p1, o1) = sweep.param.at(&sweep.base, &options, 0.16).unwrap();
        let m1 = StepMap::new(&p1, &o1, &sweep.cycle);
        let rec1 = settle_and_record(&m1, &rec0.last().unwrap().to, &sweep).unwrap();
        let omegas = |v: f64| -> Vec<f64> {
            steps
                .iter()
                .filter(|s| s.value == v)
                .map(|s| s.omega)
                .collect()
        };
        assert_eq!(
            omegas(0.15),
            rec0.iter().map(|s| s.to.omega()).collect::<Vec<_>>()
        );
        assert_eq!(
            omegas(0.16),
            rec1.iter().map(|s| s.to.omega()).collect::<Vec<_>>()
        );
        // A fresh start at 0.16 takes a different path (it is not what the
        // sweep did): its recorded steps differ from the continued ones.
        let fresh = settle_and_record(&m1, &m1.first(&o1).unwrap().to, &sweep).unwrap();
        assert_ne!(fresh[0].to.omega(), rec1[0].to.omega());
        // And the analysis is the one of those steps.
        let row = analyse(&m1, &sweep, &o1, 0.16, &rec1);
        assert_eq!(
            (row.period, row.floquet_max),
            (points[1].period, points[1].floquet_max)
        );
    }
}
