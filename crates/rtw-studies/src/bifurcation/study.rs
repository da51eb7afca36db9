//! One parameter swept with continuation on the step map (a bifurcation
//! diagram): [`Sweep`] checks the settings, [`run_to_files`] runs the sweep
//! and writes its files.

use crate::bifurcation::files::{check_outputs, write};
use crate::bifurcation::summary::{period_str, summary_markdown};
use crate::bifurcation::sweep::{PointRow, run_sweep};
use anyhow::Result;
use rtw_engine::files::FileSet;
use rtw_engine::io::destination::summary_path;
use rtw_engine::scan::Run;
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
/// `FILE.md`, the three moved into place together; refuses first, unless
/// `force`, files there that are not a sweep's. `run`'s progress hears of
/// each value when it is done ([`Progress::advanced`]) with its line
/// ([`Progress::note`]: `phi = 0.02000 (1/121): walk period 1 …`); its stop
/// flag ends the sweep with [`Stopped`], nothing written.
///
/// [`Progress::advanced`]: rtw_engine::scan::Progress::advanced
/// [`Progress::note`]: rtw_engine::scan::Progress::note
/// [`Stopped`]: rtw_engine::scan::workers::Stopped
pub fn run_to_files(sweep: &Sweep, out: &Path, force: bool, run: &Run) -> Result<SweepFiles> {
    let _lock = Lock::for_result(out, &format!("writing the sweep {}", out.display()))?;
    check_outputs(out, force)?;
    let t0 = Instant::now();
    let n = sweep.values.len();
    run.progress.start(n as u64);
    let swept = run_sweep(sweep, run, |i, r| {
        run.progress.note(&value_line(sweep, i, n, r));
        run.progress.advanced();
    });
    run.progress.finish(swept.is_ok());
    let (points, steps) = swept?;
    let wall = t0.elapsed().as_secs_f64();
    let mut set = FileSet::default();
    let steps_path = write(&mut set, out, sweep, &points, &steps, wall)?;
    let summary = summary_markdown(sweep, &points, wall);
    set.add_bytes(&summary_path(out), summary.as_bytes())?;
    set.commit()?;
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
