//! A design search's files in its folder `OUT/`:
//! - `search.parquet`: one row per evaluated design, in order, with the
//!   settings, the options and every evaluation as JSON in its metadata
//!   (`rtw.design`); written again, atomically, after each generation,
//!   so a stopped search keeps every finished design and resumes from them;
//! - `designs.parquet`: the reported designs (the front, or the best), each
//!   with the widest stable interval of its profile made again on the fine
//!   grid (`phi_lo`, `phi_hi`), beside what the search found;
//! - `search.md`: the summary.
//!
//! The three appear together at the end; an earlier `search.parquet` of
//! other settings is refused unless `force`.

pub use super::summary::markdown;
use super::summary::{HEADING, width};
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
use rtw_engine::io::table::{self, Column, Get, column};
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

/// A row of either file: an evaluation, the rod length, and (reported
/// designs) what the search had found.
struct Line {
    e: Evaluation,
    /// The gait the search is of (`None`: any stable gait).
    gait: Option<rtw_model::Label>,
    length: f64,
    found: Option<Evaluation>,
    checked: Option<super::check::Checked>,
}

fn design_columns() -> Vec<Column<Line>> {
    vec![
        column(
            "index",
            false,
            "1",
            "the design's place in the order of evaluation",
            Get::I64(|r| Some(r.e.index as i64)),
        ),
        column(
            "length",
            false,
            "m",
            "rod length L (fixed)",
            Get::F64(|r| Some(r.length)),
        ),
        column(
            "rho",
            false,
            "kg/m",
            "mass per length ρ of a rod",
            Get::F64(|r| Some(r.e.design[0])),
        ),
        column(
            "alpha",
            false,
            "1",
            "connection ratio α",
            Get::F64(|r| Some(r.e.design[1])),
        ),
        column(
            "fn",
            false,
            "Hz",
            "design eigen-frequency f_n",
            Get::F64(|r| Some(r.e.design[2])),
        ),
        column(
            "zeta",
            false,
            "1",
            "damping ratio ζ",
            Get::F64(|r| Some(r.e.design[3])),
        ),
        column(
            "feasible",
            false,
            "-",
            "whether every objective is defined (it does not fall)",
            Get::Bool(|r| Some(r.e.feasible())),
        ),
        column(
            "infeasible",
            true,
            "-",
            "why not: no stable slope (of the gait) in the range, or not that gait at speed_phi",
            Get::Str(|r| r.e.infeasible.as_deref()),
        ),
        column(
            "phi_lo",
            true,
            "rad",
            "the widest interval of stable slopes (of the gait, if the config names one): its lowest \
             simulated slope; in designs.parquet, the widest run of directly checked slopes with no \
             failure in the fine profile's interval",
            Get::F64(|r| r.e.phi_lo),
        ),
        column(
            "phi_hi",
            true,
            "rad",
            "its highest simulated slope",
            Get::F64(|r| r.e.phi_hi),
        ),
        column(
            "slope_range",
            true,
            "rad",
            "phi_hi − phi_lo",
            Get::F64(|r| width(&r.e)),
        ),
        column(
            "phi_min",
            true,
            "rad",
            "the shallowest stable slope (of the gait)",
            Get::F64(|r| r.e.phi_min),
        ),
        column(
            "label_at_speed_phi",
            true,
            "-",
            "the gait at speed_phi (objective speed)",
            Get::Str(|r| r.e.label_at_speed_phi.map(|l| l.as_str())),
        ),
        column(
            "speed",
            true,
            "m/s",
            "mean downhill speed at speed_phi",
            Get::F64(|r| r.e.speed),
        ),
        column(
            "label_at_mfpt_phi",
            true,
            "-",
            "the gait at mfpt_phi (objective mfpt)",
            Get::Str(|r| r.e.label_at_mfpt_phi.map(|l| l.as_str())),
        ),
        column(
            "mfpt",
            true,
            "1",
            "mean first-passage time (expected steps to fall) at mfpt_phi on a rough slope of \
             robustness.sigma (docs/robustness.md)",
            Get::F64(|r| r.e.mfpt),
        ),
        column(
            "runs",
            false,
            "1",
            "simulations spent on the design",
            Get::I64(|r| Some(r.e.runs as i64)),
        ),
    ]
}

fn search_columns() -> Vec<Column<Line>> {
    let mut c = design_columns();
    c.splice(
        1..1,
        [
            column(
                "round",
                false,
                "1",
                "the sub-search (weight) of a two-objective search",
                Get::I64(|r: &Line| Some(r.e.round as i64)),
            ),
            column(
                "generation",
                false,
                "1",
                "the generation within its sub-search",
                Get::I64(|r: &Line| Some(r.e.generation as i64)),
            ),
        ],
    );
    c.push(column(
        "p_fall",
        true,
        "1",
        "the learned probability that the design falls, when it was drawn (cmaes)",
        Get::F64(|r| r.e.p_fall),
    ));
    c.push(column("score", true, "1", "the value its sub-search maximised (normalised objective, or the weighted Chebyshev scalarisation)", Get::F64(|r| r.e.score)));
    c
}

fn reported_columns() -> Vec<Column<Line>> {
    let mut c = design_columns();
    c.extend([
        column(
            "found_phi_lo",
            true,
            "rad",
            "phi_lo of the search's own (coarser) profile",
            Get::F64(|r: &Line| r.found.as_ref()?.phi_lo),
        ),
        column(
            "found_phi_hi",
            true,
            "rad",
            "phi_hi of the search's own profile",
            Get::F64(|r: &Line| r.found.as_ref()?.phi_hi),
        ),
        column(
            "found_slope_range",
            true,
            "rad",
            "slope_range of the search's own profile",
            Get::F64(|r: &Line| width(r.found.as_ref()?)),
        ),
        column(
            "profile_phi_lo",
            true,
            "rad",
            "the fine profile's widest interval (of the gait), before the direct check",
            Get::F64(|r: &Line| Some(r.checked?.profile.0)),
        ),
        column(
            "profile_phi_hi",
            true,
            "rad",
            "its upper end",
            Get::F64(|r: &Line| Some(r.checked?.profile.1)),
        ),
        column(
            "checked_slopes",
            true,
            "1",
            "slopes of the fine profile's interval simulated directly (201 across it and every \
             multiple of 0.005 inside it)",
            Get::I64(|r: &Line| Some(r.checked?.slopes as i64)),
        ),
        column(
            "checked_failures",
            true,
            "1",
            "of them, not stable (for a search of one gait: not that gait): isolated failing \
             slopes the profile's grid did not resolve",
            Get::I64(|r: &Line| Some(r.checked?.failures as i64)),
        ),
        column(
            "gait",
            false,
            "-",
            "the gait phi_lo..phi_hi was checked for at every checked slope (\"any\": any \
             stable gait)",
            Get::Str(|r: &Line| Some(r.gait.map_or("any", |g| g.as_str()))),
        ),
        column(
            "phi_lo_end",
            true,
            "-",
            "how the interval ends at phi_lo: \"sharp\" (no slope below it holds the gait, \
             checked or profiled) or \"interleaved\" (some do, between failures)",
            Get::Str(|r: &Line| Some(r.checked?.ends().0)),
        ),
        column(
            "phi_hi_end",
            true,
            "-",
            "how it ends at phi_hi: \"sharp\" or \"interleaved\"",
            Get::Str(|r: &Line| Some(r.checked?.ends().1)),
        ),
    ]);
    c
}

/// `search.parquet`'s schema.
pub(crate) fn search_schema() -> arrow_schema::SchemaRef {
    table::schema(&search_columns())
}

/// `designs.parquet`'s schema.
pub(crate) fn designs_schema() -> arrow_schema::SchemaRef {
    table::schema(&reported_columns())
}

/// Every evaluation as a table: the columns of `search.parquet`
/// (docs/results-other-commands.md).
pub fn search_batch(s: &SearchSettings, evals: &[Evaluation]) -> RecordBatch {
    let rows: Vec<Line> = evals
        .iter()
        .map(|e| Line {
            e: e.clone(),
            gait: s.gait,
            length: s.length,
            found: None,
            checked: None,
        })
        .collect();
    let cols = search_columns();
    table::batch(&cols, table::schema(&cols), &rows)
}

/// The reported designs as a table: the columns of `designs.parquet`.
pub fn reported_batch(s: &SearchSettings, reported: &[Reported]) -> RecordBatch {
    let rows: Vec<Line> = reported
        .iter()
        .map(|r| Line {
            e: r.verified.clone(),
            gait: s.gait,
            length: s.length,
            found: Some(r.found.clone()),
            checked: r.checked,
        })
        .collect();
    let cols = reported_columns();
    table::batch(&cols, table::schema(&cols), &rows)
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
    let (p_fall, score) = (f("p_fall")?, f("score")?);
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
            schema: table::schema(&search_columns()),
        },
        Output {
            path: designs_path(out),
            flag: "--out",
            schema: table::schema(&reported_columns()),
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
/// the evaluations written after each generation, and the three files
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
    set.add_bytes(
        &destination::summary_path(&main),
        markdown(&search, &reported).as_bytes(),
    )?;
    set.commit()?;
    Ok((search, reported))
}
