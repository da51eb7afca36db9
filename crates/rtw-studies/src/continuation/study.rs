//! A diagram as a study: its outputs checked, the diagram (and with
//! `through`, its segments) computed, and every file of it written
//! together: `FILE.parquet`, `FILE.special.parquet`, `FILE.curve.parquet`
//! (with a curve), `FILE.segments.json` (with `through`) and `FILE.md`,
//! each to a temporary file first and all moved into place at the end
//! ([`FileSet`]), so that an interrupted diagram leaves none of them (and an
//! earlier diagram's files as they were). The command line only parses and
//! prints.

use super::{Continuation, files, segments, summary};
use anyhow::{Result, bail};
use rtw_engine::files::FileSet;
use rtw_engine::io::destination::summary_path;
use rtw_engine::scan::Run;
use rtw_engine::scan::lock::Lock;
use std::path::Path;
use std::time::Instant;

/// Most segments `through` follows each way.
pub const THROUGH_MAX: usize = 100;

/// Checks `through` (segments each way; 0: none), naming the flag and the
/// range.
pub fn check_through(through: usize) -> Result<()> {
    if through > THROUGH_MAX {
        bail!("--through {through}: must lie in [0, {THROUGH_MAX}]");
    }
    Ok(())
}

/// Runs the diagram `c` into `out` and its companions (refusing, unless
/// `force`, files that are not a diagram's), with up to `through` segments
/// each way (0: none); returns the summary written to `FILE.md`. `run`'s
/// progress sees two stages: the diagram (one unit), then the directions
/// followed through the mode changes (a unit each); its stop flag ends the
/// study at its model run's next step with
/// [`Stopped`](rtw_engine::scan::workers::Stopped), nothing written.
pub fn run_to_files(
    c: &Continuation,
    through: usize,
    out: &Path,
    force: bool,
    run: &Run,
) -> Result<String> {
    let progress = run.progress;
    check_through(through)?;
    let _lock = Lock::for_result(out, &format!("writing the diagram {}", out.display()))?;
    files::check_outputs(out, force)?;
    if through > 0 {
        segments::check_output(out, force)?;
    }
    let t0 = Instant::now();
    progress.stage("continuation: the branches through the start");
    progress.start(1);
    let result = run.cancellable(|| super::run(c)).and_then(|r| r);
    if result.is_ok() {
        progress.advanced();
    }
    progress.finish(result.is_ok());
    let result = result?;
    let wall = t0.elapsed().as_secs_f64();
    let rows = files::rows(c, &result);
    let mut md = summary::summary_markdown(
        c,
        result.diagram.start.period,
        result.diagram.start.floquet_max(),
        &rows,
        result.diagram.branches.len(),
        wall,
    );
    let dirs = if through > 0 {
        rtw_engine::pause_unless("continuation-segments", run.stop);
        progress.stage("continuation --through: directions followed");
        let dirs = run.cancellable(|| segments::run(c, &result.diagram, through, progress));
        progress.finish(dirs.is_ok());
        Some(dirs?)
    } else {
        None
    };
    let mut set = FileSet::default();
    files::write(&mut set, out, c, &rows, wall)?;
    if let Some(dirs) = &dirs {
        segments::write(&mut set, out, c, dirs)?;
        md.push_str(&segments::markdown(c, dirs));
    }
    set.add_bytes(&summary_path(out), md.as_bytes())?;
    set.commit()?;
    Ok(md)
}
