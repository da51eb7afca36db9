//! k-means clustering of the failed samples (MODEL.md §8, Fig. S4).
//!
//! The failures (labels `collapse` and `stall`) are clustered on their
//! standardized (α, f_n, φ) with k-means: k-means++ starts from a ChaCha8
//! generator seeded with the scan seed, several restarts, the lowest inertia
//! wins, Lloyd iterations until no assignment changes. The result is
//! deterministic for a seed. Clusters are reported in original units, ordered
//! by size, with the silhouette score and the cross-table against the
//! mechanistic kind; a cluster is named by its dominant kind: "stiffness
//! collapse" (collapse) or "energy barrier" (stall).

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rtw_model::Label;
use serde::Serialize;

/// A k-means partition.
#[derive(Clone, Debug, PartialEq)]
pub struct KMeans<const D: usize> {
    pub centres: Vec<[f64; D]>,
    /// Cluster of each point.
    pub assignment: Vec<usize>,
    /// Sum of squared distances to the assigned centres.
    pub inertia: f64,
}

fn dist2<const D: usize>(a: &[f64; D], b: &[f64; D]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum()
}

/// Index and squared distance of the nearest centre (lowest index on ties).
fn nearest<const D: usize>(p: &[f64; D], centres: &[[f64; D]]) -> (usize, f64) {
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
pub fn kmeans<const D: usize>(
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
pub fn silhouette<const D: usize>(
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
pub const SILHOUETTE_MAX_POINTS: usize = 5000;

/// One failed sample.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Failure {
    /// Its row's `sample_id`, so a cluster member can be traced back to its sample.
    pub sample_id: u64,
    pub alpha: f64,
    pub f_n: f64,
    pub phi: f64,
    /// `collapse` or `stall`.
    pub label: Label,
}

/// One cluster of failures, in original units.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FailureCluster {
    /// "stiffness collapse", "energy barrier" or "mixed".
    pub name: String,
    pub size: usize,
    pub alpha: f64,
    #[serde(rename = "fn")]
    pub f_n: f64,
    pub phi: f64,
    /// Cross-table row: how many of its members collapsed / stalled.
    pub collapse: usize,
    pub stall: usize,
}

/// The clustering of a scan's failures.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FailureClusters {
    pub k: usize,
    pub failures: usize,
    pub clusters: Vec<FailureCluster>,
    /// Mean silhouette in the standardized space (`None`: fewer than 2 clusters).
    pub silhouette: Option<f64>,
    /// Inertia in the standardized space.
    pub inertia: f64,
    /// Cluster (index into `clusters`) of each failure, in the order given to
    /// [`cluster_failures`]; written by `cluster --assignments`, kept out of
    /// the summary JSON (one entry per failure).
    #[serde(skip)]
    pub assignment: Vec<usize>,
}

/// Clusters the failures on standardized (α, f_n, φ). `None` when there are
/// fewer failures than `k`.
pub fn cluster_failures(
    failures: &[Failure],
    k: usize,
    seed: u64,
    restarts: usize,
) -> Option<FailureClusters> {
    let raw: Vec<[f64; 3]> = failures.iter().map(|f| [f.alpha, f.f_n, f.phi]).collect();
    let n = raw.len() as f64;
    let mean: [f64; 3] = std::array::from_fn(|d| raw.iter().map(|p| p[d]).sum::<f64>() / n);
    let sd: [f64; 3] = std::array::from_fn(|d| {
        let v = raw.iter().map(|p| (p[d] - mean[d]).powi(2)).sum::<f64>() / n;
        if v > 0.0 { v.sqrt() } else { 1.0 }
    });
    let z: Vec<[f64; 3]> = raw
        .iter()
        .map(|p| std::array::from_fn(|d| (p[d] - mean[d]) / sd[d]))
        .collect();
    let km = kmeans(&z, k, seed, restarts)?;
    let stride = z.len().div_ceil(SILHOUETTE_MAX_POINTS).max(1);
    let (zs, az): (Vec<[f64; 3]>, Vec<usize>) = z
        .iter()
        .zip(&km.assignment)
        .step_by(stride)
        .map(|(p, a)| (*p, *a))
        .unzip();
    let silhouette = silhouette(&zs, &az, k);
    let clusters = km
        .centres
        .iter()
        .enumerate()
        .map(|(j, c)| {
            let members = || {
                failures
                    .iter()
                    .zip(&km.assignment)
                    .filter(move |(_, a)| **a == j)
            };
            let collapse = members()
                .filter(|(f, _)| f.label == Label::Collapse)
                .count();
            let stall = members().filter(|(f, _)| f.label == Label::Stall).count();
            let name = match collapse.cmp(&stall) {
                std::cmp::Ordering::Greater => "stiffness collapse",
                std::cmp::Ordering::Less => "energy barrier",
                std::cmp::Ordering::Equal => "mixed",
            };
            let orig: [f64; 3] = std::array::from_fn(|d| c[d] * sd[d] + mean[d]);
            FailureCluster {
                name: name.into(),
                size: members().count(),
                alpha: orig[0],
                f_n: orig[1],
                phi: orig[2],
                collapse,
                stall,
            }
        })
        .collect();
    Some(FailureClusters {
        k,
        failures: failures.len(),
        clusters,
        silhouette,
        inertia: km.inertia,
        assignment: km.assignment,
    })
}

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

    #[test]
    fn names_clusters_by_dominant_kind_in_original_units() {
        let mut failures = Vec::new();
        let mut rng = ChaCha8Rng::seed_from_u64(9);
        for i in 0..30 {
            // Small α with low f_n: collapses (one stall among them).
            failures.push(Failure {
                sample_id: i,
                alpha: 0.02 + 0.05 * rng.random::<f64>(),
                f_n: 1.6 + 0.5 * rng.random::<f64>(),
                phi: 0.1 + 0.15 * rng.random::<f64>(),
                label: if i == 0 {
                    Label::Stall
                } else {
                    Label::Collapse
                },
            });
        }
        for i in 30..50 {
            // Any α, high f_n, small φ: stalls.
            failures.push(Failure {
                sample_id: i,
                alpha: 0.4 * rng.random::<f64>(),
                f_n: 3.5 + 1.5 * rng.random::<f64>(),
                phi: 0.05 + 0.02 * rng.random::<f64>(),
                label: Label::Stall,
            });
        }
        let fc = cluster_failures(&failures, 2, 1, 10).unwrap();
        assert_eq!(fc.failures, 50);
        let c0 = &fc.clusters[0];
        assert_eq!(
            (c0.name.as_str(), c0.size, c0.collapse, c0.stall),
            ("stiffness collapse", 30, 29, 1)
        );
        let c1 = &fc.clusters[1];
        assert_eq!(
            (c1.name.as_str(), c1.size, c1.collapse, c1.stall),
            ("energy barrier", 20, 0, 20)
        );
        assert!(c0.alpha < 0.07 && c0.f_n < 2.1, "{c0:?}");
        assert!(c1.phi < 0.07 && c1.f_n > 3.5, "{c1:?}");
        assert!(fc.silhouette.unwrap() > 0.4);
        // The assignment follows the input order: the 30 collapses' blob is cluster 0.
        assert_eq!(fc.assignment.len(), 50);
        assert!(fc.assignment[..30].iter().all(|a| *a == 0));
        assert!(fc.assignment[30..].iter().all(|a| *a == 1));
        assert!(cluster_failures(&failures[..1], 2, 1, 10).is_none());
    }
}
