//! One sample's row, the unit of work of every scan and of a single run
//! (`rtw-scan simulate`, Python's `simulate`).

use crate::io::scan_rows::Row;
use crate::scan::panic::catch_panic;
use rtw_model::{Options, Outcome, Params, Physical};
use std::time::Instant;

/// A simulator: `rtw_model::simulate` or a test double.
pub type Simulator<'a> = &'a (dyn Fn(&Params, &Options) -> Outcome + Sync);

/// Runs one sample: derived parameters, the simulation (panics caught) and
/// its wall time. Used by scans and by `rtw-scan simulate`.
pub fn run_one(
    sample_id: u64,
    params: Params,
    options: &Options,
    sim: impl FnOnce(&Params, &Options) -> Outcome,
) -> Row {
    let physical = Physical::new(&params, options.normalization, options.g);
    let started = Instant::now();
    let (outcome, message) = match params.validate() {
        Err(e) => (None, Some(format!("invalid parameters: {e}"))),
        Ok(()) => match catch_panic(|| sim(&params, options)) {
            Ok(o) => (Some(o), None),
            Err(msg) => (None, Some(msg)),
        },
    };
    Row {
        sample_id,
        params,
        physical,
        outcome,
        message,
        wall_time_s: started.elapsed().as_secs_f64(),
    }
}
