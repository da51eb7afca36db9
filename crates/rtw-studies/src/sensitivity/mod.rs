//! Sobol sensitivity indices of a scan's outputs to its uniform inputs.
//!
//! Outputs: each outcome label as an indicator (1 where the sample has it,
//! 0 elsewhere), `stable` (skip, walk or crawl) and `failure` (the rest: they
//! are complements, so their indices are equal), and the continuous outputs
//! `speed`, `f_w` and `floquet_max` (the last only where every row has one,
//! i.e. a scan with `limit_cycle = true` in which every sample found one).
//! A failed sample is a value of every indicator and is never dropped.
//!
//! - A scan run with `sampling = "saltelli"`: first-order and total indices
//!   by the estimators SALib's `sobol.analyze(calc_second_order=False)` uses
//!   (Saltelli et al. 2010, Comput. Phys. Commun. 181:259, for S1; Jansen
//!   1999 for ST, both over the variance of the `A` and `B` rows), on the
//!   output standardised by its mean and standard deviation, as SALib does.
//!   A constant output has every index 0, as in SALib.
//! - Any other scan: the given-data first-order estimator SALib's
//!   `delta.analyze` computes as `S1` (Plischke 2010's equal-frequency
//!   bins: the variance of the bin means over the output's variance; ST is
//!   not estimable from given data and is NaN).
//!
//! Confidence: `Z₀.₉₇₅ × ` the standard deviation (ddof 1) of the index over
//! bootstrap resamples (of base rows, or of rows), drawn from a seed.

mod binned;
mod study;
mod summary;

pub use summary::{WIDE, markdown, wide_warning};

pub use binned::binned;

pub use study::{
    Analysis, RESAMPLES, Settings, analyse_file, analyse_table, analyse_to_file, check_out,
    scan_file, write,
};

use anyhow::{Result, anyhow, bail};
use arrow_array::{Array, Float64Array, RecordBatch, StringArray};
use arrow_schema::{DataType, Field, Schema};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rtw_engine::analysis::report::Z95;
use rtw_engine::config::ScanConfig;
use rtw_engine::config::axis::Axis;
use rtw_engine::config::count::count;
use rtw_engine::io::table::{f64_column, label_column};
use rtw_engine::sampling::Sampling;
use rtw_engine::scan::progress::Progress;
use rtw_engine::scan::workers::Stopped;
use rtw_model::Param;
use rtw_model::outcome::Label;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

/// One row of `indices.parquet`.
#[derive(Clone, Debug, PartialEq)]
pub struct Index {
    /// The output: a label, `stable`, `failure`, or a continuous column.
    pub output: String,
    /// The input (a uniform axis of the scan).
    pub parameter: &'static str,
    /// First-order index.
    pub s1: f64,
    /// Half-width of its 95 % bootstrap interval.
    pub s1_conf: f64,
    /// Total index (NaN from given data).
    pub st: f64,
    /// Half-width of its 95 % bootstrap interval (NaN from given data).
    pub st_conf: f64,
}

/// How the indices were estimated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// A Saltelli design: S1 (Saltelli 2010) and ST (Jansen).
    Saltelli,
    /// Given data: binned first-order indices only.
    Binned,
}

impl Method {
    /// The method's name in the file's metadata and in messages.
    pub fn name(self) -> &'static str {
        match self {
            Method::Saltelli => "saltelli",
            Method::Binned => "binned-first-order",
        }
    }
}

/// The scan's rows, columns as vectors in sample-id order.
pub struct Columns {
    /// The uniform inputs: name and values.
    pub inputs: Vec<(&'static str, Vec<f64>)>,
    /// The outputs: name and values (finite or NaN).
    pub outputs: Vec<(String, Vec<f64>)>,
}

/// The continuous outputs analysed where every row has a value.
const CONTINUOUS: [&str; 3] = ["speed", "f_w", "floquet_max"];

/// Reads the inputs and outputs of a scan's batches (in sample-id order),
/// keeping only those columns.
pub fn columns(
    cfg: &ScanConfig,
    batches: impl IntoIterator<Item = Result<RecordBatch>>,
) -> Result<Columns> {
    let uniform: Vec<&'static str> = Param::ALL
        .iter()
        .zip(&cfg.params)
        .filter(|(_, a)| matches!(a, Axis::Uniform { .. }))
        .map(|(i, _)| i.name())
        .collect();
    let mut inputs: Vec<(&'static str, Vec<f64>)> =
        uniform.iter().map(|n| (*n, Vec::new())).collect();
    let mut labels = Vec::new();
    let mut continuous: Vec<(&str, Vec<f64>, bool)> =
        CONTINUOUS.iter().map(|n| (*n, Vec::new(), true)).collect();
    for b in batches {
        let b = &b?;
        for (name, v) in inputs.iter_mut() {
            v.extend(f64_column(b, name)?.values().iter());
        }
        labels.extend(label_column(b)?);
        for (name, v, complete) in continuous.iter_mut() {
            let c = f64_column(b, name)?;
            *complete &= c.null_count() == 0;
            // A run without a value has a null: a NaN is no value rtw-scan
            // writes, and would silently drop the output.
            if let Some(i) = (0..c.len()).find(|&i| c.is_valid(i) && !c.value(i).is_finite()) {
                bail!(
                    "column `{name}`, row {}: {} is invalid: must be a finite number or null; the \
                     file is corrupt or was not written by rtw-scan",
                    v.len() + i,
                    c.value(i)
                );
            }
            v.extend((0..c.len()).map(|i| if c.is_null(i) { f64::NAN } else { c.value(i) }));
        }
    }
    let indicator = |f: &dyn Fn(Label) -> bool| -> Vec<f64> {
        labels.iter().map(|l| f64::from(u8::from(f(*l)))).collect()
    };
    let mut outputs: Vec<(String, Vec<f64>)> = Label::ALL
        .iter()
        .map(|l| (l.as_str().to_string(), indicator(&|x| x == *l)))
        .collect();
    outputs.push(("stable".into(), indicator(&|x| x.is_stable())));
    outputs.push(("failure".into(), indicator(&|x| x.is_failure())));
    for (name, v, complete) in continuous {
        if complete {
            outputs.push((name.to_string(), v));
        }
    }
    Ok(Columns { inputs, outputs })
}

/// Population mean and variance.
fn mean_var(y: impl Iterator<Item = f64> + Clone) -> (f64, f64) {
    let (n, s) = y.clone().fold((0usize, 0.0), |(n, s), v| (n + 1, s + v));
    let m = s / n as f64;
    let var = y.map(|v| (v - m) * (v - m)).sum::<f64>() / n as f64;
    (m, var)
}

/// The sample standard deviation (ddof 1).
fn std1(v: &[f64]) -> f64 {
    let (_, var) = mean_var(v.iter().copied());
    (var * v.len() as f64 / (v.len() as f64 - 1.0)).sqrt()
}

/// S1 and ST of each of `d` inputs from the base rows `rows` of a
/// standardised Saltelli output `y` (`N (d + 2)` values, SALib's order).
fn saltelli_once(y: &[f64], d: usize, rows: &[usize]) -> Vec<(f64, f64)> {
    let w = d + 2;
    let a = |j: usize| y[j * w];
    let b = |j: usize| y[j * w + d + 1];
    let ab = |j: usize, k: usize| y[j * w + 1 + k];
    let all = rows.iter().flat_map(|&j| [a(j), b(j)]);
    let (lo, hi) = all
        .clone()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
            (l.min(v), h.max(v))
        });
    let (_, var) = mean_var(all);
    let n = rows.len() as f64;
    (0..d)
        .map(|k| {
            if hi - lo <= f64::EPSILON || var <= f64::EPSILON {
                return (0.0, 0.0);
            }
            let s1 = rows.iter().map(|&j| b(j) * (ab(j, k) - a(j))).sum::<f64>() / n / var;
            let st = 0.5 * rows.iter().map(|&j| (a(j) - ab(j, k)).powi(2)).sum::<f64>() / n / var;
            (s1, st)
        })
        .collect()
}

/// S1, S1_conf, ST, ST_conf of each input from a Saltelli output `y`
/// (`N (d + 2)` values in SALib's order), with `resamples` bootstrap
/// resamples of the base rows drawn from `seed`.
/// Setting `cancel` ends it between two resamples, with `None`.
pub fn saltelli(
    y: &[f64],
    d: usize,
    resamples: usize,
    seed: u64,
    cancel: &AtomicBool,
    progress: &dyn Progress,
) -> Option<Vec<[f64; 4]>> {
    let n = y.len() / (d + 2);
    let (m, var) = mean_var(y.iter().copied());
    let sd = var.sqrt();
    let z: Vec<f64> = y.iter().map(|v| (v - m) / sd).collect();
    let constant = sd.is_nan() || sd <= 0.0;
    let base: Vec<usize> = (0..n).collect();
    let point = if constant {
        vec![(0.0, 0.0); d]
    } else {
        saltelli_once(&z, d, &base)
    };
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let boot: Vec<Vec<(f64, f64)>> = (0..resamples)
        .map(|_| {
            if cancel.load(Ordering::Relaxed) {
                return None;
            }
            let rows: Vec<usize> = (0..n).map(|_| rng.random_range(0..n)).collect();
            let once = if constant {
                vec![(0.0, 0.0); d]
            } else {
                saltelli_once(&z, d, &rows)
            };
            progress.advanced();
            Some(once)
        })
        .collect::<Option<_>>()?;
    Some(
        (0..d)
            .map(|k| {
                let s1: Vec<f64> = boot.iter().map(|r| r[k].0).collect();
                let st: Vec<f64> = boot.iter().map(|r| r[k].1).collect();
                [point[k].0, Z95 * std1(&s1), point[k].1, Z95 * std1(&st)]
            })
            .collect(),
    )
}

/// The indices of every output to every uniform input of a complete scan,
/// with `resamples` (in [`RESAMPLES`]) bootstrap resamples drawn from
/// `seed`, `progress` counting the resamples (of each output, and of each
/// input for the binned index). Setting `cancel` ends it between two
/// resamples, with the error [`Stopped`].
pub fn indices(
    cfg: &ScanConfig,
    cols: &Columns,
    resamples: usize,
    seed: u64,
    cancel: &AtomicBool,
    progress: &dyn Progress,
) -> Result<(Method, Vec<Index>)> {
    count("resamples", &resamples.to_string(), RESAMPLES, "")?;
    let d = cols.inputs.len();
    if d == 0 {
        bail!("the scan has no uniform axis: there is no input to attribute its outputs to");
    }
    if cfg.grid_size()? != 1 {
        bail!(
            "the scan has grid axes: its indices would mix the grid points; scan each grid point \
             on its own (fixed values) to analyse it"
        );
    }
    let rows = cols.outputs.first().map_or(0, |(_, y)| y.len());
    if rows as u64 != cfg.total_rows()? {
        bail!(
            "the scan has {rows} rows of {}: analyse the merged scan (rtw-scan merge), not a part",
            cfg.total_rows()?
        );
    }
    let method = if cfg.sampling == Sampling::Saltelli {
        Method::Saltelli
    } else {
        Method::Binned
    };
    // A resample of one output (of one output to one input, binned) is the
    // unit of progress.
    let per_output = match method {
        Method::Saltelli => resamples,
        Method::Binned => resamples * d,
    };
    progress.start((per_output * cols.outputs.len()) as u64);
    // Every output to every input at once: they share each resample's rows.
    let given_data = match method {
        Method::Saltelli => None,
        Method::Binned => {
            let x: Vec<&[f64]> = cols.inputs.iter().map(|(_, x)| x.as_slice()).collect();
            let y: Vec<&[f64]> = cols.outputs.iter().map(|(_, y)| y.as_slice()).collect();
            Some(
                binned(&x, &y, resamples, seed, cancel, progress)
                    .ok_or_else(|| anyhow!(Stopped))?,
            )
        }
    };
    let mut out = Vec::new();
    for (o, (name, y)) in cols.outputs.iter().enumerate() {
        let rows = match &given_data {
            None => {
                saltelli(y, d, resamples, seed, cancel, progress).ok_or_else(|| anyhow!(Stopped))?
            }
            Some(s1) => s1[o]
                .iter()
                .map(|&[s1, c]| [s1, c, f64::NAN, f64::NAN])
                .collect(),
        };
        for ((parameter, _), [s1, s1_conf, st, st_conf]) in cols.inputs.iter().zip(rows) {
            out.push(Index {
                output: name.clone(),
                parameter,
                s1,
                s1_conf,
                st,
                st_conf,
            });
        }
    }
    Ok((method, out))
}

/// The indices as one record batch: output, parameter, S1, S1_conf, ST, ST_conf.
pub fn to_batch(rows: &[Index]) -> RecordBatch {
    let f = |name: &str| Field::new(name, DataType::Float64, false);
    let schema = Schema::new(vec![
        Field::new("output", DataType::Utf8, false),
        Field::new("parameter", DataType::Utf8, false),
        f("S1"),
        f("S1_conf"),
        f("ST"),
        f("ST_conf"),
    ]);
    let col = |g: fn(&Index) -> f64| -> Arc<dyn Array> {
        Arc::new(Float64Array::from_iter_values(rows.iter().map(g)))
    };
    RecordBatch::try_new(
        Arc::new(schema),
        vec![
            Arc::new(StringArray::from_iter_values(
                rows.iter().map(|r| &r.output),
            )),
            Arc::new(StringArray::from_iter_values(
                rows.iter().map(|r| r.parameter),
            )),
            col(|r| r.s1),
            col(|r| r.s1_conf),
            col(|r| r.st),
            col(|r| r.st_conf),
        ],
    )
    .expect("the indices' columns match their schema")
}

#[cfg(test)]
mod tests {
    use super::*;
    use rtw_engine::scan::progress::Silent;

    /// The Ishigami function, whose indices are known in closed form.
    fn ishigami(x: [f64; 3]) -> f64 {
        let [a, b, c] = x.map(|u| -std::f64::consts::PI + 2.0 * std::f64::consts::PI * u);
        a.sin() + 7.0 * b.sin().powi(2) + 0.1 * c.powi(4) * a.sin()
    }

    #[test]
    fn saltelli_indices_of_ishigami_match_the_closed_form() {
        use rtw_engine::sampling::Design;
        let n = 1 << 13;
        let design = Design::new(Sampling::Saltelli, 3, n, 3).unwrap();
        let y: Vec<f64> = (0..n * 5)
            .map(|i| {
                let mut p = [0.0; 3];
                design.point(i, &[], &mut p);
                ishigami(p)
            })
            .collect();
        let go = AtomicBool::new(false);
        let s = saltelli(&y, 3, 100, 1, &go, &Silent).unwrap();
        // Ishigami (a = 7, b = 0.1): S1 = 0.314, 0.442, 0; ST = 0.558, 0.442, 0.244.
        let (s1, st) = ([0.3139, 0.4424, 0.0], [0.5576, 0.4424, 0.2437]);
        for k in 0..3 {
            assert!((s[k][0] - s1[k]).abs() < 0.03, "S1 {k}: {:?}", s[k]);
            assert!((s[k][2] - st[k]).abs() < 0.03, "ST {k}: {:?}", s[k]);
            assert!(s[k][1] > 0.0 && s[k][1] < 0.1 && s[k][3] > 0.0 && s[k][3] < 0.1);
        }
        // A constant output has no influence, as in SALib.
        assert_eq!(
            saltelli(&vec![1.0; 50], 3, 10, 1, &go, &Silent).unwrap()[0],
            [0.0; 4]
        );
        // A set cancel flag ends it.
        assert!(saltelli(&y, 3, 100, 1, &AtomicBool::new(true), &Silent).is_none());
    }
}
