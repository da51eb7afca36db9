//! The mean first-passage time of a metastable walker by adaptive
//! multilevel splitting (AMS) of its excursions, with diagnostics: a second
//! estimator beside [`crate::metastable`]'s counting, whose cost grows as
//! `log(MFPT)` and not as the MFPT.
//!
//! **The regime.** A Fleming–Viot cloud of `cloud` walkers steps from the
//! start for `burn_in` steps and `sample_steps` more; a walker that falls
//! restarts as a copy of a survivor drawn uniformly, so the cloud samples
//! the walker conditioned on not falling (its quasi-stationary distribution,
//! QSD). Until a walker first falls it is plain Monte Carlo from the start,
//! which gives the transient (`head`, the mean steps within the burn-in, and
//! `alive`, the share still walking after it). The reference set `A` is the
//! states whose [`Walker::score`] is at most the `quantile` of the sampled
//! scores; the sampled states in `A` are where excursions start.
//!
//! **An excursion** from a state of `A` is the steps until the walker is
//! back in `A` (a state scoring at most `A`'s level: a return) or has
//! fallen; `max_excursion` steps out count as a return. Its value is its
//! largest score (`∞` once it fell).
//!
//! **The splitting** (Cérou and Guyader, Stoch. Anal. Appl. 25(2) 2007; in
//! the discrete-time form whose estimate is unbiased for any score,
//! Bréhier, Gazeau, Goudenège, Lelièvre and Rousset, Ann. Appl. Probab.
//! 26(6) 2016): `N = replicas` independent excursions; at each iteration the
//! level `z` is the `kill`-th lowest value, every excursion of value at most
//! `z` (`K ≥ kill` of them, ties included) is replaced by a copy of a
//! survivor drawn uniformly, cut at the survivor's first state scoring above
//! `z` and continued with fresh randomness. It stops when fewer than `kill`
//! excursions have not fallen (or after `max_iterations`); then
//!
//! `p̂ = ∏ⱼ (1 − Kⱼ/N) × (fallen / N)`,
//!
//! an unbiased estimate of `p`, the probability that an excursion falls
//! before it returns (0 when an iteration would kill every excursion).
//!
//! **The MFPT** by renewal at the returns to `A`: each excursion falls with
//! probability `p`, independently of the ones before, so the number of
//! returns before the fall is geometric with mean `(1 − p)/p`, and
//!
//! `MFPT_A = E[T | returned] (1 − p)/p + E[T | fell]`,
//!
//! `T` an excursion's steps (a fall counts as a step). `E[T | returned]` is
//! the mean over the first iteration's independent excursions that
//! returned, `E[T | fell]` over the final excursions that fell. From the
//! start, `mfpt = head + alive × MFPT_A` (the survivors of the burn-in are in
//! the QSD, whose MFPT differs from `A`'s by less than an excursion).
//!
//! **Batches and the interval.** Each of `batches` independent batches gives
//! `p̂` and the two means; `p` is their mean, with a Student-t 95 %
//! interval, and so are the means. `MFPT_A`'s interval takes the ends that
//! make it smallest and largest (infinite when `p`'s interval reaches 0).
//!
//! **Diagnostics** per batch ([`SplitBatch`]): the levels, the iterations,
//! the distinct first-iteration ancestors of the final excursions (one: all
//! are copies of a single excursion, and the batch has seen one way to fall)
//! and their count at each iteration.
//!
//! The estimate is a pure function of the walker, its start and
//! [`SplitOptions::seed`].

use crate::metastable::{Rng, Walker, t95};

/// The settings of [`split`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SplitOptions {
    /// Seed of every batch's randomness.
    pub seed: u64,
    /// Independent batches (at least 2): their spread gives the interval.
    pub batches: usize,
    /// Excursions of a splitting, `N` (at least 2).
    pub replicas: usize,
    /// Excursions killed at each iteration, at least (`1 ≤ kill < N`).
    pub kill: usize,
    /// Walkers of the Fleming–Viot cloud (at least 2).
    pub cloud: usize,
    /// The cloud's steps from the start before it samples the QSD.
    pub burn_in: usize,
    /// The cloud's steps that sample the QSD (at least 1).
    pub sample_steps: usize,
    /// `A` holds the sampled states scoring at most this quantile of the
    /// sampled scores.
    pub quantile: f64,
    /// An excursion this many steps out counts as returned.
    pub max_excursion: usize,
    /// A splitting stops after this many iterations, its estimate then the
    /// product so far times the share fallen.
    pub max_iterations: usize,
}

impl Default for SplitOptions {
    fn default() -> Self {
        Self {
            seed: 0,
            batches: 12,
            replicas: 100,
            kill: 1,
            cloud: 32,
            burn_in: 20,
            sample_steps: 50,
            quantile: 0.5,
            max_excursion: 1000,
            max_iterations: 1_000_000,
        }
    }
}

/// What one batch of [`split`] measured.
#[derive(Clone, Debug, PartialEq)]
pub struct SplitBatch {
    /// `p̂`: the probability that an excursion from `A` falls before it
    /// returns.
    pub p: f64,
    /// The mean steps of the first iteration's excursions that returned.
    pub returned_steps: f64,
    /// The mean steps of the final excursions that fell (NaN: none fell).
    pub fall_steps: f64,
    /// The cloud's walkers' mean steps within the burn-in.
    pub head: f64,
    /// The share of them still walking after it.
    pub alive: f64,
    /// `A`'s level (the quantile of the sampled scores).
    pub level_a: f64,
    /// The level of each iteration.
    pub levels: Vec<f64>,
    /// The distinct first-iteration ancestors of the excursions after each
    /// iteration.
    pub ancestors_by_iteration: Vec<usize>,
    /// The distinct first-iteration ancestors of the final excursions that
    /// fell (of all of them when none fell).
    pub ancestors: usize,
    /// The final excursions that fell.
    pub fell: usize,
    /// The splitting stopped at `max_iterations`.
    pub capped: bool,
    /// Steps this batch took.
    pub steps: u64,
}

impl SplitBatch {
    /// The iterations of the splitting.
    pub fn iterations(&self) -> usize {
        self.levels.len()
    }
}

/// The estimate of [`split`].
#[derive(Clone, Debug, PartialEq)]
pub struct Split {
    /// Expected steps to fall from the start, `head + alive × MFPT_A`.
    pub mfpt: f64,
    /// Lower end of its 95 % interval.
    pub lo: f64,
    /// Upper end (infinite when the interval of `p` reaches 0).
    pub hi: f64,
    /// `MFPT_A`, the expected steps to fall from `A` (see the module doc).
    pub mfpt_a: f64,
    /// Its 95 % interval.
    pub mfpt_a_interval: (f64, f64),
    /// `p`, the mean of the batches' `p̂`.
    pub p: f64,
    /// Its 95 % interval.
    pub p_interval: (f64, f64),
    /// `E[T | returned]`, mean over the batches.
    pub returned_steps: f64,
    /// `E[T | fell]`, mean over the batches in which some fell.
    pub fall_steps: f64,
    /// The per-step fall probability of the regime, `1 / MFPT_A`.
    pub fall_rate: f64,
    /// Each batch.
    pub batches: Vec<SplitBatch>,
    /// Steps the walker took in all (the cost).
    pub steps: u64,
}

/// The expected steps to fall from `A` by renewal: `returned × (1 − p)/p +
/// fell` (infinite for `p = 0`).
pub fn renewal_mfpt(p: f64, returned: f64, fell: f64) -> f64 {
    if p <= 0.0 {
        f64::INFINITY
    } else {
        returned * (1.0 - p) / p + fell
    }
}

/// The mean of `v` and the half width of its Student-t 95 % interval (NaN
/// for an empty `v`, infinite half width for one value).
fn mean_half(v: &[f64]) -> (f64, f64) {
    let m = v.len() as f64;
    let mean = v.iter().sum::<f64>() / m;
    if v.len() < 2 {
        return (mean, f64::INFINITY);
    }
    let var = v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (m - 1.0);
    (mean, t95(v.len() - 1) * (var / m).sqrt())
}

/// The MFPT of `walker` from the start `start` by adaptive multilevel
/// splitting (see the module doc); `None` when the walker
/// [stopped](Walker::stopped) it part way.
pub fn split<W: Walker>(walker: &W, start: &W::State, o: &SplitOptions) -> Option<Split> {
    assert!(
        o.batches >= 2 && o.replicas >= 2 && o.cloud >= 2 && o.sample_steps >= 1,
        "split: at least 2 batches, 2 replicas, 2 walkers and 1 sampled step"
    );
    assert!(
        o.kill >= 1 && o.kill < o.replicas,
        "split: kill in [1, replicas)"
    );
    let batches: Vec<SplitBatch> = (0..o.batches)
        .map(|b| {
            let mut rng = Rng::new(Rng::new(o.seed ^ 0x0073_706c_6974).next_u64() ^ b as u64);
            // Decorrelate neighbouring batch seeds.
            rng.next_u64();
            batch(walker, start, o, &mut rng)
        })
        .collect::<Option<_>>()?;
    let of = |f: fn(&SplitBatch) -> f64| -> Vec<f64> {
        batches.iter().map(f).filter(|v| !v.is_nan()).collect()
    };
    let (p, p_half) = mean_half(&of(|b| b.p));
    let (p_lo, p_hi) = ((p - p_half).max(0.0), (p + p_half).min(1.0));
    let (tr, tr_half) = mean_half(&of(|b| b.returned_steps));
    let (tf, tf_half) = mean_half(&of(|b| b.fall_steps));
    // A batch with no fall has no `E[T | fell]`; none at all leaves it 1
    // step, its least, and the MFPT infinite anyway.
    let (tf, tf_half) = if tf.is_nan() {
        (1.0, 0.0)
    } else {
        (tf, tf_half)
    };
    let tf_lo = (tf - tf_half).max(1.0);
    let mfpt_a = renewal_mfpt(p, tr, tf);
    let a_lo = renewal_mfpt(p_hi, (tr - tr_half).max(1.0), tf_lo);
    let a_hi = renewal_mfpt(p_lo, tr + tr_half, tf + tf_half);
    let (head, head_half) = mean_half(&of(|b| b.head));
    let (alive, alive_half) = mean_half(&of(|b| b.alive));
    let steps = batches.iter().map(|b| b.steps).sum();
    Some(Split {
        mfpt: head + alive * mfpt_a,
        lo: (head - head_half).max(0.0) + (alive - alive_half).max(0.0) * a_lo,
        hi: head + head_half + (alive + alive_half).min(1.0) * a_hi,
        mfpt_a,
        mfpt_a_interval: (a_lo, a_hi),
        p,
        p_interval: (p_lo, p_hi),
        returned_steps: tr,
        fall_steps: tf,
        fall_rate: 1.0 / mfpt_a,
        batches,
        steps,
    })
}

/// The QSD's sample and the transient, from the Fleming–Viot cloud.
struct Cloud<S> {
    sample: Vec<(f64, S)>,
    head: f64,
    alive: f64,
}

/// Part 1 of a batch: the Fleming–Viot cloud from `start`.
fn cloud<W: Walker>(
    walker: &W,
    start: &W::State,
    o: &SplitOptions,
    rng: &mut Rng,
    steps: &mut u64,
) -> Option<Cloud<W::State>> {
    let mut cloud: Vec<W::State> = vec![start.clone(); o.cloud];
    let mut original = vec![true; o.cloud];
    let mut head = 0.0;
    let mut sample = Vec::with_capacity(o.cloud * o.sample_steps);
    for i in 0..o.burn_in + o.sample_steps {
        if walker.stopped() {
            return None;
        }
        *steps += cloud.len() as u64;
        let next: Vec<Option<W::State>> = cloud.iter().map(|s| walker.step(s, rng)).collect();
        if i < o.burn_in {
            for (orig, s) in original.iter_mut().zip(&next) {
                if *orig {
                    head += 1.0;
                    *orig = s.is_some();
                }
            }
        }
        let alive: Vec<usize> = (0..next.len()).filter(|&j| next[j].is_some()).collect();
        cloud = next
            .iter()
            .map(|s| match (s, alive.is_empty()) {
                (Some(s), _) => s.clone(),
                // The whole cloud fell: it starts again.
                (None, true) => start.clone(),
                // A fallen walker restarts as a copy of a survivor.
                (None, false) => next[alive[rng.below(alive.len())]]
                    .clone()
                    .unwrap_or_else(|| start.clone()),
            })
            .collect();
        if i >= o.burn_in {
            sample.extend(cloud.iter().map(|s| (walker.score(s), s.clone())));
        }
    }
    let n = o.cloud as f64;
    Some(Cloud {
        sample,
        head: head / n,
        alive: original.iter().filter(|&&a| a).count() as f64 / n,
    })
}

/// An excursion: its states after its start, their scores, whether it fell
/// after the last, and its first-iteration ancestor.
#[derive(Clone)]
struct Excursion<S> {
    from: usize,
    states: Vec<S>,
    scores: Vec<f64>,
    fell: bool,
    ancestor: usize,
}

impl<S> Excursion<S> {
    /// Its largest score, infinite once it fell.
    fn value(&self) -> f64 {
        if self.fell {
            f64::INFINITY
        } else {
            self.scores
                .iter()
                .copied()
                .fold(f64::NEG_INFINITY, f64::max)
        }
    }

    /// Its steps (a fall is one).
    fn len(&self) -> usize {
        self.states.len() + usize::from(self.fell)
    }
}

/// Continues `e` from its last state (from `from` when it has none) until
/// it returns to `A` (a score at most `level_a`) or falls.
fn go_on<W: Walker>(
    walker: &W,
    from: &W::State,
    mut e: Excursion<W::State>,
    level_a: f64,
    o: &SplitOptions,
    rng: &mut Rng,
    steps: &mut u64,
) -> Option<Excursion<W::State>> {
    loop {
        if walker.stopped() {
            return None;
        }
        let last = e.states.last().unwrap_or(from);
        *steps += 1;
        match walker.step(last, rng) {
            None => {
                e.fell = true;
                return Some(e);
            }
            Some(next) => {
                let s = walker.score(&next);
                e.states.push(next);
                e.scores.push(s);
                if s <= level_a || e.states.len() >= o.max_excursion {
                    return Some(e);
                }
            }
        }
    }
}

/// The distinct ancestors among `reps` (those that fell, if any did and
/// `fell_only`).
fn ancestors<S>(reps: &[Excursion<S>], fell_only: bool) -> usize {
    let mut a: Vec<usize> = reps
        .iter()
        .filter(|e| !fell_only || e.fell)
        .map(|e| e.ancestor)
        .collect();
    a.sort_unstable();
    a.dedup();
    a.len()
}

/// One batch: the cloud, then the splitting of the excursions from `A`.
fn batch<W: Walker>(
    walker: &W,
    start: &W::State,
    o: &SplitOptions,
    rng: &mut Rng,
) -> Option<SplitBatch> {
    let mut steps = 0u64;
    let c = cloud(walker, start, o, rng, &mut steps)?;
    let mut scores: Vec<f64> = c.sample.iter().map(|s| s.0).collect();
    scores.sort_by(f64::total_cmp);
    let level_a = scores[((o.quantile * scores.len() as f64) as usize).min(scores.len() - 1)];
    let near: Vec<&W::State> = c
        .sample
        .iter()
        .filter(|s| s.0 <= level_a)
        .map(|s| &s.1)
        .collect();
    let n = o.replicas;
    let mut reps = Vec::with_capacity(n);
    for i in 0..n {
        let from = rng.below(near.len());
        let e = Excursion {
            from,
            states: Vec::new(),
            scores: Vec::new(),
            fell: false,
            ancestor: i,
        };
        reps.push(go_on(walker, near[from], e, level_a, o, rng, &mut steps)?);
    }
    let returned: Vec<f64> = reps
        .iter()
        .filter(|e| !e.fell)
        .map(|e| e.len() as f64)
        .collect();
    let returned_steps = if returned.is_empty() {
        f64::NAN
    } else {
        returned.iter().sum::<f64>() / returned.len() as f64
    };
    let mut weight = 1.0;
    let (mut levels, mut by_iteration) = (Vec::new(), Vec::new());
    let mut capped = false;
    loop {
        let mut values: Vec<f64> = reps.iter().map(Excursion::value).collect();
        values.sort_by(f64::total_cmp);
        let z = values[o.kill - 1];
        if z == f64::INFINITY {
            break;
        }
        if levels.len() >= o.max_iterations {
            capped = true;
            break;
        }
        let (killed, alive): (Vec<usize>, Vec<usize>) = (0..n).partition(|&i| reps[i].value() <= z);
        levels.push(z);
        if alive.is_empty() {
            // Every excursion at the level: none climbs above it.
            weight = 0.0;
            by_iteration.push(ancestors(&reps, false));
            break;
        }
        weight *= 1.0 - killed.len() as f64 / n as f64;
        for i in killed {
            let parent = &reps[alive[rng.below(alive.len())]];
            // The parent's first state above `z` (it has one: its value is
            // above `z`, or it fell, and then the fall itself is the cut).
            let child = match parent.scores.iter().position(|&s| s > z) {
                None => parent.clone(),
                Some(c) => {
                    let e = Excursion {
                        from: parent.from,
                        states: parent.states[..=c].to_vec(),
                        scores: parent.scores[..=c].to_vec(),
                        fell: false,
                        ancestor: parent.ancestor,
                    };
                    if parent.scores[c] <= level_a || e.states.len() >= o.max_excursion {
                        // The cut is the parent's return itself.
                        e
                    } else {
                        go_on(walker, near[parent.from], e, level_a, o, rng, &mut steps)?
                    }
                }
            };
            reps[i] = child;
        }
        by_iteration.push(ancestors(&reps, false));
    }
    let fell: Vec<&Excursion<W::State>> = reps.iter().filter(|e| e.fell).collect();
    let fall_steps = if fell.is_empty() {
        f64::NAN
    } else {
        fell.iter().map(|e| e.len() as f64).sum::<f64>() / fell.len() as f64
    };
    Some(SplitBatch {
        p: weight * fell.len() as f64 / n as f64,
        returned_steps,
        fall_steps,
        head: c.head,
        alive: c.alive,
        level_a,
        levels,
        ancestors_by_iteration: by_iteration,
        ancestors: ancestors(&reps, !fell.is_empty()),
        fell: fell.len(),
        capped,
        steps,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A gambler's walk on `0..=top` that steps up with probability `up`,
    /// falls below 0 and is held at `top`; `A` is `{top}` (score `top − s`,
    /// quantile 0: the QSD's mode is the top).
    struct Ladder {
        up: f64,
        top: i32,
    }

    impl Walker for Ladder {
        type State = i32;
        fn step(&self, s: &i32, rng: &mut Rng) -> Option<i32> {
            let next = if rng.uniform() < self.up {
                (s + 1).min(self.top)
            } else {
                s - 1
            };
            (next >= 0).then_some(next)
        }
        fn score(&self, s: &i32) -> f64 {
            f64::from(self.top - s)
        }
    }

    /// The gambler's ruin from `top − 1` before `top`, exactly: with
    /// `r = (1 − up)/up`, from `i` the walk reaches `top` before `−1` with
    /// probability `(1 − r^(i+1)) / (1 − r^(top+1))`.
    fn ruin(l: &Ladder) -> f64 {
        let r = (1.0 - l.up) / l.up;
        let i = f64::from(l.top - 1);
        1.0 - (1.0 - r.powf(i + 1.0)) / (1.0 - r.powf(f64::from(l.top) + 1.0))
    }

    #[test]
    fn the_splitting_s_p_is_the_gambler_s_ruin() {
        // From the top an excursion steps down with probability 1 − up
        // (staying is a return of one step); then it is ruined with the
        // gambler's probability: p ≈ 3e-4 and 2e-8.
        for (up, top) in [(0.6, 20), (0.7, 22)] {
            let l = Ladder { up, top };
            let exact = (1.0 - up) * ruin(&l);
            let o = SplitOptions {
                quantile: 0.0,
                replicas: 200,
                batches: 12,
                ..SplitOptions::default()
            };
            let s = split(&l, &top, &o).unwrap();
            let (lo, hi) = s.p_interval;
            assert!(
                lo <= exact && exact <= hi,
                "{exact:e} vs {:?}",
                s.p_interval
            );
            assert!(hi / lo < 2.0, "{:?}", s.p_interval);
            // Each batch ends with every excursion fallen, and its levels
            // climb.
            for b in &s.batches {
                assert_eq!(b.fell, o.replicas);
                assert!(b.levels.windows(2).all(|w| w[0] <= w[1]));
                assert!(b.ancestors >= 1 && b.ancestors <= o.replicas);
            }
            assert_eq!(Some(s), split(&l, &top, &o));
        }
    }

    #[test]
    fn the_renewal_mfpt_is_the_geometric_count_of_returns() {
        // Returns of 2 steps, a fall after 5 with probability 1/4 each
        // excursion: 3 returns expected before it.
        assert_eq!(renewal_mfpt(0.25, 2.0, 5.0), 3.0 * 2.0 + 5.0);
        assert_eq!(renewal_mfpt(0.0, 2.0, 5.0), f64::INFINITY);
    }
}
