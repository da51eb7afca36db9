//! # rtw-engine
//!
//! The scan engine of the RTW model (`rtw-model`), and the guarded path
//! every study writes through: configs read and checked, seeded parallel
//! scans streamed to Parquet with resume and shards, locks, files that
//! appear together or not at all, and what a finished scan says (outcome
//! shares with intervals, failure clusters). It knows no terminal: what
//! watches a run ([`scan::Progress`]) and what stops it (a stop flag) are
//! passed in. The studies built on it are `rtw-studies`'; the `rtw-scan`
//! command and the Python package are faces over both.
//!
//! The folders are the layers, each using only the ones above it in this
//! table (and `hash`, the fixed hash functions):
//!
//! | module | role |
//! |---|---|
//! | [`files`] | the file system's primitives: temporary files renamed into place, file sets written together, bounded reads, cleanup on a signal |
//! | [`sizes`] | byte counts read from text (`2GB`) and written for people |
//! | [`sampling`] | the sampling designs: draw → unit-cube point (random, Sobol, Halton, LHS, grid, Saltelli) |
//! | [`config`] | TOML → validated [`config::ScanConfig`]: schema, variant and `--set` layers, the parameter vocabulary, hashing |
//! | [`io`] | column tables; Parquet written atomically with a content hash and read back checked; traces, assignments; the destination checks |
//! | [`scan`] | sample ids → parameters → rows: parallel chunks, resume, shards, progress, locks, the worker pool |
//! | [`analysis`] | k-means of the failures, shares with Wilson intervals, summary files, a scan read whole and verified |
//! | [`entry`] | the scan's entry points: a scan and its merge, its summary and clusters |
//!
//! The stand-in simulator `fake` and the test pauses are in every build,
//! hidden and inert: the test build of the command (`rtw-scan-test`) is
//! the one that reaches them.

#![warn(missing_docs)]

pub mod analysis;
#[cfg(test)]
#[path = "../build_id.rs"]
mod build_id;
pub mod config;
pub mod entry;
// The stand-in simulator of the tests, compiled in every build (a feature
// only the tests turned on made `cargo test` build this crate and the
// studies a second time): reached only through the hidden `--fake-sim` of
// the test build of the command, `rtw-scan-test`.
#[doc(hidden)]
pub mod fake;
pub mod files;
pub mod hash;
pub mod io;
pub mod sampling;
pub mod scan;
pub mod sizes;
pub use analysis::views;

pub use analysis::report::{Z95, failure_clusters, wilson};
/// A scan read whole and verified; its sensitivity indices checked as its own.
pub use analysis::scan_table::{ScanTable, read_indices, read_scan_table};
/// A scan's folder read for a report: the files beside the scan only when they are its own.
pub use analysis::verified::{
    Assignments, ScanFolder, read_assignments, read_scan_folder, read_summary,
};
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

/// Test builds only (once [`allow_test_pauses`] has run, as `rtw-scan-test`
/// does first): with `RTW_SCAN_PAUSE=POINT` in the environment, a run says
/// `paused at POINT` on stderr and waits there a minute, so that the tests and `scripts/fault_inject.sh` can kill it at
/// exactly that step of its end: `manifest` (`.partial` made, its manifest
/// not yet), `merge` (the scan file half written), `merged` (the scan file
/// complete, `.partial` whole), `cleanup` (`.partial` partly removed).
/// Otherwise (`rtw-scan`, Python) it does nothing here. It waits once per process (the merge
/// passes its point once per file).
pub fn pause_at(point: &str) {
    pause_unless(point, &std::sync::atomic::AtomicBool::new(false));
}

/// [`pause_at`] for a study that takes a stop flag: the wait ends as soon as
/// `stop` is set, so that a test interrupting the study there sees it stop
/// as it would anywhere else.
pub fn pause_unless(point: &str, stop: &std::sync::atomic::AtomicBool) {
    use std::sync::atomic::Ordering;
    if TEST_PAUSES.load(Ordering::SeqCst)
        && std::env::var("RTW_SCAN_PAUSE").is_ok_and(|p| p == point)
    {
        static PAUSED: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);
        if PAUSED.swap(true, Ordering::SeqCst) {
            return;
        }
        eprintln!("rtw-scan: paused at {point} (RTW_SCAN_PAUSE)");
        let t0 = std::time::Instant::now();
        while t0.elapsed() < std::time::Duration::from_secs(60) && !stop.load(Ordering::SeqCst) {
            std::thread::sleep(std::time::Duration::from_millis(20));
        }
    }
}

static TEST_PAUSES: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// Lets `RTW_SCAN_PAUSE` pause this process ([`pause_at`]): called first by
/// the test build of the command, `rtw-scan-test`, and by nothing else.
#[doc(hidden)]
pub fn allow_test_pauses() {
    TEST_PAUSES.store(true, std::sync::atomic::Ordering::SeqCst);
}

#[cfg(test)]
mod tests {
    use std::time::{Duration, Instant};

    #[test]
    fn the_pauses_are_inert_until_the_test_build_of_the_command_allows_them() {
        // They are compiled into every build: in `rtw-scan` and Python a
        // stray RTW_SCAN_PAUSE must not stop a run for a minute.
        // SAFETY: no other test of this crate reads or sets RTW_SCAN_PAUSE.
        unsafe { std::env::set_var("RTW_SCAN_PAUSE", "a-point-of-this-test") };
        let t0 = Instant::now();
        super::pause_at("a-point-of-this-test");
        assert!(t0.elapsed() < Duration::from_secs(1), "{:?}", t0.elapsed());
        // Allowed, it waits there until its stop flag is set.
        super::allow_test_pauses();
        let stop = std::sync::atomic::AtomicBool::new(false);
        let t0 = Instant::now();
        std::thread::scope(|s| {
            s.spawn(|| {
                std::thread::sleep(Duration::from_millis(300));
                stop.store(true, std::sync::atomic::Ordering::SeqCst);
            });
            super::pause_unless("a-point-of-this-test", &stop);
        });
        assert!(
            t0.elapsed() >= Duration::from_millis(300),
            "{:?}",
            t0.elapsed()
        );
    }
}
