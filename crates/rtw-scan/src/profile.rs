//! `profile`: a design's gait along the slope, each change of label located
//! by bisection (the library's `profile`; this only turns flags into its
//! settings and prints what it returns).

use super::progress::StderrProgress;
use super::signal::STOP;
use super::simulate::{DesignArgs, OptionArgs};
use anyhow::Result;
use clap::Args;
use rtw_engine::scan::Run;
use rtw_engine::scan::workers::parse_threads;
use rtw_studies::profile::{self, Names, Settings};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Args, Debug)]
pub(super) struct ProfileArgs {
    #[command(flatten)]
    design: DesignArgs,
    /// The slope range's start φ [rad].
    #[arg(long, allow_negative_numbers = true, value_parser = super::values::float)]
    from: f64,
    /// The slope range's end φ [rad], above --from.
    #[arg(long, allow_negative_numbers = true, value_parser = super::values::float)]
    to: f64,
    /// Locate each change of label to a bracket at most this wide [rad], in [1e-9, --grid].
    #[arg(long, default_value_t = 1e-3, value_parser = super::values::float)]
    tol: f64,
    /// The coarse grid's spacing [rad] (at most; the range is cut into equal cells): a feature
    /// narrower than it, with one label at both its ends, is not seen.
    #[arg(long, default_value_t = 0.01, value_parser = super::values::float)]
    grid: f64,
    #[command(flatten)]
    options: OptionArgs,
    /// Worker threads [default: one per core; at most 4 per core]. The profile does not depend on it.
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    threads: Option<String>,
    /// Print the profile as one JSON object (intervals per gait, phi_min, phi_lo, phi_hi, changes,
    /// segments) instead of its summary.
    #[arg(long)]
    json: bool,
    /// Write every simulated slope (a scan's columns) to this Parquet file, its summary beside it (FILE.md).
    #[arg(long, value_name = "FILE.parquet")]
    out: Option<PathBuf>,
    /// Write even over files that are not a slope profile's.
    #[arg(long)]
    force: bool,
    /// Show no progress.
    #[arg(long)]
    quiet: bool,
}

pub(super) fn cmd_profile(a: ProfileArgs) -> Result<ExitCode> {
    let settings = Settings::parse(a.design.values(), a.from, a.to, a.tol, a.grid, &Names::CLI)?;
    let threads = a
        .threads
        .as_deref()
        .map(|t| parse_threads(t, "--threads"))
        .transpose()?;
    let options = a.options.resolve()?;
    let progress = StderrProgress::unless(a.quiet);
    let run = Run::new(&progress, &STOP).on(threads);
    let p = match &a.out {
        Some(out) => profile::run_to_files(&settings, &options, out, a.force, &run)?,
        None => profile::run(&settings, &options, &run)?,
    };
    if a.json {
        outln!("{}", serde_json::to_string_pretty(&p.to_json())?);
    } else {
        out!("{}", profile::markdown(&p));
    }
    if let Some(out) = &a.out {
        eprintln!("rtw-scan: {} slopes written to {}", p.runs(), out.display());
    }
    Ok(ExitCode::SUCCESS)
}
