//! Logistic regression on standardized features, fitted by Newton's method
//! (iteratively reweighted least squares): a learned committor-like score
//! for [`crate::splitting`] (Lucente, Rolland, Herbert and Bouchet,
//! J. Stat. Mech. 2022: a score learned from observed transitions).
//!
//! The model is `P(y = 1 | x) = σ(w₀ + Σᵢ wᵢ (xᵢ − mᵢ)/sᵢ)`, `mᵢ` and `sᵢ` the
//! training features' means and standard deviations (a constant feature
//! gets `sᵢ = 1`), `σ` the logistic function. The fit maximizes the
//! log-likelihood less `ridge/2 × Σᵢ₌₁ wᵢ²` (the intercept is not
//! penalized; a small ridge keeps the weights finite when the classes are
//! separable). Each Newton step solves `(XᵀWX + ridge·I') Δ = Xᵀ(y − p) −
//! ridge·w'` by Cholesky; it stops when the step is below `1e-10` in every
//! weight or after 100 steps.

use nalgebra::{DMatrix, DVector};

/// A fitted logistic regression.
#[derive(Clone, Debug, PartialEq)]
pub struct Logistic {
    /// The training features' means.
    pub mean: Vec<f64>,
    /// Their standard deviations (1 for a constant feature).
    pub scale: Vec<f64>,
    /// The intercept, then one weight per standardized feature.
    pub weights: Vec<f64>,
    /// Newton steps taken.
    pub iterations: usize,
}

/// Why a fit failed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum FitError {
    /// No rows, rows of different lengths, or labels not one per row.
    #[error("logistic fit: {0}")]
    Shape(String),
    /// The Newton system was not positive definite.
    #[error("logistic fit: singular Newton system (add a ridge)")]
    Singular,
}

/// The logistic function, stable for large `|t|`.
pub fn sigmoid(t: f64) -> f64 {
    if t >= 0.0 {
        1.0 / (1.0 + (-t).exp())
    } else {
        let e = t.exp();
        e / (1.0 + e)
    }
}

impl Logistic {
    /// Fits the model to rows `x` with labels `y` (see the module doc).
    pub fn fit(x: &[Vec<f64>], y: &[bool], ridge: f64) -> Result<Self, FitError> {
        let n = x.len();
        if n == 0 || y.len() != n {
            return Err(FitError::Shape(format!("{n} rows, {} labels", y.len())));
        }
        let d = x[0].len();
        if x.iter().any(|r| r.len() != d) {
            return Err(FitError::Shape("rows of different lengths".into()));
        }
        let mean: Vec<f64> = (0..d)
            .map(|j| x.iter().map(|r| r[j]).sum::<f64>() / n as f64)
            .collect();
        let scale: Vec<f64> = (0..d)
            .map(|j| {
                let v = x.iter().map(|r| (r[j] - mean[j]).powi(2)).sum::<f64>() / n as f64;
                if v > 0.0 { v.sqrt() } else { 1.0 }
            })
            .collect();
        // The design matrix: a column of ones, then the standardized features.
        let z = DMatrix::from_fn(n, d + 1, |i, j| {
            if j == 0 {
                1.0
            } else {
                (x[i][j - 1] - mean[j - 1]) / scale[j - 1]
            }
        });
        let t = DVector::from_fn(n, |i, _| f64::from(u8::from(y[i])));
        let mut w = DVector::zeros(d + 1);
        let mut iterations = 0;
        for _ in 0..100 {
            iterations += 1;
            let p = (&z * &w).map(sigmoid);
            let mut grad = z.transpose() * (&t - &p);
            let weights = p.map(|v| (v * (1.0 - v)).max(1e-12));
            let mut zw = z.clone();
            for (i, wi) in weights.iter().enumerate() {
                zw.row_mut(i).scale_mut(*wi);
            }
            let mut h = z.transpose() * zw;
            for j in 1..=d {
                grad[j] -= ridge * w[j];
                h[(j, j)] += ridge;
            }
            let delta = h.cholesky().ok_or(FitError::Singular)?.solve(&grad);
            w += &delta;
            if delta.amax() < 1e-10 {
                break;
            }
        }
        Ok(Self {
            mean,
            scale,
            weights: w.iter().copied().collect(),
            iterations,
        })
    }

    /// The log-odds `w₀ + Σᵢ wᵢ (xᵢ − mᵢ)/sᵢ` of the features `x`.
    pub fn logit(&self, x: &[f64]) -> f64 {
        self.weights[0]
            + x.iter()
                .zip(self.mean.iter().zip(&self.scale))
                .zip(&self.weights[1..])
                .map(|((v, (m, s)), w)| w * (v - m) / s)
                .sum::<f64>()
    }

    /// The probability `σ(logit)`.
    pub fn probability(&self, x: &[f64]) -> f64 {
        sigmoid(self.logit(x))
    }
}

/// The area under the ROC curve of `scores` for `labels` (the
/// Mann–Whitney probability that a positive outscores a negative, ties
/// counting half); NaN without both classes.
pub fn auc(scores: &[f64], labels: &[bool]) -> f64 {
    let mut order: Vec<usize> = (0..scores.len()).collect();
    order.sort_by(|&a, &b| scores[a].total_cmp(&scores[b]));
    // Mid-ranks (1-based) over runs of equal scores.
    let mut rank = vec![0.0; scores.len()];
    let mut i = 0;
    while i < order.len() {
        let mut j = i;
        while j + 1 < order.len() && scores[order[j + 1]] == scores[order[i]] {
            j += 1;
        }
        let mid = (i + j) as f64 / 2.0 + 1.0;
        for &k in &order[i..=j] {
            rank[k] = mid;
        }
        i = j + 1;
    }
    let pos = labels.iter().filter(|&&l| l).count() as f64;
    let neg = labels.len() as f64 - pos;
    let sum: f64 = rank
        .iter()
        .zip(labels)
        .filter(|(_, l)| **l)
        .map(|(r, _)| r)
        .sum();
    (sum - pos * (pos + 1.0) / 2.0) / (pos * neg)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::metastable::Rng;

    /// One binary feature, no ridge: the maximum likelihood puts each
    /// group's probability at its observed share (the closed form).
    #[test]
    fn a_binary_feature_s_fit_is_the_groups_shares() {
        // Group 0: 3 of 10 positive; group 1: 8 of 10.
        let x: Vec<Vec<f64>> = (0..20)
            .map(|i| vec![f64::from(u8::from(i >= 10))])
            .collect();
        let y: Vec<bool> = (0..20).map(|i| (i < 3) || (10..18).contains(&i)).collect();
        let m = Logistic::fit(&x, &y, 0.0).unwrap();
        assert!((m.probability(&[0.0]) - 0.3).abs() < 1e-9, "{m:?}");
        assert!((m.probability(&[1.0]) - 0.8).abs() < 1e-9, "{m:?}");
        // The log-odds ratio in the raw feature's units.
        let slope = m.logit(&[1.0]) - m.logit(&[0.0]);
        let exact = (0.8f64 / 0.2).ln() - (0.3f64 / 0.7).ln();
        assert!((slope - exact).abs() < 1e-9, "{slope} vs {exact}");
    }

    /// Labels drawn from a known model over 40 000 rows: the fit recovers
    /// its weights (raw units) within 0.1, and the score equations hold at
    /// the fit (the gradient of the likelihood is 0).
    #[test]
    fn the_fit_recovers_the_model_that_drew_the_labels() {
        let mut rng = Rng::new(3);
        let (b0, b) = (-1.0, [2.0, -0.5, 0.0]);
        let x: Vec<Vec<f64>> = (0..40_000)
            .map(|_| vec![rng.normal(), 3.0 + 2.0 * rng.normal(), rng.uniform()])
            .collect();
        let y: Vec<bool> = x
            .iter()
            .map(|r| {
                let t = b0 + b.iter().zip(r).map(|(w, v)| w * v).sum::<f64>();
                rng.uniform() < sigmoid(t)
            })
            .collect();
        let m = Logistic::fit(&x, &y, 0.0).unwrap();
        for (j, bj) in b.iter().enumerate() {
            let raw = m.weights[j + 1] / m.scale[j];
            assert!((raw - bj).abs() < 0.1, "weight {j}: {raw} vs {bj}");
        }
        let mut e = [0.0; 4];
        e[0] = m.logit(&[0.0, 0.0, 0.0]);
        assert!((e[0] - b0).abs() < 0.1, "intercept {} vs {b0}", e[0]);
        for j in 0..4 {
            let g: f64 = x
                .iter()
                .zip(&y)
                .map(|(r, &l)| {
                    let f = if j == 0 { 1.0 } else { r[j - 1] };
                    (f64::from(u8::from(l)) - m.probability(r)) * f
                })
                .sum();
            assert!(g.abs() < 1e-6 * x.len() as f64, "gradient {j}: {g}");
        }
        assert!(m.iterations < 20, "{}", m.iterations);
    }

    /// Separable classes: without a ridge the weights would grow without
    /// bound; with one the fit stays finite and orders the classes.
    #[test]
    fn a_ridge_keeps_a_separable_fit_finite() {
        let x: Vec<Vec<f64>> = (0..10).map(|i| vec![f64::from(i)]).collect();
        let y: Vec<bool> = (0..10).map(|i| i >= 5).collect();
        let m = Logistic::fit(&x, &y, 1e-3).unwrap();
        assert!(m.weights.iter().all(|w| w.is_finite()));
        assert!(
            m.probability(&[9.0]) > 0.9 && m.probability(&[0.0]) < 0.1,
            "{m:?}"
        );
        assert!(Logistic::fit(&[], &[], 0.0).is_err());
    }

    /// The AUC against a count by hand: positives 0.9, 0.4, 0.4; negatives
    /// 0.4, 0.2: of the 6 pairs 0.9 wins 2, each 0.4 beats 0.2 and ties
    /// 0.4: (2 + 2 × 1.5) / 6.
    #[test]
    fn the_auc_is_the_share_of_pairs_ordered() {
        let s = [0.9, 0.4, 0.4, 0.4, 0.2];
        let l = [true, true, true, false, false];
        assert!((auc(&s, &l) - 5.0 / 6.0).abs() < 1e-12);
        assert_eq!(auc(&[1.0, 0.0], &[true, false]), 1.0);
        assert!(auc(&[1.0], &[true]).is_nan());
    }
}
