//! # rtw-studies
//!
//! The studies of the RTW over the scan engine (`rtw-engine`): each a
//! folder with its settings (checked before any work), its run, its files
//! (written together through the engine's file sets) and its summary. The
//! `rtw-scan` command and the Python package call these entries and only
//! parse and print.
//!
//! | module | study | writes |
//! |---|---|---|
//! | [`refine`] | samples added to a finished scan in rounds where neighbouring labels disagree | `refine/round-RRR/`, `refine/samples.parquet` |
//! | [`sensitivity`] | Sobol indices of every output to every uniform input (Saltelli design or given data) | `FILE.parquet`, `FILE.md` |
//! | [`bifurcation`] | one parameter swept, following the attractor on the step map | `FILE.parquet`, `FILE.steps.parquet`, `FILE.md` |
//! | [`continuation`] | a gait's branch in one input (stable and unstable), its bifurcations, period-2 branches, fold and period-doubling curves in two inputs | `FILE.parquet`, `FILE.special.parquet`, `FILE.curve.parquet`, `FILE.segments.json`, `FILE.md` |
//! | [`basin`] | a slice of a gait's basin of attraction | `FILE.parquet`, `FILE.md` |
//! | [`profile`] | a design's slope profile: its gait along φ, each change located by bisection, its stable intervals | `FILE.parquet`, `FILE.md` |
//! | [`search`] | design search over slope profiles with falls a learned constraint; a Pareto front of two objectives | `DIR/search.parquet`, `DIR/designs.parquet`, `DIR/summary.md` |
//! | [`dictionary`] | every Parquet column's unit and meaning, of the engine's files and the studies' (docs/data-dictionary.md) | – |

#![warn(missing_docs)]

pub mod basin;
pub mod bifurcation;
pub mod continuation;
pub mod dictionary;
pub mod profile;
pub mod refine;
pub mod search;
pub mod sensitivity;
