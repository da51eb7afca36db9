//! Event location: which guards crossed over a step, and where the earliest
//! crossing lies on the step's dense output (Illinois root finding).
//!
//! A guard crossed over a step when its values at the step's ends lie on
//! opposite sides of zero, or when it went out and back inside the step (a
//! tip that touches and lifts, a brief slip). The second kind is found
//! without a cap on the step: from the guard's values and rates at both ends,
//! its cubic Hermite model on the step ([`cubic_dip`]); only a guard whose
//! model cannot exclude a dip is sampled on the dense output, at the model's
//! minimum, and the interval split there, with the model's error measured at
//! the sample bounding the next level. A sample on the crossed side closes a
//! bracket that the root finder then shrinks like any other.
//!
//! The model assumes a guard smooth over the step. With
//! [`EngineOptions::hidden_crossings`](crate::EngineOptions::hidden_crossings)
//! the engine also finds what it hides: a step is split at each kink of the
//! right-hand side that changed side over it (a guard computed from its
//! forces kinks there too) and each piece is searched like a step of its
//! own; every guard is checked at the earliest event; and the piece before
//! a located root is searched for an earlier one.

mod dip;
mod hidden;

use crate::dense::Dense;
use crate::system::{Crossing, Guards, HybridSystem, MAX_GUARDS, MAX_KINKS};
use dip::{Knot, find_dip, knot, may_dip};
use hidden::{Kinks, check_at_event, locate_first, locate_kinks};

/// Iteration cap of the event root finder (it normally needs 5–15).
const ROOT_MAX_ITER: u32 = 200;

/// The direction in which guard `kind` crossed from `p` (step start) to `q`
/// (step end): `Some(true)` falling, `Some(false)` rising, `None` no crossing.
/// A start value of exactly 0 never counts as a crossing.
#[inline]
pub(crate) fn crossing_dir(kind: Crossing, p: f64, q: f64) -> Option<bool> {
    armed(kind, p).filter(|&falling| is_crossed(falling, q))
}

/// Whether a guard value is on the crossed side.
#[inline]
fn is_crossed(falling: bool, v: f64) -> bool {
    if falling { v <= 0.0 } else { v >= 0.0 }
}

/// The side σ a guard that fires `falling` starts on: +1 above zero, −1
/// below (its signed value `s = σ g` is positive until it crosses).
#[inline]
fn side(falling: bool) -> f64 {
    if falling { 1.0 } else { -1.0 }
}

/// Fixed-size scratch of event location.
pub(crate) struct Scratch<const N: usize> {
    /// State at a trial time.
    ya: [f64; N],
    /// State at the crossed end of the current bracket.
    yc: [f64; N],
    /// State at the earliest event found so far.
    pub(crate) ybest: [f64; N],
    /// The step's kinks.
    kinks: Kinks<N>,
}

impl<const N: usize> Scratch<N> {
    pub(crate) fn new() -> Self {
        Self {
            ya: [0.0; N],
            yc: [0.0; N],
            ybest: [0.0; N],
            kinks: Kinks {
                len: 0,
                t: [0.0; MAX_KINKS],
                y: [[0.0; N]; MAX_KINKS],
                g: [[0.0; MAX_GUARDS]; MAX_KINKS],
                before: [[0.0; MAX_GUARDS]; MAX_KINKS],
                after: [[0.0; MAX_GUARDS]; MAX_KINKS],
            },
        }
    }
}

/// Illinois (modified regula falsi) on `g = f(t, y)` (a guard, a kink)
/// along `dense`, from the bracket `[a, b]` with `ga` not crossed at `a` and
/// `gb` crossed at `b` (`sc.yc` holds the state at `b`). Shrinks the bracket
/// to `b − a <= tol` and returns it as `(a, s(a), b)`, with `s = ±g`
/// positive on the side `g` starts on; `sc.yc` is then the state at `b`, the
/// crossed end. Only `f` is evaluated: for a guard, that guard alone
/// ([`HybridSystem::guard`]).
// `!(a < b)` is deliberate throughout the engine: it is true for NaN too.
#[allow(clippy::too_many_arguments, clippy::neg_cmp_op_on_partial_ord)]
fn illinois<const N: usize, F: Fn(f64, &[f64; N]) -> f64>(
    f: F,
    dense: &Dense<N>,
    falling: bool,
    a: f64,
    ga: f64,
    b: f64,
    gb: f64,
    tol: f64,
    sc: &mut Scratch<N>,
) -> (f64, f64, f64) {
    // s(t) > 0 before the crossing, s(t) <= 0 after it.
    let sgn = if falling { 1.0 } else { -1.0 };
    let (mut a, mut fa) = (a, sgn * ga);
    // `fa` as evaluated, before the Illinois halvings.
    let mut sa = fa;
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
        let fc = sgn * f(c, &sc.ya);
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
            sa = fc;
            if side > 0 {
                fb *= 0.5;
            }
            side = 1;
        }
    }
    (a, sa, b)
}

/// A guard's bracket `(falling, a, g(a), b, g(b))`: not crossed at `a`,
/// crossed at `b`, in the direction `falling`.
type Bracket = (bool, f64, f64, f64, f64);

/// The earliest [`Bracket`] of guard `i` on the
/// step, before `t_limit` for a dip, and the knot that starts its smooth
/// piece: the step is split at its kinks (`sc.kinks`), and each piece is
/// searched like a step of its own, by the values at its ends and, where
/// both are uncrossed, a dip search ([`find_dip`]). A guard crossed at a
/// kink by no more than the step's error is not split there. `sc.yc` is the
/// state at `b`. `None`: the guard did not cross, or cannot fire.
#[allow(clippy::too_many_arguments)]
#[inline]
fn first_bracket<const N: usize, S: HybridSystem<N>>(
    sys: &S,
    dense: &Dense<N>,
    i: usize,
    (gp, gn): (&Guards, &Guards),
    (rp, rn): (&[f64; MAX_GUARDS], &[f64; MAX_GUARDS]),
    t_limit: f64,
    err: &[f64; N],
    sc: &mut Scratch<N>,
) -> Option<(Bracket, Knot)> {
    let falling = armed(gn.crossing[i], gp.value[i])?;
    let sg = side(falling);
    let mut a = knot(sg, dense.t0, gp.value[i], rp[i]);
    let mut dy = [0.0; N];
    for k in 0..sc.kinks.len {
        let (t, s) = (sc.kinks.t[k], sg * sc.kinks.g[k][i]);
        if s <= 0.0 {
            let y = sc.kinks.y[k];
            if past_noise(sys, i, t, &y, err, s, sg, &mut dy) {
                sc.yc = y;
                return Some(((falling, a.t, sg * a.s, t, sg * s), a));
            }
            continue;
        }
        let b = knot(sg, t, sg * s, sc.kinks.before[k][i]);
        if let Some((ta, ga, tb, gb)) = find_dip(sys, dense, i, sg, a, b, t_limit, err, sc) {
            return Some(((falling, ta, ga, tb, gb), a));
        }
        a = knot(sg, t, sg * s, sc.kinks.after[k][i]);
    }
    let q = gn.value[i];
    if is_crossed(falling, q) {
        sc.yc = dense.y1;
        return Some(((falling, a.t, sg * a.s, dense.t1, q), a));
    }
    let b = knot(sg, dense.t1, q, rn[i]);
    let (ta, ga, tb, gb) = find_dip(sys, dense, i, sg, a, b, t_limit, err, sc)?;
    Some(((falling, ta, ga, tb, gb), a))
}

/// Whether any guard crossed over the step `[t0, t1]`, at its end or (by
/// [`may_dip`]) possibly inside it.
pub(crate) fn any_crossing(
    gp: &Guards,
    gn: &Guards,
    rp: &[f64; MAX_GUARDS],
    rn: &[f64; MAX_GUARDS],
    t0: f64,
    t1: f64,
) -> bool {
    let len = gp.len.min(gn.len);
    (0..len).any(|i| {
        let kind = gn.crossing[i];
        crossing_dir(kind, gp.value[i], gn.value[i]).is_some()
            || may_dip(kind, gp.value[i], gn.value[i], rp[i], rn[i], t0, t1)
    })
}

/// Whether guard `idx`, at `s = σ g <= 0` on its crossed side at `(t, y)`,
/// is past zero by more than the step's error estimate `err` moves it: a
/// shallower crossing is not resolved by the solution (a tip freed on the
/// ground with zero velocity dips a nanometre below it on the dense output).
/// `dy` is scratch.
#[allow(clippy::too_many_arguments)]
#[inline]
fn past_noise<const N: usize, S: HybridSystem<N>>(
    sys: &S,
    idx: usize,
    t: f64,
    y: &[f64; N],
    err: &[f64; N],
    s: f64,
    sg: f64,
    dy: &mut [f64; N],
) -> bool {
    for ((d, y), e) in dy.iter_mut().zip(y).zip(err) {
        *d = y + e;
    }
    let noise = (s - sg * sys.guard(t, dy, idx)).abs();
    s < -noise || noise == 0.0
}

/// The direction in which guard `kind`, at `p` at the step's start, fires
/// when it next crosses: `Some(true)` falling (it is above zero),
/// `Some(false)` rising (below), `None` when it cannot fire from there.
#[inline]
fn armed(kind: Crossing, p: f64) -> Option<bool> {
    match kind {
        Crossing::Falling | Crossing::Either if p > 0.0 => Some(true),
        Crossing::Rising | Crossing::Either if p < 0.0 => Some(false),
        _ => None,
    }
}

/// Locates the earliest root, on `dense`, of the guards that crossed over
/// the step: between `gp` (at `dense.t0`) and `gn` (at `dense.t1`), or
/// out and back inside it (found from the rates `rp`, `rn` at the ends, see
/// [`find_dip`]; `err` is the step's local error estimate). With `hidden`
/// ([`EngineOptions::hidden_crossings`](crate::EngineOptions::hidden_crossings)),
/// the step is first split at the kinks in `kinks = (start, changed)` (bits
/// of [`HybridSystem::kink_sides`]), and the crossings the ends hide are
/// sought too. Returns the guard's index and its event time; `sc.ybest` is
/// the state there (on the crossed side). Ties go to the lower index.
#[allow(clippy::too_many_arguments)]
pub(crate) fn locate_earliest<const N: usize, S: HybridSystem<N>>(
    sys: &S,
    dense: &Dense<N>,
    gp: &Guards,
    gn: &Guards,
    rp: &[f64; MAX_GUARDS],
    rn: &[f64; MAX_GUARDS],
    err: &[f64; N],
    tol: f64,
    (hidden, kinks): (bool, (u32, u32)),
    sc: &mut Scratch<N>,
) -> Option<(usize, f64)> {
    let len = gp.len.min(gn.len);
    let (start, changed) = kinks;
    if hidden && changed != 0 {
        locate_kinks(sys, dense, start, changed, tol, sc);
    } else {
        sc.kinks.len = 0;
    }
    let mut best: Option<(usize, f64)> = None;
    for i in 0..len {
        // The guard's bracket: not crossed at `a`, crossed at `b`, `sc.yc`
        // the state at `b`.
        let t_limit = best.map_or(dense.t1, |(_, t_best)| t_best);
        let Some(((falling, a, ga, b, gb), k0)) =
            first_bracket(sys, dense, i, (gp, gn), (rp, rn), t_limit, err, sc)
        else {
            continue;
        };
        // Right end of the bracket: its own, or the earliest event so far if
        // that is earlier and this guard has already crossed there (else its
        // root is later).
        let (b, gb) = match best {
            Some((_, t_best)) if t_best <= b => {
                if t_best <= a {
                    continue;
                }
                let v = sys.guard(t_best, &sc.ybest, i);
                if !is_crossed(falling, v) {
                    continue;
                }
                sc.yc = sc.ybest;
                (t_best, v)
            }
            _ => (b, gb),
        };
        let sg = side(falling);
        let t_i = locate_first(sys, dense, i, sg, k0, (a, ga, b, gb), err, tol, hidden, sc);
        if best.is_none_or(|(_, t_best)| t_i < t_best) {
            best = Some((i, t_i));
            sc.ybest = sc.yc;
        }
    }
    if hidden {
        best = check_at_event(sys, dense, gp, rp, len, best, err, tol, sc);
    }
    best
}
