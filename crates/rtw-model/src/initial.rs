//! The initial state (docs/model.md §6): the star standing on two feet (spokes at
//! −60° and −120°), the front foot pinned at the origin, turning rigidly about
//! it at `initial.omega`.

use crate::contact::RodMode;
use crate::geometry::{RodFrame, RodState, Tip, perp, rest_star, scale};
use crate::options::{InitialShape, Options};
use crate::outcome::FailureDetail;
use crate::rtw::{N, Rtw};
use nalgebra::{SMatrix, SVector};
use std::f64::consts::PI;

/// Front foot: tip + of rod a; rear foot: tip − of rod c.
const FRONT: (usize, Tip) = (0, Tip::Plus);
const REAR: (usize, Tip) = (2, Tip::Minus);

/// Sets `rtw.modes` and returns the initial state, or the reason there is none.
pub fn initial_state(rtw: &mut Rtw, opts: &Options) -> Result<[f64; N], FailureDetail> {
    let half = rtw.body.half_length;
    // Spoke a+ at −60°: the hub sits (L/2) back along it from the origin.
    let theta_a = -PI / 3.0;
    let hub = scale(-half, [theta_a.cos(), theta_a.sin()]);
    let mut rods = rest_star(hub, theta_a);
    if opts.initial.shape == InitialShape::Static {
        rods = static_equilibrium(rtw, rods).ok_or(FailureDetail::NoStandingEquilibrium)?;
    }
    // Rigid rotation about the front foot P = origin.
    let omega = opts.initial.omega;
    for r in rods.iter_mut() {
        r.v = scale(omega, perp(r.c));
        r.omega = omega;
    }
    let mut y = [0.0; N];
    rtw.modes = [RodMode::Free; 3];
    rtw.store(&rods, &mut y);
    // The front foot does not move (the star turns about it): mode choice.
    let (loads, _) = rtw.loads(&frames(&rods));
    let (i, tip) = FRONT;
    rtw.modes[i] = rtw.body.choose_mode(&rods[i], tip, true, &loads[i], rtw.mu);
    rtw.body
        .slots(rtw.modes[i], &rods[i], &mut y[6 * i..6 * i + 6]);
    // The rear foot lifts if the star rolls forward, rests if it does not
    // turn, and lands (an impact) if it rolls back.
    let (i, tip) = REAR;
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
            .slots(rtw.modes[i], &rods[i], &mut y[6 * i..6 * i + 6]);
    }
    Ok(y)
}

fn frames(rods: &[RodState; 3]) -> [RodFrame; 3] {
    std::array::from_fn(|i| RodFrame::new(&rods[i]))
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
    const DOF: [(usize, usize); 6] = [(2, 5), (6, 9), (7, 10), (8, 11), (12, 15), (14, 17)];
    let mut y = [0.0; N];
    sys.store(&star, &mut y);
    let residual = |y: &[f64; N]| {
        let mut dy = [0.0; N];
        sys.dynamics(y, &mut dy);
        SVector::<f64, 6>::from_fn(|k, _| dy[DOF[k].1])
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
        for (k, &(slot, _)) in DOF.iter().enumerate() {
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
        for (k, &(slot, _)) in DOF.iter().enumerate() {
            y[slot] += damp * step[k];
        }
        if !y.iter().all(|v| v.is_finite()) {
            return None;
        }
    }
    None
}
