//! Where a search's candidates come from: CMA-ES in the unit box with the
//! learned fall constraint (a candidate likely to fall is drawn again), or
//! the designs of a scrambled Sobol sequence, the baseline.

use super::cmaes::Cmaes;
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

/// The search's proposals for one generation.
pub(super) enum Proposer {
    Cmaes {
        es: Box<Cmaes>,
        rng: Box<ChaCha8Rng>,
        model: FallModel,
    },
    Sobol(Sobol, u64, usize),
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
            Proposer::Cmaes { es, rng, model } => {
                let mut least: Option<(Vec<f64>, f64)> = None;
                let mut last = Vec::new();
                for _ in 0..TRIES {
                    let u = es.sample(rng);
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
        }
    }

    /// Learns a generation's evaluations (their unit-box places `us`).
    pub(super) fn tell(&mut self, us: &[Vec<f64>], evals: &[Evaluation]) {
        if let Proposer::Cmaes { es, rng, model } = self {
            for (u, e) in us.iter().zip(evals) {
                model.add(u.clone(), !e.feasible());
            }
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
    }
}
