//! Run statistics over the analysis window and the gait label (MODEL.md §5).

use crate::geometry::Tip;
use crate::outcome::{ContactFractions, Label};

/// How many touchdowns the return map keeps (a fixed ring: no allocation).
const RETURN_MAP_LEN: usize = 64;
/// Longest period searched for on the touchdown return map.
pub const MAX_PERIOD: usize = 12;
/// Relative tolerance of the period test (a chaotic gait misses it by O(1)).
const PERIOD_TOL: f64 = 1e-3;

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
        }
    }

    /// Accounts for `[t0, t1]` spent in one contact state with `sliding` rods sliding.
    pub fn on_interval(&mut self, t0: f64, t1: f64, contact_state: usize, sliding: usize) {
        self.slide_time += sliding as f64 * (t1 - t0);
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
        let at = |k: usize| self.returns[(self.returns_len - len + k) % RETURN_MAP_LEN];
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
    fn new_foot_counts_only_changes_of_tip() {
        let mut s = GaitStats::new(0.0);
        s.on_touchdown(1.0, 0, Tip::Plus, -1.0);
        s.on_touchdown(1.1, 0, Tip::Plus, -1.0); // a bounce on the same foot
        s.on_touchdown(1.5, 0, Tip::Minus, -1.0);
        assert_eq!((s.window_touchdowns, s.window_newfoot), (3, 2));
    }
}
