//! Signals: SIGINT (Ctrl-C), SIGTERM and SIGHUP stop a `run` (the
//! library's stop flag, [`STOP`], which also ends the samples in flight at
//! their runs' next step), keeping its finished chunks, and end any other
//! command at once, its temporary files removed.

use anyhow::{Context, Result};
use rtw_engine::files;
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

/// Exit code of a command whose stdout was closed before it finished
/// writing (`rtw-scan … | head -c 1`): 128 + SIGPIPE, what a shell reports
/// for a process a closed pipe ended.
pub(super) const EXIT_STDOUT_CLOSED: i32 = 141;

/// Writes `args` to stdout, as `print!` does, for every command through
/// [`out!`](super::out) and [`outln!`](super::outln). A closed stdout
/// (EPIPE) ends the process quietly with [`EXIT_STDOUT_CLOSED`]: what it
/// prints comes after its files are finished, so they are kept, and its
/// temporary and lock files are removed, as a signal's exit removes them.
///
/// Why not SIGPIPE's default action, which ends a process at its first write
/// to a closed pipe? It ends it where it stands, with no chance to remove
/// its temporary files (a write to stdout while a file is half written would
/// leave it), and it would end Python's process too where the library is
/// loaded into it. Here the one place that writes stdout decides.
pub(super) fn print_out(args: std::fmt::Arguments<'_>) {
    use std::io::Write;
    let mut stdout = std::io::stdout().lock();
    let written = stdout.write_fmt(args).and_then(|()| stdout.flush());
    let Err(e) = written else {
        return;
    };
    files::remove_live_files();
    if e.kind() == std::io::ErrorKind::BrokenPipe {
        std::process::exit(EXIT_STDOUT_CLOSED);
    }
    eprintln!("error: cannot write to stdout: {e}");
    std::process::exit(1);
}
