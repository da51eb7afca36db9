//! `run` and `merge`: a scan, whole or in shards, and its summary.

use super::progress::StderrProgress;
use super::signal::{EXIT_INTERRUPTED, GRACEFUL, STOP};
use super::{FakeSim, with_simulator};
use anyhow::{Result, anyhow};
use clap::Args;
use rtw_engine::config::ScanConfig;
use rtw_engine::entry::scan::{self, RunSettings, RunStatus, Shard};
use rtw_engine::hash::fnv1a64;
use rtw_engine::scan::Run;
use rtw_engine::scan::workers::parse_threads;
use std::num::NonZeroUsize;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::Ordering;

#[derive(Args, Debug)]
pub(super) struct RunArgs {
    /// Scan config (TOML).
    config: PathBuf,
    /// Output directory [default: runs/<scan name>/: the config's name (or file stem), +VARIANT with
    /// --variant, +set-HASH with --set, so that no ad-hoc run lands in results/ or in another run's directory].
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// Worker threads [default: one per core; at most 4 per core]. The rows do not depend on it.
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    threads: Option<String>,
    /// Layer a model variant file (configs/variants/*.toml: name, description, [simulation]) over the
    /// config's [simulation] table; the scan is named CONFIG-NAME+VARIANT-NAME.
    #[arg(long, value_name = "FILE")]
    variant: Option<PathBuf>,
    /// Override one simulation option after the variant (repeatable), e.g. initial.omega=-3.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
    /// Finish the interrupted run in DIR (keeps its finished chunks).
    #[arg(long)]
    resume: bool,
    /// Run only shard K of N (0-based): the K-th contiguous block of sample ids, into DIR/part-K.parquet; join the N parts with `rtw-scan merge DIR`.
    #[arg(long, value_name = "K/N")]
    shard: Option<Shard>,
    /// Write even into a directory that holds another scan's results (another config, another --shard
    /// split), its unfinished run or summaries rtw-scan did not write, replacing them; compute anew a
    /// scan it holds complete; start even when the output may not fit on the disk. Never writes through
    /// a symlink or over a special file.
    #[arg(long)]
    force: bool,
    /// Print no progress (errors and the interruption notice still go to stderr).
    #[arg(long)]
    quiet: bool,
    /// Rows per chunk and row group (a resumed run keeps its own).
    #[arg(long, hide = true, value_name = "N", value_parser = super::values::positive,
          default_value_t = NonZeroUsize::new(scan::DEFAULT_CHUNK_SIZE).unwrap())]
    chunk_size: NonZeroUsize,
}

#[derive(Args, Debug)]
pub(super) struct MergeArgs {
    /// The directory holding part-0.parquet … part-(N-1).parquet.
    dir: PathBuf,
    /// Replace a DIR/samples.parquet of another scan, or summaries that are not its own (never a
    /// symlink or a special file).
    #[arg(long)]
    force: bool,
    /// Print nothing on stderr but errors.
    #[arg(long)]
    quiet: bool,
}

/// The default output directory of a run: `runs/NAME/`, NAME the scan's
/// name (the config's `name` or file stem, `+VARIANT` with a variant) and,
/// with `--set`, `+set-` and a hash of the overrides, so that runs with
/// different overrides never share a directory and no ad-hoc run writes
/// into `results/` (the committed results, which scripts write explicitly).
fn default_out_dir(cfg: &ScanConfig, config_path: &Path, sets: &[String]) -> Result<PathBuf> {
    let stem = config_path
        .file_stem()
        .ok_or_else(|| anyhow!("config path {} has no file name", config_path.display()))?
        .to_string_lossy()
        .into_owned();
    let mut name = cfg.name.clone().unwrap_or(stem);
    if !sets.is_empty() {
        let h = fnv1a64(sets.join("\n").as_bytes());
        name += &format!("+set-{:08x}", h >> 32);
    }
    let name: String = name
        .chars()
        .map(|c| {
            if c == '/' || c == '\\' || c.is_control() {
                '_'
            } else {
                c
            }
        })
        .collect();
    let name = name.trim_start_matches('.');
    Ok(Path::new("runs").join(if name.is_empty() { "scan" } else { name }))
}

pub(super) fn cmd_run(a: RunArgs, fake: FakeSim) -> Result<ExitCode> {
    // A flag's value is refused before the config is read, as clap refuses it.
    let threads = a
        .threads
        .as_deref()
        .map(|t| parse_threads(t, "--threads"))
        .transpose()?;
    let cfg = super::validate::scan_config(&a.config, a.variant.as_deref(), &a.set)?;
    let out = match a.out.clone() {
        Some(d) => d,
        None => default_out_dir(&cfg, &a.config, &a.set)?,
    };
    scan::check_outputs(&cfg, &out, a.shard, a.force)?;
    GRACEFUL.store(true, Ordering::SeqCst);
    let settings = RunSettings {
        out_dir: out.clone(),
        resume: a.resume,
        chunk_size: a.chunk_size,
        shard: a.shard,
        force: a.force,
    };
    let progress = StderrProgress::unless(a.quiet);
    let run = Run::new(&progress, &STOP).on(threads);
    let status = with_simulator(fake, |sim| scan::run_scan(&cfg, &settings, sim, &run))?;
    finish_run(&a, &out, status)
}

/// What a run prints and returns once it has ended.
fn finish_run(a: &RunArgs, out: &Path, status: RunStatus) -> Result<ExitCode> {
    match status {
        RunStatus::Complete {
            samples,
            computed,
            rows,
        } => {
            if computed == 0 && !a.quiet {
                // Said with or without --resume: a finished scan of this
                // config and version is not run again (its rows would be
                // the same). Without --resume the user asked for a run, and
                // learns how to have one.
                let anew = if a.resume {
                    ""
                } else {
                    ": nothing computed (--force computes it anew)"
                };
                eprintln!("rtw-scan: {} is already complete{anew}", samples.display());
            }
            if let Some(s) = a.shard {
                // One part is not the scan: the summary comes with `merge`.
                // (stdout: scripts grep it; it is the command's result.)
                outln!(
                    "rtw-scan: shard {s}: {rows} rows in {}; when all {} shards are done: rtw-scan merge {}",
                    samples.display(),
                    s.count,
                    out.display()
                );
                return Ok(ExitCode::SUCCESS);
            }
            write_and_print_summary(out, &samples)
        }
        RunStatus::Interrupted {
            chunks_done,
            chunks,
            partial,
        } => {
            let mut again = format!("rtw-scan run {}", a.config.display());
            if let Some(v) = &a.variant {
                again += &format!(" --variant {}", v.display());
            }
            for s in &a.set {
                again += &format!(" --set {s}");
            }
            let shard = a.shard.map_or(String::new(), |s| format!(" --shard {s}"));
            eprintln!(
                "rtw-scan: interrupted: {chunks_done} of {chunks} chunks kept in {}; finish with: {again} --out {}{shard} --resume",
                partial.display(),
                out.display()
            );
            Ok(ExitCode::from(EXIT_INTERRUPTED))
        }
    }
}

/// The end of a whole scan (`run`, `merge`): its summary written beside
/// the samples file, and printed.
fn write_and_print_summary(dir: &Path, samples: &Path) -> Result<ExitCode> {
    let summary = scan::write_summary(dir, samples)?;
    out!("{}", summary.to_markdown());
    Ok(ExitCode::SUCCESS)
}

pub(super) fn cmd_merge(a: MergeArgs) -> Result<ExitCode> {
    let merged = scan::merge(&a.dir, a.force)?;
    if !a.quiet {
        eprintln!(
            "rtw-scan: merged {} shards, {} rows, into {}",
            merged.shards,
            merged.rows,
            merged.samples.display()
        );
    }
    write_and_print_summary(&a.dir, &merged.samples)
}
