//! One parameter swept with continuation on the step map (a bifurcation
//! diagram): [`Sweep`] checks the settings, [`run_to_files`] runs the sweep
//! and writes its files.

use crate::bifurcation::files::{check_outputs, write};
use crate::bifurcation::summary::{period_str, summary_markdown};
use crate::bifurcation::sweep::{PointRow, run_sweep};
use anyhow::Result;
use rtw_engine::files::write_atomic;
use rtw_engine::io::destination::summary_path;
use rtw_engine::scan::lock::Lock;
use std::path::{Path, PathBuf};
use std::time::Instant;

use crate::bifurcation::sweep::Sweep;

/// What a sweep wrote.
#[derive(Clone, Debug)]
pub struct SweepFiles {
    /// The values swept (rows of `FILE.parquet`).
    pub values: usize,
    /// The recorded steps (rows of `FILE.steps.parquet`).
    pub steps: usize,
    /// `FILE.steps.parquet`.
    pub steps_path: PathBuf,
    /// The summary, as written to `FILE.md`.
    pub summary: String,
}

/// Runs the sweep into `out` (`FILE.parquet`, one row per value), its
/// `FILE.steps.parquet` (one row per recorded step) and its summary
/// `FILE.md`; refuses first, unless `force`, files there that are not a
/// sweep's. `on_value` hears of each value when it is done, in one line
/// (`phi = 0.02000 (1/121): walk period 1 …`).
pub fn run_to_files(
    sweep: &Sweep,
    out: &Path,
    force: bool,
    mut on_value: impl FnMut(&str),
) -> Result<SweepFiles> {
    let _lock = Lock::for_result(out, &format!("writing the sweep {}", out.display()))?;
    check_outputs(out, force)?;
    let t0 = Instant::now();
    let n = sweep.values.len();
    let (points, steps) = run_sweep(sweep, |i, r| on_value(&value_line(sweep, i, n, r)));
    let wall = t0.elapsed().as_secs_f64();
    let steps_path = write(out, sweep, &points, &steps, wall)?;
    let summary = summary_markdown(sweep, &points, wall);
    write_atomic(&summary_path(out), summary.as_bytes())?;
    Ok(SweepFiles {
        values: points.len(),
        steps: steps.len(),
        steps_path,
        summary,
    })
}

/// The line that says value `i` of `n` is done.
fn value_line(sweep: &Sweep, i: usize, n: usize, r: &PointRow) -> String {
    format!(
        "{} = {:.5} ({}/{n}): {} period {} max|mu| {}{} [{:.2} s]",
        sweep.param.name(),
        r.value,
        i + 1,
        r.label.as_str(),
        period_str(r.period),
        r.floquet_max.map_or("-".into(), |m| format!("{m:.4}")),
        if r.restarted { " (restarted)" } else { "" },
        r.wall_time_s,
    )
}
