//! One run as `rtw-scan simulate` makes it, in memory: its row's values (what
//! `simulate --json` prints) and its trace as the table `simulate --trace`
//! writes. The Python package returns these.

use crate::io::kv;
use crate::io::metadata::with_metadata;
use crate::io::scan_rows::{JsonRow, Value, robustness_entries, values};
use crate::io::trace::{TraceNames, check_trace_size, trace_batch, trace_metadata};
use crate::scan::one::run_one;
use crate::sizes::human_bytes;
use anyhow::{Result, anyhow, bail};
use arrow_array::RecordBatch;
use rtw_model::{Options, Params};

/// Schema-metadata key of a trace returned in memory that holds its run's
/// row, the JSON object of `simulate --json`.
pub const META_OUTCOME: &str = "rtw.outcome";

/// One run's row as `simulate --json` prints it: the values in column order
/// ([`crate::io::row_columns`]), then the robustness measures the options
/// asked for (`robustness.*`, after the columns and only when asked for).
#[derive(Clone, Debug, PartialEq)]
pub struct RowValues {
    /// The scan row's values, in column order.
    pub columns: Vec<Value>,
    /// The robustness measures asked for, by name (`step_down_max`, m;
    /// `steps_to_fall` and its interval and censored count).
    pub robustness: Vec<(&'static str, Value)>,
}

/// Runs `params` with `options` (panics caught, as in a scan) and returns
/// its row's values, as `simulate --json` prints them.
pub fn simulate_row(params: Params, options: &Options) -> RowValues {
    let row = run_one(0, params, options, rtw_model::simulate);
    RowValues {
        columns: values(&row),
        robustness: robustness_entries(&row, &options.robustness)
            .into_iter()
            .map(|(k, v)| (k, Value::Float(crate::io::robustness_columns::kept(v))))
            .collect(),
    }
}

/// The run of [`simulate_row`] as its trace: the columns and field metadata
/// of a `simulate --trace` file, its file metadata (version, parameters,
/// options) and the run's row as JSON ([`META_OUTCOME`]) in the schema. A
/// trace estimated above `limit` bytes is refused before the run, in the
/// caller's `names`.
pub fn simulate_traced(
    params: Params,
    options: &Options,
    limit: u64,
    names: TraceNames,
) -> Result<RecordBatch> {
    if let Some(memory) = physical_memory()
        && limit > memory
    {
        bail!(
            "{}: {} is more than this machine's memory ({}): a trace returned in memory must fit \
             in it; write a longer trace to a file with `rtw-scan simulate ... --trace FILE.parquet \
             --trace-limit SIZE`",
            names.limit,
            human_bytes(limit as f64),
            human_bytes(memory as f64)
        );
    }
    check_trace_size(options, limit, names)?;
    let mut samples = Vec::new();
    // The estimate is an upper bound; should memory still run out, the
    // trace stops growing and the call fails instead of aborting.
    let mut full = None;
    let row = run_one(0, params, options, |p: &Params, o: &Options| {
        rtw_model::simulate_traced(p, o, &mut |s| {
            if full.is_none() {
                match samples.try_reserve(1) {
                    Ok(()) => samples.push(*s),
                    Err(e) => full = Some(e),
                }
            }
        })
    });
    if let Some(e) = full {
        return Err(anyhow!(e).context(format!(
            "the trace ran out of memory after {} samples: raise {}",
            samples.len(),
            names.dt
        )));
    }
    let mut metadata = trace_metadata(&params, options)?;
    metadata.push(kv(
        META_OUTCOME,
        serde_json::to_string(&JsonRow(&row, &options.robustness))?,
    ));
    Ok(with_metadata(trace_batch(&samples), metadata)?)
}

/// The machine's memory in bytes (`MemTotal` of `/proc/meminfo`), where the
/// system tells it: the bound of what a call may hold in memory.
pub fn physical_memory() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemTotal:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    kib.checked_mul(1024)
}
