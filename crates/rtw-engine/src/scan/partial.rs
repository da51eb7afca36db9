//! What is in a run's `.partial` directory: its manifest, its finished
//! chunks, the temporary files of a killed writer, and entries rtw-scan did
//! not make, which it never removes; and the clean-ups that keep to that.

use anyhow::{Context, Result};
use std::path::Path;

/// `N` of a file named `chunk-NNNNN.parquet`.
fn chunk_number(name: &str) -> Option<u64> {
    name.strip_prefix("chunk-")
        .and_then(|n| n.strip_suffix(".parquet"))
        .filter(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()))
        .and_then(|n| n.parse().ok())
}

/// What an entry of `.partial` is.
#[derive(Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Entry {
    Manifest,
    Chunk(u64),
    /// The temporary file of a killed writer of the manifest or a chunk
    /// (`.NAME.XXXXXX.tmp`, [`crate::files`]).
    Temp,
    /// Anything else: not made by rtw-scan, so never removed by it.
    Unknown,
}

/// What the entry `name` of `.partial` is; only regular files are rtw-scan's
/// (a directory or a symlink under a chunk's name is someone else's).
fn entry_kind(name: &str, is_file: bool) -> Entry {
    let own = |n: &str| n == "manifest.json" || chunk_number(n).is_some();
    let temp = name
        .strip_prefix('.')
        .and_then(|n| n.strip_suffix(".tmp"))
        .and_then(|n| n.rsplit_once('.'))
        .is_some_and(|(n, random)| random.len() == 6 && own(n));
    match (is_file, chunk_number(name)) {
        (false, _) => Entry::Unknown,
        (true, Some(c)) => Entry::Chunk(c),
        _ if name == "manifest.json" => Entry::Manifest,
        _ if temp => Entry::Temp,
        _ => Entry::Unknown,
    }
}

/// The entries of `partial` with their kinds, sorted by name.
fn entries(partial: &Path) -> Result<Vec<(String, Entry)>> {
    let mut found = Vec::new();
    for entry in
        std::fs::read_dir(partial).with_context(|| format!("cannot read {}", partial.display()))?
    {
        let entry = entry?;
        let name = entry.file_name().to_string_lossy().into_owned();
        let kind = entry_kind(&name, entry.file_type()?.is_file());
        found.push((name, kind));
    }
    found.sort();
    Ok(found)
}

/// The chunk numbers of the `chunk-NNNNN.parquet` files in `partial`.
pub(crate) fn chunks_on_disk(partial: &Path) -> Result<Vec<u64>> {
    let mut found: Vec<u64> = entries(partial)?
        .into_iter()
        .filter_map(|(_, kind)| match kind {
            Entry::Chunk(c) => Some(c),
            _ => None,
        })
        .collect();
    found.sort_unstable();
    Ok(found)
}

/// Removes the temporary files a killed run left in `partial` (its own
/// only), and returns the names of the entries rtw-scan did not make, which
/// it leaves alone.
pub(crate) fn remove_stray_temps(partial: &Path) -> Result<Vec<String>> {
    let mut unknown = Vec::new();
    for (name, kind) in entries(partial)? {
        match kind {
            Entry::Temp => remove(&partial.join(&name))?,
            Entry::Unknown => unknown.push(name),
            Entry::Manifest | Entry::Chunk(_) => {}
        }
    }
    Ok(unknown)
}

/// Removes what rtw-scan made in `partial` (chunks first, the manifest last,
/// so that a kill meanwhile leaves a state a resume recognises) and then the
/// directory, unless it holds entries rtw-scan did not make: their names are
/// returned, and they stay where they are.
pub(crate) fn remove_partial(partial: &Path) -> Result<Vec<String>> {
    let found = entries(partial)?;
    let mut unknown = Vec::new();
    let mut removed = 0;
    for (name, kind) in found.iter().filter(|(_, k)| *k != Entry::Manifest) {
        if *kind == Entry::Unknown {
            unknown.push(name.clone());
            continue;
        }
        remove(&partial.join(name))?;
        removed += 1;
        if removed == 1 {
            crate::pause_at("cleanup");
        }
    }
    if found.iter().any(|(_, k)| *k == Entry::Manifest) {
        remove(&partial.join("manifest.json"))?;
    }
    if unknown.is_empty() {
        std::fs::remove_dir(partial)
            .with_context(|| format!("cannot remove {}", partial.display()))?;
    }
    Ok(unknown)
}

fn remove(path: &Path) -> Result<()> {
    std::fs::remove_file(path).with_context(|| format!("cannot remove {}", path.display()))
}
