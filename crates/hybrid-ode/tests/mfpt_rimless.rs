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
use hybrid_ode::splitting::{SplitOptions, split};

mod rimless_reference;
use rimless_reference::{GAMMA0, Rough, chain, omega_max, reference};

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
