//! `sensitivity`: Sobol indices of a finished scan's outputs.

use crate::analysis::sensitivity::{self, Index};
use crate::files;
use crate::io::metadata::{FileKind, META_SENSITIVITY, META_VERSION, kv};
use crate::io::{destination, parquet};
use anyhow::Result;
use clap::Args;
use std::num::NonZeroUsize;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Args, Debug)]
pub(super) struct SensitivityArgs {
    /// A scan: its samples.parquet, or the directory holding it.
    scan: PathBuf,
    /// Where to write the indices [default: indices.parquet beside the scan file].
    #[arg(long, value_name = "FILE.parquet")]
    out: Option<PathBuf>,
    /// Bootstrap resamples of the confidence intervals.
    #[arg(long, default_value = "100", value_parser = super::values::positive)]
    resamples: NonZeroUsize,
    /// Seed of the bootstrap resamples [default: the scan's seed].
    #[arg(long)]
    seed: Option<u64>,
    /// Print JSON (one object per index) instead of a table.
    #[arg(long)]
    json: bool,
    /// Write the indices even over a file that is not an indices file (never over a symlink or a
    /// special file).
    #[arg(long)]
    force: bool,
}

pub(super) fn cmd_sensitivity(a: SensitivityArgs) -> Result<ExitCode> {
    let scan = if a.scan.is_dir() {
        a.scan.join("samples.parquet")
    } else {
        a.scan.clone()
    };
    let out = a
        .out
        .clone()
        .unwrap_or_else(|| scan.with_file_name("indices.parquet"));
    destination::check_destination(&out, FileKind::Sensitivity, &[&scan], "--out", a.force)?;
    let (cfg, cols) = sensitivity::read(&scan)?;
    let seed = a.seed.unwrap_or(cfg.seed);
    let (method, rows) = sensitivity::indices(&cfg, &cols, a.resamples.get(), seed)?;
    let about = serde_json::json!({
        "method": method.name(),
        "scan": scan.display().to_string(),
        "config_hash": cfg.hash(),
        "rows": cols.outputs.first().map_or(0, |(_, y)| y.len()),
        "resamples": a.resamples.get(),
        "seed": seed,
    });
    files::remove_stray_temps(&out)?;
    parquet::write_file(
        &out,
        &sensitivity::to_batch(&rows),
        vec![
            kv(META_VERSION, env!("CARGO_PKG_VERSION").into()),
            kv(META_SENSITIVITY, about.to_string()),
        ],
    )?;
    if a.json {
        let all: Vec<_> = rows.iter().map(json).collect();
        println!("{}", serde_json::to_string_pretty(&all)?);
    } else {
        print!("{}", table(method.name(), &rows));
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

/// The indices as a Markdown table, ± the 95 % half-widths.
fn table(method: &str, rows: &[Index]) -> String {
    let mut s = format!(
        "Sobol indices ({method}), ± 95 % bootstrap half-width\n\n| output | parameter | S1 | ST |\n|---|---|---:|---:|\n"
    );
    for r in rows {
        let st = if r.st.is_nan() {
            "–".to_string()
        } else {
            format!("{:.3} ± {:.3}", r.st, r.st_conf)
        };
        s.push_str(&format!(
            "| {} | {} | {:.3} ± {:.3} | {st} |\n",
            r.output, r.parameter, r.s1, r.s1_conf
        ));
    }
    s
}
