//! `basin`: a slice of a gait's basin of attraction, a grid of perturbed
//! section points each iterated on the step map and classified.

use super::bifurcation::ModelArgs;
use super::progress::StderrProgress;
use super::signal::STOP;
use anyhow::Result;
use clap::Args;
use rtw_engine::config::params::checked_params;
use rtw_engine::scan::Run;
use rtw_engine::scan::workers::parse_threads;
use rtw_studies::basin::{self, OUTCOMES, Settings, outcome_index};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Args, Debug)]
pub(super) struct BasinArgs {
    #[command(flatten)]
    model: ModelArgs,
    /// The grid's first axis, COORD:FROM:TO:POINTS: offsets FROM..TO (POINTS of them, ends included) of COORD
    /// from the gait's fixed point; COORD is omega_a, omega_b, omega_c (a rod's ω, rad/s) or theta_a, theta_b,
    /// theta_c (a rod's θ, rad), rod a being the landing rod.
    #[arg(long, value_name = "COORD:FROM:TO:POINTS", allow_hyphen_values = true)]
    x: String,
    /// The grid's second axis, as --x, another coordinate.
    #[arg(long, value_name = "COORD:FROM:TO:POINTS", allow_hyphen_values = true)]
    y: String,
    /// Most steps each point is iterated on the step map, an integer in [1, 100000].
    #[arg(
        long,
        value_name = "N",
        default_value = "60",
        allow_hyphen_values = true
    )]
    steps: String,
    /// A point returns when its scaled distance to the gait's orbit is at most this.
    #[arg(long, default_value_t = 1e-3, value_parser = super::values::float)]
    tol: f64,
    /// Worker threads [default: one per core; at most 4 per core]. The rows do not depend on it.
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    threads: Option<String>,
    /// The grid, one row per point.
    #[arg(long, value_name = "FILE.parquet")]
    out: PathBuf,
    /// Write even over a file that is not a basin slice.
    #[arg(long)]
    force: bool,
    /// Print no progress (errors still go to stderr).
    #[arg(long)]
    quiet: bool,
}

pub(super) fn cmd_basin(a: BasinArgs) -> Result<ExitCode> {
    let (p, options) = a.model.resolve()?;
    let params = checked_params([p.length, p.rho, p.alpha, p.f_n, p.zeta, p.phi], "--")?;
    // The options are checked where they are read (`simulation_options`).
    let settings = Settings::parse(&a.x, &a.y, &a.steps, a.tol, "--")?;
    let threads = a
        .threads
        .as_deref()
        .map(|t| parse_threads(t, "--threads"))
        .transpose()?;
    let spec = settings.spec;
    let progress = StderrProgress::study(a.quiet, "basin: grid points");
    let (slice, points, wall) = basin::run_to_files(
        &params,
        &options,
        &settings,
        &a.out,
        a.force,
        &Run::new(&progress, &STOP).on(threads),
    )?;
    let per_point = wall / points.len() as f64;
    let (cx, cy) = slice.centre();
    outln!(
        "gait: {}, period {} (max |mu| {:.4}), fixed point {} = {cx:.6}, {} = {cy:.6}",
        slice.label.as_str(),
        slice.cycle.period,
        slice.cycle.floquet_max(),
        spec.x.coord,
        spec.y.coord,
    );
    let mut counts = [0usize; OUTCOMES.len()];
    for p in &points {
        counts[outcome_index(&p.fate)] += 1;
    }
    let shown: Vec<String> = OUTCOMES
        .iter()
        .zip(counts)
        .map(|(o, n)| format!("{o} {n}"))
        .collect();
    outln!("{} points: {}", points.len(), shown.join(", "));
    outln!(
        "{wall:.1} s ({:.1} ms per point, wall-clock over the worker threads); written to {}",
        1e3 * per_point,
        a.out.display()
    );
    Ok(ExitCode::SUCCESS)
}
