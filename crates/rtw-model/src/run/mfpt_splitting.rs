//! The mean first-passage time of a stable gait on a rough slope by
//! adaptive multilevel splitting ([`hybrid_ode::splitting`]) with a score
//! learned where falls are cheap: the second MFPT estimator, whose cost
//! grows as `log(MFPT)` where counting's grows as the MFPT.
//!
//! **The walker** is [`crate::run::mfpt`]'s: the settled gait on the rough
//! slope of `robustness.sigma`, a step a run of `1 / f_w_newfoot` seconds
//! before which the patches more than a rod length beyond the furthest tip
//! are drawn afresh, a fall a failed run or `stall_time` without a
//! touchdown.
//!
//! **The score sees the ground ahead.** A fall is decided by patches already
//! laid under and just ahead of the walker, which its own state does not
//! show (CHANGELOG.md, "The MFPT's estimators tried and dropped"). The
//! score is a function of the *extended* state: the section state and the
//! kept patches within reach ([`features`]): the rise from the patch under
//! the furthest tip to the next one (the only patch ahead that is kept),
//! the rise from the patch under the centre of mass to the one under the
//! furthest tip, the furthest tip's distance to the next edge, their squares
//! and products, the centre of mass's velocity relative to the settled
//! gait's, and its height above the ground under it.
//!
//! **The score is learned** (Lucente et al., J. Stat. Mech. 2022; trained at
//! higher noise and used at lower, Wang, Castellana and Dijkstra, NPG 2021):
//! plain walks from the settled gait at `train_sigma` (5 cm by default,
//! where Fig. 7(a) falls every ~150 steps), every state labelled by whether
//! the walk fell within `horizon` steps of it; a logistic regression on the
//! standardized features ([`hybrid_ode::logistic`]) gives `P(fall within
//! horizon steps | extended state)`, whose log-odds is the score. Its AUC
//! is measured on the held-out walks (every fourth). The splitting is
//! unbiased for any score; the score sets only its variance.
//!
//! **Cost**: the training walks (`train_walks` walks of at most
//! `train_max_steps` steps) and the splitting's batches, every step counted.

use crate::options::{RobustnessOptions, TerrainOptions};
use crate::outcome::MeanFirstPassage;
use crate::run::mfpt::{self, com_velocity, furthest_tip};
use crate::run::settled::SettledGait;
use hybrid_ode::Work;
use hybrid_ode::logistic::{Logistic, auc};
use hybrid_ode::metastable::{Rng, Walker};
use hybrid_ode::splitting::{Split, SplitOptions, split};

/// The settings of the RTW's splitting: the score's training and the
/// splitting's own.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SplitSettings {
    /// The roughness the score is learned at (m); the target's when larger.
    pub train_sigma: f64,
    /// Training walks from the settled gait.
    pub train_walks: usize,
    /// A training walk stops after this many steps.
    pub train_max_steps: usize,
    /// A state's label: the walk fell within this many steps of it.
    pub horizon: usize,
    /// The logistic fit's ridge.
    pub ridge: f64,
    /// The score is the learned log-odds averaged over the steps, each
    /// step's weighing this much (1: the log-odds of the state alone).
    pub smoothing: f64,
    /// Plain walks at the target roughness (of at most `train_max_steps`
    /// steps) on which the score's AUC is measured; 0: none.
    pub target_walks: usize,
    /// The splitting's settings (its seed is `terrain.seed`'s).
    pub split: SplitOptions,
}

/// By default the score learns from 400 walks at 5 cm (~60 000 steps, a few
/// seconds) and averages the log-odds with weight 0.3 a step (spikes of
/// a single bad patch smoothed, the tens of steps of a walk's decline before
/// its fall kept: measured at 3 cm, the unsmoothed score's quantile
/// among all states is 0.99 in the 3 steps before a fall, 0.87 20 and 40
/// steps before, 0.5 by 80), and the splitting runs 8 batches of 400
/// excursions from the better half of a cloud of 32 walkers (20 steps of
/// burn-in, 20 sampled).
pub const SPLIT_SETTINGS: SplitSettings = SplitSettings {
    train_sigma: 0.05,
    train_walks: 400,
    train_max_steps: 2000,
    horizon: 3,
    ridge: 1e-3,
    smoothing: 0.3,
    target_walks: 0,
    split: SplitOptions {
        seed: 0,
        batches: 8,
        replicas: 400,
        kill: 1,
        cloud: 32,
        burn_in: 20,
        sample_steps: 20,
        quantile: 0.5,
        max_excursion: 200,
        max_iterations: 200_000,
    },
};

/// The splitting's MFPT of a gait and what it measured on the way.
#[derive(Clone, Debug, PartialEq)]
pub struct SplitMfpt {
    /// Expected steps to fall from the settled gait meeting the rough slope.
    pub mfpt: f64,
    /// Lower end of its 95 % interval.
    pub mfpt_lo: f64,
    /// Upper end (infinite when the interval of `p` reaches 0).
    pub mfpt_hi: f64,
    /// The per-step fall probability of the regime, `1 / MFPT_A`.
    pub fall_rate: f64,
    /// Steps simulated in all: the training walks and the splitting.
    pub steps: u64,
    /// The splitting's estimate, with each batch's diagnostics.
    pub split: Split,
    /// The learned score.
    pub score: Logistic,
    /// The score's AUC on the held-out training walks.
    pub train_auc: f64,
    /// The training walks' falls, and their steps.
    pub train_falls: usize,
    /// Steps of the training walks.
    pub train_steps: u64,
    /// The score's AUC on plain walks at the target roughness, their falls
    /// and steps (when [`SplitSettings::target_walks`] asked for them).
    pub target_auc: Option<(f64, usize, u64)>,
    /// On those walks, the score's mean quantile among all their states at
    /// each of [`LAGS`] steps before a fall (0.5: no sign of the fall).
    pub target_lags: Vec<(usize, f64)>,
}

impl SplitMfpt {
    /// The estimate in the columns every MFPT method writes (`mfpt`,
    /// `mfpt_lo`, `mfpt_hi`, `fall_rate`), its diagnostics left out.
    pub(crate) fn mean_first_passage(&self) -> MeanFirstPassage {
        MeanFirstPassage {
            mfpt: self.mfpt,
            lo: self.mfpt_lo,
            hi: self.mfpt_hi,
            fall_rate: self.fall_rate,
            steps: self.steps,
        }
    }
}

/// The walker's state at a step: the counted estimator's
/// ([`mfpt::State`]), and the splitting's score there.
#[derive(Clone)]
pub(crate) struct State {
    walker: mfpt::State,
    /// The learned log-odds averaged over the steps so far (exponentially,
    /// [`SplitSettings::smoothing`]): the splitting's score.
    risk: f64,
}

/// The number of [`features`].
pub const FEATURES: usize = 11;

/// The extended state's features (see the module doc), lengths in rod
/// lengths `l` and velocities relative to the settled gait's, in units of
/// its mean speed.
pub(crate) fn features(
    st: &mfpt::State,
    v_settled: [f64; 2],
    speed: f64,
    l: f64,
) -> [f64; FEATURES] {
    let t = &st.rtw.terrain;
    let front = furthest_tip(&st.rtw, &st.y);
    let com = st.rtw.centre_of_mass(&st.y);
    let h_front = t.ground(front);
    // The next patch's first point: the edge after the front (the patches
    // are `t.patch` long from `t.step_at`).
    let k = ((front - t.step_at) / t.patch).floor().max(-1.0) + 1.0;
    let edge = t.step_at + k * t.patch;
    let h_next = t.ground(edge + 1e-9 * l);
    let ahead = (h_next - h_front) / l;
    let under = (h_front - t.ground(com[0])) / l;
    let gap = (edge - front) / t.patch;
    let v = com_velocity(&st.rtw, &st.y);
    let height = (com[1] - t.ground(com[0])) / l;
    [
        ahead,
        under,
        gap,
        ahead * ahead,
        under * under,
        ahead * gap,
        ahead * under,
        (v[0] - v_settled[0]) / speed,
        (v[1] - v_settled[1]) / speed,
        height,
        gap * gap,
    ]
}

/// The settled gait as a walker on the rough slope (the counted
/// estimator's, [`mfpt::RtwWalker`]), scored by `score`.
struct RtwWalker<'a, 'b> {
    walker: mfpt::RtwWalker<'a, 'b>,
    score: Option<Logistic>,
    /// The weight of each step's log-odds in the score's average.
    smoothing: f64,
}

impl<'a, 'b> RtwWalker<'a, 'b> {
    /// The settled gait `s` as a walker, its score not learned yet.
    fn new(s: &'a SettledGait<'b>, smoothing: f64) -> Self {
        RtwWalker {
            walker: mfpt::RtwWalker::new(s),
            score: None,
            smoothing,
        }
    }

    fn features(&self, st: &State) -> [f64; FEATURES] {
        let w = &self.walker;
        features(&st.walker, w.v_settled, w.speed, w.s.phys.length)
    }

    /// The walker at the settled gait meeting the rough slope of `sigma`.
    fn start(&self, sigma: f64, terrain: TerrainOptions) -> State {
        State {
            walker: self.walker.start(sigma, terrain),
            risk: f64::NAN,
        }
    }

    /// What the walker has cost so far.
    fn into_work(self) -> Work {
        self.walker.work.into_inner()
    }
}

impl Walker for RtwWalker<'_, '_> {
    type State = State;

    fn step(&self, st: &State, rng: &mut Rng) -> Option<State> {
        let mut next = State {
            walker: self
                .walker
                .step_branched(&st.walker, rng.next_u64(), f64::NAN)?,
            risk: 0.0,
        };
        next.risk = match &self.score {
            None => 0.0,
            Some(m) => {
                let now = m.logit(&self.features(&next));
                if st.risk.is_nan() {
                    now
                } else {
                    st.risk + self.smoothing * (now - st.risk)
                }
            }
        };
        Some(next)
    }

    /// The learned log-odds of a fall within the horizon, averaged over
    /// the steps so far (0 before the score is learned).
    fn score(&self, st: &State) -> f64 {
        if st.risk.is_nan() { 0.0 } else { st.risk }
    }

    fn stopped(&self) -> bool {
        crate::cancel::requested()
    }
}

/// Plain walks from a start: every state's features, the steps from it to
/// the walk's fall (none for a walk that did not fall), the walk it came
/// from; the falls and the steps.
struct Walks {
    x: Vec<Vec<f64>>,
    to_fall: Vec<Option<usize>>,
    walk_of: Vec<usize>,
    falls: usize,
    steps: u64,
}

impl Walks {
    /// Whether each state's walk fell within `horizon` steps of it.
    fn labels(&self, horizon: usize) -> Vec<bool> {
        self.to_fall
            .iter()
            .map(|k| k.is_some_and(|k| k <= horizon))
            .collect()
    }
}

/// `walks` plain walks from `start` of at most `max_steps` steps each;
/// `None` when stopped.
fn walks(
    w: &RtwWalker<'_, '_>,
    start: &State,
    walks: usize,
    max_steps: usize,
    rng: &mut Rng,
) -> Option<Walks> {
    let mut out = Walks {
        x: Vec::new(),
        to_fall: Vec::new(),
        walk_of: Vec::new(),
        falls: 0,
        steps: 0,
    };
    for walk in 0..walks {
        let mut st = start.clone();
        let mut rows = Vec::new();
        let mut fell = false;
        for _ in 0..max_steps {
            if w.stopped() {
                return None;
            }
            out.steps += 1;
            match w.step(&st, rng) {
                Some(next) => {
                    rows.push(w.features(&next).to_vec());
                    st = next;
                }
                None => {
                    fell = true;
                    break;
                }
            }
        }
        out.falls += usize::from(fell);
        let n = rows.len();
        for (i, r) in rows.into_iter().enumerate() {
            // Row i is the state after step i + 1; the fall is step n + 1.
            out.to_fall.push(fell.then_some(n - i));
            out.x.push(r);
            out.walk_of.push(walk);
        }
    }
    Some(out)
}

/// The lags before a fall at which [`SplitMfpt::target_lags`] places the
/// score.
pub const LAGS: [usize; 8] = [1, 2, 3, 5, 10, 20, 40, 80];

/// The MFPT of the settled gait `s` on the rough slope of `r.sigma` with
/// `terrain`'s seed and patch length, by splitting with the learned score
/// (see the module doc), with [`SPLIT_SETTINGS`] and `r.mfpt_batches`
/// batches: the inputs of [`crate::run::mfpt::mean_first_passage`]. `None`
/// when the stop flag ended it part way or the score could not be fitted.
pub(crate) fn mean_first_passage_splitting(
    s: &SettledGait<'_>,
    r: &RobustnessOptions,
    terrain: TerrainOptions,
    work: &mut Work,
) -> Option<SplitMfpt> {
    let set = SplitSettings {
        split: SplitOptions {
            batches: (r.mfpt_batches as usize).max(2),
            ..SPLIT_SETTINGS.split
        },
        ..SPLIT_SETTINGS
    };
    split_with(s, r.sigma, terrain, &set, work)
}

/// [`mean_first_passage_splitting`] with its settings spelled out.
pub(crate) fn split_with(
    s: &SettledGait<'_>,
    sigma: f64,
    terrain: TerrainOptions,
    set: &SplitSettings,
    work: &mut Work,
) -> Option<SplitMfpt> {
    let mut w = RtwWalker::new(s, set.smoothing);
    // Learn the score where falls are cheap.
    let mut rng = Rng::new(Rng::new(terrain.seed ^ 0x0074_7261_696e).next_u64());
    let train_start = w.start(set.train_sigma.max(sigma), terrain);
    let trained = walks(
        &w,
        &train_start,
        set.train_walks,
        set.train_max_steps,
        &mut rng,
    );
    let Some(trained) = trained else {
        *work += w.into_work();
        return None;
    };
    let (x, y, walk_of) = (&trained.x, trained.labels(set.horizon), &trained.walk_of);
    let (train_falls, train_steps) = (trained.falls, trained.steps);
    let held = |i: &usize| walk_of[*i] % 4 == 3;
    let pick = |keep: bool| -> (Vec<Vec<f64>>, Vec<bool>) {
        (0..x.len())
            .filter(|i| held(i) != keep)
            .map(|i| (x[i].clone(), y[i]))
            .unzip()
    };
    let (fit_x, fit_y) = pick(true);
    let (held_x, held_y) = pick(false);
    let Ok(model) = Logistic::fit(&fit_x, &fit_y, set.ridge) else {
        *work += w.into_work();
        return None;
    };
    let held_scores: Vec<f64> = held_x.iter().map(|r| model.logit(r)).collect();
    let train_auc = auc(&held_scores, &held_y);
    w.score = Some(model.clone());
    // The splitting at the target roughness.
    let start = w.start(sigma, terrain);
    let (mut target_auc, mut target_lags) = (None, Vec::new());
    if set.target_walks > 0 {
        let Some(t) = walks(&w, &start, set.target_walks, set.train_max_steps, &mut rng) else {
            *work += w.into_work();
            return None;
        };
        let scores: Vec<f64> = t.x.iter().map(|r| model.logit(r)).collect();
        target_auc = Some((auc(&scores, &t.labels(set.horizon)), t.falls, t.steps));
        let mut sorted = scores.clone();
        sorted.sort_by(f64::total_cmp);
        let quantile = |v: f64| sorted.partition_point(|&s| s < v) as f64 / sorted.len() as f64;
        for lag in LAGS {
            let at: Vec<f64> = (0..scores.len())
                .filter(|&i| t.to_fall[i] == Some(lag))
                .map(|i| quantile(scores[i]))
                .collect();
            if !at.is_empty() {
                target_lags.push((lag, at.iter().sum::<f64>() / at.len() as f64));
            }
        }
    }
    let out = split(
        &w,
        &start,
        &SplitOptions {
            seed: terrain.seed,
            ..set.split
        },
    );
    *work += w.into_work();
    let out = out?;
    Some(SplitMfpt {
        mfpt: out.mfpt,
        mfpt_lo: out.lo,
        mfpt_hi: out.hi,
        fall_rate: out.fall_rate,
        steps: out.steps + train_steps,
        split: out,
        score: model,
        train_auc,
        train_falls,
        train_steps,
        target_auc,
        target_lags,
    })
}

/// Runs `f` on the settled gait of the stable flat run of `params` under
/// `options` (`None` when that run is not a stable gait).
#[cfg(test)]
pub(crate) fn with_settled<T>(
    params: &crate::params::Params,
    options: &crate::options::Options,
    f: impl FnOnce(&SettledGait<'_>) -> T,
) -> Option<T> {
    let mut flat_options = *options;
    flat_options.robustness = RobustnessOptions::default();
    crate::run::recorder::with_end_state(params, &flat_options, |phys, rtw, y, flat| {
        flat.label.is_stable().then(|| {
            f(&crate::run::settled::settled(
                params, options, phys, rtw, y, flat,
            ))
        })
    })
    .flatten()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::options::Options;

    fn env<T: std::str::FromStr>(name: &str, default: T) -> T {
        std::env::var(name)
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(default)
    }

    /// The features see the kept ground and only it: redrawing the patches
    /// beyond reach (what the next step does) leaves them as they were,
    /// while the walker on another draw of the kept patches sees its own.
    #[test]
    fn the_features_read_the_kept_patches_and_no_others() {
        let o = Options::default();
        with_settled(&crate::params::Params::fig7a(), &o, |s| {
            let set = SPLIT_SETTINGS;
            let w = RtwWalker::new(s, set.smoothing);
            let mut rng = Rng::new(1);
            let mut st = w.start(0.03, TerrainOptions::default());
            for _ in 0..5 {
                st = w.step(&st, &mut rng).expect("five steps at 3 cm");
            }
            let f = w.features(&st);
            let reach = furthest_tip(&st.walker.rtw, &st.walker.y) + s.phys.length;
            let mut redrawn = st.clone();
            redrawn
                .walker
                .rtw
                .branch_terrain_beyond(reach, 12345, &redrawn.walker.y);
            assert_eq!(f, w.features(&redrawn));
            // The same walker on other kept patches: the rise ahead differs.
            let mut other = st.clone();
            let front = furthest_tip(&st.walker.rtw, &st.walker.y);
            other.walker.rtw.branch_terrain_beyond(
                front - 2.0 * s.phys.length,
                999,
                &other.walker.y,
            );
            assert_ne!(f[0], w.features(&other)[0], "{f:?}");
            assert!(f.iter().all(|v| v.is_finite()), "{f:?}");
        })
        .expect("Fig. 7(a) is a stable gait");
    }

    /// Where falls are frequent (σ = 5 cm, ~150 steps) the splitting's
    /// interval, by the entry the option will call (its default settings,
    /// `robustness.mfpt_batches` batches), holds plain Monte Carlo to the
    /// fall from the same start: the training walks, 400 walks each run to
    /// its fall, independent of the splitting's randomness (their mean 143
    /// steps; with 8 batches the splitting gave 139 [98, 216]). The score's held-out AUC is well above chance, and every step
    /// is counted.
    #[test]
    fn the_splitting_holds_plain_monte_carlo_where_falls_are_frequent() {
        let r = RobustnessOptions {
            sigma: 0.05,
            mfpt_batches: 6,
            ..RobustnessOptions::default()
        };
        let set = SPLIT_SETTINGS;
        let m = with_settled(&crate::params::Params::fig7a(), &Options::default(), |s| {
            mean_first_passage_splitting(s, &r, TerrainOptions::default(), &mut Work::default())
        })
        .flatten()
        .unwrap();
        assert_eq!(m.split.batches.len(), 6);
        assert_eq!(m.train_falls, set.train_walks, "every training walk fell");
        let monte_carlo = m.train_steps as f64 / set.train_walks as f64;
        assert!(
            m.mfpt_lo <= monte_carlo && monte_carlo <= m.mfpt_hi,
            "Monte Carlo {monte_carlo} vs {} [{}, {}]",
            m.mfpt,
            m.mfpt_lo,
            m.mfpt_hi
        );
        assert!(m.mfpt_hi < 5.0 * m.mfpt_lo, "{m:?}");
        assert!(m.train_auc > 0.75, "{}", m.train_auc);
        assert_eq!(m.steps, m.split.steps + m.train_steps);
    }

    /// The command-line entry of `scripts/mfpt_split_check.sh`: the
    /// splitting's MFPT of Fig. 7(a) at `RTW_SPLIT_SIGMA` (m), with
    /// `RTW_SPLIT_BATCHES`, `RTW_SPLIT_REPLICAS`, `RTW_SPLIT_SEED` (and the
    /// other `RTW_SPLIT_*` below, each a field of [`SplitSettings`]), printed
    /// as one `key=value` line per quantity on stderr.
    #[test]
    #[ignore]
    fn mfpt_split_fig7a() {
        let sigma: f64 = env("RTW_SPLIT_SIGMA", 0.03);
        let set = SplitSettings {
            split: SplitOptions {
                batches: env("RTW_SPLIT_BATCHES", SPLIT_SETTINGS.split.batches),
                replicas: env("RTW_SPLIT_REPLICAS", SPLIT_SETTINGS.split.replicas),
                quantile: env("RTW_SPLIT_QUANTILE", SPLIT_SETTINGS.split.quantile),
                cloud: env("RTW_SPLIT_CLOUD", SPLIT_SETTINGS.split.cloud),
                sample_steps: env("RTW_SPLIT_SAMPLE_STEPS", SPLIT_SETTINGS.split.sample_steps),
                ..SPLIT_SETTINGS.split
            },
            train_walks: env("RTW_SPLIT_TRAIN_WALKS", SPLIT_SETTINGS.train_walks),
            train_sigma: env("RTW_SPLIT_TRAIN_SIGMA", SPLIT_SETTINGS.train_sigma),
            horizon: env("RTW_SPLIT_HORIZON", SPLIT_SETTINGS.horizon),
            smoothing: env("RTW_SPLIT_SMOOTHING", SPLIT_SETTINGS.smoothing),
            target_walks: env("RTW_SPLIT_TARGET_WALKS", 0),
            train_max_steps: env("RTW_SPLIT_MAX_STEPS", SPLIT_SETTINGS.train_max_steps),
            ..SPLIT_SETTINGS
        };
        let terrain = TerrainOptions {
            seed: env("RTW_SPLIT_SEED", 0u64),
            ..TerrainOptions::default()
        };
        let t0 = std::time::Instant::now();
        let m = with_settled(&crate::params::Params::fig7a(), &Options::default(), |s| {
            split_with(s, sigma, terrain, &set, &mut Work::default())
        })
        .flatten()
        .expect("Fig. 7(a) is a stable gait and the estimate finished");
        let secs = t0.elapsed().as_secs_f64();
        let b = &m.split.batches;
        eprintln!("sigma={sigma}");
        eprintln!("mfpt={:.6e}", m.mfpt);
        eprintln!("mfpt_lo={:.6e}", m.mfpt_lo);
        eprintln!("mfpt_hi={:.6e}", m.mfpt_hi);
        eprintln!("p={:.6e}", m.split.p);
        eprintln!("p_lo={:.6e}", m.split.p_interval.0);
        eprintln!("p_hi={:.6e}", m.split.p_interval.1);
        eprintln!("returned_steps={:.4}", m.split.returned_steps);
        eprintln!("fall_steps={:.4}", m.split.fall_steps);
        eprintln!("steps={}", m.steps);
        eprintln!("train_steps={}", m.train_steps);
        eprintln!("train_falls={}", m.train_falls);
        eprintln!("train_auc={:.4}", m.train_auc);
        eprintln!("wall_s={secs:.1}");
        if let Some((a, falls, steps)) = m.target_auc {
            eprintln!("target_auc={a:.4}");
            eprintln!("target_falls={falls}");
            eprintln!("target_steps={steps}");
            eprintln!("target_lags={:?}", m.target_lags);
        }
        eprintln!("batch_p={:?}", b.iter().map(|b| b.p).collect::<Vec<_>>());
        eprintln!(
            "batch_ancestors={:?}",
            b.iter().map(|b| b.ancestors).collect::<Vec<_>>()
        );
        eprintln!(
            "batch_iterations={:?}",
            b.iter().map(|b| b.iterations()).collect::<Vec<_>>()
        );
        eprintln!(
            "batch_fell={:?}",
            b.iter().map(|b| b.fell).collect::<Vec<_>>()
        );
        // How the genealogy narrowed: the distinct ancestors after a
        // quarter, half, three quarters and all of each batch's
        // iterations, and the levels there (A's level first).
        let at = |b: &hybrid_ode::splitting::SplitBatch, f: usize| {
            let n = b.ancestors_by_iteration.len();
            let i = (f * n / 4).clamp(1, n.max(1)) - 1;
            (
                b.ancestors_by_iteration.get(i).copied().unwrap_or(0),
                b.levels.get(i).copied().unwrap_or(f64::NAN),
            )
        };
        eprintln!(
            "batch_ancestors_path={}",
            b.iter()
                .map(|b| format!("{:?}", (1..=4).map(|f| at(b, f).0).collect::<Vec<_>>()))
                .collect::<Vec<_>>()
                .join(" ")
        );
        eprintln!(
            "batch_levels_path={}",
            b.iter()
                .map(|b| format!(
                    "[{:.2}; {}]",
                    b.level_a,
                    (1..=4)
                        .map(|f| format!("{:.2}", at(b, f).1))
                        .collect::<Vec<_>>()
                        .join(", ")
                ))
                .collect::<Vec<_>>()
                .join(" ")
        );
        eprintln!("weights={:?}", m.score.weights);
    }
}
