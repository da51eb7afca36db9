//! The initial state (docs/model.md §6): the star standing on the slope, then
//! pushed, turning rigidly about its front (most downhill) foot at
//! `initial.omega`.
//!
//! How it stands is `initial.shape`:
//!
//! * `rigid_star`: the rest shape on two feet (spokes at −60° and −120°),
//!   front foot at the origin; not an equilibrium.
//! * `static`: the static equilibrium on those two feet, by Newton, with the
//!   front foot pinned, the rear one frictionless and rod b free. A star that
//!   would need a third foot to stand has no solution there.
//! * `settled`: the two-foot equilibrium of `static` where it exists (it is
//!   an equilibrium with both feet sticking too: the rear foot needs no
//!   friction there); elsewhere the physical procedure: the rest star is set
//!   down at rest on its two feet and let settle under gravity, with the
//!   run's own contact law (friction, slip, a third foot landing, a rod lying
//!   down). The settling is
//!   a dynamic relaxation, the classic form-finding method for tensegrities
//!   (Barnes 1999): a velocity damping that vanishes at rest is added, so the
//!   state it comes to rest in is a static equilibrium of the real forces, on
//!   whichever feet the star needs. A star that cannot stand falls while
//!   settling or never comes to rest, and the failure says which.

use crate::options::{CannotStand, InitialShape, Options};
use crate::outcome::{FailureDetail, Stance};
use crate::plant::contact::RodMode;
use crate::plant::geometry::{RodFrame, RodState, Tip, perp, rest_star, scale, sub};
use crate::plant::rtw::{AtState, Rtw, Transition};
use crate::plant::slots::{self, N, OMEGA, THETA, VELOCITIES, VX, VY, X, Y};
use hybrid_ode::{Dense, EndReason, Flow, Observer, StepEnd, Work, run};
use nalgebra::{SMatrix, SVector};
use std::f64::consts::PI;

/// A start: the initial state and how the star stood before the push.
pub type Start = ([f64; N], Stance);
/// A star at rest: its rods and the tip of each rod on the ground.
type Standing = ([RodState; 3], [Option<Tip>; 3]);

/// Front foot: tip + of rod a; rear foot: tip − of rod c.
const FRONT: (usize, Tip) = (0, Tip::Plus);
const REAR: (usize, Tip) = (2, Tip::Minus);
/// The tips on the ground, per rod, of a star standing on its two feet.
const TWO_FEET: [Option<Tip>; 3] = [Some(FRONT.1), None, Some(REAR.1)];

/// Sets `rtw.modes` and returns the initial state with how the star stood,
/// or the reason it could not. The integrator work of standing the star
/// (`settled` only) is added to `work`.
pub fn initial_state(
    rtw: &mut Rtw,
    opts: &Options,
    work: &mut Work,
) -> Result<Start, FailureDetail> {
    let half = rtw.body.half_length;
    // Spoke a+ at −60°: the hub sits (L/2) back along it from the origin.
    let theta_a = -PI / 3.0;
    let hub = scale(-half, [theta_a.cos(), theta_a.sin()]);
    let star = rest_star(hub, theta_a);
    let (rods, feet) = match opts.initial.shape {
        InitialShape::RigidStar => (star, TWO_FEET),
        InitialShape::Static => (
            static_equilibrium(rtw, star).ok_or(FailureDetail::NoStandingEquilibrium)?,
            TWO_FEET,
        ),
        // A two-foot equilibrium with a frictionless rear foot is one with
        // both feet sticking too (the rear foot needs no friction): where it
        // exists the star stands there; only where it does not is it set
        // down. A star that rolls away as it is set down keeps its shape:
        // `initial.cannot_stand` says whether that fails or is pushed anyway.
        InitialShape::Settled => match static_equilibrium(rtw, star) {
            Some(rods) => (rods, TWO_FEET),
            None => match settle(rtw, star, opts, work)? {
                Some(standing) => standing,
                None if opts.initial.cannot_stand == CannotStand::Push => (star, TWO_FEET),
                None => return Err(FailureDetail::StandingRollsAway),
            },
        },
    };
    let stance = match (opts.initial.shape, feet.iter().flatten().count()) {
        (InitialShape::RigidStar, _) => Stance::RestShape,
        (InitialShape::Settled, _) if rods == star => Stance::RestShape,
        (_, 3) => Stance::ThreeFeet,
        _ => Stance::TwoFeet,
    };
    Ok((push(rtw, rods, feet, opts.initial.omega), stance))
}

/// The standing star `rods` with tips `feet` on the ground, turned rigidly
/// about its front foot at `omega`: the front foot's mode chosen at rest,
/// every other foot lifting (the star rolls forward), resting (it does not
/// turn) or landing (an impact: it rolls back).
fn push(rtw: &mut Rtw, mut rods: [RodState; 3], feet: [Option<Tip>; 3], omega: f64) -> [f64; N] {
    let tip_of = |rods: &[RodState; 3], i: usize| {
        feet[i].map(|tip| (i, tip, rtw.body.tip_point(&rods[i], tip).0))
    };
    let (front, front_tip, pivot) = (0..3)
        .filter_map(|i| tip_of(&rods, i))
        .max_by(|a, b| a.2[0].total_cmp(&b.2[0]))
        .expect("a standing star has a foot on the ground");
    for r in rods.iter_mut() {
        r.v = scale(omega, perp(sub(r.c, pivot)));
        r.omega = omega;
    }
    let mut y = [0.0; N];
    rtw.modes = [RodMode::Free; 3];
    rtw.store(&rods, &mut y);
    // The front foot does not move (the star turns about it): mode choice.
    let (loads, _) = rtw.loads(&frames(&rods));
    rtw.modes[front] = rtw
        .body
        .choose_mode(&rods[front], front_tip, true, &loads[front], rtw.mu);
    rtw.body.slots(
        rtw.modes[front],
        &rods[front],
        slots::rod_mut(&mut y, front),
    );
    for (i, tip) in (0..3)
        .filter(|&i| i != front)
        .filter_map(|i| feet[i].map(|t| (i, t)))
    {
        let (_, v_tip) = rtw.body.tip_point(&rods[i], tip);
        if v_tip[1] < 0.0 {
            rtw.touchdown(&mut y, i, tip);
        } else if v_tip[1] == 0.0 {
            let rods = rtw.rods(&y);
            let (loads, _) = rtw.loads(&rtw.frames(&y));
            rtw.modes[i] = rtw
                .body
                .choose_mode(&rods[i], tip, v_tip[0] == 0.0, &loads[i], rtw.mu);
            rtw.body
                .slots(rtw.modes[i], &rods[i], slots::rod_mut(&mut y, i));
        }
    }
    y
}

fn frames(rods: &[RodState; 3]) -> [RodFrame; 3] {
    std::array::from_fn(|i| RodFrame::new(&rods[i]))
}

/// Velocity damping of the dynamic relaxation, as a multiple of the string
/// frequency `sqrt(k/m)`: about critical for the slowest elastic mode of a
/// prestressed star (the softened mechanism, [`crate::modal`]), so that
/// every mode decays within a few of its periods.
const RELAX_DAMPING: f64 = 2.0;
/// Longest a star may take to come to rest, in periods `2π sqrt(m/k)`.
const SETTLE_PERIODS: f64 = 200.0;
/// At rest: every rod's speed below this × sqrt(g L) and every acceleration
/// below this × g (angular ones at the tip).
const REST_TOL: f64 = 1e-9;
/// Rolled or slid away: the centre of mass moved this × L along the slope
/// while being set down (half a step: a star that sags on its feet moves it
/// far less, one that tips over onto the next foot moves it L/2).
const AWAY: f64 = 0.25;

/// Watches the star being set down (the RTW with the relaxation's damping):
/// stops the run when it is at rest, rolls away or falls.
struct Settling {
    failure: Option<FailureDetail>,
    at_rest: bool,
    /// It rolled or slid away from its feet ([`AWAY`]).
    rolled_away: bool,
    /// sqrt(g L) and g: the scales of [`REST_TOL`].
    speed_scale: f64,
    accel_scale: f64,
    /// Where the centre of mass started along the slope, and how far it may go.
    com_x0: f64,
    away: f64,
}

/// The largest of a rod velocity's (or acceleration's) components, angular
/// ones at the tip, over the three rods of `v`.
fn largest_rate(v: &[f64; N], half: f64) -> f64 {
    (0..3)
        .map(|i| {
            let [x, y, w] = VELOCITIES.map(|k| v[slots::at(i, k)].abs());
            x.max(y).max(w * half)
        })
        .fold(0.0, f64::max)
}

impl Observer<N, Rtw> for Settling {
    fn on_transition(&mut self, _: &Rtw, _t: f64, _y: &[f64; N], tr: &Transition) -> Flow {
        match *tr {
            Transition::Failure(FailureDetail::RodDown) => {
                self.failure = Some(FailureDetail::StandingRodDown);
                Flow::Stop
            }
            Transition::Failure(FailureDetail::CentreOfMassLow) => {
                self.failure = Some(FailureDetail::StandingComLow);
                Flow::Stop
            }
            Transition::Failure(other) => {
                self.failure = Some(other);
                Flow::Stop
            }
            Transition::Touchdown { .. } | Transition::ModeChange { .. } => Flow::Continue,
        }
    }

    fn reads_interior(&self, _: &Rtw, _t0: f64, _t1: f64) -> bool {
        false
    }

    fn on_step(&mut self, rtw: &Rtw, dense: &Dense<N>, _: StepEnd<'_, AtState>) -> Flow {
        let y = &dense.y1;
        if (rtw.centre_of_mass(y)[0] - self.com_x0).abs() > self.away {
            self.rolled_away = true;
            return Flow::Stop;
        }
        let half = rtw.body.half_length;
        if largest_rate(y, half) > REST_TOL * self.speed_scale {
            return Flow::Continue;
        }
        let mut dy = [0.0; N];
        rtw.dynamics(y, &mut dy);
        self.at_rest = largest_rate(&dy, half) <= REST_TOL * self.accel_scale;
        if self.at_rest {
            Flow::Stop
        } else {
            Flow::Continue
        }
    }
}

/// Sets the rest star down at rest on its two feet and lets it settle
/// (module docs). Returns the rods at rest and the tips on the ground,
/// `None` if it rolls or slides away instead (it has no equilibrium on the
/// slope but keeps its shape), or why it cannot stand.
fn settle(
    rtw: &Rtw,
    star: [RodState; 3],
    opts: &Options,
    work: &mut Work,
) -> Result<Option<Standing>, FailureDetail> {
    let mut sys = Settling {
        failure: None,
        at_rest: false,
        rolled_away: false,
        speed_scale: (rtw.gravity[0].hypot(rtw.gravity[1]) * 2.0 * rtw.body.half_length).sqrt(),
        accel_scale: rtw.gravity[0].hypot(rtw.gravity[1]),
        com_x0: 0.0,
        away: AWAY * 2.0 * rtw.body.half_length,
    };
    let mut relaxing = rtw.clone();
    let string_rate = (rtw.strings.k / rtw.body.m).sqrt();
    relaxing.relax = RELAX_DAMPING * string_rate;
    relaxing.modes = [RodMode::Free; 3];
    let mut y = [0.0; N];
    relaxing.store(&star, &mut y);
    sys.com_x0 = relaxing.centre_of_mass(&y)[0];
    // Both feet are set down at rest: the mode-choice rule at rest.
    let (loads, _) = relaxing.loads(&frames(&star));
    for (i, tip) in [FRONT, REAR] {
        relaxing.modes[i] = relaxing
            .body
            .choose_mode(&star[i], tip, true, &loads[i], relaxing.mu);
        relaxing
            .body
            .slots(relaxing.modes[i], &star[i], slots::rod_mut(&mut y, i));
    }
    let t_max = SETTLE_PERIODS * 2.0 * PI / string_rate;
    // The rest test reads speeds of REST_TOL × sqrt(g L): the run must be
    // accurate to a tenth of that, or its own error keeps the star moving
    // (with steps as long as the tolerance allows, rtol 1e-4 never settles).
    let mut engine = opts.engine();
    engine.atol = engine.atol.min(0.1 * REST_TOL * sys.speed_scale);
    let end = run(&mut relaxing, &mut sys, 0.0, &mut y, t_max, &engine);
    *work += end.work;
    if let Some(failure) = sys.failure {
        return Err(failure);
    }
    match end.reason {
        EndReason::Stopped if sys.rolled_away => return Ok(None),
        EndReason::Stopped if sys.at_rest => {}
        EndReason::NonFinite => return Err(FailureDetail::NonFinite),
        EndReason::StepUnderflow => return Err(FailureDetail::StepUnderflow),
        EndReason::WorkBudget => return Err(FailureDetail::WorkBudget),
        EndReason::Zeno => return Err(FailureDetail::Zeno),
        EndReason::TimeUp | EndReason::Stopped => {
            return Err(FailureDetail::NoStandingEquilibrium);
        }
    }
    let mut rods = relaxing.rods(&y);
    // At rest up to REST_TOL: the push starts from exactly zero velocity.
    for r in rods.iter_mut() {
        r.v = [0.0, 0.0];
        r.omega = 0.0;
    }
    Ok(Some((rods, relaxing.modes.map(RodMode::tip))))
}

/// The static equilibrium standing on the two feet, near the rest shape:
/// front foot pinned, rear foot on a frictionless contact (so the problem is
/// statically determinate), rod b free. Unknowns (θ_a; x_b, y_b, θ_b; x_tip,c,
/// θ_c); equations: every acceleration of that configuration at rest is zero.
/// Newton with a finite-difference Jacobian. `None` if it does not converge
/// or the solution cannot stand (a foot pulled, a rod through the ground).
fn static_equilibrium(rtw: &Rtw, star: [RodState; 3]) -> Option<[RodState; 3]> {
    let mut sys = rtw.clone();
    sys.modes = [
        RodMode::Stick { tip: FRONT.1 },
        RodMode::Free,
        RodMode::Slide {
            tip: REAR.1,
            dir: 1.0,
        },
    ];
    sys.mu = f64::INFINITY;
    // (slot of the unknown, slot of its equation's acceleration)
    let dof = |rod: usize, (q, rate): (usize, usize)| (slots::at(rod, q), slots::at(rod, rate));
    let (along_x, along_y, turn) = ((X, VX), (Y, VY), (THETA, OMEGA));
    let dofs: [(usize, usize); 6] = [
        dof(0, turn),
        dof(1, along_x),
        dof(1, along_y),
        dof(1, turn),
        dof(2, along_x),
        dof(2, turn),
    ];
    let mut y = [0.0; N];
    sys.store(&star, &mut y);
    let residual = |y: &[f64; N]| {
        let mut dy = [0.0; N];
        sys.dynamics(y, &mut dy);
        SVector::<f64, 6>::from_fn(|k, _| dy[dofs[k].1])
    };
    let scale_acc = rtw.gravity[1].abs().max(1e-12);
    for _ in 0..50 {
        let r = residual(&y);
        if r.norm() < 1e-11 * scale_acc {
            let rods = sys.rods(&y);
            let frames = sys.frames(&y);
            let (loads, _) = sys.loads(&frames);
            let standing = [0usize, 2].iter().all(|&i| {
                sys.body
                    .accel(sys.modes[i], &frames[i], &loads[i], sys.mu)
                    .lambda[1]
                    > 0.0
            });
            let above = rods.iter().all(|r| {
                let (p, _) = sys.body.tip_point(r, Tip::Plus);
                let (q, _) = sys.body.tip_point(r, Tip::Minus);
                p[1] > -1e-9 && q[1] > -1e-9
            });
            return (standing && above).then_some(rods);
        }
        let mut jac = SMatrix::<f64, 6, 6>::zeros();
        for (k, &(slot, _)) in dofs.iter().enumerate() {
            let h = 1e-7 * (1.0 + y[slot].abs());
            let mut yp = y;
            let mut ym = y;
            yp[slot] += h;
            ym[slot] -= h;
            jac.set_column(k, &((residual(&yp) - residual(&ym)) / (2.0 * h)));
        }
        let step = jac.lu().solve(&(-r))?;
        // Damped: never move an angle by more than 0.2 rad at once.
        let biggest = step.iter().fold(0.0f64, |a, s| a.max(s.abs()));
        let damp = if biggest > 0.2 { 0.2 / biggest } else { 1.0 };
        for (k, &(slot, _)) in dofs.iter().enumerate() {
            y[slot] += damp * step[k];
        }
        if !y.iter().all(|v| v.is_finite()) {
            return None;
        }
    }
    None
}
