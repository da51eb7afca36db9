//! The dip search: whether a guard that is on one side of zero at both ends
//! of a step can have gone out and back inside it, from the cubic Hermite
//! model of its values and rates at the ends, and where, sampled on the
//! dense output.

use super::{Scratch, armed, past_noise, side};
use crate::dense::Dense;
use crate::system::{Crossing, HybridSystem};

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

/// A guard's signed value `s = σ g` (σ = ±1, positive on the side it starts
/// on) and its time derivative at time `t`.
#[derive(Clone, Copy)]
pub(super) struct Knot {
    pub(super) t: f64,
    pub(super) s: f64,
    pub(super) ds: f64,
}

/// The side σ (+1 above zero, −1 below) from which guard `kind` could cross
/// and come back within a step whose ends are `p` and `q`: both on that side
/// strictly, and the guard fires leaving it. `None`: no dip can fire.
#[inline]
fn dip_side(kind: Crossing, p: f64, q: f64) -> Option<f64> {
    // Strictly on that side (a NaN is on neither).
    armed(kind, p)
        .filter(|&falling| if falling { q > 0.0 } else { q < 0.0 })
        .map(side)
}

/// The time of the minimum of the cubic Hermite model of `s` on `[a.t, b.t]`
/// (through both values and slopes), if the model cannot exclude `s <= 0`
/// there: its interior minimum is at most `margin` (when given) or
/// [`DIP_MARGIN`] × its depth below the chord. Also returns the model's value
/// there. `None` when the slopes allow no interior minimum (`s` does not
/// fall at `a` nor rise at `b`: a cubic with `ṡ(a) >= 0 >= ṡ(b)` has none).
#[inline]
pub(super) fn cubic_dip(a: &Knot, b: &Knot, margin: Option<f64>) -> Option<(f64, f64)> {
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
pub(super) fn excluded_cheaply(p0: f64, p1: f64, m0: f64, m1: f64) -> bool {
    if !(m0 < 0.0 || m1 > 0.0) {
        return true;
    }
    let bound = 4.0 / 27.0 * (m0.abs() + m1.abs());
    p0.min(p1) - bound > DIP_MARGIN * bound
}

/// The knot, on side `sg`, of a guard at `(t, g)` with rate `r`.
#[inline]
pub(super) fn knot(sg: f64, t: f64, g: f64, r: f64) -> Knot {
    Knot {
        t,
        s: sg * g,
        ds: sg * r,
    }
}

/// Searches the dense output for a point where guard `idx`, on side `sg` at
/// both ends of the step, is on the crossed side, before `t_limit`: splits
/// the step at the minimum of the guard's cubic model wherever the model
/// cannot exclude a crossing, earliest interval first. Returns the bracket
/// `(a, g(a), b, g(b))` with `b` the first such point found (`sc.yc` is the
/// state there), or `None`.
#[allow(clippy::too_many_arguments)]
pub(super) fn find_dip<const N: usize, S: HybridSystem<N>>(
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
        if s <= 0.0 && past_noise(sys, idx, tm, &sc.ya, err, s, sg, &mut dy) {
            sc.yc = sc.ya;
            return Some((a.t, sg * a.s, tm, sg * s));
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

/// Whether guard `i` may have crossed inside the step `[t0, t0 + h]` and come
/// back, from its values `gp`, `gn` and rates `rp`, `rn` at the ends: the
/// cheap test that decides whether the step's full dense output is needed.
#[inline]
pub(super) fn may_dip(
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
    let (a, b) = (knot(sg, t0, gp, rp), knot(sg, t1, gn, rn));
    let h = b.t - a.t;
    // The cheap tests here, inlined; `cubic_dip` repeats them and decides
    // the rest.
    if h > 0.0 && excluded_cheaply(a.s, b.s, h * a.ds, h * b.ds) {
        return false;
    }
    cubic_dip(&a, &b, None).is_some()
}
