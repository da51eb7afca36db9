//! The refusal to write one kind of file over another (or over a command's
//! own input), unless `--force`.

use crate::io::metadata::FileKind;
use crate::io::parquet::open;
use anyhow::{Result, bail};
use std::path::Path;

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
