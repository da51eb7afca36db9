//! A reported interval checked by direct simulation. A design can fail at
//! isolated slopes inside an interval its profile calls stable: a failing
//! window narrower than 1e-6 rad, or a single φ whose neighbours 1e-12 away
//! are stable (the gait coexists there with the stalled rest or a collapse,
//! and whether the article's start reaches the gait depends on φ more finely
//! than any grid). So each reported interval is simulated again at
//! [`SLOPES`] slopes evenly across it and at every multiple of [`ROUND`]
//! inside it (the slopes a reader is likely to try), and the interval
//! reported is the widest run of checked slopes with no failure: a slope
//! fails when it is not stable, or, for a search of one gait, when it is
//! not that gait (a walk interval with a skip window inside it is not a
//! walk interval).

use crate::profile::run_at_slope;
use rayon::prelude::*;
use rtw_model::{Label, Options, Params};
use std::sync::atomic::AtomicBool;

/// Slopes evenly across the interval, its ends included.
pub const SLOPES: usize = 201;
/// … and every multiple of this inside it (rad).
pub const ROUND: f64 = 0.005;

/// What the check found: the widest run of checked slopes with no failure.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Checked {
    /// The profile's interval that was checked.
    pub profile: (f64, f64),
    /// The widest run of stable checked slopes in it.
    pub lo: f64,
    /// Its end.
    pub hi: f64,
    /// Slopes simulated.
    pub slopes: u64,
    /// Of them, not stable (or, when a gait was checked, not that gait).
    pub failures: u64,
    /// Whether a slope below `lo` holds too (a checked slope, or one of the
    /// profile's other intervals): `lo` is then an interleaved end, where
    /// failing and holding slopes alternate, not a sharp one with only
    /// failure beyond.
    pub beyond_lo: bool,
    /// The same above `hi`.
    pub beyond_hi: bool,
}

impl Checked {
    /// How the interval ends at `lo` and at `hi`: `"sharp"` (no slope
    /// beyond it holds) or `"interleaved"`.
    pub fn ends(&self) -> (&'static str, &'static str) {
        let kind = |beyond: bool| if beyond { "interleaved" } else { "sharp" };
        (kind(self.beyond_lo), kind(self.beyond_hi))
    }
}

/// The slopes checked in `[lo, hi]`, ascending, each once.
pub(crate) fn slopes(lo: f64, hi: f64) -> Vec<f64> {
    let mut v: Vec<f64> = (0..SLOPES)
        .map(|i| {
            if i + 1 == SLOPES {
                hi
            } else {
                lo + (hi - lo) * i as f64 / (SLOPES - 1) as f64
            }
        })
        .collect();
    let first = (lo / ROUND).ceil() as i64;
    let last = (hi / ROUND).floor() as i64;
    v.extend(
        (first..=last)
            .map(|k| k as f64 * ROUND)
            .filter(|p| (lo..=hi).contains(p)),
    );
    v.sort_by(f64::total_cmp);
    v.dedup();
    v
}

/// The widest run of `true` in `stable` (ties: the first), as indices.
pub(crate) fn widest_run(phis: &[f64], stable: &[bool]) -> Option<(usize, usize)> {
    let mut best: Option<(usize, usize)> = None;
    let mut start = None;
    for i in 0..=stable.len() {
        let good = stable.get(i).copied().unwrap_or(false);
        match (good, start) {
            (true, None) => start = Some(i),
            (false, Some(a)) => {
                let wider = best.is_none_or(|(b0, b1)| phis[i - 1] - phis[a] > phis[b1] - phis[b0]);
                if wider {
                    best = Some((a, i - 1));
                }
                start = None;
            }
            _ => {}
        }
    }
    best
}

/// Design `params` simulated at every checked slope of `[lo, hi]` under
/// `options`, in parallel on the pool the caller installed, each slope
/// kept when it is stable and, if `gait` is given, that gait; `None` when
/// stopped.
pub(crate) fn check(
    params: Params,
    (lo, hi): (f64, f64),
    options: &Options,
    gait: Option<Label>,
    cancel: &AtomicBool,
) -> Option<Checked> {
    let phis = slopes(lo, hi);
    let stable: Option<Vec<bool>> = phis
        .par_iter()
        .map(|&phi| {
            let label = run_at_slope(params, phi, options, cancel)?.label();
            Some(label.is_stable() && gait.is_none_or(|g| g == label))
        })
        .collect();
    let stable = stable?;
    let failures = stable.iter().filter(|s| !**s).count() as u64;
    let (a, b) = widest_run(&phis, &stable).unwrap_or((0, 0));
    let any = stable.iter().any(|s| *s);
    let (lo_ok, hi_ok) = if any {
        (phis[a], phis[b])
    } else {
        (f64::NAN, f64::NAN)
    };
    let beyond_lo = any && stable[..a].iter().any(|s| *s);
    let beyond_hi = any && stable[b + 1..].iter().any(|s| *s);
    Some(Checked {
        profile: (lo, hi),
        lo: lo_ok,
        hi: hi_ok,
        slopes: phis.len() as u64,
        failures,
        beyond_lo,
        beyond_hi,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The widest-walk search's first reported design (results/design/
    /// designs-widest-walk.parquet, row 0, its interval as the stable-only
    /// check gave it): its slope profile (`rtw-scan profile … --grid 0.0015
    /// --tol 0.0002`, an independent bisection) finds it skipping on
    /// [0.13736, 0.13923] inside that interval. A check of the walk must see
    /// those slopes fail and keep a walking interval above them.
    #[test]
    fn a_gait_checked_interval_holds_only_that_gait() {
        let design = Params {
            length: 0.8,
            rho: 3.3385616626338726,
            alpha: 0.24993740931144315,
            f_n: 2.66035097853401,
            zeta: 0.06457513238933699,
            phi: 0.053500000000000006,
        };
        let (lo, hi) = (0.053500000000000006, 0.35750000000000004);
        let options = Options::default();
        let cancel = AtomicBool::new(false);
        let any = check(design, (lo, hi), &options, None, &cancel).unwrap();
        let walk = check(design, (lo, hi), &options, Some(Label::Walk), &cancel).unwrap();
        assert!(walk.failures > any.failures, "{any:?} {walk:?}");
        assert!(walk.lo > 0.13923 && walk.hi <= hi, "{walk:?}");
        // Walking slopes below the skip window: its lower end interleaves.
        assert_eq!(walk.ends().0, "interleaved", "{walk:?}");
        for phi in slopes(lo, hi) {
            if (walk.lo..=walk.hi).contains(&phi) {
                let label = run_at_slope(design, phi, &options, &cancel)
                    .unwrap()
                    .label();
                assert_eq!(label, Label::Walk, "φ = {phi}");
            }
        }
    }

    #[test]
    fn the_slopes_span_the_interval_with_its_round_values_and_the_widest_clean_run_is_kept() {
        let v = slopes(0.101, 0.2);
        assert_eq!((v[0], *v.last().unwrap()), (0.101, 0.2));
        assert!(v.windows(2).all(|w| w[0] < w[1]));
        // 201 across it, and 0.105, 0.11, …, 0.195 (0.2 is its end already).
        assert!(v.contains(&(21.0 * ROUND)) && v.contains(&(39.0 * ROUND)));
        assert_eq!(v.len(), SLOPES + 19);
        let phis = [0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6];
        let ok = [true, true, false, true, true, true, false];
        assert_eq!(widest_run(&phis, &ok), Some((3, 5)));
        assert_eq!(widest_run(&phis, &[false; 7]), None);
        assert_eq!(widest_run(&phis, &[true; 7]), Some((0, 6)));
    }
}
