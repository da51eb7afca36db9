//! # rtw-scan
//!
//! Seeded, parallel parameter scans of the RTW model (`rtw-model`), streamed
//! to Parquet, with outcome statistics and failure clustering. The binary
//! `rtw-scan` is a thin shell over [`cli::main`].
//!
//! A scan flows through the modules in this order:
//!
//! | module | role |
//! |---|---|
//! | [`config`] | TOML config → validated [`config::ScanConfig`] (errors name the key) |
//! | [`sample`] | sample id → parameters, from (seed, id) only |
//! | [`run`] | parallel chunks, durable parts, resume, panics → `diverged` rows |
//! | [`shard`] | `--shard K/N` id ranges; `merge` checks and joins the parts |
//! | [`output`] | the row schema; Parquet, JSON and text forms; trace files |
//! | [`dictionary`] | every Parquet column's unit and meaning (field metadata, docs/data-dictionary.md) |
//! | [`cluster`] | k-means++ of (a bounded sample of) the failures, silhouette, naming by kind |
//! | [`report`] | shares with Wilson intervals, paper numbers, summary files |
//! | [`bifurcation`] | one parameter swept with continuation on the step map: `bifurcation` |
//! | [`cli`] | the `run`, `merge`, `simulate`, `bifurcation`, `cluster`, `summary` subcommands |
//! | [`fake`] | a deterministic stand-in simulator for testing the machinery |
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

pub mod bifurcation;
pub mod cli;
pub mod cluster;
pub mod config;
pub mod dictionary;
pub mod fake;
pub mod output;
pub mod report;
pub mod run;
pub mod sample;
pub mod shard;
