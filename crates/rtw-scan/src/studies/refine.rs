//! Samples added to a finished scan in rounds where the labels of
//! neighbouring samples disagree (docs/refine.md): [`Refine`] says what and
//! how, [`refine()`] runs the rounds not yet complete and writes the
//! combined file.

use crate::analysis::report::open_scan;
use anyhow::Result;
use std::path::Path;

pub use crate::refine::{Refine, RefineStatus, check_budget, refine};

/// The seed a refinement of the scan in `dir` takes unless told otherwise:
/// the scan's own (read from its verified `samples.parquet`).
pub fn default_seed(dir: &Path) -> Result<u64> {
    Ok(open_scan(&dir.join("samples.parquet"))?.1.seed)
}
