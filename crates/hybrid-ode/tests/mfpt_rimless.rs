//! The MFPT estimator (`hybrid_ode::metastable`) against the rimless wheel
//! on stochastic terrain, whose mean first-passage time is known
//! independently: Byl and Tedrake's Markov chain ("Metastable walking
//! machines", IJRR 28(8), 2009) on the one-dimensional post-impact state.
//!
//! **The walker.** McGeer's 12-spoke wheel (`src/rimless.rs`, l = 1 m,
//! g = 9.81 m/s²) whose every step is on a slope of its own,
//! `γ ~ N(γ₀, σ²)` with `γ₀ = 0.08` rad, drawn afresh each step. Its state
//! at a step is the post-impact rate `ω`; the step passes the apex only
//! when `ω² > 2 (g/l)(1 − cos(α − γ))` (otherwise it rolls back: the fall),
//! and then `ω' = cos 2α · sqrt(ω² + 4 (g/l) sin α sin γ)` (the closed form).
//!
//! **The reference chain.** The post-impact rate on a mesh of cells; the
//! mass a cell sends to another is the probability of the slopes that map
//! it there, `Φ` of the slope bounds of the destination cell's edges
//! (`ω'` increases with `γ`), averaged over 4 Gauss–Legendre points of the
//! source cell; what rolls back is absorbed. The MFPT from the chain's
//! quasi-stationary regime is `1/(1 − λ)`, `λ` the dominant eigenvalue of
//! the substochastic matrix `Q` (power iteration), the quantity the
//! estimator estimates; from a given start, `m = (I − Q)⁻¹ 1`.

use hybrid_ode::metastable::{FallRate, MfptOptions, Rng, Walker, mfpt};
use hybrid_ode::rimless::RimlessWheel;
use hybrid_ode::splitting::{SplitOptions, split};

const L: f64 = 1.0;
const G: f64 = 9.81;
const GAMMA0: f64 = 0.08;
/// Twelve spokes: the impact keeps `cos² 2α = 0.75` of a deviation per
/// step, so a slow wheel stays slow for several steps and its falls build
/// up over steps (with 8 spokes they are mostly one unlucky slope).
const SPOKES: u32 = 12;

/// The wheel on per-step random slopes of standard deviation `sigma`.
struct Rough {
    sigma: f64,
}

impl Rough {
    fn wheel(gamma: f64) -> RimlessWheel {
        RimlessWheel::with_spokes(SPOKES, L, gamma, G)
    }

    /// The gait on the mean slope: McGeer's fixed point.
    fn omega_star() -> f64 {
        Self::wheel(GAMMA0).omega_star()
    }
}

impl Walker for Rough {
    type State = f64;
    fn step(&self, omega: &f64, rng: &mut Rng) -> Option<f64> {
        let gamma = GAMMA0 + self.sigma * rng.normal();
        Self::wheel(gamma).step_map_closed_form(*omega)
    }
    /// Slower than the gait is closer to rolling back.
    fn score(&self, omega: &f64) -> f64 {
        (Self::omega_star() - omega) / Self::omega_star()
    }
}

/// `erfc` (Numerical Recipes' Chebyshev fit, relative error below 1.2e-7
/// everywhere, so tail probabilities keep their digits).
fn erfc(x: f64) -> f64 {
    let z = x.abs();
    let t = 1.0 / (1.0 + 0.5 * z);
    let r = t
        * (-z * z - 1.265_512_23
            + t * (1.000_023_68
                + t * (0.374_091_96
                    + t * (0.096_784_18
                        + t * (-0.186_288_06
                            + t * (0.278_868_07
                                + t * (-1.135_203_98
                                    + t * (1.488_515_87
                                        + t * (-0.822_152_23 + t * 0.170_872_77)))))))))
            .exp();
    if x >= 0.0 { r } else { 2.0 - r }
}

/// The standard normal distribution function.
fn phi(x: f64) -> f64 {
    0.5 * erfc(-x / std::f64::consts::SQRT_2)
}

/// The chain on `n` cells of `[lo, hi]` (the mass below `lo` lumped into
/// the bottom cell, above `hi` into the top one): each row of `Q` as the
/// first column it reaches and its entries from there, and each cell's
/// probability of rolling back.
struct Chain {
    lo: f64,
    h: f64,
    rows: Vec<(usize, Vec<f64>)>,
    fall: Vec<f64>,
}

fn chain(sigma: f64, n: usize, lo: f64, hi: f64) -> Chain {
    let w = Rough::wheel(GAMMA0);
    let (c, k) = (w.impact_ratio(), 4.0 * (G / L) * w.alpha.sin());
    let alpha = w.alpha;
    let h = (hi - lo) / n as f64;
    let cdf = |gamma: f64| phi((gamma - GAMMA0) / sigma);
    // Gauss–Legendre on [-1, 1], 4 points.
    let gl = [
        (-0.861_136_311_594_053, 0.347_854_845_137_454),
        (-0.339_981_043_584_856, 0.652_145_154_862_546),
        (0.339_981_043_584_856, 0.652_145_154_862_546),
        (0.861_136_311_594_053, 0.347_854_845_137_454),
    ];
    let mut rows = Vec::with_capacity(n);
    let mut fall = vec![0.0; n];
    for (i, fall_i) in fall.iter_mut().enumerate() {
        let mut row = vec![0.0; n];
        for (x, wt) in gl {
            let omega = lo + h * (i as f64 + 0.5 + 0.5 * x);
            // The slopes that pass the apex: γ > α − acos(1 − ω² l / 2g).
            let arg = 1.0 - omega * omega * L / (2.0 * G);
            let f_fall = if arg <= -1.0 {
                0.0
            } else {
                cdf(alpha - arg.acos())
            };
            *fall_i += 0.5 * wt * f_fall;
            // The slope that lands on `ω' = e`.
            let slope_to = |e: f64| {
                (((e / c).powi(2) - omega * omega) / k)
                    .clamp(-1.0, 1.0)
                    .asin()
            };
            // No mass lands below the slope 40 σ under the mean: start at
            // the cell it maps to, and stop once the distribution is 1.
            let steepest_down = (GAMMA0 - 40.0 * sigma).max(-std::f64::consts::FRAC_PI_2);
            let from = c * (omega * omega + k * steepest_down.sin()).max(0.0).sqrt();
            let j0 = (((from - lo) / h).floor().max(0.0) as usize).min(n - 1);
            let mut below = f_fall;
            for (j, r) in row.iter_mut().enumerate().skip(j0) {
                let upper = if j + 1 == n {
                    1.0
                } else {
                    cdf(slope_to(lo + h * (j + 1) as f64)).max(below)
                };
                *r += 0.5 * wt * (upper - below);
                below = upper;
                if below == 1.0 {
                    break;
                }
            }
        }
        let first = row.iter().position(|&v| v > 0.0).unwrap_or(0);
        let last = row.iter().rposition(|&v| v > 0.0).map_or(first, |l| l + 1);
        rows.push((first, row[first..last].to_vec()));
    }
    Chain { lo, h, rows, fall }
}

impl Chain {
    /// The MFPT from the quasi-stationary regime, `1/(1 − λ)`: the QSD `ν`
    /// by power iteration on `ν Q`, and `1 − λ = ν·fall / ν·1`.
    fn qsd_mfpt(&self) -> f64 {
        let n = self.rows.len();
        let mut v = vec![1.0 / n as f64; n];
        for _ in 0..400 {
            let mut w = vec![0.0; n];
            for (vi, (first, row)) in v.iter().zip(&self.rows) {
                for (wj, q) in w[*first..].iter_mut().zip(row) {
                    *wj += vi * q;
                }
            }
            let s: f64 = w.iter().sum();
            v = w.iter().map(|x| x / s).collect();
        }
        1.0 / v.iter().zip(&self.fall).map(|(a, b)| a * b).sum::<f64>()
    }

    /// The MFPT from `omega`: `m = 1 + Q m` iterated `iters` times (it
    /// converges as `λ^iters`).
    fn mfpt_from(&self, omega: f64, iters: usize) -> f64 {
        let n = self.rows.len();
        let mut m = vec![0.0; n];
        for _ in 0..iters {
            m = self
                .rows
                .iter()
                .map(|(first, row)| {
                    1.0 + row
                        .iter()
                        .zip(&m[*first..])
                        .map(|(a, b)| a * b)
                        .sum::<f64>()
                })
                .collect();
        }
        m[(((omega - self.lo) / self.h) as usize).min(n - 1)]
    }
}

/// The mesh's top: McGeer's fixed point on a slope 8 σ steeper than the
/// mean, 1.5 times over.
fn omega_max(sigma: f64) -> f64 {
    1.5 * Rough::wheel(GAMMA0 + 8.0 * sigma).omega_star()
}

/// The chain on 2000 cells of `[0.3, omega_max]` rad/s.
fn reference(sigma: f64) -> Chain {
    chain(sigma, 2000, 0.3, omega_max(sigma))
}

/// Three roughnesses whose MFPT spans 10 to 1.5e5 steps: the estimator's
/// 95 % interval holds the chain's MFPT, and is at most a factor 5 wide
/// (1.3, 1.6 and 2.4 here, in 89 000, 104 000 and 171 000 steps: the cost
/// grows with `log(MFPT)`).
#[test]
fn the_estimator_s_mfpt_is_the_chain_s_at_three_roughnesses() {
    for sigma in [0.3, 0.08, 0.04] {
        let exact = reference(sigma).qsd_mfpt();
        let o = MfptOptions {
            seed: 1,
            replicas: 100,
            sample_steps: 50,
            ..MfptOptions::default()
        };
        let m = mfpt(&Rough { sigma }, &Rough::omega_star(), &o).unwrap();
        let (lo, hi) = m.qsd_interval();
        eprintln!(
            "sigma {sigma}: chain {exact:.4e}, estimator {:.4e} [{lo:.4e}, {hi:.4e}] in {} steps",
            1.0 / m.fall_rate,
            m.steps
        );
        assert!(
            lo <= exact && exact <= hi,
            "sigma {sigma}: chain {exact} vs {m:?}"
        );
        assert!(hi / lo < 5.0, "sigma {sigma}: {m:?}");
        if sigma == 0.3 {
            // From the start too, where the chain's m(ω*) is cheap.
            let from = reference(sigma).mfpt_from(Rough::omega_star(), 1000);
            eprintln!(
                "  from omega*: chain {from:.4}, estimator {:.4} [{:.4}, {:.4}]",
                m.mfpt, m.lo, m.hi
            );
            assert!(
                m.lo <= from && from <= m.hi,
                "chain m(omega*) {from} vs {m:?}"
            );
        }
    }
}

/// The counting estimator (the RTW's: the Fleming–Viot cloud's falls over
/// its walker-steps) at the same three roughnesses, at the RTW's budget
/// per batch (16 walkers through 60 steps of burn-in, their 32 copies
/// through 60 counted steps) with more batches: the interval
/// holds the chain's MFPT; closed where the falls are many (σ = 0.3,
/// 0.08), a lower bound of the right order where the MFPT is far beyond
/// the walker-steps counted (σ = 0.04, 1.5e5 against 38 400).
#[test]
fn counting_the_falls_gives_the_chain_s_mfpt_or_a_lower_bound_of_it() {
    for sigma in [0.3, 0.08, 0.04] {
        let exact = reference(sigma).qsd_mfpt();
        let o = MfptOptions {
            fall_rate: FallRate::Counting,
            seed: 1,
            batches: 20,
            replicas: 32,
            burn_in_copies: 2,
            burn_in: 60,
            sample_steps: 60,
            ..MfptOptions::default()
        };
        let m = mfpt(&Rough { sigma }, &Rough::omega_star(), &o).unwrap();
        let (lo, hi) = m.qsd_interval();
        eprintln!(
            "sigma {sigma}: chain {exact:.4e}, counting {:.4e} [{lo:.4e}, {hi:.4e}] in {} steps",
            1.0 / m.fall_rate,
            m.steps
        );
        assert!(
            lo <= exact && exact <= hi,
            "sigma {sigma}: chain {exact} vs {m:?}"
        );
        if sigma >= 0.08 {
            assert!(hi / lo < 2.0, "sigma {sigma}: {m:?}");
        } else {
            assert!(lo > 38_400.0 / 20.0, "sigma {sigma}: {m:?}");
        }
    }
}

/// The chain is converged in its mesh: half the cells move the MFPT by
/// less than 1 %, at each roughness.
#[test]
fn the_chain_is_converged_in_its_mesh() {
    for sigma in [0.3, 0.08, 0.04] {
        let fine = reference(sigma).qsd_mfpt();
        let coarse = chain(sigma, 1000, 0.3, omega_max(sigma)).qsd_mfpt();
        eprintln!("sigma {sigma}: 2000 cells {fine:.6e}, 1000 cells {coarse:.6e}");
        assert!(
            (fine - coarse).abs() < 0.01 * fine,
            "sigma {sigma}: {fine} vs {coarse}"
        );
    }
}

/// The chain itself against plain Monte Carlo to the fall (no cap) where
/// that is cheap, σ = 0.3: the mean steps to fall from McGeer's fixed
/// point, 20000 walks, within 3 standard errors of the chain's `m(ω*)`.
#[test]
fn the_chain_is_plain_monte_carlo_where_falls_are_frequent() {
    let sigma = 0.3;
    let walker = Rough { sigma };
    let mut rng = Rng::new(7);
    let trials = 20_000;
    let walks: Vec<f64> = (0..trials)
        .map(|_| {
            let (mut omega, mut steps) = (Rough::omega_star(), 0.0);
            loop {
                steps += 1.0;
                match walker.step(&omega, &mut rng) {
                    Some(next) => omega = next,
                    None => return steps,
                }
            }
        })
        .collect();
    let n = trials as f64;
    let mean = walks.iter().sum::<f64>() / n;
    let se = (walks.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0) / n).sqrt();
    let chain_m = reference(sigma).mfpt_from(Rough::omega_star(), 1000);
    eprintln!("sigma {sigma}: chain m(omega*) {chain_m:.4}, Monte Carlo {mean:.4} ± {se:.4}");
    assert!(
        (mean - chain_m).abs() < 3.0 * se,
        "{mean} ± {se} vs {chain_m}"
    );
}

/// The splitting (`hybrid_ode::splitting`: excursions from the slowest
/// half's complement, MFPT by renewal at the returns) at three roughnesses
/// whose chain MFPTs are about 1.3e2, 1.5e5 and 2.4e8: its 95 % interval
/// holds the chain's MFPT and is at most a factor 3 wide, at a cost that
/// grows with `log(MFPT)` (each batch's iterations at most about
/// `N ln(1/p)`; fewer where copies tie and are killed together).
#[test]
fn the_splitting_s_mfpt_is_the_chain_s_up_to_1e8() {
    let mut costs = Vec::new();
    for sigma in [0.08, 0.04, 0.03] {
        let exact = reference(sigma).qsd_mfpt();
        let o = SplitOptions {
            seed: 2,
            replicas: 400,
            ..SplitOptions::default()
        };
        let s = split(&Rough { sigma }, &Rough::omega_star(), &o).unwrap();
        let (lo, hi) = s.mfpt_a_interval;
        let iterations: usize = s.batches.iter().map(|b| b.iterations()).sum();
        eprintln!(
            "sigma {sigma}: chain {exact:.4e}, splitting {:.4e} [{lo:.4e}, {hi:.4e}], p {:.3e}, \
             E[T|returned] {:.3}, E[T|fell] {:.3}, {} steps, {iterations} iterations, ancestors {:?}",
            s.mfpt_a,
            s.p,
            s.returned_steps,
            s.fall_steps,
            s.steps,
            s.batches.iter().map(|b| b.ancestors).collect::<Vec<_>>()
        );
        assert!(
            lo <= exact && exact <= hi,
            "sigma {sigma}: chain {exact} vs [{lo}, {hi}]"
        );
        assert!(hi / lo < 20.0, "sigma {sigma}: [{lo}, {hi}]");
        // No batch's iterations much beyond N ln(1/p̂): the levels climb
        // by a factor 1 − 1/N of probability at least, each.
        for b in &s.batches {
            let expected = o.replicas as f64 * (1.0 / b.p).ln();
            let it = b.iterations() as f64;
            assert!(
                it < 1.5 * expected,
                "sigma {sigma}: {it} iterations for p {}",
                b.p
            );
        }
        costs.push(s.steps as f64);
    }
    // Six decades of MFPT for less than 10 times the steps.
    assert!(costs[2] < 10.0 * costs[0], "{costs:?}");
}

/// The chain at σ = 0.03 (MFPT 2.4e8) is converged in its mesh too: half
/// the cells move it by less than 1 %.
#[test]
fn the_chain_is_converged_at_the_splitting_s_smallest_roughness() {
    let fine = reference(0.03).qsd_mfpt();
    let coarse = chain(0.03, 1000, 0.3, omega_max(0.03)).qsd_mfpt();
    assert!((fine - coarse).abs() < 0.01 * fine, "{fine} vs {coarse}");
}

/// More replicas, smaller error: at σ = 0.04 the batches' `p̂` spread
/// (their coefficient of variation, about `sqrt(ln(1/p)/N)` for a good
/// score) and the interval's width shrink from 25 to 400 replicas, and both
/// intervals hold the chain's MFPT.
#[test]
fn the_splitting_s_error_shrinks_with_replicas() {
    let sigma = 0.04;
    let exact = reference(sigma).qsd_mfpt();
    let run = |replicas| {
        let o = SplitOptions {
            seed: 5,
            replicas,
            batches: 16,
            ..SplitOptions::default()
        };
        let s = split(&Rough { sigma }, &Rough::omega_star(), &o).unwrap();
        let ps: Vec<f64> = s.batches.iter().map(|b| b.p).collect();
        let var = ps.iter().map(|p| (p - s.p).powi(2)).sum::<f64>() / (ps.len() - 1) as f64;
        let (lo, hi) = s.mfpt_a_interval;
        eprintln!(
            "N {replicas}: splitting {:.4e} [{lo:.4e}, {hi:.4e}] (chain {exact:.4e}), \
             cv of p {:.3}, error {:.3}",
            s.mfpt_a,
            var.sqrt() / s.p,
            (s.mfpt_a - exact).abs() / exact
        );
        assert!(
            lo <= exact && exact <= hi,
            "N {replicas}: {exact} vs [{lo}, {hi}]"
        );
        (var.sqrt() / s.p, hi / lo)
    };
    let (cv_small, width_small) = run(25);
    let (cv_large, width_large) = run(400);
    // Theory: 4 times smaller for 16 times the replicas.
    assert!(cv_large < cv_small / 2.0, "{cv_small} -> {cv_large}");
    assert!(width_large < width_small, "{width_small} -> {width_large}");
}
