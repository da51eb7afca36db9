//! Where a search's candidates come from: CMA-ES in the unit box, or
//! MAP-Elites variation of the archive's elites, each with the learned fall
//! constraint (a candidate likely to fall is drawn again); or the designs
//! of a scrambled Sobol sequence, the baseline.

use super::archive::{self, Elites};
use super::cmaes::{Cmaes, normal};
use super::fall_model::FallModel;
use super::{Evaluation, Method, SearchSettings};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rtw_engine::sampling::Sobol;

/// The start's step size in the unit box.
const SIGMA0: f64 = 0.3;
/// Below this step size a sub-search has converged and restarts from a
/// random mean (its budget is not yet spent).
const SIGMA_RESTART: f64 = 1e-4;
/// Draws for one candidate before the least likely to fall is taken.
const TRIES: usize = 64;
/// Generations an archive search draws from the Sobol sequence before it
/// varies its elites (and for as long as it has fewer than two).
const ARCHIVE_START: u64 = 2;
/// The isotropic step of the archive's variation in the unit box, and the
/// step along the line to a second elite: Iso+LineDD (Vassiliades & Mouret,
/// GECCO 2018), the isotropic step five times theirs because a search
/// here spends a few hundred designs, not a million.
const SIGMA_ISO: f64 = 0.05;
const SIGMA_LINE: f64 = 0.2;

/// The search's proposals for one generation.
pub(super) enum Proposer {
    Cmaes {
        es: Box<Cmaes>,
        rng: Box<ChaCha8Rng>,
        model: FallModel,
    },
    Sobol(Sobol, u64, usize),
    Archive(Box<ArchiveSearch>),
}

/// MAP-Elites: the elites of its sub-search, a start from the Sobol
/// sequence, and the fall model its variation consults.
pub(super) struct ArchiveSearch {
    settings: SearchSettings,
    rng: ChaCha8Rng,
    model: FallModel,
    elites: Elites,
    sobol: Sobol,
    drawn: u64,
    n: usize,
}

impl Proposer {
    pub(super) fn new(s: &SearchSettings, round: u64) -> Self {
        let n = s.free().len();
        match s.method {
            Method::Cmaes => {
                let mut rng = ChaCha8Rng::seed_from_u64(s.seed);
                rng.set_stream(round);
                Proposer::Cmaes {
                    rng: Box::new(rng),
                    es: Box::new(Cmaes::new(vec![0.5; n], SIGMA0, s.batch as usize)),
                    model: FallModel::default(),
                }
            }
            Method::Sobol => Proposer::Sobol(Sobol::scrambled(n, s.seed), 0, n),
            Method::Archive => {
                let mut rng = ChaCha8Rng::seed_from_u64(s.seed);
                rng.set_stream(round);
                Proposer::Archive(Box::new(ArchiveSearch {
                    settings: s.clone(),
                    rng,
                    model: FallModel::default(),
                    elites: Elites::default(),
                    sobol: Sobol::scrambled(n, s.seed),
                    drawn: 0,
                    n,
                }))
            }
        }
    }

    /// One candidate in the unit box and its learned fall probability.
    pub(super) fn propose(&mut self, avoid: f64) -> (Vec<f64>, Option<f64>) {
        match self {
            Proposer::Sobol(sobol, i, n) => {
                let mut u = vec![0.0; *n];
                sobol.point(*i, &mut u);
                *i += 1;
                (u, None)
            }
            Proposer::Cmaes { es, rng, model } => avoiding(model, avoid, || es.sample(rng)),
            Proposer::Archive(a) => {
                a.drawn += 1;
                if a.drawn <= ARCHIVE_START * a.settings.batch || a.elites.len() < 2 {
                    let mut u = vec![0.0; a.n];
                    a.sobol.point(a.drawn - 1, &mut u);
                    let p = a.model.p_infeasible(&u);
                    return (u, Some(p));
                }
                let ArchiveSearch {
                    rng, model, elites, ..
                } = &mut **a;
                let points = elites.points();
                avoiding(model, avoid, || {
                    // The parent: the better of two elites drawn at random
                    // (a binary tournament), so that the few hundred
                    // designs a search can afford go where designs are
                    // better; the second elite, at random, gives the line.
                    let (a, b) = (
                        rng.random_range(0..points.len()),
                        rng.random_range(0..points.len()),
                    );
                    let i = if points[b].0 > points[a].0 { b } else { a };
                    let j = rng.random_range(0..points.len());
                    let along = SIGMA_LINE * normal(rng);
                    points[i]
                        .1
                        .iter()
                        .zip(points[j].1)
                        .map(|(a, b)| a + SIGMA_ISO * normal(rng) + along * (b - a))
                        .collect()
                })
            }
        }
    }

    /// Learns a generation's evaluations (their unit-box places `us`).
    pub(super) fn tell(&mut self, us: &[Vec<f64>], evals: &[Evaluation]) {
        if let Some(model) = self.fall_model() {
            for (u, e) in us.iter().zip(evals) {
                model.add(u.clone(), !e.feasible());
            }
        }
        match self {
            Proposer::Archive(a) => {
                for (u, e) in us.iter().zip(evals) {
                    if let (Some(c), Some(score)) = (archive::cell(&a.settings, e), e.score) {
                        a.elites.offer(c, score, e.index, u);
                    }
                }
            }
            Proposer::Cmaes { es, rng, .. } => {
                let mut ranked: Vec<(f64, &Vec<f64>)> = us
                    .iter()
                    .zip(evals)
                    .filter_map(|(u, e)| e.score.map(|sc| (sc, u)))
                    .collect();
                ranked.sort_by(|a, b| b.0.total_cmp(&a.0));
                es.tell(
                    &ranked
                        .into_iter()
                        .map(|(_, u)| u.clone())
                        .collect::<Vec<_>>(),
                );
                if es.sigma() < SIGMA_RESTART {
                    let n = us.first().map_or(0, Vec::len);
                    let mean: Vec<f64> = (0..n).map(|_| rng.random::<f64>()).collect();
                    **es = Cmaes::new(mean, SIGMA0, es.lambda);
                }
            }
            Proposer::Sobol(..) => {}
        }
    }

    /// The learned fall constraint of a proposer that screens its
    /// candidates (the Sobol sequence screens none).
    fn fall_model(&mut self) -> Option<&mut FallModel> {
        match self {
            Proposer::Cmaes { model, .. } => Some(model),
            Proposer::Archive(a) => Some(&mut a.model),
            Proposer::Sobol(..) => None,
        }
    }
}

/// A candidate from `draw` that the fall model lets through: the first of
/// `TRIES` draws inside the unit box whose learned fall probability is at
/// most `avoid`, else the least likely to fall of them (else the last draw
/// clamped to the box).
fn avoiding(
    model: &FallModel,
    avoid: f64,
    mut draw: impl FnMut() -> Vec<f64>,
) -> (Vec<f64>, Option<f64>) {
    let mut least: Option<(Vec<f64>, f64)> = None;
    let mut last = Vec::new();
    for _ in 0..TRIES {
        let u = draw();
        if u.iter().any(|v| !(0.0..=1.0).contains(v)) {
            last = u;
            continue;
        }
        let p = model.p_infeasible(&u);
        if p <= avoid {
            return (u, Some(p));
        }
        if least.as_ref().is_none_or(|l| p < l.1) {
            least = Some((u, p));
        }
    }
    match least {
        Some((u, p)) => (u, Some(p)),
        None => {
            let u: Vec<f64> = last.iter().map(|v| v.clamp(0.0, 1.0)).collect();
            let p = model.p_infeasible(&u);
            (u, Some(p))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A closed-form landscape in the unit box of the four inputs: the
    /// score `1 − |u − c|²` peaks at 1 at `c`; designs with `u₃ > 0.8` fall;
    /// the descriptors are `u₀` (the interval's middle, over the slopes) and
    /// `u₁` (the walk share), so that every cell holds feasible designs.
    const C: [f64; 4] = [0.3, 0.7, 0.2, 0.75];

    fn settings(method: &str, avoid: f64, seed: u64) -> SearchSettings {
        SearchSettings::parse(&format!(
            "name = \"t\"\nseed = {seed}\nbudget = 100\nobjectives = [\"slope_range\"]\n\
             method = \"{method}\"\navoid = {avoid}\n\
             [box]\nrho = [1.0, 5.0]\nalpha = [0.0, 0.4]\nfn = [1.5, 5.0]\nzeta = [0.05, 0.1]\n\
             [slopes]\nfrom = 0.0\nto = 0.4\n"
        ))
        .unwrap()
    }

    fn judged(s: &SearchSettings, index: u64, u: &[f64]) -> Evaluation {
        let falls = u[3] > 0.8;
        let score = 1.0 - u.iter().zip(C).map(|(a, c)| (a - c) * (a - c)).sum::<f64>();
        let mid = s.from + u[0] * (s.to - s.from);
        Evaluation {
            index,
            round: 0,
            generation: 0,
            design: s.design_at(u),
            p_fall: None,
            runs: 1,
            phi_lo: Some(mid),
            phi_hi: Some(mid),
            phi_min: Some(mid),
            walk_share: Some(u[1]),
            label_at_speed_phi: None,
            speed: None,
            label_at_mfpt_phi: None,
            mfpt: None,
            infeasible: falls.then(|| "falls".into()),
            values: if falls { vec![] } else { vec![0.0] },
            score: (!falls).then_some(score),
        }
    }

    /// Generations of the batch drawn by the search of `s` and judged on
    /// the landscape until `designs` are: their points and evaluations.
    fn drive(s: &SearchSettings, designs: u64) -> (Vec<Vec<f64>>, Vec<Evaluation>) {
        let mut p = Proposer::new(s, 0);
        let (mut points, mut all) = (Vec::new(), Vec::new());
        while (all.len() as u64) < designs {
            let us: Vec<Vec<f64>> = (0..s.batch).map(|_| p.propose(s.avoid).0).collect();
            let evals: Vec<Evaluation> = us
                .iter()
                .enumerate()
                .map(|(k, u)| judged(s, (all.len() + k) as u64, u))
                .collect();
            p.tell(&us, &evals);
            points.extend(us);
            all.extend(evals);
        }
        (points, all)
    }

    /// The best score, the archive's QD-score and the falls of `designs`
    /// designs drawn by `method` in generations of the batch.
    fn search(method: &str, avoid: f64, seed: u64, designs: u64) -> (f64, f64, usize) {
        let s = settings(method, avoid, seed);
        let (_, all) = drive(&s, designs);
        let best = all.iter().filter_map(|e| e.score).fold(f64::MIN, f64::max);
        let (_, qd) = archive::coverage_and_qd(&s, &all);
        (best, qd, all.iter().filter(|e| !e.feasible()).count())
    }

    #[test]
    fn map_elites_finds_a_better_best_than_sobol_on_a_closed_form_landscape() {
        // 200 designs, as many as a design search of 20,000 simulations
        // profiles; ten seeds, paired. The optimum scores 1. What holds:
        // the paired t 95 % interval of the mean difference excludes 0
        // (measured: +0.014 [+0.003, +0.025]; 8 of 10 seeds better).
        let diff: Vec<f64> = (1..=10)
            .map(|seed| search("archive", 0.5, seed, 200).0 - search("sobol", 0.5, seed, 200).0)
            .collect();
        let n = diff.len() as f64;
        let mean = diff.iter().sum::<f64>() / n;
        let sd = (diff.iter().map(|d| (d - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
        // t(0.975, 9) = 2.262.
        let lo = mean - 2.262 * sd / n.sqrt();
        assert!(lo > 0.0, "mean {mean:+.4}, lower end {lo:+.4}: {diff:?}");
    }

    #[test]
    fn a_candidate_the_fall_model_expects_to_fall_is_drawn_again() {
        let mut model = FallModel::default();
        for i in 0..10 {
            let x = i as f64 / 20.0;
            model.add(vec![x, 0.1], true); // the strip near y = 0.1 falls
            model.add(vec![x, 0.9], false);
        }
        // The draws alternate between the strip, outside the box and the
        // feasible side: the first feasible-side draw is taken.
        let mut k = 0;
        let (u, p) = avoiding(&model, 0.5, || {
            k += 1;
            match k % 3 {
                1 => vec![0.2, 0.1],
                2 => vec![1.5, 0.5],
                _ => vec![0.2, 0.9],
            }
        });
        assert_eq!((u, k), (vec![0.2, 0.9], 3));
        assert!(p.unwrap() < 0.5);
        // With avoid = 1 nothing is drawn again.
        let (u, _) = avoiding(&model, 1.0, || vec![0.2, 0.1]);
        assert_eq!(u, [0.2, 0.1]);
    }

    #[test]
    fn an_archive_search_draws_the_same_designs_again_from_the_same_evaluations() {
        let s = settings("archive", 0.5, 7);
        let draw = || drive(&s, 6 * s.batch).0;
        let (a, b) = (draw(), draw());
        assert_eq!(a, b);
        // Past the Sobol start it varies its elites: not Sobol's points.
        let s = settings("sobol", 0.5, 7);
        let mut sobol = Proposer::new(&s, 0);
        let points: Vec<Vec<f64>> = (0..48).map(|_| sobol.propose(0.5).0).collect();
        assert_eq!(a[..16], points[..16]);
        assert_ne!(a[16..], points[16..]);
    }
}
