//! `rtw._rtw`: the native layer of the Python package `rtw`
//! (`python/rtw/__init__.py` is its documented face).
//!
//! Only conversions and GIL handling live here: inputs and options are
//! checked by rtw-scan's config layers (the messages of the CLI), runs and
//! scans are rtw-scan's and rtw-model's own code, and tables cross into
//! Python through the Arrow C data interface (arrow-pyarrow: pyarrow imports
//! the Rust buffers, no value is copied or boxed as a Python object).

use anyhow::anyhow;
use arrow_array::RecordBatch;
use arrow_pyarrow::{IntoPyArrow, Table};
use pyo3::exceptions::{PyKeyboardInterrupt, PyMemoryError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rtw_model::cycles::stepmap::{CycleOptions, StepMap};
use rtw_model::plant::strings::StringSet;
use rtw_model::{Options, Params, Physical, modal};
use rtw_scan::config::layers::{load_layered, parse_layered, simulation_options};
use rtw_scan::config::params::checked_params;
use rtw_scan::io::{TraceNames, parse_size};
use rtw_scan::scan::scan_batch;
use rtw_scan::scan::single::{simulate_json, simulate_traced_json};
use std::collections::TryReserveError;
use std::num::NonZeroUsize;
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::mpsc::{RecvTimeoutError, channel};
use std::time::Duration;

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
        return PyMemoryError::new_err(format!("{e:#}"));
    }
    PyValueError::new_err(format!("{e:#}"))
}

/// The six inputs and the layered options (config's `[simulation]`, variant,
/// `KEY=VALUE` sets), checked as `rtw-scan simulate` checks them.
fn inputs(
    values: [f64; 6],
    config: Option<PathBuf>,
    variant: Option<PathBuf>,
    sets: &[String],
) -> PyResult<(Params, Options)> {
    let params = checked_params(values, "").map_err(value_error)?;
    let options =
        simulation_options(config.as_deref(), variant.as_deref(), sets).map_err(value_error)?;
    Ok((params, options))
}

/// A batch as a `pyarrow.Table`, through the C data interface.
fn to_table(py: Python<'_>, batch: RecordBatch) -> PyResult<Bound<'_, PyAny>> {
    let schema = batch.schema();
    Table::try_new(vec![batch], schema)
        .map_err(|e| PyRuntimeError::new_err(e.to_string()))?
        .into_pyarrow(py)
}

/// One run: its row as the JSON object of `rtw-scan simulate --json`.
#[pyfunction]
#[pyo3(signature = (values, config, variant, sets))]
fn simulate(
    py: Python<'_>,
    values: [f64; 6],
    config: Option<PathBuf>,
    variant: Option<PathBuf>,
    sets: Vec<String>,
) -> PyResult<String> {
    let (params, options) = inputs(values, config, variant, &sets)?;
    py.detach(|| simulate_json(params, &options))
        .map_err(value_error)
}

/// One run and its trace: (the `--json` row, a `pyarrow.Table` of the
/// `simulate --trace` columns). `limit` caps the trace's size in memory
/// before compression (`2GB`, `500MB`, bytes), as `--trace-limit` does.
#[pyfunction]
#[pyo3(signature = (values, config, variant, sets, limit))]
fn trace(
    py: Python<'_>,
    values: [f64; 6],
    config: Option<PathBuf>,
    variant: Option<PathBuf>,
    sets: Vec<String>,
    limit: String,
) -> PyResult<(String, Bound<'_, PyAny>)> {
    let limit = parse_size(&limit).map_err(|e| PyValueError::new_err(format!("limit: {e}")))?;
    let (params, options) = inputs(values, config, variant, &sets)?;
    let (json, batch) = py
        .detach(|| simulate_traced_json(params, &options, limit, PYTHON_TRACE_NAMES))
        .map_err(value_error)?;
    Ok((json, to_table(py, batch)?))
}

/// A scan (config file `path` or TOML `text`, then variant and sets) as a
/// `pyarrow.Table` of the rows of `rtw-scan run`. It runs on a worker thread
/// (rayon inside) with the GIL released; this thread polls Python's signal
/// handlers every [`SIGNAL_POLL`], calls `progress(done, total)` (rows
/// computed, rows in all) when given, and on an exception (KeyboardInterrupt,
/// or one raised by `progress`) stops the scan, waits for the samples in
/// flight, and raises it. `progress` is called a last time once every row is in.
#[pyfunction]
#[pyo3(signature = (path, text, variant, sets, threads, progress=None))]
fn scan<'py>(
    py: Python<'py>,
    path: Option<PathBuf>,
    text: Option<String>,
    variant: Option<PathBuf>,
    sets: Vec<String>,
    threads: Option<usize>,
    progress: Option<Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    let cfg = match (path, text) {
        (Some(p), None) => load_layered(&p, variant.as_deref(), &sets),
        (None, Some(t)) => parse_layered(&t, variant.as_deref(), &sets),
        _ => Err(anyhow!("give a config path or TOML text")),
    }
    .map_err(value_error)?;
    let threads = match threads {
        None => None,
        Some(n) => Some(
            NonZeroUsize::new(n)
                .ok_or_else(|| PyValueError::new_err("threads: 0 is invalid: must be >= 1"))?,
        ),
    };
    let total = cfg.total_rows().map_err(value_error)?;
    let stop = Arc::new(AtomicBool::new(false));
    let rows_done = Arc::new(AtomicU64::new(0));
    let (done, finished) = channel();
    let worker = {
        let stop = Arc::clone(&stop);
        let rows_done = Arc::clone(&rows_done);
        std::thread::spawn(move || {
            let result = scan_batch(&cfg, threads, &stop, &rows_done);
            // The receiver is gone only if this function already returned.
            let _ = done.send(());
            result
        })
    };
    let mut finished = finished;
    loop {
        // The receiver is `Send` but not `Sync`: it goes into the detached
        // closure and comes back.
        let (wait, back) = py.detach(move || (finished.recv_timeout(SIGNAL_POLL), finished));
        finished = back;
        match wait {
            Err(RecvTimeoutError::Timeout) => {}
            Ok(()) | Err(RecvTimeoutError::Disconnected) => break,
        }
        let shown = match &progress {
            Some(f) => f
                .call1((rows_done.load(Ordering::Relaxed), total))
                .map(drop),
            None => Ok(()),
        };
        if let Err(interrupt) = shown.and_then(|()| py.check_signals()) {
            stop.store(true, Ordering::SeqCst);
            // The samples in flight finish (each is bounded by t_max and max_steps).
            let _ = py.detach(|| worker.join());
            return Err(interrupt);
        }
    }
    let result = py
        .detach(|| worker.join())
        .map_err(|_| PyRuntimeError::new_err("the scan's worker thread panicked"))?;
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
/// section, Newton on `Pⁿ(z) = z`, Floquet multipliers), as a dict.
#[pyfunction]
#[pyo3(signature = (values, config, variant, sets, settle_steps))]
fn limit_cycle<'py>(
    py: Python<'py>,
    values: [f64; 6],
    config: Option<PathBuf>,
    variant: Option<PathBuf>,
    sets: Vec<String>,
    settle_steps: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let (params, options) = inputs(values, config, variant, &sets)?;
    if !(1..=MAX_SETTLE_STEPS).contains(&settle_steps) {
        return Err(PyValueError::new_err(format!(
            "settle_steps: {settle_steps} is invalid: must be an integer >= 1 and at most {MAX_SETTLE_STEPS}"
        )));
    }
    let cycle = CycleOptions {
        settle_steps,
        ..CycleOptions::default()
    };
    let lc = py
        .detach(|| StepMap::new(&params, &options, &cycle).limit_cycle(&options, &cycle))
        .map_err(|e| PyRuntimeError::new_err(format!("no limit cycle: {e}")))?;
    let d = PyDict::new(py);
    d.set_item("period", lc.period)?;
    d.set_item("fixed_point", lc.fixed_point.z.clone())?;
    d.set_item("residual", lc.fixed_point.residual)?;
    d.set_item("iterations", lc.fixed_point.iterations)?;
    let multipliers: Vec<(f64, f64)> = lc.multipliers.iter().map(|m| (m.re, m.im)).collect();
    d.set_item("multipliers", multipliers)?;
    d.set_item("floquet_max", lc.floquet_max())?;
    d.set_item("stable", lc.is_stable())?;
    d.set_item("label", lc.label(&options.labels).as_str())?;
    let step_times: Vec<f64> = lc.steps.iter().map(|s| s.time).collect();
    d.set_item("step_times", step_times)?;
    Ok(d)
}

/// The eigen-frequencies of rtw-model's `modal`: S18's f_n, the approximate
/// 3-rotor model's modes and the free 9-DOF star's, as a dict.
#[pyfunction]
#[pyo3(signature = (values, config, variant, sets))]
fn modes<'py>(
    py: Python<'py>,
    values: [f64; 6],
    config: Option<PathBuf>,
    variant: Option<PathBuf>,
    sets: Vec<String>,
) -> PyResult<Bound<'py, PyDict>> {
    let (params, options) = inputs(values, config, variant, &sets)?;
    let phys = Physical::new(&params, options.normalization, options.g);
    let strings = StringSet::new(&phys, &options);
    let approx = modal::approximate_modes(&phys, &strings);
    let star = modal::free_star_modes(&phys, &strings);
    let d = PyDict::new(py);
    d.set_item("s18_hz", modal::s18_frequency(&phys))?;
    d.set_item("approx_hz", approx.freq_hz)?;
    d.set_item("approx_damped_hz", approx.damped_freq_hz)?;
    d.set_item("approx_damping_ratio", approx.damping_ratio)?;
    d.set_item("star_hz", star.freq_hz.to_vec())?;
    d.set_item("star_rigid_modes", star.rigid_modes)?;
    Ok(d)
}

/// Points `0 … n−1` of the Sobol sequence in `dims` dimensions, as rtw-scan's
/// `sampling = "sobol"` makes them: unscrambled without `seed`
/// (`scipy.stats.qmc.Sobol(dims, scramble=False)`), else scrambled from
/// `seed` as a scan with that seed scrambles it.
#[pyfunction]
#[pyo3(signature = (dims, n, seed=None))]
fn sobol_points(dims: usize, n: u64, seed: Option<u64>) -> PyResult<Vec<Vec<f64>>> {
    use rtw_scan::scan::design::{SOBOL_MAX_DIMS, Sobol};
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

/// Sobol indices of a scan table's outputs (`rtw-scan sensitivity`): a
/// `pyarrow.Table` of output, parameter, S1, S1_conf, ST, ST_conf. The
/// table carries its config in the schema's `rtw.config` metadata (as
/// `scan` returns it and a scan file holds it).
#[pyfunction]
#[pyo3(signature = (table, resamples, seed))]
fn sensitivity<'py>(
    py: Python<'py>,
    table: Bound<'py, PyAny>,
    resamples: usize,
    seed: Option<u64>,
) -> PyResult<Bound<'py, PyAny>> {
    use arrow_pyarrow::FromPyArrow;
    use rtw_scan::sensitivity as sa;
    let (batches, schema) = Table::from_pyarrow_bound(&table)
        .map_err(|e| PyValueError::new_err(format!("table: not a pyarrow table: {e}")))?
        .into_inner();
    let text = schema.metadata().get("rtw.config").ok_or_else(|| {
        PyValueError::new_err(
            "table: no `rtw.config` in its schema metadata: not a table of rtw.scan; give a scan file by its path",
        )
    })?;
    let cfg = rtw_scan::config::parse(text).map_err(value_error)?;
    let rows = py
        .detach(|| {
            let cols = sa::columns(&cfg, batches.into_iter().map(Ok))?;
            sa::indices(&cfg, &cols, resamples, seed.unwrap_or(cfg.seed))
        })
        .map_err(value_error)?
        .1;
    to_table(py, sa::to_batch(&rows))
}

/// The module `rtw._rtw`.
#[pymodule]
fn _rtw(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(trace, m)?)?;
    m.add_function(wrap_pyfunction!(scan, m)?)?;
    m.add_function(wrap_pyfunction!(limit_cycle, m)?)?;
    m.add_function(wrap_pyfunction!(modes, m)?)?;
    m.add_function(wrap_pyfunction!(sobol_points, m)?)?;
    m.add_function(wrap_pyfunction!(sensitivity, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
