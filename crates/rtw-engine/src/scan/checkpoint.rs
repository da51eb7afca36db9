//! What makes an interrupted scan resumable: where its files go
//! (`Layout`), the manifest that ties its unfinished chunks to one config,
//! the checks that keep a chunk, the refusal to mix another scan's results
//! into a directory, and the one decision a run makes from what it finds
//! (`Checkpoint::open` → `Resume`).

use crate::config;
use crate::config::ScanConfig;
use crate::files;
use crate::io::metadata::{self, META_CONFIG, META_CONFIG_HASH, META_SHARD, META_VERSION, VERSION};
use crate::io::parquet::{self, READ_BATCH_ROWS};
use crate::io::{scan_files, table};
use crate::scan::partial::{chunks_on_disk, remove_partial, remove_stray_temps};
use crate::scan::progress::Progress;
use crate::scan::shard::{self, Shard};
use anyhow::{Context, Result, anyhow, bail};
use arrow_array::cast::AsArray;
use arrow_array::types::Int64Type;
use rtw_model::Label;
use serde::{Deserialize, Serialize};
use std::collections::BTreeSet;
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};

/// What `.partial/manifest.json` records to make a resume safe.
#[derive(Debug, PartialEq, Serialize, Deserialize)]
pub struct Manifest {
    pub(crate) version: String,
    /// The config the scan was started with, as TOML text.
    pub config: String,
    pub(crate) chunk_size: usize,
    pub(crate) rows: u64,
    /// The shard (`K/N`) this run computes; absent for a whole scan.
    #[serde(default)]
    pub(crate) shard: Option<String>,
}

/// Where a scan (or one shard of it) writes.
pub(crate) struct Layout {
    /// `samples.parquet`, or `part-K.parquet` for shard K.
    pub(crate) samples: PathBuf,
    /// `.partial`, or `.partial-K` for shard K (shards share a directory).
    pub(crate) partial: PathBuf,
}

impl Layout {
    pub(crate) fn new(out_dir: &Path, shard: Option<Shard>) -> Self {
        match shard {
            None => Self {
                samples: out_dir.join("samples.parquet"),
                partial: out_dir.join(".partial"),
            },
            Some(s) => Self {
                samples: out_dir.join(s.part_name()),
                partial: out_dir.join(s.partial_name()),
            },
        }
    }
    pub(crate) fn manifest(&self) -> PathBuf {
        self.partial.join("manifest.json")
    }
    pub(crate) fn chunk(&self, c: u64) -> PathBuf {
        self.partial.join(format!("chunk-{c:05}.parquet"))
    }
}

/// Most rows per chunk (`--chunk-size`): a chunk's rows are held in memory
/// until it is written (about 400 bytes a row: 26 MB at the limit), so a
/// huge size would allocate gigabytes. 256 (the default) already makes the
/// chunk files' overhead small.
pub(crate) const MAX_CHUNK_SIZE: usize = 65_536;

/// Refuses a chunk size outside `1..=MAX_CHUNK_SIZE`.
pub(crate) fn check_chunk_size(n: usize) -> Result<()> {
    if !(1..=MAX_CHUNK_SIZE).contains(&n) {
        bail!("--chunk-size: {n} is invalid: must be in 1..={MAX_CHUNK_SIZE} (rows per chunk)");
    }
    Ok(())
}

/// What a run asks of the unfinished run it may find: `--resume` (finish
/// it), `--force` (discard one it cannot finish) and the chunk size of a run
/// it starts.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Intent {
    pub(crate) resume: bool,
    pub(crate) force: bool,
    pub(crate) chunk_size: usize,
}

/// What [`Checkpoint::open`] found on disk, and so what is left to compute.
#[derive(Debug, PartialEq)]
pub(crate) enum Resume {
    /// The result file is there, complete, for this very config and shard
    /// (a resume of a finished run): nothing is left to compute.
    Complete,
    /// Finished chunks are kept: the run goes on in chunks of `chunk_size`
    /// (the size it was started with), computing the chunks not in `kept`.
    Continue {
        chunk_size: usize,
        kept: BTreeSet<u64>,
    },
    /// Nothing is kept: every chunk is computed, in chunks of `chunk_size`.
    Fresh { chunk_size: usize },
}

/// The rows of a scan, or of one shard of it, on their way to its result
/// file: where they go ([`Layout`]) and what an unfinished run in its
/// `.partial` must match to be resumed (the config, the rows, the shard).
pub(crate) struct Checkpoint<'a> {
    pub(crate) layout: Layout,
    cfg: &'a ScanConfig,
    /// `cfg` as TOML: what the manifest and every chunk record.
    config: String,
    /// The sample ids of the rows.
    pub(crate) ids: Range<u64>,
    /// The shard as `K/N`; `None` for a whole scan.
    shard: Option<String>,
}

impl<'a> Checkpoint<'a> {
    /// The checkpoint of the rows `ids` of `cfg` (shard `shard`, if any) in
    /// the output directory `out`.
    pub(crate) fn new(
        out: &Path,
        cfg: &'a ScanConfig,
        ids: Range<u64>,
        shard: Option<Shard>,
    ) -> Self {
        Self {
            layout: Layout::new(out, shard),
            cfg,
            config: cfg.to_toml(),
            ids,
            shard: shard.map(|s| s.to_string()),
        }
    }

    pub(crate) fn rows(&self) -> u64 {
        self.ids.end - self.ids.start
    }

    /// How many chunks of `chunk_size` rows the rows make.
    pub(crate) fn chunks(&self, chunk_size: usize) -> u64 {
        self.rows().div_ceil(chunk_size as u64)
    }

    /// The sample ids of chunk `c` in chunks of `chunk_size` rows.
    pub(crate) fn chunk_ids(&self, chunk_size: usize, c: u64) -> Range<u64> {
        let cs = chunk_size as u64;
        self.ids.start + c * cs..(self.ids.start + (c + 1) * cs).min(self.ids.end)
    }

    /// Decides, from what is on disk and what the run asks, whether the
    /// rows are complete, an unfinished run goes on, or a run starts; and
    /// makes the state on disk that decision's: a complete result's
    /// leftover `.partial` is cleaned up, a new run's manifest written, the
    /// temporary files of a killed run removed, and each finished chunk
    /// checked (config, version, rows, ids) and kept or removed to be
    /// computed again. Refuses, naming both sides, what it must not resume
    /// or discard (see `unfinished_run`). Once the run is to compute,
    /// `progress` hears its start and each row kept; `stop` set ends the
    /// checking of chunks early (those not checked yet are not kept).
    pub(crate) fn open(
        &self,
        intent: Intent,
        stop: &AtomicBool,
        progress: &dyn Progress,
    ) -> Result<Resume> {
        let layout = &self.layout;
        // A finished result of this config and shard is complete for a
        // resume; without one, when this very version made it too: its rows
        // depend only on (seed, sample id) and the build, so running them
        // again would rewrite the same rows (the main command run twice).
        // Another version's file is computed anew, and `force` always is.
        let complete = is_complete(&layout.samples, &self.config, self.shard.as_deref())
            && (intent.resume || (!intent.force && made_by_this_version(&layout.samples)));
        if complete {
            // Complete: at most the clean-up of a run killed after its merge is left.
            if layout.partial.is_dir() {
                report_unknown(progress, &layout.partial, &remove_partial(&layout.partial)?);
            }
            return Ok(Resume::Complete);
        }
        let chunk_size = match self.unfinished_run(intent, progress)? {
            Some(manifest) => manifest.chunk_size,
            None => self.start(intent.chunk_size)?,
        };
        let unknown = remove_stray_temps(&layout.partial)?;
        if !unknown.is_empty() {
            progress.warn(&format!(
                "rtw-scan: ignoring {} in {}: not made by rtw-scan (left as they are)",
                unknown.join(", "),
                layout.partial.display()
            ));
        }
        progress.start(self.rows());
        let kept = self.keep_finished(chunk_size, stop, progress)?;
        Ok(if kept.is_empty() {
            Resume::Fresh { chunk_size }
        } else {
            Resume::Continue { chunk_size, kept }
        })
    }

    /// Starts a run in chunks of `chunk_size`: its `.partial` and manifest.
    /// No finished chunk is kept under an old manifest: a `.partial` without
    /// one is a run killed before it wrote one, or one holding only files
    /// rtw-scan did not make.
    fn start(&self, chunk_size: usize) -> Result<usize> {
        let partial = &self.layout.partial;
        crate::io::destination::output_dir(
            partial,
            "--out",
            "a run's unfinished chunks (rtw-scan makes it)",
        )?;
        crate::pause_at("manifest");
        let manifest = Manifest {
            version: VERSION.into(),
            config: self.config.clone(),
            chunk_size,
            rows: self.rows(),
            shard: self.shard.clone(),
        };
        files::write_atomic(
            &self.layout.manifest(),
            &serde_json::to_vec_pretty(&manifest)?,
        )?;
        Ok(chunk_size)
    }

    /// The finished chunks in `.partial` that hold their rows for this run,
    /// their rows reported to `progress` as kept; the others are removed, to
    /// be computed again. Found by listing `.partial`, so the work before
    /// the first sample grows with the chunks kept, not with the scan's size.
    fn keep_finished(
        &self,
        chunk_size: usize,
        stop: &AtomicBool,
        progress: &dyn Progress,
    ) -> Result<BTreeSet<u64>> {
        let chunks = self.chunks(chunk_size);
        let mut kept = BTreeSet::new();
        for c in chunks_on_disk(&self.layout.partial)? {
            let path = self.layout.chunk(c);
            if stop.load(Ordering::SeqCst) {
                break;
            }
            let checked = if c < chunks {
                chunk_labels(&path, self.chunk_ids(chunk_size, c), &self.config)
            } else {
                Err(anyhow!("beyond the scan's {chunks} chunks"))
            };
            match checked {
                Ok(labels) => {
                    kept.insert(c);
                    labels.into_iter().for_each(|l| progress.kept(l));
                }
                Err(e) => {
                    progress.note(&format!("redoing {}: {e:#}", path.display()));
                    std::fs::remove_file(&path)
                        .with_context(|| format!("cannot remove {}", path.display()))?;
                }
            }
        }
        Ok(kept)
    }

    /// The unfinished run in `.partial` to resume, if there is one, with its
    /// manifest. Refuses (naming both sides) an unfinished run of another
    /// config, shard or rtw-scan version unless `force` (which discards it),
    /// and one of this very scan without `resume`. A `.partial` without a
    /// manifest holds no finished chunk of a run that can be resumed from
    /// it: `None` (chunks in it, left by a clean-up killed after the merge
    /// or by a lost manifest, are checked one by one like any other).
    fn unfinished_run(&self, intent: Intent, progress: &dyn Progress) -> Result<Option<Manifest>> {
        let (layout, cfg, rows, shard) =
            (&self.layout, self.cfg, self.rows(), self.shard.as_deref());
        let partial = &layout.partial;
        if !layout.manifest().exists() {
            if partial.is_dir() && !chunks_on_disk(partial)?.is_empty() && !intent.resume {
                if !intent.force {
                    bail!(
                        "{} holds finished chunks of an unfinished run: pass --resume to finish it, or \
                         --force to discard it",
                        partial.display()
                    );
                }
                report_unknown(progress, partial, &remove_partial(partial)?);
            }
            return Ok(None);
        }
        let m = read_manifest(&layout.manifest())
            .map_err(|e| e.context("restore it, or pass --force to discard the unfinished run"));
        let refusal = match &m {
            Err(_) => None,
            Ok(m) if m.config != self.config || m.rows != rows || m.shard.as_deref() != shard => {
                Some(anyhow!(
                    "cannot {} in {}: its unfinished run was started with a different config or \
                     --shard split: {}. Choose another --out, or pass --force to discard it",
                    if intent.resume { "resume" } else { "start" },
                    partial.display(),
                    describe_mismatch(m, cfg, rows, shard)
                ))
            }
            Ok(m) => metadata::refuse_mixed_versions(
                &format!(
                    "cannot resume the unfinished run in {}: its chunks and this run",
                    partial.display()
                ),
                ("its chunks", &m.version),
                ("this run", VERSION),
                &format!(
                    "one result never mixes two versions' rows: finish it with rtw-scan {}, or pass \
                     --force to discard it and compute the scan anew",
                    m.version
                ),
            )
            .err(),
        };
        if intent.force && (m.is_err() || refusal.is_some()) {
            report_unknown(progress, partial, &remove_partial(partial)?);
            return Ok(None);
        }
        let m = m?;
        if let Some(e) = refusal {
            return Err(e);
        }
        if !intent.resume {
            bail!(
                "{} holds an unfinished run of this scan: pass --resume to finish it, or delete it to start over",
                partial.display()
            );
        }
        check_chunk_size(m.chunk_size)
            .with_context(|| format!("{} is corrupt", layout.manifest().display()))?;
        Ok(Some(m))
    }
}

/// Says which entries of `partial` rtw-scan left in place, not having made them.
pub(crate) fn report_unknown(progress: &dyn Progress, partial: &Path, unknown: &[String]) {
    if !unknown.is_empty() {
        progress.warn(&format!(
            "rtw-scan: kept {}: it holds {}, not made by rtw-scan",
            partial.display(),
            unknown.join(", ")
        ));
    }
}

/// Checks a chunk file (config, row count, ids) and returns its labels.
pub(crate) fn chunk_labels(
    path: &Path,
    ids: std::ops::Range<u64>,
    config: &str,
) -> Result<Vec<Label>> {
    let input = parquet::open(path, READ_BATCH_ROWS)?;
    if input.metadata.get(META_CONFIG).map(String::as_str) != Some(config) {
        bail!("written for another config");
    }
    metadata::refuse_other_version(
        "the chunk and this run",
        &input.metadata,
        "the chunk",
        "this run",
        "it is computed again",
    )?;
    if input.rows as u64 != ids.end - ids.start {
        bail!("{} rows, expected {}", input.rows, ids.end - ids.start);
    }
    let mut labels = Vec::new();
    let mut next = ids.start;
    for batch in input.reader {
        let batch = batch?;
        let col = batch
            .column_by_name("sample_id")
            .and_then(|c| c.as_primitive_opt::<Int64Type>())
            .ok_or_else(|| anyhow!("no Int64 sample_id column"))?;
        for id in col.iter() {
            if id != Some(next as i64) {
                bail!("sample_id {id:?} where {next} was expected");
            }
            next += 1;
        }
        scan_files::check_scan_values(&batch, path, labels.len() as u64)?;
        labels.extend(table::label_column(&batch)?);
    }
    Ok(labels)
}

/// Refuses to run into a directory that holds another scan's results: a
/// `samples.parquet` or `part-K.parquet` of another config (hash), or, for a
/// shard, the parts of another split of this scan.
pub(crate) fn refuse_other_results(
    out: &Path,
    cfg: &ScanConfig,
    shard: Option<Shard>,
) -> Result<()> {
    let hash = cfg.hash();
    let ours = metadata::scan_label(&hash, cfg.name.as_deref(), cfg.seed);
    let mut names: Vec<String> = std::fs::read_dir(out)
        .with_context(|| format!("cannot read {}", out.display()))?
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n == "samples.parquet" || shard::part_index(n).is_some())
        .collect();
    names.sort();
    for name in names {
        let path = out.join(&name);
        let meta = match parquet::open(&path, 1) {
            Ok(i) => i.metadata,
            Err(e) => bail!(
                "{} holds {name}, which is not a scan rtw-scan can read ({e:#}); this run is {ours}: \
                 choose another --out, or pass --force to replace it",
                out.display()
            ),
        };
        if meta.get(META_CONFIG_HASH) != Some(&hash) {
            bail!(
                "{} holds another scan's results: {name} is {}; this run is {ours}. Choose another \
                 --out, or pass --force to replace them",
                out.display(),
                metadata::scan_label_of(&meta)
            );
        }
        let theirs = meta.get(META_SHARD).and_then(|t| t.parse::<Shard>().ok());
        if let (Some(s), Some(t)) = (shard, theirs)
            && s.count != t.count
        {
            bail!(
                "{} holds the parts of a {}-shard split of this scan ({name} is shard {t}); this run \
                 is shard {s}, and merge joins the parts of one split only. Use --shard K/{}, another \
                 --out, or pass --force",
                out.display(),
                t.count,
                t.count
            );
        }
    }
    Ok(())
}

/// Reads a scan's manifest (`.partial/manifest.json`), bounded in size.
pub fn read_manifest(path: &Path) -> Result<Manifest> {
    // The manifest holds the config and a few numbers.
    let text =
        files::read_limited(path, "manifest", 2 * files::CONFIG_MAX_BYTES).with_context(|| {
            format!(
                "cannot read {}: delete its directory to start over",
                path.display()
            )
        })?;
    serde_json::from_slice(&text).with_context(|| format!("{} is corrupt", path.display()))
}

/// Why the unfinished run of `manifest` is not the run of `cfg` (rows
/// `rows`, shard `shard`): both named (config hash, name, seed), then each
/// setting that differs, there (on disk) and here (requested).
pub(crate) fn describe_mismatch(
    manifest: &Manifest,
    cfg: &ScanConfig,
    rows: u64,
    shard: Option<&str>,
) -> String {
    let ours = metadata::scan_label(&cfg.hash(), cfg.name.as_deref(), cfg.seed);
    let theirs_hash = config::config_hash(&manifest.config);
    let theirs_cfg = config::parse(&manifest.config).ok();
    let theirs = match &theirs_cfg {
        Some(c) => metadata::scan_label(&theirs_hash, c.name.as_deref(), c.seed),
        None => format!("config hash {theirs_hash}"),
    };
    let none = || "none".to_string();
    let mut differ = Vec::new();
    let mut add = |what: &str, there: String, here: String| {
        if there != here {
            differ.push(format!("{what} {there} there, {here} here"));
        }
    };
    if let Some(c) = &theirs_cfg {
        add(
            "name",
            c.name.clone().unwrap_or_else(none),
            cfg.name.clone().unwrap_or_else(none),
        );
        add("seed", c.seed.to_string(), cfg.seed.to_string());
    }
    add("rows", manifest.rows.to_string(), rows.to_string());
    add(
        "shard",
        manifest.shard.clone().unwrap_or_else(none),
        shard.map_or_else(none, str::to_string),
    );
    if differ.is_empty() {
        differ.push(
            "the same name, seed, rows and shard, but other settings (parameter ranges or \
             [simulation]; its config is in manifest.json)"
                .to_string(),
        );
    }
    format!("it is {theirs}, this run is {ours}: {}", differ.join("; "))
}

/// Was `samples` written by this very build of rtw (its `rtw.version`)?
fn made_by_this_version(samples: &Path) -> bool {
    parquet::open(samples, 1)
        .map(|i| i.metadata.get(META_VERSION).map(String::as_str) == Some(VERSION))
        .unwrap_or(false)
}

/// Does `samples` exist, complete, for this very config (and shard)?
pub fn is_complete(samples: &Path, config: &str, shard: Option<&str>) -> bool {
    parquet::open(samples, 1)
        .map(|i| {
            i.metadata.get(META_CONFIG).map(String::as_str) == Some(config)
                && i.metadata.get(META_SHARD).map(String::as_str) == shard
        })
        .unwrap_or(false)
}
