//! The crossings a guard's values and rates at a step's ends hide
//! ([`EngineOptions::hidden_crossings`](crate::EngineOptions::hidden_crossings)):
//! the step split at the kinks of the right-hand side, a guard crossed at
//! another guard's event, a first root before the one a bracket converged
//! to.

use super::dip::{Knot, find_dip, knot};
use super::{Scratch, armed, illinois, is_crossed, past_noise, side};
use crate::dense::Dense;
use crate::system::{Guards, HybridSystem, MAX_GUARDS, MAX_KINKS, fd_delta};

/// The tolerance of a kink's location, relative to the step's length.
const KINK_TIME_TOL: f64 = 1e-8;

/// The kinks of the right-hand side that changed side over a step
/// ([`HybridSystem::kink_sides`]), located on its dense output, in time
/// order, with every guard there: its value, and its rates just before and
/// just after (a backward and a forward difference on the dense output, for
/// the rate jumps at a kink).
pub(super) struct Kinks<const N: usize> {
    pub(super) len: usize,
    pub(super) t: [f64; MAX_KINKS],
    pub(super) y: [[f64; N]; MAX_KINKS],
    pub(super) g: [[f64; MAX_GUARDS]; MAX_KINKS],
    pub(super) before: [[f64; MAX_GUARDS]; MAX_KINKS],
    pub(super) after: [[f64; MAX_GUARDS]; MAX_KINKS],
}

/// Locates the kinks in `changed` (bits of [`HybridSystem::kink_sides`],
/// `start` the bits at the step's start) on `dense` and evaluates the guards
/// at each, into `sc.kinks`.
pub(super) fn locate_kinks<const N: usize, S: HybridSystem<N>>(
    sys: &S,
    dense: &Dense<N>,
    start: u32,
    changed: u32,
    tol: f64,
    sc: &mut Scratch<N>,
) {
    sc.kinks.len = 0;
    let mut bits = changed;
    while bits != 0 {
        let j = bits.trailing_zeros() as usize;
        bits &= bits - 1;
        // Bit set: below zero; a kink not below zero at the start falls.
        let falling = start & (1 << j) == 0;
        let f = |t: f64, y: &[f64; N]| sys.kink(t, y, j);
        let (ga, gb) = (f(dense.t0, &dense.y0), f(dense.t1, &dense.y1));
        sc.yc = dense.y1;
        // A kink need not be located as tightly as an event: off by δ, a
        // guard's value there is off by its rates' jump times δ.
        let tol = tol.max(KINK_TIME_TOL * (dense.t1 - dense.t0));
        let (_, _, t) = illinois(f, dense, falling, dense.t0, ga, dense.t1, gb, tol, sc);
        // In time order; a kink at the time of one already found adds nothing.
        let k = &mut sc.kinks;
        let at = k.t[..k.len].partition_point(|&u| u < t);
        if at < k.len && k.t[at] == t {
            continue;
        }
        k.t.copy_within(at..k.len, at + 1);
        k.y.copy_within(at..k.len, at + 1);
        k.t[at] = t;
        k.y[at] = sc.yc;
        k.len += 1;
    }
    let mut g = Guards::default();
    let mut dy = [0.0; N];
    for k in 0..sc.kinks.len {
        let (t, y) = (sc.kinks.t[k], sc.kinks.y[k]);
        sys.guards(t, &y, &mut g);
        sc.kinks.g[k] = g.value;
        dense.eval_rate(t, &mut dy);
        let d = fd_delta(&y, &dy);
        for (side, out) in [
            (-1.0, &mut sc.kinks.before[k]),
            (1.0, &mut sc.kinks.after[k]),
        ] {
            if d == 0.0 {
                *out = [0.0; MAX_GUARDS];
                continue;
            }
            dense.eval(t + side * d, &mut sc.ya);
            let mut gd = Guards::default();
            sys.guards(t + side * d, &sc.ya, &mut gd);
            for ((r, a), b) in out.iter_mut().zip(&gd.value).zip(&g.value).take(g.len) {
                *r = side * (a - b) / d;
            }
        }
    }
}

/// The earliest root of guard `idx` that the dip search can find from the
/// bracket `[a, b]` (`ga` not crossed, `gb` crossed, `sc.yc` the state at
/// `b`), where `k0` is the guard's knot, on the side `sg` it starts on, at
/// the start of the smooth piece of the step that holds the bracket: the
/// root in the bracket and, with `hidden`, again before it. Illinois
/// converges to one of the roots in its bracket, and a guard that went out,
/// back and out again (a stick force leaving its cone twice) has its first
/// crossing before the root found: the piece up to the bracket's uncrossed
/// end is searched for a dip like a step of its own. Returns the root;
/// `sc.yc` is the state there.
// `!(a < b)` is deliberate, as in `illinois`: it is true for NaN too.
#[allow(clippy::too_many_arguments, clippy::neg_cmp_op_on_partial_ord)]
#[inline]
pub(super) fn locate_first<const N: usize, S: HybridSystem<N>>(
    sys: &S,
    dense: &Dense<N>,
    idx: usize,
    sg: f64,
    k0: Knot,
    bracket: (f64, f64, f64, f64),
    err: &[f64; N],
    tol: f64,
    hidden: bool,
    sc: &mut Scratch<N>,
) -> f64 {
    let falling = sg > 0.0;
    let (mut a, mut ga, mut b, mut gb) = bracket;
    let mut dy = [0.0; N];
    loop {
        let guard = |t: f64, y: &[f64; N]| sys.guard(t, y, idx);
        let (a_end, s_a, root) = illinois(guard, dense, falling, a, ga, b, gb, tol, sc);
        // A bracket from the piece's start leaves nothing before it.
        if !hidden || !(a_end > k0.t) {
            return root;
        }
        let yc = sc.yc;
        dense.eval(a_end, &mut sc.ya);
        dense.eval_rate(a_end, &mut dy);
        let ka = Knot {
            t: a_end,
            s: s_a,
            ds: sg * sys.guard_rate(a_end, &sc.ya, &dy, idx),
        };
        match find_dip(sys, dense, idx, sg, k0, ka, a_end, err, sc) {
            Some(earlier) => (a, ga, b, gb) = earlier,
            None => {
                sc.yc = yc;
                return root;
            }
        }
    }
}

/// The knot, on side `sg`, that starts the smooth piece of guard `i` holding
/// time `t`: its latest kink before `t` where it is uncrossed, or the step's
/// start.
pub(super) fn piece_start<const N: usize>(
    kinks: &Kinks<N>,
    i: usize,
    sg: f64,
    t: f64,
    start: Knot,
) -> Knot {
    (0..kinks.len)
        .rev()
        .find(|&k| kinks.t[k] < t && sg * kinks.g[k][i] > 0.0)
        .map_or(start, |k| {
            knot(sg, kinks.t[k], kinks.g[k][i], kinks.after[k][i])
        })
}

/// A guard whose dip the search could neither rule out nor find may be on
/// its crossed side at the earliest event `best`: after that event's reset
/// it would start the next step crossed and never fire. Each guard armed at
/// the step's start is checked there, by the dip search's own rule, and one
/// past zero is located within its piece before the event; the earlier
/// event is checked again, until none is crossed. Returns the earliest
/// event; `sc.ybest` is the state there.
// The guard index `i` is what the system is asked about; the arrays follow it.
#[allow(clippy::too_many_arguments, clippy::needless_range_loop)]
pub(super) fn check_at_event<const N: usize, S: HybridSystem<N>>(
    sys: &S,
    dense: &Dense<N>,
    gp: &Guards,
    rp: &[f64; MAX_GUARDS],
    len: usize,
    mut best: Option<(usize, f64)>,
    err: &[f64; N],
    tol: f64,
    sc: &mut Scratch<N>,
) -> Option<(usize, f64)> {
    let mut at_best = Guards::default();
    let mut dy = [0.0; N];
    // Each pass moves the event strictly earlier, to another guard's root;
    // one pass per guard bounds the search.
    for _ in 0..len {
        let Some((ib, t_best)) = best else { break };
        sys.guards(t_best, &sc.ybest, &mut at_best);
        let mut earlier: Option<(usize, f64)> = None;
        let mut y_earlier = sc.ybest;
        for i in 0..len.min(at_best.len) {
            let Some(falling) = armed(gp.crossing[i], gp.value[i]) else {
                continue;
            };
            let v = at_best.value[i];
            let sg = side(falling);
            if i == ib
                || !is_crossed(falling, v)
                || !past_noise(sys, i, t_best, &sc.ybest, err, sg * v, sg, &mut dy)
            {
                continue;
            }
            let k0 = knot(sg, dense.t0, gp.value[i], rp[i]);
            let k0 = piece_start(&sc.kinks, i, sg, t_best, k0);
            sc.yc = sc.ybest;
            let bracket = (k0.t, sg * k0.s, t_best, v);
            let t_i = locate_first(sys, dense, i, sg, k0, bracket, err, tol, true, sc);
            if t_i < earlier.map_or(t_best, |(_, t)| t) {
                earlier = Some((i, t_i));
                y_earlier = sc.yc;
            }
        }
        let Some(e) = earlier else { break };
        best = Some(e);
        sc.ybest = y_earlier;
    }
    best
}

#[cfg(test)]
mod tests {
    //! Each hidden crossing on one constructed step, with and without the
    //! search: `x = t` on `[t0, t1]` (the cubic Hermite of `ẋ = 1`, exact).
    use super::super::*;
    use crate::system::Flow;

    /// Guards `guards(x)`, all falling; the right-hand side kinks at `kink`.
    struct Line {
        guards: fn(f64) -> Vec<f64>,
        kink: Option<f64>,
    }

    impl HybridSystem<1> for Line {
        type Aux = ();
        type Transition = Flow;
        fn rhs(&self, _t: f64, _y: &[f64; 1], dy: &mut [f64; 1]) {
            dy[0] = 1.0;
        }
        fn guards(&self, _t: f64, y: &[f64; 1], out: &mut Guards) {
            out.clear();
            for g in (self.guards)(y[0]) {
                out.push(g, Crossing::Falling);
            }
        }
        fn kink(&self, _t: f64, y: &[f64; 1], _index: usize) -> f64 {
            y[0] - self.kink.unwrap()
        }
        fn reset(&mut self, _t: f64, _y: &mut [f64; 1], _index: usize) -> Flow {
            Flow::Continue
        }
    }

    /// The step's event as the engine finds it: none unless a guard crossed
    /// at the step's end, may have inside it, or (with the search) the
    /// right-hand side kinked inside it.
    fn event(sys: &Line, (t0, t1): (f64, f64), hidden: bool) -> Option<(usize, f64)> {
        let mut dense = Dense::constant(t0, &[t0]);
        dense.set_hermite(t0, &[t0], &[1.0], t1 - t0, t1, &[t1], &[1.0]);
        let (mut gp, mut gn) = (Guards::default(), Guards::default());
        sys.guards(t0, &[t0], &mut gp);
        sys.guards(t1, &[t1], &mut gn);
        let (mut rp, mut rn) = ([0.0; MAX_GUARDS], [0.0; MAX_GUARDS]);
        for i in 0..gp.len {
            rp[i] = sys.guard_rate(t0, &[t0], &[1.0], i);
            rn[i] = sys.guard_rate(t1, &[t1], &[1.0], i);
        }
        // Kink 0's bit is set below it: set at the start, cleared at the end.
        let kinked = sys.kink.is_some_and(|k| t0 < k && k < t1);
        let kinks = if hidden && kinked { (1, 1) } else { (0, 0) };
        if !any_crossing(&gp, &gn, &rp, &rn, t0, t1) && kinks.1 == 0 {
            return None;
        }
        let err = [1e-12];
        let mut sc = Scratch::new();
        locate_earliest(
            sys,
            &dense,
            &gp,
            &gn,
            &rp,
            &rn,
            &err,
            1e-13,
            (hidden, kinks),
            &mut sc,
        )
    }

    /// Whether `got` is guard `guard` at `t` to 1e-12.
    fn is(got: Option<(usize, f64)>, guard: usize, t: f64) -> bool {
        got.is_some_and(|(g, te)| g == guard && (te - t).abs() <= 1e-12)
    }

    #[test]
    fn a_v_at_a_kink_is_found_only_by_splitting_the_step_there() {
        // |x − 1| − 0.01 from x = 0.5 to 1.5: equal ends, opposite rates; its
        // cubic model bottoms out at 0.24, its minimum is −0.01 at the kink.
        let sys = Line {
            guards: |x| vec![(x - 1.0).abs() - 0.01],
            kink: Some(1.0),
        };
        assert_eq!(event(&sys, (0.5, 1.5), false), None);
        let found = event(&sys, (0.5, 1.5), true);
        assert!(is(found, 0, 0.99), "{found:?}");
    }

    #[test]
    fn a_guard_crossed_at_another_guards_event_is_located_before_it() {
        // Guard 0 dips below zero within 1 ± 0.0083, with no slope at the
        // step's ends; guard 1 crosses at 1.005, inside that dip.
        let sys = Line {
            guards: |x| vec![1.0 - 2.0 * (-((x - 1.0) / 0.01).powi(2)).exp(), 1.005 - x],
            kink: None,
        };
        let plain = event(&sys, (0.5, 1.5), false);
        assert!(is(plain, 1, 1.005), "{plain:?}");
        let found = event(&sys, (0.5, 1.5), true);
        assert!(is(found, 0, 1.0 - 0.01 * 2f64.ln().sqrt()), "{found:?}");
    }

    #[test]
    fn a_guard_with_three_roots_in_its_bracket_fires_at_the_first() {
        // (0.9 − x)(x − 0.95)(x − 2) on [0, 2.5] falls at 0.9, rises at 0.95
        // and falls at 2: the root finder's first secant lands in the hump
        // between the last two and it converges to 2.
        let sys = Line {
            guards: |x| vec![(0.9 - x) * (x - 0.95) * (x - 2.0)],
            kink: None,
        };
        let plain = event(&sys, (0.0, 2.5), false);
        assert!(is(plain, 0, 2.0), "{plain:?}");
        let found = event(&sys, (0.0, 2.5), true);
        assert!(is(found, 0, 0.9), "{found:?}");
    }
}
