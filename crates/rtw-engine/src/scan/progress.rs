//! What watches a scan as it runs ([`Progress`]): the library reports to it
//! and shows nothing itself. The command line's bar and lines on stderr, and
//! Python's `progress(done, total)` callback, are implementations of it.

use rtw_model::Label;
use std::sync::atomic::{AtomicU64, Ordering};

/// Watches a scan: the runner calls it from its worker threads as the rows
/// come in, and with what the user of a run into files should know. Every
/// method but [`Progress::computed`] does nothing unless implemented.
pub trait Progress: Sync {
    /// The run starts, after its checks, with `total` rows to hold (a
    /// shard's own rows for a shard), those kept from an interrupted run
    /// included.
    fn start(&self, total: u64) {
        let _ = total;
    }

    /// The runs that follow are one stage of a longer study ("round 2 of
    /// 16" of a refinement): each has its own [`Progress::start`] and count.
    fn stage(&self, text: &str) {
        let _ = text;
    }

    /// A row kept from an interrupted run (`--resume`), with its label.
    fn kept(&self, label: Label) {
        let _ = label;
    }

    /// A row just computed, with its label.
    fn computed(&self, label: Label);

    /// One unit of a study's work that has no label done (a basin slice's
    /// grid point, a bootstrap resample of a sensitivity analysis), out of
    /// the `total` of its [`Progress::start`].
    fn advanced(&self) {}

    /// A detail of the run's progress (a damaged chunk computed again), for
    /// a display that shows the progress.
    fn note(&self, text: &str) {
        let _ = text;
    }

    /// Something the user must learn even when no progress is shown: a file
    /// rtw-scan did not make, left in place.
    fn warn(&self, text: &str) {
        let _ = text;
    }

    /// The run ended: every row in (`complete`), or stopped with its
    /// finished chunks kept.
    fn finish(&self, complete: bool) {
        let _ = complete;
    }
}

/// Nothing watches the scan.
pub struct Silent;

impl Progress for Silent {
    fn computed(&self, _: Label) {}
}

/// A counter of the rows computed, read from another thread while the scan
/// runs (Python's `rtw.scan` calls `progress(done, total)` with it).
impl Progress for AtomicU64 {
    fn computed(&self, _: Label) {
        self.fetch_add(1, Ordering::Relaxed);
    }

    fn advanced(&self) {
        self.fetch_add(1, Ordering::Relaxed);
    }
}

/// A study's progress read from another thread while it runs: its total
/// (set by [`Progress::start`]), the units done (Python's studies call
/// `progress(done, total)` with them), and the notes and warnings the study
/// said since they were last taken ([`Counter::take_said`]: Python makes
/// the warnings `UserWarning`s and logs the notes).
#[derive(Debug, Default)]
pub struct Counter {
    /// Units done: rows computed or kept, or unlabelled units.
    pub done: AtomicU64,
    /// The total of the last [`Progress::start`].
    pub total: AtomicU64,
    said: std::sync::Mutex<Said>,
}

/// What a study said through [`Progress::note`] and [`Progress::warn`].
#[derive(Debug, Default)]
pub struct Said {
    /// Its notes, in order.
    pub notes: Vec<String>,
    /// Its warnings, in order.
    pub warnings: Vec<String>,
}

impl Counter {
    /// The notes and warnings said since the last call, taken.
    pub fn take_said(&self) -> Said {
        std::mem::take(&mut *self.said.lock().unwrap_or_else(|e| e.into_inner()))
    }
}

impl Progress for Counter {
    fn start(&self, total: u64) {
        self.done.store(0, Ordering::Relaxed);
        self.total.store(total, Ordering::Relaxed);
    }

    fn kept(&self, _: Label) {
        self.done.fetch_add(1, Ordering::Relaxed);
    }

    fn computed(&self, _: Label) {
        self.done.fetch_add(1, Ordering::Relaxed);
    }

    fn advanced(&self) {
        self.done.fetch_add(1, Ordering::Relaxed);
    }

    fn note(&self, text: &str) {
        let mut said = self.said.lock().unwrap_or_else(|e| e.into_inner());
        said.notes.push(text.to_string());
    }

    fn warn(&self, text: &str) {
        let mut said = self.said.lock().unwrap_or_else(|e| e.into_inner());
        said.warnings.push(text.to_string());
    }
}
