//! `rtw._rtw`: the native layer of the Python package `rtw`
//! (`python/rtw/__init__.py` is its documented face).
//!
//! Only conversions and GIL handling live here: inputs and options are
//! checked by rtw-scan's config layers (the messages of the CLI; options
//! arrive as typed values, `options.rs`), runs and scans are rtw-scan's and
//! rtw-model's own code, results are typed objects (`types.rs`), and tables
//! cross into Python through the Arrow C data interface (arrow-pyarrow:
//! pyarrow imports the Rust buffers, no value is copied or boxed as a
//! Python object).

mod design;
mod geometry;
mod options;
mod page;
mod studies;
mod types;
mod views;

use arrow_array::RecordBatch;
use arrow_pyarrow::{IntoPyArrow, Table};
use design::DesignKeys;
use options::{PyConfig, PyOverrides};
use pyo3::exceptions::{PyKeyboardInterrupt, PyMemoryError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyInt, PyTuple};
use rtw_engine::config::count::count_usize;
use rtw_engine::config::layers::{
    load_layered, parse_layered, simulation_options, simulation_options_of,
};
use rtw_engine::config::params::checked_params;
use rtw_engine::io::{TraceNames, parse_size};
use rtw_engine::scan::Run;
use rtw_engine::scan::progress::Counter;
use rtw_engine::scan::scan_batch;
use rtw_engine::scan::single::{simulate_row, simulate_traced};
use rtw_engine::scan::workers::{Stopped, parse_threads};
use rtw_model::cycles::{CycleOptions, StepMap};
use rtw_model::outcome::{ContactFractions, StepShares};
use rtw_model::{Label, Options, Params, Physical, modal};
use std::collections::TryReserveError;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::mpsc::{RecvTimeoutError, channel};
use std::time::Duration;
use types::{DesignSearch, LimitCycle, Modes, Outcome, Profile};

/// How often a running scan looks for a signal (Ctrl-C) in Python.
const SIGNAL_POLL: Duration = Duration::from_millis(50);

/// How `rtw.trace` spells the settings of a trace's size.
const PYTHON_TRACE_NAMES: TraceNames = TraceNames {
    limit: "limit",
    dt: "dt",
};

/// Most settling steps of `limit_cycle` (as `bifurcation --transient`).
const MAX_SETTLE_STEPS: usize = 10_000_000;

/// An rtw error as Python's `ValueError`, with every context (`{:#}`); an
/// allocation that could not be made as `MemoryError`.
fn value_error(e: anyhow::Error) -> PyErr {
    if e.chain().any(|c| c.is::<TryReserveError>()) {
        return PyMemoryError::new_err(rtw_engine::error_message(&e));
    }
    PyValueError::new_err(rtw_engine::error_message(&e))
}

/// The six inputs and the layered options (config's `[simulation]`, variant,
/// the `options` dict), checked as `rtw-scan simulate` checks them.
fn inputs(
    values: [f64; 6],
    config: Option<Bound<'_, PyAny>>,
    variant: Option<PathBuf>,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<(Params, Options)> {
    let params = checked_params(values, "").map_err(value_error)?;
    Ok((params, model(config.as_ref(), variant, options)?))
}

/// The model's options: a config's `[simulation]` table (a path, TOML text
/// or a dict: [`PyConfig`]), then a variant file, then `options`.
fn model(
    config: Option<&Bound<'_, PyAny>>,
    variant: Option<PathBuf>,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<Options> {
    let config = PyConfig::new(config)?;
    let overrides = PyOverrides::new(options)?;
    simulation_options_of(
        config.as_ref().map(PyConfig::source),
        variant.as_deref(),
        overrides.layer(),
    )
    .map_err(value_error)
}

/// A batch as a `pyarrow.Table`, through the C data interface.
fn to_table(py: Python<'_>, batch: RecordBatch) -> PyResult<Bound<'_, PyAny>> {
    let schema = batch.schema();
    tables(py, vec![batch], schema)
}

/// Batches of one schema (its metadata kept) as a `pyarrow.Table`, through
/// the C data interface.
fn tables(
    py: Python<'_>,
    batches: Vec<RecordBatch>,
    schema: arrow_schema::SchemaRef,
) -> PyResult<Bound<'_, PyAny>> {
    Table::try_new(batches, schema)
        .map_err(|e| PyRuntimeError::new_err(e.to_string()))?
        .into_pyarrow(py)
}

/// A count's text for the library's parsers, which check it against its
/// range as they check a flag's value: a Python `int`'s digits (any size),
/// anything else as `repr` shows it (`2.5`, `True`, `'10'`), which no parser
/// takes for a count.
fn digits(value: &Bound<'_, PyAny>) -> PyResult<String> {
    let text = if value.is_instance_of::<PyInt>() && !value.is_instance_of::<PyBool>() {
        value.str()?
    } else {
        value.repr()?
    };
    Ok(text.to_string())
}

/// Runs `job` on a worker thread with the GIL released, handing it a cancel
/// flag. This thread polls Python's signal handlers every [`SIGNAL_POLL`]
/// and calls `tick` between polls; on an exception (KeyboardInterrupt, or
/// one `tick` raised) it sets the flag, waits for the job to stop, and
/// raises the exception.
fn interruptible<T: Send>(
    py: Python<'_>,
    job: impl FnOnce(&AtomicBool) -> T + Send,
    mut tick: impl FnMut() -> PyResult<()>,
) -> PyResult<T> {
    let cancel = AtomicBool::new(false);
    let (done, finished) = channel();
    std::thread::scope(|s| {
        let flag = &cancel;
        let worker = s.spawn(move || {
            let result = job(flag);
            // The receiver is gone only if this function already returned.
            let _ = done.send(());
            result
        });
        let mut finished = finished;
        loop {
            // The receiver is `Send` but not `Sync`: it goes into the
            // detached closure and comes back.
            let (wait, back) = py.detach(move || (finished.recv_timeout(SIGNAL_POLL), finished));
            finished = back;
            match wait {
                Err(RecvTimeoutError::Timeout) => {}
                Ok(()) | Err(RecvTimeoutError::Disconnected) => break,
            }
            if let Err(interrupt) = tick().and_then(|()| py.check_signals()) {
                cancel.store(true, Ordering::SeqCst);
                // What is in flight ends soon: a scan's samples at their runs'
                // next step (rtw_model::cancellable), a grid point, a resample.
                let _ = py.detach(|| worker.join());
                return Err(interrupt);
            }
        }
        py.detach(|| worker.join())
            .map_err(|_| PyRuntimeError::new_err("the worker thread panicked"))
    })
}

/// An rtw error as Python's, a study stopped by its cancel flag as
/// `KeyboardInterrupt` (only a signal sets it).
fn study_error(e: anyhow::Error) -> PyErr {
    if e.is::<Stopped>() {
        return PyKeyboardInterrupt::new_err(e.to_string());
    }
    value_error(e)
}

/// Tells Python what a study said since the last call (warnings as
/// `UserWarning`, notes to the `rtw` logger at INFO), then calls its
/// `progress(done, total)`, if any, once its total is known.
fn report(py: Python<'_>, progress: Option<&Bound<'_, PyAny>>, counter: &Counter) -> PyResult<()> {
    let said = counter.take_said();
    let logger = py.import("logging")?.call_method1("getLogger", ("rtw",))?;
    for note in said.notes {
        logger.call_method1("info", ("%s", note))?;
    }
    for warning in said.warnings {
        types::warn(py, Some(warning))?;
    }
    let total = counter.total.load(Ordering::Relaxed);
    match progress {
        Some(f) if total > 0 => f
            .call1((counter.done.load(Ordering::Relaxed), total))
            .map(drop),
        _ => Ok(()),
    }
}

/// One run: its row, the fields of `rtw-scan simulate --json`.
#[pyfunction]
#[pyo3(signature = (values, config, variant, options))]
fn simulate(
    py: Python<'_>,
    values: [f64; 6],
    config: Option<Bound<'_, PyAny>>,
    variant: Option<PathBuf>,
    options: Option<Bound<'_, PyDict>>,
) -> PyResult<Outcome> {
    let (params, options) = inputs(values, config, variant, options.as_ref())?;
    // Interruptible as the studies are: a run with a robustness measure (an
    // MFPT of thousands of batches) takes minutes.
    let row = interruptible(
        py,
        |cancel| rtw_model::cancellable(cancel, || simulate_row(params, &options)),
        || Ok(()),
    )?;
    // Cut short without a signal seen here: only a signal sets the flag.
    row.map(Outcome::new)
        .ok_or_else(|| PyKeyboardInterrupt::new_err("interrupted"))
}

/// One run's trace: a `pyarrow.Table` of the `simulate --trace` columns,
/// the run's row as JSON in its metadata (`rtw.outcome`). `limit` caps the
/// trace's size in memory before compression (`2GB`, `500MB`, bytes), as
/// `--trace-limit` does.
#[pyfunction]
#[pyo3(signature = (values, config, variant, options, limit))]
fn trace<'py>(
    py: Python<'py>,
    values: [f64; 6],
    config: Option<Bound<'_, PyAny>>,
    variant: Option<PathBuf>,
    options: Option<Bound<'py, PyDict>>,
    limit: String,
) -> PyResult<Bound<'py, PyAny>> {
    let limit = parse_size(&limit).map_err(|e| PyValueError::new_err(format!("limit: {e}")))?;
    let (params, options) = inputs(values, config, variant, options.as_ref())?;
    let batch = py
        .detach(|| simulate_traced(params, &options, limit, PYTHON_TRACE_NAMES))
        .map_err(value_error)?;
    to_table(py, batch)
}

/// A scan (config file `path` or TOML `text`, then variant and sets, then
/// the design keys `sampling`, `samples`, `seed` over the config's) as a
/// `pyarrow.Table` of the rows of `rtw-scan run`. It runs on a worker thread
/// (rayon inside) with the GIL released; this thread polls Python's signal
/// handlers every [`SIGNAL_POLL`], calls `progress(done, total)` (rows
/// computed, rows in all) when given, and on an exception (KeyboardInterrupt,
/// or one raised by `progress`) stops the scan, waits for the samples in
/// flight, and raises it. `progress` is called a last time once every row is in.
#[pyfunction]
#[pyo3(signature = (config, variant, options, threads, progress=None, sampling=None, samples=None, seed=None))]
#[allow(clippy::too_many_arguments)]
fn scan<'py>(
    py: Python<'py>,
    config: Bound<'py, PyAny>,
    variant: Option<PathBuf>,
    options: Option<Bound<'py, PyDict>>,
    threads: Option<Bound<'py, PyAny>>,
    progress: Option<Bound<'py, PyAny>>,
    sampling: Option<Bound<'py, PyAny>>,
    samples: Option<Bound<'py, PyAny>>,
    seed: Option<Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    let overrides = PyOverrides::new(options.as_ref())?;
    let sampling = match sampling {
        None => None,
        Some(s) => match s.extract::<String>() {
            Ok(name) => Some(name),
            Err(_) => {
                let shown = s.repr()?.to_string();
                return Err(value_error(design::invalid_sampling(&shown)));
            }
        },
    };
    let design = DesignKeys {
        sampling,
        samples: samples.as_ref().map(digits).transpose()?,
        seed: seed.as_ref().map(digits).transpose()?,
    };
    let cfg = match PyConfig::new(Some(&config))?.expect("given") {
        PyConfig::File(p) => load_layered(&p, variant.as_deref(), overrides.layer()),
        PyConfig::Text(t) => parse_layered(&t, variant.as_deref(), overrides.layer()),
    }
    .and_then(|cfg| design.apply(cfg))
    .map_err(value_error)?;
    let threads = match threads {
        None => None,
        Some(n) => Some(parse_threads(&digits(&n)?, "threads").map_err(value_error)?),
    };
    let total = cfg.total_rows().map_err(value_error)?;
    let rows_done = AtomicU64::new(0);
    let result = interruptible(
        py,
        |stop| scan_batch(&cfg, threads, stop, &rows_done),
        || match &progress {
            Some(f) => f
                .call1((rows_done.load(Ordering::Relaxed), total))
                .map(drop),
            None => Ok(()),
        },
    )?;
    match result.map_err(value_error)? {
        Some(batch) => {
            if let Some(f) = &progress {
                f.call1((rows_done.load(Ordering::Relaxed), total))?;
            }
            to_table(py, batch)
        }
        // Stopped without a signal seen here: only a signal sets `stop`.
        None => Err(PyKeyboardInterrupt::new_err("the scan was stopped")),
    }
}

/// The limit cycle the run from the options' initial state settles into
/// (rtw-model's step map: `settle_steps` steps, the period found on the
/// section, Newton on `Pⁿ(z) = z`, Floquet multipliers).
#[pyfunction]
#[pyo3(signature = (values, config, variant, options, settle_steps))]
fn limit_cycle(
    py: Python<'_>,
    values: [f64; 6],
    config: Option<Bound<'_, PyAny>>,
    variant: Option<PathBuf>,
    options: Option<Bound<'_, PyDict>>,
    settle_steps: Bound<'_, PyAny>,
) -> PyResult<LimitCycle> {
    let (params, options) = inputs(values, config, variant, options.as_ref())?;
    let settle_steps = count_usize(
        "settle_steps",
        &digits(&settle_steps)?,
        1..=MAX_SETTLE_STEPS,
        "",
    )
    .map_err(value_error)?;
    let cycle = CycleOptions {
        settle_steps,
        ..CycleOptions::default()
    };
    let lc = py
        .detach(|| StepMap::new(&params, &options, &cycle).limit_cycle(&options, &cycle))
        .map_err(|e| PyRuntimeError::new_err(format!("no limit cycle: {e}")))?;
    Ok(LimitCycle::new(&lc, lc.label(&options.labels).as_str()))
}

/// The eigen-frequencies of rtw-model's `modal`: S18's f_n, the approximate
/// 3-rotor model's modes and the free 9-DOF star's.
#[pyfunction]
#[pyo3(signature = (values, config, variant, options))]
fn modes(
    values: [f64; 6],
    config: Option<Bound<'_, PyAny>>,
    variant: Option<PathBuf>,
    options: Option<Bound<'_, PyDict>>,
) -> PyResult<Modes> {
    let (params, options) = inputs(values, config, variant, options.as_ref())?;
    let phys = Physical::new(&params, options.normalization, options.g);
    let approx = modal::approximate_modes(&phys, &options.strings);
    let star = modal::free_star_modes(&phys, &options.strings);
    Ok(Modes::new(modal::s18_frequency(&phys), &approx, &star))
}

/// The label rtw-model gives a stable gait (Table S1's rule) with these
/// contact fractions over its window (`nlsp`, `tlsp`) and shares of steps
/// with flight and with triple support, under the options' `labels.*`
/// thresholds (the `options` dict over the defaults).
#[pyfunction]
#[pyo3(signature = (nlsp, tlsp, flight_steps, triple_steps, options))]
fn label(
    nlsp: f64,
    tlsp: f64,
    flight_steps: f64,
    triple_steps: f64,
    options: Option<Bound<'_, PyDict>>,
) -> PyResult<&'static str> {
    let overrides = PyOverrides::new(options.as_ref())?;
    let options = simulation_options(None, None, overrides.layer()).map_err(value_error)?;
    let fractions = ContactFractions {
        nlsp,
        tlsp,
        ..ContactFractions::default()
    };
    let steps = StepShares {
        flight: flight_steps,
        triple: triple_steps,
        ..StepShares::default()
    };
    Ok(Label::of_gait(&fractions, &steps, &options.labels).as_str())
}

/// Every failure of the scan file `path` with its cluster (an index into
/// its summary's `clusters`), as `rtw-scan cluster --assignments` writes
/// them; `None` when there are fewer failures than the config's k.
#[pyfunction]
fn failure_clusters(py: Python<'_>, path: PathBuf) -> PyResult<Option<Vec<(u64, usize)>>> {
    py.detach(|| rtw_engine::failure_clusters(&path))
        .map_err(value_error)
}

/// The Wilson score interval (lo, hi) of `k` successes in `n` trials, as
/// fractions, at normal quantile `z`: the intervals of rtw-scan's summaries.
#[pyfunction]
#[pyo3(signature = (k, n, z))]
fn wilson(k: u64, n: u64, z: f64) -> PyResult<(f64, f64)> {
    if k > n {
        return Err(PyValueError::new_err(format!(
            "k: {k} is invalid: must be at most n ({n})"
        )));
    }
    Ok(rtw_engine::wilson(k, n, z))
}

/// Label names in `Label::ALL`'s order, those for which `keep` holds.
fn label_names(keep: fn(Label) -> bool) -> Vec<&'static str> {
    Label::ALL
        .into_iter()
        .filter(|l| keep(*l))
        .map(Label::as_str)
        .collect()
}

/// Points `0 … n−1` of the Sobol sequence in `dims` dimensions, as rtw-scan's
/// `sampling = "sobol"` makes them: unscrambled without `seed`
/// (`scipy.stats.qmc.Sobol(dims, scramble=False)`), else scrambled from
/// `seed` as a scan with that seed scrambles it.
#[pyfunction]
#[pyo3(signature = (dims, n, seed=None))]
fn sobol_points(dims: usize, n: u64, seed: Option<u64>) -> PyResult<Vec<Vec<f64>>> {
    use rtw_engine::sampling::{SOBOL_MAX_DIMS, Sobol};
    if !(1..=SOBOL_MAX_DIMS).contains(&dims) {
        return Err(PyValueError::new_err(format!(
            "dims: {dims} is invalid: must be in [1, {SOBOL_MAX_DIMS}]"
        )));
    }
    if n > 1 << 20 {
        return Err(PyValueError::new_err(format!(
            "n: {n} is invalid: must be at most 2^20 (points held in memory)"
        )));
    }
    let s = seed.map_or_else(|| Sobol::plain(dims), |seed| Sobol::scrambled(dims, seed));
    Ok((0..n)
        .map(|i| {
            let mut p = vec![0.0; dims];
            s.point(i, &mut p);
            p
        })
        .collect())
}

/// Sobol indices of a scan's outputs (`rtw-scan sensitivity`): a
/// `pyarrow.Table` of output, parameter, S1, S1_conf, ST, ST_conf. `scan`
/// is a scan file's path (or its directory), read through the library's verified
/// reader, or a table carrying its config in the schema's `rtw.config` metadata
/// (as `scan` returns it), checked as a file's rows are. `resamples` and `seed`
/// are checked as the CLI's flags. Ctrl-C raises KeyboardInterrupt; warns as the CLI.
#[pyfunction]
#[pyo3(signature = (scan, resamples, seed, progress=None))]
fn sensitivity<'py>(
    py: Python<'py>,
    scan: Bound<'py, PyAny>,
    resamples: Bound<'py, PyAny>,
    seed: Option<Bound<'py, PyAny>>,
    progress: Option<Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    use arrow_pyarrow::FromPyArrow;
    use rtw_studies::sensitivity as sa;
    let seed = seed.as_ref().map(digits).transpose()?;
    let settings =
        sa::Settings::parse(&digits(&resamples)?, seed.as_deref(), "").map_err(value_error)?;
    let counter = Counter::default();
    let analysis = if let Ok(path) = scan.extract::<PathBuf>() {
        interruptible(
            py,
            |cancel| sa::analyse_file(&path, &settings, &Run::new(&counter, cancel)),
            || report(py, progress.as_ref(), &counter),
        )?
    } else {
        let (batches, schema) = Table::from_pyarrow_bound(&scan)
            .map_err(|e| {
                PyValueError::new_err(format!("scan: not a path nor a pyarrow table: {e}"))
            })?
            .into_inner();
        let metadata: std::collections::HashMap<String, String> =
            schema.metadata().clone().into_iter().collect();
        interruptible(
            py,
            |cancel| sa::analyse_table(&metadata, batches, &settings, &Run::new(&counter, cancel)),
            || report(py, progress.as_ref(), &counter),
        )?
    }
    .map_err(study_error)?;
    report(py, progress.as_ref(), &counter)?;
    types::warn(py, sa::wide_warning(&analysis.indices))?;
    to_table(py, sa::to_batch(&analysis.indices))
}

/// A scan read whole through rtw-scan's verified reader (`summary`'s and
/// `sensitivity`'s checks: footer and content hash, row values, ids once
/// each in order, every shard of an unmerged set): a `pyarrow.Table` with
/// the scan's metadata in its schema, and the files read.
#[pyfunction]
fn read_scan<'py>(py: Python<'py>, path: PathBuf) -> PyResult<(Bound<'py, PyAny>, Vec<PathBuf>)> {
    let scan = py
        .detach(|| rtw_engine::read_scan_table(&path))
        .map_err(value_error)?;
    Ok((tables(py, scan.batches, scan.schema)?, scan.files))
}

/// What `read_scan_folder` gives: the rows, the files read, `summary.json`'s
/// text, and the assignments file with each failure's (0-based) cluster.
type ScanFolder<'py> = (
    Bound<'py, PyAny>,
    Vec<PathBuf>,
    Option<String>,
    Option<(PathBuf, Vec<(u64, usize)>)>,
);

/// A scan as `read_scan` reads it, with the files beside it that are its
/// own: `summary.json` when it counts the scan's rows, the assignments file
/// of `cluster --assignments` when it is intact and records this scan's
/// content hash (rtw-scan's `read_scan_folder`); another file is refused,
/// named. The HTML report reads a scan's folder through it.
#[pyfunction]
fn read_scan_folder<'py>(py: Python<'py>, path: PathBuf) -> PyResult<ScanFolder<'py>> {
    let folder = py
        .detach(|| rtw_engine::read_scan_folder(&path))
        .map_err(value_error)?;
    let scan = folder.scan;
    Ok((
        tables(py, scan.batches, scan.schema)?,
        scan.files,
        folder.summary,
        folder.assignments.map(|a| (a.path, a.clusters)),
    ))
}

/// The sensitivity indices at `path` as a `pyarrow.Table`, refused unless
/// they were computed from the scan with metadata `scan` and `rows` rows.
#[pyfunction]
fn read_indices<'py>(
    py: Python<'py>,
    path: PathBuf,
    scan: std::collections::BTreeMap<String, String>,
    rows: u64,
) -> PyResult<Bound<'py, PyAny>> {
    let (batches, schema) = py
        .detach(|| rtw_engine::read_indices(&path, &scan, rows))
        .map_err(value_error)?;
    tables(py, batches, schema)
}

/// The module `rtw._rtw`.
#[pymodule]
fn _rtw(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(trace, m)?)?;
    m.add_function(wrap_pyfunction!(scan, m)?)?;
    m.add_function(wrap_pyfunction!(limit_cycle, m)?)?;
    m.add_function(wrap_pyfunction!(modes, m)?)?;
    m.add_function(wrap_pyfunction!(studies::basin, m)?)?;
    m.add_function(wrap_pyfunction!(studies::profile, m)?)?;
    m.add_function(wrap_pyfunction!(studies::design_search, m)?)?;
    m.add_function(wrap_pyfunction!(sobol_points, m)?)?;
    m.add_function(wrap_pyfunction!(sensitivity, m)?)?;
    m.add_function(wrap_pyfunction!(label, m)?)?;
    m.add_function(wrap_pyfunction!(wilson, m)?)?;
    m.add_function(wrap_pyfunction!(failure_clusters, m)?)?;
    m.add_function(wrap_pyfunction!(read_scan, m)?)?;
    m.add_function(wrap_pyfunction!(read_indices, m)?)?;
    m.add_function(wrap_pyfunction!(read_scan_folder, m)?)?;
    m.add_function(wrap_pyfunction!(studies::read_design, m)?)?;
    m.add_function(wrap_pyfunction!(views::scan_views, m)?)?;
    m.add_function(wrap_pyfunction!(views::density_grid, m)?)?;
    m.add_function(wrap_pyfunction!(page::check_page, m)?)?;
    m.add_function(wrap_pyfunction!(page::write_page, m)?)?;
    m.add_class::<Outcome>()?;
    m.add_class::<LimitCycle>()?;
    m.add_class::<Modes>()?;
    m.add_class::<Profile>()?;
    m.add_class::<DesignSearch>()?;
    m.add("LABELS", PyTuple::new(m.py(), label_names(|_| true))?)?;
    m.add(
        "STABLE_LABELS",
        PyTuple::new(m.py(), label_names(Label::is_stable))?,
    )?;
    m.add(
        "FAILURE_LABELS",
        PyTuple::new(m.py(), label_names(Label::is_failure))?,
    )?;
    m.add("Z95", rtw_engine::Z95)?;
    m.add("PAGE_GENERATOR", page::GENERATOR)?;
    geometry::register(m)?;
    m.add("__version__", rtw_engine::VERSION)?;
    Ok(())
}
