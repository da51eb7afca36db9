//! `continuation`: a gait's limit cycle continued in one input (and its folds
//! and period doublings in two) by pseudo-arclength on the step map.

use super::bifurcation::ModelArgs;
use super::progress::StderrProgress;
use super::signal::{EXIT_INTERRUPTED, GRACEFUL, STOP};
use anyhow::Result;
use clap::Args;
use rtw_engine::scan::Run;
use rtw_engine::scan::workers::Stopped;
use rtw_model::Param;
use rtw_model::cycles::Section;
use rtw_studies::continuation::{self as study, Continuation, CurveSettings};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::Ordering;

#[derive(Args, Debug)]
pub(super) struct ContinuationArgs {
    /// The continued input: length, rho, alpha, fn, zeta or phi.
    #[arg(long, default_value = "phi")]
    param: String,
    /// The branches end below this value.
    #[arg(long, allow_negative_numbers = true, default_value_t = 0.02, value_parser = super::values::float)]
    from: f64,
    /// The branches end above this value.
    #[arg(long, allow_negative_numbers = true, default_value_t = 0.35, value_parser = super::values::float)]
    to: f64,
    #[command(flatten)]
    model: ModelArgs,
    /// First step, in scaled arclength (coordinates over their scales, the input over 0.1·max(1, |start|)).
    #[arg(long, default_value_t = 0.02, value_parser = super::values::float)]
    ds: f64,
    /// Largest step, in scaled arclength.
    #[arg(long, default_value_t = 0.05, value_parser = super::values::float)]
    ds_max: f64,
    /// Most points per branch.
    #[arg(long, default_value_t = 400)]
    max_points: usize,
    /// The step map's section: `stays` (a new foot that stays on the ground: the walk's step) or
    /// `touch-and-go` (every new foot's touchdown: for skips whose feet touch and lift at once).
    #[arg(long, default_value = "stays")]
    section: String,
    /// Also continue each fold and period doubling of the branches through the start in this second input
    /// (the boundary of the region where the gait exists and is stable).
    #[arg(long, value_name = "PARAM")]
    curve: Option<String>,
    /// The curves end below this value of the second input.
    #[arg(long, allow_negative_numbers = true, requires = "curve", value_parser = super::values::float)]
    curve_from: Option<f64>,
    /// The curves end above this value of the second input.
    #[arg(long, allow_negative_numbers = true, requires = "curve", value_parser = super::values::float)]
    curve_to: Option<f64>,
    /// Also continue the gait's branch through the changes of its mode sequence, up to this many segments
    /// each way, and each period-2 branch on from where its smooth continuation stopped; each change
    /// located and named (FILE.segments.json and a table in FILE.md; 0: off).
    #[arg(long, default_value_t = 0, value_name = "N", value_parser = super::values::through)]
    through: usize,
    /// Branch points (FILE.special.parquet, FILE.curve.parquet and FILE.md are written beside it)
    /// [default: runs/continuation/PARAM.parquet].
    #[arg(long, value_name = "FILE.parquet")]
    out: Option<PathBuf>,
    /// Write even over files that are not this command's kind.
    #[arg(long)]
    force: bool,
    /// Print no progress (the diagram, then each direction followed through the mode
    /// changes; errors still go to stderr).
    #[arg(long)]
    quiet: bool,
}

/// Parses an input's name, naming the flag and the choices.
fn input(name: &str, flag: &str) -> Result<Param> {
    name.parse::<Param>().map_err(|_| {
        anyhow::anyhow!(
            "{flag}: unknown input `{name}`: must be one of {}",
            Param::ALL.map(Param::name).join(", ")
        )
    })
}

pub(super) fn cmd_continuation(a: ContinuationArgs) -> Result<ExitCode> {
    let (base, options) = a.model.resolve()?;
    let param = input(&a.param, "--param")?;
    let curve = match &a.curve {
        None => None,
        Some(name) => {
            let p2 = input(name, "--curve")?;
            let (Some(lo), Some(hi)) = (a.curve_from, a.curve_to) else {
                anyhow::bail!("--curve {name}: needs --curve-from and --curve-to");
            };
            Some(CurveSettings {
                param: p2,
                range: (lo, hi),
            })
        }
    };
    let section = match a.section.as_str() {
        "stays" => Section::Stays,
        "touch-and-go" => Section::TouchAndGo,
        other => anyhow::bail!("--section {other}: must be `stays` or `touch-and-go`"),
    };
    let mut c = Continuation::new(
        param,
        base,
        options,
        (a.from, a.to),
        a.ds,
        a.ds_max,
        a.max_points,
        curve,
    )?;
    c.cycle.section = section;
    let out = a.out.unwrap_or_else(|| {
        Path::new("runs/continuation").join(format!("{}.parquet", param.name()))
    });
    let progress = StderrProgress::study(a.quiet, "continuation");
    // A first signal stops the diagram at its model run's next step;
    // nothing is written (its files appear together or not at all).
    GRACEFUL.store(true, Ordering::SeqCst);
    let md = match study::run_to_files(&c, a.through, &out, a.force, &Run::new(&progress, &STOP)) {
        Err(e) if e.downcast_ref::<Stopped>().is_some() && STOP.load(Ordering::SeqCst) => {
            eprintln!("rtw-scan: interrupted: the continuation stopped; nothing was written");
            return Ok(ExitCode::from(EXIT_INTERRUPTED));
        }
        md => md?,
    };
    out!("{md}");
    Ok(ExitCode::SUCCESS)
}
