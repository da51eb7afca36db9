//! `bifurcation`: one parameter swept with continuation on the step map.
//! The study is the library's ([`rtw_studies::bifurcation`]); this
//! parses and prints.

use super::progress::StderrProgress;
use super::signal::{EXIT_INTERRUPTED, GRACEFUL, STOP};
use super::validate::simulation_options;
use anyhow::Result;
use clap::Args;
use rtw_engine::config::params::SweepParam;
use rtw_engine::scan::Run;
use rtw_engine::scan::workers::Stopped;
use rtw_model::{Options, Params};
use rtw_studies::bifurcation::{self, Sweep};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::Ordering;

/// The start of a sweep or a diagram: the base point (default Fig. 7(a))
/// and the model (`bifurcation` and `continuation` take it alike).
#[derive(Args, Debug)]
pub(super) struct ModelArgs {
    /// Base point: rod length L [m] (default: Fig. 7(a)).
    #[arg(long, value_parser = super::values::float)]
    length: Option<f64>,
    /// Base point: mass per length ρ [kg/m].
    #[arg(long, value_parser = super::values::float)]
    rho: Option<f64>,
    /// Base point: connection ratio α.
    #[arg(long, value_parser = super::values::float)]
    alpha: Option<f64>,
    /// Base point: eigen-frequency f_n [Hz].
    #[arg(long = "fn", value_name = "FN", value_parser = super::values::float)]
    f_n: Option<f64>,
    /// Base point: damping ratio ζ.
    #[arg(long, value_parser = super::values::float)]
    zeta: Option<f64>,
    /// Base point: slope φ [rad].
    #[arg(long, allow_negative_numbers = true, value_parser = super::values::float)]
    phi: Option<f64>,
    /// Take the [simulation] options of this config file.
    #[arg(long, value_name = "FILE")]
    config: Option<PathBuf>,
    /// Layer a model variant file (configs/variants/*.toml) over them.
    #[arg(long, value_name = "FILE")]
    variant: Option<PathBuf>,
    /// Override one simulation option (repeatable), e.g. strings.rest_length_ratio=0.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
}

impl ModelArgs {
    /// The base point and the resolved options (checked).
    pub(super) fn resolve(&self) -> Result<(Params, Options)> {
        let d = Params::fig7a();
        let base = Params {
            length: self.length.unwrap_or(d.length),
            rho: self.rho.unwrap_or(d.rho),
            alpha: self.alpha.unwrap_or(d.alpha),
            f_n: self.f_n.unwrap_or(d.f_n),
            zeta: self.zeta.unwrap_or(d.zeta),
            phi: self.phi.unwrap_or(d.phi),
        };
        let options =
            simulation_options(self.config.as_deref(), self.variant.as_deref(), &self.set)?;
        Ok((base, options))
    }
}

#[derive(Args, Debug)]
pub(super) struct BifurcationArgs {
    /// The swept parameter: length, rho, alpha, fn, zeta, phi or s (strings.rest_length_ratio).
    #[arg(long, default_value = "phi")]
    param: String,
    /// First value of the sweep.
    #[arg(long, allow_negative_numbers = true, default_value_t = 0.02, value_parser = super::values::float)]
    from: f64,
    /// Last value of the sweep (from > to sweeps downwards).
    #[arg(long, allow_negative_numbers = true, default_value_t = 0.35, value_parser = super::values::float)]
    to: f64,
    /// Number of values, from and to included.
    #[arg(long, default_value_t = 121)]
    points: usize,
    #[command(flatten)]
    model: ModelArgs,
    /// Steps iterated at each value before recording.
    #[arg(long, default_value_t = 200)]
    transient: usize,
    /// Steps recorded at each value (periods up to record/2, at most 12, are detected).
    #[arg(long, default_value_t = 48)]
    record: usize,
    /// Per-value output (FILE.steps.parquet and FILE.md are written beside it) [default: runs/bifurcation/PARAM.parquet].
    #[arg(long, value_name = "FILE.parquet")]
    out: Option<PathBuf>,
    /// Write even over files that are not this sweep's kind.
    #[arg(long)]
    force: bool,
    /// Print no per-value progress.
    #[arg(long)]
    quiet: bool,
}

pub(super) fn cmd_bifurcation(a: BifurcationArgs) -> Result<ExitCode> {
    let (base, options) = a.model.resolve()?;
    let param = SweepParam::parse(&a.param)?;
    let sweep = Sweep::new(
        param,
        a.from,
        a.to,
        a.points,
        base,
        options,
        a.transient,
        a.record,
    )?;
    let out = a
        .out
        .unwrap_or_else(|| Path::new("runs/bifurcation").join(format!("{}.parquet", param.name())));
    let progress = StderrProgress::study(a.quiet, "bifurcation: values");
    // A first signal stops the sweep at its value in flight's next step;
    // nothing is written (the three files appear together or not at all).
    GRACEFUL.store(true, Ordering::SeqCst);
    let written =
        match bifurcation::run_to_files(&sweep, &out, a.force, &Run::new(&progress, &STOP)) {
            Err(e) if e.downcast_ref::<Stopped>().is_some() && STOP.load(Ordering::SeqCst) => {
                eprintln!("rtw-scan: interrupted: the sweep stopped; nothing was written");
                return Ok(ExitCode::from(EXIT_INTERRUPTED));
            }
            written => written?,
        };
    if !a.quiet {
        eprintln!(
            "rtw-scan: {} values in {}, {} recorded steps in {}",
            written.values,
            out.display(),
            written.steps,
            written.steps_path.display()
        );
    }
    out!("{}", written.summary);
    Ok(ExitCode::SUCCESS)
}
