//! Where to spend the next samples of a scan: where a nearest-neighbour
//! classifier of the outcome labels is unsure.
//!
//! The criterion (uncertainty sampling over a pool of candidates): the
//! samples are points of the unit cube (each uniform axis mapped to
//! `(v − lo) / (hi − lo)`; fixed axes play no part), each with the outcome
//! label rtw gave it (a failure kind is a label of its own). A round of `n`
//! points draws a pool of `POOL × n` uniform candidates and scores each by
//! the disagreement of its `k = D + 2` nearest samples (D uniform axes):
//! `1 − (the share of the commonest label among them)`, zero where they
//! agree, times the distance to the nearest sample, so that a candidate in a
//! wide gap between samples of different labels goes before one next to a
//! sample already placed there. The highest-scoring candidates are taken;
//! a tenth of the round (and whatever the candidates with a positive score
//! do not fill) are plain uniform draws over the cube, so that a region
//! where no label change has been seen yet (a small island of another label
//! between the first samples) is still explored.
//!
//! A round is a deterministic function of the existing rows (in their
//! order), the seed and the round number: the candidates and the uniform
//! draws come from ChaCha8 seeded by the seed, on a stream of the round, and
//! ties between equal scores go to the earlier candidate.
//!
//! The neighbour search is brute force, O(POOL · n · N · D) per round for N
//! rows so far (in parallel over the candidates).

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use rtw_engine::scan::progress::Progress;
use std::sync::atomic::{AtomicBool, Ordering};

/// The share of a round's points that are uniform draws (exploration).
pub(crate) const EXPLORE_SHARE: f64 = 0.1;

/// Candidates drawn per point of a round.
pub(crate) const POOL: usize = 20;

/// The neighbours whose labels a candidate is scored by, in `dims` axes.
pub(crate) fn neighbours(dims: usize) -> usize {
    dims + 2
}

/// The `n` new points (unit cube, `dims` coordinates each) of round
/// `round`, from the samples `x` (unit cube) and their labels; `progress`
/// counts the candidates as they are scored (one [`Progress::advanced`]
/// each, out of a [`Progress::start`] of all of them): with 10⁶ rows a
/// round's neighbour search takes minutes, so it reads `stop` before each
/// candidate and gives `None` (no points) once it is set.
#[allow(clippy::too_many_arguments)]
pub(crate) fn propose(
    x: &[Vec<f64>],
    labels: &[usize],
    dims: usize,
    n: usize,
    seed: u64,
    round: u64,
    progress: &dyn Progress,
    stop: &AtomicBool,
) -> Option<Vec<Vec<f64>>> {
    assert_eq!(x.len(), labels.len(), "one label per sample");
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(round);
    let draw = |rng: &mut ChaCha8Rng| (0..dims).map(|_| rng.random::<f64>()).collect::<Vec<_>>();
    let pool: Vec<Vec<f64>> = (0..POOL * n).map(|_| draw(&mut rng)).collect();
    let k = neighbours(dims).min(x.len());
    progress.start(pool.len() as u64);
    let scores: Vec<f64> = pool
        .par_iter()
        .map(|c| {
            // A stopped search skips the rest: each score is a pass over
            // every row, and the round's points are not wanted any more.
            if stop.load(Ordering::Relaxed) {
                return 0.0;
            }
            let s = score(x, labels, c, k);
            progress.advanced();
            s
        })
        .collect();
    if stop.load(Ordering::SeqCst) {
        progress.finish(false);
        return None;
    }
    progress.finish(true);
    let mut order: Vec<usize> = (0..pool.len()).filter(|&i| scores[i] > 0.0).collect();
    order.sort_by(|&a, &b| scores[b].total_cmp(&scores[a]).then(a.cmp(&b)));
    let explore = ((n as f64) * EXPLORE_SHARE).ceil() as usize;
    let mut out: Vec<Vec<f64>> = order
        .iter()
        .take(n.saturating_sub(explore))
        .map(|&i| pool[i].clone())
        .collect();
    while out.len() < n {
        out.push(draw(&mut rng));
    }
    Some(out)
}

fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| (p - q) * (p - q))
        .sum::<f64>()
        .sqrt()
}

/// A candidate's score: the disagreement of its `k` nearest samples' labels
/// times its distance to the nearest sample (0 without samples).
fn score(x: &[Vec<f64>], labels: &[usize], c: &[f64], k: usize) -> f64 {
    let near = nearest(x, c, k);
    let Some(&(d0, _)) = near.first() else {
        return 0.0;
    };
    let mut counts = std::collections::BTreeMap::new();
    for &(_, j) in &near {
        *counts.entry(labels[j]).or_insert(0usize) += 1;
    }
    let top = counts.values().copied().max().unwrap_or(0);
    (1.0 - top as f64 / near.len() as f64) * d0
}

/// The `k` samples nearest to `c`, as (distance, index), nearest first; ties
/// to the lower index.
fn nearest(x: &[Vec<f64>], c: &[f64], k: usize) -> Vec<(f64, usize)> {
    let mut best: Vec<(f64, usize)> = Vec::with_capacity(k + 1);
    if k == 0 {
        return best;
    }
    for (j, p) in x.iter().enumerate() {
        let d = distance(c, p);
        if best.len() == k && d >= best[k - 1].0 {
            continue;
        }
        let at = best.partition_point(|&(e, m)| e < d || (e == d && m < j));
        best.insert(at, (d, j));
        best.truncate(k);
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use rtw_engine::scan::progress::Silent;

    /// `propose` never stopped.
    fn proposed(
        x: &[Vec<f64>],
        labels: &[usize],
        dims: usize,
        n: usize,
        seed: u64,
        round: u64,
        progress: &dyn Progress,
    ) -> Vec<Vec<f64>> {
        propose(
            x,
            labels,
            dims,
            n,
            seed,
            round,
            progress,
            &AtomicBool::new(false),
        )
        .expect("not stopped")
    }

    /// A stopped round scores no candidate and proposes no point: with 10⁶
    /// rows its neighbour search would otherwise run on for minutes after
    /// a Ctrl-C.
    #[test]
    fn a_stopped_round_scores_nothing_and_proposes_nothing() {
        use std::sync::atomic::AtomicU64;
        struct Count(AtomicU64);
        impl Progress for Count {
            fn computed(&self, _: rtw_model::Label) {}
            fn advanced(&self) {
                self.0.fetch_add(1, Ordering::SeqCst);
            }
        }
        let x = uniform(200, 1);
        let l: Vec<usize> = x.iter().map(|p| disc(p)).collect();
        let count = Count(AtomicU64::new(0));
        let stop = AtomicBool::new(true);
        assert!(propose(&x, &l, 2, 50, 7, 1, &count, &stop).is_none());
        assert_eq!(count.0.load(Ordering::SeqCst), 0, "candidates were scored");
    }

    /// A two-label problem in the unit square: label 1 inside the disc of
    /// radius 0.3 around (0.5, 0.5), 0 outside.
    fn disc(p: &[f64]) -> usize {
        usize::from((p[0] - 0.5).powi(2) + (p[1] - 0.5).powi(2) < 0.09)
    }

    fn uniform(n: usize, seed: u64) -> Vec<Vec<f64>> {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        (0..n)
            .map(|_| vec![rng.random::<f64>(), rng.random::<f64>()])
            .collect()
    }

    fn boundary_distance(p: &[f64]) -> f64 {
        (((p[0] - 0.5).powi(2) + (p[1] - 0.5).powi(2)).sqrt() - 0.3).abs()
    }

    #[test]
    fn same_rows_and_seed_give_the_same_points() {
        let x = uniform(300, 1);
        let l: Vec<usize> = x.iter().map(|p| disc(p)).collect();
        let a = proposed(&x, &l, 2, 50, 7, 1, &Silent);
        assert_eq!(a, proposed(&x, &l, 2, 50, 7, 1, &Silent));
        assert_ne!(
            a,
            proposed(&x, &l, 2, 50, 8, 1, &Silent),
            "the seed matters"
        );
        assert_ne!(
            a,
            proposed(&x, &l, 2, 50, 7, 2, &Silent),
            "the round matters"
        );
    }

    #[test]
    fn budget_is_respected_and_points_stay_in_the_cube() {
        let x = uniform(200, 2);
        let l: Vec<usize> = x.iter().map(|p| disc(p)).collect();
        for n in [0, 1, 9, 10, 57, 1000] {
            let p = proposed(&x, &l, 2, n, 3, 1, &Silent);
            assert_eq!(p.len(), n);
            assert!(p.iter().flatten().all(|v| (0.0..=1.0).contains(v)));
        }
        // One label only: no boundary, every point explores.
        let one = vec![0; x.len()];
        assert_eq!(proposed(&x, &one, 2, 20, 3, 1, &Silent).len(), 20);
    }

    #[test]
    fn new_points_lie_near_the_label_change() {
        let x = uniform(400, 3);
        let l: Vec<usize> = x.iter().map(|p| disc(p)).collect();
        let p = proposed(&x, &l, 2, 100, 5, 1, &Silent);
        let explore = (100.0 * EXPLORE_SHARE).ceil() as usize;
        let (near, far) = p.split_at(100 - explore);
        // Uniform points lie at a mean distance ~0.15 from the circle; the
        // bisected edges' points within the spacing of the samples (~0.05).
        let mean =
            |s: &[Vec<f64>]| s.iter().map(|q| boundary_distance(q)).sum::<f64>() / s.len() as f64;
        let uniform_mean = mean(&uniform(10_000, 9));
        assert!(mean(near) < 0.03, "refined mean distance {}", mean(near));
        assert!(uniform_mean > 0.1, "uniform mean distance {uniform_mean}");
        assert!(near.iter().all(|q| boundary_distance(q) < 0.1));
        assert_eq!(far.len(), explore);
    }

    #[test]
    fn rounds_shrink_the_error_of_the_label_map() {
        // Nearest-neighbour misclassification on a grid, uniform vs refined
        // at equal counts: the refined samples must do better.
        let grid: Vec<Vec<f64>> = (0..100)
            .flat_map(|i| {
                (0..100).map(move |j| vec![(i as f64 + 0.5) / 100.0, (j as f64 + 0.5) / 100.0])
            })
            .collect();
        let error = |x: &[Vec<f64>]| {
            let l: Vec<usize> = x.iter().map(|p| disc(p)).collect();
            grid.iter()
                .filter(|g| {
                    let (_, j) = x
                        .iter()
                        .enumerate()
                        .map(|(j, p)| (distance(g, p), j))
                        .min_by(|a, b| a.0.total_cmp(&b.0))
                        .unwrap();
                    l[j] != disc(g)
                })
                .count() as f64
                / grid.len() as f64
        };
        let mut x = uniform(100, 4);
        for round in 1..=4 {
            let l: Vec<usize> = x.iter().map(|p| disc(p)).collect();
            x.extend(proposed(&x, &l, 2, 100, 11, round, &Silent));
        }
        let refined = error(&x);
        let random = error(&uniform(500, 4));
        assert!(
            refined < 0.5 * random,
            "refined {refined}, uniform {random}"
        );
    }
}
