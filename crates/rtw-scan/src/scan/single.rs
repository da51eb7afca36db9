//! One run as `rtw-scan simulate` makes it, in memory: its row as the JSON
//! object `simulate --json` prints and its trace as the table
//! `simulate --trace` writes. The Python package returns these.

use crate::io::metadata::with_metadata;
use crate::io::scan_rows::JsonRow;
use crate::io::trace::{TraceNames, check_trace_size, trace_batch, trace_metadata};
use crate::scan::run::run_one;
use anyhow::Result;
use arrow_array::RecordBatch;
use rtw_model::{Options, Params};

/// Runs `params` with `options` (panics caught, as in a scan) and returns
/// its row as the JSON object of `simulate --json`, keys in column order.
pub fn simulate_json(params: Params, options: &Options) -> Result<String> {
    let row = run_one(0, params, options, rtw_model::simulate);
    Ok(serde_json::to_string(&JsonRow(&row))?)
}

/// [`simulate_json`] with the run's trace: the columns and field metadata
/// of a `simulate --trace` file, its file metadata (version, parameters,
/// options) in the schema. A trace estimated above `limit` bytes is refused
/// before the run, in the caller's `names`.
pub fn simulate_traced_json(
    params: Params,
    options: &Options,
    limit: u64,
    names: TraceNames,
) -> Result<(String, RecordBatch)> {
    check_trace_size(options, limit, names)?;
    let mut samples = Vec::new();
    let row = run_one(0, params, options, |p: &Params, o: &Options| {
        rtw_model::simulate_traced(p, o, &mut |s| samples.push(*s))
    });
    let batch = trace_batch(&samples);
    let batch = with_metadata(batch, trace_metadata(&params, options)?)?;
    Ok((serde_json::to_string(&JsonRow(&row))?, batch))
}
