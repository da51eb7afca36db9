//! Signals: SIGINT (Ctrl-C), SIGTERM and SIGHUP stop a `run` (the
//! library's stop flag, [`STOP`], which also ends the samples in flight at
//! their runs' next step), keeping its finished chunks, and end any other
//! command at once, its temporary files removed.

use crate::files;
use anyhow::{Context, Result};
use std::sync::atomic::{AtomicBool, Ordering};

/// Exit code of a command stopped by SIGINT (Ctrl-C), SIGTERM (what Slurm
/// and `kill` send) or SIGHUP (a closed terminal): 128 + SIGINT, for all three.
pub(super) const EXIT_INTERRUPTED: u8 = 130;

/// Set by the first signal of a `run`, which then stops its samples in
/// flight and keeps its finished chunks.
pub(super) static STOP: AtomicBool = AtomicBool::new(false);
/// Whether the command in progress stops gracefully on a first signal
/// (`run`); every other command removes its temporary files and exits.
pub(super) static GRACEFUL: AtomicBool = AtomicBool::new(false);

/// SIGINT, SIGTERM and SIGHUP (ctrlc's `termination` feature) all end a
/// command the same way, with [`EXIT_INTERRUPTED`].
pub(super) fn install_signal_handler() -> Result<()> {
    ctrlc::set_handler(|| {
        if GRACEFUL.load(Ordering::SeqCst) {
            if !STOP.swap(true, Ordering::SeqCst) {
                eprintln!(
                    "rtw-scan: interrupted: stopping the samples in flight, keeping the finished chunks (interrupt again to quit at once)"
                );
                return;
            }
            eprintln!("rtw-scan: second interrupt, exiting now");
        }
        files::remove_live_files();
        std::process::exit(EXIT_INTERRUPTED.into());
    })
    .context("cannot install the signal handler")
}
