//! What a finished scan says: outcome shares and their intervals, and the
//! failures clustered.
//!
//! | module | role |
//! |---|---|
//! | `kmeans` | k-means++ with restarts, silhouette |
//! | `clusters` | (a bounded sample of) the failures clustered, named by kind, counted exactly |
//! | [`assignments`] | `cluster --assignments` files: each failure and its cluster |
//! | [`report`] | shares with Wilson intervals, paper numbers, `summary.json`/`summary.md` |
//! | [`scan_table`] | a scan read whole and verified (files, hashes, ids, shard set); its sensitivity indices checked as its own |
//! | [`verified`] | a scan's folder for a report: the scan, and its `summary.json` and assignments file only when they are its own |
//! | [`views`] | a large scan aggregated for the report: coded columns, per-outcome densities, a stratified sample |

pub mod assignments;
pub(crate) mod clusters;
pub(crate) mod kmeans;
pub mod report;
pub mod scan_table;
pub mod verified;
pub mod views;
