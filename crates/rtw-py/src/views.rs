//! The report's views of a large scan, aggregated in rtw-scan
//! (`rtw_engine::views`): Python only packs them into the page.

use arrow_pyarrow::{FromPyArrow, Table};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};
use rtw_model::Label;

/// The rows of `table` (a scan as `read_scan` gives it) for a page that
/// cannot carry them one by one: a dict with `labels` (the outcome names,
/// `Label::ALL`'s order), `outcome` (bytes: each row's index in `labels`),
/// `columns` ({name: (range or None, bytes)}: each row's bin of
/// `CODE_BINS` on the column's range, `CODE_NONE` when it has no value),
/// `density` (per label, its rows on the grid of the columns `x` and `y`,
/// row-major) and `sample` (at most `sample` row indices: every outcome an
/// equal share, a rarer one all its rows; seeded by `seed`).
#[pyfunction]
#[pyo3(signature = (table, columns, x, y, sample, seed))]
pub(crate) fn scan_views<'py>(
    py: Python<'py>,
    table: Bound<'py, PyAny>,
    columns: Vec<String>,
    x: String,
    y: String,
    sample: usize,
    seed: u64,
) -> PyResult<Bound<'py, PyDict>> {
    let (batches, _) = Table::from_pyarrow_bound(&table)
        .map_err(|e| PyValueError::new_err(format!("table: not a pyarrow table: {e}")))?
        .into_inner();
    let v = py
        .detach(|| rtw_engine::views::views(&batches, &columns, (&x, &y), sample, seed))
        .map_err(|e| PyValueError::new_err(format!("{e:#}")))?;
    let out = PyDict::new(py);
    let labels: Vec<&str> = Label::ALL.iter().map(|l| l.as_str()).collect();
    out.set_item("labels", labels)?;
    out.set_item("outcome", PyBytes::new(py, &v.outcomes))?;
    let cols = PyDict::new(py);
    for (name, coded) in &v.columns {
        cols.set_item(name, (coded.range, PyBytes::new(py, &coded.codes)))?;
    }
    out.set_item("columns", cols)?;
    out.set_item("density", v.density)?;
    out.set_item("sample", v.sample)?;
    out.set_item("code_bins", rtw_engine::views::CODE_BINS)?;
    out.set_item("code_none", rtw_engine::views::CODE_NONE)?;
    Ok(out)
}

/// Per group `0..groups`, the rows of `group` (a byte a row: each row's
/// group; other values are left out) counted on the grid of two coded columns `x` and `y` (as
/// `scan_views` gives them), row-major: the report's failure projections
/// per cluster.
#[pyfunction]
pub(crate) fn density_grid(
    group: &[u8],
    groups: usize,
    x: &[u8],
    y: &[u8],
) -> PyResult<Vec<Vec<u32>>> {
    // A group is a byte: more grids than its values count nothing, and a
    // count from the caller must not size an allocation that aborts Python.
    if groups > 256 {
        return Err(PyValueError::new_err(format!(
            "groups: {groups} is invalid: must be at most 256 (a group is one byte)"
        )));
    }
    if group.len() != x.len() || x.len() != y.len() {
        return Err(PyValueError::new_err(format!(
            "group, x, y: {}, {} and {} rows: must be one byte for each row",
            group.len(),
            x.len(),
            y.len()
        )));
    }
    Ok(rtw_engine::views::density(group, groups, x, y))
}
