//! Samples added to a finished scan in rounds where the labels of
//! neighbouring samples disagree (docs/refine.md): [`Refine`] says what and
//! how, [`refine()`] runs the rounds not yet complete and writes the
//! combined file.

use anyhow::Result;
use rtw_engine::analysis::report::open_scan;
use std::path::Path;

/// The seed a refinement of the scan in `dir` takes unless told otherwise:
/// the scan's own (read from its verified `samples.parquet`).
pub fn default_seed(dir: &Path) -> Result<u64> {
    Ok(open_scan(&dir.join("samples.parquet"))?.1.seed)
}
