//! The objects `rtw` returns: `Outcome`, `LimitCycle`, `Modes`. Frozen,
//! compared by their results (never by what a run measured of the machine:
//! [`MEASURED`]), with a `repr` and `to_dict()`; their fields are read
//! from rtw-scan's and rtw-model's definitions, and `_rtw.pyi` is checked
//! against them by tests/test_types.py.

use pyo3::exceptions::PyAttributeError;
use pyo3::prelude::*;
use pyo3::types::{PyComplex, PyDict, PyString, PyTuple};
use rtw_engine::io::{ColumnKind, Kind, Value, row_columns};
use rtw_engine::scan::single::RowValues;
use std::collections::HashMap;
use std::sync::LazyLock;

/// The columns of a scan row (rtw-scan's `COLUMNS` table), in order.
static COLUMNS: LazyLock<Vec<ColumnKind>> = LazyLock::new(|| row_columns().collect());

/// The columns a run measures of the machine, not of the model: two identical
/// runs differ in them, so `==` of a result, and of a table of rows, skips
/// them. (The work counts, `steps` to `events`, are the integrator's and
/// the same on every run.)
pub(crate) const MEASURED: [&str; 1] = ["wall_time_s"];

/// Each column's position in a row, by name.
static POSITION: LazyLock<HashMap<&'static str, usize>> = LazyLock::new(|| {
    COLUMNS
        .iter()
        .enumerate()
        .map(|(i, c)| (c.name, i))
        .collect()
});

/// One run's row: the fields of ``rtw-scan simulate --json``, as attributes.
///
/// The same keys as a ``samples.parquet`` row (docs/data-dictionary.md), in
/// column order: the inputs, the derived physical parameters, ``outcome``
/// (the label), ``failure`` and ``message`` (``None`` when the run
/// finished), the gait metrics, the limit-cycle summary, the work counts and
/// ``wall_time_s`` (the run's own time in Rust). Metrics that do not apply,
/// and non-finite values, are ``None``, as in the JSON. Immutable;
/// :meth:`to_dict` gives a plain ``dict``. The fields are the columns of
/// rtw-scan's row table, so they cannot drift from the files.
///
/// ``period`` is the gait's period as the ``period`` column has it: in
/// touchdowns on the touchdown return map of this run, or, with
/// ``limit_cycle=True`` and a cycle found, in steps on the step map
/// (``LimitCycle.period``); the two can differ for one walk
/// (docs/data-dictionary.md).
#[pyclass(frozen, eq, module = "rtw", name = "Outcome")]
pub(crate) struct Outcome {
    values: Vec<Value>,
    /// The robustness measures the run was asked for (`step_down_max`),
    /// after the columns, as `--json` prints them; empty by default.
    robustness: Vec<(&'static str, Value)>,
}

impl Outcome {
    pub(crate) fn new(row: RowValues) -> Self {
        debug_assert_eq!(row.columns.len(), COLUMNS.len());
        Self {
            values: row.columns,
            robustness: row.robustness,
        }
    }
}

impl PartialEq for Outcome {
    /// The same results: every column but the [`MEASURED`] ones.
    fn eq(&self, other: &Self) -> bool {
        self.robustness == other.robustness
            && COLUMNS
                .iter()
                .zip(self.values.iter().zip(&other.values))
                .all(|(c, (a, b))| MEASURED.contains(&c.name) || a == b)
    }
}

fn value<'py>(py: Python<'py>, v: &Value) -> PyResult<Bound<'py, PyAny>> {
    Ok(match v {
        Value::Float(x) => x.into_pyobject(py)?.into_any(),
        Value::Int(x) => x.into_pyobject(py)?.into_any(),
        Value::Bool(x) => x.into_pyobject(py)?.into_any(),
        Value::Text(x) => x.as_deref().into_pyobject(py)?.into_any(),
    })
}

#[pymethods]
impl Outcome {
    /// The field `name`.
    fn __getattr__<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
        if let Some(&i) = POSITION.get(name) {
            return value(py, &self.values[i]);
        }
        match self.robustness.iter().find(|(k, _)| *k == name) {
            Some((_, v)) => value(py, v),
            None => Err(PyAttributeError::new_err(format!(
                "Outcome has no field {name:?}"
            ))),
        }
    }

    fn __setattr__(&self, _name: &str, _value: Bound<'_, PyAny>) -> PyResult<()> {
        Err(PyAttributeError::new_err("Outcome is immutable"))
    }

    fn __dir__(&self) -> Vec<&'static str> {
        let mut names: Vec<&str> = COLUMNS.iter().map(|c| c.name).collect();
        names.extend(self.robustness.iter().map(|(k, _)| *k));
        names.push("to_dict");
        names
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        let shown = ["outcome", "failure", "speed", "f_w", "period", "t_end"]
            .iter()
            .map(|k| {
                Ok(format!(
                    "{k}={}",
                    value(py, &self.values[POSITION[k]])?.repr()?
                ))
            })
            .collect::<PyResult<Vec<_>>>()?;
        Ok(format!("Outcome({}, ...)", shown.join(", ")))
    }

    /// The fields as a new `dict`, in column order (what `--json` prints).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (c, v) in COLUMNS.iter().zip(&self.values) {
            d.set_item(c.name, value(py, v)?)?;
        }
        for (k, v) in &self.robustness {
            d.set_item(*k, value(py, v)?)?;
        }
        Ok(d)
    }

    /// The fields' names and types, in column order, as Python annotations
    /// (`"float | None"`).
    #[classattr]
    fn __annotations__(py: Python<'_>) -> PyResult<Py<PyDict>> {
        let d = PyDict::new(py);
        for c in COLUMNS.iter() {
            let ty = match c.kind {
                Kind::Float => "float",
                Kind::Int => "int",
                Kind::Bool => "bool",
                Kind::Text => "str",
            };
            let ty = if c.nullable {
                format!("{ty} | None")
            } else {
                ty.to_string()
            };
            d.set_item(c.name, ty)?;
        }
        Ok(d.unbind())
    }
}

/// A frozen class whose fields are listed once: the struct's fields, each
/// read by its getter (`get_all`), and their names in order as the class's
/// `__match_args__` (positional patterns in `match`), from which `repr` and
/// `to_dict` are made.
macro_rules! fields_class {
    ($(#[$meta:meta])* $name:ident { $($field:ident: $ty:ty,)* }) => {
        $(#[$meta])*
        #[pyclass(frozen, eq, get_all, module = "rtw")]
        #[derive(PartialEq)]
        pub(crate) struct $name {
            $($field: $ty,)*
        }

        #[pymethods]
        impl $name {
            /// The fields' names, in order.
            #[classattr]
            fn __match_args__(py: Python<'_>) -> PyResult<Py<PyTuple>> {
                Ok(PyTuple::new(py, [$(stringify!($field)),*])?.unbind())
            }

            fn __repr__(slf: &Bound<'_, Self>) -> PyResult<String> {
                repr_of(slf.as_any())
            }

            /// The fields as a new `dict`, in order.
            fn to_dict<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyDict>> {
                dict_of(slf.as_any())
            }
        }
    };
}

/// The fields of a class made by `fields_class!` as (name, value) pairs, in order.
fn getters<'py>(
    slf: &Bound<'py, PyAny>,
) -> PyResult<Vec<(Bound<'py, PyString>, Bound<'py, PyAny>)>> {
    let names = slf.get_type().getattr("__match_args__")?;
    let mut out = Vec::new();
    for name in names.try_iter()? {
        let name = name?.cast_into::<PyString>()?;
        let v = slf.getattr(&name)?;
        out.push((name, v));
    }
    Ok(out)
}

fn repr_of(slf: &Bound<'_, PyAny>) -> PyResult<String> {
    let fields = getters(slf)?
        .iter()
        .map(|(n, v)| Ok(format!("{n}={}", v.repr()?)))
        .collect::<PyResult<Vec<_>>>()?;
    Ok(format!("{}({})", slf.get_type().name()?, fields.join(", ")))
}

fn dict_of<'py>(slf: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(slf.py());
    for (n, v) in getters(slf)? {
        d.set_item(n, v)?;
    }
    Ok(d)
}

/// Values that Python sees as a tuple (floats, intervals, changes).
#[derive(PartialEq)]
pub(crate) struct Tuple<T>(pub(crate) Vec<T>);

impl<'a, 'py, T> IntoPyObject<'py> for &'a Tuple<T>
where
    &'a T: IntoPyObject<'py>,
{
    type Target = PyTuple;
    type Output = Bound<'py, PyTuple>;
    type Error = PyErr;
    fn into_pyobject(self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        PyTuple::new(py, &self.0)
    }
}

/// Floats that Python sees as a tuple.
type Floats = Tuple<f64>;

/// Complex numbers (re, im) that Python sees as a tuple of `complex`.
#[derive(PartialEq)]
struct Complexes(Vec<(f64, f64)>);

impl<'py> IntoPyObject<'py> for &Complexes {
    type Target = PyTuple;
    type Output = Bound<'py, PyTuple>;
    type Error = PyErr;
    fn into_pyobject(self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        PyTuple::new(
            py,
            self.0
                .iter()
                .map(|&(re, im)| PyComplex::from_doubles(py, re, im)),
        )
    }
}

fields_class! {
/// A periodic gait on the step map (the section at each new foot's touchdown).
///
/// Attributes:
///     period: the step map's period in steps (1: every step the same), the
///         fixed point of ``Pⁿ``. Not the ``Outcome.period`` of a run
///         without ``limit_cycle=True``, which counts touchdowns on the
///         touchdown return map of the simulated run.
///     fixed_point: the fixed point ``z`` of ``Pⁿ`` (the map's coordinates in
///         the orbit's contact modes).
///     residual: ``max |Pⁿ(z) − z| / scale`` at the solution.
///     iterations: Newton iterations taken.
///     multipliers: the nontrivial Floquet multipliers of ``Pⁿ``, largest
///         modulus first.
///     floquet_max: the largest multiplier modulus.
///     stable: every multiplier inside the unit circle.
///     label: the gait label of the orbit's steps (walk, skip, crawl, ...).
///     step_times: the duration of each step of the orbit (s).
    LimitCycle {
        period: usize,
        fixed_point: Floats,
        residual: f64,
        iterations: u32,
        multipliers: Complexes,
        floquet_max: f64,
        stable: bool,
        label: String,
        step_times: Floats,
    }
}

impl LimitCycle {
    pub(crate) fn new(lc: &rtw_model::cycles::LimitCycle, label: &str) -> Self {
        Self {
            period: lc.period,
            fixed_point: Tuple(lc.fixed_point.z.clone()),
            residual: lc.fixed_point.residual,
            iterations: lc.fixed_point.iterations,
            multipliers: Complexes(lc.multipliers.iter().map(|m| (m.re, m.im)).collect()),
            floquet_max: lc.floquet_max(),
            stable: lc.is_stable(),
            label: label.to_string(),
            step_times: Tuple(lc.steps.iter().map(|s| s.time).collect()),
        }
    }
}

fields_class! {
/// Eigen-frequencies of one design (rtw-model's ``modal``), in Hz.
///
/// Attributes:
///     s18_hz: the supplementary's S18 ``f_n`` of the derived constants.
///     approx_hz: undamped frequencies of the approximate 3-rotor model's
///         oscillating modes (``√3 f_n`` twice at zero rest length).
///     approx_damped_hz: damped frequencies of its complex pairs.
///     approx_damping_ratio: their damping ratios, same order.
///     star_hz: the nine frequencies of the free 9-DOF star, sorted; the
///         first ``star_rigid_modes`` are rigid (≈ 0).
///     star_rigid_modes: how many of ``star_hz`` are rigid modes (3).
    Modes {
        s18_hz: f64,
        approx_hz: Floats,
        approx_damped_hz: Floats,
        approx_damping_ratio: Floats,
        star_hz: Floats,
        star_rigid_modes: usize,
    }
}

impl Modes {
    pub(crate) fn new(
        s18_hz: f64,
        approx: &rtw_model::modal::ApproxModes,
        star: &rtw_model::modal::StarModes,
    ) -> Self {
        Self {
            s18_hz,
            approx_hz: Tuple(approx.freq_hz.clone()),
            approx_damped_hz: Tuple(approx.damped_freq_hz.clone()),
            approx_damping_ratio: Tuple(approx.damping_ratio.clone()),
            star_hz: Tuple(star.freq_hz.to_vec()),
            star_rigid_modes: star.rigid_modes,
        }
    }
}

/// A pyarrow table as a field: compared with pyarrow's `==` (`Table.equals`)
/// without its [`MEASURED`] columns, so that two identical studies are equal.
pub(crate) struct TableField(pub(crate) Py<PyAny>);

impl TableField {
    /// The table without the columns that measure the machine.
    fn results<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let table = self.0.bind(py);
        let names: Vec<String> = table.getattr("column_names")?.extract()?;
        let measured: Vec<&str> = MEASURED
            .into_iter()
            .filter(|m| names.iter().any(|n| n == m))
            .collect();
        table.call_method1("drop_columns", (measured,))
    }
}

impl PartialEq for TableField {
    fn eq(&self, other: &Self) -> bool {
        Python::attach(|py| match (self.results(py), other.results(py)) {
            (Ok(a), Ok(b)) => a.eq(b).unwrap_or(false),
            _ => false,
        })
    }
}

impl<'py> IntoPyObject<'py> for &TableField {
    type Target = PyAny;
    type Output = Bound<'py, PyAny>;
    type Error = PyErr;
    fn into_pyobject(self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        Ok(self.0.bind(py).clone())
    }
}

/// Intervals `(lo, hi)`, which Python sees as a tuple of pairs.
type Intervals = Tuple<(f64, f64)>;

/// Each stable gait's intervals, which Python sees as a `dict`.
#[derive(PartialEq)]
pub(crate) struct GaitIntervals(pub(crate) Vec<(&'static str, Intervals)>);

impl<'py> IntoPyObject<'py> for &GaitIntervals {
    type Target = PyDict;
    type Output = Bound<'py, PyDict>;
    type Error = PyErr;
    fn into_pyobject(self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (gait, i) in &self.0 {
            d.set_item(*gait, i)?;
        }
        Ok(d)
    }
}

/// Label changes `(phi_left, phi_right, label_left, label_right, sharp)`,
/// which Python sees as a tuple of tuples.
type Changes = Tuple<(f64, f64, &'static str, &'static str, bool)>;

fields_class! {
/// A design's slope profile (``rtw-scan profile``): its gait along φ, each
/// change of label located to ``tol`` by bisection.
///
/// Attributes:
///     intervals: each stable gait (``walk``, ``skip``, ``crawl``) → its
///         intervals ``(lo, hi)`` of slopes (rad), each end a simulated slope
///         with that gait.
///     stable_intervals: the intervals of stable slopes, whatever the gait
///         (neighbouring stable intervals joined).
///     phi_min: the shallowest stable slope (``None``: none in the range).
///     phi_lo: the start of the widest interval of stable slopes.
///     phi_hi: its end.
///     changes: every change of label, ``(phi_left, phi_right, label_left,
///         label_right, sharp)``, ``phi_right - phi_left <= tol``, in φ order;
///         ``sharp``: the labels one ``tol`` either side of its middle are
///         ``label_left`` and ``label_right`` (not so where two labels
///         interleave at scales below ``tol``).
///     runs: the simulations made (grid and bisection).
///     table: every simulated slope as a ``pyarrow.Table``, in φ order, with
///         the columns of a scan's rows (docs/data-dictionary.md).
    Profile {
        intervals: GaitIntervals,
        stable_intervals: Intervals,
        phi_min: Option<f64>,
        phi_lo: Option<f64>,
        phi_hi: Option<f64>,
        changes: Changes,
        runs: usize,
        table: TableField,
    }
}

impl Profile {
    pub(crate) fn new(p: &rtw_studies::profile::Profile, table: Py<PyAny>) -> Self {
        let widest = p.widest();
        Self {
            intervals: GaitIntervals(
                rtw_model::Label::ALL
                    .into_iter()
                    .filter(|l| l.is_stable())
                    .map(|l| (l.as_str(), Tuple(p.intervals(l))))
                    .collect(),
            ),
            stable_intervals: Tuple(p.stable_intervals()),
            phi_min: p.phi_min(),
            phi_lo: widest.map(|w| w.0),
            phi_hi: widest.map(|w| w.1),
            changes: Tuple(
                p.changes
                    .iter()
                    .map(|c| {
                        (
                            c.phi_left,
                            c.phi_right,
                            c.label_left.as_str(),
                            c.label_right.as_str(),
                            c.sharp(),
                        )
                    })
                    .collect(),
            ),
            runs: p.runs(),
            table: TableField(table),
        }
    }
}

fields_class! {
/// A design search (``rtw-scan design``): every evaluated design and the
/// reported ones.
///
/// Attributes:
///     summary: the search's summary (``search.md``), Markdown.
///     runs: the simulations spent.
///     evaluations: every evaluated design as a ``pyarrow.Table``, in order
///         (the columns of ``search.parquet``, docs/design.md).
///     designs: the reported designs (the Pareto front, or the best), each
///         profiled again on the fine grid, as a ``pyarrow.Table`` (the
///         columns of ``designs.parquet``): ``phi_lo`` and ``phi_hi`` are
///         that profile's widest stable interval, checked by direct
///         simulation and cut to its widest run of stable checked slopes.
///     archive: the best design of each archive cell, as a ``pyarrow.Table``
///         (the columns of ``archive.parquet``).
    DesignSearch {
        summary: String,
        runs: u64,
        evaluations: TableField,
        designs: TableField,
        archive: TableField,
    }
}

impl DesignSearch {
    pub(crate) fn new(
        summary: String,
        runs: u64,
        evaluations: Py<PyAny>,
        designs: Py<PyAny>,
        archive: Py<PyAny>,
    ) -> Self {
        Self {
            summary,
            runs,
            evaluations: TableField(evaluations),
            designs: TableField(designs),
            archive: TableField(archive),
        }
    }
}

/// A library warning as Python's `UserWarning`, pointing at the caller of
/// the `rtw` wrapper that called in (stacklevel 2); nothing when `None`.
pub(crate) fn warn(py: Python<'_>, warning: Option<String>) -> PyResult<()> {
    let Some(warning) = warning else {
        return Ok(());
    };
    let message = std::ffi::CString::new(warning)
        .map_err(|e| pyo3::exceptions::PyValueError::new_err(e.to_string()))?;
    let category = py.get_type::<pyo3::exceptions::PyUserWarning>();
    PyErr::warn(py, category.as_any(), &message, 2)
}
