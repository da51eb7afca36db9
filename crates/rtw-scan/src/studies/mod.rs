//! The studies: each a library entry point that the command line (and
//! Python) calls, which parses and prints only. A study takes checked
//! settings, a progress observer ([`crate::scan::Progress`]) or a callback,
//! and a stop flag where it runs long; it checks its outputs before any
//! work, and writes its files atomically, refusing to replace a file it
//! did not make.
//!
//! | study | entry | writes |
//! |---|---|---|
//! | a scan | [`scan::run_scan`], [`scan::check_outputs`] before it, [`scan::write_summary`] after it | `samples.parquet` (or `part-K.parquet`), `summary.json`, `summary.md` |
//! | a sharded scan joined | [`scan::merge`], then [`scan::write_summary`] | `samples.parquet`, `summary.json`, `summary.md` |
//! | a scan's summary, its failure clusters | [`summary::summary_to_files`], [`summary::cluster`] | `summary.json`, `summary.md`; the assignments file |
//! | refinement | [`refine::refine`] | `refine/round-RRR/`, `refine/samples.parquet` |
//! | a bifurcation sweep | [`bifurcation::run_to_files`] | `FILE.parquet`, `FILE.steps.parquet`, `FILE.md` |
//! | continuation | [`continuation::run_to_files`] | `FILE.parquet`, `FILE.special.parquet`, `FILE.curve.parquet`, `FILE.segments.json`, `FILE.md` |
//!
//! The studies of their own folder have their entry there: sensitivity
//! ([`crate::sensitivity`]), a basin slice ([`crate::basin::run_to_files`]),
//! a slope profile ([`crate::profile::run_to_files`]) and design search
//! ([`crate::search`]).

pub mod bifurcation;
pub mod continuation;
pub mod refine;
pub mod scan;
pub mod summary;
