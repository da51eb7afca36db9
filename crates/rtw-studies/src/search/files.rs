//! A design search's files in its folder `OUT/`:
//! - `search.parquet`: one row per evaluated design, in order, with the
//!   settings, the options and every evaluation as JSON in its metadata
//!   (`rtw.design`); written again, atomically, after each generation,
//!   so a stopped search keeps every finished design and resumes from them;
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
/// and options (none when there is no `search.parquet`), read back from its
/// columns, bit for bit. A search of other settings is refused unless
/// `force` (then it is replaced).
pub fn stored(
    out: &Path,
    s: &SearchSettings,
    options: &Options,
    force: bool,
) -> Result<Vec<Evaluation>> {
    let path = search_path(out);
    if !path.exists() {
        return Ok(Vec::new());
    }
    let input = parquet::open(&path, 8192)?;
    let Some(json) = input.metadata.get(META_DESIGN).cloned() else {
        // Not a search: check_outputs refuses it (or --force replaces it).
        return Ok(Vec::new());
    };
    // The identity is compared as written: JSON text of the same settings
    // and options is the same text.
    if json != identity(s, options)? {
        if force {
            return Ok(Vec::new());
        }
        let theirs = serde_json::from_str::<serde_json::Value>(&json).unwrap_or_default();
        let name = theirs["settings"]["name"].as_str().unwrap_or_default();
        let ours: serde_json::Value = serde_json::from_str(&identity(s, options)?)?;
        bail!(
            "--out {}: holds the search {name:?} of other settings or options ({}): it would be \
             replaced; the same config, --set and --variant as there resume it; choose another \
             folder, or pass --force",
            out.display(),
            super::identity::differences(&theirs, &ours).join("; ")
        );
    }
    // The same settings, but perhaps not the same numbers: an evaluation is
    // what the build that made it computes.
    if let Err(e) = metadata::refuse_other_version(
        &format!(
            "--out {}: its stored evaluations and this search",
            out.display()
        ),
        &input.metadata,
        "the evaluations",
        "this search",
        "a search never resumes from another version's numbers: choose another folder, or pass \
         --force to compute the search anew",
    ) {
        return if force { Ok(Vec::new()) } else { Err(e) };
    }
    let mut evals = Vec::new();
    for batch in input.reader {
        evals.extend(evaluations_of(s, &batch?).with_context(|| format!("{}", path.display()))?);
    }
    Ok(evals)
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
/// that are not a search's; removes stray temporary files.
pub fn check_outputs(out: &Path, force: bool) -> Result<()> {
    let main = search_path(out);
    let outputs = [
        Output {
            path: main.clone(),
            flag: "--out",
            schema: search_schema(),
        },
        Output {
            path: designs_path(out),
            flag: "--out",
            schema: designs_schema(),
        },
        Output {
            path: archive_path(out),
            flag: "--out",
            schema: archive_schema(),
        },
    ];
    destination::check_outputs(
        &main,
        &outputs,
        FileKind::Design,
        "a design search",
        |l| l.starts_with(HEADING),
        force,
    )
}

/// The search of `s` into `out` ([`super::run`], then [`super::report`]):
/// the outputs checked first, an earlier run of the same settings resumed,
/// the evaluations written after each generation, and the four files
/// together at the end.
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
    let earlier = stored(out, s, options, force)?;
    if !earlier.is_empty() {
        progress.note(&format!(
            "resuming: {} designs kept from {}",
            earlier.len(),
            search_path(out).display()
        ));
    }
    let t0 = Instant::now();
    let mut write = |evals: &[Evaluation]| -> Result<()> {
        parquet::write_file(
            &main,
            &search_batch(s, evals),
            metadata(s, options, t0.elapsed().as_secs_f64())?,
        )
    };
    let search = super::run(s, options, &earlier, run, &mut write)?;
    let reported = super::report(&search, options, run)?;
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
    Ok((search, reported))
}
