//! The slope profile of one design (`rtw-scan profile`, Python's
//! `rtw.profile`): its gait at each slope φ of a range, every change of
//! label located to a tolerance in φ by bisection, and what a designer reads
//! off it: the stable intervals per gait, the shallowest stable slope and
//! the widest interval of stable slopes.
//!
//! A coarse grid of slopes (spacing at most `grid`) is simulated first; each
//! pair of neighbouring slopes whose labels differ is a bracket, halved
//! until it is at most `tol` wide (a midpoint of a third label splits it
//! into two brackets, both followed). Each change costs about
//! log2(grid / tol) runs instead of the (to − from) / tol of a grid that
//! fine. Every round's runs (the grid, then one midpoint per open bracket)
//! go to the scans' worker pool, and every φ is a pure function of the
//! settings, so the profile does not depend on the thread count. A feature
//! narrower than the grid spacing whose two ends have one label is not seen:
//! the grid is the profile's resolution, the tolerance its precision.

pub mod cost;
pub(crate) mod files;
mod locate;

use anyhow::{Result, anyhow, bail};
use arrow_array::RecordBatch;
use rtw_engine::config::params::checked_params;
use rtw_engine::io::scan_rows::{self, Row};
use rtw_engine::scan::Run;
use rtw_engine::scan::one::run_one;
use rtw_engine::scan::progress::Progress;
use rtw_engine::scan::workers::{Stopped, worker_pool};
use rtw_model::{Label, Num, Options, Param, Params};
use std::sync::atomic::AtomicBool;

pub use files::{markdown, run_to_files};
pub use locate::{Change, Segment};

/// Most slopes of the coarse grid: (to − from) / grid is at most this.
pub const MAX_GRID_POINTS: f64 = 100_000.0;
/// The finest tolerance in φ (rad): below it the bisection would chase the
/// integration error of the runs, not the slope where the gait changes.
pub const MIN_TOL: f64 = 1e-9;

/// How the settings are named in messages: the command line's flags or
/// Python's keywords. Each face passes its own; the checks and their words
/// are the same.
#[derive(Clone, Copy, Debug)]
pub struct Names {
    /// The design's inputs are named `{prefix}{name}` (`--rho`, `rho`).
    pub prefix: &'static str,
    /// The range's start.
    pub from: &'static str,
    /// The range's end.
    pub to: &'static str,
    /// The tolerance.
    pub tol: &'static str,
    /// The coarse grid's spacing.
    pub grid: &'static str,
}

impl Names {
    /// `rtw-scan profile`'s flags.
    pub const CLI: Names = Names {
        prefix: "--",
        from: "--from",
        to: "--to",
        tol: "--tol",
        grid: "--grid",
    };
    /// `rtw.profile`'s keywords.
    pub const PYTHON: Names = Names {
        prefix: "",
        from: "phi_from",
        to: "phi_to",
        tol: "tol",
        grid: "grid",
    };
}

/// A profile's settings, checked: the design (its φ the range's start), the
/// slope range, the tolerance and the coarse grid (the worker threads are
/// the study's [`Run`]'s).
#[derive(Clone, Copy, Debug)]
pub struct Settings {
    /// The design; its `phi` is `from`.
    pub design: Params,
    /// The range's start (rad).
    pub from: f64,
    /// The range's end (rad), above `from`.
    pub to: f64,
    /// Each change of label is located to a bracket at most this wide (rad).
    pub tol: f64,
    /// The coarse grid's spacing is at most this (rad).
    pub grid: f64,
}

impl Settings {
    /// The settings as given: the design's five inputs (L, ρ, α, f_n, ζ),
    /// the slope range, the tolerance and grid in rad; each refused naming it as `names` spells it,
    /// with its valid range.
    pub fn parse(
        design: [f64; 5],
        from: f64,
        to: f64,
        tol: f64,
        grid: f64,
        names: &Names,
    ) -> Result<Self> {
        let slope = |v: f64, name: &str| -> Result<f64> {
            if Param::Phi.check(v).is_ok() {
                Ok(v)
            } else {
                bail!(
                    "{name}: {} is invalid: must be a slope φ {}",
                    Num(v),
                    Param::Phi.range()
                )
            }
        };
        let from = slope(from, names.from)?;
        let to = slope(to, names.to)?;
        if to <= from {
            bail!(
                "{}: {} is invalid: must be above {} ({})",
                names.to,
                Num(to),
                names.from,
                Num(from)
            );
        }
        // The ends were typed in decimal and rounded to binary64, each by up to
        // half an ulp of itself, so their difference can miss the span as typed
        // by far more than an ulp of the span (0.16 − 0.14 is 0.01999999999999999):
        // the bounds are the span as typed, the shortest decimal within that
        // rounding, and its MAX_GRID_POINTS-th part, each met to a few ulps.
        let span = to - from;
        let typed = shortest_within(span, (from.abs() + to.abs()) * f64::EPSILON);
        let widest = span.max(typed);
        let finest = widest / MAX_GRID_POINTS;
        let ulps = 4.0 * f64::EPSILON;
        if !(grid.is_finite() && grid >= finest * (1.0 - ulps) && grid <= widest * (1.0 + ulps)) {
            bail!(
                "{}: {} is invalid: must be in [{}, {}] rad (at most {} slopes over {}..{}, at \
                 least two)",
                names.grid,
                Num(grid),
                Num(shortest_within(finest, finest * ulps)),
                Num(typed),
                MAX_GRID_POINTS,
                names.from,
                names.to
            );
        }
        if !(tol.is_finite() && (MIN_TOL..=grid).contains(&tol)) {
            bail!(
                "{}: {} is invalid: must be in [{}, {}] rad (at most {}, the coarse grid's \
                 spacing)",
                names.tol,
                Num(tol),
                Num(MIN_TOL),
                Num(grid),
                names.grid
            );
        }
        let [length, rho, alpha, f_n, zeta] = design;
        let design = checked_params([length, rho, alpha, f_n, zeta, from], names.prefix)?;
        Ok(Self {
            design,
            from,
            to,
            tol,
            grid,
        })
    }

    /// The coarse grid: `n + 1` slopes from `from` to `to`, evenly spaced at
    /// most `grid` apart.
    pub(crate) fn coarse(&self) -> Vec<f64> {
        let span = self.to - self.from;
        // The ratio is at most MAX_GRID_POINTS (checked), and at least 1.
        let n = ((span / self.grid) * (1.0 - 1e-12)).ceil().max(1.0) as usize;
        (0..=n)
            .map(|i| {
                if i == n {
                    self.to
                } else {
                    self.from + span * i as f64 / n as f64
                }
            })
            .collect()
    }
}

/// The shortest decimal within `within` of `x` (`x` itself if none is
/// shorter): how a bound computed from typed values reads as typed.
fn shortest_within(x: f64, within: f64) -> f64 {
    (0..17)
        .filter_map(|digits| format!("{x:.digits$e}").parse::<f64>().ok())
        .find(|v| (v - x).abs() <= within)
        .unwrap_or(x)
}

/// A design's slope profile: every simulated slope in φ order, the label
/// changes, the label's segments, and what they give.
pub struct Profile {
    /// The settings it was made with.
    pub settings: Settings,
    /// The simulation options of its runs.
    pub(crate) options: Options,
    /// One row per simulated slope, in φ order (`sample_id` its position).
    pub(crate) rows: Vec<Row>,
    /// Every change of label, each bracket at most `tol` wide, in φ order.
    pub changes: Vec<Change>,
    /// The runs of one label between changes, in φ order.
    pub segments: Vec<Segment>,
    /// Runs made on the coarse grid.
    pub coarse_runs: usize,
}

impl Profile {
    /// The stable intervals of `label`: its segments' `[lo, hi]`, each end a
    /// simulated slope with that label.
    pub fn intervals(&self, label: Label) -> Vec<(f64, f64)> {
        self.segments
            .iter()
            .filter(|s| s.label == label)
            .map(|s| (s.lo, s.hi))
            .collect()
    }

    /// The intervals of stable slopes, whatever the gait: neighbouring
    /// stable segments joined (a walk that turns into a skip is stable
    /// through the change, to within its bracket).
    pub fn stable_intervals(&self) -> Vec<(f64, f64)> {
        let mut out: Vec<(f64, f64)> = Vec::new();
        let mut previous_stable = false;
        for s in &self.segments {
            let stable = s.label.is_stable();
            match out.last_mut() {
                Some(last) if stable && previous_stable => last.1 = s.hi,
                _ if stable => out.push((s.lo, s.hi)),
                _ => {}
            }
            previous_stable = stable;
        }
        out
    }

    /// The shallowest stable slope: the lowest simulated φ with a stable
    /// gait (located to `tol` unless it is `from`).
    pub fn phi_min(&self) -> Option<f64> {
        self.segments
            .iter()
            .find(|s| s.label.is_stable())
            .map(|s| s.lo)
    }

    /// The widest interval of stable slopes (`phi_lo`, `phi_hi`); of equal
    /// ones, the shallowest.
    pub fn widest(&self) -> Option<(f64, f64)> {
        widest(self.stable_intervals())
    }

    /// Runs made in all (the coarse grid and the bisections).
    pub fn runs(&self) -> usize {
        self.rows.len()
    }

    /// Every simulated slope as a record batch: the columns of a scan's
    /// rows (docs/data-dictionary.md), with the robustness columns its
    /// options ask for (`robustness.mfpt`: the MFPT along φ), one row per
    /// slope in φ order.
    pub fn table(&self) -> RecordBatch {
        scan_rows::to_batch(&self.rows, &self.options.robustness)
    }

    /// The profile as JSON: what `rtw-scan profile --json` prints and its
    /// Parquet file's metadata holds.
    pub fn to_json(&self) -> serde_json::Value {
        let s = &self.settings;
        let interval = |i: (f64, f64)| serde_json::json!([i.0, i.1]);
        let gaits: serde_json::Map<String, serde_json::Value> = Label::ALL
            .iter()
            .filter(|l| l.is_stable())
            .map(|&l| {
                let v: Vec<_> = self.intervals(l).into_iter().map(interval).collect();
                (l.as_str().to_string(), v.into())
            })
            .collect();
        let widest = self.widest();
        serde_json::json!({
            "design": {
                "length": s.design.length, "rho": s.design.rho, "alpha": s.design.alpha,
                "fn": s.design.f_n, "zeta": s.design.zeta,
            },
            "from": s.from,
            "to": s.to,
            "tol": s.tol,
            "grid": s.grid,
            "runs": self.runs(),
            "coarse_runs": self.coarse_runs,
            "intervals": gaits,
            "stable_intervals": self.stable_intervals().into_iter().map(interval).collect::<Vec<_>>(),
            "phi_min": self.phi_min(),
            "phi_lo": widest.map(|w| w.0),
            "phi_hi": widest.map(|w| w.1),
            "changes": self.changes.iter().map(|c| serde_json::json!({
                "phi_left": c.phi_left, "phi_right": c.phi_right,
                "label_left": c.label_left.as_str(), "label_right": c.label_right.as_str(),
                "label_below": c.label_below.as_str(), "label_above": c.label_above.as_str(),
                "sharp": c.sharp(),
            })).collect::<Vec<_>>(),
            "segments": self.segments.iter().map(|g| serde_json::json!({
                "label": g.label.as_str(), "lo": g.lo, "hi": g.hi, "runs": g.runs,
            })).collect::<Vec<_>>(),
        })
    }
}

/// The widest of `intervals` (`(lo, hi)`); of equal ones, the first.
pub(crate) fn widest(intervals: impl IntoIterator<Item = (f64, f64)>) -> Option<(f64, f64)> {
    intervals
        .into_iter()
        .fold(None, |best: Option<(f64, f64)>, i| match best {
            Some(b) if b.1 - b.0 >= i.1 - i.0 => Some(b),
            _ => Some(i),
        })
}

/// `design` run at slope `phi` under `options`, as `rtw-scan simulate` runs
/// it; `None` when `cancel` stopped it.
pub(crate) fn run_at_slope(
    design: Params,
    phi: f64,
    options: &Options,
    cancel: &AtomicBool,
) -> Option<Row> {
    let params = Params { phi, ..design };
    rtw_model::cancellable(cancel, || run_one(0, params, options, rtw_model::simulate))
}

/// The slope profile of `settings` under `options` (both checked): each φ
/// run as `rtw-scan simulate` runs it, the runs of a round in parallel on
/// the scans' worker pool of `run.threads`, each counted in `run.progress`.
/// Setting `run.stop` stops it within moments (every run in flight ends at its next step),
/// with the error [`Stopped`]. `rtw-scan profile` and `rtw.profile` both
/// run it.
pub fn run(settings: &Settings, options: &Options, run: &Run) -> Result<Profile> {
    let (progress, cancel) = (run.progress, run.stop);
    let pool = worker_pool(run.threads)?;
    progress.stage("profile: the coarse grid's slopes");
    progress.start(settings.coarse().len() as u64);
    // After the start, so that a bar shows it too.
    let (said, warning) = cost::of_profile(settings, options);
    progress.note(&said);
    if let Some(w) = warning {
        progress.warn(&w);
    }
    let profile = pool
        .install(|| profile_here(settings, options, progress, cancel))
        .ok_or_else(|| anyhow!(Stopped))?;
    progress.finish(true);
    Ok(profile)
}

/// The profile of [`run`] on the pool the caller installed (a design
/// search profiles its designs in parallel on its own pool); `None` when
/// stopped.
pub(crate) fn profile_here(
    settings: &Settings,
    options: &Options,
    progress: &dyn Progress,
    cancel: &AtomicBool,
) -> Option<Profile> {
    let eval = |phi: f64| -> Option<Row> {
        let row = run_at_slope(settings.design, phi, options, cancel)?;
        progress.computed(row.label());
        Some(row)
    };
    let coarse = settings.coarse();
    let located = locate::locate(&coarse, settings.tol, &eval, Row::label, progress)?;
    let mut rows: Vec<Row> = located.points.into_iter().map(|(_, r)| r).collect();
    for (i, r) in rows.iter_mut().enumerate() {
        r.sample_id = i as u64;
    }
    Some(Profile {
        settings: *settings,
        options: *options,
        rows,
        changes: located.changes,
        segments: located.segments,
        coarse_runs: coarse.len(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Fig. 7(a) design's settings over [from, to] at `grid`, tol 1e-3.
    fn fig7a(from: f64, to: f64, grid: f64) -> Settings {
        let design = [0.8, 2.5, 0.125, 3.269, 0.0514];
        Settings::parse(design, from, to, 1e-3, grid, &Names::CLI).unwrap()
    }

    fn seg(label: Label, lo: f64, hi: f64) -> Segment {
        Segment {
            label,
            lo,
            hi,
            runs: 2,
        }
    }

    /// A profile with these segments (no rows: the summaries read only them).
    fn profile(segments: Vec<Segment>) -> Profile {
        let settings = fig7a(0.0, 0.4, 0.01);
        Profile {
            settings,
            options: Options::default(),
            rows: Vec::new(),
            changes: Vec::new(),
            segments,
            coarse_runs: 0,
        }
    }

    #[test]
    fn neighbouring_stable_gaits_join_and_the_widest_interval_is_the_longest_run_of_them() {
        use Label::*;
        let p = profile(vec![
            seg(Stall, 0.0, 0.04),
            seg(Walk, 0.041, 0.1),
            seg(Collapse, 0.101, 0.11),
            seg(Walk, 0.111, 0.2),
            seg(Skip, 0.201, 0.25),
            seg(Crawl, 0.251, 0.26),
            seg(Collapse, 0.261, 0.4),
        ]);
        assert_eq!(p.phi_min(), Some(0.041));
        assert_eq!(p.intervals(Walk), [(0.041, 0.1), (0.111, 0.2)]);
        assert_eq!(p.intervals(Crawl), [(0.251, 0.26)]);
        assert_eq!(p.stable_intervals(), [(0.041, 0.1), (0.111, 0.26)]);
        assert_eq!(p.widest(), Some((0.111, 0.26)));
        let json = p.to_json();
        assert_eq!(
            (json["phi_lo"].as_f64(), json["phi_hi"].as_f64()),
            (Some(0.111), Some(0.26))
        );
        // No stable slope: none of them.
        let p = profile(vec![seg(Collapse, 0.0, 0.4)]);
        assert_eq!((p.phi_min(), p.widest()), (None, None));
        assert!(p.stable_intervals().is_empty());
    }

    #[test]
    fn the_grid_spans_the_range_in_equal_cells_at_most_grid_wide() {
        let s = fig7a(0.05, 0.3, 0.01);
        let g = s.coarse();
        assert_eq!(g.len(), 26);
        assert_eq!((g[0], g[25]), (0.05, 0.3));
        assert!(g.windows(2).all(|w| w[1] - w[0] <= 0.01 + 1e-15));
        // A grid that does not divide the range: ceil, so cells stay within it.
        let s = fig7a(0.0, 0.1, 0.03);
        let g = s.coarse();
        assert_eq!(g.len(), 5);
        assert!(g.windows(2).all(|w| w[1] - w[0] <= 0.03));
    }

    #[test]
    fn a_grid_as_wide_as_the_range_as_typed_is_one_cell_and_the_bounds_read_as_typed() {
        // 0.16 − 0.14 is 0.01999999999999999 in binary64: the typed 0.02 is the span.
        let s = fig7a(0.14, 0.16, 0.02);
        assert_eq!(s.coarse(), [0.14, 0.16]);
        // The finest grid, 1e5 cells, as the message shows it.
        let design = [0.8, 2.5, 0.125, 3.269, 0.0514];
        let finest = Settings::parse(design, 0.14, 0.16, 1e-9, 2e-7, &Names::CLI).unwrap();
        assert_eq!(finest.coarse().len(), 100_001);
        for grid in [0.021, 1.9e-7] {
            let e = Settings::parse(design, 0.14, 0.16, 1e-9, grid, &Names::CLI).unwrap_err();
            assert_eq!(
                e.to_string(),
                format!(
                    "--grid: {} is invalid: must be in [2e-7, 0.02] rad (at most 100000 slopes \
                     over --from..--to, at least two)",
                    Num(grid)
                )
            );
        }
        // The ends' rounding is an ulp of each end, not of the span: 1.501 − 1.5 is
        // 500 ulps of the span below 0.001.
        let s = fig7a(1.5, 1.501, 0.001);
        assert_eq!(s.coarse(), [1.5, 1.501]);
    }
}
