//! A deterministic stand-in for `rtw_model::simulate`, for testing the scan
//! machinery (determinism, resume, panics → `diverged`) without physics.
//!
//! Reachable from the binary only through the hidden `--fake-sim MS` flag.
//! Its labels are crude functions of the parameters shaped like docs/model.md §8's
//! picture (small α with low f_n collapses, small φ stalls); they mean
//! nothing physically. It panics for `rho > 4.75` and returns a numerical
//! `diverged` for `rho < 1.1`, so scans over ρ ∈ [1, 5] exercise both paths.

use rtw_model::outcome::{ContactFractions, Energy, FailureDetail, IntegratorWork, StepShares};
use rtw_model::{Label, Options, Outcome, Params};
use std::time::Duration;

/// The fake outcome of `p`; sleeps `delay` first (to make runs slow enough
/// to interrupt in tests).
pub fn simulate(p: &Params, o: &Options, delay: Duration) -> Outcome {
    if !delay.is_zero() {
        std::thread::sleep(delay);
    }
    if p.rho > 4.75 {
        panic!("fake simulator: rho = {} > 4.75", p.rho);
    }
    let (label, failure) = if p.rho < 1.1 {
        (Label::Diverged, Some(FailureDetail::WorkBudget))
    } else if p.alpha < 0.15 && p.f_n < 2.5 {
        (Label::Collapse, Some(FailureDetail::RodDown))
    } else if p.phi < 0.1 {
        (Label::Stall, Some(FailureDetail::NoTouchdown))
    } else if p.f_n > 3.5 {
        (Label::Skip, None)
    } else if p.alpha > 0.3 {
        (Label::Crawl, None)
    } else {
        (Label::Walk, None)
    };
    let t_end = if failure.is_some() {
        o.t_max * p.phi / 0.3
    } else {
        o.t_max
    };
    let nlsp = if label == Label::Skip { 0.3 } else { 0.0 };
    let tlsp = if label == Label::Crawl { 0.1 } else { 0.0 };
    let slsp = (1.0 - nlsp - tlsp) * p.zeta * 10.0;
    Outcome {
        label,
        failure,
        start: Default::default(),
        t_end,
        fractions: ContactFractions {
            nlsp,
            slsp,
            dlsp: 1.0 - nlsp - tlsp - slsp,
            tlsp,
        },
        step_shares: StepShares {
            steps: 20,
            flight: nlsp.min(1.0) * 2.0,
            triple: tlsp * 5.0,
        },
        touchdowns: (t_end * p.f_n) as u64,
        f_w: p.f_n,
        f_w_newfoot: p.f_n * 0.9,
        speed: p.phi * p.length * 5.0,
        mu_required: 1.0 / p.phi,
        slide_time: 0.0,
        energy: Energy {
            initial: p.rho,
            last: p.rho * 0.5,
            gravity_released: p.phi,
            impact_loss: p.phi * 0.5,
            damping_loss: p.zeta,
            ..Default::default()
        },
        period: 1,
        cycle: None,
        work: IntegratorWork {
            steps: 1000,
            rejected: 10,
            rhs_evals: 7000,
            events: 100,
        },
        robustness: None,
    }
}
