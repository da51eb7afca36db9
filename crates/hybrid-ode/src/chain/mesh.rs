//! The mesh of [`super`]: k-means cells over standardised features, and
//! the effective dimension of the sample they cut.

use crate::metastable::Rng;
use nalgebra::{DMatrix, SymmetricEigen};

pub(super) fn dist2(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum()
}

/// The index of the centre nearest `f`.
pub(super) fn nearest(centres: &[Vec<f64>], f: &[f64]) -> usize {
    let mut best = (f64::INFINITY, 0);
    for (i, c) in centres.iter().enumerate() {
        let d = dist2(c, f);
        if d < best.0 {
            best = (d, i);
        }
    }
    best.1
}

/// k-means of `points` into at most `k` non-empty clusters: k-means++
/// seeding, then Lloyd's iterations until no point moves (at most 100).
/// Returns the centres that hold at least `min_members` points.
pub fn kmeans(points: &[Vec<f64>], k: usize, min_members: usize, rng: &mut Rng) -> Vec<Vec<f64>> {
    let k = k.min(points.len()).max(1);
    let mut centres = vec![points[rng.below(points.len())].clone()];
    let mut d2: Vec<f64> = points.iter().map(|p| dist2(p, &centres[0])).collect();
    while centres.len() < k {
        let total: f64 = d2.iter().sum();
        if total <= 0.0 {
            break;
        }
        let mut u = rng.uniform() * total;
        let mut pick = points.len() - 1;
        for (i, d) in d2.iter().enumerate() {
            if u < *d {
                pick = i;
                break;
            }
            u -= d;
        }
        let c = points[pick].clone();
        for (d, p) in d2.iter_mut().zip(points) {
            *d = d.min(dist2(p, &c));
        }
        centres.push(c);
    }
    let mut label = vec![usize::MAX; points.len()];
    for _ in 0..100 {
        let mut moved = false;
        for (l, p) in label.iter_mut().zip(points) {
            let n = nearest(&centres, p);
            if n != *l {
                *l = n;
                moved = true;
            }
        }
        if !moved {
            break;
        }
        let dim = points[0].len();
        let mut sum = vec![vec![0.0; dim]; centres.len()];
        let mut count = vec![0usize; centres.len()];
        for (l, p) in label.iter().zip(points) {
            count[*l] += 1;
            for (s, x) in sum[*l].iter_mut().zip(p) {
                *s += x;
            }
        }
        for ((c, s), n) in centres.iter_mut().zip(sum).zip(&count) {
            if *n > 0 {
                *c = s.into_iter().map(|x| x / *n as f64).collect();
            }
        }
    }
    // Keep the centres that hold at least `min_members` points (or the
    // most populous one).
    let mut count = vec![0usize; centres.len()];
    for p in points {
        count[nearest(&centres, p)] += 1;
    }
    let most = count.iter().copied().max().unwrap_or(0);
    centres
        .into_iter()
        .zip(count)
        .filter_map(|(c, n)| (n >= min_members.min(most).max(1)).then_some(c))
        .collect()
}

/// Principal components that hold 95 % of the variance of `points`.
pub(super) fn effective_dimension(points: &[Vec<f64>]) -> usize {
    let d = points[0].len();
    if d == 0 {
        return 0;
    }
    let n = points.len() as f64;
    let mut cov = DMatrix::<f64>::zeros(d, d);
    for p in points {
        for i in 0..d {
            for j in 0..d {
                cov[(i, j)] += p[i] * p[j] / n;
            }
        }
    }
    let mut ev: Vec<f64> = SymmetricEigen::new(cov)
        .eigenvalues
        .iter()
        .map(|v| v.max(0.0))
        .collect();
    ev.sort_by(|a, b| b.total_cmp(a));
    let total: f64 = ev.iter().sum();
    let mut acc = 0.0;
    for (i, v) in ev.iter().enumerate() {
        acc += v;
        if acc >= 0.95 * total {
            return i + 1;
        }
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kmeans_finds_separated_clusters() {
        let mut rng = Rng::new(3);
        let points: Vec<Vec<f64>> = (0..300)
            .map(|i| {
                let c = (i % 3) as f64 * 10.0;
                vec![c + 0.1 * rng.normal(), -c + 0.1 * rng.normal()]
            })
            .collect();
        let mut centres = kmeans(&points, 3, 1, &mut Rng::new(1));
        centres.sort_by(|a, b| a[0].total_cmp(&b[0]));
        for (i, c) in centres.iter().enumerate() {
            assert!((c[0] - 10.0 * i as f64).abs() < 0.1, "{centres:?}");
        }
    }
}
