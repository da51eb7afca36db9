//! The given-data first-order index (SALib delta's `S1`: the variance of
//! the means of an output in equal-frequency bins of an input's ranks, over
//! the output's variance) of every output to every input at once.
//!
//! Every output and input is resampled with the same rows (one stream drawn
//! from the seed), so each resample's rows are drawn once; each input puts
//! them in its order once, for every output; and each output's mean and
//! variance over them are computed once, for every input. The 0/1 outputs
//! (the outcome indicators) are counted by the pattern of ones each row has
//! rather than summed one by one: a sum of zeros and ones is exact in any
//! order, so the counts give the very sums that adding them gives. The
//! other outputs are added in the order of the input's ranks, as before;
//! every index is bit for bit what one output to one input at a time gives.

use super::{mean_var, std1};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use rtw_engine::analysis::report::Z95;
use rtw_engine::scan::progress::Progress;
use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, Ordering};

/// The number of equal-frequency bins for `n` rows (SALib delta's rule).
pub(super) fn bins(n: usize) -> usize {
    let n = n as f64;
    let exp = 2.0 / (7.0 + ((1500.0 - n) / 500.0).tanh());
    (n.powf(exp).ceil().min(48.0)).round() as usize
}

/// Where each of the `bins(n)` bins of `n` ranked rows ends: bin `j` holds
/// the ranks (1-based) in (`j n / m`, `(j + 1) n / m`], as SALib's
/// `delta.sobol_first` cuts them.
fn bin_ends(n: usize) -> Vec<usize> {
    let m = bins(n);
    let edge = |j: usize| j as f64 * n as f64 / m as f64;
    let mut rank = 0usize;
    (0..m)
        .map(|j| {
            while rank < n && (rank + 1) as f64 <= edge(j + 1) {
                rank += 1;
            }
            rank
        })
        .collect()
}

/// The rows of `x` ranked once, so that each resample is put in the order
/// of its `x` by counting (O(n)) rather than by sorting (O(n log n)).
pub(super) struct Ranks {
    /// The dense rank of each row's `x` among `x`'s distinct values.
    group: Vec<usize>,
    /// Number of distinct values.
    groups: usize,
}

/// A resample's working memory, kept from one input to the next.
#[derive(Default)]
pub(super) struct Scratch {
    /// Rows per distinct value, then where each value's rows go.
    counts: Vec<usize>,
    /// The resample's rows in the order of their `x`.
    pub(super) sorted: Vec<usize>,
}

impl Ranks {
    pub(super) fn of(x: &[f64]) -> Self {
        let mut by_x: Vec<usize> = (0..x.len()).collect();
        by_x.sort_by(|&p, &q| x[p].total_cmp(&x[q]));
        let mut group = vec![0; x.len()];
        let mut g = 0;
        for k in 1..by_x.len() {
            if x[by_x[k]].total_cmp(&x[by_x[k - 1]]).is_ne() {
                g += 1;
            }
            group[by_x[k]] = g;
        }
        let groups = if x.is_empty() { 0 } else { g + 1 };
        Self { group, groups }
    }

    /// `rows` in the order of their `x`, ties in the order they come in
    /// `rows`: exactly what a stable sort by `x` gives (a counting sort by
    /// the value's rank, which keeps the rows' order).
    pub(super) fn sort(&self, rows: &[usize], scratch: &mut Scratch) {
        let Scratch { counts, sorted } = scratch;
        counts.clear();
        counts.resize(self.groups + 1, 0);
        for &r in rows {
            counts[self.group[r] + 1] += 1;
        }
        for g in 1..counts.len() {
            counts[g] += counts[g - 1];
        }
        sorted.clear();
        sorted.resize(rows.len(), 0);
        for &r in rows {
            let at = &mut counts[self.group[r]];
            sorted[*at] = r;
            *at += 1;
        }
    }
}

/// The outputs as the estimator reads them: the 0/1 outputs as one pattern
/// of ones per row, the others row by row.
struct Outputs {
    /// How many outputs.
    len: usize,
    /// The 0/1 outputs' places among the outputs.
    indicators: Vec<usize>,
    /// Each row's pattern: an index into `patterns`.
    pattern: Vec<u8>,
    /// The distinct patterns: bit `b` set where indicator `b` is 1.
    patterns: Vec<u64>,
    /// The other outputs' places among the outputs.
    continuous: Vec<usize>,
    /// Their values, row-major (`continuous.len()` per row).
    values: Vec<f64>,
}

impl Outputs {
    fn of(outputs: &[&[f64]]) -> Self {
        let n = outputs.first().map_or(0, |y| y.len());
        let zero_one = |y: &[f64]| {
            y.iter()
                .all(|v| v.to_bits() == 0.0f64.to_bits() || v.to_bits() == 1.0f64.to_bits())
        };
        let mut indicators: Vec<usize> = (0..outputs.len())
            .filter(|&o| zero_one(outputs[o]))
            .take(64)
            .collect();
        let mut pattern = Vec::with_capacity(n);
        let mut patterns = Vec::new();
        let mut code: HashMap<u64, u8> = HashMap::new();
        let mut row_bits = vec![0u64; n];
        for (b, &o) in indicators.iter().enumerate() {
            for (bits, &v) in row_bits.iter_mut().zip(outputs[o]) {
                *bits |= u64::from(v == 1.0) << b;
            }
        }
        for bits in row_bits {
            let p = match code.get(&bits) {
                Some(&p) => p,
                None => {
                    let Ok(p) = u8::try_from(patterns.len()) else {
                        break;
                    };
                    code.insert(bits, p);
                    patterns.push(bits);
                    p
                }
            };
            pattern.push(p);
        }
        if pattern.len() < n {
            // More patterns than a byte tells apart: every output is summed.
            indicators.clear();
            pattern.clear();
            patterns.clear();
        }
        let continuous: Vec<usize> = (0..outputs.len())
            .filter(|o| !indicators.contains(o))
            .collect();
        let values = (0..n)
            .flat_map(|r| continuous.iter().map(move |&o| outputs[o][r]))
            .collect();
        Self {
            len: outputs.len(),
            indicators,
            pattern,
            patterns,
            continuous,
            values,
        }
    }

    /// Indicator `b` of the pattern `p`.
    fn one(&self, p: u8, b: usize) -> bool {
        self.patterns[usize::from(p)] >> b & 1 == 1
    }

    /// The ones of indicator `b` among rows counted by pattern (`per`).
    fn ones(&self, per: &[usize], b: usize) -> usize {
        self.patterns
            .iter()
            .zip(per)
            .filter(|(p, _)| *p >> b & 1 == 1)
            .map(|(_, c)| c)
            .sum()
    }
}

/// An output's mean and variance over a resample's rows, or `None` where it
/// is constant there (its index is then 0).
type Moments = Option<(f64, f64)>;

/// Every output's [`Moments`] over `rows`, each reduced in the rows' order
/// as [`mean_var`] reduces one output.
fn moments(out: &Outputs, rows: &[usize]) -> Vec<Moments> {
    let n = rows.len();
    let mut got = vec![None; out.len];
    let kc = out.continuous.len();
    if !out.indicators.is_empty() {
        let mut ones = vec![0usize; out.patterns.len()];
        for &r in rows {
            ones[usize::from(out.pattern[r])] += 1;
        }
        let mut mean = Vec::new();
        for (b, &o) in out.indicators.iter().enumerate() {
            let count = out.ones(&ones, b);
            // A sum of zeros and ones is the count of ones, in any order.
            let m = count as f64 / n as f64;
            mean.push(m);
            if count != 0 && count != n {
                got[o] = Some((m, 0.0));
            }
        }
        let mut sq = vec![0.0f64; out.indicators.len()];
        for &r in rows {
            let p = out.pattern[r];
            for (b, s) in sq.iter_mut().enumerate() {
                let d = f64::from(u8::from(out.one(p, b))) - mean[b];
                *s += d * d;
            }
        }
        for (&o, s) in out.indicators.iter().zip(sq) {
            if let Some((_, var)) = &mut got[o] {
                *var = s / n as f64;
            }
        }
    }
    for (c, &o) in out.continuous.iter().enumerate() {
        let y = rows.iter().map(|&r| out.values[r * kc + c]);
        let (lo, hi) = y
            .clone()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
                (l.min(v), h.max(v))
            });
        if hi - lo != 0.0 {
            got[o] = Some(mean_var(y));
        }
    }
    got
}

/// The binned first-order index of every output to the input ranked by
/// `ranks` over the resample `rows`, given the outputs' [`Moments`] there.
fn s1_once(
    ranks: &Ranks,
    out: &Outputs,
    rows: &[usize],
    moments: &[Moments],
    ends: &[usize],
    scratch: &mut Scratch,
) -> Vec<f64> {
    let n = rows.len();
    ranks.sort(rows, scratch);
    let sorted = &scratch.sorted;
    let kc = out.continuous.len();
    let mut vi = vec![0.0f64; out.len];
    let mut ones = vec![0usize; out.patterns.len()];
    let mut sums = vec![0.0f64; kc];
    let mut start = 0;
    for &end in ends {
        let c = end - start;
        if c == 0 {
            continue;
        }
        ones.fill(0);
        sums.fill(0.0);
        for &r in &sorted[start..end] {
            if !ones.is_empty() {
                ones[usize::from(out.pattern[r])] += 1;
            }
            // In the order of the input's ranks, as one output at a time
            // adds them.
            for (s, v) in sums.iter_mut().zip(&out.values[r * kc..(r + 1) * kc]) {
                *s += v;
            }
        }
        let mut add = |o: usize, s: f64| {
            if let Some((mean, _)) = moments[o] {
                vi[o] += c as f64 / n as f64 * (s / c as f64 - mean).powi(2);
            }
        };
        for (b, &o) in out.indicators.iter().enumerate() {
            let count = out.ones(&ones, b);
            add(o, count as f64);
        }
        for (&o, &s) in out.continuous.iter().zip(&sums) {
            add(o, s);
        }
        start = end;
    }
    vi.iter()
        .zip(moments)
        .map(|(v, m)| m.map_or(0.0, |(_, var)| v / var))
        .collect()
}

/// S1 and S1_conf of every output (`outputs`, each a value per row) to
/// every input (`inputs`), as `[output][input]`, with `resamples`
/// bootstrap resamples of the rows drawn from `seed`: each resample's rows
/// are the ones drawing for one output and one input alone would give.
/// `progress` advances by one per output, input and resample. Setting
/// `cancel` ends it between two resamples, with `None`.
pub fn binned(
    inputs: &[&[f64]],
    outputs: &[&[f64]],
    resamples: usize,
    seed: u64,
    cancel: &AtomicBool,
    progress: &dyn Progress,
) -> Option<Vec<Vec<[f64; 2]>>> {
    let n = outputs.first().map_or(0, |y| y.len());
    let out = Outputs::of(outputs);
    let ends = bin_ends(n);
    let ranks: Vec<Ranks> = inputs.par_iter().map(|x| Ranks::of(x)).collect();
    // Every input's index over `rows`: [input][output].
    let once = |rows: &[usize], scratch: &mut Scratch| -> Vec<Vec<f64>> {
        let m = moments(&out, rows);
        ranks
            .iter()
            .map(|r| s1_once(r, &out, rows, &m, &ends, scratch))
            .collect()
    };
    let all: Vec<usize> = (0..n).collect();
    let point = once(&all, &mut Scratch::default());
    drop(all);
    // Resamples run in parallel, a few at a time (their rows are held
    // until done), each drawn in turn from the one stream: the same on any
    // thread count.
    let batch = 2 * rayon::current_num_threads();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut boot: Vec<Vec<Vec<f64>>> = Vec::with_capacity(resamples);
    while boot.len() < resamples {
        if cancel.load(Ordering::Relaxed) {
            return None;
        }
        let draws: Vec<Vec<usize>> = (0..batch.min(resamples - boot.len()))
            .map(|_| (0..n).map(|_| rng.random_range(0..n)).collect())
            .collect();
        let done: Vec<Vec<Vec<f64>>> = draws
            .par_iter()
            .map_init(Scratch::default, |scratch, rows| {
                if cancel.load(Ordering::Relaxed) {
                    return None;
                }
                let s1 = once(rows, scratch);
                for _ in 0..inputs.len() * outputs.len() {
                    progress.advanced();
                }
                Some(s1)
            })
            .collect::<Option<_>>()?;
        boot.extend(done);
    }
    Some(
        (0..outputs.len())
            .map(|o| {
                (0..inputs.len())
                    .map(|i| {
                        let b: Vec<f64> = boot.iter().map(|s| s[i][o]).collect();
                        [point[i][o], Z95 * std1(&b)]
                    })
                    .collect()
            })
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use rtw_engine::scan::progress::Silent;

    /// Counting a resample into the order of its `x` gives exactly the
    /// stable sort's order (ties, repeated rows and all), so the binned
    /// index is what it was when each resample was sorted.
    #[test]
    fn a_resample_counted_into_order_is_the_stable_sort_of_its_x() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        for levels in [3, 50, 1_000_000] {
            let x: Vec<f64> = (0..500)
                .map(|_| rng.random_range(0..levels) as f64 / levels as f64)
                .collect();
            let ranks = Ranks::of(&x);
            let mut scratch = Scratch::default();
            for _ in 0..20 {
                let rows: Vec<usize> = (0..500).map(|_| rng.random_range(0..500)).collect();
                let mut sorted = rows.clone();
                sorted.sort_by(|&p, &q| x[p].total_cmp(&x[q]));
                ranks.sort(&rows, &mut scratch);
                assert_eq!(scratch.sorted, sorted, "{levels} levels");
            }
        }
    }

    #[test]
    fn binned_first_order_sees_the_input_that_matters() {
        let mut rng = ChaCha8Rng::seed_from_u64(4);
        let n = 4000;
        let x0: Vec<f64> = (0..n).map(|_| rng.random()).collect();
        let x1: Vec<f64> = (0..n).map(|_| rng.random()).collect();
        let y: Vec<f64> = x0.iter().map(|v| f64::from(u8::from(*v > 0.5))).collect();
        let go = AtomicBool::new(false);
        let s = binned(&[&x0, &x1], &[&y], 50, 1, &go, &Silent).unwrap();
        let ([s0, c0], [s1, _]) = (s[0][0], s[0][1]);
        assert!(binned(&[&x0], &[&y], 50, 1, &AtomicBool::new(true), &Silent).is_none());
        assert!(s0 > 0.9 && c0 < 0.05, "{s0} ± {c0}");
        assert!(s1 < 0.05, "{s1}");
        assert_eq!((bins(256), bins(1000), bins(28672)), (5, 6, 31));
    }

    /// The estimator written plainly, one output to one input at a time:
    /// its own stream of resamples from `seed`, each resample sorted
    /// (stably) by `x`, its bins cut by SALib's `delta.sobol_first` rule.
    fn one_at_a_time(x: &[f64], y: &[f64], resamples: usize, seed: u64) -> [f64; 2] {
        let n = y.len();
        let once = |rows: &[usize]| -> f64 {
            let yr = rows.iter().map(|&i| y[i]);
            let (lo, hi) = yr
                .clone()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
                    (l.min(v), h.max(v))
                });
            if hi - lo == 0.0 {
                return 0.0;
            }
            let (mean, var) = mean_var(yr);
            let mut order: Vec<usize> = (0..n).collect();
            order.sort_by(|&p, &q| x[rows[p]].total_cmp(&x[rows[q]]));
            let m = bins(n);
            let edge = |j: usize| j as f64 * n as f64 / m as f64;
            let (mut vi, mut rank) = (0.0, 0usize);
            for j in 0..m {
                let (mut s, mut c) = (0.0, 0usize);
                while rank < n && (rank + 1) as f64 <= edge(j + 1) {
                    s += y[rows[order[rank]]];
                    c += 1;
                    rank += 1;
                }
                if c > 0 {
                    vi += c as f64 / n as f64 * (s / c as f64 - mean).powi(2);
                }
            }
            vi / var
        };
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let boot: Vec<f64> = (0..resamples)
            .map(|_| {
                let rows: Vec<usize> = (0..n).map(|_| rng.random_range(0..n)).collect();
                once(&rows)
            })
            .collect();
        let all: Vec<usize> = (0..n).collect();
        [once(&all), Z95 * std1(&boot)]
    }

    /// Sharing each resample's rows, ranks and moments across outputs and
    /// inputs, and counting the 0/1 outputs by pattern, gives every index
    /// and half-width bit for bit as one output to one input at a time:
    /// inputs with ties (a few levels, many, none), outputs that are
    /// indicators (one-hot labels and their unions, one never 1), constant,
    /// and continuous over many magnitudes (where the order of addition
    /// shows in the last bits); also with more 0/1 patterns than a byte
    /// tells apart, where every output is summed.
    #[test]
    fn every_output_to_every_input_at_once_is_one_at_a_time_bit_for_bit() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let n = 700;
        let levels = |k: u32, rng: &mut ChaCha8Rng| -> Vec<f64> {
            (0..n)
                .map(|_| f64::from(rng.random_range(0..k)) / 7.0)
                .collect()
        };
        let inputs = [
            levels(3, &mut rng),
            levels(40, &mut rng),
            (0..n).map(|_| rng.random()).collect::<Vec<f64>>(),
        ];
        let label: Vec<u32> = inputs[0]
            .iter()
            .map(|&v| (v * 7.0) as u32 + rng.random_range(0..2))
            .collect();
        let is = |f: &dyn Fn(u32) -> bool| -> Vec<f64> {
            label.iter().map(|&l| f64::from(u8::from(f(l)))).collect()
        };
        let speed: Vec<f64> = inputs[2]
            .iter()
            .map(|v| (v * 30.0 + rng.random::<f64>()).exp() * 1e-3)
            .collect();
        let outputs_labelled = vec![
            is(&|l| l == 0),
            is(&|l| l == 1),
            is(&|l| l == 2),
            is(&|l| l == 3),
            is(&|l| l >= 2),
            is(&|l| l < 2),
            is(&|l| l > 9),
            vec![2.5; n],
            speed,
            levels(5, &mut rng),
        ];
        let many_patterns: Vec<Vec<f64>> = (0..9)
            .map(|_| {
                (0..n)
                    .map(|_| f64::from(rng.random_range(0..2u8)))
                    .collect()
            })
            .collect();
        let go = AtomicBool::new(false);
        for (outputs, shared_patterns) in [(outputs_labelled, true), (many_patterns, false)] {
            let x: Vec<&[f64]> = inputs.iter().map(Vec::as_slice).collect();
            let y: Vec<&[f64]> = outputs.iter().map(Vec::as_slice).collect();
            assert_eq!(!Outputs::of(&y).indicators.is_empty(), shared_patterns);
            let (resamples, seed) = (9, 11);
            let at_once = binned(&x, &y, resamples, seed, &go, &Silent).unwrap();
            for (o, yo) in y.iter().enumerate() {
                for (i, xi) in x.iter().enumerate() {
                    let want = one_at_a_time(xi, yo, resamples, seed);
                    assert_eq!(
                        at_once[o][i].map(f64::to_bits),
                        want.map(f64::to_bits),
                        "output {o}, input {i}: {:?} against {want:?}",
                        at_once[o][i]
                    );
                }
            }
        }
    }
}
