//! A run's progress on stderr: a bar on a terminal, plain lines otherwise
//! (the library's [`Progress`] observer, as the command line shows it).

use crate::io::scan_rows::label_index;
use crate::scan::progress::Progress;
use indicatif::{ProgressBar, ProgressStyle};
use rtw_model::Label;
use std::io::IsTerminal;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Mutex, OnceLock};
use std::time::{Duration, Instant};

/// How progress is shown on stderr.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum ProgressMode {
    /// A bar when stderr is a terminal, else plain lines.
    Auto,
    /// Plain lines every 5 s or 10 %.
    Lines,
    /// Nothing.
    Quiet,
}

/// Progress on stderr: a bar on a terminal, plain lines otherwise. The bar
/// is drawn from [`Progress::start`] on, once the run has passed its checks.
pub(crate) struct StderrProgress {
    mode: ProgressMode,
    bar: OnceLock<ProgressBar>,
    lines: Option<Mutex<LineState>>,
    counts: [AtomicU64; 6],
    done: AtomicU64,
    previous: AtomicU64,
    total: AtomicU64,
    started: OnceLock<Instant>,
}

struct LineState {
    last: Instant,
    decile: u64,
    /// `done` at the last line printed.
    printed: u64,
}

impl StderrProgress {
    const EVERY: Duration = Duration::from_secs(5);

    pub(crate) fn new(mode: ProgressMode) -> Self {
        let terminal = std::io::stderr().is_terminal();
        let lines = (mode == ProgressMode::Lines || (mode == ProgressMode::Auto && !terminal))
            .then(|| {
                Mutex::new(LineState {
                    last: Instant::now(),
                    decile: 0,
                    printed: 0,
                })
            });
        Self {
            mode,
            bar: OnceLock::new(),
            lines,
            counts: Default::default(),
            done: AtomicU64::new(0),
            previous: AtomicU64::new(0),
            total: AtomicU64::new(0),
            started: OnceLock::new(),
        }
    }

    fn count(&self, label: Label) {
        let i = label_index(label);
        self.counts[i].fetch_add(1, Ordering::Relaxed);
        self.done.fetch_add(1, Ordering::Relaxed);
    }

    fn counts_text(&self) -> String {
        Label::ALL
            .iter()
            .zip(&self.counts)
            .map(|(l, c)| format!("{l} {}", c.load(Ordering::Relaxed)))
            .collect::<Vec<_>>()
            .join(", ")
    }

    fn line(&self) -> String {
        let done = self.done.load(Ordering::Relaxed);
        let new = done - self.previous.load(Ordering::Relaxed);
        let secs = self
            .started
            .get()
            .map_or(0.0, |t| t.elapsed().as_secs_f64());
        let total = self.total.load(Ordering::Relaxed);
        let rate = new as f64 / secs.max(1e-9);
        let eta = if rate > 0.0 {
            format!("{:.0} s", (total - done) as f64 / rate)
        } else {
            "?".into()
        };
        format!(
            "[{secs:.1} s] {done}/{} ({:.1} %), {rate:.2} samples/s, ETA {eta} | {}",
            total,
            100.0 * done as f64 / total.max(1) as f64,
            self.counts_text()
        )
    }
}

impl Progress for StderrProgress {
    fn start(&self, total: u64) {
        self.total.store(total, Ordering::Relaxed);
        let _ = self.started.set(Instant::now());
        if self.mode == ProgressMode::Auto && self.lines.is_none() {
            let bar = ProgressBar::new(total);
            bar.set_style(
                ProgressStyle::with_template(
                    "{elapsed_precise} [{wide_bar}] {pos}/{len} {per_sec} ETA {eta}\n{msg}",
                )
                .expect("valid template")
                .progress_chars("=> "),
            );
            bar.enable_steady_tick(Duration::from_millis(200));
            let _ = self.bar.set(bar);
        }
    }

    fn kept(&self, label: Label) {
        self.count(label);
        self.previous.fetch_add(1, Ordering::Relaxed);
        if let Some(bar) = self.bar.get() {
            bar.inc(1);
            bar.reset_eta();
        }
    }

    fn computed(&self, label: Label) {
        self.count(label);
        if let Some(bar) = self.bar.get() {
            bar.inc(1);
            bar.set_message(self.counts_text());
        }
        if let Some(lines) = &self.lines {
            let mut st = lines.lock().expect("progress lock");
            let done = self.done.load(Ordering::Relaxed);
            let decile = done * 10 / self.total.load(Ordering::Relaxed).max(1);
            if st.last.elapsed() >= Self::EVERY || decile > st.decile {
                st.last = Instant::now();
                st.decile = decile;
                st.printed = done;
                eprintln!("{}", self.line());
            }
        }
    }

    fn note(&self, text: &str) {
        match self.bar.get() {
            Some(bar) => bar.println(text),
            None if self.lines.is_some() => eprintln!("{text}"),
            None => {}
        }
    }

    fn warn(&self, text: &str) {
        match self.bar.get() {
            Some(bar) => bar.println(text),
            None => eprintln!("{text}"),
        }
    }

    fn finish(&self, complete: bool) {
        if let Some(bar) = self.bar.get() {
            bar.set_message(self.counts_text());
            if complete {
                bar.finish()
            } else {
                bar.abandon()
            }
        }
        if let Some(lines) = &self.lines {
            let st = lines.lock().expect("progress lock");
            if st.printed != self.done.load(Ordering::Relaxed) {
                eprintln!("{}", self.line());
            }
        }
    }
}
