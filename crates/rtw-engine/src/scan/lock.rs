//! One writer per result: a lock file beside it.

use crate::files::{self, Registered};
use anyhow::{Context, Result, bail};
use std::fs::File;
use std::path::{Path, PathBuf};

/// An exclusive lock on writing one result (`DIR/.NAME.lock` for `DIR/NAME`),
/// held by one process at a time; the file names the holder's PID. The
/// operating system releases it when the process ends, however it ends, so a
/// killed run never leaves a stale lock; the file itself is removed on drop.
pub struct Lock {
    _file: File,
    path: PathBuf,
    _live: Registered,
}

impl Lock {
    /// The lock file of the result `dest`.
    pub(crate) fn path_for(dest: &Path) -> PathBuf {
        let name = dest.file_name().and_then(|n| n.to_str()).unwrap_or("out");
        dest.with_file_name(format!(".{name}.lock"))
    }

    /// Takes the lock of the result `dest` of a study that writes (its
    /// folder made first), held until the study's files are in: every
    /// study that writes takes it, so a second writer of one result is
    /// refused, naming the first, where it would replace the first's files
    /// or mix its own among them. `doing` as for `Lock::acquire`.
    pub fn for_result(dest: &Path, doing: &str) -> Result<Self> {
        // A file, a device or a dangling symlink where the folder goes is
        // refused saying what is there, not with the OS's "File exists".
        if let Some(dir) = dest.parent().filter(|d| !d.as_os_str().is_empty()) {
            crate::io::destination::output_dir(dir, "--out", "the study's files")?;
        }
        Self::acquire_then(dest, doing, "")
    }

    /// Takes the lock of `dest`, or says which process holds it; `doing`
    /// says what the holder is doing ("running this scan in DIR").
    pub(crate) fn acquire(dest: &Path, doing: &str) -> Result<Self> {
        Self::acquire_then(
            dest,
            doing,
            "; what it leaves unfinished, --resume finishes",
        )
    }

    /// [`Lock::acquire`], the refusal ending in `then` (what to do after
    /// the holder is stopped).
    fn acquire_then(dest: &Path, doing: &str, then: &str) -> Result<Self> {
        use std::io::Write;
        let path = Self::path_for(dest);
        loop {
            // A symlink or special file where the lock goes is refused, not
            // followed: taking the lock truncates the file it opens.
            files::refuse_special(&path, "the lock file")?;
            let mut options = std::fs::OpenOptions::new();
            options.read(true).write(true).create(true).truncate(false);
            // ... and one made between that check and the open is not
            // followed either.
            #[cfg(unix)]
            std::os::unix::fs::OpenOptionsExt::custom_flags(
                &mut options,
                rustix::fs::OFlags::NOFOLLOW.bits() as i32,
            );
            let mut file = options
                .open(&path)
                .with_context(|| format!("cannot create the lock file {}", path.display()))?;
            if !file.metadata().is_ok_and(|m| m.is_file()) {
                files::refuse_special(&path, "the lock file")?;
                bail!("the lock file {}: is not a regular file", path.display());
            }
            match file.try_lock() {
                Ok(()) => {}
                Err(std::fs::TryLockError::WouldBlock) => {
                    // A PID is a few bytes: read no more than that.
                    let pid = files::read_limited(&path, "lock file", 64)
                        .map(|b| String::from_utf8_lossy(&b).into_owned())
                        .unwrap_or_default();
                    let pid = pid.trim();
                    let pid = if pid.is_empty() { "?" } else { pid };
                    bail!(
                        "another rtw-scan (PID {pid}) is {doing} (it holds {}): wait for it to \
                         finish, or stop it (kill -INT {pid}){then}",
                        path.display()
                    );
                }
                Err(std::fs::TryLockError::Error(e)) => {
                    return Err(e).with_context(|| format!("cannot lock {}", path.display()));
                }
            }
            // The last holder removes the file as it lets go: if that
            // happened between our open and our lock, we hold a file that is
            // no longer at `path`; try again with the one that is.
            if same_file(&file, &path) {
                // What rtw-scan leaves there (after a kill) is a PID; a file
                // holding anything else is not its lock, and is not emptied.
                let mut held = Vec::new();
                std::io::Read::read_to_end(&mut std::io::Read::take(&file, 65), &mut held)?;
                if held.len() > 64
                    || !held
                        .iter()
                        .all(|b| b.is_ascii_digit() || b.is_ascii_whitespace())
                {
                    bail!(
                        "the lock file {} holds something other than a process id: rtw-scan did \
                         not make it; move it away",
                        path.display()
                    );
                }
                file.set_len(0)?;
                std::io::Seek::rewind(&mut file)?;
                writeln!(file, "{}", std::process::id())?;
                return Ok(Self {
                    _file: file,
                    _live: Registered::new(path.clone()),
                    path,
                });
            }
        }
    }
}

impl Drop for Lock {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.path);
    }
}

#[cfg(unix)]
fn same_file(file: &File, path: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    match (file.metadata(), std::fs::metadata(path)) {
        (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
        _ => false,
    }
}

#[cfg(not(unix))]
fn same_file(_: &File, path: &Path) -> bool {
    path.exists()
}
