//! Whether a scan's output fits on its disk: estimated at the start, so a
//! scan that cannot finish (10¹² samples, about 200 TB) is refused at once
//! rather than filling the disk after months.

use crate::sizes::human_bytes;
use anyhow::{Context, Result, bail};
use std::path::Path;

/// Bytes per row of a finished scan file: `results/paper/samples.parquet`
/// is 214 769 bytes for its 1000 rows (zstd, row groups of up to
/// `MAX_ROW_GROUP_ROWS`), rounded up. The columns are the same for every
/// scan; their values compress about alike.
pub(crate) const BYTES_PER_ROW: u64 = 213;

/// Bytes free to an unprivileged writer on the filesystem holding `dir` (or
/// its nearest existing ancestor, when `dir` is still to be made); `None`
/// where that cannot be told.
fn free_bytes(dir: &Path) -> Option<u64> {
    let mut at = dir;
    while !at.exists() {
        at = at.parent().filter(|p| !p.as_os_str().is_empty())?;
    }
    #[cfg(unix)]
    {
        let s = rustix::fs::statvfs(at).ok()?;
        Some(s.f_bavail.saturating_mul(s.f_frsize))
    }
    #[cfg(not(unix))]
    {
        let _ = at;
        None
    }
}

/// Bytes of the files in `partial` (the chunks a resumed run keeps): they
/// are part of what the run needs, already on the disk.
fn bytes_kept(partial: &Path) -> Result<u64> {
    let Ok(entries) = std::fs::read_dir(partial) else {
        return Ok(0);
    };
    let mut n = 0u64;
    for e in entries {
        let e = e.with_context(|| format!("cannot read {}", partial.display()))?;
        n = n.saturating_add(e.metadata().map_or(0, |m| m.len()));
    }
    Ok(n)
}

/// Refuses a run of `rows` rows into `out` whose estimated peak use of the
/// disk exceeds the space free on it: the chunks in `partial` and the
/// finished file exist side by side while the file is written, so the peak
/// is twice the file ([`BYTES_PER_ROW`] per row); the chunks `partial`
/// already holds count as free. `--force` starts it anyway.
pub(crate) fn check_free_space(rows: u64, out: &Path, partial: &Path) -> Result<()> {
    let Some(free) = free_bytes(out) else {
        return Ok(());
    };
    let file = rows.saturating_mul(BYTES_PER_ROW);
    let peak = file.saturating_mul(2);
    let available = free.saturating_add(bytes_kept(partial)?);
    if peak > available {
        bail!(
            "this scan needs about {} on disk ({rows} rows × {BYTES_PER_ROW} bytes, the bytes per row \
             of results/paper/samples.parquet, twice: its chunks and the finished file exist \
             together while it is written), but the filesystem of {} has {} free: choose an --out on \
             a larger disk, fewer samples, or --shard; pass --force to start anyway",
            human_bytes(peak as f64),
            out.display(),
            human_bytes(free as f64)
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bytes_per_row_is_that_of_the_committed_paper_scan() {
        let paper =
            Path::new(env!("CARGO_MANIFEST_DIR")).join("../../results/paper/samples.parquet");
        let size = std::fs::metadata(&paper).unwrap().len();
        let rows = crate::io::parquet::open(&paper, 1).unwrap().rows as u64;
        assert_eq!(size.div_ceil(rows), BYTES_PER_ROW);
    }

    #[test]
    fn a_scan_larger_than_the_disk_is_refused_and_a_small_one_is_not() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("not/yet/made");
        check_free_space(1000, &out, &out.join(".partial")).unwrap();
        let e = check_free_space(u64::MAX / 4, &out, &out.join(".partial")).unwrap_err();
        let e = format!("{e:#}");
        assert!(e.contains("free") && e.contains("--force"), "{e}");
    }
}
