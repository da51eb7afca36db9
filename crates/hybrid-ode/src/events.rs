//! Event location: which guards crossed over a step, and where the earliest
//! crossing lies on the step's dense output (Illinois root finding).

use crate::dense::Dense;
use crate::system::{Crossing, Guards, HybridSystem};

/// Iteration cap of the event root finder (it normally needs 5–15).
const ROOT_MAX_ITER: u32 = 200;

/// The direction in which guard `kind` crossed from `p` (step start) to `q`
/// (step end): `Some(true)` falling, `Some(false)` rising, `None` no crossing.
/// A start value of exactly 0 never counts as a crossing.
#[inline]
pub(crate) fn crossing_dir(kind: Crossing, p: f64, q: f64) -> Option<bool> {
    let falls = p > 0.0 && q <= 0.0;
    let rises = p < 0.0 && q >= 0.0;
    match kind {
        Crossing::Falling if falls => Some(true),
        Crossing::Rising if rises => Some(false),
        Crossing::Either if falls => Some(true),
        Crossing::Either if rises => Some(false),
        _ => None,
    }
}

/// Whether a guard value is on the crossed side.
#[inline]
fn is_crossed(falling: bool, v: f64) -> bool {
    if falling { v <= 0.0 } else { v >= 0.0 }
}

/// Fixed-size scratch of event location.
pub(crate) struct Scratch<const N: usize> {
    /// State at a trial time.
    ya: [f64; N],
    /// State at the crossed end of the current bracket.
    yc: [f64; N],
    /// State at the earliest event found so far.
    pub(crate) ybest: [f64; N],
}

impl<const N: usize> Scratch<N> {
    pub(crate) fn new() -> Self {
        Self {
            ya: [0.0; N],
            yc: [0.0; N],
            ybest: [0.0; N],
        }
    }
}

/// Illinois (modified regula falsi) on guard `idx` along `dense`, from the
/// bracket `[a, b]` with `ga` not crossed at `a` and `gb` crossed at `b`
/// (`sc.yc` holds the state at `b`). Shrinks the bracket to `b − a <= tol`
/// and returns `b`, the crossed end; `sc.yc` is then the state there. Only
/// guard `idx` is evaluated ([`HybridSystem::guard`]).
// `!(a < b)` is deliberate throughout the engine: it is true for NaN too.
#[allow(clippy::too_many_arguments, clippy::neg_cmp_op_on_partial_ord)]
fn illinois<const N: usize, S: HybridSystem<N>>(
    sys: &S,
    dense: &Dense<N>,
    idx: usize,
    falling: bool,
    a: f64,
    ga: f64,
    b: f64,
    gb: f64,
    tol: f64,
    sc: &mut Scratch<N>,
) -> f64 {
    // s(t) > 0 before the crossing, s(t) <= 0 after it.
    let sgn = if falling { 1.0 } else { -1.0 };
    let (mut a, mut fa) = (a, sgn * ga);
    let (mut b, mut fb) = (b, sgn * gb);
    // Never ask for less than a few ulps of t.
    let tol = tol.max(4.0 * f64::EPSILON * a.abs().max(b.abs()).max(1e-300));
    let half = 0.5 * tol;
    let mut side = 0i8;
    let mut w_check = b - a;
    let mut since_check = 0u32;
    for _ in 0..ROOT_MAX_ITER {
        let w = b - a;
        if !(w > tol) {
            break;
        }
        // Safeguard: if four iterations did not halve the bracket, bisect.
        since_check += 1;
        let mut bisect = false;
        if since_check == 4 {
            bisect = w > 0.5 * w_check;
            since_check = 0;
            w_check = w;
        }
        let mut c = if !bisect && fa.is_finite() && fb.is_finite() && fa != fb {
            a + w * (fa / (fa - fb))
        } else {
            a + 0.5 * w
        };
        // Keep the trial at least tol/2 inside the bracket, so that a root
        // within tol/2 of an end closes the bracket on the next evaluation.
        if !(c >= a + half) {
            c = a + half;
        } else if !(c <= b - half) {
            c = b - half;
        }
        dense.eval(c, &mut sc.ya);
        let fc = sgn * sys.guard(c, &sc.ya, idx);
        if fc <= 0.0 {
            b = c;
            fb = fc;
            sc.yc = sc.ya;
            if side < 0 {
                fa *= 0.5;
            }
            side = -1;
        } else {
            a = c;
            fa = fc;
            if side > 0 {
                fb *= 0.5;
            }
            side = 1;
        }
    }
    b
}

/// Locates the earliest root, on `dense`, of the guards that crossed between
/// `gp` (at `dense.t0`) and `gn` (at `dense.t1`). Returns the guard's index
/// and its event time; `sc.ybest` is the state there (on the crossed side).
/// Ties go to the lower index.
pub(crate) fn locate_earliest<const N: usize, S: HybridSystem<N>>(
    sys: &S,
    dense: &Dense<N>,
    gp: &Guards,
    gn: &Guards,
    tol: f64,
    sc: &mut Scratch<N>,
) -> Option<(usize, f64)> {
    let len = gp.len.min(gn.len);
    let mut best: Option<(usize, f64)> = None;
    for i in 0..len {
        let Some(falling) = crossing_dir(gn.crossing[i], gp.value[i], gn.value[i]) else {
            continue;
        };
        // Right end of the bracket: the step's end, or the earliest event so
        // far if this guard has already crossed there (else its root is later).
        let (b, gb) = match best {
            None => {
                sc.yc = dense.y1;
                (dense.t1, gn.value[i])
            }
            Some((_, t_best)) => {
                let v = sys.guard(t_best, &sc.ybest, i);
                if !is_crossed(falling, v) {
                    continue;
                }
                sc.yc = sc.ybest;
                (t_best, v)
            }
        };
        let t_i = illinois(
            sys,
            dense,
            i,
            falling,
            dense.t0,
            gp.value[i],
            b,
            gb,
            tol,
            sc,
        );
        if best.is_none_or(|(_, t_best)| t_i < t_best) {
            best = Some((i, t_i));
            sc.ybest = sc.yc;
        }
    }
    best
}
