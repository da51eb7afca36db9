//! Run statistics over the analysis window and the gait label (docs/model.md §5).

use crate::geometry::Tip;
use crate::outcome::{ContactFractions, Label};

/// How many touchdowns the return map keeps (a fixed ring: no allocation).
const RETURN_MAP_LEN: usize = 64;
/// Longest period searched for on the touchdown return map.
pub const MAX_PERIOD: usize = 12;
/// Relative tolerance of the period test (a chaotic gait misses it by O(1)).
const PERIOD_TOL: f64 = 1e-3;
/// Returns a run's latest touchdowns must repeat over before an early stop
/// (`Options::stop_when_settled`) calls its gait settled; at least 3 periods
/// of the longest period searched for.
pub const SETTLE_RETURNS: usize = 36;

/// What the run looked like at one touchdown, for the settled window.
#[derive(Clone, Copy, Debug, Default)]
struct Mark {
    t: f64,
    /// Whole-run seconds in each contact state up to `t`.
    state_time: [f64; 4],
    /// Whole-run count of new-foot touchdowns up to `t`.
    newfoot: u64,
    /// Downhill position of the centre of mass at `t`.
    com_x: f64,
    /// Largest friction ratio needed since the previous touchdown.
    mu: f64,
    /// The landing rod's ω after the impact.
    omega_after: f64,
}

/// The statistics of a settled gait over a whole number of its periods,
/// ending at the touchdown where the return map was found converged: what a
/// full-length run measures over its analysis window, for a periodic gait.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settled {
    /// Window `[t0, t1]` between two touchdowns, `period × m` returns long.
    pub t0: f64,
    pub t1: f64,
    pub period: u32,
    pub fractions: ContactFractions,
    /// Touchdowns per second over the window (returns / duration).
    pub f_w: f64,
    pub f_w_newfoot: f64,
    pub speed: f64,
    pub mu_required: f64,
}

/// Statistics gathered as a run goes.
#[derive(Clone, Debug)]
pub struct GaitStats {
    /// Start of the analysis window.
    pub window_start: f64,
    /// Seconds in each contact state (0…3 rods on the ground) within the window.
    pub state_time: [f64; 4],
    /// Rod-seconds sliding, whole run.
    pub slide_time: f64,
    /// All touchdowns.
    pub touchdowns: u64,
    /// Touchdowns within the window.
    pub window_touchdowns: u64,
    /// Touchdowns within the window on a tip other than that rod's last one.
    pub window_newfoot: u64,
    last_tip: [Option<Tip>; 3],
    /// Time of the last touchdown (0 at the start).
    pub last_touchdown: f64,
    /// Downhill position of the centre of mass at the window start.
    pub window_com_x: Option<f64>,
    /// Ring of (time since previous touchdown, landing rod's ω after impact) in the window.
    returns: [(f64, f64); RETURN_MAP_LEN],
    returns_len: usize,
    prev_window_touchdown: Option<f64>,
    /// Whole-run seconds per contact state and new-foot touchdowns (for the settled window).
    run_state_time: [f64; 4],
    run_newfoot: u64,
    /// Ring of the latest `SETTLE_RETURNS + 1` touchdown marks.
    marks: [Mark; SETTLE_RETURNS + 1],
    marks_len: usize,
}

impl GaitStats {
    pub fn new(window_start: f64) -> Self {
        Self {
            window_start,
            state_time: [0.0; 4],
            slide_time: 0.0,
            touchdowns: 0,
            window_touchdowns: 0,
            window_newfoot: 0,
            last_tip: [None; 3],
            last_touchdown: 0.0,
            window_com_x: None,
            returns: [(0.0, 0.0); RETURN_MAP_LEN],
            returns_len: 0,
            prev_window_touchdown: None,
            run_state_time: [0.0; 4],
            run_newfoot: 0,
            marks: [Mark::default(); SETTLE_RETURNS + 1],
            marks_len: 0,
        }
    }

    /// Accounts for `[t0, t1]` spent in one contact state with `sliding` rods sliding.
    pub fn on_interval(&mut self, t0: f64, t1: f64, contact_state: usize, sliding: usize) {
        self.slide_time += sliding as f64 * (t1 - t0);
        self.run_state_time[contact_state] += t1 - t0;
        let lo = t0.max(self.window_start);
        if t1 > lo {
            self.state_time[contact_state] += t1 - lo;
        }
    }

    pub fn on_touchdown(&mut self, t: f64, rod: usize, tip: Tip, omega_after: f64) {
        self.touchdowns += 1;
        self.last_touchdown = t;
        let newfoot = self.last_tip[rod] != Some(tip);
        self.last_tip[rod] = Some(tip);
        self.run_newfoot += newfoot as u64;
        if t < self.window_start {
            return;
        }
        self.window_touchdowns += 1;
        self.window_newfoot += newfoot as u64;
        if let Some(prev) = self.prev_window_touchdown {
            self.returns[self.returns_len % RETURN_MAP_LEN] = (t - prev, omega_after);
            self.returns_len += 1;
        }
        self.prev_window_touchdown = Some(t);
    }

    /// Contact-state fractions over the window.
    pub fn fractions(&self) -> ContactFractions {
        let total: f64 = self.state_time.iter().sum();
        let f = |i: usize| {
            if total > 0.0 {
                self.state_time[i] / total
            } else {
                0.0
            }
        };
        ContactFractions {
            nlsp: f(0),
            slsp: f(1),
            dlsp: f(2),
            tlsp: f(3),
        }
    }

    /// The smallest `n ≤ MAX_PERIOD` such that the last touchdowns of the
    /// window repeat every `n` (step time and post-impact ω within a relative
    /// 1e-3), or 0 if none. Needs at least `3n` and 8 returns.
    pub fn period(&self) -> u32 {
        let len = self.returns_len.min(RETURN_MAP_LEN);
        find_period(len, |k| {
            self.returns[(self.returns_len - len + k) % RETURN_MAP_LEN]
        })
    }

    /// Records the touchdown at `t` (after [`GaitStats::on_touchdown`]) for
    /// the settled-gait test, with the centre of mass's downhill position
    /// and the largest friction ratio needed since the previous touchdown.
    /// Returns the settled statistics once the latest [`SETTLE_RETURNS`]
    /// returns repeat with a period (the same test as [`GaitStats::period`]).
    pub fn mark(&mut self, t: f64, omega_after: f64, com_x: f64, mu: f64) -> Option<Settled> {
        const M: usize = SETTLE_RETURNS + 1;
        self.marks[self.marks_len % M] = Mark {
            t,
            state_time: self.run_state_time,
            newfoot: self.run_newfoot,
            com_x,
            mu,
            omega_after,
        };
        self.marks_len += 1;
        if self.marks_len < M {
            return None;
        }
        // Mark j of the last M (0 oldest); return k is the step into mark k + 1.
        let mark = |j: usize| self.marks[(self.marks_len - M + j) % M];
        let ret = |k: usize| (mark(k + 1).t - mark(k).t, mark(k + 1).omega_after);
        let n = find_period(SETTLE_RETURNS, ret) as usize;
        if n == 0 {
            return None;
        }
        // A whole number of periods, ending now.
        let returns = SETTLE_RETURNS - SETTLE_RETURNS % n;
        let (a, b) = (mark(M - 1 - returns), mark(M - 1));
        let duration = b.t - a.t;
        let st: [f64; 4] = std::array::from_fn(|i| b.state_time[i] - a.state_time[i]);
        let total: f64 = st.iter().sum();
        let f = |i: usize| if total > 0.0 { st[i] / total } else { 0.0 };
        Some(Settled {
            t0: a.t,
            t1: b.t,
            period: n as u32,
            fractions: ContactFractions {
                nlsp: f(0),
                slsp: f(1),
                dlsp: f(2),
                tlsp: f(3),
            },
            f_w: returns as f64 / duration,
            f_w_newfoot: (b.newfoot - a.newfoot) as f64 / duration,
            speed: (b.com_x - a.com_x) / duration,
            mu_required: (M - returns..M).map(|j| mark(j).mu).fold(0.0, f64::max),
        })
    }
}

/// The smallest `n ≤ MAX_PERIOD` such that returns `0..len` (step time,
/// post-impact ω) repeat every `n` within a relative [`PERIOD_TOL`] of their
/// mean step time and largest |ω|, or 0. Needs `len >= max(3n, 8)`.
fn find_period(len: usize, at: impl Fn(usize) -> (f64, f64)) -> u32 {
    let scale_t = (0..len).map(|k| at(k).0).sum::<f64>() / len.max(1) as f64;
    let scale_w = (0..len).map(|k| at(k).1.abs()).fold(0.0, f64::max);
    (1..=MAX_PERIOD)
        .find(|&n| {
            len >= (3 * n).max(8)
                && (n..len).all(|k| {
                    let (a, b) = (at(k), at(k - n));
                    (a.0 - b.0).abs() <= PERIOD_TOL * scale_t
                        && (a.1 - b.1).abs() <= PERIOD_TOL * scale_w
                })
        })
        .map_or(0, |n| n as u32)
}

/// Table S1's row for the RTW: flight → skip, else triple support → crawl, else walk.
pub fn label(f: &ContactFractions, eps: f64) -> Label {
    if f.nlsp > eps {
        Label::Skip
    } else if f.tlsp > eps {
        Label::Crawl
    } else {
        Label::Walk
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_follow_table_s1() {
        let f = |n, s, d, t| ContactFractions {
            nlsp: n,
            slsp: s,
            dlsp: d,
            tlsp: t,
        };
        assert_eq!(label(&f(0.3, 0.7, 0.0, 0.0), 0.01), Label::Skip);
        assert_eq!(label(&f(0.005, 0.5, 0.495, 0.0), 0.01), Label::Walk);
        assert_eq!(label(&f(0.0, 0.4, 0.5, 0.1), 0.01), Label::Crawl);
        // Flight wins over triple support.
        assert_eq!(label(&f(0.05, 0.4, 0.45, 0.1), 0.01), Label::Skip);
    }

    #[test]
    fn fractions_count_only_the_window() {
        let mut s = GaitStats::new(10.0);
        s.on_interval(9.0, 11.0, 1, 0);
        s.on_interval(11.0, 14.0, 2, 1);
        let f = s.fractions();
        assert!((f.slsp - 0.25).abs() < 1e-15 && (f.dlsp - 0.75).abs() < 1e-15);
        assert!((s.slide_time - 3.0).abs() < 1e-15);
    }

    #[test]
    fn period_of_a_synthetic_return_sequence() {
        for n in [1usize, 2, 3, 5] {
            let mut s = GaitStats::new(0.0);
            let mut t = 0.0;
            for k in 0..60 {
                let phase = (k % n) as f64;
                t += 0.3 + 0.05 * phase;
                s.on_touchdown(t, k % 3, Tip::Plus, -2.0 - 0.4 * phase);
            }
            assert_eq!(s.period(), n as u32);
        }
        // An aperiodic (chaotic-looking) sequence has none.
        let mut s = GaitStats::new(0.0);
        let (mut t, mut x) = (0.0, 0.3);
        for k in 0..60 {
            x = 3.9 * x * (1.0 - x);
            t += 0.2 + 0.1 * x;
            s.on_touchdown(t, k % 3, Tip::Minus, -1.0 - x);
        }
        assert_eq!(s.period(), 0);
    }

    #[test]
    fn settles_on_a_periodic_sequence_over_whole_periods() {
        // Period 2: 0.2 s in single support, then 0.3 s in double support,
        // touchdowns at the end of each, moving 0.1 m per touchdown.
        let mut s = GaitStats::new(10.0);
        let (mut t, mut settled, mut k) = (0.0, None, 0);
        while settled.is_none() {
            let (dt, state, omega) = if k % 2 == 0 {
                (0.2, 1, -2.0)
            } else {
                (0.3, 2, -2.5)
            };
            s.on_interval(t, t + dt, state, 0);
            t += dt;
            let tip = if k % 2 == 0 { Tip::Plus } else { Tip::Minus };
            s.on_touchdown(t, k % 3, tip, omega);
            settled = s.mark(t, omega, 0.1 * (k + 1) as f64, 0.5 + 0.01 * (k % 2) as f64);
            k += 1;
            assert!(k < 1000, "never settled");
        }
        let st = settled.unwrap();
        // The earliest it can: SETTLE_RETURNS returns after the first touchdown.
        assert_eq!(k, SETTLE_RETURNS + 1);
        assert_eq!(st.period, 2);
        // Whole periods: fractions are exactly 0.4 / 0.6.
        assert!(
            (st.fractions.slsp - 0.4).abs() < 1e-12,
            "{:?}",
            st.fractions
        );
        assert!((st.fractions.dlsp - 0.6).abs() < 1e-12);
        assert!((st.f_w - 4.0).abs() < 1e-9, "2 touchdowns per 0.5 s");
        assert!((st.speed - 0.4).abs() < 1e-9, "0.2 m per 0.5 s");
        assert!((st.f_w_newfoot - 4.0).abs() < 1e-9);
        assert!((st.mu_required - 0.51).abs() < 1e-12);
        assert!((st.t1 - t).abs() < 1e-12);
    }

    #[test]
    fn an_aperiodic_sequence_never_settles() {
        let mut s = GaitStats::new(0.0);
        let (mut t, mut x) = (0.0, 0.3);
        for k in 0..500 {
            x = 3.9 * x * (1.0 - x);
            t += 0.2 + 0.1 * x;
            s.on_touchdown(t, k % 3, Tip::Minus, -1.0 - x);
            assert_eq!(s.mark(t, -1.0 - x, t, 0.0), None);
        }
    }

    #[test]
    fn new_foot_counts_only_changes_of_tip() {
        let mut s = GaitStats::new(0.0);
        s.on_touchdown(1.0, 0, Tip::Plus, -1.0);
        s.on_touchdown(1.1, 0, Tip::Plus, -1.0); // a bounce on the same foot
        s.on_touchdown(1.5, 0, Tip::Minus, -1.0);
        assert_eq!((s.window_touchdowns, s.window_newfoot), (3, 2));
    }
}
