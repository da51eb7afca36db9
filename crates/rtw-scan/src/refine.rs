//! `refine`: samples added to a finished scan where its labels change.

use super::progress::StderrProgress;
use super::signal::{EXIT_INTERRUPTED, GRACEFUL, STOP};
use super::{FakeSim, with_simulator};
use anyhow::Result;
use clap::Args;
use rtw_engine::entry::scan::{DEFAULT_CHUNK_SIZE, RunSettings, RunStatus, Shard};
use rtw_engine::scan::Run;
use rtw_engine::scan::workers::check_threads;
use rtw_studies::refine::{self, Refine, RefineStatus, check_budget};
use std::num::NonZeroUsize;
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::atomic::Ordering;

/// Rounds unless told otherwise: on the benchmark (docs/refine.md) the
/// label map gained with every split of a 400-sample budget up to 16 rounds
/// of 25 (2: none, 4: ratio 0.65, 8: 0.37, 16: 0.35, 40: 0.34).
const DEFAULT_ROUNDS: u64 = 16;

#[derive(Args, Debug)]
pub(super) struct RefineArgs {
    /// A finished scan's directory (its samples.parquet).
    dir: PathBuf,
    /// New samples in all rounds together (an integer >= 1).
    #[arg(long, value_name = "N")]
    budget: u64,
    /// Rounds the budget is split into (1 to --budget) [default: 16, at most --budget]; each round
    /// looks at every row before it.
    #[arg(long, value_name = "R")]
    rounds: Option<u64>,
    /// Seed of the rounds' candidates and uniform draws [default: the scan's seed].
    #[arg(long)]
    seed: Option<u64>,
    /// Worker threads [default: one per core]. The rows do not depend on it.
    #[arg(long, value_name = "N", value_parser = super::values::positive)]
    threads: Option<NonZeroUsize>,
    /// Run only shard K of N of the next unfinished round (into its directory's part-K.parquet); join
    /// them with `rtw-scan merge DIR/refine/round-RRR`, then run refine again for the next round.
    #[arg(long, value_name = "K/N")]
    shard: Option<Shard>,
    /// Discard an unfinished round of other points, and replace a DIR/refine/samples.parquet that is
    /// not this refinement's (never a symlink or a special file).
    #[arg(long)]
    force: bool,
    /// Print no progress.
    #[arg(long)]
    quiet: bool,
}

pub(super) fn cmd_refine(a: RefineArgs, fake: FakeSim) -> Result<ExitCode> {
    let rounds = a.rounds.unwrap_or(DEFAULT_ROUNDS.min(a.budget.max(1)));
    check_budget(a.budget, rounds)?;
    check_threads(a.threads, "--threads")?;
    let seed = match a.seed {
        Some(s) => s,
        None => refine::default_seed(&a.dir)?,
    };
    let r = Refine {
        dir: a.dir.clone(),
        budget: a.budget,
        rounds,
        seed,
        run: RunSettings {
            out_dir: a.dir.clone(),
            resume: true,
            chunk_size: NonZeroUsize::new(DEFAULT_CHUNK_SIZE).expect("positive"),
            shard: a.shard,
            force: a.force,
        },
    };
    GRACEFUL.store(true, Ordering::SeqCst);
    let progress = StderrProgress::unless(a.quiet);
    let run = Run::new(&progress, &STOP).on(a.threads);
    finish(
        &a,
        with_simulator(fake, |sim| refine::refine(&r, sim, &run))?,
    )
}

fn finish(a: &RefineArgs, status: RefineStatus) -> Result<ExitCode> {
    match status {
        RefineStatus::Complete { combined, rows } => {
            outln!(
                "rtw-scan: refined: {rows} rows (the scan's and {} new) in {}",
                a.budget,
                combined.display()
            );
            Ok(ExitCode::SUCCESS)
        }
        RefineStatus::Interrupted { round } => {
            eprintln!(
                "rtw-scan: interrupted while choosing the points of round {round}: the finished \
                 rounds are kept; finish with the same command"
            );
            Ok(ExitCode::from(EXIT_INTERRUPTED))
        }
        RefineStatus::Stopped { round, dir, status } => match status {
            RunStatus::Complete { samples, rows, .. } => {
                outln!(
                    "rtw-scan: round {round}: {rows} rows in {}; when every shard is done: rtw-scan merge {}, \
                     then run refine again",
                    samples.display(),
                    dir.display()
                );
                Ok(ExitCode::SUCCESS)
            }
            RunStatus::Interrupted {
                chunks_done,
                chunks,
                partial,
            } => {
                eprintln!(
                    "rtw-scan: interrupted in round {round}: {chunks_done} of {chunks} chunks kept in {}; \
                     finish with the same command",
                    partial.display()
                );
                Ok(ExitCode::from(EXIT_INTERRUPTED))
            }
        },
    }
}
