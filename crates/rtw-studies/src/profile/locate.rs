//! Where the label changes along φ: a coarse grid, then each bracket whose
//! ends disagree halved until it is at most the tolerance wide. Generic in
//! what is run at a slope, so that the bisection is tested on a labeller
//! whose changes are known.

use rayon::prelude::*;
use rtw_engine::scan::progress::Progress;
use rtw_model::Label;

/// A change of label between two simulated slopes at most `tol` apart:
/// `label_left` at `phi_left`, `label_right` at `phi_right`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Change {
    /// The slope below the change (rad).
    pub phi_left: f64,
    /// The slope above the change (rad).
    pub phi_right: f64,
    /// The label at `phi_left`.
    pub label_left: Label,
    /// The label at `phi_right`.
    pub label_right: Label,
    /// The label one `tol` below the bracket's middle (within the range).
    pub label_below: Label,
    /// The label one `tol` above the bracket's middle (within the range).
    pub label_above: Label,
}

impl Change {
    /// Whether the change is sharp: the labels one `tol` either side of it
    /// are those of its bracket's ends. Where two labels interleave at
    /// scales below `tol` (a walk that turns into a skip through a band of
    /// both), the bracket holds a change, but not the only one nearby.
    pub fn sharp(&self) -> bool {
        self.label_below == self.label_left && self.label_above == self.label_right
    }
}

/// A run of one label along φ, between two changes (or the range's ends):
/// every slope simulated in `[lo, hi]` has `label`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment {
    /// The label.
    pub label: Label,
    /// Its lowest simulated slope (rad).
    pub lo: f64,
    /// Its highest simulated slope (rad).
    pub hi: f64,
    /// The slopes simulated in it.
    pub runs: usize,
}

/// What [`locate`] found: every simulated slope with its result, in φ
/// order, the changes and the segments.
pub(crate) struct Located<T> {
    pub(crate) points: Vec<(f64, T)>,
    pub(crate) changes: Vec<Change>,
    pub(crate) segments: Vec<Segment>,
}

/// One round: `eval` at every slope, in parallel (on the pool the caller
/// installed); `None` when any run was stopped.
fn round<T: Send>(
    slopes: &[f64],
    eval: &(dyn Fn(f64) -> Option<T> + Sync),
) -> Option<Vec<(f64, T)>> {
    slopes
        .par_iter()
        .map(|&phi| eval(phi).map(|t| (phi, t)))
        .collect()
}

/// The profile of `eval` over the slopes `coarse` (ascending): every pair
/// of neighbours with different labels halved, all brackets of a round at
/// once, until each is at most `tol` wide. A midpoint with a third label
/// leaves a change on each side, both followed. `None` when `eval` was
/// stopped.
pub(crate) fn locate<T: Send>(
    coarse: &[f64],
    tol: f64,
    eval: &(dyn Fn(f64) -> Option<T> + Sync),
    label: impl Fn(&T) -> Label,
    progress: &dyn Progress,
) -> Option<Located<T>> {
    let mut points = round(coarse, eval)?;
    let mut open: Vec<Change> = points
        .windows(2)
        .filter_map(|w| {
            let (a, b) = (label(&w[0].1), label(&w[1].1));
            (a != b).then_some(Change {
                phi_left: w[0].0,
                phi_right: w[1].0,
                label_left: a,
                label_right: b,
                label_below: a,
                label_above: b,
            })
        })
        .collect();
    let mut changes = Vec::new();
    let mut rounds = 0;
    loop {
        let (done, rest): (Vec<Change>, Vec<Change>) = open
            .into_iter()
            .partition(|c| c.phi_right - c.phi_left <= tol);
        changes.extend(done);
        if rest.is_empty() {
            break;
        }
        rounds += 1;
        progress.stage(&format!("bisection round {rounds}"));
        progress.start(rest.len() as u64);
        let mids: Vec<f64> = rest
            .iter()
            .map(|c| c.phi_left + 0.5 * (c.phi_right - c.phi_left))
            .collect();
        let found = round(&mids, eval)?;
        open = Vec::new();
        for (c, (m, t)) in rest.iter().zip(&found) {
            let at = label(t);
            if at != c.label_left {
                open.push(Change {
                    phi_right: *m,
                    label_right: at,
                    ..*c
                });
            }
            if at != c.label_right {
                open.push(Change {
                    phi_left: *m,
                    label_left: at,
                    ..*c
                });
            }
        }
        points.extend(found);
    }
    changes.sort_by(|a, b| a.phi_left.total_cmp(&b.phi_left));
    // Each change checked one tol either side of its middle, as a direct
    // simulation there would check it; these runs are not profile points.
    let (from, to) = (coarse[0], coarse[coarse.len() - 1]);
    let checks: Vec<f64> = changes
        .iter()
        .flat_map(|c| {
            let mid = c.phi_left + 0.5 * (c.phi_right - c.phi_left);
            [(mid - tol).max(from), (mid + tol).min(to)]
        })
        .collect();
    if !checks.is_empty() {
        progress.stage("each change checked one tol either side");
        progress.start(checks.len() as u64);
    }
    let checked = round(&checks, eval)?;
    for (c, pair) in changes.iter_mut().zip(checked.chunks(2)) {
        c.label_below = label(&pair[0].1);
        c.label_above = label(&pair[1].1);
    }
    points.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut segments: Vec<Segment> = Vec::new();
    for (phi, t) in &points {
        let l = label(t);
        match segments.last_mut() {
            Some(s) if s.label == l => {
                s.hi = *phi;
                s.runs += 1;
            }
            _ => segments.push(Segment {
                label: l,
                lo: *phi,
                hi: *phi,
                runs: 1,
            }),
        }
    }
    Some(Located {
        points,
        changes,
        segments,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use rtw_engine::scan::progress::Silent;
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// The coarse grid of `Settings::coarse` over [from, to] at `grid`.
    fn grid(from: f64, to: f64, n: usize) -> Vec<f64> {
        (0..=n)
            .map(|i| from + (to - from) * i as f64 / n as f64)
            .collect()
    }

    /// A labeller with changes at known slopes: `walk` below the first,
    /// then `skip`, then `collapse` above the second; counts its runs.
    fn fake(
        first: f64,
        second: f64,
        runs: &AtomicUsize,
    ) -> impl Fn(f64) -> Option<Label> + Sync + '_ {
        move |phi| {
            runs.fetch_add(1, Ordering::Relaxed);
            Some(if phi < first {
                Label::Walk
            } else if phi < second {
                Label::Skip
            } else {
                Label::Collapse
            })
        }
    }

    #[test]
    fn a_change_is_located_within_tol_in_log2_of_grid_over_tol_runs() {
        // 26 slopes 0.01 apart over [0.05, 0.3]; the walk ends at 0.123456.
        let coarse = grid(0.05, 0.3, 25);
        for tol in [1e-3, 1e-6] {
            let runs = AtomicUsize::new(0);
            let eval = fake(0.123456, 10.0, &runs);
            let l = locate(&coarse, tol, &eval, |l| *l, &Silent).unwrap();
            assert_eq!(l.changes.len(), 1);
            let c = l.changes[0];
            assert!(c.phi_right - c.phi_left <= tol, "{c:?}");
            assert!(c.phi_left < 0.123456 && 0.123456 <= c.phi_right, "{c:?}");
            assert_eq!((c.label_left, c.label_right), (Label::Walk, Label::Skip));
            // Bisection: the grid, then ceil(log2(0.01 / tol)) midpoints
            // (4 at 1e-3, 14 at 1e-6), where a grid at tol would take
            // 0.25 / tol + 1 runs.
            let halvings = (0.01 / tol).log2().ceil() as usize;
            // And two runs checking it, one tol either side: it is sharp.
            assert_eq!(runs.load(Ordering::Relaxed), 26 + halvings + 2);
            assert!(c.sharp(), "{c:?}");
            assert_eq!(l.points.len(), 26 + halvings);
            assert!(l.points.windows(2).all(|w| w[0].0 < w[1].0));
        }
    }

    #[test]
    fn two_changes_inside_one_grid_cell_are_both_located() {
        // The skip lasts 1.7e-3 rad, inside the cell [0.12, 0.13]: the
        // first midpoint's third label splits the bracket in two.
        let coarse = grid(0.05, 0.3, 25);
        let runs = AtomicUsize::new(0);
        let eval = fake(0.1234, 0.1251, &runs);
        let l = locate(&coarse, 1e-4, &eval, |l| *l, &Silent).unwrap();
        let got: Vec<(Label, Label)> = l
            .changes
            .iter()
            .map(|c| (c.label_left, c.label_right))
            .collect();
        assert_eq!(
            got,
            [(Label::Walk, Label::Skip), (Label::Skip, Label::Collapse)]
        );
        for (c, at) in l.changes.iter().zip([0.1234, 0.1251]) {
            assert!(c.phi_right - c.phi_left <= 1e-4, "{c:?}");
            assert!(c.phi_left < at && at <= c.phi_right, "{c:?} {at}");
        }
        let labels: Vec<Label> = l.segments.iter().map(|s| s.label).collect();
        assert_eq!(labels, [Label::Walk, Label::Skip, Label::Collapse]);
        assert_eq!(l.segments[0].lo, 0.05);
        assert_eq!(l.segments[2].hi, 0.3);
        assert_eq!(l.segments[1].lo, l.changes[0].phi_right);
        assert_eq!(l.segments[1].hi, l.changes[1].phi_left);
    }

    #[test]
    fn a_change_inside_a_band_of_two_labels_is_not_sharp() {
        // Walk below 0.1537, skip above, but also a skip blip in
        // [0.1510, 0.1513] and a walk blip in [0.1551, 0.1553]: the grid and
        // the bisection (midpoints 0.155, 0.1525, 0.15375) find the change
        // in [0.1525, 0.15375]; one tol (2e-3) either side of its middle
        // (0.151125, 0.155125) the labels are the other ones.
        let coarse = grid(0.05, 0.3, 25);
        let eval = |phi: f64| {
            let skip = (phi >= 0.1537 && !(0.1551..0.1553).contains(&phi))
                || (0.1510..0.1513).contains(&phi);
            Some(if skip { Label::Skip } else { Label::Walk })
        };
        let l = locate(&coarse, 2e-3, &eval, |l| *l, &Silent).unwrap();
        assert_eq!(l.changes.len(), 1);
        let c = l.changes[0];
        assert!(c.phi_left < 0.1537 && 0.1537 <= c.phi_right, "{c:?}");
        assert_eq!((c.label_below, c.label_above), (Label::Skip, Label::Walk));
        assert!(!c.sharp());
    }

    #[test]
    fn a_stopped_eval_gives_none() {
        let coarse = grid(0.0, 0.1, 10);
        let eval = |phi: f64| (phi < 0.05).then_some(Label::Walk);
        assert!(locate(&coarse, 1e-3, &eval, |l| *l, &Silent).is_none());
    }
}
