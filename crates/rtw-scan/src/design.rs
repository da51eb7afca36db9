//! `design`: the design search (the library's `search`; this only turns
//! flags into its settings and prints what it returns).

use super::progress::StderrProgress;
use super::signal::{EXIT_INTERRUPTED, GRACEFUL, STOP};
use super::simulate::ModelArgs;
use anyhow::Result;
use clap::Args;
use rtw_engine::scan::Run;
use rtw_engine::scan::workers::{Stopped, parse_threads};
use rtw_studies::search::{SearchSettings, files};
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::atomic::Ordering;

#[derive(Args, Debug)]
pub(super) struct DesignArgs {
    /// The search's config (configs/design/*.toml; docs/cli.md lists its keys), with the
    /// model's options in its [simulation] table.
    config: PathBuf,
    /// The search's folder [default: runs/design/NAME].
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    #[command(flatten)]
    options: ModelArgs,
    /// Worker threads [default: one per core; at most 4 per core]. The search does not depend on it.
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    threads: Option<String>,
    /// Write even over files that are not this search's.
    #[arg(long)]
    force: bool,
    /// Show no progress.
    #[arg(long)]
    quiet: bool,
}

pub(super) fn cmd_design(a: DesignArgs) -> Result<ExitCode> {
    let settings = SearchSettings::read(&a.config)?;
    let options = a.options.resolve_over(Some(&a.config))?;
    let threads = a
        .threads
        .as_deref()
        .map(|t| parse_threads(t, "--threads"))
        .transpose()?;
    let out = a
        .out
        .unwrap_or_else(|| PathBuf::from("runs/design").join(&settings.name));
    let progress = StderrProgress::unless(a.quiet);
    // A first signal stops the designs in flight; every finished design is
    // in OUT/search.parquet, and the same command resumes from them.
    GRACEFUL.store(true, Ordering::SeqCst);
    let done = files::run_to_files(
        &settings,
        &options,
        &out,
        a.force,
        &Run::new(&progress, &STOP).on(threads),
    );
    let (search, reported) = match done {
        Err(e) if e.downcast_ref::<Stopped>().is_some() && STOP.load(Ordering::SeqCst) => {
            let kept =
                files::stored(&out, &settings, &options, false).map_or(0, |k| k.evaluations.len());
            eprintln!(
                "rtw-scan: interrupted: {kept} designs kept in {}; the same command resumes \
                 the search from them",
                files::search_path(&out).display()
            );
            return Ok(ExitCode::from(EXIT_INTERRUPTED));
        }
        done => done?,
    };
    out!("{}", files::markdown(&search, &reported));
    eprintln!(
        "rtw-scan: {} designs ({} simulations, budget {}) written to {}",
        search.evaluations.len(),
        search.runs(),
        settings.budget,
        out.display()
    );
    Ok(ExitCode::SUCCESS)
}
