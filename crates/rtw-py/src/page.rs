//! The HTML pages `rtw.report` makes (a scan's page, a design search's),
//! written as rtw-scan writes its files: never through a symlink nor over
//! something that is not a plain file (not even with `force`), never over a
//! file rtw did not make (unless `force`), and atomically, through a
//! temporary file beside the page renamed into place, so a failed write
//! leaves the old page whole.
//!
//! rtw-scan keeps its destination checks and its atomic write private to
//! the crate (`files::refuse_special`, `files::write_atomic`, and no check
//! for a file that is not Parquet): [`refuse_special`] and [`write_atomic`]
//! here follow them, and go once rtw-scan exposes them.

use pyo3::exceptions::{PyFileNotFoundError, PyValueError};
use pyo3::prelude::*;
use std::io::{Read, Write};
use std::path::{Path, PathBuf};

/// The marker every page carries in its `<head>`, by which a page rtw made
/// is told from a file someone else made.
pub(crate) const GENERATOR: &str = r#"<meta name="generator" content="rtw report">"#;

/// How much of an existing file is read to find [`GENERATOR`]: the pages
/// put it in the first lines of their `<head>`.
const MARKER_BYTES: u64 = 4096;

/// Refuses `path` (named `out` in messages) as the place of a page: always a
/// symlink or something that is not a regular file; unless `force`, a file
/// that is not a page rtw made; and a folder that does not exist
/// (`FileNotFoundError`).
#[pyfunction]
pub(crate) fn check_page(path: PathBuf, force: bool) -> PyResult<()> {
    refuse_special(&path)?;
    if !force && path.exists() && !made_by_rtw(&path)? {
        return Err(PyValueError::new_err(format!(
            "out: {} exists and is not an rtw report: choose another file or pass --force (force=True)",
            path.display()
        )));
    }
    let dir = folder(&path);
    if !dir.is_dir() {
        return Err(PyFileNotFoundError::new_err(format!(
            "out: the folder {} does not exist",
            dir.display()
        )));
    }
    Ok(())
}

/// Writes the page `html` at `path`, checked first as [`check_page`] checks
/// it (again: a file may have appeared since), atomically.
#[pyfunction]
pub(crate) fn write_page(py: Python<'_>, path: PathBuf, html: &str, force: bool) -> PyResult<()> {
    check_page(path.clone(), force)?;
    py.detach(|| write_atomic(&path, html.as_bytes()))
}

/// The folder a page goes in (`.` for a bare file name).
fn folder(path: &Path) -> &Path {
    path.parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."))
}

/// Whether the file at `path` begins as a page rtw made.
fn made_by_rtw(path: &Path) -> PyResult<bool> {
    let mut head = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(MARKER_BYTES).read_to_end(&mut head))
        .map_err(|e| PyValueError::new_err(format!("out: cannot read {}: {e}", path.display())))?;
    let marker = GENERATOR.as_bytes();
    Ok(head.windows(marker.len()).any(|w| w == marker))
}

/// Refuses `path` when it is a symlink or exists and is not a regular file
/// (a directory, a device, a FIFO): replacing one would destroy what it is,
/// not a page, so `force` never overrides this.
fn refuse_special(path: &Path) -> PyResult<()> {
    let shown = path.display();
    match std::fs::symlink_metadata(path) {
        Ok(m) if m.file_type().is_symlink() => Err(PyValueError::new_err(format!(
            "out: {shown} is a symlink: rtw never writes through a symlink nor replaces one, \
             not even with --force (force=True); choose another file, or remove the link"
        ))),
        Ok(m) if !m.is_file() => Err(PyValueError::new_err(format!(
            "out: {shown} is not a regular file ({}): rtw writes only plain files and never \
             replaces anything else, not even with --force (force=True); choose another file",
            if m.is_dir() {
                "a directory"
            } else {
                "a special file"
            }
        ))),
        _ => Ok(()),
    }
}

/// Writes `bytes` to a temporary file `.NAME.XXXXXX.tmp` beside `path`
/// (0666 less the umask, as any file the user makes), synced, then renamed
/// over `path`: the page is the old one or the new one, never a part. On an
/// error the temporary file is removed.
fn write_atomic(path: &Path, bytes: &[u8]) -> PyResult<()> {
    let cannot = |e: std::io::Error| {
        PyValueError::new_err(format!("out: cannot write {}: {e}", path.display()))
    };
    let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("page");
    let prefix = format!(".{name}.");
    let mut builder = tempfile::Builder::new();
    builder.prefix(&prefix).suffix(".tmp");
    #[cfg(unix)]
    builder.permissions(std::os::unix::fs::PermissionsExt::from_mode(0o666));
    let mut tmp = builder.tempfile_in(folder(path)).map_err(cannot)?;
    tmp.write_all(bytes).map_err(cannot)?;
    tmp.as_file().sync_all().map_err(cannot)?;
    // Checked again at the rename: what appeared at `path` meanwhile (a
    // symlink, a FIFO) is not replaced either.
    refuse_special(path)?;
    tmp.persist(path).map_err(|e| cannot(e.error))?;
    Ok(())
}
