//! The learned score of the fall that [`super::ChainOptions::by_fall`] cuts
//! the cells along.

/// A linear score of the standardised features fitted to the log of the
/// members' fall masses: the direction in which the states that fall lie.
pub(super) struct FallScore {
    weights: Vec<f64>,
}

impl FallScore {
    pub(super) fn fit(points: &[Vec<f64>], fall: &[f64]) -> Self {
        use nalgebra::{DMatrix, DVector};
        let (n, d) = (points.len(), points[0].len());
        let x = DMatrix::from_fn(n, d + 1, |i, j| if j == 0 { 1.0 } else { points[i][j - 1] });
        let y = DVector::from_fn(n, |i, _| fall[i].max(1e-300).ln());
        let mut a = x.transpose() * &x;
        for j in 1..=d {
            a[(j, j)] += 1e-3 * n as f64;
        }
        let b = x.transpose() * y;
        let w = a
            .cholesky()
            .map(|c| c.solve(&b))
            .unwrap_or_else(|| DVector::zeros(d + 1));
        Self {
            weights: w.iter().copied().collect(),
        }
    }

    pub(super) fn at(&self, p: &[f64]) -> f64 {
        self.weights[0]
            + p.iter()
                .zip(&self.weights[1..])
                .map(|(a, b)| a * b)
                .sum::<f64>()
    }
}
