//! Refinement rounds of a finished scan: samples added where labels change.
//!
//! `rtw-scan refine DIR --budget N --rounds R --seed S` splits the budget
//! into R rounds (sizes differing by at most one). Round r's points are
//! proposed by `propose::propose` from the rows of
//! `DIR/samples.parquet` and of rounds 1 … r − 1, in that order, so a round
//! is a deterministic function of those rows and the seed. Each round is an
//! ordinary scan in `DIR/refine/round-RRR/` (its rows `0 … n − 1` in
//! `samples.parquet`, its summary beside them), run by the scan machinery
//! (chunks, `--resume`, `--shard K/N` and `merge`), with its points stored
//! in the config it carries: the scan's config with `samples = n`, `sampling
//! = "points"`, the points in its `[points]` table
//! ([`rtw_engine::config::points`]), and the name `NAME+refine-r-HASH`, HASH a
//! hash of the points
//! and the seed, so that another seed or other rows never resume or merge
//! into it. When every round is complete, `DIR/refine/samples.parquet` holds
//! every row, the scan's first and then each round's, with `sample_id`s
//! numbered on from the scan's (round r's row i is `N₀ + n₁ + … + i`).

pub(crate) mod propose;
mod study;

pub use study::default_seed;

use ::parquet::file::metadata::KeyValue;
use anyhow::{Context, Result, bail};
use arrow_array::{Int64Array, RecordBatch};
use propose::propose;
use rtw_engine::analysis::report::open_scan;
use rtw_engine::config::ScanConfig;
use rtw_engine::config::axis::Axis;
use rtw_engine::config::points::MAX_POINTS;
use rtw_engine::hash::fnv1a64;
use rtw_engine::io::destination::check_destination;
use rtw_engine::io::metadata::{self, FileKind, META_CONFIG, META_CONTENT_HASH, META_REFINE, kv};
use rtw_engine::io::parquet::{self, MAX_ROW_GROUP_ROWS, ParquetFile, READ_BATCH_ROWS};
use rtw_engine::io::scan_rows::label_index;
use rtw_engine::io::table::{f64_column, label_column};
use rtw_engine::sampling::Sampling;
use rtw_engine::scan::Run;
use rtw_engine::scan::checkpoint::is_complete;
use rtw_engine::scan::lock::Lock;
use rtw_engine::scan::one::Simulator;
use rtw_engine::scan::run::{RunSettings, RunStatus, run_scan_with};
use rtw_engine::scan::sample::Sampler;
use rtw_model::{Param, Params};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// What to refine, and how.
#[derive(Clone, Debug)]
pub struct Refine {
    /// The scan's directory (its `samples.parquet`).
    pub dir: PathBuf,
    /// New samples in all rounds together.
    pub budget: u64,
    /// Rounds the budget is split into.
    pub rounds: u64,
    /// Seed of the rounds' candidates and uniform draws.
    pub seed: u64,
    /// How each round runs (its `out_dir` is set per round).
    pub run: RunSettings,
}

/// How a refinement ended.
#[derive(Clone, Debug, PartialEq)]
pub enum RefineStatus {
    /// Every round is in; `combined` holds every row.
    Complete {
        /// `DIR/refine/samples.parquet`: the scan's rows and the new ones.
        combined: PathBuf,
        /// Its rows.
        rows: u64,
    },
    /// Round `round` (its directory `dir`) stopped before its end: it was
    /// interrupted, or one shard of it ran.
    Stopped {
        /// The round (1-based).
        round: u64,
        /// Its directory, `DIR/refine/round-RRR`.
        dir: PathBuf,
        /// How its scan ended.
        status: RunStatus,
    },
    /// Stopped while choosing round `round`'s points, before its scan
    /// began: the finished rounds are kept, and the same command goes on.
    Interrupted {
        /// The round (1-based).
        round: u64,
    },
}

/// Most new samples of a refinement: a round holds its pool of
/// `POOL × n` candidates in memory (about 150 MB for 10⁵ points in 6
/// inputs) and scores each against every row so far.
pub(crate) const MAX_BUDGET: u64 = 100_000;

/// Most rows of the scan refined: they are held in memory (about 100 bytes
/// each) for the neighbour search.
pub(crate) const MAX_BASE_ROWS: i64 = 1_000_000;

/// Checks the flags: `1 ≤ budget ≤ MAX_BUDGET`, `⌈budget / MAX_POINTS⌉ ≤
/// rounds ≤ budget`.
pub fn check_budget(budget: u64, rounds: u64) -> Result<()> {
    if !(1..=MAX_BUDGET).contains(&budget) {
        bail!(
            "--budget: {budget} is invalid: must be an integer in [1, {MAX_BUDGET}] (new samples \
             in all rounds; each round holds 20 candidates a point in memory and compares each \
             with every row so far)"
        );
    }
    // A round stores its points in its config: at most MAX_POINTS each.
    let fewest = budget.div_ceil(MAX_POINTS);
    if rounds < fewest || rounds > budget {
        bail!(
            "--rounds: {rounds} is invalid: must be an integer from {fewest} to --budget \
             ({budget}), so that every round adds a sample and holds at most {MAX_POINTS} points \
             (a round's config stores them)"
        );
    }
    Ok(())
}

/// Whose a refinement is: the rows it refines (their content hash), its
/// seed, budget and rounds. Its combined file carries it (`rtw.refine`), and
/// a refinement replaces only its own files: another's (another seed,
/// budget, rounds or base rows) are refused unless `--force`, saying what
/// differs.
struct Identity {
    base: String,
    seed: u64,
    budget: u64,
    rounds: u64,
}

impl Identity {
    fn of(r: &Refine, base: &str) -> Self {
        Self {
            base: base.to_string(),
            seed: r.seed,
            budget: r.budget,
            rounds: r.rounds,
        }
    }

    fn to_json(&self) -> serde_json::Value {
        serde_json::json!({
            "budget": self.budget, "rounds": self.rounds, "seed": self.seed, "base": self.base,
        })
    }

    /// The flags that make this refinement.
    fn flags(&self) -> String {
        format!(
            "--budget {} --rounds {} --seed {}",
            self.budget, self.rounds, self.seed
        )
    }

    /// What differs between this refinement and one whose `rtw.refine` is
    /// `theirs` (a file made before the base rows were recorded leaves them
    /// out), or nothing.
    fn differences(&self, theirs: &serde_json::Value) -> Vec<String> {
        let mut d = Vec::new();
        for (key, ours) in [
            ("budget", self.budget),
            ("rounds", self.rounds),
            ("seed", self.seed),
        ] {
            let there = theirs[key].as_u64();
            if there != Some(ours) {
                let there = there.map_or("none".to_string(), |v| v.to_string());
                d.push(format!("--{key} {there} there, {ours} here"));
            }
        }
        if let Some(base) = theirs["base"].as_str()
            && base != self.base
        {
            d.push(format!(
                "the scan's rows (content hash {base} there, {} here: the scan was rerun or \
                 changed since)",
                self.base
            ));
        }
        d
    }

    /// Refuses a combined file at `combined` that is another refinement's,
    /// or not a refinement's at all.
    fn refuse_another_at(&self, combined: &Path) -> Result<()> {
        let Ok(input) = parquet::open(combined, 1) else {
            return Ok(()); // none, or refused by check_destination already
        };
        let theirs = input
            .metadata
            .get(META_REFINE)
            .and_then(|t| serde_json::from_str::<serde_json::Value>(t).ok());
        let Some(theirs) = &theirs else {
            // A scan's own rows (check_destination let only a scan's file
            // through): no refinement made it, so none can go on from it.
            bail!(
                "{} is a scan's samples file (`rtw-scan run` wrote it; it has no `rtw.refine` \
                 metadata), not a refinement's file: no refinement can go on from it. Move it \
                 away (or the folder {}) to refine here ({}), or pass --force to replace it",
                combined.display(),
                combined.parent().unwrap_or(Path::new(".")).display(),
                self.flags()
            );
        };
        let diffs = self.differences(theirs);
        if diffs.is_empty() {
            return Ok(());
        }
        bail!(
            "{} holds another refinement's rows: {}. Keep it (the same command with its flags \
             goes on from it), move the folder {} away to make this one ({}), or pass --force \
             to replace it",
            combined.display(),
            diffs.join("; "),
            combined.parent().unwrap_or(Path::new(".")).display(),
            self.flags()
        )
    }

    /// Refuses round `round`'s directory `dir` when it holds another
    /// refinement's round (its rows or its unfinished run were made for
    /// other points than `rcfg`'s).
    fn refuse_another_round(&self, dir: &Path, round: u64, rcfg: &ScanConfig) -> Result<()> {
        let ours = rcfg.to_toml();
        let theirs = {
            let samples = dir.join("samples.parquet");
            let manifest = dir.join(".partial").join("manifest.json");
            if samples.exists() {
                parquet::open(&samples, 1)
                    .ok()
                    .and_then(|i| i.metadata.get(META_CONFIG).cloned())
            } else if manifest.exists() {
                rtw_engine::scan::checkpoint::read_manifest(&manifest)
                    .ok()
                    .map(|m| m.config)
            } else {
                return Ok(());
            }
        };
        if theirs.as_deref() == Some(ours.as_str()) {
            return Ok(());
        }
        bail!(
            "{} holds round {round} of another refinement of this scan (other points: another \
             --budget, --rounds or --seed than this one's {}, or other rows before it). Finish \
             that refinement with its own flags, move the folder {} away to make this one, or \
             pass --force to discard that round",
            dir.display(),
            self.flags(),
            dir.parent().unwrap_or(Path::new(".")).display()
        )
    }
}

/// The sizes of the rounds: `budget` split into `rounds`, the first ones one
/// larger when it does not divide.
pub(crate) fn round_sizes(budget: u64, rounds: u64) -> Vec<u64> {
    (0..rounds)
        .map(|r| budget / rounds + u64::from(r < budget % rounds))
        .collect()
}

/// The uniform axes of a scan `(param, lo, hi)`; refuses grid axes (a
/// refinement moves every varied input continuously).
fn uniform_axes(cfg: &ScanConfig) -> Result<Vec<(Param, f64, f64)>> {
    let mut axes = Vec::new();
    for (p, axis) in Param::ALL.into_iter().zip(&cfg.params) {
        match axis {
            Axis::Fixed(_) => {}
            Axis::Uniform { lo, hi } => axes.push((p, *lo, *hi)),
            _ => bail!(
                "refine needs a scan whose inputs are fixed or {{ uniform = [lo, hi] }}: `{}` is a grid",
                p.name()
            ),
        }
    }
    if axes.is_empty() {
        bail!("refine needs a scan with at least one uniform input: every input is fixed");
    }
    Ok(axes)
}

/// The rows of a scan file as unit-cube points of `axes` and label indices,
/// appended to `x` and `labels`.
fn read_rows(
    path: &Path,
    axes: &[(Param, f64, f64)],
    x: &mut Vec<Vec<f64>>,
    labels: &mut Vec<usize>,
) -> Result<()> {
    let (input, _) = open_scan(path)?;
    for batch in input.reader {
        let batch = batch.with_context(|| format!("reading {}", path.display()))?;
        let cols = axes
            .iter()
            .map(|(p, _, _)| f64_column(&batch, p.name()))
            .collect::<Result<Vec<_>>>()
            .with_context(|| path.display().to_string())?;
        for r in 0..batch.num_rows() {
            x.push(
                cols.iter()
                    .zip(axes)
                    .map(|(c, (_, lo, hi))| ((c.value(r) - lo) / (hi - lo)).clamp(0.0, 1.0))
                    .collect(),
            );
        }
        labels.extend(
            label_column(&batch)
                .with_context(|| path.display().to_string())?
                .into_iter()
                .map(label_index),
        );
    }
    Ok(())
}

/// The config of round `round` with `points`: see the module's text.
fn round_config(cfg: &ScanConfig, round: u64, seed: u64, points: Vec<Params>) -> ScanConfig {
    let mut bytes = seed.to_le_bytes().to_vec();
    for p in &points {
        for q in Param::ALL {
            bytes.extend(p[q].to_bits().to_le_bytes());
        }
    }
    let mut c = cfg.clone();
    c.name = Some(format!(
        "{}+refine-{round}-{:016x}",
        cfg.name.as_deref().unwrap_or("scan"),
        fnv1a64(&bytes)
    ));
    c.samples = points.len() as u64;
    c.sampling = Sampling::Points;
    c.points = Some(points.into());
    c
}

/// The directory of round `round`.
pub(crate) fn round_dir(dir: &Path, round: u64) -> PathBuf {
    dir.join("refine").join(format!("round-{round:03}"))
}

/// Runs the rounds that are not complete yet, then writes the combined file.
pub fn refine(r: &Refine, sim: Simulator, run: &Run) -> Result<RefineStatus> {
    let (stop, progress) = (run.stop, run.progress);
    check_budget(r.budget, r.rounds)?;
    let base = r.dir.join("samples.parquet");
    let (input, cfg) = open_scan(&base)?;
    if input.rows > MAX_BASE_ROWS {
        bail!(
            "{}: {} rows is more than refine reads: at most {MAX_BASE_ROWS} (held in memory for \
             the neighbour search); refine a smaller scan",
            base.display(),
            input.rows
        );
    }
    let base_hash = input
        .metadata
        .get(META_CONTENT_HASH)
        .cloned()
        .unwrap_or_default();
    drop(input);
    let axes = uniform_axes(&cfg)?;
    let combined = r.dir.join("refine").join("samples.parquet");
    let _lock = Lock::for_result(&combined, &format!("refining {}", r.dir.display()))?;
    check_destination(&combined, FileKind::Scan, &[&base], "DIR", r.run.force)?;
    let ours = Identity::of(r, &base_hash);
    if !r.run.force {
        ours.refuse_another_at(&combined)?;
    }
    let fixed = Sampler::new(&cfg).params(0);
    let (mut x, mut labels) = (Vec::new(), Vec::new());
    read_rows(&base, &axes, &mut x, &mut labels)?;
    let mut files = vec![base];
    for (round, n) in (1..).zip(round_sizes(r.budget, r.rounds)) {
        progress.stage(&format!(
            "round {round} of {}: choosing {n} points among {} candidates by their neighbours in \
             {} rows",
            r.rounds,
            propose::POOL as u64 * n,
            x.len()
        ));
        let Some(unit) = propose(
            &x,
            &labels,
            axes.len(),
            n as usize,
            r.seed,
            round,
            progress,
            stop,
        ) else {
            return Ok(RefineStatus::Interrupted { round });
        };
        let points: Vec<Params> = unit
            .iter()
            .map(|u| {
                let mut p = fixed;
                for ((q, lo, hi), v) in axes.iter().zip(u) {
                    p[*q] = (lo + v * (hi - lo)).clamp(*lo, *hi);
                }
                p
            })
            .collect();
        let rcfg = round_config(&cfg, round, r.seed, points);
        let dir = round_dir(&r.dir, round);
        let samples = dir.join("samples.parquet");
        if !is_complete(&samples, &rcfg.to_toml(), None) {
            if !r.run.force {
                ours.refuse_another_round(&dir, round, &rcfg)?;
            }
            let settings = RunSettings {
                out_dir: dir.clone(),
                ..r.run.clone()
            };
            let sampler = Sampler::new(&rcfg);
            progress.stage(&format!("round {round} of {}", r.rounds));
            let status = run_scan_with(&rcfg, &sampler, &settings, sim, run)?;
            if r.run.shard.is_some() || matches!(status, RunStatus::Interrupted { .. }) {
                return Ok(RefineStatus::Stopped { round, dir, status });
            }
        }
        read_rows(&samples, &axes, &mut x, &mut labels)?;
        files.push(samples);
    }
    let mut about = ours.to_json();
    about["files"] = files
        .iter()
        .map(|f| f.display().to_string())
        .collect::<Vec<_>>()
        .into();
    let mut all = cfg.clone();
    all.name = Some(format!("{}+refined", cfg.name.as_deref().unwrap_or("scan")));
    all.samples = x.len() as u64;
    all.sampling = Sampling::Random;
    all.points = None;
    let mut meta = metadata::scan_metadata(&all);
    meta.push(kv(META_REFINE, about.to_string()));
    renumber(&files, &combined, meta)?;
    Ok(RefineStatus::Complete {
        combined,
        rows: x.len() as u64,
    })
}

/// Concatenates scan files into `dest`, their `sample_id`s numbered `0 …`
/// in file order (every other value as it is).
fn renumber(files: &[PathBuf], dest: &Path, meta: Vec<KeyValue>) -> Result<()> {
    rtw_engine::files::remove_stray_temps(dest)?;
    let first = parquet::open(&files[0], READ_BATCH_ROWS)?;
    let schema = first.reader.schema();
    let props = parquet::writer_properties(&schema, MAX_ROW_GROUP_ROWS, meta);
    let mut out = ParquetFile::create(dest, schema.clone(), props)?;
    let (mut next, mut wall) = (0i64, 0.0);
    for f in files {
        let input = parquet::open(f, READ_BATCH_ROWS)?;
        wall += input
            .metadata
            .get(metadata::META_WALL_TIME)
            .and_then(|v| v.parse::<f64>().ok())
            .unwrap_or(0.0);
        for batch in input.reader {
            let batch = batch.with_context(|| format!("reading {}", f.display()))?;
            let n = batch.num_rows() as i64;
            let mut cols = batch.columns().to_vec();
            let at = schema.index_of("sample_id")?;
            cols[at] = Arc::new(Int64Array::from_iter_values(next..next + n));
            next += n;
            out.write(
                &RecordBatch::try_new(schema.clone(), cols)
                    .with_context(|| format!("{}: not the scan's columns", f.display()))?,
            )?;
        }
    }
    out.append_metadata(metadata::META_WALL_TIME, wall.to_string());
    out.finish()
}
