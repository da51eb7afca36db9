//! A basin slice's Parquet file: one row per grid point, the slice's
//! settings and the gait's fixed point in its metadata ([`META_BASIN`]).

use crate::basin::{OUTCOMES, outcome_index, point_label};
use crate::bifurcation::sweep::PointLabel;
use anyhow::Result;
use arrow_array::RecordBatch;
use arrow_schema::SchemaRef;
use rtw_engine::config::variant::ModelChoices;
use rtw_engine::files;
use rtw_engine::io::destination::check_destination;
use rtw_engine::io::metadata::{
    FileKind, META_BASIN, META_CYCLE, META_OPTIONS, META_PARAMS, META_VARIANT, META_VERSION,
    META_WALL_TIME, kv,
};
use rtw_engine::io::parquet;
use rtw_engine::io::table::{self, Column, Get, column};
use rtw_engine::scan::Run;
use rtw_engine::scan::lock::Lock;
use rtw_model::cycles::{Basin, BasinPoint, CycleOptions, Fate, StepError};
use rtw_model::{Options, Params};
use std::path::Path;
use std::time::Instant;

/// One grid point with what its row shows.
pub(crate) struct Row {
    point: BasinPoint,
    /// The fixed point's values of the two coordinates.
    centre: (f64, f64),
    /// Why its first failing step failed.
    failure: Option<String>,
}

/// Why a step failed, as a column value: the run's failure detail
/// (`rod_down`, `riser`, …) or the map's own stop.
fn failure_text(e: &StepError) -> String {
    match e {
        StepError::Failure(d) => d.as_str().to_string(),
        StepError::NoNewFoot => "no_new_foot".into(),
        StepError::LandingFootLeft => "landing_foot_left".into(),
        StepError::Numerical(r) => format!("numerical: {r:?}"),
    }
}

/// The rows of `points`, a slice of `basin`.
pub(crate) fn rows(basin: &Basin, points: &[BasinPoint]) -> Vec<Row> {
    points
        .iter()
        .map(|&point| Row {
            point,
            centre: basin.centre(),
            failure: match &point.fate {
                Fate::Fails(e) => Some(failure_text(e)),
                _ => None,
            },
        })
        .collect()
}

fn columns() -> Vec<Column<Row>> {
    vec![
        column(
            "x",
            false,
            "rad or rad/s",
            "offset of the x coordinate (--x: a rod's θ or ω) from the gait's fixed point",
            Get::F64(|r| Some(r.point.dx)),
        ),
        column(
            "y",
            false,
            "rad or rad/s",
            "offset of the y coordinate (--y) from the gait's fixed point",
            Get::F64(|r| Some(r.point.dy)),
        ),
        column(
            "x_value",
            false,
            "rad or rad/s",
            "the x coordinate's value at the start: the fixed point's plus x",
            Get::F64(|r| Some(r.centre.0 + r.point.dx)),
        ),
        column(
            "y_value",
            false,
            "rad or rad/s",
            "the y coordinate's value at the start: the fixed point's plus y",
            Get::F64(|r| Some(r.centre.1 + r.point.dy)),
        ),
        column(
            "outcome",
            false,
            "-",
            "returns: came within --tol of the gait; survives: took every step (--steps) without; \
             fails: a step failed; infeasible: a tip started below the ground (not simulated)",
            Get::Label {
                index: |r| outcome_index(&r.point.fate),
                names: || OUTCOMES.to_vec(),
            },
        ),
        column(
            "label",
            true,
            "-",
            "the gait's label (returns), the label of the last steps (survives: another gait, \
             or the same one not yet back), the failure's (fails: collapse, stall, diverged, or \
             failure: the step map stopped); null when infeasible",
            Get::Str(|r| point_label(&r.point).map(PointLabel::as_str)),
        ),
        column(
            "failure",
            true,
            "-",
            "why the failing step failed (rod_down, riser, no_new_foot, …)",
            Get::Str(|r| r.failure.as_deref()),
        ),
        column(
            "steps",
            false,
            "1",
            "steps taken without failing (returns: the step at which it came back)",
            Get::I64(|r| Some(r.point.steps as i64)),
        ),
        column(
            "distance",
            true,
            "1",
            "scaled distance of the last section point to the gait's orbit (positions over L, \
             rates over sqrt(g/L), speeds over sqrt(gL)); null: no orbit point in its contact modes",
            Get::F64(|r| Some(r.point.distance).filter(|d| d.is_finite())),
        ),
        column(
            "period",
            true,
            "1",
            "period of the last section points (returns: the gait's; survives: if they repeat)",
            Get::I64(|r| r.point.period.map(|p| p as i64)),
        ),
    ]
}

/// The slice file's schema.
pub(crate) fn schema() -> SchemaRef {
    table::schema(&columns())
}

/// Rows → a record batch of [`schema`].
pub(crate) fn batch(rows: &[Row]) -> RecordBatch {
    table::batch(&columns(), schema(), rows)
}

/// The slice's settings and the gait as JSON ([`META_BASIN`]).
pub(crate) fn basin_json(basin: &Basin) -> serde_json::Value {
    let s = basin.spec();
    let (cx, cy) = basin.centre();
    let axis = |a: &rtw_model::cycles::Axis, centre: f64| {
        serde_json::json!({
            "coord": a.coord.to_string(), "from": a.from, "to": a.to, "points": a.points, "centre": centre,
        })
    };
    serde_json::json!({
        "x": axis(&s.x, cx),
        "y": axis(&s.y, cy),
        "steps": s.steps,
        "tol": s.tol,
        "gait": basin.label.as_str(),
        "period": basin.cycle.period,
        "floquet_max": basin.cycle.floquet_max(),
    })
}

/// Writes the slice's file at `out` (atomically).
pub(crate) fn write(
    out: &Path,
    basin: &Basin,
    params: &Params,
    options: &Options,
    cycle: &CycleOptions,
    rows: &[Row],
    wall_time_s: f64,
) -> Result<()> {
    if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)?;
    }
    let meta = vec![
        kv(META_VERSION, rtw_engine::io::metadata::VERSION.into()),
        kv(META_BASIN, basin_json(basin).to_string()),
        kv(META_PARAMS, serde_json::to_string(params)?),
        kv(META_OPTIONS, toml::to_string(options)?),
        kv(META_VARIANT, ModelChoices::of(options).to_string()),
        kv(META_CYCLE, format!("{cycle:?}")),
        kv(META_WALL_TIME, format!("{wall_time_s:.3}")),
    ];
    parquet::write_file(out, &batch(rows), meta)
}

/// Refuses, unless `force`, to write the slice at `out` over a file that
/// is not a basin slice (never over a symlink or a special file), and
/// removes stray temporary files of an interrupted write.
pub(crate) fn check_output(out: &Path, force: bool) -> Result<()> {
    check_destination(out, FileKind::Basin, &[], "--out", force)?;
    files::remove_stray_temps(out)
}

/// The basin slice of `settings` around the gait of `params` under
/// `options` (both already checked, see [`crate::basin::slice`]) written to
/// `out`, refused first, unless `force`, over a file that is not a basin
/// slice. Returns the slice, its points in grid order and the wall time
/// in seconds. `rtw-scan basin` runs it.
pub fn run_to_files(
    params: &Params,
    options: &Options,
    settings: &crate::basin::Settings,
    out: &Path,
    force: bool,
    run: &Run,
) -> Result<(Basin, Vec<BasinPoint>, f64)> {
    let progress = run.progress;
    let _lock = Lock::for_result(out, &format!("writing the basin slice {}", out.display()))?;
    check_output(out, force)?;
    let cycle = CycleOptions::default();
    let t0 = Instant::now();
    let slice = crate::basin::slice(params, options, settings, run);
    progress.finish(slice.is_ok());
    let (slice, points) = slice?;
    let wall = t0.elapsed().as_secs_f64();
    write(
        out,
        &slice,
        params,
        options,
        &cycle,
        &rows(&slice, &points),
        wall,
    )?;
    Ok((slice, points, wall))
}
