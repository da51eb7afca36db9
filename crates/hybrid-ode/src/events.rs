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

use crate::dense::Dense;
use crate::system::{Crossing, Guards, HybridSystem, MAX_GUARDS};

/// Iteration cap of the event root finder (it normally needs 5–15).
const ROOT_MAX_ITER: u32 = 200;

/// Samples of one guard's dense output per step, at most, in the search for
/// a dip (a search that needs more gives up: no event).
const DIP_MAX_SAMPLES: usize = 8;

/// On a step with no error estimate of the guard's cubic model yet, the
/// model cannot exclude a dip whose predicted minimum clears zero by less
/// than this fraction of its depth below the chord. The model's error is
/// O(h⁴ g⁗) against a depth of O(h² g''): a few per cent of the depth on a
/// step that resolves the guard's motion (an oscillation of frequency ω
/// over a step h: (ωh)²/48 of it), so a half is a wide margin.
const DIP_MARGIN: f64 = 0.5;

/// Safety factor on the measured model error of a sub-interval's margin.
const DIP_ERR_SAFETY: f64 = 2.0;

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

/// A guard's signed value `s = σ g` (σ = ±1, positive on the side it starts
/// on) and its time derivative at time `t`.
#[derive(Clone, Copy)]
struct Knot {
    t: f64,
    s: f64,
    ds: f64,
}

/// The side σ (+1 above zero, −1 below) from which guard `kind` could cross
/// and come back within a step whose ends are `p` and `q`: both on that side
/// strictly, and the guard fires leaving it. `None`: no dip can fire.
#[inline]
fn dip_side(kind: Crossing, p: f64, q: f64) -> Option<f64> {
    let above = p > 0.0 && q > 0.0;
    let below = p < 0.0 && q < 0.0;
    match kind {
        Crossing::Falling | Crossing::Either if above => Some(1.0),
        Crossing::Rising | Crossing::Either if below => Some(-1.0),
        _ => None,
    }
}

/// The time of the minimum of the cubic Hermite model of `s` on `[a.t, b.t]`
/// (through both values and slopes), if the model cannot exclude `s <= 0`
/// there: its interior minimum is at most `margin` (when given) or
/// [`DIP_MARGIN`] × its depth below the chord. Also returns the model's value
/// there. `None` when the slopes allow no interior minimum (`s` does not
/// fall at `a` nor rise at `b`: a cubic with `ṡ(a) >= 0 >= ṡ(b)` has none).
#[inline]
fn cubic_dip(a: &Knot, b: &Knot, margin: Option<f64>) -> Option<(f64, f64)> {
    let h = b.t - a.t;
    // `!(h > 0)` also catches NaN.
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    if !(h > 0.0) {
        return None;
    }
    let (p0, p1, m0, m1) = (a.s, b.s, h * a.ds, h * b.ds);
    if margin.is_none() && excluded_cheaply(p0, p1, m0, m1) {
        return None;
    }
    if !(m0 < 0.0 || m1 > 0.0) {
        return None;
    }
    // p(θ) = (2θ³−3θ²+1)p0 + (θ³−2θ²+θ)m0 + (3θ²−2θ³)p1 + (θ³−θ²)m1;
    // p'(θ) = Aθ² + Bθ + C.
    let d = p0 - p1;
    let qa = 6.0 * d + 3.0 * (m0 + m1);
    let qb = -6.0 * d - 4.0 * m0 - 2.0 * m1;
    let qc = m0;
    let p = |th: f64| {
        let th2 = th * th;
        let th3 = th2 * th;
        (2.0 * th3 - 3.0 * th2 + 1.0) * p0
            + (th3 - 2.0 * th2 + th) * m0
            + (3.0 * th2 - 2.0 * th3) * p1
            + (th3 - th2) * m1
    };
    // The critical points in (0, 1); a minimum is where p'' = 2Aθ + B > 0.
    let mut best: Option<(f64, f64)> = None;
    let mut consider = |th: f64| {
        if th > 0.0 && th < 1.0 && 2.0 * qa * th + qb > 0.0 {
            let v = p(th);
            if best.is_none_or(|(_, bv)| v < bv) {
                best = Some((th, v));
            }
        }
    };
    if qa.abs() <= 1e-12 * (qb.abs() + qc.abs()) {
        if qb != 0.0 {
            consider(-qc / qb);
        }
    } else {
        let disc = qb * qb - 4.0 * qa * qc;
        if disc >= 0.0 {
            // Roots without cancellation.
            let q = -0.5 * (qb + qb.signum() * disc.sqrt());
            if q != 0.0 {
                consider(q / qa);
                consider(qc / q);
            } else {
                consider(-qb / (2.0 * qa));
            }
        }
    }
    let (th, v) = best?;
    let margin = margin.unwrap_or(DIP_MARGIN * (p0 + th * (p1 - p0) - v));
    (v <= margin).then_some((a.t + th * h, v))
}

/// Whether the cubic Hermite model with end values `p0`, `p1` and scaled
/// slopes `m0`, `m1` (slope × step) has no dip that [`cubic_dip`] without a
/// margin could report, by the cheap tests alone: no interior minimum (`s`
/// does not fall at the start nor rise at the end), or a minimum that a
/// bound keeps above [`DIP_MARGIN`] × its depth. The slope terms' basis
/// functions are at most 4/27 in size, so the model stays above
/// min(p0, p1) − B and its depth below the chord is at most B,
/// B = 4/27 (|m0| + |m1|): a minimum above B/2 excludes a dip. Always
/// inlined: it decides nearly every guard at every step end.
#[inline(always)]
fn excluded_cheaply(p0: f64, p1: f64, m0: f64, m1: f64) -> bool {
    if !(m0 < 0.0 || m1 > 0.0) {
        return true;
    }
    let bound = 4.0 / 27.0 * (m0.abs() + m1.abs());
    p0.min(p1) - bound > DIP_MARGIN * bound
}

/// The knots, on side `sg`, of a guard's `(time, value, rate)` at a step's
/// two ends.
#[inline]
fn end_knots(sg: f64, p: (f64, f64, f64), q: (f64, f64, f64)) -> (Knot, Knot) {
    let knot = |(t, g, r): (f64, f64, f64)| Knot {
        t,
        s: sg * g,
        ds: sg * r,
    };
    (knot(p), knot(q))
}

/// Whether guard `i` may have crossed inside the step `[t0, t0 + h]` and come
/// back, from its values `gp`, `gn` and rates `rp`, `rn` at the ends: the
/// cheap test that decides whether the step's full dense output is needed.
#[inline]
pub(crate) fn may_dip(
    kind: Crossing,
    gp: f64,
    gn: f64,
    rp: f64,
    rn: f64,
    t0: f64,
    t1: f64,
) -> bool {
    let Some(sg) = dip_side(kind, gp, gn) else {
        return false;
    };
    let (a, b) = end_knots(sg, (t0, gp, rp), (t1, gn, rn));
    let h = b.t - a.t;
    // The cheap tests here, inlined; `cubic_dip` repeats them and decides
    // the rest.
    if h > 0.0 && excluded_cheaply(a.s, b.s, h * a.ds, h * b.ds) {
        return false;
    }
    cubic_dip(&a, &b, None).is_some()
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

/// Searches the dense output for a point where guard `idx`, on side `sg` at
/// both ends of the step, is on the crossed side, before `t_limit`: splits
/// the step at the minimum of the guard's cubic model wherever the model
/// cannot exclude a crossing, earliest interval first. Returns the bracket
/// `(a, g(a), b, g(b))` with `b` the first such point found (`sc.yc` is the
/// state there), or `None`.
#[allow(clippy::too_many_arguments)]
fn find_dip<const N: usize, S: HybridSystem<N>>(
    sys: &S,
    dense: &Dense<N>,
    idx: usize,
    sg: f64,
    k0: Knot,
    k1: Knot,
    t_limit: f64,
    err: &[f64; N],
    sc: &mut Scratch<N>,
) -> Option<(f64, f64, f64, f64)> {
    // Intervals to examine, with the margin measured for them (None: none yet).
    let mut stack = [(k0, k1, None::<f64>); DIP_MAX_SAMPLES + 1];
    let mut len = 1;
    let mut samples = 0;
    let mut dy = [0.0; N];
    while len > 0 {
        len -= 1;
        let (a, b, margin) = stack[len];
        if a.t >= t_limit {
            continue;
        }
        let Some((tm, predicted)) = cubic_dip(&a, &b, margin) else {
            continue;
        };
        if samples == DIP_MAX_SAMPLES {
            break;
        }
        samples += 1;
        dense.eval(tm, &mut sc.ya);
        let s = sg * sys.guard(tm, &sc.ya, idx);
        if s <= 0.0 {
            // A dip counts when it goes past zero by more than the step's
            // error estimate moves the guard: a shallower one is not
            // resolved by the solution (a tip freed on the ground with zero
            // velocity dips a nanometre below it on the dense output).
            for ((d, y), e) in dy.iter_mut().zip(&sc.ya).zip(err) {
                *d = y + e;
            }
            let noise = (s - sg * sys.guard(tm, &dy, idx)).abs();
            if s < -noise || noise == 0.0 {
                sc.yc = sc.ya;
                return Some((a.t, sg * a.s, tm, sg * s));
            }
        }
        dense.eval_rate(tm, &mut dy);
        let m = Knot {
            t: tm,
            s,
            ds: sg * sys.guard_rate(tm, &sc.ya, &dy, idx),
        };
        // The model erred by this much at its minimum; halves of the
        // interval are modelled better (O(h⁴)), so it bounds their error.
        let err = DIP_ERR_SAFETY * (s - predicted).abs();
        stack[len] = (m, b, Some(err));
        stack[len + 1] = (a, m, Some(err));
        len += 2;
    }
    None
}

/// Locates the earliest root, on `dense`, of the guards that crossed over
/// the step: between `gp` (at `dense.t0`) and `gn` (at `dense.t1`), or
/// out and back inside it (found from the rates `rp`, `rn` at the ends, see
/// [`find_dip`]; `err` is the step's local error estimate). Returns the guard's index and its event time; `sc.ybest`
/// is the state there (on the crossed side). Ties go to the lower index.
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
    sc: &mut Scratch<N>,
) -> Option<(usize, f64)> {
    let len = gp.len.min(gn.len);
    let mut best: Option<(usize, f64)> = None;
    for i in 0..len {
        let kind = gn.crossing[i];
        // The guard's bracket: not crossed at `a`, crossed at `b`, `sc.yc`
        // the state at `b`.
        let (falling, a, ga, b, gb) = if let Some(falling) =
            crossing_dir(kind, gp.value[i], gn.value[i])
        {
            sc.yc = dense.y1;
            (falling, dense.t0, gp.value[i], dense.t1, gn.value[i])
        } else if let Some(sg) = dip_side(kind, gp.value[i], gn.value[i]) {
            let (k0, k1) = end_knots(
                sg,
                (dense.t0, gp.value[i], rp[i]),
                (dense.t1, gn.value[i], rn[i]),
            );
            let t_limit = best.map_or(dense.t1, |(_, t_best)| t_best);
            let Some((a, ga, b, gb)) = find_dip(sys, dense, i, sg, k0, k1, t_limit, err, sc) else {
                continue;
            };
            (sg > 0.0, a, ga, b, gb)
        } else {
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
        let t_i = illinois(sys, dense, i, falling, a, ga, b, gb, tol, sc);
        if best.is_none_or(|(_, t_best)| t_i < t_best) {
            best = Some((i, t_i));
            sc.ybest = sc.yc;
        }
    }
    best
}
