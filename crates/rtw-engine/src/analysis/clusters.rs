//! k-means clustering of the failed samples (docs/model.md §8, Fig. S4).
//!
//! The failures (labels `collapse` and `stall`) are clustered on their
//! standardized (α, f_n, φ) with k-means: k-means++ starts from a ChaCha8
//! generator seeded with the scan seed, several restarts, the lowest inertia
//! wins, Lloyd iterations until no assignment changes. The result is
//! deterministic for a seed. Clusters are reported in original units, ordered
//! by size, with the silhouette score and the cross-table against the
//! mechanistic kind; a cluster is named by its dominant kind: "stiffness
//! collapse" (collapse) or "energy barrier" (stall).
//!
//! So that memory does not grow with the scan, k-means sees at most
//! [`CLUSTER_MAX_POINTS`] failures: a [`FailureSample`] keeps a seeded,
//! deterministic random subset of them while the rows stream past. When
//! there are more, every failure is then counted in the cluster of its
//! nearest centre ([`FailureClusters::cluster_of`], [`ClusterTally`]), so
//! sizes and cross-table stay exact counts over all failures. With fewer
//! failures than the cap the sample is all of them and nothing changes.

use crate::analysis::kmeans::{SILHOUETTE_MAX_POINTS, kmeans, nearest, silhouette};
pub(crate) use crate::config::CLUSTER_MAX_POINTS;
use crate::hash::mix;
use rtw_model::Label;
use serde::Serialize;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// One failed sample.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Failure {
    /// Its row's `sample_id`, so a cluster member can be traced back to its sample.
    pub(crate) sample_id: u64,
    pub(crate) alpha: f64,
    pub(crate) f_n: f64,
    pub(crate) phi: f64,
    /// `collapse` or `stall`.
    pub(crate) label: Label,
}

/// A failure with its sampling key; ordered by key.
#[derive(Clone, Copy, Debug)]
struct Keyed {
    key: u64,
    failure: Failure,
}

impl PartialEq for Keyed {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}
impl Eq for Keyed {}
impl PartialOrd for Keyed {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Keyed {
    fn cmp(&self, other: &Self) -> Ordering {
        (self.key, self.failure.sample_id).cmp(&(other.key, other.failure.sample_id))
    }
}

/// A bounded random sample of a scan's failures, built while its rows
/// stream past (bottom-k sampling): each failure gets a pseudo-random key
/// that depends only on (seed, sample_id), and the `cap` failures with the
/// smallest keys are kept. The sample is thus uniform, deterministic for a
/// seed, and the same whatever order the rows come in; memory is `cap`
/// failures however many there are.
#[derive(Clone, Debug)]
pub(crate) struct FailureSample {
    cap: usize,
    seed_key: u64,
    seen: usize,
    /// Max-heap on the key: the top is the first to go.
    kept: BinaryHeap<Keyed>,
}

impl FailureSample {
    /// An empty sample of at most `cap` failures (at least one).
    pub(crate) fn new(cap: usize, seed: u64) -> Self {
        let cap = cap.max(1);
        Self {
            cap,
            seed_key: mix(seed),
            seen: 0,
            kept: BinaryHeap::with_capacity(cap.min(4096)),
        }
    }

    /// Offers one failure.
    pub(crate) fn push(&mut self, failure: Failure) {
        self.seen += 1;
        // mix is a bijection, so distinct sample_ids get distinct keys.
        let key = mix(self.seed_key ^ mix(failure.sample_id));
        let keyed = Keyed { key, failure };
        if self.kept.len() < self.cap {
            self.kept.push(keyed);
        } else if self.kept.peek().is_some_and(|top| keyed < *top) {
            self.kept.pop();
            self.kept.push(keyed);
        }
    }

    /// Failures offered so far (all of the scan's once it has been read).
    pub(crate) fn seen(&self) -> usize {
        self.seen
    }

    /// Whether some failures were left out (more were offered than fit).
    pub(crate) fn is_subset(&self) -> bool {
        self.seen > self.kept.len()
    }

    /// The kept failures in `sample_id` order (all of them when they fit).
    pub(crate) fn points(&self) -> Vec<Failure> {
        let mut v: Vec<Failure> = self.kept.iter().map(|k| k.failure).collect();
        v.sort_by_key(|f| f.sample_id);
        v
    }
}

/// One cluster of failures, in original units.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub(crate) struct FailureCluster {
    /// "stiffness collapse", "energy barrier" or "mixed".
    pub(crate) name: String,
    pub(crate) size: usize,
    pub(crate) alpha: f64,
    #[serde(rename = "fn")]
    pub(crate) f_n: f64,
    pub(crate) phi: f64,
    /// Cross-table row: how many of its members collapsed / stalled.
    pub(crate) collapse: usize,
    pub(crate) stall: usize,
}

/// Members per cluster and kind: what sizes, cross-table and names are made of.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct ClusterTally {
    collapse: Vec<usize>,
    stall: Vec<usize>,
}

impl ClusterTally {
    pub(crate) fn new(k: usize) -> Self {
        Self {
            collapse: vec![0; k],
            stall: vec![0; k],
        }
    }

    /// Counts one failure (`collapse` or `stall`) in `cluster`.
    pub(crate) fn add(&mut self, cluster: usize, label: Label) {
        match label {
            Label::Collapse => self.collapse[cluster] += 1,
            Label::Stall => self.stall[cluster] += 1,
            _ => {}
        }
    }
}

/// The standardization of (α, f_n, φ) a clustering was made in.
#[derive(Clone, Debug, PartialEq)]
struct Standardization {
    mean: [f64; 3],
    sd: [f64; 3],
}

impl Standardization {
    fn of(raw: &[[f64; 3]]) -> Self {
        let n = raw.len() as f64;
        let mean: [f64; 3] = std::array::from_fn(|d| raw.iter().map(|p| p[d]).sum::<f64>() / n);
        let sd: [f64; 3] = std::array::from_fn(|d| {
            let v = raw.iter().map(|p| (p[d] - mean[d]).powi(2)).sum::<f64>() / n;
            if v > 0.0 { v.sqrt() } else { 1.0 }
        });
        Self { mean, sd }
    }

    fn z(&self, f: &Failure) -> [f64; 3] {
        let p = [f.alpha, f.f_n, f.phi];
        std::array::from_fn(|d| (p[d] - self.mean[d]) / self.sd[d])
    }
}

/// The clustering of a scan's failures.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FailureClusters {
    pub(crate) k: usize,
    /// Every failure of the scan; sizes and cross-table count them all.
    pub(crate) failures: usize,
    /// How many failures k-means ran on, when that is a random sample
    /// ([`FailureSample`]) rather than all of them; absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(crate) clustered: Option<usize>,
    pub(crate) clusters: Vec<FailureCluster>,
    /// Mean silhouette in the standardized space (`None`: fewer than 2 clusters).
    pub(crate) silhouette: Option<f64>,
    /// Inertia in the standardized space (of the clustered failures).
    pub(crate) inertia: f64,
    /// Cluster (index into `clusters`) of each clustered failure, in the
    /// order given to [`cluster_failures`]; written by `cluster
    /// --assignments`, kept out of the summary JSON (one entry per failure).
    #[serde(skip)]
    pub(crate) assignment: Vec<usize>,
    #[serde(skip)]
    scale: Standardization,
    /// The centres in standardized units, in `clusters` order.
    #[serde(skip)]
    centres_z: Vec<[f64; 3]>,
}

impl FailureClusters {
    /// The cluster of any failure: the nearest centre in the standardized
    /// space k-means worked in. For a clustered failure this is its
    /// assignment whenever Lloyd's iterations converged (they stop when no
    /// point changes cluster), which is why a scan whose failures all fit in
    /// the sample keeps k-means' own assignment instead.
    pub(crate) fn cluster_of(&self, f: &Failure) -> usize {
        nearest(&self.scale.z(f), &self.centres_z).0
    }

    /// Sets sizes, cross-table and names from `tally`, the members of every
    /// one of the scan's `failures` (of which `clustered` went into k-means).
    pub(crate) fn set_counts(&mut self, tally: &ClusterTally, failures: usize, clustered: usize) {
        for (j, c) in self.clusters.iter_mut().enumerate() {
            let (collapse, stall) = (tally.collapse[j], tally.stall[j]);
            c.name = match collapse.cmp(&stall) {
                Ordering::Greater => "stiffness collapse",
                Ordering::Less => "energy barrier",
                Ordering::Equal => "mixed",
            }
            .into();
            c.size = collapse + stall;
            c.collapse = collapse;
            c.stall = stall;
        }
        self.failures = failures;
        self.clustered = (clustered < failures).then_some(clustered);
    }
}

/// Clusters the failures on standardized (α, f_n, φ). `None` when there are
/// fewer failures than `k`.
pub(crate) fn cluster_failures(
    failures: &[Failure],
    k: usize,
    seed: u64,
    restarts: usize,
) -> Option<FailureClusters> {
    let raw: Vec<[f64; 3]> = failures.iter().map(|f| [f.alpha, f.f_n, f.phi]).collect();
    let scale = Standardization::of(&raw);
    let z: Vec<[f64; 3]> = failures.iter().map(|f| scale.z(f)).collect();
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
        .map(|c| {
            let orig: [f64; 3] = std::array::from_fn(|d| c[d] * scale.sd[d] + scale.mean[d]);
            FailureCluster {
                name: String::new(),
                size: 0,
                alpha: orig[0],
                f_n: orig[1],
                phi: orig[2],
                collapse: 0,
                stall: 0,
            }
        })
        .collect();
    let mut tally = ClusterTally::new(k);
    for (f, a) in failures.iter().zip(&km.assignment) {
        tally.add(*a, f.label);
    }
    let mut fc = FailureClusters {
        k,
        failures: failures.len(),
        clustered: None,
        clusters,
        silhouette,
        inertia: km.inertia,
        assignment: km.assignment,
        scale,
        centres_z: km.centres,
    };
    fc.set_counts(&tally, failures.len(), failures.len());
    Some(fc)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;

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

    fn failure(sample_id: u64, label: Label, alpha: f64, f_n: f64, phi: f64) -> Failure {
        Failure {
            sample_id,
            alpha,
            f_n,
            phi,
            label,
        }
    }

    #[test]
    fn failure_sample_is_capped_deterministic_order_free_and_uniform() {
        let n = 10_000u64;
        let cap = 500;
        let all: Vec<Failure> = (0..n)
            .map(|i| failure(i, Label::Stall, 0.1, 2.0, 0.1))
            .collect();
        let sample = |seed: u64, order: &mut dyn Iterator<Item = &Failure>| {
            let mut s = FailureSample::new(cap, seed);
            order.for_each(|f| s.push(*f));
            s
        };
        let a = sample(7, &mut all.iter());
        assert_eq!(
            (a.seen(), a.points().len(), a.is_subset()),
            (10_000, cap, true)
        );
        let ids: Vec<u64> = a.points().iter().map(|f| f.sample_id).collect();
        assert!(ids.windows(2).all(|w| w[0] < w[1]), "sorted, no repeats");
        // The same failures whatever order they come in (shards, threads).
        let b = sample(7, &mut all.iter().rev());
        assert_eq!(a.points(), b.points());
        // Another seed, another sample (most of it).
        let c = sample(8, &mut all.iter());
        let common = c
            .points()
            .iter()
            .filter(|f| ids.binary_search(&f.sample_id).is_ok())
            .count();
        assert!(common < cap / 4, "{common} of {cap} in common");
        // Uniform: 500 of 0..9999 drawn without replacement have a mean id
        // of 4999.5 with standard deviation 2886.8 / √500 · √(1 − 500/10000)
        // = 125.8; allow 4σ.
        let mean = ids.iter().sum::<u64>() as f64 / cap as f64;
        assert!((mean - 4999.5).abs() < 4.0 * 125.8, "mean id {mean}");
        // When everything fits, the sample is every failure, in id order.
        let d = sample(7, &mut all[..300].iter().rev());
        assert!(!d.is_subset());
        assert_eq!(d.points(), all[..300].to_vec());
    }

    #[test]
    fn clustering_a_sample_counts_every_failure_exactly() {
        // Two separated blobs: 3000 collapses at small (α, f_n), 2000 stalls
        // (20 of them collapses) at large f_n and small φ. Interleaved ids.
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let mut all = Vec::new();
        for i in 0..5000u64 {
            let u: [f64; 3] = std::array::from_fn(|_| rng.random::<f64>());
            all.push(if i % 5 < 3 {
                failure(
                    i,
                    Label::Collapse,
                    0.02 + 0.05 * u[0],
                    1.6 + 0.5 * u[1],
                    0.1 + 0.15 * u[2],
                )
            } else {
                let label = if i % 250 == 4 {
                    Label::Collapse
                } else {
                    Label::Stall
                };
                failure(i, label, 0.4 * u[0], 3.5 + 1.5 * u[1], 0.05 + 0.02 * u[2])
            });
        }
        let mut sample = FailureSample::new(400, 3);
        all.iter().for_each(|f| sample.push(*f));
        let points = sample.points();
        let mut fc = cluster_failures(&points, 2, 3, 10).unwrap();
        assert_eq!((fc.failures, fc.clustered), (400, None));
        // Every clustered point's nearest centre is its k-means cluster.
        for (f, a) in points.iter().zip(&fc.assignment) {
            assert_eq!(fc.cluster_of(f), *a);
        }
        let mut tally = ClusterTally::new(2);
        all.iter()
            .for_each(|f| tally.add(fc.cluster_of(f), f.label));
        fc.set_counts(&tally, all.len(), points.len());
        assert_eq!((fc.failures, fc.clustered), (5000, Some(400)));
        let c = &fc.clusters;
        assert_eq!(
            (c[0].name.as_str(), c[0].size, c[0].collapse, c[0].stall),
            ("stiffness collapse", 3000, 3000, 0)
        );
        assert_eq!(
            (c[1].name.as_str(), c[1].size, c[1].collapse, c[1].stall),
            ("energy barrier", 2000, 20, 1980)
        );
        // The same counts as k-means on every failure.
        let full = cluster_failures(&all, 2, 3, 10).unwrap();
        let sizes = |fc: &FailureClusters| -> Vec<(usize, usize, usize)> {
            fc.clusters
                .iter()
                .map(|c| (c.size, c.collapse, c.stall))
                .collect()
        };
        assert_eq!(sizes(&fc), sizes(&full));
        // "clustered" is in the JSON only when k-means saw a sample.
        let json = serde_json::to_value(&fc).unwrap();
        assert_eq!(json["clustered"], 400);
        assert!(
            serde_json::to_value(&full)
                .unwrap()
                .get("clustered")
                .is_none()
        );
    }
}
