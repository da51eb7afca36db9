//! # rtw-scan
//!
//! Seeded, parallel parameter scans of the RTW model (`rtw-model`), streamed
//! to Parquet, with outcome statistics and failure clustering. The binary
//! `rtw-scan` is a thin shell over `main` (the `cli` feature).
//!
//! The folders are the layers, each using only the ones above it in this
//! table (and `hash`, the fixed hash functions):
//!
//! | module | role |
//! |---|---|
//! | `files` | the file system's primitives: temporary files renamed into place, bounded reads, cleanup on a signal |
//! | `sizes` | byte counts read from text (`2GB`) and written for people |
//! | [`sampling`] | the sampling designs: draw → unit-cube point (random, Sobol, Halton, LHS, grid, Saltelli) |
//! | [`config`] | TOML → validated [`config::ScanConfig`]: schema, variant and `--set` layers, the parameter vocabulary, hashing |
//! | [`io`] | column tables; Parquet written atomically with a content hash and read back checked; traces, assignments |
//! | [`scan`] | sample ids → parameters → rows: parallel chunks, resume, shards, progress, locks |
//! | `analysis` | k-means of the failures, shares with Wilson intervals, summary files |
//! | `refine` | refinement rounds: where a round samples (candidates whose nearest samples' labels disagree) and each round run as a scan of stored points |
//! | `bifurcation` | one parameter swept, following the attractor on the step map: its files and summary |
//! | `basin` | a slice of a gait's basin of attraction: its grid points in parallel, its Parquet file |
//! | [`profile`] | a design's slope profile: its gait along φ, each change of label located by bisection, its stable intervals |
//! | [`search`] | design search: the design of a box that walks on the widest range of slopes, the shallowest slope or fastest, by CMA-ES over slope profiles with falls a learned constraint; a Pareto front of two objectives |
//! | `continuation` | a gait's branch followed in one input (stable and unstable), its bifurcations, the period-2 branches born there, fold and period-doubling curves in two inputs |
//! | [`studies`] | the public entry point of each study computed above (a scan and its merge, its summary and clusters, refinement, a bifurcation sweep, continuation), which the command line calls and only prints |
//! | [`dictionary`] | every Parquet column's unit and meaning (docs/data-dictionary.md) |
//! | `cli` | the `run`, `merge`, `simulate`, `bifurcation`, `continuation`, `cluster`, `summary` subcommands; the progress bar and the signal handler (the `cli` feature only) |
//!
//! The public API is what the binary, `rtw-bench` and the tests use; the
//! rest is private to the crate. The command line (`cli`, with clap, ctrlc
//! and indicatif) is the default `cli` feature, which only the binary needs:
//! the library's users (rtw-py, rtw-bench) leave it out, and the library
//! itself shows nothing on a terminal. What watches a scan, and what stops
//! it, are passed to it ([`scan::Progress`], a stop flag). The deterministic
//! stand-in simulator `fake` (hidden flag `--fake-sim`) exists only with the
//! `fake-sim` feature, which the crate's own tests turn on; they run it as
//! the binary `rtw-scan-test`, which a plain build never writes.
//!
//! ## Usage
//!
//! ```text
//! rtw-scan run configs/paper.toml [--out DIR] [--threads N] [--resume] [--shard K/N]
//! rtw-scan merge DIR
//! rtw-scan simulate --length 0.8 --rho 2.5 --alpha 0.125 --fn 3.269 --zeta 0.0514 --phi 0.15 \
//!     [--config FILE] [--set contact.mu=0.8]... [--json] [--trace trace.parquet]
//! rtw-scan cluster results/paper/samples.parquet [--k 3] [--json]
//! rtw-scan summary results/paper/samples.parquet [--json]
//! ```
//!
//! `run` writes `DIR/samples.parquet`, `DIR/summary.json` and
//! `DIR/summary.md` (default `DIR`: `runs/<scan name>/`). The
//! Parquet file is checked from Python (pandas, polars, pyarrow) by
//! `scripts/check_parquet.py`.

#![warn(missing_docs)]

pub(crate) mod analysis;
pub mod basin;
pub(crate) mod bifurcation;
#[cfg(test)]
#[path = "../build_id.rs"]
mod build_id;
#[cfg(feature = "cli")]
mod cli;
pub mod config;
pub(crate) mod continuation;
pub mod dictionary;
#[cfg(any(test, feature = "fake-sim"))]
pub(crate) mod fake;
pub(crate) mod files;
pub(crate) mod hash;
pub mod io;
pub mod profile;
pub(crate) mod refine;
pub mod sampling;
pub mod scan;
pub mod search;
pub(crate) mod sizes;
pub mod studies;
/// Sobol sensitivity indices of a scan's outputs (`rtw-scan sensitivity`).
pub use analysis::sensitivity;
pub use analysis::views;

pub use analysis::report::{Z95, failure_clusters, wilson};
/// A scan read whole and verified; its sensitivity indices checked as its own.
pub use analysis::scan_table::{ScanTable, read_indices, read_scan_table};
/// A scan's folder read for a report: the files beside the scan only when they are its own.
pub use analysis::verified::{
    Assignments, ScanFolder, read_assignments, read_scan_folder, read_summary,
};
#[cfg(feature = "cli")]
pub use cli::main;
/// An error as a front end shows it: its chain on one line, each thing said
/// once.
pub use files::error_message;
/// For a front end's signal handler, which ends the process without
/// running destructors: removes every temporary and lock file this process
/// has open, finishing first a set of files being moved into place.
pub use files::remove_live_files;
/// The version every file rtw-scan writes records (`rtw.version`): rows of
/// two versions never end up in one result, and a study never resumes from
/// another version's rows (docs/results-on-disk.md, "Versions").
pub use io::metadata::VERSION;

/// Test builds only (the `fake-sim` feature): with `RTW_SCAN_PAUSE=POINT` in
/// the environment, a run says `paused at POINT` on stderr and waits there a
/// minute, so that the tests and `scripts/fault_inject.sh` can kill it at
/// exactly that step of its end: `manifest` (`.partial` made, its manifest
/// not yet), `merge` (the scan file half written), `merged` (the scan file
/// complete, `.partial` whole), `cleanup` (`.partial` partly removed). A
/// plain build does nothing here. It waits once per process (the merge
/// passes its point once per file).
pub(crate) fn pause_at(point: &str) {
    #[cfg(feature = "fake-sim")]
    if std::env::var("RTW_SCAN_PAUSE").is_ok_and(|p| p == point) {
        static PAUSED: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);
        if PAUSED.swap(true, std::sync::atomic::Ordering::SeqCst) {
            return;
        }
        eprintln!("rtw-scan: paused at {point} (RTW_SCAN_PAUSE)");
        std::thread::sleep(std::time::Duration::from_secs(60));
    }
    #[cfg(not(feature = "fake-sim"))]
    let _ = point;
}
