//! The mean first-passage time (MFPT) of a metastable walker from a Markov
//! chain on a mesh of the states it reaches, at a cost that does not grow
//! with the MFPT (Byl and Tedrake, IJRR 28(8) 2009; the reachable-set mesh
//! of Saglam and Byl, arXiv 1412.6704).
//!
//! **The walker** ([`ChainWalker`]) takes one standard-normal input per step
//! (on a rough ground: the height of the patch drawn afresh ahead, in units
//! of σ), and its step is a deterministic function of (state, input); it
//! exposes a feature vector of its *extended* state (its own state and
//! whatever of the ground already laid is within its reach), which is what
//! decides its next steps.
//!
//! **The estimate** ([`chain_mfpt`]):
//!
//! 1. **Cells.** A sample of the quasi-stationary distribution (QSD; e.g.
//!    [`qsd_cloud`], a Fleming–Viot cloud) is cut to `members` states; the
//!    features, standardised over the sample, are clustered by k-means
//!    (k-means++ seeding from [`ChainOptions::seed`], Lloyd iterations)
//!    into `cells` cells.
//! 2. **One step of each member**, its input integrated over N(0, 1) by
//!    Gauss–Hermite quadrature (`nodes` nodes), not sampled. An input
//!    *dooms* the member when the step falls or the `lookahead` steps after
//!    it with the mean input (0) do: a fall set by the ground just laid
//!    comes a step or two later. Where the most extreme input (`±Z_FAR`)
//!    dooms it, the critical input is found by bisection between it and the
//!    nearest node that does not, and the tail beyond it is the law's own,
//!    `Φ(z_c)` or `Φ(−z_c)` from `erfc`: a tail of 10⁻⁹ comes from the law,
//!    not from counting. The nodes inside the surviving range carry its
//!    mass (their weights rescaled to it); a doomed node inside it falls.
//! 3. **The chain.** `Q[a][b]` is the mean over cell `a`'s members of the
//!    mass their step sends to the cell nearest to where it lands (the
//!    rest, to the fall). `Q` is substochastic; the MFPT from the QSD is
//!    `1/(1 − λ)`, `λ` its dominant eigenvalue. It is found by power
//!    iteration on the left (`ν ← νQ / |νQ|`) and `1 − λ` computed as the
//!    QSD's fall mass `ν·f` (`f` each cell's fall), never as `1 − λ`: at an
//!    MFPT of 10¹² the subtraction would keep no digit, and solving
//!    `(I − Q) m = 1` would need a matrix of condition about the MFPT; the
//!    iteration converges at the chain's mixing rate, whatever the MFPT.
//!
//! **Options for a walker like the RTW**: the input stratified in the
//! halvings of each tail's mass instead of the nodes
//! ([`ChainOptions::strata`], for a doom set that is not a clean tail);
//! a doom test that stops once the walker has left the input's ground
//! ([`ChainWalker::behind`], for falls called long after the step that
//! deals them); members weighted by their likelihood ratio
//! ([`ChainWalker::weight`], for a sample drawn from a wider law: each
//! cell's row and the one-step estimate are then weighted means); cells
//! cut as quantile bins of a learned score of the fall
//! ([`ChainOptions::by_fall`]).
//!
//! **Its error** is the discretisation's: the MFPT at `cells` and at
//! `2 × cells` cells (the same members, so no step is re-simulated) and a
//! bootstrap over each cell's members; `lo` and `hi` are the extremes of
//! the two meshes' estimates and the bootstrap's 2.5 % and 97.5 %
//! quantiles. It is not a confidence interval of the truth: the quadrature
//! (see the nodes' convergence in the rimless tests), the lookahead's
//! rule and the sample's coverage of the QSD are not in it.
//!
//! **Cost**: per member `nodes × (1 + lookahead)` steps plus, for each
//! doomed tail, `BISECTIONS + 1` doom tests; nothing grows with the MFPT.

use crate::metastable::Rng;

mod mesh;
mod quadrature;
mod score;
mod strata;
pub use mesh::kmeans;
use mesh::{effective_dimension, nearest};
pub use quadrature::{erfc, gauss_hermite, normal_cdf};
use score::FallScore;
use strata::member_step_stratified;

/// A walker for the chain: one standard-normal input per step, the step a
/// deterministic function of (state, input).
pub trait ChainWalker {
    /// The state at a step (the extended state: with the ground within reach).
    type State: Clone;
    /// The step from `state` with the input `z` (standard normal): the next
    /// state, or `None` when it fell. The same `(state, z)` gives the same
    /// result.
    fn step_with(&self, state: &Self::State, z: f64) -> Option<Self::State>;
    /// The features of the extended state on which the cells are cut (any
    /// fixed length; they are standardised over the sample).
    fn features(&self, state: &Self::State) -> Vec<f64>;
    /// The state's weight in the sample (its likelihood ratio when part of
    /// it was drawn from a wider law than the walker's): 1 by default.
    fn weight(&self, state: &Self::State) -> f64 {
        let _ = state;
        1.0
    }
    /// Whether the input of the step from `from` is behind the walker now
    /// at `now`: it has left the ground that input laid, so no later step
    /// can fall because of it and a doom test may stop. By default never:
    /// the test takes all its `lookahead` steps.
    fn behind(&self, from: &Self::State, now: &Self::State) -> bool {
        let _ = (from, now);
        false
    }
    /// Whether the estimate is no longer wanted (a Ctrl-C): read before
    /// each member's step; then the estimate returns `None`.
    fn stopped(&self) -> bool {
        false
    }
}

/// The settings of [`chain_mfpt`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChainOptions {
    /// Seed of the k-means seeding, the members' choice and the bootstrap.
    pub seed: u64,
    /// Cells of the mesh (its discretisation test also builds twice as many).
    pub cells: usize,
    /// States of the sample whose steps are taken (at most the sample's).
    pub members: usize,
    /// Gauss–Hermite nodes of a step's input.
    pub nodes: usize,
    /// Steps with the mean input after a step that must not fall for the
    /// step's input not to doom it.
    pub lookahead: usize,
    /// Bootstrap resamples of the members.
    pub bootstrap: usize,
    /// A cell of fewer members is dropped (its members go to the nearest
    /// kept cell). 1 keeps every cell. A cell of one outlying member whose
    /// steps land nearer it than any other cell keeps its mass for ever:
    /// a trap of the chain that no walker has (on the RTW at σ = 5 cm, an
    /// MFPT of 2 × 10¹² where the members' mean fall gives 132). But where
    /// the falls go through rare states, the few members there are the
    /// chain's only view of them (the rimless wheel at σ = 0.04: 1.8 × 10⁴
    /// with 5, against 1.5 × 10⁵ with 1 and in the reference).
    pub min_members: usize,
    /// Halvings of each tail's mass by which a step's input is stratified
    /// instead of by Gauss–Hermite nodes (0: the nodes). Stratum `k` of the
    /// upper tail holds the inputs whose tail mass `Φ(−z)` is in
    /// `[2^−(k+2), 2^−(k+1))`, the last every input beyond; one input is
    /// drawn in each, at a uniform quantile from the member's own seed. A
    /// doom set of any shape (a speckle of moderate inputs or a clean tail
    /// at 8 σ) is then integrated without bias, at a few inputs per
    /// standard deviation where the law's mass is.
    pub strata: usize,
    /// Cut the cells along a learned score of the fall (the members' log
    /// fall mass regressed on their features) into quantile bins, not by
    /// k-means over all the features.
    pub by_fall: bool,
}

impl Default for ChainOptions {
    fn default() -> Self {
        Self {
            seed: 0,
            cells: 100,
            members: 2000,
            nodes: 9,
            lookahead: 0,
            bootstrap: 40,
            min_members: 1,
            strata: 0,
            by_fall: false,
        }
    }
}

/// The chain's estimate and its diagnostics.
#[derive(Clone, Debug, PartialEq)]
pub struct ChainMfpt {
    /// MFPT from the QSD at `cells` cells, `1/(ν·f)`.
    pub mfpt: f64,
    /// Lower end of the discretisation's range (see the module doc).
    pub lo: f64,
    /// Upper end.
    pub hi: f64,
    /// The QSD's fall probability per step, `1/mfpt`.
    pub fall_rate: f64,
    /// The MFPT at twice the cells (the discretisation test).
    pub mfpt_fine: f64,
    /// The MFPT without the mesh: one over the members' mean fall mass (a
    /// check of the mesh: the members sample the QSD, and each one's fall
    /// mass is its exact tail).
    pub mfpt_one_step: f64,
    /// Cells of the coarse mesh (fewer than asked when the members are fewer).
    pub cells: usize,
    /// Members whose steps were taken.
    pub members: usize,
    /// Inputs of a member's step: the Gauss–Hermite nodes, or twice the strata.
    pub nodes: usize,
    /// Features' principal components that hold 95 % of the sample's
    /// (standardised) variance: the effective dimension of the cloud.
    pub dimension: usize,
    /// The features' count.
    pub features: usize,
    /// Steps taken in all (the cost).
    pub steps: u64,
}

/// The farthest input tested for a doomed tail (`Φ(−10) ≈ 7.6 × 10⁻²⁴`).
const Z_FAR: f64 = 10.0;
/// Bisections of a critical input (its error `2 Z_FAR / 2²⁰`, a relative
/// error of a tail at `z` about `z` times that).
const BISECTIONS: usize = 20;

/// A sample of the QSD: a Fleming–Viot cloud of `replicas` walkers from
/// `start`, each input drawn from N(0, 1); a walker that falls restarts as
/// a copy of a survivor; after `burn_in` steps the cloud's states at each of
/// `sample_steps` steps are kept. `None` if the walker stopped it.
pub fn qsd_cloud<W: ChainWalker>(
    walker: &W,
    start: &W::State,
    replicas: usize,
    burn_in: usize,
    sample_steps: usize,
    rng: &mut Rng,
    steps: &mut u64,
) -> Option<Vec<W::State>> {
    let mut cloud = vec![start.clone(); replicas];
    let mut sample = Vec::with_capacity(replicas * sample_steps);
    for i in 0..burn_in + sample_steps {
        if walker.stopped() {
            return None;
        }
        *steps += cloud.len() as u64;
        let next: Vec<Option<W::State>> = cloud
            .iter()
            .map(|s| walker.step_with(s, rng.normal()))
            .collect();
        let alive: Vec<usize> = (0..next.len()).filter(|&j| next[j].is_some()).collect();
        cloud = next
            .iter()
            .map(|s| match s {
                Some(s) => s.clone(),
                None if alive.is_empty() => start.clone(),
                None => next[alive[rng.below(alive.len())]].clone().unwrap(),
            })
            .collect();
        if i >= burn_in {
            sample.extend(cloud.iter().cloned());
        }
    }
    Some(sample)
}

/// What one member's step does: where each surviving node lands (its
/// weight, the landing state's standardised features) and the mass that
/// falls.
struct Step {
    lands: Vec<(f64, Vec<f64>)>,
    fall: f64,
}

/// The next state of `s` with input `z`, `None` if it falls or the
/// `lookahead` steps after it with input 0 do.
fn undoomed<W: ChainWalker>(
    w: &W,
    s: &W::State,
    z: f64,
    lookahead: usize,
    steps: &mut u64,
) -> Option<W::State> {
    *steps += 1;
    let next = w.step_with(s, z)?;
    let mut t = next.clone();
    for _ in 0..lookahead {
        if w.behind(s, &t) {
            break;
        }
        *steps += 1;
        t = w.step_with(&t, 0.0)?;
    }
    Some(next)
}

/// Whether `s` survives `lookahead` steps with the mean input (0), or
/// until it has left the ground it has laid ([`ChainWalker::behind`]).
fn viable_state<W: ChainWalker>(w: &W, s: &W::State, lookahead: usize, steps: &mut u64) -> bool {
    let mut t = s.clone();
    for _ in 0..lookahead {
        if w.behind(s, &t) {
            break;
        }
        *steps += 1;
        match w.step_with(&t, 0.0) {
            Some(next) => t = next,
            None => return false,
        }
    }
    true
}

/// The critical input between `doomed` (dooms) and `alive` (does not).
fn critical<W: ChainWalker>(
    w: &W,
    s: &W::State,
    mut doomed: f64,
    mut alive: f64,
    lookahead: usize,
    steps: &mut u64,
) -> f64 {
    for _ in 0..BISECTIONS {
        let mid = 0.5 * (doomed + alive);
        if undoomed(w, s, mid, lookahead, steps).is_some() {
            alive = mid;
        } else {
            doomed = mid;
        }
    }
    0.5 * (doomed + alive)
}

/// One member's step, its input integrated over N(0, 1) (module doc, 2).
fn member_step<W: ChainWalker>(
    w: &W,
    s: &W::State,
    nodes: &[(f64, f64)],
    lookahead: usize,
    scale: &Scale,
    steps: &mut u64,
) -> Step {
    let at: Vec<Option<W::State>> = nodes
        .iter()
        .map(|&(z, _)| undoomed(w, s, z, lookahead, steps))
        .collect();
    let first_alive = at.iter().position(Option::is_some);
    let last_alive = at.iter().rposition(Option::is_some);
    let (Some(first), Some(last)) = (first_alive, last_alive) else {
        return Step {
            lands: Vec::new(),
            fall: 1.0,
        };
    };
    // The doomed tails, each beyond its critical input.
    let z_lo = if undoomed(w, s, -Z_FAR, lookahead, steps).is_none() {
        critical(w, s, -Z_FAR, nodes[first].0, lookahead, steps)
    } else {
        f64::NEG_INFINITY
    };
    let z_hi = if undoomed(w, s, Z_FAR, lookahead, steps).is_none() {
        critical(w, s, Z_FAR, nodes[last].0, lookahead, steps)
    } else {
        f64::INFINITY
    };
    let tails = normal_cdf(z_lo) + normal_cdf(-z_hi);
    let inside: Vec<usize> = (0..nodes.len())
        .filter(|&i| nodes[i].0 > z_lo && nodes[i].0 < z_hi)
        .collect();
    let weight: f64 = inside.iter().map(|&i| nodes[i].1).sum();
    let rescale = (1.0 - tails) / weight;
    let mut lands = Vec::with_capacity(inside.len());
    let mut fall = tails;
    for i in inside {
        let m = nodes[i].1 * rescale;
        match &at[i] {
            Some(next) => lands.push((m, scale.apply(&w.features(next)))),
            None => fall += m,
        }
    }
    Step { lands, fall }
}

/// The features' standardisation over the sample (dimensions that do not
/// vary are dropped).
struct Scale {
    mean: Vec<f64>,
    sd: Vec<f64>,
    keep: Vec<usize>,
}

impl Scale {
    fn of(sample: &[Vec<f64>]) -> Self {
        let d = sample[0].len();
        let n = sample.len() as f64;
        let mean: Vec<f64> = (0..d)
            .map(|k| sample.iter().map(|f| f[k]).sum::<f64>() / n)
            .collect();
        let sd: Vec<f64> = (0..d)
            .map(|k| (sample.iter().map(|f| (f[k] - mean[k]).powi(2)).sum::<f64>() / n).sqrt())
            .collect();
        let keep = (0..d)
            .filter(|&k| sd[k] > 0.0 && sd[k].is_finite())
            .collect();
        Self { mean, sd, keep }
    }

    fn apply(&self, f: &[f64]) -> Vec<f64> {
        self.keep
            .iter()
            .map(|&k| (f[k] - self.mean[k]) / self.sd[k])
            .collect()
    }
}

/// The cell of a point of the standardised features.
type CellOf<'a> = Box<dyn Fn(&[f64]) -> usize + 'a>;

/// A member's step on a mesh: the mass landing in each cell, the fall, and
/// the member's weight.
type Mapped = (Vec<(usize, f64)>, f64, f64);

/// The QSD's fall rate `ν·f` of the chain whose cell `a` is the mean of the
/// steps `rows[a]` (each a member's step, its landings already mapped to
/// cells).
fn qsd_fall_rate(rows: &[Vec<&Mapped>]) -> f64 {
    let n = rows.len();
    // Each cell's row, sparse, and its fall.
    let mut q: Vec<Vec<(usize, f64)>> = Vec::with_capacity(n);
    let mut f = vec![0.0; n];
    for (a, members) in rows.iter().enumerate() {
        let mut row = vec![0.0; n];
        let m: f64 = members.iter().map(|t| t.2).sum();
        for (lands, fall, wt) in members {
            for &(b, w) in lands {
                row[b] += w * wt / m;
            }
            f[a] += fall * wt / m;
        }
        q.push(row.into_iter().enumerate().filter(|r| r.1 > 0.0).collect());
    }
    let mut v = vec![1.0 / n as f64; n];
    for _ in 0..100_000 {
        let mut w = vec![0.0; n];
        for (vi, row) in v.iter().zip(&q) {
            for &(b, x) in row {
                w[b] += vi * x;
            }
        }
        let s: f64 = w.iter().sum();
        if s <= 0.0 {
            return 1.0;
        }
        let change: f64 = w.iter().zip(&v).map(|(a, b)| (a / s - b).abs()).sum();
        v = w.into_iter().map(|x| x / s).collect();
        if change < 1e-12 {
            break;
        }
    }
    v.iter().zip(&f).map(|(a, b)| a * b).sum()
}

/// The chain's MFPT from the QSD that `sample` samples (see the module
/// doc); `None` when the walker stopped it part way.
pub fn chain_mfpt<W: ChainWalker>(
    walker: &W,
    sample: &[W::State],
    o: &ChainOptions,
) -> Option<ChainMfpt> {
    assert!(
        !sample.is_empty() && o.cells >= 1 && o.members >= 1 && o.nodes >= 1,
        "chain_mfpt: a sample, and at least one cell, member and node"
    );
    let mut rng = Rng::new(o.seed ^ 0x6368_6169_6e00);
    rng.next_u64();
    // The members: an even pick through the sample (which is in time
    // order) of its viable states, those that survive `lookahead` steps
    // with the mean input. Every landing is viable (that is the lookahead's
    // test), so the cells are meshed over viable states: a state whose
    // fall is already laid counts as fallen at the step that laid it, not
    // again in the cell it would land in.
    let mut steps = 0u64;
    let mut viable: Vec<&W::State> = Vec::with_capacity(sample.len());
    for s in sample {
        if walker.stopped() {
            return None;
        }
        if viable_state(walker, s, o.lookahead, &mut steps) {
            viable.push(s);
        }
    }
    if viable.is_empty() {
        viable = sample.iter().collect();
    }
    let m = o.members.min(viable.len());
    let members: Vec<&W::State> = (0..m).map(|i| viable[i * viable.len() / m]).collect();
    let raw: Vec<Vec<f64>> = members.iter().map(|s| walker.features(s)).collect();
    let scale = Scale::of(&raw);
    let points: Vec<Vec<f64>> = raw.iter().map(|f| scale.apply(f)).collect();
    let nodes = gauss_hermite(o.nodes);
    let mut taken = Vec::with_capacity(m);
    for s in &members {
        if walker.stopped() {
            return None;
        }
        taken.push(if o.strata > 0 {
            let seed = o.seed ^ (0x5742_0000 + taken.len() as u64);
            member_step_stratified(walker, s, o.strata, o.lookahead, seed, &scale, &mut steps)
        } else {
            member_step(walker, s, &nodes, o.lookahead, &scale, &mut steps)
        });
    }
    // The one-step estimate: the members sample the QSD, so the mean of
    // their exact fall masses is its fall rate, without the mesh (and
    // without the paths of several moderate inputs that the chain sees).
    let weights: Vec<f64> = members.iter().map(|s| walker.weight(s)).collect();
    let one_step = weights.iter().sum::<f64>()
        / taken
            .iter()
            .zip(&weights)
            .map(|(t, w)| t.fall * w)
            .sum::<f64>();
    // The cells by the members' learned fall (a ridge regression of the log
    // of each member's fall mass on its features), when asked.
    let fall_score = o
        .by_fall
        .then(|| FallScore::fit(&points, &taken.iter().map(|t| t.fall).collect::<Vec<_>>()));
    // The MFPT on a mesh of `k` cells, and its bootstrap over members.
    let mut mesh = |k: usize, boot: usize| {
        let cell_of: CellOf<'_> = match &fall_score {
            Some(score) => {
                let mut s: Vec<f64> = points.iter().map(|p| score.at(p)).collect();
                s.sort_by(f64::total_cmp);
                let k = k.min(s.len());
                // The bins' upper edges: quantiles of the members' scores.
                let edges: Vec<f64> = (1..k).map(|i| s[i * s.len() / k]).collect();
                Box::new(move |p: &[f64]| {
                    let v = score.at(p);
                    edges.partition_point(|e| *e <= v)
                })
            }
            None => {
                let centres = kmeans(&points, k, o.min_members, &mut rng);
                Box::new(move |p: &[f64]| nearest(&centres, p))
            }
        };
        let cell: Vec<usize> = points.iter().map(|p| cell_of(p)).collect();
        let mapped: Vec<Mapped> = taken
            .iter()
            .zip(&weights)
            .map(|(t, wt)| {
                (
                    t.lands.iter().map(|(w, f)| (cell_of(f), *w)).collect(),
                    t.fall,
                    *wt,
                )
            })
            .collect();
        let cells = cell.iter().max().map_or(1, |c| c + 1);
        let mut by_cell: Vec<Vec<usize>> = vec![Vec::new(); cells];
        for (i, c) in cell.iter().enumerate() {
            by_cell[*c].push(i);
        }
        let rate = |pick: &mut dyn FnMut(&[usize]) -> Vec<usize>| {
            let rows: Vec<Vec<&Mapped>> = by_cell
                .iter()
                .map(|ms| pick(ms).into_iter().map(|i| &mapped[i]).collect())
                .collect();
            qsd_fall_rate(&rows)
        };
        let p = rate(&mut |ms| ms.to_vec());
        let mut boots = Vec::with_capacity(boot);
        for b in 0..boot {
            let mut r = Rng::new(o.seed ^ (0xb007 + b as u64));
            r.next_u64();
            let q = rate(&mut |ms| (0..ms.len()).map(|_| ms[r.below(ms.len())]).collect());
            boots.push(1.0 / q);
        }
        (1.0 / p, cells, boots)
    };
    if walker.stopped() {
        return None;
    }
    let (coarse, cells, mut boots) = mesh(o.cells, o.bootstrap);
    if walker.stopped() {
        return None;
    }
    let (fine, _, _) = mesh(2 * o.cells, 0);
    boots.sort_by(f64::total_cmp);
    let quantile = |q: f64| {
        if boots.is_empty() {
            coarse
        } else {
            boots[((q * boots.len() as f64) as usize).min(boots.len() - 1)]
        }
    };
    Some(ChainMfpt {
        mfpt: coarse,
        lo: coarse.min(fine).min(quantile(0.025)),
        hi: coarse.max(fine).max(quantile(0.975)),
        fall_rate: 1.0 / coarse,
        mfpt_fine: fine,
        mfpt_one_step: one_step,
        cells,
        members: m,
        nodes: if o.strata > 0 { 2 * o.strata } else { o.nodes },
        dimension: effective_dimension(&points),
        features: points[0].len(),
        steps,
    })
}
