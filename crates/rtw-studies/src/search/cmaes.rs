//! CMA-ES, the covariance matrix adaptation evolution strategy, as Hansen
//! states it in "The CMA Evolution Strategy: A Tutorial" (arXiv 1604.00772,
//! 2016): the (μ/μ_w, λ) strategy with cumulative step-size adaptation and
//! rank-one plus rank-μ updates of the covariance, every constant the
//! tutorial's default (its Table 1).
//!
//! Why our own rather than a crate or Python's `cmaes`: the search must run
//! in the library, behind `rtw-scan design` and `rtw.design` alike, and
//! replay bit for bit on resume. The Rust crates found pull a second
//! nalgebra and rand (hours of build on these machines for ~150 lines),
//! and their ask/tell loops draw from their own generators. Here every
//! draw comes from the search's seeded stream, and an infeasible candidate
//! (a design that falls) is left out of the update rather than ranked with
//! a made-up value: only feasible candidates are recombined, with the
//! weights of as many as there are.

use nalgebra::{DMatrix, DVector};
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

/// The strategy's state: the mean, the step size, the covariance and its
/// evolution paths, in the search's unit box.
#[derive(Clone, Debug)]
pub(crate) struct Cmaes {
    n: usize,
    /// Candidates per generation.
    pub(crate) lambda: usize,
    mean: DVector<f64>,
    sigma: f64,
    cov: DMatrix<f64>,
    /// C = B diag(d²) Bᵀ, kept with `cov`.
    b: DMatrix<f64>,
    d: DVector<f64>,
    p_sigma: DVector<f64>,
    p_c: DVector<f64>,
    generation: u32,
}

/// The recombination weights of the best `mu` of a generation (largest
/// first), summing to 1, and their variance effective selection mass.
fn weights(mu: usize) -> (Vec<f64>, f64) {
    let raw: Vec<f64> = (1..=mu)
        .map(|i| ((mu as f64 + 0.5).ln() - (i as f64).ln()).max(0.0))
        .collect();
    let sum: f64 = raw.iter().sum();
    let w: Vec<f64> = raw.iter().map(|x| x / sum).collect();
    let mu_eff = 1.0 / w.iter().map(|x| x * x).sum::<f64>();
    (w, mu_eff)
}

impl Cmaes {
    /// The strategy at `mean` with step size `sigma`, `lambda` candidates a
    /// generation.
    pub(crate) fn new(mean: Vec<f64>, sigma: f64, lambda: usize) -> Self {
        let n = mean.len();
        Self {
            n,
            lambda,
            mean: DVector::from_vec(mean),
            sigma,
            cov: DMatrix::identity(n, n),
            b: DMatrix::identity(n, n),
            d: DVector::from_element(n, 1.0),
            p_sigma: DVector::zeros(n),
            p_c: DVector::zeros(n),
            generation: 0,
        }
    }

    /// The step size σ.
    pub(crate) fn sigma(&self) -> f64 {
        self.sigma
    }

    /// One candidate: `mean + σ B D z`, z standard normal from `rng`.
    pub(crate) fn sample(&self, rng: &mut ChaCha8Rng) -> Vec<f64> {
        let z = DVector::from_iterator(self.n, (0..self.n).map(|_| normal(rng)));
        let y = &self.b * self.d.component_mul(&z);
        (&self.mean + y * self.sigma).iter().copied().collect()
    }

    /// The update from a generation's feasible candidates, best first. With
    /// none, the state stays (only the generation counts).
    pub(crate) fn tell(&mut self, best_first: &[Vec<f64>]) {
        self.generation += 1;
        let mu_full = self.lambda / 2;
        let k = best_first.len().min(mu_full);
        if k == 0 {
            return;
        }
        let n = self.n as f64;
        let (w, mu_eff) = weights(k);
        let c_sigma = (mu_eff + 2.0) / (n + mu_eff + 5.0);
        let d_sigma = 1.0 + 2.0 * (((mu_eff - 1.0) / (n + 1.0)).sqrt() - 1.0).max(0.0) + c_sigma;
        let c_c = (4.0 + mu_eff / n) / (n + 4.0 + 2.0 * mu_eff / n);
        let c_1 = 2.0 / ((n + 1.3).powi(2) + mu_eff);
        let c_mu =
            (1.0 - c_1).min(2.0 * (mu_eff - 2.0 + 1.0 / mu_eff) / ((n + 2.0).powi(2) + mu_eff));
        let chi_n = n.sqrt() * (1.0 - 1.0 / (4.0 * n) + 1.0 / (21.0 * n * n));

        let ys: Vec<DVector<f64>> = best_first[..k]
            .iter()
            .map(|x| (DVector::from_column_slice(x) - &self.mean) / self.sigma)
            .collect();
        let y_w = ys
            .iter()
            .zip(&w)
            .fold(DVector::zeros(self.n), |acc, (y, wi)| acc + y * *wi);
        self.mean += &y_w * self.sigma;

        // C^{-1/2} y_w = B D⁻¹ Bᵀ y_w.
        let inv_sqrt = &self.b * (self.b.transpose() * &y_w).component_div(&self.d);
        self.p_sigma = &self.p_sigma * (1.0 - c_sigma)
            + inv_sqrt * (c_sigma * (2.0 - c_sigma) * mu_eff).sqrt();
        let norm = self.p_sigma.norm();
        let h_sigma = norm / (1.0 - (1.0 - c_sigma).powi(2 * self.generation as i32)).sqrt()
            < (1.4 + 2.0 / (n + 1.0)) * chi_n;
        let h = if h_sigma { 1.0 } else { 0.0 };
        self.p_c = &self.p_c * (1.0 - c_c) + &y_w * (h * (c_c * (2.0 - c_c) * mu_eff).sqrt());
        let delta = (1.0 - h) * c_c * (2.0 - c_c);
        let rank_mu = ys
            .iter()
            .zip(&w)
            .fold(DMatrix::zeros(self.n, self.n), |acc, (y, wi)| {
                acc + y * y.transpose() * *wi
            });
        self.cov = &self.cov * (1.0 + c_1 * delta - c_1 - c_mu)
            + &self.p_c * self.p_c.transpose() * c_1
            + rank_mu * c_mu;
        self.sigma *= ((c_sigma / d_sigma) * (norm / chi_n - 1.0)).exp();

        // Symmetrise against rounding, then B and D from the eigenpairs.
        let sym = (&self.cov + self.cov.transpose()) * 0.5;
        let eig = sym.clone().symmetric_eigen();
        self.cov = sym;
        self.b = eig.eigenvectors;
        self.d = eig.eigenvalues.map(|v| v.max(1e-20).sqrt());
    }
}

/// A standard normal draw (Box–Muller on two uniforms of `rng`).
pub(crate) fn normal(rng: &mut ChaCha8Rng) -> f64 {
    let u1: f64 = 1.0 - rng.random::<f64>(); // (0, 1]
    let u2: f64 = rng.random::<f64>();
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    /// Runs the strategy on `f` (to minimise) for `generations`, returning
    /// the best value seen.
    fn minimise(f: impl Fn(&[f64]) -> f64, start: Vec<f64>, generations: usize) -> f64 {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let mut es = Cmaes::new(start, 0.3, 8);
        let mut best = f64::INFINITY;
        for _ in 0..generations {
            let mut cands: Vec<(f64, Vec<f64>)> = (0..es.lambda)
                .map(|_| {
                    let x = es.sample(&mut rng);
                    (f(&x), x)
                })
                .collect();
            cands.sort_by(|a, b| a.0.total_cmp(&b.0));
            best = best.min(cands[0].0);
            es.tell(&cands.into_iter().map(|c| c.1).collect::<Vec<_>>());
        }
        best
    }

    #[test]
    fn the_weights_are_the_tutorials_and_sum_to_one() {
        // λ = 10 (the default in 10 dimensions, as pycma prints it): μ = 5,
        // μ_eff ≈ 3.1672.
        let (w, mu_eff) = weights(5);
        assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        assert!(w.windows(2).all(|p| p[0] > p[1]));
        assert!((mu_eff - 3.1672).abs() < 1e-4, "{mu_eff}");
    }

    #[test]
    fn it_finds_the_minimum_of_an_ill_conditioned_ellipsoid_and_the_rosenbrock_valley() {
        // An ellipsoid with condition 10⁴, rotated off the axes: a strategy
        // that did not learn the covariance stalls far above 1e-10.
        let ellipsoid = |x: &[f64]| {
            let (a, b) = (x[0] + x[1], x[0] - x[1]);
            let (c, d) = (x[2] - 0.5, x[3] + x[2]);
            a * a + 1e4 * b * b + 10.0 * c * c + 100.0 * d * d
        };
        assert!(minimise(ellipsoid, vec![1.0, -1.0, 1.0, 1.0], 400) < 1e-10);
        // Rosenbrock in 4 dimensions: minimum 0 at (1, 1, 1, 1).
        let rosen = |x: &[f64]| {
            (0..3)
                .map(|i| 100.0 * (x[i + 1] - x[i] * x[i]).powi(2) + (1.0 - x[i]).powi(2))
                .sum::<f64>()
        };
        assert!(minimise(rosen, vec![0.0; 4], 800) < 1e-8);
    }

    #[test]
    fn a_generation_with_no_feasible_candidate_leaves_the_state() {
        let mut es = Cmaes::new(vec![0.5; 3], 0.2, 6);
        let before = (es.mean.clone(), es.sigma, es.cov.clone());
        es.tell(&[]);
        assert_eq!((es.mean.clone(), es.sigma, es.cov.clone()), before);
    }

    #[test]
    fn normal_draws_have_the_standard_moments() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let n = 200_000;
        let xs: Vec<f64> = (0..n).map(|_| normal(&mut rng)).collect();
        let mean = xs.iter().sum::<f64>() / n as f64;
        let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / n as f64;
        // Standard errors: 1/sqrt(n) ≈ 0.0022 for the mean, sqrt(2/n) ≈ 0.0032 for the variance.
        assert!(
            mean.abs() < 0.01 && (var - 1.0).abs() < 0.015,
            "{mean} {var}"
        );
    }
}
