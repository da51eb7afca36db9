//! `simulate`: one run, its row printed, its trace written.

use super::FakeSim;
use super::validate::simulation_options;
use anyhow::Result;
use clap::Args;
use rtw_engine::config::params::checked_params;
use rtw_engine::io::scan_rows::{JsonRow, row_text};
use rtw_engine::io::{TraceNames, TraceWriter};
use rtw_engine::scan::one::run_one;
use rtw_model::options::RobustnessOptions;
use rtw_model::outcome::Energy;
use rtw_model::{Label, Options, Outcome, Params};
use std::path::PathBuf;
use std::process::ExitCode;

/// A design's five inputs without its slope: the flags of `simulate`,
/// which `profile` takes alike.
#[derive(Args, Debug)]
pub(super) struct DesignArgs {
    /// Rod length L [m].
    #[arg(long, value_parser = super::values::float)]
    length: f64,
    /// Mass per length ρ [kg/m].
    #[arg(long, value_parser = super::values::float)]
    rho: f64,
    /// Connection ratio α, in [0, 0.49].
    #[arg(long, value_parser = super::values::float)]
    alpha: f64,
    /// Eigen-frequency f_n [Hz].
    #[arg(long = "fn", value_name = "FN", value_parser = super::values::float)]
    f_n: f64,
    /// Damping ratio ζ.
    #[arg(long, value_parser = super::values::float)]
    zeta: f64,
}

impl DesignArgs {
    /// L, ρ, α, f_n, ζ as given (unchecked).
    pub(super) fn values(&self) -> [f64; 5] {
        [self.length, self.rho, self.alpha, self.f_n, self.zeta]
    }
}

/// The simulation options of `simulate` (and `profile`): a config's
/// `[simulation]`, a variant over it, `--set` overrides over both.
#[derive(Args, Debug)]
pub(super) struct OptionArgs {
    /// Take the [simulation] options of this config file.
    #[arg(long, value_name = "FILE")]
    config: Option<PathBuf>,
    #[command(flatten)]
    model: ModelArgs,
}

impl OptionArgs {
    /// The options, layered and validated.
    pub(super) fn resolve(&self) -> Result<Options> {
        self.model.resolve_over(self.config.as_deref())
    }
}

/// A model variant and `--set` overrides, over the `[simulation]` table of
/// a config: `--config`'s, or (`design`) the study's own config's, which
/// then is the table's one place.
#[derive(Args, Debug)]
pub(super) struct ModelArgs {
    /// Layer a model variant file (configs/variants/*.toml) over them, as `run --variant` does.
    #[arg(long, value_name = "FILE")]
    variant: Option<PathBuf>,
    /// Override one simulation option after the variant (repeatable), e.g. contact.mu=0.8.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
}

impl ModelArgs {
    /// The options over `config`'s `[simulation]` table, layered and validated.
    pub(super) fn resolve_over(&self, config: Option<&std::path::Path>) -> Result<Options> {
        simulation_options(config, self.variant.as_deref(), &self.set)
    }
}

#[derive(Args, Debug)]
pub(super) struct SimulateArgs {
    #[command(flatten)]
    design: DesignArgs,
    /// Slope φ [rad].
    #[arg(long, allow_negative_numbers = true, value_parser = super::values::float)]
    phi: f64,
    #[command(flatten)]
    options: OptionArgs,
    /// Print one JSON object: `outcome` (the label) and every metric, flattened, with the derived parameters.
    #[arg(long)]
    json: bool,
    /// Write the time series (one row per trace sample) to this Parquet file.
    #[arg(long, value_name = "FILE.parquet")]
    trace: Option<PathBuf>,
    /// Refuse a trace whose size before compression (samples × bytes per sample, estimated from
    /// t_max / trace_dt, or max_steps when trace_dt = 0) exceeds this, e.g. 500MB, 10GB.
    #[arg(long, value_name = "SIZE", default_value = "2GB", value_parser = rtw_engine::sizes::parse_size)]
    trace_limit: u64,
    /// Write the trace even over a file that is not a trace.
    #[arg(long)]
    force: bool,
}

pub(super) fn cmd_simulate(a: SimulateArgs, fake: FakeSim) -> Result<ExitCode> {
    let [length, rho, alpha, f_n, zeta] = a.design.values();
    let params = checked_params([length, rho, alpha, f_n, zeta, a.phi], "--")?;
    let options = a.options.resolve()?;
    let mut trace = match &a.trace {
        Some(path) => Some(TraceWriter::to_file(
            path,
            &params,
            &options,
            a.trace_limit,
            a.force,
            "--trace",
            TraceNames::CLI,
        )?),
        None => None,
    };
    let mut trace_error = None;
    if let Some(line) = measuring(&options.robustness) {
        eprintln!("{line}");
    }
    let row = run_one(0, params, &options, |p: &Params, o: &Options| -> Outcome {
        if let Some(delay) = fake {
            return rtw_engine::fake::simulate(p, o, delay);
        }
        match trace.as_mut() {
            Some(w) => rtw_model::simulate_traced(p, o, &mut |s| {
                if trace_error.is_none() {
                    trace_error = w.push(s).err();
                }
            }),
            None => rtw_model::simulate(p, o),
        }
    });
    if let Some(e) = trace_error {
        return Err(e.context("writing the trace"));
    }
    if let (Some(w), Some(path)) = (trace, &a.trace) {
        let n = w.finish()?;
        eprintln!(
            "rtw-scan: trace of {n} samples written to {}",
            path.display()
        );
    }
    if a.json {
        outln!(
            "{}",
            serde_json::to_string_pretty(&JsonRow(&row, &options.robustness))?
        );
    } else {
        out!("{}", row_text(&row, &options.robustness));
    }
    if let Some(e) = row.outcome.map(|o| o.energy)
        && e.balance_exceeds_bound()
    {
        eprintln!("warning: {}", energy_warning(&e));
    }
    // `diverged` is the one label of a run that did not finish: a panic
    // (its message) or a numerical failure (what its failure means).
    if row.label() != Label::Diverged {
        return Ok(ExitCode::SUCCESS);
    }
    let why = row
        .message()
        .or_else(|| row.outcome.and_then(|o| o.failure).map(|f| f.describe()));
    eprintln!(
        "error: the simulation did not finish: {}",
        why.unwrap_or("diverged")
    );
    Ok(ExitCode::FAILURE)
}

/// The line `simulate` prints on stderr before a run with robustness
/// measures, naming them: each runs the gait again (seconds, minutes for a
/// deep MFPT), and a command silent that long looks hung. `None` without
/// any: a bare run takes milliseconds and stays silent.
fn measuring(r: &RobustnessOptions) -> Option<String> {
    let asked: Vec<&str> = [
        ("step_down", r.step_down),
        ("step_down_h50", r.step_down_h50),
        ("step_down_at", r.step_down_at > 0.0),
        ("gsn", r.gsn),
        ("steps_to_fall", r.steps_to_fall),
        ("mfpt", r.mfpt),
    ]
    .into_iter()
    .filter_map(|(name, on)| on.then_some(name))
    .collect();
    (!asked.is_empty()).then(|| {
        format!(
            "rtw-scan: simulating, then measuring {} on the gait found (each measure runs it again)",
            asked.join(", ")
        )
    })
}

/// What `simulate` says of a run whose energy balance is off by more than
/// its bound: the integration error is then large enough to doubt the outcome.
pub(crate) fn energy_warning(e: &Energy) -> String {
    format!(
        "the energy balance is off by {:.2} % of the energy at stake (|energy_balance_error| / \
         max(|energy_initial|, energy_gravity_released)), above the bound of {} % (Fig. 7(a): \
         0.015 % at the default tolerance): the integration error may change this outcome; rerun \
         with a tighter tolerance (--set rtol=1e-6) to check it",
        100.0 * e.relative_balance_error(),
        100.0 * Energy::BALANCE_BOUND
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn simulate_options_layer_config_and_sets() {
        let dir = tempfile::tempdir().unwrap();
        let f = dir.path().join("c.toml");
        std::fs::write(
            &f,
            "seed = 1\n[simulation]\nt_max = 5.0\ncontact.mu = 0.5\n",
        )
        .unwrap();
        let o = simulation_options(
            Some(&f),
            None,
            &["contact.mu=0.8".into(), "initial.omega=-3".into()],
        )
        .unwrap();
        assert_eq!((o.t_max, o.contact.mu, o.initial.omega), (5.0, 0.8, -3.0));
        let e = simulation_options(None, None, &["contact.mu=2".into()]).unwrap_err();
        assert!(
            format!("{e:#}").contains("simulation.contact.mu: 2 is invalid"),
            "{e:#}"
        );
    }
}
