//! The HTML pages `rtw.report` makes, written through the engine's page
//! checks and atomic write (`rtw_engine::io::page`): the same refusals, in
//! the same words, as every file rtw writes. This only maps the errors to
//! Python's (`FileNotFoundError` for a missing folder, `ValueError` else).

use pyo3::exceptions::{PyFileNotFoundError, PyValueError};
use pyo3::prelude::*;
use rtw_engine::io::page::{self, MissingFolder};
use std::path::PathBuf;

/// The marker every page carries in its `<head>`.
pub(crate) const GENERATOR: &str = page::GENERATOR;

fn to_py(e: anyhow::Error) -> PyErr {
    let text = rtw_engine::error_message(&e);
    if e.downcast_ref::<MissingFolder>().is_some() {
        PyFileNotFoundError::new_err(text)
    } else {
        PyValueError::new_err(text)
    }
}

/// Refuses `path` (named `out` in messages) as the place of a page, as
/// `rtw_engine::io::page::check_page` does.
#[pyfunction]
pub(crate) fn check_page(path: PathBuf, force: bool) -> PyResult<()> {
    page::check_page(&path, "out", force).map_err(to_py)
}

/// Writes the page `html` at `path`, checked again first, atomically.
#[pyfunction]
pub(crate) fn write_page(py: Python<'_>, path: PathBuf, html: &str, force: bool) -> PyResult<()> {
    py.detach(|| page::write_page(&path, html, "out", force))
        .map_err(to_py)
}
