//! # rtw-bench
//!
//! The work–precision benchmark of the RTW model: for fixed cases and for a
//! 200-sample scan of the paper's box, every integrator × tolerance is timed
//! and its error measured against a reference run (DOP853 at rtol 1e-13).
//! `cargo run --release -p rtw-bench [-- --quick]` writes
//! `results/bench/work-precision.md` and `results/bench/work-precision.svg`.
//!
//! This library holds the pieces with something to test: the error metrics
//! on a run's events ([`Events`]), the scan comparison ([`ScanDiff`]) and
//! the SVG plot ([`svg`]).

pub mod svg;

use rtw_model::{Label, TraceSample};

/// A state in full coordinates (per rod: x, y, θ, ẋ, ẏ, ω), mode independent.
pub type Full = [f64; 18];

/// The full coordinates of a trace sample.
pub fn full(s: &TraceSample) -> Full {
    let mut out = [0.0; 18];
    for i in 0..3 {
        out[6 * i..6 * i + 3].copy_from_slice(&s.pose[i]);
        out[6 * i + 3..6 * i + 6].copy_from_slice(&s.vel[i]);
    }
    out
}

/// Largest absolute difference of two states (m, rad, m/s, rad/s alike).
pub fn state_error(a: &Full, b: &Full) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// One event of a run: its time, the state just before the reset, and
/// whether it was a touchdown (a rod went from free to grounded).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Event {
    pub t: f64,
    pub before: Full,
    pub touchdown: bool,
}

/// The events of a run, recovered from its trace with `trace_dt = 0`: the
/// engine records the state at every step end, and at an event both the
/// state where the step was cut (before the reset) and the state after it,
/// at the same time. Two consecutive samples at one time are an event.
#[derive(Clone, Debug, Default)]
pub struct Events {
    pub events: Vec<Event>,
    last: Option<TraceSample>,
}

impl Events {
    /// Feeds the next trace sample.
    pub fn push(&mut self, s: &TraceSample) {
        if let Some(prev) = &self.last
            && prev.t == s.t
        {
            let touchdown = (0..3).any(|i| prev.contact[i] == 0 && s.contact[i] != 0);
            self.events.push(Event {
                t: s.t,
                before: full(prev),
                touchdown,
            });
        }
        self.last = Some(*s);
    }

    /// Times of the first `k` touchdowns.
    pub fn touchdown_times(&self, k: usize) -> Vec<f64> {
        self.events
            .iter()
            .filter(|e| e.touchdown)
            .take(k)
            .map(|e| e.t)
            .collect()
    }
}

/// Largest state error over the first `k` events of `run` against `reference`
/// (event by event; `None` if either has no event). Compared index by index:
/// if a run takes a different sequence of events the error is O(1), as it
/// should be.
pub fn event_state_error(run: &Events, reference: &Events, k: usize) -> Option<f64> {
    let n = k.min(run.events.len()).min(reference.events.len());
    (n > 0).then(|| {
        (0..n)
            .map(|i| state_error(&run.events[i].before, &reference.events[i].before))
            .fold(0.0, f64::max)
    })
}

/// Largest error of the first `k` touchdown times against `reference`, or
/// `None` if either has none; a missing touchdown counts as infinite error.
pub fn touchdown_time_error(run: &Events, reference: &Events, k: usize) -> Option<f64> {
    let (a, b) = (run.touchdown_times(k), reference.touchdown_times(k));
    if a.is_empty() || b.is_empty() {
        return None;
    }
    if a.len() != b.len() {
        return Some(f64::INFINITY);
    }
    Some(
        a.iter()
            .zip(&b)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max),
    )
}

/// One sample of a scan, as the comparison needs it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScanPoint {
    pub label: Label,
    pub f_w: f64,
}

/// A scan against the reference scan, sample by sample.
#[derive(Clone, Debug, PartialEq)]
pub struct ScanDiff {
    /// Percent of samples per label ([`Label::ALL`] order): this scan, reference.
    pub percent: [f64; 6],
    pub reference_percent: [f64; 6],
    /// Largest |Δ%| over the labels (percentage points).
    pub max_pp: f64,
    /// Samples whose label differs: (index, reference label, this label).
    pub flips: Vec<(usize, Label, Label)>,
    /// Median relative error of f_w over the samples stable in both with one label.
    pub median_fw_rel: f64,
}

/// Compares a scan with the reference scan over the same samples.
///
/// # Panics
/// If the two have different lengths.
pub fn compare_scans(run: &[ScanPoint], reference: &[ScanPoint]) -> ScanDiff {
    assert_eq!(run.len(), reference.len(), "scans of different samples");
    let percent_of = |s: &[ScanPoint]| -> [f64; 6] {
        std::array::from_fn(|j| {
            let n = s.iter().filter(|p| p.label == Label::ALL[j]).count();
            100.0 * n as f64 / s.len().max(1) as f64
        })
    };
    let (percent, reference_percent) = (percent_of(run), percent_of(reference));
    let max_pp = (0..6)
        .map(|j| (percent[j] - reference_percent[j]).abs())
        .fold(0.0, f64::max);
    let flips = run
        .iter()
        .zip(reference)
        .enumerate()
        .filter(|(_, (a, b))| a.label != b.label)
        .map(|(i, (a, b))| (i, b.label, a.label))
        .collect();
    let mut rel: Vec<f64> = run
        .iter()
        .zip(reference)
        .filter(|(a, b)| a.label == b.label && b.label.is_stable() && b.f_w > 0.0)
        .map(|(a, b)| ((a.f_w - b.f_w) / b.f_w).abs())
        .collect();
    ScanDiff {
        percent,
        reference_percent,
        max_pp,
        flips,
        median_fw_rel: median(&mut rel),
    }
}

/// Median (0 for no values); sorts `v`.
pub fn median(v: &mut [f64]) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample(t: f64, x: f64, contact: [i8; 3]) -> TraceSample {
        TraceSample {
            t,
            pose: [[x, 0.0, 0.0]; 3],
            vel: [[0.0; 3]; 3],
            contact,
            contact_state: contact.iter().filter(|&&c| c != 0).count() as u8,
            kinetic: 0.0,
            gravity_potential: 0.0,
            string_potential: 0.0,
            damping_loss: 0.0,
            friction_loss: 0.0,
            impact_loss: 0.0,
        }
    }

    #[test]
    fn events_are_repeated_times_and_touchdowns_ground_a_free_rod() {
        let mut e = Events::default();
        // Step ends at 0.1 and 0.2, a touchdown of rod 1 at 0.25 (state
        // before: x = 2.5), a step end, a lift-off of rod 0 at 0.4.
        for s in [
            sample(0.0, 0.0, [1, 0, 0]),
            sample(0.1, 1.0, [1, 0, 0]),
            sample(0.2, 2.0, [1, 0, 0]),
            sample(0.25, 2.5, [1, 0, 0]),
            sample(0.25, 2.5, [1, -1, 0]),
            sample(0.3, 3.0, [1, -1, 0]),
            sample(0.4, 4.0, [1, -1, 0]),
            sample(0.4, 4.0, [0, -1, 0]),
        ] {
            e.push(&s);
        }
        assert_eq!(e.events.len(), 2);
        assert_eq!((e.events[0].t, e.events[0].touchdown), (0.25, true));
        assert_eq!(e.events[0].before[0], 2.5);
        assert_eq!((e.events[1].t, e.events[1].touchdown), (0.4, false));
        assert_eq!(e.touchdown_times(5), vec![0.25]);
    }

    #[test]
    fn errors_against_a_shifted_copy() {
        let mk = |dt: f64, dx: f64| {
            let mut e = Events::default();
            for k in 1..=3 {
                let t = k as f64 + dt;
                e.push(&sample(t, k as f64 + dx, [0, 0, 0]));
                e.push(&sample(t, k as f64 + dx, [1, 0, 0]));
            }
            e
        };
        let (a, b) = (mk(0.0, 0.0), mk(1e-6, 3e-4));
        assert_eq!(event_state_error(&a, &a, 5), Some(0.0));
        let es = event_state_error(&b, &a, 5).unwrap();
        assert!((es - 3e-4).abs() < 1e-15, "{es}");
        let et = touchdown_time_error(&b, &a, 5).unwrap();
        assert!((et - 1e-6).abs() < 1e-14, "{et}");
        // A run that misses a touchdown is infinitely wrong, not silently fine.
        let mut short = mk(0.0, 0.0);
        short.events.pop();
        assert_eq!(touchdown_time_error(&short, &a, 5), Some(f64::INFINITY));
        assert_eq!(event_state_error(&Events::default(), &a, 5), None);
    }

    #[test]
    fn scan_diff_counts_flips_and_fractions() {
        let p = |label, f_w| ScanPoint { label, f_w };
        let reference = [
            p(Label::Walk, 4.0),
            p(Label::Walk, 2.0),
            p(Label::Skip, 5.0),
            p(Label::Stall, 0.0),
        ];
        let run = [
            p(Label::Walk, 4.04),
            p(Label::Skip, 2.0),
            p(Label::Skip, 5.0),
            p(Label::Stall, 0.0),
        ];
        let d = compare_scans(&run, &reference);
        assert_eq!(d.flips, vec![(1, Label::Walk, Label::Skip)]);
        // Walk 50 % → 25 %, skip 25 % → 50 %.
        assert!((d.max_pp - 25.0).abs() < 1e-12);
        // f_w errors of the samples stable in both with one label: 1 % and 0.
        assert!(
            (d.median_fw_rel - 0.005).abs() < 1e-12,
            "{}",
            d.median_fw_rel
        );
        assert_eq!(compare_scans(&reference, &reference).max_pp, 0.0);
    }

    #[test]
    fn median_of_odd_and_even() {
        assert_eq!(median(&mut [3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&mut [4.0, 1.0, 2.0, 3.0]), 2.5);
        assert_eq!(median(&mut []), 0.0);
    }
}
