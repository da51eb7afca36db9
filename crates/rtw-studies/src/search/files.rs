//! A design search's files in its folder `OUT/`:
//! - `search.parquet`: one row per evaluated design, in order, with the
//!   settings and the options as JSON in its metadata (`rtw.design`);
//! - while the search runs, `search.part-NNNNNN.parquet`: after each
//!   generation its new designs, appended as one more small file (so the
//!   writes stay proportional to the designs, not to their square), each
//!   atomic and with `search.parquet`'s columns and metadata. A search that
//!   ends or is stopped merges them into `search.parquet` and removes them;
//!   one that is killed leaves them, and the same command resumes from
//!   `search.parquet` and its parts together;
//! - `designs.parquet`: the reported designs (the front, or the best), each
//!   with the widest stable interval of its profile made again on the fine
//!   grid (`phi_lo`, `phi_hi`), beside what the search found;
//! - `archive.parquet`: the archive (`archive.rs`), one row per elite: its
//!   sub-search, its cell, and its evaluation;
//! - `search.md`: the summary.
//!
//! Their columns are `columns.rs`'s.
//!
//! The four appear together at the end; an earlier `search.parquet` of
//! other settings is refused unless `force`.

pub use super::columns::{archive_batch, reported_batch, search_batch};
pub(crate) use super::columns::{archive_schema, designs_schema, search_schema};
use super::summary::HEADING;
pub use super::summary::markdown;
use super::{Evaluation, Reported, Search, SearchSettings};
use anyhow::{Context, Result, bail};
use arrow_array::RecordBatch;
use rtw_engine::config::variant::ModelChoices;
use rtw_engine::files::FileSet;
use rtw_engine::io::destination::{self, Output};
use rtw_engine::io::metadata::{
    self, FileKind, META_DESIGN, META_OPTIONS, META_VARIANT, META_VERSION, META_WALL_TIME, VERSION,
    kv,
};
use rtw_engine::io::parquet;
use rtw_engine::scan::Run;
use rtw_engine::scan::lock::Lock;
use rtw_model::Options;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The evaluations file in `out`.
pub fn search_path(out: &Path) -> PathBuf {
    out.join("search.parquet")
}

/// The `k`-th part of the evaluations in `out` (from 1), written while the
/// search runs.
pub fn part_path(out: &Path, k: usize) -> PathBuf {
    out.join(format!("{PART_PREFIX}{k:06}.parquet"))
}

const PART_PREFIX: &str = "search.part-";

/// The parts of the evaluations in `out`, with their numbers, in order.
fn parts(out: &Path) -> Result<Vec<(usize, PathBuf)>> {
    let Ok(entries) = std::fs::read_dir(out) else {
        return Ok(Vec::new());
    };
    let mut found = Vec::new();
    for entry in entries {
        let entry = entry.with_context(|| format!("cannot list {}", out.display()))?;
        let name = entry.file_name();
        let Some(k) = name
            .to_str()
            .and_then(|n| n.strip_prefix(PART_PREFIX))
            .and_then(|n| n.strip_suffix(".parquet"))
            .filter(|k| k.len() == 6 && k.bytes().all(|b| b.is_ascii_digit()))
            .and_then(|k| k.parse().ok())
        else {
            continue;
        };
        found.push((k, entry.path()));
    }
    found.sort();
    Ok(found)
}

/// The number of the part a search writes next, after `parts`: where its
/// run appends, and the one a kill can have left half-written.
fn next_part(parts: &[(usize, PathBuf)]) -> usize {
    parts.last().map_or(1, |(k, _)| k + 1)
}

/// The reported designs' file in `out`.
pub fn designs_path(out: &Path) -> PathBuf {
    out.join("designs.parquet")
}

/// The archive's file in `out`.
pub fn archive_path(out: &Path) -> PathBuf {
    out.join("archive.parquet")
}

/// The search's identity as JSON ([`META_DESIGN`]): its settings and options.
fn identity(s: &SearchSettings, options: &Options) -> Result<String> {
    Ok(serde_json::json!({
        "settings": s,
        "options": toml::to_string(options)?,
    })
    .to_string())
}

fn metadata(
    s: &SearchSettings,
    options: &Options,
    wall: f64,
) -> Result<Vec<::parquet::file::metadata::KeyValue>> {
    Ok(vec![
        kv(META_VERSION, VERSION.into()),
        kv(META_DESIGN, identity(s, options)?),
        kv(META_OPTIONS, toml::to_string(options)?),
        kv(META_VARIANT, ModelChoices::of(options).to_string()),
        kv(META_WALL_TIME, format!("{wall:.3}")),
    ])
}

/// The evaluations stored in `out` by an earlier run of the same settings
/// and options, in `search.parquet` and its parts (none when there are
/// none), read back from their columns, bit for bit, in index order (a
/// design stored twice, by a stop inside a generation and the resumed run,
/// is one). A search of other settings or of another version is refused
/// unless `force`; then its files are not read, and its parts are returned
/// as stale (to remove), its `search.parquet` replaced at the end.
pub fn stored(out: &Path, s: &SearchSettings, options: &Options, force: bool) -> Result<Stored> {
    let main = search_path(out);
    let parts = parts(out)?;
    let mut evals = std::collections::BTreeMap::new();
    let mut stale = Vec::new();
    let files = main.exists().then_some(&main).into_iter();
    for path in files.chain(parts.iter().map(|(_, p)| p)) {
        match stored_in(path, out, s, options, force)? {
            Some(found) => evals.extend(found.into_iter().map(|e| (e.index, e))),
            None if path != &main => stale.push(path.clone()),
            None => {}
        }
    }
    Ok(Stored {
        evaluations: evals.into_values().collect(),
        next_part: next_part(&parts),
        stale,
    })
}

/// What [`stored`] found in a search's folder.
#[derive(Debug)]
pub struct Stored {
    /// The stored evaluations of this search, in index order.
    pub evaluations: Vec<Evaluation>,
    /// The number of the next part to write.
    pub next_part: usize,
    /// Parts of another search (or version) that `force` replaces.
    pub stale: Vec<PathBuf>,
}

/// The evaluations in one file of a search's folder; `None` when it is not
/// this search's and `force` lets it go.
fn stored_in(
    path: &Path,
    out: &Path,
    s: &SearchSettings,
    options: &Options,
    force: bool,
) -> Result<Option<Vec<Evaluation>>> {
    let input = parquet::open(path, 8192)?;
    let Some(json) = input.metadata.get(META_DESIGN).cloned() else {
        // Not a search: check_outputs refuses it (or --force replaces it).
        return Ok(None);
    };
    // The identity is compared as written: JSON text of the same settings
    // and options is the same text.
    if json != identity(s, options)? {
        if force {
            return Ok(None);
        }
        let theirs = serde_json::from_str::<serde_json::Value>(&json).unwrap_or_default();
        let name = theirs["settings"]["name"].as_str().unwrap_or_default();
        let ours: serde_json::Value = serde_json::from_str(&identity(s, options)?)?;
        bail!(
            "--out {}: {} holds the search {name:?} of other settings or options ({}): it would \
             be replaced; the same config, --set and --variant as there resume it; choose another \
             folder, or pass --force",
            out.display(),
            path.display(),
            super::identity::differences(&theirs, &ours).join("; ")
        );
    }
    // The same settings, but perhaps not the same numbers: an evaluation is
    // what the build that made it computes.
    if let Err(e) = metadata::refuse_other_version(
        &format!(
            "--out {}: its stored evaluations and this search",
            path.display()
        ),
        &input.metadata,
        "the evaluations",
        "this search",
        "a search never resumes from another version's numbers: choose another folder, or pass \
         --force to compute the search anew",
    ) {
        return if force { Ok(None) } else { Err(e) };
    }
    let mut evals = Vec::new();
    for batch in input.reader {
        evals.extend(evaluations_of(s, &batch?).with_context(|| format!("{}", path.display()))?);
    }
    Ok(Some(evals))
}

/// The evaluations of a batch of `search.parquet`'s rows.
fn evaluations_of(s: &SearchSettings, b: &RecordBatch) -> Result<Vec<Evaluation>> {
    use arrow_array::Array;
    use arrow_array::cast::AsArray;
    use arrow_array::types::{Float64Type, Int64Type};
    let col = |name: &str| {
        b.column_by_name(name)
            .with_context(|| format!("no column {name}"))
    };
    let f = |name: &str| -> Result<Vec<Option<f64>>> {
        Ok(col(name)?.as_primitive::<Float64Type>().iter().collect())
    };
    let i = |name: &str| -> Result<Vec<u64>> {
        Ok(col(name)?
            .as_primitive::<Int64Type>()
            .values()
            .iter()
            .map(|&v| v as u64)
            .collect())
    };
    let text = |name: &str| -> Result<Vec<Option<String>>> {
        let c = col(name)?.as_string::<i32>();
        Ok((0..c.len())
            .map(|k| c.is_valid(k).then(|| c.value(k).to_string()))
            .collect())
    };
    let (index, round, generation, runs) = (i("index")?, i("round")?, i("generation")?, i("runs")?);
    let [rho, alpha, f_n, zeta] = ["rho", "alpha", "fn", "zeta"].map(&f);
    let (rho, alpha, f_n, zeta) = (rho?, alpha?, f_n?, zeta?);
    let (phi_lo, phi_hi, phi_min, speed) = (f("phi_lo")?, f("phi_hi")?, f("phi_min")?, f("speed")?);
    let mfpt = f("mfpt")?;
    let (p_fall, score, walk_share) = (f("p_fall")?, f("score")?, f("walk_share")?);
    let (infeasible, labels) = (text("infeasible")?, text("label_at_speed_phi")?);
    let mfpt_labels = text("label_at_mfpt_phi")?;
    let parse = |l: &Option<String>| -> Result<Option<rtw_model::Label>> {
        l.as_deref()
            .map(|l| l.parse().map_err(|e| anyhow::anyhow!("{e}")))
            .transpose()
    };
    (0..b.num_rows())
        .map(|k| {
            let label = parse(&labels[k])?;
            let mut e = Evaluation {
                index: index[k],
                round: round[k],
                generation: generation[k],
                design: [rho[k], alpha[k], f_n[k], zeta[k]].map(Option::unwrap_or_default),
                p_fall: p_fall[k],
                runs: runs[k],
                phi_lo: phi_lo[k],
                phi_hi: phi_hi[k],
                phi_min: phi_min[k],
                walk_share: walk_share[k],
                label_at_speed_phi: label,
                speed: speed[k],
                label_at_mfpt_phi: parse(&mfpt_labels[k])?,
                mfpt: mfpt[k],
                infeasible: infeasible[k].clone(),
                values: Vec::new(),
                score: score[k],
            };
            if e.feasible() {
                e.values =
                    super::values_of(s, &e).context("a feasible design without its objectives")?;
            }
            Ok(e)
        })
        .collect()
}

/// Refuses, unless `force`, to write a search's files in `out` over files
/// that are not a search's (its parts among them); removes stray temporary
/// files, a part's that a kill cut short among them.
pub fn check_outputs(out: &Path, force: bool) -> Result<()> {
    let main = search_path(out);
    let output = |path: PathBuf, schema| Output {
        path,
        flag: "--out",
        schema,
    };
    let parts = parts(out)?;
    let next = part_path(out, next_part(&parts));
    let mut outputs = vec![
        output(main.clone(), search_schema()),
        output(designs_path(out), designs_schema()),
        output(archive_path(out), archive_schema()),
    ];
    outputs.extend(parts.into_iter().map(|(_, p)| output(p, search_schema())));
    destination::check_outputs(
        &main,
        &outputs,
        FileKind::Design,
        "a design search",
        |l| l.starts_with(HEADING),
        force,
    )?;
    // The one part a kill can have left half-written is the next one.
    rtw_engine::files::remove_stray_temps(&next)
}

/// Removes the parts `parts` (once their rows are in `search.parquet`, or
/// when `force` replaces another search's).
fn remove_parts(parts: &[PathBuf]) -> Result<()> {
    for p in parts {
        std::fs::remove_file(p).with_context(|| format!("cannot remove {}", p.display()))?;
    }
    Ok(())
}

/// The search of `s` into `out` ([`super::run`], then [`super::report`]):
/// the outputs checked first, an earlier run of the same settings resumed,
/// each generation's new evaluations appended as a part, and the four
/// files together at the end, the parts then removed. Stopped (in the
/// search or in the verification), it merges every stored evaluation into
/// `search.parquet` before it returns the stop.
pub fn run_to_files(
    s: &SearchSettings,
    options: &Options,
    out: &Path,
    force: bool,
    run: &Run,
) -> Result<(Search, Vec<Reported>)> {
    let progress = run.progress;
    // Refused before anything is made or read.
    super::budget::check(s, options)?;
    let main = search_path(out);
    let _lock = Lock::for_result(
        &main,
        &format!("running a design search into {}", out.display()),
    )?;
    check_outputs(out, force)?;
    let found = stored(out, s, options, force)?;
    remove_parts(&found.stale)?;
    let earlier = found.evaluations;
    if !earlier.is_empty() {
        progress.note(&format!(
            "resuming: {} designs kept from {}",
            earlier.len(),
            out.display()
        ));
    }
    let t0 = Instant::now();
    // Every evaluation stored so far, by index: what a stop merges.
    let mut kept: std::collections::BTreeMap<u64, Evaluation> =
        earlier.iter().map(|e| (e.index, e.clone())).collect();
    let mut next = found.next_part;
    let result = {
        let mut append = |evals: &[Evaluation]| -> Result<()> {
            let new: Vec<Evaluation> = evals
                .iter()
                .filter(|e| !kept.contains_key(&e.index))
                .cloned()
                .collect();
            if new.is_empty() {
                return Ok(());
            }
            parquet::write_file(
                &part_path(out, next),
                &search_batch(s, &new),
                metadata(s, options, t0.elapsed().as_secs_f64())?,
            )?;
            next += 1;
            kept.extend(new.into_iter().map(|e| (e.index, e)));
            Ok(())
        };
        super::run(s, options, &earlier, run, &mut append)
    };
    let parts: Vec<PathBuf> = parts(out)?.into_iter().map(|(_, p)| p).collect();
    // A stop, in the search or in the verification of its designs, merges
    // every stored design into search.parquet, where the command says they
    // are kept.
    let stopped = |e: anyhow::Error, evals: &[Evaluation]| -> Result<(Search, Vec<Reported>)> {
        if e.is::<rtw_engine::scan::workers::Stopped>() {
            parquet::write_file(
                &main,
                &search_batch(s, evals),
                metadata(s, options, t0.elapsed().as_secs_f64())?,
            )?;
            remove_parts(&parts)?;
        }
        Err(e)
    };
    let search = match result {
        Ok(search) => search,
        Err(e) => return stopped(e, &kept.into_values().collect::<Vec<_>>()),
    };
    let reported = match super::report(&search, options, run) {
        Ok(reported) => reported,
        Err(e) => return stopped(e, &search.evaluations),
    };
    let wall = t0.elapsed().as_secs_f64();
    let mut set = FileSet::default();
    parquet::add_file(
        &mut set,
        &main,
        &search_batch(s, &search.evaluations),
        metadata(s, options, wall)?,
    )?;
    parquet::add_file(
        &mut set,
        &designs_path(out),
        &reported_batch(s, &reported),
        metadata(s, options, wall)?,
    )?;
    parquet::add_file(
        &mut set,
        &archive_path(out),
        &archive_batch(s, &search.evaluations),
        metadata(s, options, wall)?,
    )?;
    set.add_bytes(
        &destination::summary_path(&main),
        markdown(&search, &reported).as_bytes(),
    )?;
    set.commit()?;
    remove_parts(&parts)?;
    Ok((search, reported))
}
