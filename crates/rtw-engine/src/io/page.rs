//! The HTML pages a report makes (a scan's page, a design search's),
//! written as every file rtw writes: never through a symlink nor over
//! something that is not a plain file (not even with `force`), never over a
//! file rtw did not make (unless `force`), and atomically, so a failed write
//! leaves the old page whole. A page rtw made is told by the marker in its
//! `<head>`.

use crate::files;
use anyhow::{Context, Result, bail};
use std::io::Read;
use std::path::Path;

/// The marker every page carries in its `<head>`, by which a page rtw made
/// is told from a file someone else made.
pub const GENERATOR: &str = r#"<meta name="generator" content="rtw report">"#;

/// How much of an existing file is read to find [`GENERATOR`]: the pages
/// put it in the first lines of their `<head>`.
const MARKER_BYTES: u64 = 4096;

/// The folder a page was to go in does not exist (Python raises it as
/// `FileNotFoundError`).
#[derive(Debug)]
pub struct MissingFolder(pub String);

impl std::fmt::Display for MissingFolder {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for MissingFolder {}

/// Refuses `dest` (named by `flag` in messages) as the place of a page:
/// always a symlink or something that is not a regular file; unless
/// `force`, a file that is not a page rtw made; and a folder that does not
/// exist ([`MissingFolder`]).
pub fn check_page(dest: &Path, flag: &str, force: bool) -> Result<()> {
    files::refuse_special(dest, flag)?;
    if !force && dest.exists() && !made_by_rtw(dest, flag)? {
        bail!(
            "{flag}: {} exists and is not an rtw report: choose another file or pass --force \
             (force=True)",
            dest.display()
        );
    }
    let dir = dest
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    if !dir.is_dir() {
        return Err(MissingFolder(format!(
            "{flag}: the folder {} does not exist",
            dir.display()
        ))
        .into());
    }
    Ok(())
}

/// Writes the page `html` at `dest`, checked first as [`check_page`]
/// checks it (again: a file may have appeared since), through a temporary
/// file beside it renamed into place.
pub fn write_page(dest: &Path, html: &str, flag: &str, force: bool) -> Result<()> {
    check_page(dest, flag, force)?;
    files::write_atomic(dest, html.as_bytes())
        .with_context(|| format!("{flag}: cannot write {}", dest.display()))
}

/// Whether the file at `dest` begins as a page rtw made.
fn made_by_rtw(dest: &Path, flag: &str) -> Result<bool> {
    let mut head = Vec::new();
    std::fs::File::open(dest)
        .and_then(|f| f.take(MARKER_BYTES).read_to_end(&mut head))
        .with_context(|| format!("{flag}: cannot read {}", dest.display()))?;
    let marker = GENERATOR.as_bytes();
    Ok(head.windows(marker.len()).any(|w| w == marker))
}
