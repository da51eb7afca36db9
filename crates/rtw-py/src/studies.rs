//! The studies over one design or a box of designs: a basin slice, a slope
//! profile and a design search. Each turns Python's arguments into the
//! library's checked settings and runs the library's entry point with the
//! GIL released, as `rtw-scan basin`, `profile` and `design` do.

use crate::options::PyOverrides;
use crate::types::{DesignSearch, Profile};
use crate::{
    digits, inputs, interruptible, model, report, study_error, tables, to_table, value_error,
};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rtw_engine::config::layers::simulation_options;
use rtw_engine::scan::Run;
use rtw_engine::scan::progress::Counter;
use rtw_engine::scan::workers::parse_threads;
use rtw_model::Options;
use rtw_studies::basin::{Settings as BasinSettings, slice_table};
use rtw_studies::profile::{
    Names as ProfileNames, Settings as ProfileSettings, run as run_profile,
};
use rtw_studies::search::{self, Reported, Search, SearchSettings};
use std::num::NonZeroUsize;
use std::path::PathBuf;
use std::sync::atomic::AtomicBool;

/// A slice of the gait's basin of attraction (`rtw-scan basin`): a
/// `pyarrow.Table` with one row per grid point, the columns of the CLI's
/// Parquet file, made by the same library function from the settings as
/// given (checked there, as the CLI's flags are). Runs as `scan` does:
/// Ctrl-C stops it after the points in flight and raises KeyboardInterrupt.
#[pyfunction]
#[pyo3(signature = (values, config, variant, options, x, y, steps, tol, threads, progress=None))]
#[allow(clippy::too_many_arguments)] // the design's layers and the slice's settings, as `rtw-scan basin`
pub(crate) fn basin<'py>(
    py: Python<'py>,
    values: [f64; 6],
    config: Option<Bound<'_, PyAny>>,
    variant: Option<PathBuf>,
    options: Option<Bound<'_, PyDict>>,
    x: &str,
    y: &str,
    steps: Bound<'py, PyAny>,
    tol: f64,
    threads: Option<Bound<'py, PyAny>>,
    progress: Option<Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    let threads = threads.as_ref().map(digits).transpose()?;
    let settings = BasinSettings::parse(x, y, &digits(&steps)?, tol, "").map_err(value_error)?;
    let threads = threads
        .as_deref()
        .map(|t| parse_threads(t, "threads"))
        .transpose()
        .map_err(value_error)?;
    let (params, options) = inputs(values, config, variant, options.as_ref())?;
    let counter = Counter::default();
    let batch = interruptible(
        py,
        |cancel| {
            slice_table(
                &params,
                &options,
                &settings,
                &Run::new(&counter, cancel).on(threads),
            )
        },
        || report(py, progress.as_ref(), &counter),
    )?
    .map_err(study_error)?;
    report(py, progress.as_ref(), &counter)?;
    to_table(py, batch)
}

/// The slope profile of one design (`rtw-scan profile`): its gait along φ
/// over [`phi_from`, `phi_to`], each change of label located to `tol` by
/// bisection from a grid at most `grid` apart. The settings and the design
/// are checked by the library's `profile::Settings::parse`, as the CLI's
/// flags are (named as Python's keywords). Ctrl-C stops it and raises
/// KeyboardInterrupt.
#[pyfunction]
#[pyo3(signature = (design, config, variant, options, phi_from, phi_to, tol, grid, threads))]
#[allow(clippy::too_many_arguments)] // the design's layers and the profile's settings, as `rtw-scan profile`
pub(crate) fn profile<'py>(
    py: Python<'py>,
    design: [f64; 5],
    config: Option<Bound<'_, PyAny>>,
    variant: Option<PathBuf>,
    options: Option<Bound<'_, PyDict>>,
    phi_from: f64,
    phi_to: f64,
    tol: f64,
    grid: f64,
    threads: Option<Bound<'py, PyAny>>,
) -> PyResult<Profile> {
    let threads = threads.as_ref().map(digits).transpose()?;
    let settings =
        ProfileSettings::parse(design, phi_from, phi_to, tol, grid, &ProfileNames::PYTHON)
            .map_err(value_error)?;
    let threads = threads
        .as_deref()
        .map(|t| parse_threads(t, "threads"))
        .transpose()
        .map_err(value_error)?;
    let options = model(config.as_ref(), variant, options.as_ref())?;
    let counter = Counter::default();
    let p = interruptible(
        py,
        |cancel| run_profile(&settings, &options, &Run::new(&counter, cancel).on(threads)),
        || report(py, None, &counter),
    )?
    .map_err(study_error)?;
    report(py, None, &counter)?;
    let table = to_table(py, p.table())?.unbind();
    Ok(Profile::new(&p, table))
}

/// A design search (`rtw-scan design CONFIG`): the config read and checked
/// by the library's `SearchSettings::read`, run by the same library
/// functions: into the folder `out` (resumed there, files written as the
/// CLI writes them) or, without `out`, in memory. Ctrl-C stops it and
/// raises KeyboardInterrupt; with `out`, every finished design is kept.
#[pyfunction]
#[pyo3(name = "design", signature = (path, out, variant, options, threads, force, progress=None))]
#[allow(clippy::too_many_arguments)] // the search's config, folder and model layers, as `rtw-scan design`
pub(crate) fn design_search<'py>(
    py: Python<'py>,
    path: PathBuf,
    out: Option<PathBuf>,
    variant: Option<PathBuf>,
    options: Option<Bound<'_, PyDict>>,
    threads: Option<Bound<'py, PyAny>>,
    force: bool,
    progress: Option<Bound<'py, PyAny>>,
) -> PyResult<DesignSearch> {
    let settings = SearchSettings::read(&path).map_err(value_error)?;
    let threads = threads
        .as_ref()
        .map(digits)
        .transpose()?
        .map(|t| parse_threads(&t, "threads"))
        .transpose()
        .map_err(value_error)?;
    let overrides = PyOverrides::new(options.as_ref())?;
    let options = simulation_options(Some(&path), variant.as_deref(), overrides.layer())
        .map_err(value_error)?;
    let counter = Counter::default();
    let (found, reported) = interruptible(
        py,
        |cancel| match &out {
            Some(dir) => search::files::run_to_files(
                &settings,
                &options,
                dir,
                force,
                &Run::new(&counter, cancel).on(threads),
            ),
            None => search_in_memory(&settings, &options, threads, &counter, cancel),
        },
        || report(py, progress.as_ref(), &counter),
    )?
    .map_err(study_error)?;
    report(py, progress.as_ref(), &counter)?;
    let evaluations = to_table(
        py,
        search::files::search_batch(&settings, &found.evaluations),
    )?;
    let designs = to_table(py, search::files::reported_batch(&settings, &reported))?;
    let archive = to_table(
        py,
        search::files::archive_batch(&settings, &found.evaluations),
    )?;
    Ok(DesignSearch::new(
        search::files::markdown(&found, &reported),
        found.runs(),
        evaluations.unbind(),
        designs.unbind(),
        archive.unbind(),
    ))
}

/// The search of `s` with no folder: [`search::run`] (nothing stored
/// between generations), then [`search::report`] of its designs, as
/// `search::files::run_to_files` chains them around its files. rtw-scan has
/// no entry for the two without files; this is the one place that chains them.
fn search_in_memory(
    s: &SearchSettings,
    options: &Options,
    threads: Option<NonZeroUsize>,
    counter: &Counter,
    cancel: &AtomicBool,
) -> anyhow::Result<(Search, Vec<Reported>)> {
    let run = Run::new(counter, cancel).on(threads);
    let found = search::run(s, options, &[], &run, &mut |_| Ok(()))?;
    let reported = search::report(&found, options, &run)?;
    Ok((found, reported))
}

/// A design file as Python gets it: its path, its role, its table.
type DesignTable<'py> = (PathBuf, &'static str, Bound<'py, PyAny>);

/// The design files in `path` (a search's folder, an atlas such as
/// `results/design/`, or one file), each read whole through rtw-scan's
/// verified reader: `(file, role, table)` with role `evaluations`,
/// `reported` or `profile` and the file's metadata in the table's schema;
/// `None` when `path` holds no search's files.
#[pyfunction]
pub(crate) fn read_design<'py>(
    py: Python<'py>,
    path: PathBuf,
) -> PyResult<Option<Vec<DesignTable<'py>>>> {
    let Some(files) = py
        .detach(|| search::read::read_folder(&path))
        .map_err(value_error)?
    else {
        return Ok(None);
    };
    files
        .into_iter()
        .map(|f| Ok((f.path, f.role.name(), tables(py, f.batches, f.schema)?)))
        .collect::<PyResult<_>>()
        .map(Some)
}
