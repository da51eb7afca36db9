//! Run statistics over the analysis window and the gait label (docs/model.md §5).

use crate::options::LabelOptions;
use crate::outcome::Outcome;
use crate::outcome::{ContactFractions, MAX_PERIOD, StepCounts, StepShares, step_kind};
use crate::plant::geometry::Tip;

/// How many touchdowns the return map keeps (a fixed ring: no allocation).
const RETURN_MAP_LEN: usize = 64;
/// Relative tolerance of the period test (a chaotic gait misses it by O(1)).
const PERIOD_TOL: f64 = 1e-3;
/// Returns a run's latest touchdowns must repeat over before an early stop
/// (`Options::stop_when_settled`) calls its gait settled; at least 3 periods
/// of the longest period searched for.
pub(crate) const SETTLE_RETURNS: usize = 36;

/// What the run looked like at one touchdown, for the settled window.
#[derive(Clone, Copy, Debug, Default)]
struct Mark {
    t: f64,
    /// Whole-run seconds in each contact state up to `t`.
    state_time: [f64; 4],
    /// Whole-run count of new-foot touchdowns up to `t`.
    newfoot: u64,
    /// Whole-run counts of steps, and of steps with flight and with triple support.
    steps: StepCounts,
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
pub(crate) struct Settled {
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
    pub step_shares: StepShares,
}

/// Statistics gathered as a run goes.
#[derive(Clone, Debug)]
pub(crate) struct GaitStats {
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
    /// What makes a step one with flight or triple support.
    labels: LabelOptions,
    /// Seconds per contact state since the latest new foot's touchdown, and its time.
    step_time: [f64; 4],
    step_start: Option<f64>,
    /// Steps so far (whole run), and those wholly inside the window.
    run_steps: StepCounts,
    window_steps: StepCounts,
}

impl GaitStats {
    /// Statistics over the window from `window_start` on, judging steps by `labels`.
    pub(crate) fn new(window_start: f64, labels: LabelOptions) -> Self {
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
            labels,
            step_time: [0.0; 4],
            step_start: None,
            run_steps: StepCounts::default(),
            window_steps: StepCounts::default(),
        }
    }

    /// Accounts for `[t0, t1]` spent in one contact state with `sliding` rods sliding.
    pub(crate) fn on_interval(&mut self, t0: f64, t1: f64, contact_state: usize, sliding: usize) {
        self.slide_time += sliding as f64 * (t1 - t0);
        self.run_state_time[contact_state] += t1 - t0;
        self.step_time[contact_state] += t1 - t0;
        let lo = t0.max(self.window_start);
        if t1 > lo {
            self.state_time[contact_state] += t1 - lo;
        }
    }

    pub(crate) fn on_touchdown(&mut self, t: f64, rod: usize, tip: Tip, omega_after: f64) {
        self.touchdowns += 1;
        self.last_touchdown = t;
        let newfoot = self.last_tip[rod] != Some(tip);
        if newfoot {
            // A step of the wheel ends here: from the previous new foot's
            // touchdown (none before the first) to this one.
            if let Some(start) = self.step_start {
                let kind = step_kind(&self.step_time, &self.labels);
                self.run_steps.add(kind);
                if start >= self.window_start {
                    self.window_steps.add(kind);
                }
            }
            self.step_time = [0.0; 4];
            self.step_start = Some(t);
        }
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

    /// Shares of the window's whole steps with flight and with triple support.
    pub(crate) fn step_shares(&self) -> StepShares {
        self.window_steps.shares()
    }

    /// Contact-state fractions over the window.
    pub(crate) fn fractions(&self) -> ContactFractions {
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
    pub(crate) fn period(&self) -> u32 {
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
    pub(crate) fn mark(
        &mut self,
        t: f64,
        omega_after: f64,
        com_x: f64,
        mu: f64,
    ) -> Option<Settled> {
        const M: usize = SETTLE_RETURNS + 1;
        self.marks[self.marks_len % M] = Mark {
            t,
            state_time: self.run_state_time,
            newfoot: self.run_newfoot,
            steps: self.run_steps,
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
        if b.newfoot == a.newfoot {
            // Returns that repeat without a new foot are a tip bouncing in
            // place (chatter), not a step of the wheel.
            return None;
        }
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
            step_shares: b.steps.since(a.steps).shares(),
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

/// The time the flat gait takes for `steps` steps. A step is a new foot's
/// touchdown, as on the step map's section: counting every touchdown
/// (`f_w`) would shorten a skip's horizon by its bounces, and a chattering
/// tip's to almost nothing. A gait that took no new foot in its window (a
/// star sliding on without stepping) has no step time: then `t_max`, the
/// horizon the flat run was judged over.
pub(crate) fn steps_to_time(steps: f64, flat: &Outcome, t_max: f64) -> f64 {
    if flat.f_w_newfoot > 0.0 {
        steps / flat.f_w_newfoot
    } else {
        t_max
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::outcome::Label;

    /// Runs a constructed timeline: each entry is (seconds per contact state
    /// in order, whether the touchdown that ends it is a bounce). Touchdowns
    /// land rods 0, 1, 2 in turn, each time on the rod's other tip (a new
    /// foot); a bounce lands the last tip again.
    fn timeline(
        steps: &[(&[(usize, f64)], bool)],
        labels: LabelOptions,
    ) -> (ContactFractions, StepShares) {
        let mut s = GaitStats::new(0.0, labels);
        let mut t = 0.0;
        let mut rod = 0;
        // The first touchdown opens the first step.
        s.on_touchdown(t, 2, Tip::Minus, -2.0);
        let mut tips = [Tip::Plus; 3];
        for (phases, bounce) in steps {
            for &(state, dt) in phases.iter() {
                s.on_interval(t, t + dt, state, 0);
                t += dt;
            }
            if *bounce {
                // The rod that landed last lands the same tip again.
                let last = (rod + 2) % 3;
                s.on_touchdown(t, last, tips[last].other(), -2.0);
            } else {
                s.on_touchdown(t, rod, tips[rod], -2.0);
                tips[rod] = tips[rod].other();
                rod = (rod + 1) % 3;
            }
        }
        (s.fractions(), s.step_shares())
    }

    #[test]
    fn a_walk_with_an_occasional_hop_is_a_walk_by_its_typical_step() {
        // Eight steps of 0.2 s single + 0.2 s double support; two of them
        // also hop for 0.05 s: 3 % flight over the window, in 1/4 of the steps.
        let walk: &[(usize, f64)] = &[(1, 0.2), (2, 0.2)];
        let hop: &[(usize, f64)] = &[(1, 0.2), (0, 0.05), (2, 0.2)];
        let steps = [walk, hop, walk, walk, walk, hop, walk, walk].map(|p| (p, false));
        let (f, shares) = timeline(&steps, LabelOptions::default());
        assert!((f.nlsp - 0.1 / 3.3).abs() < 1e-12, "{f:?}");
        assert_eq!(shares.steps, 8);
        assert!((shares.flight - 0.25).abs() < 1e-15);
        assert_eq!(
            Label::of_gait(&f, &shares, &LabelOptions::default()),
            Label::Walk
        );
        assert_eq!(
            Label::of_gait(&f, &shares, &LabelOptions::any()),
            Label::Skip
        );
        // Flight in every step is a skip under both rules.
        let steps = [hop; 8].map(|p| (p, false));
        let (f, shares) = timeline(&steps, LabelOptions::default());
        assert_eq!(shares.flight, 1.0);
        assert_eq!(
            Label::of_gait(&f, &shares, &LabelOptions::default()),
            Label::Skip
        );
    }

    #[test]
    fn a_step_runs_from_one_new_foot_to_the_next_and_is_judged_by_its_own_fractions() {
        // A skip lands a foot, bounces on it (no new step), flies, lands the
        // next: each of the 4 steps has its flight, so all have flight.
        let fly: &[(usize, f64)] = &[(0, 0.1), (1, 0.1)];
        let bounce: &[(usize, f64)] = &[(1, 0.1)];
        let steps = [
            (fly, false),
            (bounce, true),
            (fly, false),
            (fly, false),
            (bounce, true),
            (fly, false),
        ];
        let (_, shares) = timeline(&steps, LabelOptions::default());
        assert_eq!(shares.steps, 4);
        assert_eq!(shares.flight, 1.0);
        // A step's flight must exceed labels.flight of that step: 0.001 s
        // in 0.4 s (0.25 %) does not count at 1 %, does at 0.1 %.
        let blip: &[(usize, f64)] = &[(1, 0.199), (0, 0.001), (2, 0.2)];
        let steps = [(blip, false); 4];
        assert_eq!(timeline(&steps, LabelOptions::default()).1.flight, 0.0);
        let fine = LabelOptions {
            flight: 0.001,
            ..LabelOptions::default()
        };
        assert_eq!(timeline(&steps, fine).1.flight, 1.0);
    }

    #[test]
    fn a_crawl_needs_triple_support_in_its_typical_step() {
        let crawl: &[(usize, f64)] = &[(2, 0.2), (3, 0.1), (1, 0.1)];
        let walk: &[(usize, f64)] = &[(2, 0.2), (1, 0.2)];
        let mostly = [crawl, crawl, walk, crawl].map(|p| (p, false));
        let (f, shares) = timeline(&mostly, LabelOptions::default());
        assert!((shares.triple - 0.75).abs() < 1e-15);
        assert_eq!(
            Label::of_gait(&f, &shares, &LabelOptions::default()),
            Label::Crawl
        );
        let rarely = [walk, crawl, walk, walk].map(|p| (p, false));
        let (f, shares) = timeline(&rarely, LabelOptions::default());
        assert_eq!(
            Label::of_gait(&f, &shares, &LabelOptions::default()),
            Label::Walk
        );
        assert_eq!(
            Label::of_gait(&f, &shares, &LabelOptions::any()),
            Label::Crawl
        );
    }

    #[test]
    fn fractions_count_only_the_window() {
        let mut s = GaitStats::new(10.0, LabelOptions::default());
        s.on_interval(9.0, 11.0, 1, 0);
        s.on_interval(11.0, 14.0, 2, 1);
        let f = s.fractions();
        assert!((f.slsp - 0.25).abs() < 1e-15 && (f.dlsp - 0.75).abs() < 1e-15);
        assert!((s.slide_time - 3.0).abs() < 1e-15);
    }

    #[test]
    fn period_of_a_synthetic_return_sequence() {
        for n in [1usize, 2, 3, 5] {
            let mut s = GaitStats::new(0.0, LabelOptions::default());
            let mut t = 0.0;
            for k in 0..60 {
                let phase = (k % n) as f64;
                t += 0.3 + 0.05 * phase;
                s.on_touchdown(t, k % 3, Tip::Plus, -2.0 - 0.4 * phase);
            }
            assert_eq!(s.period(), n as u32);
        }
        // An aperiodic (chaotic-looking) sequence has none.
        let mut s = GaitStats::new(0.0, LabelOptions::default());
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
        let mut s = GaitStats::new(10.0, LabelOptions::default());
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
        let mut s = GaitStats::new(0.0, LabelOptions::default());
        let (mut t, mut x) = (0.0, 0.3);
        for k in 0..500 {
            x = 3.9 * x * (1.0 - x);
            t += 0.2 + 0.1 * x;
            s.on_touchdown(t, k % 3, Tip::Minus, -1.0 - x);
            assert_eq!(s.mark(t, -1.0 - x, t, 0.0), None);
        }
    }

    #[test]
    fn a_tip_bouncing_in_place_never_settles() {
        // A tip chattering on the ground repeats its returns (the same tiny
        // interval, the same ω) but the wheel takes no step: no gait, and a
        // "settled" window over it would report tens of kHz as the step
        // frequency. A gait's window must hold a new foot.
        let mut s = GaitStats::new(0.0, LabelOptions::default());
        s.on_touchdown(1.0, 0, Tip::Plus, -0.1);
        let mut t = 1.0;
        for _ in 0..200 {
            t += 2.0e-5;
            s.on_touchdown(t, 0, Tip::Plus, -0.1);
            assert_eq!(s.mark(t, -0.1, 0.5, 0.1), None);
        }
    }

    #[test]
    fn new_foot_counts_only_changes_of_tip() {
        let mut s = GaitStats::new(0.0, LabelOptions::default());
        s.on_touchdown(1.0, 0, Tip::Plus, -1.0);
        s.on_touchdown(1.1, 0, Tip::Plus, -1.0); // a bounce on the same foot
        s.on_touchdown(1.5, 0, Tip::Minus, -1.0);
        assert_eq!((s.window_touchdowns, s.window_newfoot), (3, 2));
    }
}
