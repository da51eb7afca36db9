//! Basin-of-attraction slices ([`rtw_model::cycles::Basin`]): the grid's
//! points simulated in parallel, and the grid's Parquet file (`files`).
//!
//! Each point depends only on its offsets, so the rows are the same for
//! any thread count, in grid order (row-major: `y` outer, `x` inner).

pub(crate) mod files;

pub use files::run_to_files;

use crate::bifurcation::sweep::{PointLabel, failure_label};
use anyhow::{Result, anyhow, bail};
use arrow_array::RecordBatch;
use rayon::prelude::*;
use rtw_engine::scan::Run;
use rtw_engine::scan::workers::{Stopped, worker_pool};
use rtw_model::cycles::{
    Axis, Basin, BasinError, BasinPoint, BasinSpec, Coord, CycleOptions, Fate,
};
use rtw_model::{Options, Params};
use std::sync::atomic::Ordering;

/// A slice's settings, checked: the grid and its steps and tolerance (the
/// worker threads are the study's [`Run`]'s).
#[derive(Clone, Copy, Debug)]
pub struct Settings {
    /// The grid, the steps and the tolerance.
    pub spec: BasinSpec,
}

impl Settings {
    /// The settings as given (the axes `COORD:FROM:TO:POINTS`, the steps
    /// as the digits written), each checked against its range
    /// and named in an error as `prefix` + its name (`--steps` on the
    /// command line, `steps` in Python), the axes with their text.
    pub fn parse(x: &str, y: &str, steps: &str, tol: f64, prefix: &str) -> Result<Self> {
        let name = |n: &str| format!("{prefix}{n}");
        // The range of the steps is rtw-model's (`BasinSpec::validate`): a
        // count beyond any integer is out of it like a large one, and text
        // that is no count at all like zero; the message shows it as given.
        let digits = steps.trim();
        let spec = BasinSpec {
            x: parse_axis(x, &name("x"))?,
            y: parse_axis(y, &name("y"))?,
            steps: digits.parse().unwrap_or_else(|_| {
                if !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()) {
                    usize::MAX
                } else {
                    0
                }
            }),
            tol,
        };
        if let Err(BasinError::Invalid { field, what, range }) = spec.validate() {
            let (given, what) = match field {
                "x" => (format!(" {x}"), what),
                "y" => (format!(" {y}"), what),
                "steps" => (String::new(), digits.to_string()),
                _ => (String::new(), what),
            };
            bail!("{}{given}: {what} is invalid: must be {range}", name(field));
        }
        Ok(Self { spec })
    }
}

/// The basin slice of `settings` around the gait of `params` under
/// `options` (both already checked): the gait, and every grid point in
/// grid order (row-major: `y` outer, `x` inner), the same on any number of
/// threads. `run.progress` counts the grid points as they are done;
/// `run.stop` set stops it after the points in flight, with the error
/// [`Stopped`]; it works on `run.threads` workers. `rtw-scan basin` and Python's `rtw.basin` both run it.
pub fn slice(
    params: &Params,
    options: &Options,
    settings: &Settings,
    run: &Run,
) -> Result<(Basin, Vec<BasinPoint>)> {
    let (cancel, progress) = (run.stop, run.progress);
    // Started first: the pool refuses a thread count beyond its cap before
    // the gait is solved.
    let pool = worker_pool(run.threads)?;
    let slice = Basin::new(params, options, &CycleOptions::default(), settings.spec)?;
    progress.start(slice.len() as u64);
    let points: Option<Vec<BasinPoint>> = pool.install(|| {
        (0..slice.len())
            .into_par_iter()
            .map(|i| {
                (!cancel.load(Ordering::Relaxed)).then(|| {
                    let point = slice.point(i);
                    progress.advanced();
                    point
                })
            })
            .collect()
    });
    let points = points.ok_or_else(|| anyhow!(Stopped))?;
    Ok((slice, points))
}

/// [`slice()`] as the rows `rtw-scan basin` writes: one per grid point.
/// Python's `rtw.basin` is this function.
pub fn slice_table(
    params: &Params,
    options: &Options,
    settings: &Settings,
    run: &Run,
) -> Result<RecordBatch> {
    let (slice, points) = slice(params, options, settings, run)?;
    Ok(files::batch(&files::rows(&slice, &points)))
}

/// The `outcome` column's values, in key order.
pub const OUTCOMES: [&str; 4] = ["returns", "survives", "fails", "infeasible"];

/// Position of a point's fate in [`OUTCOMES`].
pub fn outcome_index<E>(fate: &Fate<E>) -> usize {
    match fate {
        Fate::Returns => 0,
        Fate::Survives => 1,
        Fate::Fails(_) => 2,
        Fate::Infeasible => 3,
    }
}

/// A point's label: its gait's (a return, or the last steps of a point that
/// took every step), its failure's (as a sweep labels a failed step), none
/// when infeasible.
pub(crate) fn point_label(p: &BasinPoint) -> Option<PointLabel> {
    match (&p.fate, p.label) {
        (Fate::Fails(e), _) => Some(failure_label(e)),
        (_, Some(l)) => Some(PointLabel::Outcome(l)),
        _ => None,
    }
}

/// Parses an axis `COORD:FROM:TO:POINTS` given by `flag`, naming the flag
/// and what it must be. The ranges themselves are checked by
/// [`rtw_model::cycles::BasinSpec::validate`].
pub fn parse_axis(text: &str, flag: &str) -> Result<Axis> {
    let parts: Vec<&str> = text.split(':').collect();
    let [coord, from, to, points] = parts[..] else {
        bail!("{flag} {text}: must be COORD:FROM:TO:POINTS, e.g. omega_a:-40:40:41");
    };
    let coord: Coord = coord
        .parse()
        .map_err(|e| anyhow::anyhow!("{flag} {text}: {e}"))?;
    let number = |s: &str, what: &str| {
        s.trim().parse::<f64>().map_err(|_| {
            anyhow::anyhow!("{flag} {text}: {what} `{s}` is invalid: must be a number")
        })
    };
    let from = number(from, "FROM")?;
    let to = number(to, "TO")?;
    let Ok(points) = points.trim().parse::<usize>() else {
        bail!("{flag} {text}: POINTS `{points}` is invalid: must be an integer in [1, 1000]");
    };
    Ok(Axis {
        coord,
        from,
        to,
        points,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axes_parse_and_bad_ones_name_the_flag() {
        let a = parse_axis("theta_b:-1.2:0.8:21", "--y").unwrap();
        assert_eq!(
            (a.coord, a.from, a.to, a.points),
            (Coord::Theta(1), -1.2, 0.8, 21)
        );
        for (text, want) in [
            (
                "omega_a:-1:1",
                "--x omega_a:-1:1: must be COORD:FROM:TO:POINTS",
            ),
            (
                "omega:-1:1:3",
                "--x omega:-1:1:3: unknown coordinate `omega`: must be one of omega_a,",
            ),
            (
                "omega_a:x:1:3",
                "--x omega_a:x:1:3: FROM `x` is invalid: must be a number",
            ),
            (
                "omega_a:-1:1:-3",
                "--x omega_a:-1:1:-3: POINTS `-3` is invalid: must be an integer in [1, 1000]",
            ),
        ] {
            let e = parse_axis(text, "--x").unwrap_err().to_string();
            assert!(e.starts_with(want), "{e}");
        }
    }
}
