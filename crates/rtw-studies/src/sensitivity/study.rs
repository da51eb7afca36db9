//! The sensitivity study, one entry point for `rtw-scan sensitivity` and
//! Python's `rtw.sensitivity`: its settings checked against their ranges,
//! the scan read through the checks every reader of scan files makes (its
//! content hash, values, ids in order from 0; a refined file refused), the
//! indices computed, and their file written with whose indices they are.

use super::{Columns, Index, Method, columns, indices, to_batch};
use anyhow::{Context, Result, anyhow, bail};
use arrow_array::RecordBatch;
use rtw_engine::analysis::report::{holds_refined_rows, open_scan};
use rtw_engine::config::count::count;
use rtw_engine::config::{self, ScanConfig};
use rtw_engine::files;
use rtw_engine::io::content_hash::ContentHash;
use rtw_engine::io::metadata::{
    FileKind, META_CONFIG, META_CONTENT_HASH, META_SENSITIVITY, VERSION, kv,
};
use rtw_engine::io::{destination, parquet, scan_files};
use rtw_engine::scan::Run;
use rtw_engine::scan::lock::Lock;
use rtw_engine::scan::progress::Progress;
use std::collections::HashMap;
use std::ops::RangeInclusive;
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

/// Bootstrap resamples of the confidence intervals: a half-width is a
/// standard deviation over them, so at least 2; at most 10⁴, where its own
/// sampling error is under 1 % (SALib's default is 100), and the resamples'
/// memory and time stay bounded.
pub const RESAMPLES: RangeInclusive<u64> = 2..=10_000;

/// A sensitivity study's settings, checked.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Settings {
    /// Bootstrap resamples, in [`RESAMPLES`].
    pub resamples: usize,
    /// Seed of the resamples (`None`: the scan's seed).
    pub seed: Option<u64>,
}

impl Settings {
    /// The settings as given (the digits written), each checked against
    /// its range and named in an error as `prefix` + its name
    /// (`--resamples` on the command line, `resamples` in Python).
    pub fn parse(resamples: &str, seed: Option<&str>, prefix: &str) -> Result<Self> {
        let resamples = count(&format!("{prefix}resamples"), resamples, RESAMPLES, "")?;
        let seed = seed
            .map(|s| count(&format!("{prefix}seed"), s, 0..=u64::MAX, ""))
            .transpose()?;
        Ok(Self {
            // At most RESAMPLES' end.
            resamples: resamples as usize,
            seed,
        })
    }
}

/// A study's result: the indices and what they are of (the metadata of
/// their file).
#[derive(Clone, Debug)]
pub struct Analysis {
    /// How they were estimated.
    pub method: Method,
    /// One per output and uniform input.
    pub indices: Vec<Index>,
    /// method, scan, scan_content_hash (whose indices they are: the scan's
    /// rows' content hash), config_hash, rows, resamples, seed.
    pub about: serde_json::Value,
}

/// The scan file a path names: itself, or a directory's `samples.parquet`.
pub fn scan_file(path: &Path) -> PathBuf {
    if path.is_dir() {
        path.join("samples.parquet")
    } else {
        path.to_path_buf()
    }
}

/// Refuses a refinement's rows (`refined`), naming them as `what` and
/// pointing to the scan's own rows when known (`own`).
fn refuse_refined(refined: bool, what: &str, own: Option<PathBuf>) -> Result<()> {
    // Refinement adds samples where the labels change: they are not draws
    // from the inputs' distribution, and every estimator here weighs each
    // row as one.
    if refined {
        bail!(
            "{what} holds a refined scan: its added samples crowd where the labels change, so they \
             are not draws from the inputs' distribution and Sobol indices from them would be \
             biased; analyse the scan's own rows{}",
            own.map_or(String::new(), |p| format!(" ({})", p.display()))
        );
    }
    Ok(())
}

/// The inputs and outputs of a scan's `batches`, each checked as every
/// reader of scan files checks them (values in range, ids once each in
/// order from 0, so that Saltelli's rows pair up), errors naming `what`.
fn checked_columns(
    cfg: &ScanConfig,
    what: &Path,
    batches: impl Iterator<Item = Result<RecordBatch>>,
) -> Result<Columns> {
    let (mut rows, mut next) = (0u64, Some(0));
    let batches = batches.map(|b| {
        let b = b?;
        scan_files::check_scan_values(&b, what, rows)?;
        next = scan_files::check_ids(&b, what, rows, next)?;
        rows += b.num_rows() as u64;
        Ok(b)
    });
    columns(cfg, batches).with_context(|| what.display().to_string())
}

/// The indices of the scan file `scan` (or the directory holding it), read
/// through the verified reader: its content hash, its values and ids, and
/// not a refine's combined file. `run`'s stop flag stops it between two
/// resamples (the error [`Stopped`](rtw_engine::scan::workers::Stopped)).
pub fn analyse_file(scan: &Path, settings: &Settings, run: &Run) -> Result<Analysis> {
    let (cancel, progress) = (run.stop, run.progress);
    let scan = scan_file(scan);
    let (input, cfg) = open_scan(&scan)?;
    // The scan refined is the folder holding `refine/` (its combined file
    // and its rounds are inside it).
    let own = scan
        .ancestors()
        .find(|d| d.file_name().is_some_and(|n| n == "refine"))
        .and_then(Path::parent)
        .map(|d| d.join("samples.parquet"));
    refuse_refined(
        holds_refined_rows(input.metadata.keys(), &cfg),
        &scan.display().to_string(),
        own,
    )?;
    let hash = input.metadata.get(META_CONTENT_HASH).cloned();
    let cols = checked_columns(&cfg, &scan, input.reader)?;
    analyse(
        &cfg,
        &cols,
        settings,
        cancel,
        progress,
        &scan.display().to_string(),
        hash,
    )
}

/// The indices of a scan table in memory (what Python's `rtw.scan` returns,
/// or a scan file read by another tool), its scan's metadata in `metadata`
/// (`rtw.config`; its `rtw.content_hash`, when it has one, is checked), with
/// the checks of [`analyse_file`].
pub fn analyse_table(
    metadata: &HashMap<String, String>,
    batches: Vec<RecordBatch>,
    settings: &Settings,
    run: &Run,
) -> Result<Analysis> {
    let (cancel, progress) = (run.stop, run.progress);
    let what = Path::new("the table");
    let text = metadata.get(META_CONFIG).ok_or_else(|| {
        anyhow!(
            "the table: no `{META_CONFIG}` in its schema metadata: not a table of rtw.scan; give a \
             scan file by its path"
        )
    })?;
    let cfg = config::parse(text).context("the config stored in the table")?;
    refuse_refined(holds_refined_rows(metadata.keys(), &cfg), "the table", None)?;
    let expected = metadata.get(META_CONTENT_HASH);
    if let Some(want) = expected {
        let mut hash = ContentHash::new(batches.first().map_or(0, RecordBatch::num_columns));
        for b in &batches {
            hash.update(b)?;
        }
        let got = hash.value();
        if got != *want {
            bail!(
                "the table is corrupt: its rows hash to {got}, not to the {want} of its \
                 `{META_CONTENT_HASH}`; read the scan file again"
            );
        }
    }
    let cols = checked_columns(&cfg, what, batches.into_iter().map(Ok))?;
    analyse(
        &cfg,
        &cols,
        settings,
        cancel,
        progress,
        "a table",
        expected.cloned(),
    )
}

fn analyse(
    cfg: &ScanConfig,
    cols: &Columns,
    settings: &Settings,
    cancel: &AtomicBool,
    progress: &dyn Progress,
    scan: &str,
    content_hash: Option<String>,
) -> Result<Analysis> {
    let seed = settings.seed.unwrap_or(cfg.seed);
    let (method, rows) = indices(cfg, cols, settings.resamples, seed, cancel, progress)?;
    let about = serde_json::json!({
        "method": method.name(),
        "scan": scan,
        "scan_content_hash": content_hash,
        "config_hash": cfg.hash(),
        "rows": cols.outputs.first().map_or(0, |(_, y)| y.len()),
        "resamples": settings.resamples,
        "seed": seed,
    });
    Ok(Analysis {
        method,
        indices: rows,
        about,
    })
}

/// Refuses to write the indices of the scan file `scan` at `out` (given by
/// `--out`), before they are computed: over anything `destination` refuses
/// (the scan itself, a special file, a file of another kind) and, unless
/// `force`, over the indices of another scan. An indices file says whose it
/// is by its scan's content hash (`scan_content_hash`); one written before
/// that key existed, by its scan's config hash.
pub fn check_out(out: &Path, scan: &Path, force: bool) -> Result<()> {
    let scan = scan_file(scan);
    destination::check_destination(out, FileKind::Sensitivity, &[&scan], "--out", force)?;
    if force || !out.exists() {
        return Ok(());
    }
    let theirs: serde_json::Value = parquet::open(out, 1)?
        .metadata
        .get(META_SENSITIVITY)
        .and_then(|s| serde_json::from_str(s).ok())
        .unwrap_or_default();
    let (input, cfg) = open_scan(&scan)?;
    let ours = input.metadata.get(META_CONTENT_HASH);
    let same = match theirs.get("scan_content_hash").and_then(|h| h.as_str()) {
        Some(h) => ours.is_some_and(|o| o == h),
        None => theirs.get("config_hash").and_then(|h| h.as_str()) == Some(&cfg.hash()),
    };
    if !same {
        let whose = theirs.get("scan").and_then(|s| s.as_str()).unwrap_or("?");
        bail!(
            "--out {}: holds the indices of another scan ({whose}, not {}): refusing to replace \
             them; choose another file, or pass --force to replace it",
            out.display(),
            scan.display()
        );
    }
    Ok(())
}

/// The indices of the scan file `scan` ([`analyse_file`]) written to `out`
/// ([`write()`]): the lock of `out` taken and `out` checked ([`check_out`])
/// before any resample, so a second analysis into one file is refused.
pub fn analyse_to_file(
    scan: &Path,
    out: &Path,
    settings: &Settings,
    force: bool,
    run: &Run,
) -> Result<Analysis> {
    let _lock = Lock::for_result(out, &format!("writing the indices {}", out.display()))?;
    check_out(out, scan, force)?;
    let analysis = analyse_file(scan, settings, run);
    run.progress.finish(analysis.is_ok());
    let analysis = analysis?;
    write(out, &analysis)?;
    Ok(analysis)
}

/// Writes the indices of `analysis` to `out` (atomically), their metadata
/// saying whose they are ([`Analysis::about`]).
pub fn write(out: &Path, analysis: &Analysis) -> Result<()> {
    files::remove_stray_temps(out)?;
    parquet::write_file(
        out,
        &to_batch(&analysis.indices),
        vec![
            kv(rtw_engine::io::metadata::META_VERSION, VERSION.into()),
            kv(META_SENSITIVITY, analysis.about.to_string()),
        ],
    )
}
