//! # rtw-scan: the command line
//!
//! A thin layer in named stages: clap arguments (each
//! subcommand family's `…Args`, raw text) → `validate` (flag text → typed,
//! checked values: `--set KEY=VALUE` → typed overrides) and `values` (the
//! parsers of single flag values) → calls into the libraries' entries
//! (`rtw_engine::entry` for a scan, `rtw_studies` for the other studies), which
//! take only typed values; a handler prints what they return. This file holds the
//! command tree and the exit codes, `signal` the signal handling, and
//! `progress` the progress shown on stderr.
//!
//! The subcommands:
//!
//! | subcommand | file | the library entry it calls |
//! |---|---|---|
//! | `run` | `run.rs` | `rtw_engine::entry::scan::{check_outputs, run_scan, write_summary}` |
//! | `merge` | `run.rs` | `rtw_engine::entry::scan::{merge, write_summary}` |
//! | `simulate` | `simulate.rs` | `rtw_engine::scan::one::run_one` (the scan's own sample) |
//! | `summary` | `analysis.rs` | `rtw_engine::entry::summary::summary_to_files` |
//! | `cluster` | `analysis.rs` | `rtw_engine::entry::summary::cluster` |
//! | `refine` | `refine.rs` | `rtw_studies::refine::refine` |
//! | `sensitivity` | `sensitivity.rs` | `rtw_studies::sensitivity::analyse_to_file` |
//! | `bifurcation` | `bifurcation.rs` | `rtw_studies::bifurcation::run_to_files` |
//! | `continuation` | `continuation.rs` | `rtw_studies::continuation::run_to_files` |
//! | `basin` | `basin.rs` | `rtw_studies::basin::run_to_files` |
//! | `profile` | `profile.rs` | `rtw_studies::profile::run_to_files` |
//! | `design` | `design.rs` | `rtw_studies::search::files::run_to_files` |

/// `print!` to stdout through [`signal::print_out`]: a closed stdout ends
/// the command quietly (exit 141) instead of a panic. Every command's
/// output to stdout goes through it or [`outln!`].
macro_rules! out {
    ($($arg:tt)*) => {
        $crate::signal::print_out(format_args!($($arg)*))
    };
}

/// `println!` to stdout through [`signal::print_out`] (see [`out!`]).
macro_rules! outln {
    ($($arg:tt)*) => {
        $crate::signal::print_out(format_args!("{}\n", format_args!($($arg)*)))
    };
}

mod analysis;
mod basin;
mod bifurcation;
mod continuation;
mod design;
mod profile;
mod progress;
mod refine;
mod run;
mod sensitivity;
mod signal;
mod simulate;
mod validate;
mod values;

use analysis::{ClusterArgs, SummaryArgs};
use basin::BasinArgs;
use bifurcation::BifurcationArgs;
use clap::{Arg, ArgAction, ArgMatches, CommandFactory, FromArgMatches, Parser, Subcommand};
use continuation::ContinuationArgs;
use design::DesignArgs;
use profile::ProfileArgs;
use refine::RefineArgs;
use rtw_engine::scan::one::Simulator;
use rtw_model::{Options, Outcome, Params};
use run::{MergeArgs, RunArgs};
use sensitivity::SensitivityArgs;
use signal::install_signal_handler;
use simulate::SimulateArgs;
use std::process::ExitCode;
use std::time::Duration;

/// The exit codes every command documents in its `--help`.
const EXIT_CODES: &str = "Exit status:\n  \
    0    success\n  \
    1    error: bad input (named with its valid range), a refusal to overwrite (see --force), a corrupt \
or unreadable file, an I/O failure\n  \
    2    bad command line (unknown flag, missing argument)\n  \
    130  interrupted by SIGINT (Ctrl-C), SIGTERM or SIGHUP; a scan keeps its finished chunks (finish it \
with --resume), any other command leaves no partial file\n  \
    141  stdout was closed before all was printed (`| head`): the files written are kept";

/// The exit codes of `simulate`, which also fails when the run does not finish.
const EXIT_CODES_SIMULATE: &str = "Exit status:\n  \
    0    the simulation finished (whatever its outcome label)\n  \
    1    error: bad input, a refusal to overwrite (see --force), an oversized trace (see --trace-limit), \
or a simulation that did not finish (a `diverged` run: numerical failure or panic)\n  \
    2    bad command line\n  \
    130  interrupted by SIGINT, SIGTERM or SIGHUP (no partial trace is left)\n  \
    141  stdout was closed before all was printed (`| head`): a trace written is kept";

#[derive(Parser, Debug)]
#[command(
    name = "rtw-scan",
    version = rtw_engine::VERSION,
    about = "Seeded, parallel parameter scans of the RTW model, streamed to Parquet, with failure clustering.",
    long_about = "Seeded, parallel parameter scans of the rimless wheel-like tensegrity (RTW) model, streamed to \
                  Parquet, with outcome statistics and k-means clustering of the failures.\n\n\
                  A scan's rows depend only on (seed, sample_id): any thread count, an interrupted and resumed \
                  run, or a subset gives the same rows."
)]
pub(crate) struct Cli {
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
        chunks in progress (the workers take the samples in order: those of the samples in flight, one per \
        worker): finish it with --resume. Run again over its finished scan (the same config and rtw version), \
        it says the scan is complete and computes nothing (--force computes it anew). A sample that panics or fails numerically becomes a `diverged` row; \
        the scan goes on.\n\n\
        Config keys: seed, samples, name (optional), sampling (random, sobol, halton, lhs, grid or saltelli: the \
        design of the uniform axes, docs/cli.md); [params] length, rho, alpha, fn, zeta, phi, each a number, \
        { uniform = [lo, hi] }, { linspace = [lo, hi, n] } or a list [a, b, ...] (grids combine as a product, each \
        grid point gets `samples` random draws); [cluster] k (default 2), restarts (default 10); [simulation]: \
        every rtw_model option (t_max, method, rtol, initial.omega, strings.rest_length_ratio, contact.mu, ...): \
        configs/template.toml has every key with its unit, range and default.\n\n\
        A run refuses to write into a directory holding another scan's results (another config hash, or \
        another --shard split) unless --force, and one process at a time writes a result (a lock file names \
        it). SIGINT, SIGTERM and SIGHUP stop it like Ctrl-C: the samples in flight stop within moments (their \
        rows are dropped), the finished chunks are kept, exit status 130; a second signal quits at once. Progress goes to stderr, the summary to stdout.",
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
        The simulation options come from the [simulation] table of --config (default: the adopted model, docs/model.md §9), \
        then --variant (a configs/variants/*.toml layered over them), \
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
    /// Continue a gait's limit cycle in one input, stable and unstable: branches, bifurcations, curves in two inputs.
    #[command(
        long_about = "Continue a gait's limit cycle in one input by pseudo-arclength continuation on the step map.\n\n\
        Solves the limit cycle the start (default Fig. 7(a)) settles into, then follows its fixed point of the \
        step map's period-th power both ways in --param, stable and unstable, over [--from, --to], with Jacobians \
        from the variational equations. Folds, branch points, period doublings and Neimark–Sacker points are \
        located on the Floquet multipliers (test functions, bisection); at each period doubling it switches onto \
        the period-2 branch born there. A branch ends where the fixed point leaves the start's mode pattern \
        (which feet touch, how): the step map is not smooth there. With --curve P2, each fold and period doubling \
        of the branches through the start is continued in (--param, P2) over [--curve-from, --curve-to]: the \
        boundary of the region where the gait exists and is stable. Writes FILE.parquet (one row per branch point \
        and orbit step), FILE.special.parquet (bifurcations, branch starts and ends), FILE.curve.parquet (with \
        --curve) and FILE.md, and prints the summary. Options as `simulate` (--config, --variant, --set).",
        after_help = EXIT_CODES
    )]
    Continuation(ContinuationArgs),
    /// A slice of a gait's basin of attraction: a grid over two section coordinates, each point iterated and classified.
    #[command(
        long_about = "A slice of a gait's basin of attraction on the step map's section (docs/robustness.md).\n\n\
        Solves the limit cycle the design (default Fig. 7(a)) settles into, then offsets two of its section \
        coordinates (--x, --y: a rod's θ or ω) over a grid, every other coordinate held at the fixed point's value, \
        and iterates each point on the step map for at most --steps steps: `returns` when it comes within --tol of \
        the gait's orbit, `survives` when it takes every step without (the label and period of its last steps say \
        what it walks in), `fails` when a step fails, `infeasible` when a tip starts below the ground. Writes \
        FILE.parquet, one row per point (x, y, outcome, label, steps, distance, ...), and prints the counts. \
        Options as `simulate` (--config, --variant, --set).",
        after_help = EXIT_CODES
    )]
    Basin(BasinArgs),
    /// Cluster the failed samples of a finished scan (k-means on standardized α, f_n, φ).
    #[command(after_help = EXIT_CODES)]
    Cluster(ClusterArgs),
    /// Recompute a finished scan's summary: prints it and rewrites summary.json and summary.md beside the file.
    #[command(after_help = EXIT_CODES)]
    Summary(SummaryArgs),
    /// Sobol indices (first-order and total, bootstrap intervals) of a scan's outcome classes and outputs.
    #[command(
        long_about = "Sobol indices of a finished scan's outputs to its uniform inputs: each outcome label as an \
        indicator (failed samples included, never dropped), stable, failure, and speed, f_w and floquet_max \
        (where every row has one). A scan run with sampling = \"saltelli\" gets first-order and total indices \
        (SALib's sobol estimators); any other scan the given-data binned first-order index (SALib delta's S1; ST \
        is NaN). Writes FILE.parquet (output, parameter, S1, S1_conf, ST, ST_conf) and prints a table.",
        after_help = EXIT_CODES
    )]
    Sensitivity(SensitivityArgs),
    /// Add samples to a finished scan in rounds, where the labels of neighbouring samples disagree.
    #[command(
        long_about = "Add --budget samples to a finished scan in --rounds rounds, near the boundaries between \
        outcome labels (docs/refine.md): each round takes, from a pool of uniform candidates, those whose nearest \
        samples (unit box of the uniform inputs) disagree most on their label, farthest from any sample first, \
        with a tenth of its points uniform. \
        Round r is a deterministic function of the scan's rows, the earlier rounds' rows and --seed, and runs as \
        an ordinary scan in DIR/refine/round-RRR/ (chunks kept on interruption, --shard and merge as for run); \
        finished rounds are kept and a repeated command goes on from there. At the end DIR/refine/samples.parquet \
        holds every row, the new ones with sample_ids after the scan's.",
        after_help = EXIT_CODES
    )]
    Refine(RefineArgs),
    /// A design's gait along the slope: each change of label located by bisection, the stable intervals per gait.
    #[command(
        long_about = "The slope profile of one design: its gait at each slope φ of [--from, --to], every change \
        of label located to --tol by bisection.\n\n\
        Simulates the design (the flags of `simulate`) on a grid of slopes at most --grid apart, then halves each \
        pair of neighbouring slopes whose labels differ until it is at most --tol wide (about log2(grid/tol) runs \
        per change), the runs of each round in parallel. Prints the stable slope intervals of each gait (walk, \
        skip, crawl), phi_min (the shallowest stable slope), the widest interval of stable slopes (phi_lo, \
        phi_hi) and the changes (φ_left, φ_right, label_left, label_right); with --out, writes every simulated \
        slope (a scan's columns) to FILE.parquet and the summary to FILE.md. Options as `simulate` (--config, \
        --variant, --set).",
        after_help = EXIT_CODES
    )]
    Profile(ProfileArgs),
    /// Search a box of designs for the one that walks on the widest range of slopes (slope_range), the
    /// shallowest (phi_min), the fastest (speed) or the longest before a fall on a rough slope (mfpt).
    #[command(
        long_about = "Search the box of designs (ρ, α, f_n, ζ) of CONFIG for those that maximise its objectives \
        (docs/design.md): slope_range (the widest interval of stable slopes, of one gait if `gait` is set), \
        phi_min (the shallowest stable slope, minimised), speed (at speed_phi) or mfpt (the mean first-passage \
        time at mfpt_phi on a rough slope of robustness.sigma, set with --set). Each candidate is judged by its \
        slope profile (as `profile`); a design with no stable slope falls, and the search learns where designs \
        fall and draws again there rather than scoring a fall. Candidates come from CMA-ES (method = \"cmaes\"), \
        from a MAP-Elites archive (method = \"archive\") or, as the baseline, a Sobol sequence (method = \"sobol\"); \
        two objectives give a Pareto front. Writes OUT/search.parquet (every evaluation, after each generation: an \
        interrupted search resumes with the same command), OUT/designs.parquet (the reported designs, each profiled \
        again on the fine grid, phi_lo and phi_hi their widest stable interval), OUT/archive.parquet (the best \
        design of each cell: where it works × how much of it walks) and OUT/search.md. The model: the config's [simulation] table, then --variant and --set.",
        after_help = EXIT_CODES
    )]
    Design(DesignArgs),
}

/// Parses the command line, runs it, and turns errors into a message and
/// exit code 1.
pub fn main() -> ExitCode {
    run_command(Cli::command())
}

/// The test build of the command, `rtw-scan-test` (its own package, so
/// that neither a plain build nor `cargo install` makes it): `main` with the
/// hidden flag `--fake-sim` on `run`, `refine` and `simulate` (the engine's
/// stand-in simulator) and the engine's test pauses (`RTW_SCAN_PAUSE`)
/// allowed. The flags are added here at run time rather than behind a
/// feature: a feature would compile this library a second time for the
/// tests; `rtw-scan`'s command never has them.
#[doc(hidden)]
pub fn test_main() -> ExitCode {
    rtw_engine::allow_test_pauses();
    run_command(with_test_flags(Cli::command()))
}

/// The stand-in simulator the test build's `--fake-sim` asks for, sleeping
/// that long a sample; `None` for the model (always, in `rtw-scan`).
type FakeSim = Option<Duration>;

/// The id of the test build's `--fake-sim`.
const FAKE_SIM: &str = "fake_sim";

/// `cli` with the test build's hidden flags.
fn with_test_flags(cli: clap::Command) -> clap::Command {
    let sleeping = || {
        Arg::new(FAKE_SIM)
            .long("fake-sim")
            .value_name("MS")
            .value_parser(clap::value_parser!(u64))
            .hide(true)
            .help("Testing only: use the fake simulator, sleeping MS milliseconds per sample.")
    };
    cli.mut_subcommand("run", |c| c.arg(sleeping()))
        .mut_subcommand("refine", |c| c.arg(sleeping()))
        .mut_subcommand("simulate", |c| {
            c.arg(
                Arg::new(FAKE_SIM)
                    .long("fake-sim")
                    .action(ArgAction::SetTrue)
                    .hide(true)
                    .help("Testing only: use the fake simulator."),
            )
        })
}

/// What the subcommand's `--fake-sim` asked for, if the command has it.
fn fake_sim(m: &ArgMatches) -> FakeSim {
    let (_, sub) = m.subcommand()?;
    if let Ok(Some(&ms)) = sub.try_get_one::<u64>(FAKE_SIM) {
        return Some(Duration::from_millis(ms));
    }
    matches!(sub.try_get_one::<bool>(FAKE_SIM), Ok(Some(true))).then_some(Duration::ZERO)
}

/// Calls `f` with the simulator of a scan or refinement: the model's, or the
/// engine's stand-in where `--fake-sim` asked for it.
fn with_simulator<R>(fake: FakeSim, f: impl FnOnce(Simulator) -> R) -> R {
    match fake {
        Some(delay) => f(&move |p: &Params, o: &Options| -> Outcome {
            rtw_engine::fake::simulate(p, o, delay)
        }),
        None => f(&rtw_model::simulate),
    }
}

/// Parses the command line with `cli` (clap's errors and `--help` exit
/// here, as `Parser::parse` does), runs it, and turns errors into a message
/// and exit code 1.
fn run_command(mut cli: clap::Command) -> ExitCode {
    let matches = cli.get_matches_mut();
    let fake = fake_sim(&matches);
    let cli = Cli::from_arg_matches(&matches).unwrap_or_else(|e| e.format(&mut cli).exit());
    if let Err(e) = install_signal_handler() {
        eprintln!("error: {e:#}");
        return ExitCode::FAILURE;
    }
    let result = match cli.command {
        Command::Run(a) => run::cmd_run(a, fake),
        Command::Merge(a) => run::cmd_merge(a),
        Command::Simulate(a) => simulate::cmd_simulate(a, fake),
        Command::Bifurcation(a) => bifurcation::cmd_bifurcation(a),
        Command::Continuation(a) => continuation::cmd_continuation(a),
        Command::Basin(a) => basin::cmd_basin(a),
        Command::Cluster(a) => analysis::cmd_cluster(a),
        Command::Summary(a) => analysis::cmd_summary(a),
        Command::Sensitivity(a) => sensitivity::cmd_sensitivity(a),
        Command::Refine(a) => refine::cmd_refine(a, fake),
        Command::Profile(a) => profile::cmd_profile(a),
        Command::Design(a) => design::cmd_design(a),
    };
    result.unwrap_or_else(|e| {
        eprintln!("error: {}", rtw_engine::files::error_message(&e));
        ExitCode::FAILURE
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    #[test]
    fn cli_is_well_formed() {
        Cli::command().debug_assert();
    }

    /// `--fake-sim` exists only in the test build's command: `rtw-scan`
    /// refuses it as clap refuses any unknown flag, and the test build reads
    /// it on the three subcommands that take it, as milliseconds a sample
    /// (`simulate`'s is a bare switch, no delay).
    #[test]
    fn only_the_test_build_has_the_fake_simulator() {
        let run = ["rtw-scan", "run", "c.toml", "--out", "o", "--fake-sim", "7"];
        let refine = [
            "rtw-scan",
            "refine",
            "d",
            "--budget",
            "4",
            "--fake-sim",
            "0",
        ];
        let simulate = [
            "rtw-scan",
            "simulate",
            "--length",
            "0.8",
            "--rho",
            "2.5",
            "--alpha",
            "0.125",
            "--fn",
            "3.269",
            "--zeta",
            "0.0514",
            "--phi",
            "0.15",
            "--fake-sim",
        ];
        let args: [&[&str]; 3] = [&run, &refine, &simulate];
        for (argv, delay) in args.into_iter().zip([7, 0, 0]) {
            let e = Cli::command().try_get_matches_from(argv).unwrap_err();
            assert_eq!(
                e.kind(),
                clap::error::ErrorKind::UnknownArgument,
                "{argv:?}"
            );
            let m = with_test_flags(Cli::command())
                .try_get_matches_from(argv)
                .unwrap_or_else(|e| panic!("{argv:?}: {e}"));
            assert_eq!(fake_sim(&m), Some(Duration::from_millis(delay)), "{argv:?}");
            Cli::from_arg_matches(&m).unwrap();
            // Without the flag, the test build runs the model.
            let cut = argv.iter().position(|a| *a == "--fake-sim").unwrap();
            let m = with_test_flags(Cli::command())
                .try_get_matches_from(&argv[..cut])
                .unwrap();
            assert_eq!(fake_sim(&m), None, "{argv:?}");
        }
    }

    /// docs/cli.md is the flag reference: each subcommand's section names
    /// every flag it takes (hidden testing flags aside).
    #[test]
    fn docs_cli_md_names_every_flag_of_every_subcommand() {
        let doc = std::fs::read_to_string(
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/cli.md"),
        )
        .unwrap();
        let mut missing = Vec::new();
        for sub in Cli::command().get_subcommands() {
            let heading = format!("### `rtw-scan {}`", sub.get_name());
            let Some((_, section)) = doc.split_once(&heading) else {
                missing.push(format!("a section `{heading}`"));
                continue;
            };
            // The section ends at the next heading of its level or above.
            let end = ["\n### ", "\n## "]
                .iter()
                .filter_map(|h| section.find(h))
                .min()
                .unwrap_or(section.len());
            let section = &section[..end];
            let shown = sub.get_arguments().filter(|a| {
                !a.is_hide_set() && !["help", "version"].contains(&a.get_id().as_str())
            });
            for arg in shown {
                // A positional as the help shows it: its value name (an id
                // may differ from it, to keep clear of a flag's).
                let name = match arg.get_long() {
                    Some(long) => format!("`--{long}"),
                    None => match arg.get_value_names().and_then(|v| v.first()) {
                        Some(value) => format!("`{value}"),
                        None => format!("`{}", arg.get_id().as_str().to_uppercase()),
                    },
                };
                if !section.contains(&name) {
                    missing.push(format!("{}: {name}`", sub.get_name()));
                }
            }
        }
        assert!(
            missing.is_empty(),
            "docs/cli.md lacks:\n{}",
            missing.join("\n")
        );
    }

    /// `design --help` and `design -h` name every objective a config may
    /// ask for: the short help is the one a user sees first.
    #[test]
    fn design_help_names_every_objective() {
        let mut cli = Cli::command();
        let design = cli
            .find_subcommand_mut("design")
            .expect("a design subcommand");
        let helps = [
            ("--help", design.render_long_help().to_string()),
            ("-h", design.render_help().to_string()),
        ];
        for (flag, help) in helps {
            for o in rtw_studies::search::Objective::ALL {
                assert!(
                    help.contains(o.as_str()),
                    "design {flag} does not name {}:\n{help}",
                    o.as_str()
                );
            }
        }
    }

    /// One flag for one idea: every subcommand that takes simulation options
    /// takes them the same three ways (config, variant, set).
    #[test]
    fn model_options_are_spelled_alike_in_every_subcommand() {
        for sub in Cli::command().get_subcommands() {
            // By id: `run` takes its config as its argument, the others as --config.
            let ids: Vec<&str> = sub.get_arguments().map(|a| a.get_id().as_str()).collect();
            if ids.contains(&"set") {
                for flag in ["config", "variant", "set"] {
                    assert!(
                        ids.contains(&flag),
                        "{} takes --set but not --{flag}",
                        sub.get_name()
                    );
                }
            }
        }
    }
}
