//! The archive of a design search: the best design of each cell of two
//! descriptors a designer reads, as MAP-Elites keeps it (Mouret & Clune,
//! "Illuminating search spaces by mapping elites", arXiv 1504.04909).
//!
//! The descriptors:
//! - **where it works**: the middle of the widest interval the objectives
//!   read (of the gait, if the config names one), in `SLOPE_BINS` equal
//!   bins over the search's slopes `[from, to]`;
//! - **how it moves there**: the share of its stable slopes that walk (the
//!   lengths of its walk segments over those of all its stable segments),
//!   in `WALK_BINS` equal bins of `[0, 1]`: 0 skips or crawls everywhere,
//!   1 walks everywhere.
//!
//! A feasible design enters its cell when the cell is empty or it scores
//! higher than the elite there (ties keep the elite); a design that falls
//! has no descriptors and enters no cell. Every search has an archive, of
//! the designs it evaluated whatever drew them; `method = "archive"` also
//! draws from it (`propose.rs`), which is what makes it a MAP-Elites
//! search.

use super::{Evaluation, SearchSettings};
use std::collections::BTreeMap;

/// Bins of the slope descriptor over `[from, to]`.
pub const SLOPE_BINS: usize = 8;
/// Bins of the walk share over `[0, 1]`.
pub const WALK_BINS: usize = 4;

/// A cell: its slope bin and its walk bin.
pub type Cell = (usize, usize);

/// The walk share of a design's stable segments `(label, lo, hi)`: walk
/// length over stable length; when every stable segment is a single slope
/// (zero length), the share of them that walk; `None` with none.
pub(crate) fn walk_share(
    segments: impl Iterator<Item = (rtw_model::Label, f64, f64)>,
) -> Option<f64> {
    let (mut walk, mut stable, mut n_walk, mut n) = (0.0, 0.0, 0usize, 0usize);
    for (label, lo, hi) in segments.filter(|s| s.0.is_stable()) {
        let is_walk = label == rtw_model::Label::Walk;
        stable += hi - lo;
        n += 1;
        if is_walk {
            walk += hi - lo;
            n_walk += 1;
        }
    }
    match (n, stable > 0.0) {
        (0, _) => None,
        (_, true) => Some(walk / stable),
        (_, false) => Some(n_walk as f64 / n as f64),
    }
}

/// The bin of `x` among `bins` equal bins of `[lo, hi]`, the ends in the
/// first and last bins.
fn bin(x: f64, lo: f64, hi: f64, bins: usize) -> usize {
    let t = ((x - lo) / (hi - lo)).clamp(0.0, 1.0);
    ((t * bins as f64) as usize).min(bins - 1)
}

/// The cell of a feasible evaluation (`None`: it falls, or lacks a
/// descriptor).
pub(crate) fn cell(s: &SearchSettings, e: &Evaluation) -> Option<Cell> {
    e.score?;
    let mid = 0.5 * (e.phi_lo? + e.phi_hi?);
    Some((
        bin(mid, s.from, s.to, SLOPE_BINS),
        bin(e.walk_share?, 0.0, 1.0, WALK_BINS),
    ))
}

/// One sub-search's elites: per cell, the evaluation's place in the
/// search's order, its score and its point in the unit box.
#[derive(Clone, Debug, Default)]
pub(crate) struct Elites {
    cells: BTreeMap<Cell, (f64, u64, Vec<f64>)>,
}

impl Elites {
    /// Offers the design `u` that scored `score` in `cell`; whether it
    /// entered.
    pub(crate) fn offer(&mut self, cell: Cell, score: f64, index: u64, u: &[f64]) -> bool {
        match self.cells.get(&cell) {
            Some((best, _, _)) if *best >= score => false,
            _ => {
                self.cells.insert(cell, (score, index, u.to_vec()));
                true
            }
        }
    }

    /// Cells filled.
    pub(crate) fn len(&self) -> usize {
        self.cells.len()
    }

    /// The elites' scores and points in the unit box, in cell order.
    pub(crate) fn points(&self) -> Vec<(f64, &[f64])> {
        self.cells
            .values()
            .map(|(score, _, u)| (*score, u.as_slice()))
            .collect()
    }
}

/// The archive of a finished search: per sub-search (round), each cell's
/// elite by its place in the order of evaluation, with its score.
pub fn of(s: &SearchSettings, evaluations: &[Evaluation]) -> BTreeMap<(u64, Cell), (u64, f64)> {
    let mut rounds: BTreeMap<u64, Elites> = BTreeMap::new();
    for e in evaluations {
        if let (Some(c), Some(score)) = (cell(s, e), e.score) {
            rounds
                .entry(e.round)
                .or_default()
                .offer(c, score, e.index, &[]);
        }
    }
    rounds
        .into_iter()
        .flat_map(|(round, el)| {
            el.cells
                .into_iter()
                .map(move |(c, (score, index, _))| ((round, c), (index, score)))
        })
        .collect()
}

/// Coverage and QD-score of an archive: the share of a round's
/// `SLOPE_BINS × WALK_BINS` cells filled (over every round), and the sum of
/// the elites' scores (each a normalised objective, ≥ 0 for one).
pub fn coverage_and_qd(s: &SearchSettings, evaluations: &[Evaluation]) -> (f64, f64) {
    let archive = of(s, evaluations);
    // Of every sub-search's archive, those not yet begun included: a search
    // stopped before its last weight has not filled its cells.
    let cells = (SLOPE_BINS * WALK_BINS) as f64 * super::budget::rounds(s) as f64;
    let qd = archive.values().map(|(_, score)| score).sum();
    (archive.len() as f64 / cells, qd)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rtw_model::Label::*;

    #[test]
    fn the_walk_share_weighs_stable_segments_by_length() {
        let segs = [(Walk, 0.0, 0.3), (Collapse, 0.3, 0.4), (Skip, 0.4, 0.5)];
        assert!((walk_share(segs.into_iter()).unwrap() - 0.75).abs() < 1e-15);
        // Single slopes only: counted.
        let segs = [(Walk, 0.1, 0.1), (Skip, 0.2, 0.2), (Crawl, 0.3, 0.3)];
        assert_eq!(walk_share(segs.into_iter()), Some(1.0 / 3.0));
        assert_eq!(walk_share([(Stall, 0.0, 0.4)].into_iter()), None);
    }

    #[test]
    fn bins_put_the_ends_in_the_first_and_last() {
        assert_eq!(bin(0.0, 0.0, 1.0, 4), 0);
        assert_eq!(bin(0.2499, 0.0, 1.0, 4), 0);
        assert_eq!(bin(0.25, 0.0, 1.0, 4), 1);
        assert_eq!(bin(1.0, 0.0, 1.0, 4), 3);
        assert_eq!(bin(-3.0, 0.0, 1.0, 4), 0);
    }

    #[test]
    fn coverage_counts_the_cells_of_every_sub_search_begun_or_not() {
        // Two weights; the search stopped in its first: one elite of the
        // 2 × 32 cells the finished search would have.
        let s = SearchSettings::parse(
            "name = \"t\"\nseed = 1\nbudget = 100\nobjectives = [\"slope_range\", \"speed\"]\n\
             speed_phi = 0.1\nweights = 2\n[box]\nrho = [1.0, 5.0]\nalpha = [0.0, 0.4]\n\
             fn = [1.5, 5.0]\nzeta = [0.05, 0.1]\n[slopes]\nfrom = 0.0\nto = 0.4\n",
        )
        .unwrap();
        let e = Evaluation {
            index: 0,
            round: 0,
            generation: 0,
            design: [2.0, 0.1, 3.0, 0.07],
            p_fall: None,
            runs: 40,
            phi_lo: Some(0.1),
            phi_hi: Some(0.2),
            phi_min: Some(0.1),
            walk_share: Some(1.0),
            label_at_speed_phi: Some(Walk),
            speed: Some(1.0),
            label_at_mfpt_phi: None,
            mfpt: None,
            infeasible: None,
            values: vec![0.1, 1.0],
            score: Some(0.3),
        };
        let (coverage, qd) = coverage_and_qd(&s, &[e]);
        assert_eq!(coverage, 1.0 / 64.0);
        assert_eq!(qd, 0.3);
    }

    #[test]
    fn a_cell_keeps_its_best_and_the_first_of_equals() {
        let mut el = Elites::default();
        assert!(el.offer((0, 0), 0.2, 0, &[0.1]));
        assert!(!el.offer((0, 0), 0.2, 1, &[0.2]));
        assert!(!el.offer((0, 0), 0.1, 2, &[0.3]));
        assert!(el.offer((0, 0), 0.3, 3, &[0.4]));
        assert!(el.offer((1, 0), 0.0, 4, &[0.5]));
        assert_eq!(el.len(), 2);
        assert_eq!(el.points(), [(0.3, &[0.4][..]), (0.0, &[0.5][..])]);
    }
}
