//! The command line: `run`, `merge`, `simulate`, `cluster`, `summary`.

use crate::bifurcation;
use crate::config;
use crate::fake;
use crate::output::{self, JsonRow, TraceWriter, kv};
use crate::report::{self, clusters_markdown};
use crate::run::{self, ProgressMode, RunSettings, RunStatus};
use crate::shard::{self, Shard};
use anyhow::{Context, Result, anyhow, bail};
use clap::{Args, Parser, Subcommand};
use rtw_model::{Options, Outcome, Params};
use std::num::NonZeroUsize;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

/// Exit code of a command stopped by SIGINT (Ctrl-C), SIGTERM (what Slurm
/// and `kill` send) or SIGHUP (a closed terminal): 128 + SIGINT, for all three.
const EXIT_INTERRUPTED: u8 = 130;

/// The exit codes every command documents in its `--help`.
const EXIT_CODES: &str = "Exit status:\n  \
    0    success\n  \
    1    error: bad input (named with its valid range), a refusal to overwrite (see --force), a corrupt \
or unreadable file, an I/O failure\n  \
    2    bad command line (unknown flag, missing argument)\n  \
    130  interrupted by SIGINT (Ctrl-C), SIGTERM or SIGHUP; a scan keeps its finished chunks (finish it \
with --resume), any other command leaves no partial file";

/// The exit codes of `simulate`, which also fails when the run does not finish.
const EXIT_CODES_SIMULATE: &str = "Exit status:\n  \
    0    the simulation finished (whatever its outcome label)\n  \
    1    error: bad input, a refusal to overwrite (see --force), an oversized trace (see --trace-limit), \
or a simulation that did not finish (a `diverged` run: numerical failure or panic)\n  \
    2    bad command line\n  \
    130  interrupted by SIGINT, SIGTERM or SIGHUP (no partial trace is left)";

#[derive(Parser, Debug)]
#[command(
    name = "rtw-scan",
    version,
    about = "Seeded, parallel parameter scans of the RTW model, streamed to Parquet, with failure clustering.",
    long_about = "Seeded, parallel parameter scans of the rimless wheel-like tensegrity (RTW) model, streamed to \
                  Parquet, with outcome statistics and k-means clustering of the failures.\n\n\
                  A scan's rows depend only on (seed, sample_id): any thread count, an interrupted and resumed \
                  run, or a subset gives the same rows."
)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Run a scan from a TOML config: writes DIR/samples.parquet, DIR/summary.json, DIR/summary.md.
    #[command(long_about = "Run a scan from a TOML config.\n\n\
        Writes DIR/samples.parquet (one row per sample: inputs, derived parameters, outcome, every metric, \
        integrator work, wall time), DIR/summary.json and DIR/summary.md, and prints the summary. Finished chunks \
        are kept in DIR/.partial while the run goes on, so an interrupted run (Ctrl-C, kill) loses at most the \
        chunk in progress: finish it with --resume. A sample that panics or fails numerically becomes a \
        `diverged` row; the scan goes on.\n\n\
        Config keys: seed, samples, name (optional); [params] length, rho, alpha, fn, zeta, phi, each a number, \
        { uniform = [lo, hi] }, { linspace = [lo, hi, n] } or a list [a, b, ...] (grids combine as a product, each \
        grid point gets `samples` random draws); [cluster] k (default 2), restarts (default 10); [simulation]: \
        every rtw_model option (t_max, method, rtol, initial.omega, strings.rest_length_ratio, contact.mu, ...).\n\n\
        A run refuses to write into a directory holding another scan's results (another config hash, or \
        another --shard split) unless --force, and one process at a time writes a result (a lock file names \
        it). SIGINT, SIGTERM and SIGHUP stop it like Ctrl-C: the samples in flight finish, the finished chunks \
        are kept, exit status 130; a second signal quits at once. Progress goes to stderr, the summary to stdout.",
        after_help = EXIT_CODES)]
    Run(RunArgs),
    /// Merge the shards of a scan (DIR/part-K.parquet from `run --shard K/N`) into DIR/samples.parquet and its summary.
    #[command(
        long_about = "Merge the shards of a scan into DIR/samples.parquet, DIR/summary.json and DIR/summary.md.\n\n\
        The parts DIR/part-K.parquet written by `rtw-scan run CONFIG --shard K/N --out DIR` must all come from one \
        config (same config hash) and one rtw-scan version, with the same N, every shard 0..N-1 present and their \
        sample_ids exactly 0..n-1 once each; otherwise merge refuses, naming what is missing or mismatched, and \
        writes nothing. The merged rows are the rows of a single-machine run of the config. The parts are kept \
        (polars.scan_parquet(\"DIR/part-*.parquet\") reads them directly). A corrupt part (its rows do not \
        match their content hash) is refused, and so is a DIR/samples.parquet of another scan unless --force.",
        after_help = EXIT_CODES
    )]
    Merge(MergeArgs),
    /// Simulate one RTW and print its outcome and every metric.
    #[command(
        long_about = "Simulate one RTW and print its outcome and every metric.\n\n\
        The simulation options come from the [simulation] table of --config (default: the adopted model, docs/model.md §9) and \
        then the --set overrides, e.g. --set initial.omega=-3 --set contact.mu=0.8 --set strings.slack=true \
        --set method=dop853. Values are read as TOML values (inf, true, \"text\"); a value that is not one is taken \
        as a string.",
        after_help = EXIT_CODES_SIMULATE
    )]
    Simulate(SimulateArgs),
    /// Sweep one parameter with continuation on the step map: recorded steps, period, Floquet multipliers.
    #[command(
        long_about = "Sweep one parameter with continuation on the step map (a bifurcation diagram).\n\n\
        At each value, in order, the map starts from the previous value's last section point (the first value, \
        and a value where that fails, from the initial state: column `restarted`), runs --transient steps, records \
        --record steps (post-impact angular velocity of the new stance rod, step time), detects the period, and \
        solves a periodic gait by Newton for its Floquet multipliers (DOP853, rtol 1e-11). Writes FILE.parquet \
        (one row per value) and FILE.steps.parquet (one row per recorded step), and prints a summary. The base \
        point is Fig. 7(a); the simulation options are taken as by `simulate` (--config, --variant, --set).",
        after_help = EXIT_CODES
    )]
    Bifurcation(BifurcationArgs),
    /// Cluster the failed samples of a finished scan (k-means on standardized α, f_n, φ).
    #[command(after_help = EXIT_CODES)]
    Cluster(ClusterArgs),
    /// Recompute a finished scan's summary: prints it and rewrites summary.json and summary.md beside the file.
    #[command(after_help = EXIT_CODES)]
    Summary(SummaryArgs),
}

#[derive(Args, Debug)]
struct RunArgs {
    /// Scan config (TOML).
    config: PathBuf,
    /// Output directory [default: runs/<scan name>/: the config's name (or file stem), +VARIANT with
    /// --variant, +set-HASH with --set, so that no ad-hoc run lands in results/ or in another run's directory].
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// Worker threads [default: one per core; at most 4 per core]. The rows do not depend on it.
    #[arg(long, value_name = "N")]
    threads: Option<NonZeroUsize>,
    /// Layer a model variant file (configs/variants/*.toml: name, description, [simulation]) over the
    /// config's [simulation] table; the scan is named CONFIG-NAME+VARIANT-NAME.
    #[arg(long, value_name = "FILE")]
    variant: Option<PathBuf>,
    /// Override one simulation option after the variant (repeatable), e.g. initial.omega=-3.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
    /// Finish the interrupted run in DIR (keeps its finished chunks).
    #[arg(long)]
    resume: bool,
    /// Run only shard K of N (0-based): the K-th contiguous block of sample ids, into DIR/part-K.parquet; join the N parts with `rtw-scan merge DIR`.
    #[arg(long, value_name = "K/N")]
    shard: Option<Shard>,
    /// Write even into a directory that holds another scan's results (another config, another --shard
    /// split) or its unfinished run, replacing them.
    #[arg(long)]
    force: bool,
    /// Print no progress (errors and the interruption notice still go to stderr).
    #[arg(long)]
    quiet: bool,
    /// Rows per chunk and row group (a resumed run keeps its own).
    #[arg(long, hide = true, value_name = "N", default_value_t = NonZeroUsize::new(run::DEFAULT_CHUNK_SIZE).unwrap())]
    chunk_size: NonZeroUsize,
    /// Testing only: use the fake simulator, sleeping MS milliseconds per sample.
    #[arg(long, hide = true, value_name = "MS")]
    fake_sim: Option<u64>,
}

#[derive(Args, Debug)]
struct MergeArgs {
    /// The directory holding part-0.parquet … part-(N-1).parquet.
    dir: PathBuf,
    /// Replace a DIR/samples.parquet of another scan.
    #[arg(long)]
    force: bool,
    /// Print nothing on stderr but errors.
    #[arg(long)]
    quiet: bool,
}

#[derive(Args, Debug)]
struct SimulateArgs {
    /// Rod length L [m].
    #[arg(long)]
    length: f64,
    /// Mass per length ρ [kg/m].
    #[arg(long)]
    rho: f64,
    /// Connection ratio α, in [0, 0.5).
    #[arg(long)]
    alpha: f64,
    /// Eigen-frequency f_n [Hz].
    #[arg(long = "fn", value_name = "FN")]
    f_n: f64,
    /// Damping ratio ζ.
    #[arg(long)]
    zeta: f64,
    /// Slope φ [rad].
    #[arg(long, allow_negative_numbers = true)]
    phi: f64,
    /// Take the [simulation] options of this config file.
    #[arg(long, value_name = "FILE")]
    config: Option<PathBuf>,
    /// Override one simulation option (repeatable), e.g. contact.mu=0.8.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
    /// Print one JSON object: `outcome` (the label) and every metric, flattened, with the derived parameters.
    #[arg(long)]
    json: bool,
    /// Write the time series (one row per trace sample) to this Parquet file.
    #[arg(long, value_name = "FILE.parquet")]
    trace: Option<PathBuf>,
    /// Refuse a trace whose size before compression (samples × bytes per sample, estimated from
    /// t_max / trace_dt, or max_steps when trace_dt = 0) exceeds this, e.g. 500MB, 10GB.
    #[arg(long, value_name = "SIZE", default_value = "2GB", value_parser = output::parse_size)]
    trace_limit: u64,
    /// Write the trace even over a file that is not a trace.
    #[arg(long)]
    force: bool,
    /// Testing only: use the fake simulator.
    #[arg(long, hide = true)]
    fake_sim: bool,
}

#[derive(Args, Debug)]
struct BifurcationArgs {
    /// The swept parameter: length, rho, alpha, fn, zeta, phi or s (strings.rest_length_ratio).
    #[arg(long, default_value = "phi")]
    param: String,
    /// First value of the sweep.
    #[arg(long, allow_negative_numbers = true, default_value_t = 0.02)]
    from: f64,
    /// Last value of the sweep (from > to sweeps downwards).
    #[arg(long, allow_negative_numbers = true, default_value_t = 0.35)]
    to: f64,
    /// Number of values, from and to included.
    #[arg(long, default_value_t = 121)]
    points: usize,
    /// Base point: rod length L [m] (default: Fig. 7(a)).
    #[arg(long)]
    length: Option<f64>,
    /// Base point: mass per length ρ [kg/m].
    #[arg(long)]
    rho: Option<f64>,
    /// Base point: connection ratio α.
    #[arg(long)]
    alpha: Option<f64>,
    /// Base point: eigen-frequency f_n [Hz].
    #[arg(long = "fn", value_name = "FN")]
    f_n: Option<f64>,
    /// Base point: damping ratio ζ.
    #[arg(long)]
    zeta: Option<f64>,
    /// Base point: slope φ [rad].
    #[arg(long, allow_negative_numbers = true)]
    phi: Option<f64>,
    /// Take the [simulation] options of this config file.
    #[arg(long, value_name = "FILE")]
    config: Option<PathBuf>,
    /// Layer a model variant file (configs/variants/*.toml) over them.
    #[arg(long, value_name = "FILE")]
    variant: Option<PathBuf>,
    /// Override one simulation option (repeatable), e.g. strings.rest_length_ratio=0.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
    /// Steps iterated at each value before recording.
    #[arg(long, default_value_t = 200)]
    transient: usize,
    /// Steps recorded at each value (periods up to record/2, at most 12, are detected).
    #[arg(long, default_value_t = 48)]
    record: usize,
    /// Per-value output (FILE.steps.parquet and FILE.md are written beside it) [default: runs/bifurcation/PARAM.parquet].
    #[arg(long, value_name = "FILE.parquet")]
    out: Option<PathBuf>,
    /// Write even over files that are not this sweep's kind.
    #[arg(long)]
    force: bool,
    /// Print no per-value progress.
    #[arg(long)]
    quiet: bool,
}

#[derive(Args, Debug)]
struct ClusterArgs {
    /// A samples.parquet written by `rtw-scan run`.
    samples: PathBuf,
    /// Number of clusters [default: the config's cluster.k].
    #[arg(long)]
    k: Option<NonZeroUsize>,
    /// Print JSON instead of a table.
    #[arg(long)]
    json: bool,
    /// Also write each failed sample's cluster to this Parquet file (sample_id, cluster, cluster_name,
    /// outcome, alpha, fn, phi; the clustering as JSON in its `rtw.clusters` metadata).
    #[arg(long, value_name = "FILE.parquet")]
    assignments: Option<PathBuf>,
    /// Write the assignments even over a file that is not an assignments file (or over the input).
    #[arg(long)]
    force: bool,
}

#[derive(Args, Debug)]
struct SummaryArgs {
    /// A samples.parquet written by `rtw-scan run`.
    samples: PathBuf,
    /// Number of failure clusters [default: the config's cluster.k].
    #[arg(long)]
    k: Option<NonZeroUsize>,
    /// Print the summary as JSON (what summary.json holds) instead of Markdown.
    #[arg(long)]
    json: bool,
    /// Write summary.json and summary.md even when they are another file's summary.
    #[arg(long)]
    force: bool,
}

/// Parses the command line, runs it, and turns errors into a message and
/// exit code 1.
pub fn main() -> ExitCode {
    let cli = Cli::parse();
    if let Err(e) = install_signal_handler() {
        eprintln!("error: {e:#}");
        return ExitCode::FAILURE;
    }
    let result = match cli.command {
        Command::Run(a) => cmd_run(a),
        Command::Merge(a) => cmd_merge(a),
        Command::Simulate(a) => cmd_simulate(a),
        Command::Bifurcation(a) => cmd_bifurcation(a),
        Command::Cluster(a) => cmd_cluster(a),
        Command::Summary(a) => cmd_summary(a),
    };
    result.unwrap_or_else(|e| {
        eprintln!("error: {e:#}");
        ExitCode::FAILURE
    })
}

/// Set by the first signal of a `run`, which then stops after the samples
/// in flight.
static STOP: AtomicBool = AtomicBool::new(false);
/// Whether the command in progress stops gracefully on a first signal
/// (`run`); every other command removes its temporary files and exits.
static GRACEFUL: AtomicBool = AtomicBool::new(false);

/// SIGINT, SIGTERM and SIGHUP (ctrlc's `termination` feature) all end a
/// command the same way, with [`EXIT_INTERRUPTED`].
fn install_signal_handler() -> Result<()> {
    ctrlc::set_handler(|| {
        if GRACEFUL.load(Ordering::SeqCst) {
            if !STOP.swap(true, Ordering::SeqCst) {
                eprintln!(
                    "rtw-scan: interrupted: finishing the samples in flight (interrupt again to quit at once)"
                );
                return;
            }
            eprintln!("rtw-scan: second interrupt, exiting now");
        }
        output::remove_live_files();
        std::process::exit(EXIT_INTERRUPTED.into());
    })
    .context("cannot install the signal handler")
}

/// The default output directory of a run: `runs/NAME/`, NAME the scan's
/// name (the config's `name` or file stem, `+VARIANT` with a variant) and,
/// with `--set`, `+set-` and a hash of the overrides, so that runs with
/// different overrides never share a directory and no ad-hoc run writes
/// into `results/` (the committed results, which scripts write explicitly).
fn default_out_dir(
    cfg: &config::ScanConfig,
    config_path: &Path,
    sets: &[String],
) -> Result<PathBuf> {
    let stem = config_path
        .file_stem()
        .ok_or_else(|| anyhow!("config path {} has no file name", config_path.display()))?
        .to_string_lossy()
        .into_owned();
    let mut name = cfg.name.clone().unwrap_or(stem);
    if !sets.is_empty() {
        let h = config::fnv1a64(sets.join("\n").as_bytes());
        name += &format!("+set-{:08x}", h >> 32);
    }
    let name: String = name
        .chars()
        .map(|c| {
            if c == '/' || c == '\\' || c.is_control() {
                '_'
            } else {
                c
            }
        })
        .collect();
    let name = name.trim_start_matches('.');
    Ok(Path::new("runs").join(if name.is_empty() { "scan" } else { name }))
}

fn cmd_run(a: RunArgs) -> Result<ExitCode> {
    let cfg = config::load_layered(&a.config, a.variant.as_deref(), &a.set)?;
    run::check_threads(a.threads)?;
    let out = match a.out {
        Some(d) => d,
        None => default_out_dir(&cfg, &a.config, &a.set)?,
    };
    GRACEFUL.store(true, Ordering::SeqCst);
    let settings = RunSettings {
        out_dir: out.clone(),
        threads: a.threads,
        resume: a.resume,
        chunk_size: a.chunk_size,
        progress: if a.quiet {
            ProgressMode::Quiet
        } else {
            ProgressMode::Auto
        },
        shard: a.shard,
        force: a.force,
    };
    let status = match a.fake_sim {
        Some(ms) => {
            let delay = Duration::from_millis(ms);
            run::run_scan(&cfg, &settings, &|p, o| fake::simulate(p, o, delay), &STOP)?
        }
        None => run::run_scan(&cfg, &settings, &rtw_model::simulate, &STOP)?,
    };
    match status {
        RunStatus::Complete {
            samples,
            computed,
            rows,
        } => {
            if computed == 0 && a.resume && !a.quiet {
                eprintln!("rtw-scan: {} is already complete", samples.display());
            }
            if let Some(s) = a.shard {
                // One part is not the scan: the summary comes with `merge`.
                // (stdout: scripts grep it; it is the command's result.)
                println!(
                    "rtw-scan: shard {s}: {rows} rows in {}; when all {} shards are done: rtw-scan merge {}",
                    samples.display(),
                    s.count,
                    out.display()
                );
                return Ok(ExitCode::SUCCESS);
            }
            write_and_print_summary(&out, &samples)
        }
        RunStatus::Interrupted {
            chunks_done,
            chunks,
            partial,
        } => {
            let mut again = format!("rtw-scan run {}", a.config.display());
            if let Some(v) = &a.variant {
                again += &format!(" --variant {}", v.display());
            }
            for s in &a.set {
                again += &format!(" --set {s}");
            }
            let shard = a.shard.map_or(String::new(), |s| format!(" --shard {s}"));
            eprintln!(
                "rtw-scan: interrupted: {chunks_done} of {chunks} chunks kept in {}; finish with: {again} --out {}{shard} --resume",
                partial.display(),
                out.display()
            );
            Ok(ExitCode::from(EXIT_INTERRUPTED))
        }
    }
}

/// The end of a whole scan (`run`, `merge`): `summary.json` and `summary.md`
/// beside the samples file, and the summary printed.
fn write_and_print_summary(dir: &Path, samples: &Path) -> Result<ExitCode> {
    let summary = report::summarize(samples, None)?;
    report::write_summary(dir, &summary)?;
    print!("{}", summary.to_markdown());
    Ok(ExitCode::SUCCESS)
}

fn cmd_merge(a: MergeArgs) -> Result<ExitCode> {
    let merged = shard::merge_parts(&a.dir, a.force)?;
    if !a.quiet {
        eprintln!(
            "rtw-scan: merged {} shards, {} rows, into {}",
            merged.shards,
            merged.rows,
            merged.samples.display()
        );
    }
    write_and_print_summary(&a.dir, &merged.samples)
}

/// The simulation options of `simulate`: the config's [simulation] table, then `--set`.
fn simulate_options(config_file: Option<&Path>, sets: &[String]) -> Result<Options> {
    config::simulation_options(config_file, None, sets)
}

fn cmd_simulate(a: SimulateArgs) -> Result<ExitCode> {
    let params = Params::new(a.length, a.rho, a.alpha, a.f_n, a.zeta, a.phi)
        .map_err(|e| anyhow!("--{}: {} is invalid: must be {}", e.field, e.value, e.range))?;
    let options = simulate_options(a.config.as_deref(), &a.set)?;
    let mut trace = match &a.trace {
        Some(path) => {
            output::check_destination(path, output::FileKind::Trace, &[], "--trace", a.force)?;
            let rows = output::trace_rows_bound(&options);
            let bytes = rows as f64 * output::trace_row_bytes() as f64;
            if bytes > a.trace_limit as f64 {
                bail!(
                    "--trace {}: about {} ({rows} samples × {} bytes: t_max {} s / trace_dt {} s{}) is more \
                     than --trace-limit {}: raise trace_dt (--set trace_dt=...), lower t_max, or raise --trace-limit",
                    path.display(),
                    output::human_bytes(bytes),
                    output::trace_row_bytes(),
                    options.t_max,
                    options.trace_dt,
                    if options.trace_dt > 0.0 {
                        String::new()
                    } else {
                        format!(
                            ", i.e. one per step, up to max_steps = {}",
                            options.max_steps
                        )
                    },
                    output::human_bytes(a.trace_limit as f64)
                );
            }
            output::remove_stray_temps(path)?;
            let meta = vec![
                kv(output::META_VERSION, env!("CARGO_PKG_VERSION").into()),
                kv("rtw.params", serde_json::to_string(&params)?),
                kv("rtw.options", toml::to_string(&options)?),
            ];
            Some(
                TraceWriter::create(path, meta, a.trace_limit)
                    .with_context(|| format!("trace {}", path.display()))?,
            )
        }
        None => None,
    };
    let mut trace_error = None;
    let row = run::run_one(0, params, &options, |p: &Params, o: &Options| -> Outcome {
        if a.fake_sim {
            return fake::simulate(p, o, Duration::ZERO);
        }
        match trace.as_mut() {
            Some(w) => rtw_model::simulate_traced(p, o, &mut |s| {
                if trace_error.is_none() {
                    trace_error = w.push(s).err();
                }
            }),
            None => rtw_model::simulate(p, o),
        }
    });
    if let Some(e) = trace_error {
        return Err(e.context("writing the trace"));
    }
    if let (Some(w), Some(path)) = (trace, &a.trace) {
        let n = w.finish()?;
        eprintln!(
            "rtw-scan: trace of {n} samples written to {}",
            path.display()
        );
    }
    if a.json {
        println!("{}", serde_json::to_string_pretty(&JsonRow(&row))?);
    } else {
        print!("{}", output::to_text(&row));
    }
    match &row.message {
        Some(m) => {
            eprintln!("error: the simulation did not finish: {m}");
            Ok(ExitCode::FAILURE)
        }
        None => Ok(ExitCode::SUCCESS),
    }
}

fn cmd_bifurcation(a: BifurcationArgs) -> Result<ExitCode> {
    let d = Params::fig7a();
    let base = Params {
        length: a.length.unwrap_or(d.length),
        rho: a.rho.unwrap_or(d.rho),
        alpha: a.alpha.unwrap_or(d.alpha),
        f_n: a.f_n.unwrap_or(d.f_n),
        zeta: a.zeta.unwrap_or(d.zeta),
        phi: a.phi.unwrap_or(d.phi),
    };
    let options = config::simulation_options(a.config.as_deref(), a.variant.as_deref(), &a.set)?;
    let param = bifurcation::SweepParam::parse(&a.param)?;
    let sweep = bifurcation::Sweep::new(
        param,
        a.from,
        a.to,
        a.points,
        base,
        options,
        a.transient,
        a.record,
    )?;
    let out = a
        .out
        .unwrap_or_else(|| Path::new("runs/bifurcation").join(format!("{}.parquet", param.name())));
    bifurcation::check_outputs(&out, a.force)?;
    bifurcation::cmd(&sweep, &out, a.quiet)
}

fn cmd_cluster(a: ClusterArgs) -> Result<ExitCode> {
    let data = report::read_scan(&a.samples)?;
    let k =
        a.k.map_or(data.config.cluster.k as usize, NonZeroUsize::get);
    let clusters = data.clusters(Some(k))?;
    let failures = data.failures.seen();
    if let Some(path) = &a.assignments {
        output::check_destination(
            path,
            output::FileKind::Assignments,
            &[&a.samples],
            "--assignments",
            a.force,
        )?;
        let fc = clusters.as_ref().ok_or_else(|| {
            anyhow!(
                "--assignments: {failures} failed samples (collapse or stall) in {}, fewer than k = {k}: nothing to cluster",
                a.samples.display()
            )
        })?;
        let meta = vec![
            kv(output::META_VERSION, env!("CARGO_PKG_VERSION").into()),
            kv(output::META_SEED, data.config.seed.to_string()),
        ];
        output::remove_stray_temps(path)?;
        let written = || -> Result<()> {
            let mut w = output::AssignmentsWriter::create(path, fc, meta)?;
            data.for_each_assigned(fc, |f, c| w.write(f, c))?;
            w.finish()
        };
        written().with_context(|| format!("--assignments {}", path.display()))?;
    }
    if a.json {
        println!("{}", serde_json::to_string_pretty(&clusters)?);
    } else {
        print!("{}", clusters_markdown(k, clusters.as_ref(), failures));
    }
    Ok(ExitCode::SUCCESS)
}

fn cmd_summary(a: SummaryArgs) -> Result<ExitCode> {
    let dir = a
        .samples
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    if !a.force {
        report::check_summary_target(dir, &a.samples)?;
    }
    let summary = report::summarize(&a.samples, a.k.map(NonZeroUsize::get))?;
    report::write_summary(dir, &summary)?;
    if a.json {
        println!("{}", serde_json::to_string_pretty(&summary)?);
    } else {
        print!("{}", summary.to_markdown());
    }
    Ok(ExitCode::SUCCESS)
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    #[test]
    fn cli_is_well_formed() {
        Cli::command().debug_assert();
    }

    #[test]
    fn simulate_options_layer_config_and_sets() {
        let dir = tempfile::tempdir().unwrap();
        let f = dir.path().join("c.toml");
        std::fs::write(
            &f,
            "seed = 1\n[simulation]\nt_max = 5.0\ncontact.mu = 0.5\n",
        )
        .unwrap();
        let o = simulate_options(
            Some(&f),
            &["contact.mu=0.8".into(), "initial.omega=-3".into()],
        )
        .unwrap();
        assert_eq!((o.t_max, o.contact.mu, o.initial.omega), (5.0, 0.8, -3.0));
        let e = simulate_options(None, &["contact.mu=2".into()]).unwrap_err();
        assert!(
            format!("{e:#}").contains("simulation.contact.mu: 2 is invalid"),
            "{e:#}"
        );
    }
}
