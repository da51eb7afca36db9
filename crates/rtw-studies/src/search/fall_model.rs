//! Where designs fall, learned from the designs evaluated so far: the
//! search's constraint model. A design is infeasible when it has no stable
//! slope (or none of the gait asked for) in the range, or the wrong gait at
//! the speed's slope. Rather than score such a design with a made-up bad
//! value, the search asks this model how likely a candidate is to be
//! infeasible before it spends a profile on it, and draws again when the
//! neighbours it has seen mostly fell.
//!
//! The model is a k-nearest-neighbour vote in the unit box, with a uniform
//! Beta(1, 1) prior: p = (1 + infeasible neighbours) / (2 + neighbours),
//! counting only the `K` nearest within `RADIUS`. Far from every evaluated
//! design it knows nothing (p = ½) and does not stand in the way. Fall
//! regions of the paper's box are wide and contiguous (docs/model.md §8,
//! the failure clusters), which a local vote learns in a few dozen designs.

/// Neighbours that vote.
pub(crate) const K: usize = 7;
/// Farthest neighbour that votes, in the unit box (a tenth of its diagonal
/// in four inputs is 0.2).
pub(crate) const RADIUS: f64 = 0.25;

/// The evaluated designs, each with whether it was infeasible.
#[derive(Clone, Debug, Default)]
pub(crate) struct FallModel {
    points: Vec<(Vec<f64>, bool)>,
}

impl FallModel {
    /// Learns one more evaluated design `u` (unit box).
    pub(crate) fn add(&mut self, u: Vec<f64>, infeasible: bool) {
        self.points.push((u, infeasible));
    }

    /// The probability that a design at `u` is infeasible.
    pub(crate) fn p_infeasible(&self, u: &[f64]) -> f64 {
        let mut near: Vec<(f64, bool)> = self
            .points
            .iter()
            .map(|(p, f)| {
                let d2: f64 = p.iter().zip(u).map(|(a, b)| (a - b) * (a - b)).sum();
                (d2, *f)
            })
            .filter(|(d2, _)| *d2 <= RADIUS * RADIUS)
            .collect();
        near.sort_by(|a, b| a.0.total_cmp(&b.0));
        near.truncate(K);
        let bad = near.iter().filter(|(_, f)| *f).count();
        (1.0 + bad as f64) / (2.0 + near.len() as f64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn it_knows_nothing_far_away_and_learns_a_region_that_falls() {
        let mut m = FallModel::default();
        assert_eq!(m.p_infeasible(&[0.5, 0.5]), 0.5);
        // Designs with x < 0.4 fall, the others do not.
        for i in 0..20 {
            for j in 0..20 {
                let u = vec![(i as f64 + 0.5) / 20.0, (j as f64 + 0.5) / 20.0];
                let falls = u[0] < 0.4;
                m.add(u, falls);
            }
        }
        // Deep inside either region the K nearest agree: 8/9 and 1/9.
        assert_eq!(m.p_infeasible(&[0.1, 0.5]), 8.0 / 9.0);
        assert_eq!(m.p_infeasible(&[0.9, 0.5]), 1.0 / 9.0);
        // Outside the box, beyond RADIUS of every design: the prior.
        assert_eq!(m.p_infeasible(&[2.0, 2.0]), 0.5);
    }
}
