//! A run's progress on stderr: a bar on a terminal, plain lines otherwise
//! (the library's [`Progress`] observer, as the command line shows it).

use indicatif::{ProgressBar, ProgressStyle};
use rtw_engine::io::scan_rows::label_index;
use rtw_engine::scan::progress::Progress;
use rtw_model::Label;
use std::io::IsTerminal;
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};
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
/// Each [`Progress::start`] (each round of a refinement) counts from 0, its
/// stage ([`Progress::stage`], "round 2 of 16") before its line.
pub(crate) struct StderrProgress {
    mode: ProgressMode,
    bar: Mutex<Option<ProgressBar>>,
    lines: Option<Mutex<LineState>>,
    counts: [AtomicU64; 6],
    done: AtomicU64,
    previous: AtomicU64,
    total: AtomicU64,
    started: Mutex<Option<Instant>>,
    stage: Mutex<String>,
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
            bar: Mutex::new(None),
            lines,
            counts: Default::default(),
            done: AtomicU64::new(0),
            previous: AtomicU64::new(0),
            total: AtomicU64::new(0),
            started: Mutex::new(None),
            stage: Mutex::new(String::new()),
        }
    }

    /// The bar, once [`Progress::start`] drew it.
    fn bar(&self) -> Option<ProgressBar> {
        self.bar.lock().ok()?.clone()
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

    /// Whether the work counted is labelled rows (a scan's), not a study's
    /// units.
    fn labelled(&self) -> bool {
        self.counts.iter().any(|c| c.load(Ordering::Relaxed) > 0)
    }

    /// Progress as a command's `--quiet` flag asks: none, or a bar on a
    /// terminal and plain lines elsewhere.
    pub(crate) fn unless(quiet: bool) -> Self {
        Self::new(if quiet {
            ProgressMode::Quiet
        } else {
            ProgressMode::Auto
        })
    }

    /// A study's progress on stderr (nothing with `quiet`), its units named
    /// by `stage` ("basin: grid points").
    pub(crate) fn study(quiet: bool, stage: &str) -> Self {
        let p = Self::unless(quiet);
        p.stage(stage);
        p
    }

    /// Prints the progress line, in line mode, every [`Self::EVERY`] or
    /// tenth of the total.
    fn show_line(&self) {
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

    fn line(&self) -> String {
        let done = self.done.load(Ordering::Relaxed);
        let new = done - self.previous.load(Ordering::Relaxed);
        let secs = self
            .started
            .lock()
            .ok()
            .and_then(|t| *t)
            .map_or(0.0, |t| t.elapsed().as_secs_f64());
        let total = self.total.load(Ordering::Relaxed);
        let rate = new as f64 / secs.max(1e-9);
        let eta = if rate > 0.0 {
            format!("{:.0} s", (total - done) as f64 / rate)
        } else {
            "?".into()
        };
        let stage = self.stage.lock().map(|s| s.clone()).unwrap_or_default();
        let stage = if stage.is_empty() {
            stage
        } else {
            format!("{stage}: ")
        };
        let (unit, counts) = if self.labelled() {
            (" samples/s", format!(" | {}", self.counts_text()))
        } else {
            // A study's units (grid points, resamples): named by its stage.
            ("/s", String::new())
        };
        format!(
            "{stage}[{secs:.1} s] {done}/{} ({:.1} %), {rate:.2}{unit}, ETA {eta}{counts}",
            total,
            100.0 * done as f64 / total.max(1) as f64,
        )
    }
}

impl Progress for StderrProgress {
    fn start(&self, total: u64) {
        // A new count: a refinement starts one per round.
        for c in self.counts.iter().chain([&self.done, &self.previous]) {
            c.store(0, Ordering::Relaxed);
        }
        self.total.store(total, Ordering::Relaxed);
        if let Ok(mut t) = self.started.lock() {
            *t = Some(Instant::now());
        }
        if let Some(lines) = &self.lines
            && let Ok(mut st) = lines.lock()
        {
            // A first line at once: a unit of work may take minutes (a
            // sample with every robustness measure), and until one is done
            // the command would say nothing.
            (st.decile, st.printed, st.last) = (0, 0, Instant::now());
            eprintln!("{}", self.line());
        }
        if self.mode == ProgressMode::Auto && self.lines.is_none() {
            let stage = self.stage.lock().map(|s| s.clone()).unwrap_or_default();
            let template = if stage.is_empty() {
                "{elapsed_precise} [{wide_bar}] {pos}/{len} {per_sec} ETA {eta}\n{msg}"
            } else {
                "{prefix}: {elapsed_precise} [{wide_bar}] {pos}/{len} {per_sec} ETA {eta}\n{msg}"
            };
            let bar = ProgressBar::new(total).with_prefix(stage);
            bar.set_style(
                ProgressStyle::with_template(template)
                    .expect("valid template")
                    .progress_chars("=> "),
            );
            bar.enable_steady_tick(Duration::from_millis(200));
            if let Ok(mut b) = self.bar.lock()
                && let Some(old) = b.replace(bar)
            {
                old.finish();
            }
        }
    }

    fn stage(&self, text: &str) {
        if let Ok(mut s) = self.stage.lock() {
            *s = text.to_string();
        }
    }

    fn kept(&self, label: Label) {
        self.count(label);
        self.previous.fetch_add(1, Ordering::Relaxed);
        if let Some(bar) = self.bar() {
            bar.inc(1);
            bar.reset_eta();
        }
    }

    fn computed(&self, label: Label) {
        self.count(label);
        if let Some(bar) = self.bar() {
            bar.inc(1);
            bar.set_message(self.counts_text());
        }
        self.show_line();
    }

    fn advanced(&self) {
        self.done.fetch_add(1, Ordering::Relaxed);
        if let Some(bar) = self.bar() {
            bar.inc(1);
        }
        self.show_line();
    }

    fn note(&self, text: &str) {
        match self.bar() {
            Some(bar) => bar.println(text),
            None if self.lines.is_some() => eprintln!("{text}"),
            None => {}
        }
    }

    fn warn(&self, text: &str) {
        match self.bar() {
            Some(bar) => bar.println(text),
            None => eprintln!("{text}"),
        }
    }

    fn finish(&self, complete: bool) {
        if let Some(bar) = self.bar() {
            if self.labelled() {
                bar.set_message(self.counts_text());
            }
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
