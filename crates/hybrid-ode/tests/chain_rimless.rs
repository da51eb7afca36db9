//! The chain estimator (`hybrid_ode::chain`) against the rimless wheel on
//! stochastic terrain, whose MFPT is known independently: the fine 1-D
//! chain of `rimless_reference` (2000 cells, the slope's law integrated
//! exactly over each destination cell).
//!
//! Two walkers of the same wheel (12 spokes, slope `γ ~ N(0.08, σ²)` each
//! step): `Plain`, whose state is the post-impact rate `ω` and whose step
//! draws its own slope, and `Ahead`, whose state is the *extended* one,
//! `(ω, γ_next)`: the slope of its next step is already laid, and a step
//! lays the one after (the RTW's case, where a fall is decided by the
//! ground already in reach). Both are the same Markov chain of `ω`, so
//! both have the reference's MFPT; `Ahead` falls a step after the input
//! that dooms it, which the chain's one-step lookahead sees.

use hybrid_ode::chain::{ChainMfpt, ChainOptions, ChainWalker, chain_mfpt, qsd_cloud};
use hybrid_ode::metastable::Rng;

mod rimless_reference;
use rimless_reference::{GAMMA0, Rough, reference};

/// The state is `ω`; the step's slope is its input.
struct Plain {
    sigma: f64,
}

impl ChainWalker for Plain {
    type State = f64;
    fn step_with(&self, omega: &f64, z: f64) -> Option<f64> {
        Rough::wheel(GAMMA0 + self.sigma * z).step_map_closed_form(*omega)
    }
    fn features(&self, omega: &f64) -> Vec<f64> {
        vec![*omega]
    }
}

/// The state is `(ω, γ_next)`; the input is the slope after next.
struct Ahead {
    sigma: f64,
}

impl ChainWalker for Ahead {
    type State = (f64, f64);
    fn step_with(&self, s: &(f64, f64), z: f64) -> Option<(f64, f64)> {
        let omega = Rough::wheel(s.1).step_map_closed_form(s.0)?;
        Some((omega, GAMMA0 + self.sigma * z))
    }
    fn features(&self, s: &(f64, f64)) -> Vec<f64> {
        vec![s.0, s.1]
    }
}

/// The chain's estimate for `walker`, its cells sampled by a Fleming–Viot
/// cloud of `cloud` (the same wheel, possibly rougher).
fn estimate<W: ChainWalker>(walker: &W, cloud: &W, start: W::State, o: &ChainOptions) -> ChainMfpt {
    let mut steps = 0;
    let sample = qsd_cloud(cloud, &start, 100, 30, 40, &mut Rng::new(5), &mut steps).unwrap();
    chain_mfpt(walker, &sample, o).unwrap()
}

/// The chain's MFPT, and the reference's, agree within `tol` (relative).
fn close(sigma: f64, got: &ChainMfpt, exact: f64, tol: f64) {
    eprintln!(
        "sigma {sigma}: reference {exact:.4e}, chain {:.4e} [{:.4e}, {:.4e}] (2N cells {:.4e}), \
         {} cells, {} members, {} nodes, dimension {}, {} steps",
        got.mfpt,
        got.lo,
        got.hi,
        got.mfpt_fine,
        got.cells,
        got.members,
        got.nodes,
        got.dimension,
        got.steps
    );
    assert!(
        (got.mfpt / exact).ln().abs() < (1.0 + tol).ln(),
        "sigma {sigma}: chain {got:?} vs reference {exact}"
    );
}

/// Three roughnesses whose reference MFPT spans 1.3e2, 1.5e5 and 2.4e8
/// steps (and 3.9e11 at σ = 0.025): the chain on the walker's own state
/// gives each within 25 % (measured: 1 %, 0.1 %, 8 %, 2 %), at a cost that
/// does not grow with the MFPT (about 10⁵ steps each, fewer for the
/// deeper ones). The cells come from a cloud at twice the roughness: at
/// the same roughness the cloud does not reach the slow states the falls
/// go through (σ = 0.03: 2.6e11 against 2.4e8).
#[test]
fn the_chain_s_mfpt_is_the_reference_s_at_four_roughnesses() {
    for sigma in [0.08, 0.04, 0.03, 0.025] {
        let exact = reference(sigma).qsd_mfpt();
        let o = ChainOptions {
            cells: 200,
            ..ChainOptions::default()
        };
        let got = estimate(
            &Plain { sigma },
            &Plain { sigma: 2.0 * sigma },
            Rough::omega_star(),
            &o,
        );
        close(sigma, &got, exact, 0.25);
        assert!(got.steps < 200_000, "{got:?}");
        assert_eq!(got.dimension, 1);
        // Reproducible.
        let again = estimate(
            &Plain { sigma },
            &Plain { sigma: 2.0 * sigma },
            Rough::omega_star(),
            &o,
        );
        assert_eq!(got, again);
    }
}

/// The extended state, `(ω, γ_next)`: the fall is laid a step before it
/// comes, and the one-step lookahead dooms the input that lays it. On a
/// two-dimensional mesh the chain needs more cells: at 1000 cells of 4000
/// members it is within 30 % of the reference up to 2.4e8 (measured: 4 % high,
/// 19 % and 19 % low), where 200 cells give 11 %, 66 % and 71 % low (the
/// fall mass, steep in `ω'`, averaged over a wide cell). Below that
/// (σ = 0.025, 3.9e11) it stays a factor 8 low however many cells: the
/// cloud's coverage of the slow states, not the mesh.
#[test]
fn the_chain_on_the_extended_state_is_the_reference_s() {
    for sigma in [0.08, 0.04, 0.03] {
        let exact = reference(sigma).qsd_mfpt();
        let o = ChainOptions {
            cells: 1000,
            members: 4000,
            lookahead: 1,
            ..ChainOptions::default()
        };
        let got = estimate(
            &Ahead { sigma },
            &Ahead { sigma: 2.0 * sigma },
            (Rough::omega_star(), GAMMA0),
            &o,
        );
        close(sigma, &got, exact, 0.3);
        assert_eq!(got.dimension, 2);
    }
}

/// Convergence in the chain's own knobs, at σ = 0.03 (MFPT 2.4e8): the
/// cells doubled (the estimate's own discretisation test) and the nodes
/// from 9 to 15 move the MFPT by less than 15 % (measured 3 % and 1 %).
#[test]
fn the_chain_is_converged_in_its_cells_and_nodes() {
    let sigma = 0.03;
    let run = |cells, nodes| {
        let o = ChainOptions {
            cells,
            nodes,
            ..ChainOptions::default()
        };
        estimate(
            &Plain { sigma },
            &Plain { sigma: 2.0 * sigma },
            Rough::omega_star(),
            &o,
        )
    };
    let base = run(200, 9);
    let more_nodes = run(200, 15);
    eprintln!(
        "200 cells, 9 nodes {:.4e}; 400 cells {:.4e}; 15 nodes {:.4e}",
        base.mfpt, base.mfpt_fine, more_nodes.mfpt
    );
    assert!((base.mfpt_fine / base.mfpt - 1.0).abs() < 0.15, "{base:?}");
    assert!(
        (more_nodes.mfpt / base.mfpt - 1.0).abs() < 0.15,
        "{base:?} vs {more_nodes:?}"
    );
}
