//! k-means with k-means++ starts and restarts, and the silhouette score:
//! deterministic for a seed, on points of any fixed dimension.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A k-means partition.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct KMeans<const D: usize> {
    pub(crate) centres: Vec<[f64; D]>,
    /// Cluster of each point.
    pub(crate) assignment: Vec<usize>,
    /// Sum of squared distances to the assigned centres.
    pub(crate) inertia: f64,
}

fn dist2<const D: usize>(a: &[f64; D], b: &[f64; D]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum()
}

/// Index and squared distance of the nearest centre (lowest index on ties).
pub(crate) fn nearest<const D: usize>(p: &[f64; D], centres: &[[f64; D]]) -> (usize, f64) {
    centres
        .iter()
        .enumerate()
        .map(|(j, c)| (j, dist2(p, c)))
        .fold(
            (0, f64::INFINITY),
            |best, cur| if cur.1 < best.1 { cur } else { best },
        )
}

/// k-means++ seeding: the first centre uniformly, the next ones with
/// probability proportional to the squared distance to the nearest centre.
fn plus_plus<const D: usize>(points: &[[f64; D]], k: usize, rng: &mut ChaCha8Rng) -> Vec<[f64; D]> {
    let n = points.len();
    let mut centres = vec![points[rng.random_range(0..n)]];
    let mut d2: Vec<f64> = points.iter().map(|p| dist2(p, &centres[0])).collect();
    while centres.len() < k {
        let total: f64 = d2.iter().sum();
        let next = if total > 0.0 {
            let mut target = rng.random::<f64>() * total;
            let mut pick = n - 1;
            for (i, d) in d2.iter().enumerate() {
                if target < *d {
                    pick = i;
                    break;
                }
                target -= d;
            }
            pick
        } else {
            rng.random_range(0..n)
        };
        centres.push(points[next]);
        for (d, p) in d2.iter_mut().zip(points) {
            *d = d.min(dist2(p, &points[next]));
        }
    }
    centres
}

/// Lloyd iterations from `centres` until assignments stop changing. An
/// emptied cluster is moved to the point farthest from its centre.
fn lloyd<const D: usize>(points: &[[f64; D]], mut centres: Vec<[f64; D]>) -> KMeans<D> {
    const MAX_ITER: usize = 500;
    let k = centres.len();
    let mut assignment = vec![usize::MAX; points.len()];
    for _ in 0..MAX_ITER {
        let mut changed = false;
        for (a, p) in assignment.iter_mut().zip(points) {
            let (j, _) = nearest(p, &centres);
            if *a != j {
                *a = j;
                changed = true;
            }
        }
        if !changed {
            break;
        }
        let mut sums = vec![[0.0; D]; k];
        let mut counts = vec![0usize; k];
        for (a, p) in assignment.iter().zip(points) {
            counts[*a] += 1;
            for (s, x) in sums[*a].iter_mut().zip(p) {
                *s += x;
            }
        }
        for j in 0..k {
            if counts[j] > 0 {
                centres[j] = sums[j].map(|s| s / counts[j] as f64);
            } else {
                let far = (0..points.len())
                    .max_by(|&a, &b| {
                        let da = dist2(&points[a], &centres[assignment[a]]);
                        let db = dist2(&points[b], &centres[assignment[b]]);
                        da.total_cmp(&db).then(b.cmp(&a))
                    })
                    .expect("points is not empty");
                centres[j] = points[far];
                assignment[far] = j;
            }
        }
    }
    let inertia = assignment
        .iter()
        .zip(points)
        .map(|(a, p)| dist2(p, &centres[*a]))
        .sum();
    KMeans {
        centres,
        assignment,
        inertia,
    }
}

/// k-means with k-means++ starts: the best of `restarts` runs, clusters
/// ordered by size (then by centre). `None` when there are fewer points than
/// clusters or `k == 0`.
pub(crate) fn kmeans<const D: usize>(
    points: &[[f64; D]],
    k: usize,
    seed: u64,
    restarts: usize,
) -> Option<KMeans<D>> {
    if k == 0 || points.len() < k {
        return None;
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut best: Option<KMeans<D>> = None;
    for _ in 0..restarts.max(1) {
        let run = lloyd(points, plus_plus(points, k, &mut rng));
        if best.as_ref().is_none_or(|b| run.inertia < b.inertia) {
            best = Some(run);
        }
    }
    let best = best.expect("at least one restart");
    // Canonical order: larger clusters first, then by centre.
    let mut sizes = vec![0usize; k];
    best.assignment.iter().for_each(|a| sizes[*a] += 1);
    let mut order: Vec<usize> = (0..k).collect();
    order.sort_by(|&a, &b| {
        sizes[b].cmp(&sizes[a]).then_with(|| {
            best.centres[a]
                .iter()
                .zip(&best.centres[b])
                .map(|(x, y)| x.total_cmp(y))
                .find(|o| o.is_ne())
                .unwrap_or(std::cmp::Ordering::Equal)
        })
    });
    let mut rank = vec![0; k];
    for (new, old) in order.iter().enumerate() {
        rank[*old] = new;
    }
    Some(KMeans {
        centres: order.iter().map(|&j| best.centres[j]).collect(),
        assignment: best.assignment.iter().map(|a| rank[*a]).collect(),
        inertia: best.inertia,
    })
}

/// Mean silhouette of a partition (Euclidean). A point alone in its cluster
/// scores 0. `None` with fewer than two non-empty clusters.
pub(crate) fn silhouette<const D: usize>(
    points: &[[f64; D]],
    assignment: &[usize],
    k: usize,
) -> Option<f64> {
    let mut sizes = vec![0usize; k];
    assignment.iter().for_each(|a| sizes[*a] += 1);
    if sizes.iter().filter(|s| **s > 0).count() < 2 {
        return None;
    }
    let mut total = 0.0;
    for (i, p) in points.iter().enumerate() {
        let mut sum = vec![0.0; k];
        for (q, a) in points.iter().zip(assignment) {
            sum[*a] += dist2(p, q).sqrt();
        }
        let own = assignment[i];
        if sizes[own] == 1 {
            continue;
        }
        let a = sum[own] / (sizes[own] - 1) as f64;
        let b = (0..k)
            .filter(|&j| j != own && sizes[j] > 0)
            .map(|j| sum[j] / sizes[j] as f64)
            .fold(f64::INFINITY, f64::min);
        let m = a.max(b);
        if m > 0.0 {
            total += (b - a) / m;
        }
    }
    Some(total / points.len() as f64)
}

/// Most points used for the silhouette (it is quadratic): larger sets are
/// subsampled with a fixed stride.
pub(crate) const SILHOUETTE_MAX_POINTS: usize = 5000;

#[cfg(test)]
mod tests {
    use super::*;

    /// Deterministic jittered blob of `n` points around `c`.
    fn blob(c: [f64; 2], n: usize, seed: u64) -> Vec<[f64; 2]> {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        (0..n)
            .map(|_| {
                [
                    c[0] + rng.random::<f64>() - 0.5,
                    c[1] + rng.random::<f64>() - 0.5,
                ]
            })
            .collect()
    }

    #[test]
    fn recovers_two_separated_blobs_exactly() {
        let mut pts = blob([0.0, 0.0], 40, 1);
        pts.extend(blob([10.0, 5.0], 25, 2));
        for seed in 0..5 {
            let km = kmeans(&pts, 2, seed, 5).unwrap();
            // Larger blob first.
            assert!(km.assignment[..40].iter().all(|a| *a == 0), "seed {seed}");
            assert!(km.assignment[40..].iter().all(|a| *a == 1), "seed {seed}");
            assert!(km.centres[0][0].abs() < 0.2 && (km.centres[1][0] - 10.0).abs() < 0.2);
            let s = silhouette(&pts, &km.assignment, 2).unwrap();
            assert!(s > 0.9, "silhouette {s}");
        }
    }

    #[test]
    fn deterministic_for_a_seed() {
        let mut pts = blob([0.0, 0.0], 30, 3);
        pts.extend(blob([0.5, 0.5], 30, 4));
        let a = kmeans(&pts, 3, 42, 4).unwrap();
        let b = kmeans(&pts, 3, 42, 4).unwrap();
        assert_eq!(a, b);
    }

    #[test]
    fn silhouette_of_a_hand_computed_case() {
        // 1-D points 0, 1 | 4, 6.
        // s(0): a = 1, b = (4 + 6)/2 = 5 → 0.8;  s(1): a = 1, b = (3 + 5)/2 = 4 → 0.75
        // s(4): a = 2, b = (4 + 3)/2 = 3.5 → 1.5/3.5; s(6): a = 2, b = (6 + 5)/2 = 5.5 → 3.5/5.5
        let pts = [[0.0], [1.0], [4.0], [6.0]];
        let s = silhouette(&pts, &[0, 0, 1, 1], 2).unwrap();
        let want = (0.8 + 0.75 + 1.5 / 3.5 + 3.5 / 5.5) / 4.0;
        assert!((s - want).abs() < 1e-12, "{s} vs {want}");
        // A singleton scores 0: s(6) alone, s(0) = (3.5 - 1)/3.5... computed fully:
        let s = silhouette(&pts, &[0, 0, 0, 1], 2).unwrap();
        // s(0): a = (1+4)/2 = 2.5, b = 6 → 3.5/6; s(1): a = (1+3)/2 = 2, b = 5 → 0.6;
        // s(4): a = (4+3)/2 = 3.5, b = 2 → (2-3.5)/3.5; s(6) = 0.
        let want = (3.5 / 6.0 + 0.6 - 1.5 / 3.5 + 0.0) / 4.0;
        assert!((s - want).abs() < 1e-12, "{s} vs {want}");
        assert_eq!(silhouette(&pts, &[0, 0, 0, 0], 2), None);
    }

    #[test]
    fn too_few_points_or_duplicates() {
        assert!(kmeans(&[[1.0]], 2, 0, 3).is_none());
        let same = vec![[1.0, 1.0]; 6];
        let km = kmeans(&same, 2, 0, 3).unwrap();
        assert_eq!(km.inertia, 0.0);
    }
}
