//! The refusal to write one kind of file over another (or over a command's
//! own input), unless `--force`.

use crate::io::files;
use crate::io::metadata::FileKind;
use crate::io::parquet::open;
use anyhow::{Result, bail};
use std::path::{Path, PathBuf};

/// A file beside a command's main output `out`: `NAME.WHAT.parquet`
/// (`bifurcation`'s steps file, `continuation`'s special-point and curve
/// files).
pub(crate) fn companion(out: &Path, what: &str) -> PathBuf {
    let stem = out
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    out.with_file_name(format!("{stem}.{what}.parquet"))
}

/// The Markdown summary beside a command's main output `out`: `NAME.md`.
pub(crate) fn summary_path(out: &Path) -> PathBuf {
    out.with_extension("md")
}

/// Refuses, unless `force`, to write a command's outputs: its Parquet
/// `files` (each with the flag that names it in messages; the main output
/// `out` first) over files that are not of `kind` ([`check_destination`]),
/// or its summary [`summary_path`] over an `.md` that is not the summary of
/// such output at `out` (one without `out` beside it); then removes stray
/// temporary files of all of them. `what` names the output in messages
/// (`a sweep`, `a diagram`).
pub(crate) fn check_outputs(
    out: &Path,
    files_: &[(PathBuf, &str)],
    kind: FileKind,
    what: &str,
    force: bool,
) -> Result<()> {
    for (f, flag) in files_ {
        check_destination(f, kind, &[], flag, force)?;
    }
    let md = summary_path(out);
    if !force && md.exists() && !out.exists() {
        bail!(
            "--out {}: {} exists and is not the summary of {what} there: refusing to replace it; \
             choose another file, or pass --force",
            out.display(),
            md.display()
        );
    }
    for f in files_.iter().map(|(f, _)| f).chain([&md]) {
        files::remove_stray_temps(f)?;
    }
    Ok(())
}

/// Refuses, unless `force`, to write a `kind` file at `dest` (given by the
/// option `flag`) when `dest` is one of the command's `inputs`, or exists and
/// is not a file of the same kind (another kind of rtw-scan file, another
/// Parquet file, or not a Parquet file at all). A file of the same kind is
/// the command's own earlier output and may be replaced.
pub(crate) fn check_destination(
    dest: &Path,
    kind: FileKind,
    inputs: &[&Path],
    flag: &str,
    force: bool,
) -> Result<()> {
    if force || !dest.exists() {
        return Ok(());
    }
    let shown = dest.display();
    let same = |a: &Path| match (a.canonicalize(), dest.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    };
    if let Some(input) = inputs.iter().find(|i| same(i)) {
        bail!(
            "{flag} {shown}: that is its own input {}: writing there would replace it; choose \
             another file, or pass --force",
            input.display()
        );
    }
    if dest.is_dir() {
        bail!("{flag} {shown}: is a directory");
    }
    let found = match open(dest, 1) {
        Err(_) => "a file that is not a Parquet file".to_string(),
        Ok(input) => match FileKind::of(&input.metadata) {
            Some(k) if k == kind => return Ok(()),
            Some(k) => format!("{} (from its metadata)", k.describe()),
            None => "a Parquet file rtw-scan did not write".to_string(),
        },
    };
    bail!(
        "{flag} {shown}: holds {found}, not {}: refusing to write over it; choose another file, \
         or pass --force to replace it",
        kind.describe()
    )
}
