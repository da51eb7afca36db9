//! Files that appear whole or not at all: every result is written to a
//! temporary file beside it, synced and renamed into place; the temporary
//! files (and lock files) a process holds are known, so a signal that ends
//! it at once can remove them. Nothing is written through a symlink or over
//! something that is not a plain file (`refuse_special`), and the small
//! files rtw-scan reads whole are read within a size limit (`read_limited`).

use anyhow::{Context, Result, bail};
use std::path::{Path, PathBuf};

/// A temporary file next to `dest` (same directory, so a rename moves it
/// into place atomically), named `.NAME.XXXXXX.tmp`, with the usual
/// permissions (0666 less the umask) rather than tempfile's 0600.
pub(crate) fn temp_file_for(dest: &Path) -> Result<Temp> {
    refuse_special(dest, "")?;
    let file = named_temp_for(dest)?;
    let guard = Registered::new(file.path().to_path_buf());
    Ok(Temp { file, guard })
}

/// A temporary file, known to [`remove_live_files`] until it is dropped or
/// moved into place.
pub(crate) struct Temp {
    pub(crate) file: tempfile::NamedTempFile,
    guard: Registered,
}

impl Temp {
    pub(crate) fn persist(self, dest: &Path) -> Result<()> {
        let Temp { file, guard } = self;
        // Checked again at the rename: what appeared at `dest` meanwhile
        // (a symlink, a FIFO) is not replaced either.
        refuse_special(dest, "")?;
        file.persist(dest)
            .with_context(|| format!("cannot move the finished file to {}", dest.display()))?;
        drop(guard);
        Ok(())
    }
}

/// A set of files that appear together or not at all (a diagram's branch,
/// special-point and curve files, its segments and its summary): each is
/// written whole to its temporary file first (`FileSet::add`,
/// [`FileSet::add_bytes`]), and only once all are, [`FileSet::commit`]
/// renames them into place, one after the other. A signal that comes
/// meanwhile waits for the renames to end ([`remove_live_files`] takes the
/// same lock), so an interrupted command leaves either every file of the set
/// or none of it (an earlier set, if any, stays as it was).
#[derive(Default)]
pub struct FileSet {
    files: Vec<(Temp, PathBuf)>,
}

/// Held while a [`FileSet`] is moved into place.
static COMMIT: std::sync::Mutex<()> = std::sync::Mutex::new(());

impl FileSet {
    /// Adds a finished temporary file, to be moved to `dest`.
    pub(crate) fn add(&mut self, tmp: Temp, dest: &Path) {
        self.files.push((tmp, dest.to_path_buf()));
    }

    /// Writes `bytes` to a temporary file beside `dest` and adds it.
    pub fn add_bytes(&mut self, dest: &Path, bytes: &[u8]) -> Result<()> {
        use std::io::Write;
        let mut tmp = temp_file_for(dest)?;
        tmp.file
            .write_all(bytes)
            .with_context(|| format!("cannot write {}", dest.display()))?;
        tmp.file.as_file().sync_all()?;
        self.add(tmp, dest);
        Ok(())
    }

    /// Moves every file into place, in the order they were added, once
    /// every destination is checked: what appeared at one of them since its
    /// file was written (a symlink, a directory) stops the set before any
    /// file of it is moved, and the temporary files go.
    pub fn commit(self) -> Result<()> {
        let _renaming = COMMIT.lock().unwrap_or_else(|e| e.into_inner());
        for (_, dest) in &self.files {
            refuse_special(dest, "")?;
        }
        for (tmp, dest) in self.files {
            tmp.persist(&dest)?;
        }
        Ok(())
    }
}

/// Files that exist only while a command runs (temporary files, locks):
/// removed by [`remove_live_files`] when a signal ends the process at once.
static LIVE: std::sync::Mutex<Vec<PathBuf>> = std::sync::Mutex::new(Vec::new());

/// Registers a path in [`LIVE`] for as long as it lives.
pub(crate) struct Registered(PathBuf);

impl Registered {
    pub(crate) fn new(path: PathBuf) -> Self {
        if let Ok(mut live) = LIVE.lock() {
            live.push(path.clone());
        }
        Self(path)
    }
}

impl Drop for Registered {
    fn drop(&mut self) {
        if let Ok(mut live) = LIVE.lock()
            && let Some(i) = live.iter().rposition(|p| *p == self.0)
        {
            live.swap_remove(i);
        }
    }
}

/// Removes every temporary and lock file this process has open: called by
/// the signal handler before it exits, since a process ending in
/// `std::process::exit` runs no destructors.
pub fn remove_live_files() {
    // A set of files being moved into place is finished first (renames
    // take microseconds), so that it is never left half in place.
    let _renamed = COMMIT.lock().unwrap_or_else(|e| e.into_inner());
    let live = match LIVE.try_lock() {
        Ok(live) => live.clone(),
        // Held by a thread that will never resume: read it anyway.
        Err(std::sync::TryLockError::Poisoned(p)) => p.into_inner().clone(),
        Err(std::sync::TryLockError::WouldBlock) => {
            std::thread::sleep(std::time::Duration::from_millis(50));
            LIVE.lock().map(|l| l.clone()).unwrap_or_default()
        }
    };
    for p in live {
        let _ = std::fs::remove_file(p);
    }
}

/// Removes the temporary files `.NAME.XXXXXX.tmp` that an earlier, killed
/// writer of `dest` left beside it (never anything else). Call it only while
/// no other process can be writing `dest` (under its `Lock`).
pub fn remove_stray_temps(dest: &Path) -> Result<()> {
    let dir = dest
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let Some(name) = dest.file_name().and_then(|n| n.to_str()) else {
        return Ok(());
    };
    let prefix = format!(".{name}.");
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Ok(());
    };
    for entry in entries.flatten() {
        let n = entry.file_name();
        let n = n.to_string_lossy();
        if n.starts_with(&prefix) && n.ends_with(".tmp") && n.len() == prefix.len() + 10 {
            std::fs::remove_file(entry.path())
                .with_context(|| format!("cannot remove {}", entry.path().display()))?;
        }
    }
    Ok(())
}

fn named_temp_for(dest: &Path) -> Result<tempfile::NamedTempFile> {
    let dir = dest
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = dest.file_name().and_then(|n| n.to_str()).unwrap_or("out");
    let prefix = format!(".{name}.");
    let mut builder = tempfile::Builder::new();
    builder.prefix(&prefix).suffix(".tmp");
    #[cfg(unix)]
    builder.permissions(std::os::unix::fs::PermissionsExt::from_mode(0o666));
    builder
        .tempfile_in(dir)
        .with_context(|| format!("cannot create a file in {}", dir.display()))
}

/// Writes `bytes` to `path` through a temporary file and a rename.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    use std::io::Write;
    let mut tmp = temp_file_for(path)?;
    tmp.file
        .write_all(bytes)
        .with_context(|| format!("cannot write {}", path.display()))?;
    tmp.file.as_file().sync_all()?;
    tmp.persist(path)
}

/// What a non-regular file is, for messages.
pub(crate) fn special_kind(ft: std::fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if ft.is_fifo() {
            return "a FIFO";
        } else if ft.is_char_device() {
            return "a character device";
        } else if ft.is_block_device() {
            return "a block device";
        } else if ft.is_socket() {
            return "a socket";
        }
    }
    if ft.is_dir() {
        "a directory"
    } else {
        "a special file"
    }
}

/// The regular `*.parquet` files in `dir`, sorted by name: the files a
/// reader of a folder looks at (a FIFO or a device named so is not one, and
/// is never opened).
pub fn parquet_files(dir: &Path) -> Result<Vec<PathBuf>> {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(dir)
        .with_context(|| format!("cannot read directory {}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "parquet") && p.is_file())
        .collect();
    paths.sort();
    Ok(paths)
}

/// Refuses to write at `dest` (given by the option `flag`, or `""`) when it
/// is a symlink or exists and is not a regular file (a directory, a device,
/// a FIFO, a socket). rtw-scan replaces only plain files, through a rename
/// in their folder; `--force` never overrides this, since replacing a
/// symlink or a device would destroy what it is, not a result.
pub fn refuse_special(dest: &Path, flag: &str) -> Result<()> {
    let named = if flag.is_empty() {
        dest.display().to_string()
    } else {
        format!("{flag} {}", dest.display())
    };
    match std::fs::symlink_metadata(dest) {
        Ok(m) if m.file_type().is_symlink() => bail!(
            "{named}: is a symlink: rtw-scan never writes through a symlink nor replaces one, \
             not even with --force; choose another file, or remove the link"
        ),
        Ok(m) if !m.is_file() => bail!(
            "{named}: is not a regular file ({}): rtw-scan writes only plain files and never \
             replaces anything else, not even with --force; choose another file",
            special_kind(m.file_type())
        ),
        _ => Ok(()),
    }
}

/// Most bytes of a config or variant file: the committed ones are under
/// 2 kB, and a refinement round's, which stores up to 10⁴ points of six
/// inputs, under 1.5 MB; a larger file is a mistake (`/dev/zero`, a data
/// file).
pub(crate) const CONFIG_MAX_BYTES: u64 = 4_000_000;

/// Reads `path` (`what` names it in messages: `config`, `variant`) whole,
/// refusing a file that is not a regular file (a device or FIFO never
/// ends) or is larger than `limit` bytes, before reading it.
pub(crate) fn read_limited(path: &Path, what: &str, limit: u64) -> Result<Vec<u8>> {
    use std::io::Read;
    let cannot = || format!("cannot read {what} {}", path.display());
    // Told from the path first: opening a FIFO would wait for a writer.
    let meta = std::fs::metadata(path).with_context(cannot)?;
    let too_big = |len: u64| {
        anyhow::anyhow!(
            "cannot read {what} {}: it is {} ({len} bytes), and a {what} may be at most {}",
            path.display(),
            crate::sizes::human_bytes(len as f64),
            crate::sizes::human_bytes(limit as f64)
        )
    };
    if !meta.is_file() {
        bail!(
            "cannot read {what} {}: it is not a regular file ({}), and a {what} is read only \
             from a plain file",
            path.display(),
            special_kind(meta.file_type())
        );
    }
    if meta.len() > limit {
        return Err(too_big(meta.len()));
    }
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .with_context(cannot)?
        .take(limit + 1)
        .read_to_end(&mut bytes)
        .with_context(cannot)?;
    // It grew while we read it.
    if bytes.len() as u64 > limit {
        return Err(too_big(bytes.len() as u64));
    }
    Ok(bytes)
}

/// An error as one line, each cause after the context that wraps it, as
/// `{:#}` writes it but saying each thing once: a cause whose text the link
/// before it already holds is left out (Parquet's `External: No space left
/// on device (os error 28)` shows its source, the OS's error, which `{:#}`
/// shows again), and so is a context whose text the error it wraps already
/// holds (a path given as the context of an error that starts with it).
/// What the CLI prints after `error:` and what Python raises.
pub fn error_message(e: &anyhow::Error) -> String {
    let links: Vec<String> = e.chain().map(|c| c.to_string()).collect();
    let mut kept: Vec<&str> = Vec::new();
    for (i, link) in links.iter().enumerate() {
        let said_before = kept.last().is_some_and(|k| k.contains(link.as_str()));
        let said_after = links.get(i + 1).is_some_and(|n| n.contains(link.as_str()));
        if !said_before && !said_after {
            kept.push(link);
        }
    }
    kept.join(": ")
}

#[cfg(test)]
mod tests {
    use super::{FileSet, error_message};

    /// A set whose later file can no longer go where it is to go (a
    /// directory appeared there after its file was written) moves none of
    /// its files: the earlier file of the set is not replaced ahead of the
    /// refusal.
    #[test]
    fn a_set_with_one_refused_destination_moves_none_of_its_files() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a.json"), dir.path().join("b.md"));
        std::fs::write(&a, "earlier").unwrap();
        let mut set = FileSet::default();
        set.add_bytes(&a, b"new").unwrap();
        set.add_bytes(&b, b"new").unwrap();
        std::fs::create_dir(&b).unwrap();
        let e = set.commit().unwrap_err().to_string();
        assert!(
            e.contains("b.md") && e.contains("not a regular file"),
            "{e}"
        );
        assert_eq!(std::fs::read_to_string(&a).unwrap(), "earlier");
        let left: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .filter(|n| n.ends_with(".tmp"))
            .collect();
        assert!(left.is_empty(), "temporary files left: {left:?}");
    }

    /// A disk-full error says the OS's message once: Parquet's error that
    /// wraps it also shows it, and is shown with its source.
    #[test]
    fn a_wrapped_os_error_is_said_once() {
        let os = std::io::Error::from_raw_os_error(28);
        let e = anyhow::Error::new(parquet::errors::ParquetError::External(Box::new(os)))
            .context("closing t.parquet");
        let m = error_message(&e);
        assert_eq!(m.matches("No space left on device").count(), 1, "{m}");
        assert!(m.starts_with("closing t.parquet: "), "{m}");
    }

    /// A context that the error it wraps already names (a path) is not
    /// said again; one that adds something is kept.
    #[test]
    fn a_context_the_error_already_names_is_said_once() {
        let e = anyhow::anyhow!("s/samples.parquet: column `wall_time_s`, row 2: -1 is invalid")
            .context("s/samples.parquet");
        assert_eq!(
            error_message(&e),
            "s/samples.parquet: column `wall_time_s`, row 2: -1 is invalid"
        );
        let e = anyhow::anyhow!("No such file or directory").context("cannot open c.toml");
        assert_eq!(
            error_message(&e),
            "cannot open c.toml: No such file or directory"
        );
    }
}
