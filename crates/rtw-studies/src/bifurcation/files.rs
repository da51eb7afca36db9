//! The sweep's files: `FILE.parquet` (one row per value), `FILE.steps.parquet`
//! (one row per recorded step), both made from one column table each, with
//! the sweep's settings in their metadata; and the summary `FILE.md` beside
//! them.

use crate::bifurcation::sweep::{LABELS, PointRow, StepRow, Sweep};
use ::parquet::file::metadata::KeyValue;
use anyhow::Result;
use arrow_array::RecordBatch;
use arrow_schema::SchemaRef;
use rtw_engine::config::variant::ModelChoices;
use rtw_engine::files::FileSet;
use rtw_engine::io::destination::{self, Output};
use rtw_engine::io::metadata::{
    FileKind, META_CYCLE, META_OPTIONS, META_PARAM, META_PARAMS, META_RECORD, META_TRANSIENT,
    META_VARIANT, META_VERSION, META_WALL_TIME, kv,
};
use rtw_engine::io::parquet;
use rtw_engine::io::table::{self, Column, Get, column};
use std::path::{Path, PathBuf};

/// A row of a sweep's file with the sweep it belongs to (for the columns
/// that repeat the sweep's settings on every row).
pub(crate) struct InSweep<'a, R> {
    sweep: &'a Sweep,
    row: &'a R,
}

const PARAM: &str = "the swept parameter's name (length, rho, alpha, fn, zeta, phi or s)";
const VALUE: &str =
    "the swept parameter's value, in its unit in samples.parquet (s = rest_length_ratio: 1)";
const VALUE_UNIT: &str = "as param";

fn label_names() -> Vec<&'static str> {
    LABELS.to_vec()
}

/// A row at one value of the swept parameter.
pub(crate) trait AtValue {
    /// The swept parameter's value.
    fn value(&self) -> f64;
}

impl AtValue for PointRow {
    fn value(&self) -> f64 {
        self.value
    }
}

impl AtValue for StepRow {
    fn value(&self) -> f64 {
        self.value
    }
}

/// The first two columns of both files: the swept parameter and its value.
fn swept<'a, R: AtValue>() -> [Column<InSweep<'a, R>>; 2] {
    [
        column(
            "param",
            false,
            "-",
            PARAM,
            Get::Str(|r| Some(r.sweep.param.name())),
        ),
        column(
            "value",
            false,
            VALUE_UNIT,
            VALUE,
            Get::F64(|r| Some(r.row.value())),
        ),
    ]
}

/// The per-value file's columns (`FILE.parquet`), in file order.
fn point_columns<'a>() -> Vec<Column<InSweep<'a, PointRow>>> {
    let [param, value] = swept();
    vec![
        param,
        value,
        column(
            "label",
            false,
            "-",
            "gait or failure at this value; failure: the step map stopped (no new foot landed)",
            Get::Label {
                index: |r| r.row.label.index(),
                names: label_names,
            },
        ),
        column(
            "period",
            true,
            "1",
            "period of the solved cycle in steps on the step map (its fixed point of the period-th power); null: no period found (chaotic or failure)",
            Get::I64(|r| r.row.period.map(|p| p as i64)),
        ),
        column(
            "floquet_max",
            true,
            "1",
            "largest Floquet multiplier modulus of the solved cycle (< 1: stable)",
            Get::F64(|r| r.row.floquet_max),
        ),
        column(
            "mu_re",
            true,
            "1",
            "real part of the largest multiplier (−1: period doubling, +1: fold)",
            Get::F64(|r| r.row.mu_re),
        ),
        column(
            "mu_im",
            true,
            "1",
            "imaginary part of the largest multiplier (a complex pair: Neimark–Sacker)",
            Get::F64(|r| r.row.mu_im),
        ),
        column(
            "stable",
            true,
            "-",
            "floquet_max < 1",
            Get::Bool(|r| r.row.stable),
        ),
        column(
            "restarted",
            false,
            "-",
            "the map failed from the continued point and this value started again from the initial state",
            Get::Bool(|r| Some(r.row.restarted)),
        ),
        column(
            "residual",
            true,
            "1",
            "Newton's scaled residual |Pⁿ(z) − z| at the fixed point",
            Get::F64(|r| r.row.residual),
        ),
        column(
            "newton_iterations",
            true,
            "1",
            "Newton iterations to the fixed point",
            Get::I64(|r| r.row.newton_iterations.map(i64::from)),
        ),
        column(
            "newton_error",
            true,
            "-",
            "why Newton found no fixed point although the iterates were periodic",
            Get::Str(|r| r.row.newton_error.as_deref()),
        ),
        column(
            "failure",
            true,
            "-",
            "why the step map failed at this value",
            Get::Str(|r| r.row.failure.as_deref()),
        ),
        column(
            "transient",
            false,
            "1",
            "steps iterated before recording (--transient)",
            Get::I64(|r| Some(r.sweep.transient as i64)),
        ),
        column(
            "record",
            false,
            "1",
            "steps recorded (--record)",
            Get::I64(|r| Some(r.sweep.record as i64)),
        ),
        column(
            "wall_time_s",
            false,
            "s",
            "wall-clock time of this value (machine-dependent)",
            Get::F64(|r| Some(r.row.wall_time_s)),
        ),
    ]
}

/// The per-step file's columns (`FILE.steps.parquet`), in file order.
fn step_columns<'a>() -> Vec<Column<InSweep<'a, StepRow>>> {
    let [param, value] = swept();
    vec![
        param,
        value,
        column(
            "k",
            false,
            "-",
            "index among the recorded steps (0 … record − 1)",
            Get::I64(|r| Some(r.row.k as i64)),
        ),
        column(
            "omega",
            false,
            "rad/s",
            "post-impact angular velocity of the new stance rod",
            Get::F64(|r| Some(r.row.omega)),
        ),
        column(
            "step_time",
            false,
            "s",
            "time from the previous section crossing",
            Get::F64(|r| Some(r.row.step_time)),
        ),
        column(
            "advance",
            false,
            "m",
            "downhill advance of the landing foot",
            Get::F64(|r| Some(r.row.advance)),
        ),
        column(
            "label",
            false,
            "-",
            "the value's label (as in FILE.parquet)",
            Get::Label {
                index: |r| r.row.label.index(),
                names: label_names,
            },
        ),
    ]
}

/// The schema of the per-value file `FILE.parquet`: one row per value.
pub(crate) fn points_schema() -> SchemaRef {
    table::schema(&point_columns())
}

/// The schema of the per-step file `FILE.steps.parquet`: one row per
/// recorded step.
pub(crate) fn steps_schema() -> SchemaRef {
    table::schema(&step_columns())
}

/// Rows of `sweep`, each with the sweep.
fn in_sweep<'a, R>(sweep: &'a Sweep, rows: &'a [R]) -> Vec<InSweep<'a, R>> {
    rows.iter().map(|row| InSweep { sweep, row }).collect()
}

/// Per-value rows → a record batch of [`points_schema`].
pub(crate) fn points_batch(sweep: &Sweep, rows: &[PointRow]) -> RecordBatch {
    table::batch(&point_columns(), points_schema(), &in_sweep(sweep, rows))
}

/// Per-step rows → a record batch of [`steps_schema`].
pub(crate) fn steps_batch(sweep: &Sweep, rows: &[StepRow]) -> RecordBatch {
    table::batch(&step_columns(), steps_schema(), &in_sweep(sweep, rows))
}

/// The file metadata of both output files.
fn file_metadata(sweep: &Sweep, wall_time_s: f64) -> Result<Vec<KeyValue>> {
    Ok(vec![
        kv(META_VERSION, rtw_engine::io::metadata::VERSION.into()),
        kv(META_PARAM, sweep.param.name().into()),
        kv(META_PARAMS, serde_json::to_string(&sweep.base)?),
        kv(META_OPTIONS, toml::to_string(&sweep.options)?),
        kv(META_VARIANT, ModelChoices::of(&sweep.options).to_string()),
        kv(META_CYCLE, format!("{:?}", sweep.cycle)),
        kv(META_TRANSIENT, sweep.transient.to_string()),
        kv(META_RECORD, sweep.record.to_string()),
        kv(META_WALL_TIME, format!("{wall_time_s:.3}")),
    ])
}

/// The per-step file beside the per-value file `out`: `NAME.steps.parquet`.
pub(crate) fn steps_path(out: &Path) -> PathBuf {
    destination::companion(out, "steps")
}

/// Adds both Parquet files to `set` (moved into place when it commits,
/// with the summary); returns the per-step file's path.
pub(crate) fn write(
    set: &mut FileSet,
    out: &Path,
    sweep: &Sweep,
    points: &[PointRow],
    steps: &[StepRow],
    wall_time_s: f64,
) -> Result<PathBuf> {
    if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)?;
    }
    let meta = file_metadata(sweep, wall_time_s)?;
    parquet::add_file(set, out, &points_batch(sweep, points), meta.clone())?;
    let sp = steps_path(out);
    parquet::add_file(set, &sp, &steps_batch(sweep, steps), meta)?;
    Ok(sp)
}

/// Refuses, unless `force`, to write the sweep's files (`out`, its
/// `.steps.parquet` and `.md`) over files that are not a sweep's: another
/// kind of Parquet file, or an `.md` that is not the summary of a sweep at
/// `out`.
pub(crate) fn check_outputs(out: &Path, force: bool) -> Result<()> {
    let files_ = [
        Output {
            path: out.to_path_buf(),
            flag: "--out",
            schema: points_schema(),
        },
        Output {
            path: steps_path(out),
            flag: "--out (steps file)",
            schema: steps_schema(),
        },
    ];
    // A sweep's summary starts "N values of PARAM from ...".
    let ours = |first: &str| {
        first
            .split_once(" values of ")
            .is_some_and(|(n, _)| n.parse::<usize>().is_ok())
    };
    destination::check_outputs(out, &files_, FileKind::Bifurcation, "a sweep", ours, force)
}
