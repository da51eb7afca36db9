//! Running a scan: sample ids → parameters → rows, in parallel chunks that
//! survive an interruption, optionally as one shard of many.
//!
//! | module | role |
//! |---|---|
//! | [`sample`] | sample id → parameters, from (seed, id) only |
//! | `run` | parallel chunks into durable files, resume, one sample's row; [`scan_batch`]: a scan in memory |
//! | [`single`] | one run in memory: its `--json` row and its trace (the Python package) |
//! | `checkpoint` | the layout of a run's files, the resume manifest, chunk checks |
//! | `shard` | `--shard K/N` id ranges; `merge` checks and joins the parts |
//! | `progress` | progress on stderr |
//! | `panic` | a sample's panic caught as its message |
//! | `lock` | one writer per result |
//! | `space` | whether a scan's output fits on its disk |

pub(crate) mod checkpoint;
pub(crate) mod lock;
pub(crate) mod panic;
pub(crate) mod progress;
pub(crate) mod run;
pub mod sample;
pub(crate) mod shard;
pub mod single;
pub(crate) mod space;

pub use run::scan_batch;
