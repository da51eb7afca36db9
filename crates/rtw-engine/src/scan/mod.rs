//! Running a scan: sample ids → parameters → rows, in parallel chunks that
//! survive an interruption, optionally as one shard of many.
//!
//! | module | role |
//! |---|---|
//! | [`sample`] | sample id → parameters, from (seed, id) only |
//! | `run` | a run into durable files: its chunks, resume, the merge |
//! | `chunks` | the chunk scheduler: samples in id order, each chunk handed over once its rows are in |
//! | `batch` | [`scan_batch`]: a scan in memory |
//! | `one` | one sample's row (panics caught, wall time) |
//! | `workers` | the worker pool, the thread cap, a worker's sample |
//! | [`single`] | one run in memory: its `--json` row and its trace (the Python package) |
//! | `checkpoint` | the layout of a run's files, the resume manifest, chunk checks, the resume decision |
//! | `partial` | the entries of a run's `.partial`: what rtw-scan made there, and their clean-up |
//! | `shard` | `--shard K/N` id ranges; `merge` checks and joins the parts |
//! | [`progress`] | what watches a scan: the [`Progress`] observer |
//! | `panic` | a sample's panic caught as its message |
//! | `lock` | one writer per result |
//! | `space` | whether a scan's output fits on its disk |

pub(crate) mod batch;
pub mod checkpoint;
pub(crate) mod chunks;
mod context;
#[cfg(test)]
mod fixtures;
pub mod lock;
pub mod one;
pub(crate) mod panic;
pub(crate) mod partial;
pub mod progress;
pub mod run;
pub mod sample;
pub(crate) mod shard;
pub mod single;
pub(crate) mod space;
pub mod workers;

pub use batch::scan_batch;
pub use context::Run;
pub use progress::{Progress, Silent};
