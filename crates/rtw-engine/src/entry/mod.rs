//! The scan's own entry points, which the command line (and Python) call
//! and which take checked settings, a progress observer
//! ([`crate::scan::Progress`]) and a stop flag; each checks its outputs
//! before any work and writes its files together, atomically, refusing to
//! replace a file it did not make. The other studies are rtw-studies'.
//!
//! | study | entry | writes |
//! |---|---|---|
//! | a scan | [`scan::run_scan`], [`scan::check_outputs`] before it, [`scan::write_summary`] after it | `samples.parquet` (or `part-K.parquet`), `summary.json`, `summary.md` |
//! | a sharded scan joined | [`scan::merge`], then [`scan::write_summary`] | `samples.parquet`, `summary.json`, `summary.md` |
//! | a scan's summary, its failure clusters | [`summary::summary_to_files`], [`summary::cluster`] | `summary.json`, `summary.md`; the assignments file |

pub mod scan;
pub mod summary;
