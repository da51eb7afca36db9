//! Python's `options=` dict → the config layer's typed overrides
//! ([`Overrides::Values`]), value by value: no `KEY=VALUE` text in between,
//! so a float keeps every bit and a string stays a string.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use rtw_engine::config::layers::{ConfigSource, Overrides};

/// The options of one call: dotted keys (`{"contact.mu": 0.8}`) and nested
/// dicts (`{"contact": {"mu": 0.8}}`) alike, flattened to their dotted leaf
/// keys in the dict's order, so a nested dict sets its keys and keeps the
/// table's others. Errors name the key.
pub(crate) struct PyOverrides(Vec<(String, toml::Value)>);

impl PyOverrides {
    pub(crate) fn new(options: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        let mut values = Vec::new();
        if let Some(d) = options {
            flatten("", d, &mut values)?;
        }
        Ok(Self(values))
    }

    pub(crate) fn layer(&self) -> Overrides<'_> {
        Overrides::Values(&self.0)
    }
}

fn flatten(
    prefix: &str,
    d: &Bound<'_, PyDict>,
    out: &mut Vec<(String, toml::Value)>,
) -> PyResult<()> {
    for (k, v) in d.iter() {
        let Ok(k) = k.cast::<PyString>() else {
            return Err(PyValueError::new_err(format!(
                "{prefix}{}: not an option key (a dotted name such as contact.mu)",
                k.repr()?
            )));
        };
        let key = format!("{prefix}{}", k.to_str()?);
        match v.cast::<PyDict>() {
            Ok(sub) => flatten(&format!("{key}."), sub, out)?,
            Err(_) => {
                let value = to_toml(&key, &v)?;
                out.push((key, value));
            }
        }
    }
    Ok(())
}

/// One option's value as TOML: bool, int (64-bit), float, str, a list or
/// tuple of these, a dict (an inline table).
fn to_toml(key: &str, v: &Bound<'_, PyAny>) -> PyResult<toml::Value> {
    // bool before int: Python's bool is an int.
    if let Ok(b) = v.cast::<PyBool>() {
        return Ok(toml::Value::Boolean(b.is_true()));
    }
    if v.is_instance_of::<PyInt>() {
        return v.extract::<i64>().map(toml::Value::Integer).map_err(|_| {
            PyValueError::new_err(format!(
                "{key}: {} is invalid: beyond the range of a 64-bit integer",
                v.repr().map(|r| r.to_string()).unwrap_or_default()
            ))
        });
    }
    if let Ok(f) = v.cast::<PyFloat>() {
        return Ok(toml::Value::Float(f.value()));
    }
    if let Ok(s) = v.cast::<PyString>() {
        return Ok(toml::Value::String(s.to_str()?.to_string()));
    }
    if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() {
        let items = v
            .try_iter()?
            .map(|item| to_toml(key, &item?))
            .collect::<PyResult<Vec<_>>>()?;
        return Ok(toml::Value::Array(items));
    }
    if let Ok(d) = v.cast::<PyDict>() {
        let mut table = toml::Table::new();
        for (k, item) in d.iter() {
            let k: String = k.extract()?;
            let value = to_toml(&format!("{key}.{k}"), &item)?;
            table.insert(k, value);
        }
        return Ok(toml::Value::Table(table));
    }
    // Other numbers (numpy's): an integer if it is one, else a float.
    if v.hasattr("__index__")? {
        return to_toml(key, &v.call_method0("__index__")?);
    }
    if v.hasattr("__float__")? {
        return Ok(toml::Value::Float(v.extract::<f64>()?));
    }
    Err(PyValueError::new_err(format!(
        "{key}: {} is invalid: must be a bool, int, float, str, list or dict (an option's value)",
        v.repr()?
    )))
}

/// A config as Python gives it (`rtw.Config`): a path (`str` or
/// `os.PathLike`), TOML text (a `str` holding a newline or `=`, which no
/// file name a user writes does), or a dict of its tables, read as the TOML
/// text of those tables, so a dict and the file holding it give the same
/// config.
pub(crate) enum PyConfig {
    File(std::path::PathBuf),
    Text(String),
}

impl PyConfig {
    pub(crate) fn new(config: Option<&Bound<'_, PyAny>>) -> PyResult<Option<Self>> {
        let Some(c) = config else {
            return Ok(None);
        };
        if c.cast::<PyDict>().is_ok() {
            let toml::Value::Table(table) = to_toml("config", c)? else {
                unreachable!("a dict is a table");
            };
            let text = toml::to_string(&table)
                .map_err(|e| PyValueError::new_err(format!("config: {e}")))?;
            return Ok(Some(Self::Text(text)));
        }
        if let Ok(s) = c.cast::<PyString>() {
            let s = s.to_str()?;
            if s.contains('\n') || s.contains('=') {
                return Ok(Some(Self::Text(s.to_string())));
            }
        }
        match c.extract::<std::path::PathBuf>() {
            Ok(path) => Ok(Some(Self::File(path))),
            Err(_) => Err(PyValueError::new_err(format!(
                "config: {} is invalid: must be a path, TOML text or a dict of the config's tables",
                c.repr()?
            ))),
        }
    }

    /// The source the config layer reads.
    pub(crate) fn source(&self) -> ConfigSource<'_> {
        match self {
            Self::File(p) => ConfigSource::File(p),
            Self::Text(t) => ConfigSource::Text(t),
        }
    }
}
