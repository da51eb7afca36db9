//! A step's input stratified in the halvings of each tail's mass
//! ([`super::ChainOptions::strata`]).

use super::{ChainWalker, Scale, Step, normal_cdf, undoomed};
use crate::metastable::Rng;

/// The `z` in `[a, b]` whose upper tail `Φ(−z)` is `t` (bisection: `Φ` is
/// monotone, and a tail of 10⁻¹² keeps its digits where `1 − Φ` would not).
fn upper_quantile(t: f64, mut a: f64, mut b: f64) -> f64 {
    for _ in 0..60 {
        let mid = 0.5 * (a + b);
        if normal_cdf(-mid) > t {
            a = mid;
        } else {
            b = mid;
        }
    }
    0.5 * (a + b)
}

/// One member's step, its input stratified in the halvings of each tail's
/// mass ([`ChainOptions::strata`]); `seed` draws the quantile in each.
pub(super) fn member_step_stratified<W: ChainWalker>(
    w: &W,
    s: &W::State,
    strata: usize,
    lookahead: usize,
    seed: u64,
    scale: &Scale,
    steps: &mut u64,
) -> Step {
    let mut rng = Rng::new(seed);
    rng.next_u64();
    let mut lands = Vec::new();
    let mut fall = 0.0;
    for sign in [1.0, -1.0] {
        for k in 0..strata {
            // Tail masses from `hi` down to `lo` (the last stratum: to 0).
            let hi = 0.5f64.powi(k as i32 + 1);
            let lo = if k + 1 == strata { 0.0 } else { hi * 0.5 };
            let m = hi - lo;
            let t = lo + m * rng.uniform();
            let z = sign * upper_quantile(t.max(f64::MIN_POSITIVE), 0.0, 40.0);
            match undoomed(w, s, z, lookahead, steps) {
                Some(next) => lands.push((m, scale.apply(&w.features(&next)))),
                None => fall += m,
            }
        }
    }
    Step { lands, fall }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A walker whose step falls exactly when its input exceeds `c`, or in
    /// the window `(a, b)` below it: a tail and a speckle of the doom set.
    struct Face {
        c: f64,
        a: f64,
        b: f64,
    }

    impl ChainWalker for Face {
        type State = f64;
        fn step_with(&self, s: &f64, z: f64) -> Option<f64> {
            (z <= self.c && !(self.a < z && z < self.b)).then_some(*s)
        }
        fn features(&self, s: &f64) -> Vec<f64> {
            vec![*s]
        }
    }

    #[test]
    fn the_upper_quantile_inverts_the_tail() {
        for z in [0.0, 0.7, 2.5, 5.0, 7.5] {
            let t = normal_cdf(-z);
            assert!((upper_quantile(t, 0.0, 40.0) - z).abs() < 1e-6, "{z}");
        }
    }

    /// The stratified input integrates a doom set of any shape without
    /// bias: over many seeds, the mean fall mass is the law's own mass of
    /// the set (closed form from `Φ`), a tail at 6 σ and a band inside 1 σ
    /// alike; Gauss–Hermite's nine nodes see neither band.
    #[test]
    fn the_stratified_input_integrates_a_tail_and_a_band() {
        let scale = Scale::of(&[vec![0.0], vec![1.0]]);
        for (c, a, b) in [(6.0, 10.0, 10.0), (40.0, 0.3, 0.6), (3.0, 1.2, 1.5)] {
            let w = Face { c, a, b };
            let exact = normal_cdf(-c) + (normal_cdf(b) - normal_cdf(a)).max(0.0);
            let n = 4000;
            let mut sum = 0.0;
            let mut sq = 0.0;
            let mut steps = 0;
            for seed in 0..n {
                let st = member_step_stratified(&w, &0.0, 40, 0, seed, &scale, &mut steps);
                let landed: f64 = st.lands.iter().map(|l| l.0).sum();
                assert!(
                    (landed + st.fall - 1.0).abs() < 1e-12,
                    "{landed} + {}",
                    st.fall
                );
                sum += st.fall;
                sq += st.fall * st.fall;
            }
            let mean = sum / n as f64;
            let se = ((sq / n as f64 - mean * mean).max(0.0) / n as f64).sqrt();
            eprintln!("c {c} band ({a}, {b}): {mean:.4e} ± {se:.1e} against {exact:.4e}");
            assert!(
                (mean - exact).abs() < 4.0 * se + 1e-3 * exact,
                "{mean} vs {exact}"
            );
        }
    }
}
