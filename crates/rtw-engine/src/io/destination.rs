//! The refusal to write one kind of file over another (or over a command's
//! own input), unless `--force`.

use crate::files;
use crate::io::metadata::FileKind;
use crate::io::parquet::open;
use anyhow::{Context, Result, bail};
use arrow_schema::{Schema, SchemaRef};
use std::path::{Path, PathBuf};

/// A file beside a command's main output `out`: `NAME.WHAT.parquet`
/// (`bifurcation`'s steps file, `continuation`'s special-point and curve
/// files).
pub fn companion(out: &Path, what: &str) -> PathBuf {
    let stem = out
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    out.with_file_name(format!("{stem}.{what}.parquet"))
}

/// The Markdown summary beside a command's main output `out`: `NAME.md`.
pub fn summary_path(out: &Path) -> PathBuf {
    out.with_extension("md")
}

/// One output file of a command: its path, the flag that names it in
/// messages, and the columns a file in its place must have to be this
/// command's own earlier output (a sweep's per-value and steps files are of
/// one kind, but neither may replace the other).
pub struct Output<'a> {
    /// Where it goes.
    pub path: PathBuf,
    /// The flag (or argument) that names it, for messages.
    pub flag: &'a str,
    /// The columns it has, which a file there must have to be its own.
    pub schema: SchemaRef,
}

/// Refuses to write a command's outputs: always over a symlink or a file
/// that is not a regular file; unless `force`, its Parquet `files_` (the
/// main output `out` first) over files that are not its own earlier output
/// ([`check_destination`], each with its columns), or its summary
/// [`summary_path`] over an `.md` rtw-scan did not write (`ours` tells one
/// from its first line, which this command writes in its own form); then
/// removes stray temporary files of all of them. `what` names the output in
/// messages (`a sweep`, `a diagram`).
pub fn check_outputs(
    out: &Path,
    files_: &[Output],
    kind: FileKind,
    what: &str,
    ours: fn(&str) -> bool,
    force: bool,
) -> Result<()> {
    for f in files_ {
        check_destination_of(&f.path, kind, Some(&f.schema), &[], f.flag, force)?;
    }
    let md = summary_path(out);
    files::refuse_special(&md, "--out (summary)")?;
    if !force && md.exists() {
        let first = files::read_limited(&md, "summary", SUMMARY_MAX_BYTES)
            .ok()
            .and_then(|b| String::from_utf8(b).ok())
            .map(|t| t.lines().next().unwrap_or_default().to_string());
        if !first.as_deref().is_some_and(ours) {
            bail!(
                "--out {}: {} exists and is not the summary of {what} (rtw-scan did not write it): \
                 refusing to replace it; choose another file, or pass --force",
                out.display(),
                md.display()
            );
        }
    }
    for f in files_.iter().map(|f| &f.path).chain([&md]) {
        files::remove_stray_temps(f)?;
    }
    Ok(())
}

/// Whether `path` (a regular file: refused otherwise before) begins with
/// Parquet's magic bytes.
fn starts_as_parquet(path: &Path) -> bool {
    let mut magic = [0u8; 4];
    std::fs::File::open(path)
        .and_then(|mut f| std::io::Read::read_exact(&mut f, &mut magic))
        .is_ok_and(|()| &magic == b"PAR1")
}

/// Makes the output directory `dir` (named by the option `flag` in
/// messages: `--out`), its parents too, or takes it as it is when it is one
/// (or a symlink to one). Where something else is — a file, a device, a
/// symlink that leads nowhere, here or in place of a parent — it is refused,
/// saying what is there and what to do, rather than with the OS's "File
/// exists"; nothing there is changed. `holds` says what the directory is
/// for (`a scan's files`).
pub(crate) fn output_dir(dir: &Path, flag: &str, holds: &str) -> Result<()> {
    // The deepest of `dir` and its parents that is there, and what it is.
    let Some((at, meta)) = dir
        .ancestors()
        .filter(|a| !a.as_os_str().is_empty())
        .find_map(|a| std::fs::symlink_metadata(a).ok().map(|m| (a, m)))
    else {
        return make_dir(dir, flag);
    };
    let named = format!("{flag} {}: cannot create output directory", dir.display());
    let there = if at == dir {
        "it".to_string()
    } else {
        at.display().to_string()
    };
    if meta.file_type().is_symlink() {
        return match std::fs::metadata(at) {
            Ok(m) if m.is_dir() => make_dir(dir, flag),
            _ => bail!(
                "{named}: {there} is a symlink to {}, which is not a directory (nothing is there, \
                 or a file): rtw-scan does not make what a link points to; remove the link, point \
                 it at a directory, or choose another {flag}",
                std::fs::read_link(at).map_or_else(|_| "?".into(), |t| t.display().to_string())
            ),
        };
    }
    if !meta.is_dir() {
        bail!(
            "{named}: {there} is {}, not a directory ({flag} names a directory for {holds}); \
             choose another path (a new one, or a directory of an earlier run)",
            if meta.is_file() {
                "a regular file"
            } else {
                files::special_kind(meta.file_type())
            }
        );
    }
    make_dir(dir, flag)
}

/// `create_dir_all`, its error naming `dir` and `flag`.
fn make_dir(dir: &Path, flag: &str) -> Result<()> {
    std::fs::create_dir_all(dir)
        .with_context(|| format!("{flag} {}: cannot create output directory", dir.display()))
}

/// Most bytes of a summary (Markdown or JSON) read back to tell whose it is:
/// rtw-scan's are a few kB.
pub(crate) const SUMMARY_MAX_BYTES: u64 = 16_000_000;

/// Refuses to write a `kind` file at `dest` (given by the option `flag`):
/// always when `dest` is a symlink or not a regular file; unless `force`,
/// when `dest` is one of the command's `inputs`, or exists and is not a file
/// of the same kind (another kind of rtw-scan file, another Parquet file, or
/// not a Parquet file at all). A file of the same kind is the command's own
/// earlier output and may be replaced.
pub fn check_destination(
    dest: &Path,
    kind: FileKind,
    inputs: &[&Path],
    flag: &str,
    force: bool,
) -> Result<()> {
    check_destination_of(dest, kind, None, inputs, flag, force)
}

/// [`check_destination`], where a file of the same kind must also have the
/// columns of `schema` (when given) to be the command's earlier output.
fn check_destination_of(
    dest: &Path,
    kind: FileKind,
    schema: Option<&SchemaRef>,
    inputs: &[&Path],
    flag: &str,
    force: bool,
) -> Result<()> {
    files::refuse_special(dest, flag)?;
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
    let names =
        |s: &Schema| -> Vec<String> { s.fields().iter().map(|f| f.name().clone()).collect() };
    let found = match open(dest, 1) {
        // A Parquet file whose footer fails its checks is named as such,
        // with why, not as a file of another format.
        Err(e) if starts_as_parquet(dest) => {
            format!("a Parquet file rtw-scan cannot trust ({e:#})")
        }
        Err(_) => "a file that is not a Parquet file".to_string(),
        Ok(input) => match FileKind::of(&input.metadata) {
            Some(k) if k == kind => match schema {
                Some(s) if names(s) != names(&input.reader.schema()) => bail!(
                    "{flag} {shown}: holds another file of {} (its columns are not those of \
                     this one: another output's companion, such as a steps or special-points \
                     file): refusing to write over it; choose another file, or pass --force to \
                     replace it",
                    k.describe()
                ),
                _ => return Ok(()),
            },
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
