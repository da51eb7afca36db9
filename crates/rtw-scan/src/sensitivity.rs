//! `sensitivity`: Sobol indices of a finished scan's outputs. The study is
//! the library's ([`rtw_studies::sensitivity`]); this parses and prints.

use super::progress::StderrProgress;
use super::signal::STOP;
use anyhow::Result;
use clap::Args;
use rtw_engine::scan::Run;
use rtw_studies::sensitivity::{self, Index, Settings};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Args, Debug)]
pub(super) struct SensitivityArgs {
    /// A scan: its samples.parquet, or the directory holding it.
    scan: PathBuf,
    /// Where to write the indices [default: indices.parquet beside the scan file].
    #[arg(long, value_name = "FILE.parquet")]
    out: Option<PathBuf>,
    /// Bootstrap resamples of the confidence intervals, an integer in [2, 10000].
    #[arg(
        long,
        value_name = "N",
        default_value = "100",
        allow_hyphen_values = true
    )]
    resamples: String,
    /// Seed of the bootstrap resamples, an integer in [0, 2^64 - 1] [default: the scan's seed].
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    seed: Option<String>,
    /// Print JSON (one object per index) instead of a table.
    #[arg(long)]
    json: bool,
    /// Write the indices even over a file that is not an indices file, or over another scan's
    /// indices (never over a symlink or a special file).
    #[arg(long)]
    force: bool,
    /// Print no progress (errors still go to stderr).
    #[arg(long)]
    quiet: bool,
}

pub(super) fn cmd_sensitivity(a: SensitivityArgs) -> Result<ExitCode> {
    let settings = Settings::parse(&a.resamples, a.seed.as_deref(), "--")?;
    let scan = sensitivity::scan_file(&a.scan);
    let out = a
        .out
        .clone()
        .unwrap_or_else(|| scan.with_file_name("indices.parquet"));
    let progress = StderrProgress::study(a.quiet, "sensitivity: bootstrap resamples");
    let analysis =
        sensitivity::analyse_to_file(&scan, &out, &settings, a.force, &Run::new(&progress, &STOP))?;
    if a.json {
        let all: Vec<_> = analysis.indices.iter().map(json).collect();
        outln!("{}", serde_json::to_string_pretty(&all)?);
    } else {
        out!(
            "{}",
            sensitivity::markdown(analysis.method.name(), &analysis.indices)
        );
    }
    if let Some(warning) = sensitivity::wide_warning(&analysis.indices) {
        eprintln!("warning: {warning}");
    }
    eprintln!("wrote {}", out.display());
    Ok(ExitCode::SUCCESS)
}

fn json(r: &Index) -> serde_json::Value {
    let num = |v: f64| v.is_finite().then_some(v);
    serde_json::json!({
        "output": r.output, "parameter": r.parameter,
        "S1": num(r.s1), "S1_conf": num(r.s1_conf), "ST": num(r.st), "ST_conf": num(r.st_conf),
    })
}
