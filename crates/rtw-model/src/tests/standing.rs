//! The standing start (`initial.shape = "settled"`, docs/model.md §6): a star
//! stands on two feet where it can, on three where it needs to, and one that
//! cannot stand is a `collapse` that says why. Each standing state is checked
//! against statics, independently of how it was found: at rest, every
//! acceleration vanishes, every foot presses on the ground and its force lies
//! inside the friction cone.

use crate::options::{CannotStand, InitialShape, Options};
use crate::outcome::{FailureDetail, Stance};
use crate::plant::initial::{Start, initial_state};
use crate::plant::rtw::Rtw;
use crate::plant::slots::{self, N, VELOCITIES};
use crate::{Label, Params, Physical, simulate};
use hybrid_ode::Work;

/// The paper-box sample (seed 20240501) that stands on three feet: soft
/// (f_n 1.58 Hz) and nearly without hub (α 0.055).
fn soft() -> Params {
    Params {
        length: 0.8,
        rho: 3.74977,
        alpha: 0.054966,
        f_n: 1.584928,
        zeta: 0.056339,
        phi: 0.10618,
    }
}

fn settled(omega: f64) -> Options {
    let mut o = Options::default();
    o.initial.shape = InitialShape::Settled;
    o.initial.omega = omega;
    o
}

/// The standing state (pushed at ω = 0, so at rest) and its stance.
fn stand(p: &Params, o: &Options) -> (Rtw, Result<Start, FailureDetail>, Work) {
    let phys = Physical::new(p, o.normalization, o.g);
    let mut rtw = Rtw::new(&phys, o);
    let mut work = Work::default();
    let started = initial_state(&mut rtw, o, &mut work);
    (rtw, started, work)
}

/// Statics at `y`: the largest acceleration (angular ones at the tip) over
/// g, every grounded rod's normal force, and its friction ratio.
fn statics(rtw: &Rtw, y: &[f64; N]) -> (f64, Vec<(f64, f64)>) {
    let mut dy = [0.0; N];
    let at = rtw.dynamics(y, &mut dy);
    let g = rtw.gravity()[0].hypot(rtw.gravity()[1]);
    let half = rtw.body().half_length;
    let acc = (0..3)
        .map(|i| {
            let [x, y, w] = VELOCITIES.map(|k| dy[slots::at(i, k)].abs());
            x.max(y).max(w * half)
        })
        .fold(0.0, f64::max);
    let feet = (0..3)
        .filter(|&i| rtw.modes()[i].tip().is_some())
        .map(|i| (at.lambda[i][1], at.lambda[i][0].abs() / at.lambda[i][1]))
        .collect();
    (acc / g, feet)
}

#[test]
fn a_stiff_star_stands_on_two_feet_as_the_static_start_does() {
    let p = Params::fig7a();
    let (_, settled_start, work) = stand(&p, &settled(-2.0));
    let mut static_opts = settled(-2.0);
    static_opts.initial.shape = InitialShape::Static;
    let (_, static_start, _) = stand(&p, &static_opts);
    let (y, stance) = settled_start.unwrap();
    assert_eq!(stance, Stance::TwoFeet);
    // Where a two-foot equilibrium exists it is the same state, found
    // without setting the star down (no integration).
    assert_eq!(y, static_start.unwrap().0);
    assert_eq!(work.rhs_evals, 0);
}

#[test]
fn a_soft_star_stands_on_three_feet_in_static_equilibrium() {
    let p = soft();
    let o = settled(0.0);
    // No two-foot stance exists for it: the static start gives up.
    let mut two = o;
    two.initial.shape = InitialShape::Static;
    assert_eq!(
        stand(&p, &two).1.unwrap_err(),
        FailureDetail::NoStandingEquilibrium
    );
    let (rtw, started, work) = stand(&p, &o);
    let (y, stance) = started.expect("it stands");
    assert_eq!(stance, Stance::ThreeFeet);
    assert!(work.rhs_evals > 0, "it was set down and settled");
    assert_eq!(rtw.contact_state(), 3);
    let (acc, feet) = statics(&rtw, &y);
    // Statics: at rest nothing accelerates (relative to g; the relaxation
    // stops below 1e-9 and the push at ω = 0 keeps the state).
    assert!(acc < 1e-7, "residual acceleration {acc:e} g");
    for (normal, ratio) in feet {
        assert!(normal > 0.0, "a foot pulls on the ground: {normal}");
        assert!(ratio <= o.contact.mu, "a foot outside the cone: {ratio}");
    }
}

#[test]
fn a_star_too_soft_to_stand_collapses_and_says_why() {
    // f_n 0.5 Hz on a nearly flat slope: it sags until its centre of mass
    // is below half the standing height.
    let p = Params {
        f_n: 0.5,
        phi: 0.02,
        ..Params::fig7a()
    };
    let out = simulate(&p, &settled(-2.0));
    assert_eq!(out.label, Label::Collapse);
    assert_eq!(out.failure, Some(FailureDetail::StandingComLow));
    assert!(out.failure.unwrap().describe().starts_with("cannot stand"));
    assert!(out.work.rhs_evals > 0, "the settling's work is counted");
}

#[test]
fn a_star_that_rolls_away_collapses_or_is_pushed_as_asked() {
    // From the paper box: soft, on a steep slope; set down it keeps its
    // shape but rolls away downhill.
    let p = Params {
        length: 0.8,
        rho: 1.04244,
        alpha: 0.046928,
        f_n: 1.61868,
        zeta: 0.098303,
        phi: 0.256668,
    };
    let o = settled(-2.0);
    let out = simulate(&p, &o);
    assert_eq!(out.label, Label::Collapse);
    assert_eq!(out.failure, Some(FailureDetail::StandingRollsAway));
    assert_eq!(out.t_end, 0.0);
    let mut push = o;
    push.initial.cannot_stand = CannotStand::Push;
    let out = simulate(&p, &push);
    assert_eq!(out.start, Stance::RestShape);
    assert!(out.t_end > 0.0, "pushed, it runs");
    assert_ne!(out.failure, Some(FailureDetail::StandingRollsAway));
}

#[test]
fn a_numerical_failure_while_settling_is_diverged_not_a_collapse() {
    // The soft star must settle (integration work) before it stands; with a
    // work budget of 10 steps the settling runs out of it: a numerical
    // failure, which is `diverged` (docs/model.md §5), never a physical
    // `collapse`.
    let mut o = settled(-2.0);
    o.max_steps = 10;
    let out = simulate(&soft(), &o);
    assert_eq!(out.failure, Some(FailureDetail::WorkBudget));
    assert_eq!(out.label, Label::Diverged, "{out:?}");
}
