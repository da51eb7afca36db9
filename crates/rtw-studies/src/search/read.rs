//! A folder of design-search results read back, checked, for the report: a
//! search's own folder (`search.parquet`, `designs.parquet`) or an atlas
//! (`scripts/design_atlas.sh`'s `results/design/`: the `designs-NAME.parquet`
//! of several searches and the `profile-NAME.parquet` of their winners).
//!
//! Every file is read through the verified reader (its footer, its content
//! hash, its metadata hash), so a report never shows rows that rtw-scan
//! would refuse; what each file is comes from the metadata rtw-scan wrote
//! and its columns, never from its name.

use anyhow::{Context, Result, bail};
use arrow_array::RecordBatch;
use arrow_schema::SchemaRef;
use rtw_engine::io::metadata::{FileKind, META_DESIGN, META_VERSION};
use rtw_engine::io::parquet;
use std::path::{Path, PathBuf};

/// What a design file holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    /// Every evaluated design of a search, in order (`search.parquet`).
    Evaluations,
    /// A search's reported designs, their intervals checked (`designs.parquet`).
    Reported,
    /// A design's slope profile (`rtw-scan profile`).
    Profile,
}

impl Role {
    /// The role's name, as the report and Python spell it.
    pub fn name(self) -> &'static str {
        match self {
            Self::Evaluations => "evaluations",
            Self::Reported => "reported",
            Self::Profile => "profile",
        }
    }
}

/// One file of a design folder, read whole and checked.
pub struct DesignFile {
    /// The file.
    pub path: PathBuf,
    /// What it holds.
    pub role: Role,
    /// Its schema, with the file's key-value metadata (`rtw.design` or
    /// `rtw.profile`, `rtw.variant`, …).
    pub schema: SchemaRef,
    /// Its rows.
    pub batches: Vec<RecordBatch>,
}

/// The design files in `dir` (a search's folder, an atlas), or the one file
/// `dir` names, in name order, each read whole and verified. Parquet files
/// that are neither a search's nor a profile are left out (a folder may hold
/// other things); one of ours that fails its checks is an error naming it,
/// and so is a search folder whose `designs.parquet` is of other settings
/// than its `search.parquet`. `None`: `dir` holds no search's files (the
/// caller says what else it might have been).
pub fn read_folder(dir: &Path) -> Result<Option<Vec<DesignFile>>> {
    let paths: Vec<PathBuf> = if dir.is_dir() {
        rtw_engine::files::parquet_files(dir)?
    } else {
        vec![dir.to_path_buf()]
    };
    let mut files = Vec::new();
    for path in paths {
        let input = parquet::open(&path, 8192)?;
        let role = match FileKind::of(&input.metadata) {
            Some(FileKind::Profile) => Role::Profile,
            Some(FileKind::Design) => {
                // The two files of a search share their metadata; only the
                // evaluations carry the sub-search and generation of each row.
                let names = input.reader.schema();
                if names.column_with_name("generation").is_some() {
                    Role::Evaluations
                } else {
                    Role::Reported
                }
            }
            // The names `rtw-scan design` gives its files: one without a
            // search's metadata is a search's file changed by another tool,
            // and leaving it out would show the search without it.
            _ if dir.is_dir()
                && (path == super::files::search_path(dir)
                    || path == super::files::designs_path(dir)) =>
            {
                bail!(
                    "{}: not a design search's file (no `{META_DESIGN}` metadata): it was not \
                     written by `rtw-scan design`, or another tool rewrote it; run the search \
                     again, or move the file",
                    path.display()
                )
            }
            _ => continue,
        };
        let fields = input.reader.schema().fields().clone();
        let batches = input
            .reader
            .collect::<Result<Vec<_>>>()
            .with_context(|| format!("reading {}", path.display()))?;
        let (batches, schema) = parquet::with_metadata(batches, fields, input.metadata)?;
        files.push(DesignFile {
            path,
            role,
            schema,
            batches,
        });
    }
    if !files.iter().any(|f| f.role != Role::Profile) {
        return Ok(None);
    }
    same_search(&files)?;
    Ok(Some(files))
}

/// A search's folder holds the evaluations and the reported designs of one
/// search: a `designs.parquet` left from a search of other settings would
/// put another search's designs beside these evaluations.
fn same_search(files: &[DesignFile]) -> Result<()> {
    let of = |role| {
        files
            .iter()
            .filter(move |f: &&DesignFile| f.role == role)
            .collect::<Vec<_>>()
    };
    let (evaluations, reported) = (of(Role::Evaluations), of(Role::Reported));
    if evaluations.len() > 1 {
        bail!(
            "{} and {} are the evaluations of two searches: one search's folder holds one",
            evaluations[0].path.display(),
            evaluations[1].path.display()
        );
    }
    if let Some(e) = evaluations.first() {
        for r in reported {
            // One result never holds two builds' rows: a search's numbers
            // are what the build that made them computes.
            let version = |f: &DesignFile| {
                f.schema
                    .metadata()
                    .get(META_VERSION)
                    .cloned()
                    .unwrap_or_else(|| "none".into())
            };
            let (ve, vr) = (version(e), version(r));
            if ve != vr {
                bail!(
                    "{} (rtw-scan {ve}) and {} (rtw-scan {vr}) were written by different \
                     rtw-scan versions: one search's folder holds one build's results; run the \
                     search again, or move one of them",
                    e.path.display(),
                    r.path.display()
                );
            }
            if r.schema.metadata().get(META_DESIGN) != e.schema.metadata().get(META_DESIGN) {
                bail!(
                    "{}: its designs are of other settings or options than {}'s search: \
                     run the search again, or move one of them",
                    r.path.display(),
                    e.path.display()
                );
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_folder_without_design_files_is_not_a_design_folder() {
        let dir = tempfile::tempdir().unwrap();
        assert!(read_folder(dir.path()).unwrap().is_none());
    }
}
