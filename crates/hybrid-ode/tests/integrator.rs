//! Orders of convergence, tolerance, dense output and event location of the
//! Runge–Kutta methods and the hybrid engine, each against a closed form.

use hybrid_ode::kernels::{fixed_step_solve, step_with_dense};
use hybrid_ode::{
    Crossing, Dense, EndReason, EngineOptions, Flow, Guards, HybridSystem, Method, Observer,
    RunEnd, StepEnd, run,
};

// ---------------------------------------------------------------------------
// Helpers
// ---------------------------------------------------------------------------

/// Least-squares slope of `log err` against `log h`.
fn fitted_order(hs: &[f64], errs: &[f64]) -> f64 {
    let n = hs.len() as f64;
    let xs: Vec<f64> = hs.iter().map(|h| h.ln()).collect();
    let ys: Vec<f64> = errs.iter().map(|e| e.ln()).collect();
    let mx = xs.iter().sum::<f64>() / n;
    let my = ys.iter().sum::<f64>() / n;
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

fn sci(v: &[f64]) -> String {
    v.iter()
        .map(|x| format!("{x:.3e}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The harmonic oscillator `x'' = −x`: `y = [x, v]`.
fn osc(_t: f64, y: &[f64; 2], dy: &mut [f64; 2]) {
    dy[0] = y[1];
    dy[1] = -y[0];
}

/// Its exact flow over a time `s` from `y0` (a rotation).
fn osc_flow(y0: &[f64; 2], s: f64) -> [f64; 2] {
    let (sn, cs) = s.sin_cos();
    [y0[0] * cs + y0[1] * sn, -y0[0] * sn + y0[1] * cs]
}

fn dist(a: &[f64; 2], b: &[f64; 2]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt()
}

/// Global error at `t = 10` of `method` with `n` fixed steps on the oscillator
/// from `[1, 0]` (exact: `[cos t, −sin t]`).
fn osc_fixed_error(method: Method, n: u64) -> f64 {
    let mut y = [1.0, 0.0];
    fixed_step_solve(method, osc, 0.0, &mut y, 10.0, n);
    dist(&y, &osc_flow(&[1.0, 0.0], 10.0))
}

fn check_order(method: Method, ns: &[u64], order: f64) -> f64 {
    let hs: Vec<f64> = ns.iter().map(|&n| 10.0 / n as f64).collect();
    let errs: Vec<f64> = ns.iter().map(|&n| osc_fixed_error(method, n)).collect();
    let p = fitted_order(&hs, &errs);
    println!(
        "{method:?}: h = {hs:?}, errors = {}, fitted order {p:.3}",
        sci(&errs)
    );
    assert!(
        (p - order).abs() <= 0.3,
        "{method:?}: fitted order {p} (errors {errs:?}), expected {order}"
    );
    p
}

// ---------------------------------------------------------------------------
// Orders of the methods (fixed steps, closed form x = cos t)
// ---------------------------------------------------------------------------

#[test]
fn rk4_global_error_falls_at_order_4() {
    check_order(Method::Rk4, &[40, 80, 160, 320], 4.0);
}

#[test]
fn dp5_global_error_falls_at_order_5() {
    check_order(Method::Dp54, &[40, 80, 160, 320], 5.0);
}

#[test]
fn dop853_global_error_falls_at_order_8() {
    check_order(Method::Dop853, &[8, 16, 32, 64], 8.0);
}

/// The dense output's local error at the midpoint of one step, from the exact
/// state, on `y' = y cos t` (exact `y = exp(sin t)`): `O(h^(q+1))` for a dense
/// output of order `q` (RK4's cubic Hermite 3, DP5 4, DOP853 7).
fn dense_local_error(method: Method, h: f64) -> f64 {
    let t0 = 0.3;
    let mut d = Dense::<1>::default();
    step_with_dense(
        method,
        |t, y: &[f64; 1], dy: &mut [f64; 1]| dy[0] = y[0] * t.cos(),
        t0,
        &[t0.sin().exp()],
        h,
        &mut d,
    );
    let mut out = [0.0];
    d.eval(t0 + 0.5 * h, &mut out);
    (out[0] - (t0 + 0.5 * h).sin().exp()).abs()
}

#[test]
fn dense_output_local_error_falls_at_dense_order_plus_one() {
    for (method, hs) in [
        (Method::Rk4, vec![0.2, 0.1, 0.05, 0.025]),
        (Method::Dp54, vec![0.2, 0.1, 0.05, 0.025]),
        (Method::Dop853, vec![0.32, 0.16, 0.08]),
    ] {
        let errs: Vec<f64> = hs.iter().map(|&h| dense_local_error(method, h)).collect();
        let p = fitted_order(&hs, &errs);
        let want = (method.dense_order() + 1) as f64;
        println!(
            "{method:?} dense: h = {hs:?}, errors = {}, fitted local order {p:.3}",
            sci(&errs)
        );
        assert!((p - want).abs() <= 0.3, "{method:?}: {p} vs {want}");
    }
}

#[test]
fn dense_output_interpolates_the_end_points() {
    for method in [Method::Rk4, Method::Dp54, Method::Dop853] {
        let mut d = Dense::<2>::default();
        step_with_dense(method, osc, 1.0, &[0.3, -0.7], 0.25, &mut d);
        let mut out = [0.0; 2];
        d.eval(d.t0, &mut out);
        assert_eq!(out, d.y0);
        d.eval(d.t1, &mut out);
        assert_eq!(out, d.y1);
        // The polynomial's own value at θ = 1 agrees with y1 to rounding.
        d.eval(d.t1 - 1e-15, &mut out);
        assert!(dist(&out, &d.y1) < 1e-14);
    }
}

// ---------------------------------------------------------------------------
// Adaptive runs through the engine
// ---------------------------------------------------------------------------

/// The oscillator as a hybrid system without guards; its observer measures
/// the dense output's error at each step's midpoint against the exact local
/// flow from the step's start, relative to the step tolerance there.
/// The harmonic oscillator as a system without events.
struct Oscillator;

impl HybridSystem<2> for Oscillator {
    type Aux = ();
    type Transition = Flow;

    fn rhs(&self, t: f64, y: &[f64; 2], dy: &mut [f64; 2]) {
        osc(t, y, dy);
    }
    fn guards(&self, _t: f64, _y: &[f64; 2], out: &mut Guards) {
        out.clear();
    }
    fn reset(&mut self, _t: f64, _y: &mut [f64; 2], _index: usize) -> Flow {
        unreachable!()
    }
}

/// Checks each step's dense output at its midpoint against the exact flow.
struct Midpoints {
    rtol: f64,
    atol: f64,
    worst_mid_ratio: f64,
    steps: u64,
}

impl Observer<2, Oscillator> for Midpoints {
    fn on_step(&mut self, _: &Oscillator, d: &Dense<2>, _: StepEnd<'_, ()>) -> Flow {
        let tm = 0.5 * (d.t0 + d.t1);
        let mut ym = [0.0; 2];
        d.eval(tm, &mut ym);
        let exact = osc_flow(&d.y0, tm - d.t0);
        let tol = self.atol + self.rtol * exact[0].abs().max(exact[1].abs());
        self.worst_mid_ratio = self.worst_mid_ratio.max(dist(&ym, &exact) / tol);
        self.steps += 1;
        Flow::Continue
    }
}

fn adaptive_opts(method: Method, rtol: f64) -> EngineOptions {
    EngineOptions {
        method,
        rtol,
        atol: rtol * 1e-2,
        h_max: f64::INFINITY,
        h_min: 1e-14,
        max_steps: 1_000_000,
        event_time_tol: 1e-13,
        zeno_events: 50,
        zeno_window: 1e-9,
        rk4_step: 0.01,
        hidden_crossings: false,
    }
}

#[test]
fn adaptive_runs_meet_the_tolerance() {
    // Reference: x = cos t, v = −sin t; a global error below 1e-8 at
    // rtol 1e-10 over 3 periods.
    for method in [Method::Dp54, Method::Dop853] {
        let opts = adaptive_opts(method, 1e-10);
        let mut sys = Midpoints {
            rtol: opts.rtol,
            atol: opts.atol,
            worst_mid_ratio: 0.0,
            steps: 0,
        };
        let mut y = [1.0, 0.0];
        let t_end = 6.0 * std::f64::consts::PI;
        let end = run(&mut Oscillator, &mut sys, 0.0, &mut y, t_end, &opts);
        assert_eq!(end.reason, EndReason::TimeUp);
        assert_eq!(end.t, t_end, "the last step is clamped to t_end");
        let err = dist(&y, &osc_flow(&[1.0, 0.0], t_end));
        println!("{method:?}: error {err:.3e} after {:?}", end.work);
        assert!(err < 1e-8, "{method:?}: error {err}");
        assert_eq!(sys.steps, end.work.steps);
        // Every accepted step costs evals_per_step, plus f(t0) and hinit's one,
        // plus DOP853's 3 dense stages per step (the observer wants them).
        let per_step = method.evals_per_step() + if method == Method::Dop853 { 3 } else { 0 };
        assert_eq!(
            end.work.rhs_evals,
            2 + per_step * end.work.steps + method.evals_per_step() * end.work.rejected
        );
    }
}

#[test]
fn adaptive_dense_output_is_accurate_between_steps() {
    // Reference: the exact local flow (a rotation) from each step's start.
    // The local error of the dense output at the midpoint is of the size of
    // the error the step-size control allows (DP5: 4th-order interpolant of
    // a 5th-order step; DOP853: 7th-order interpolant of an 8th-order step).
    for method in [Method::Dp54, Method::Dop853] {
        for rtol in [1e-6, 1e-9] {
            let opts = adaptive_opts(method, rtol);
            let mut sys = Midpoints {
                rtol: opts.rtol,
                atol: opts.atol,
                worst_mid_ratio: 0.0,
                steps: 0,
            };
            let mut y = [1.0, 0.0];
            run(&mut Oscillator, &mut sys, 0.0, &mut y, 20.0, &opts);
            println!(
                "{method:?} rtol {rtol:e}: worst midpoint dense error / step tolerance = {:.3}",
                sys.worst_mid_ratio
            );
            assert!(sys.worst_mid_ratio < 5.0, "{}", sys.worst_mid_ratio);
        }
    }
}

#[test]
fn rk4_runs_fixed_steps_and_clamps_the_last() {
    let opts = EngineOptions {
        method: Method::Rk4,
        rk4_step: 0.3,
        h_max: 1.0,
        ..EngineOptions::default()
    };
    let mut y = [1.0, 0.0];
    let end = run(&mut Oscillator, &mut (), 0.0, &mut y, 1.0, &opts);
    assert_eq!(end.reason, EndReason::TimeUp);
    assert_eq!(end.t, 1.0);
    // Steps 0.3, 0.3, 0.3, 0.1.
    assert_eq!(end.work.steps, 4);
    assert_eq!(end.work.rejected, 0);
    assert_eq!(end.work.rhs_evals, 1 + 4 * 4);
    assert!(dist(&y, &osc_flow(&[1.0, 0.0], 1.0)) < 1e-3);
}

// ---------------------------------------------------------------------------
// Event location: the bouncing ball
// ---------------------------------------------------------------------------

/// A ball `y'' = −g` with guard `y` (falling) and the bounce `v ← −e v`.
struct Ball {
    g: f64,
    e: f64,
    times: [f64; 64],
    n: usize,
    stop_after: usize,
}

impl Ball {
    fn new(e: f64, stop_after: usize) -> Self {
        Self {
            g: 9.81,
            e,
            times: [0.0; 64],
            n: 0,
            stop_after,
        }
    }
}

impl HybridSystem<2> for Ball {
    type Aux = ();
    type Transition = Flow;

    fn rhs(&self, _t: f64, y: &[f64; 2], dy: &mut [f64; 2]) {
        dy[0] = y[1];
        dy[1] = -self.g;
    }
    fn guards(&self, _t: f64, y: &[f64; 2], out: &mut Guards) {
        out.clear();
        out.push(y[0], Crossing::Falling);
    }
    fn reset(&mut self, t: f64, y: &mut [f64; 2], index: usize) -> Flow {
        assert_eq!(index, 0);
        assert!(y[0] <= 0.0, "the event state is on the crossed side");
        if self.n < self.times.len() {
            self.times[self.n] = t;
        }
        self.n += 1;
        y[1] *= -self.e;
        if self.n >= self.stop_after {
            Flow::Stop
        } else {
            Flow::Continue
        }
    }
}

/// Closed form: the k-th impact time of a ball dropped from `h0` at rest,
/// `t_1 = sqrt(2 h0 / g)`, `t_{k+1} = t_k + 2 e^k v_1 / g` with `v_1 = g t_1`.
fn ball_impact_time(g: f64, h0: f64, e: f64, k: usize) -> f64 {
    let t1 = (2.0 * h0 / g).sqrt();
    let v1 = g * t1;
    let mut t = t1;
    for j in 1..k {
        t += 2.0 * e.powi(j as i32) * v1 / g;
    }
    t
}

#[test]
fn falling_ball_event_time_is_exact() {
    let h0 = 1.7;
    let g = 9.81;
    for method in [Method::Dp54, Method::Dop853] {
        let opts = EngineOptions {
            h_max: 0.1,
            ..adaptive_opts(method, 1e-10)
        };
        let mut ball = Ball::new(0.0, 1);
        let mut y = [h0, 0.0];
        let end = run(&mut ball, &mut (), 0.0, &mut y, 10.0, &opts);
        assert_eq!(end.reason, EndReason::Stopped);
        let exact = (2.0 * h0 / g).sqrt();
        let err = (ball.times[0] - exact).abs();
        println!(
            "{method:?}: first impact error {err:.3e} s ({:?})",
            end.work
        );
        assert!(err <= 1e-12, "{method:?}: {err}");
        assert_eq!(end.t, ball.times[0]);
    }
}

#[test]
fn bouncing_ball_event_times_match_the_closed_form() {
    let (h0, g, e) = (1.7, 9.81, 0.8);
    for method in [Method::Dp54, Method::Dop853] {
        let opts = EngineOptions {
            h_max: 0.1,
            ..adaptive_opts(method, 1e-10)
        };
        let mut ball = Ball::new(e, 5);
        let mut y = [h0, 0.0];
        let end = run(&mut ball, &mut (), 0.0, &mut y, 100.0, &opts);
        assert_eq!(end.reason, EndReason::Stopped);
        assert_eq!(end.work.events, 5);
        for k in 1..=5 {
            let exact = ball_impact_time(g, h0, e, k);
            let err = (ball.times[k - 1] - exact).abs();
            println!("{method:?}: impact {k} error {err:.3e} s");
            // Each bounce re-locates from a state whose error is g·Δt, so
            // the located times drift by a few event tolerances at most.
            assert!(err <= 1e-12 * k as f64, "{method:?} impact {k}: {err}");
        }
    }
}

#[test]
fn rk4_locates_events_on_its_hermite_interpolant() {
    // The Hermite cubic through exact values and slopes of a parabola is the
    // parabola, and RK4 integrates y'' = −g exactly, so the event is exact.
    let (h0, g) = (1.7, 9.81);
    let opts = EngineOptions {
        method: Method::Rk4,
        rk4_step: 0.07,
        h_max: 1.0,
        ..EngineOptions::default()
    };
    let mut ball = Ball::new(0.5, 3);
    let mut y = [h0, 0.0];
    let end = run(&mut ball, &mut (), 0.0, &mut y, 100.0, &opts);
    assert_eq!(end.reason, EndReason::Stopped);
    for k in 1..=3 {
        let err = (ball.times[k - 1] - ball_impact_time(g, h0, 0.5, k)).abs();
        assert!(err <= 1e-12 * k as f64, "impact {k}: {err}");
    }
}

#[test]
fn infinitely_many_bounces_end_as_zeno() {
    // The bounce times accumulate at t∞ = t1 (1 + e)/(1 − e), the gaps being
    // 2 e^k v1/g. Events are only seen while a flight outlasts a step, so
    // h_max is kept below the gaps of the bounces the Zeno rule needs: with
    // e = 0.8, the 11 bounces with gaps < 0.05 s last at least 5 ms.
    let (g, e) = (9.81, 0.8);
    let opts = EngineOptions {
        h_max: 1e-3,
        zeno_events: 10,
        zeno_window: 0.05,
        ..adaptive_opts(Method::Dp54, 1e-10)
    };
    let mut ball = Ball::new(e, usize::MAX);
    let mut y = [1.0, 0.0];
    let end = run(&mut ball, &mut (), 0.0, &mut y, 100.0, &opts);
    assert_eq!(end.reason, EndReason::Zeno, "{end:?}");
    // The gap from impact k to k+1 is 2 e^k v1/g; the first below 0.05 s is
    // k0 = 13 (0.903·0.8^13 = 0.049). Impacts k0, k0+1, … then form a run
    // with gaps < 0.05 s, and its 11th member (> zeno_events) is impact
    // k0 + 10, where the run ends.
    let v1 = (2.0 * g * 1.0f64).sqrt();
    let k0 = (1..).find(|&k| 2.0 * e.powi(k) * v1 / g < 0.05).unwrap() as usize;
    assert_eq!(k0, 13);
    assert_eq!(end.work.events as usize, k0 + 10);
    let t_zeno = ball_impact_time(g, 1.0, e, k0 + 10);
    assert!((end.t - t_zeno).abs() < 1e-10, "{} vs {t_zeno}", end.t);
}

// ---------------------------------------------------------------------------
// Guard semantics
// ---------------------------------------------------------------------------

/// `x = sin t` (as the oscillator from `[0, 1]`) with one guard of a given
/// direction on `x`; records the event times; the reset does nothing.
struct SineGuard {
    crossing: Crossing,
    times: [f64; 16],
    n: usize,
}

impl HybridSystem<2> for SineGuard {
    type Aux = ();
    type Transition = Flow;

    fn rhs(&self, t: f64, y: &[f64; 2], dy: &mut [f64; 2]) {
        osc(t, y, dy);
    }
    fn guards(&self, _t: f64, y: &[f64; 2], out: &mut Guards) {
        out.clear();
        out.push(y[0], self.crossing);
    }
    fn reset(&mut self, t: f64, _y: &mut [f64; 2], _index: usize) -> Flow {
        self.times[self.n] = t;
        self.n += 1;
        Flow::Continue
    }
}

fn sine_events(crossing: Crossing, method: Method) -> Vec<f64> {
    let mut sys = SineGuard {
        crossing,
        times: [0.0; 16],
        n: 0,
    };
    let opts = EngineOptions {
        h_max: 0.1,
        ..adaptive_opts(method, 1e-10)
    };
    // x(0) = 0 exactly: the guard starts at 0 and must not fire at t = 0.
    let mut y = [0.0, 1.0];
    let end = run(&mut sys, &mut (), 0.0, &mut y, 10.0, &opts);
    assert_eq!(end.reason, EndReason::TimeUp);
    sys.times[..sys.n].to_vec()
}

#[test]
fn guard_directions_and_zero_start() {
    use std::f64::consts::PI;
    // Closed form: x = sin t crosses 0 at kπ, falling at odd k, rising at even k.
    for method in [Method::Dp54, Method::Dop853, Method::Rk4] {
        let tol = if method.is_adaptive() { 1e-9 } else { 1e-7 };
        let falling = sine_events(Crossing::Falling, method);
        let rising = sine_events(Crossing::Rising, method);
        let either = sine_events(Crossing::Either, method);
        let close = |got: &[f64], want: &[f64]| {
            assert_eq!(got.len(), want.len(), "{method:?}: {got:?} vs {want:?}");
            for (a, b) in got.iter().zip(want) {
                assert!((a - b).abs() < tol, "{method:?}: {got:?} vs {want:?}");
            }
        };
        close(&falling, &[PI, 3.0 * PI]);
        close(&rising, &[2.0 * PI]);
        close(&either, &[PI, 2.0 * PI, 3.0 * PI]);
    }
}

/// Two guards crossing in the same step: the earlier one wins.
struct TwoGuards {
    first: Option<(usize, f64)>,
}

impl HybridSystem<1> for TwoGuards {
    type Aux = ();
    type Transition = Flow;

    fn rhs(&self, _t: f64, _y: &[f64; 1], dy: &mut [f64; 1]) {
        dy[0] = 1.0;
    }
    fn guards(&self, _t: f64, y: &[f64; 1], out: &mut Guards) {
        out.clear();
        out.push(y[0] - 0.55, Crossing::Rising);
        out.push(y[0] - 0.52, Crossing::Rising);
        out.push(0.53 - y[0], Crossing::Falling);
    }
    fn reset(&mut self, t: f64, _y: &mut [f64; 1], index: usize) -> Flow {
        self.first = Some((index, t));
        Flow::Stop
    }
}

#[test]
fn the_earliest_of_several_crossings_fires() {
    for method in [Method::Dp54, Method::Dop853, Method::Rk4] {
        let mut sys = TwoGuards { first: None };
        let opts = EngineOptions {
            method,
            h_max: 1.0,
            rk4_step: 0.5,
            ..EngineOptions::default()
        };
        let mut y = [0.0];
        let end = run(&mut sys, &mut (), 0.0, &mut y, 2.0, &opts);
        assert_eq!(end.reason, EndReason::Stopped);
        let (i, t) = sys.first.unwrap();
        assert_eq!(i, 1, "{method:?}");
        assert!((t - 0.52).abs() <= 1e-13, "{method:?}: {t}");
    }
}

/// [`TwoGuards`] with counters, and optionally its own one-guard evaluation
/// (`HybridSystem::guard`) instead of the default through `guards`.
struct CountedGuards {
    inner: TwoGuards,
    own_guard: bool,
    guards_calls: std::cell::Cell<u64>,
    guard_calls: std::cell::Cell<[u64; 3]>,
}

impl HybridSystem<1> for CountedGuards {
    type Aux = ();
    type Transition = Flow;

    fn rhs(&self, t: f64, y: &[f64; 1], dy: &mut [f64; 1]) {
        self.inner.rhs(t, y, dy);
    }
    fn guards(&self, t: f64, y: &[f64; 1], out: &mut Guards) {
        self.guards_calls.set(self.guards_calls.get() + 1);
        self.inner.guards(t, y, out);
    }
    fn guard(&self, t: f64, y: &[f64; 1], index: usize) -> f64 {
        let mut c = self.guard_calls.get();
        c[index] += 1;
        self.guard_calls.set(c);
        if self.own_guard {
            [y[0] - 0.55, y[0] - 0.52, 0.53 - y[0]][index]
        } else {
            let mut g = Guards::default();
            self.inner.guards(t, y, &mut g);
            g.value[index]
        }
    }
    fn reset(&mut self, t: f64, y: &mut [f64; 1], index: usize) -> Flow {
        self.inner.reset(t, y, index)
    }
}

#[test]
fn root_finding_evaluates_one_guard_at_a_time() {
    // Event location asks only for the guard it locates (and, once, for a
    // later guard at the earliest event so far); the whole set is evaluated
    // at step ends only (values and rates). A system's own one-guard evaluation must give the
    // same event, bit for bit, as the default through `guards`.
    for method in [Method::Dp54, Method::Dop853, Method::Rk4] {
        let opts = EngineOptions {
            method,
            h_max: 1.0,
            rk4_step: 0.5,
            ..EngineOptions::default()
        };
        let mut found = Vec::new();
        for own_guard in [false, true] {
            let mut sys = CountedGuards {
                inner: TwoGuards { first: None },
                own_guard,
                guards_calls: Default::default(),
                guard_calls: Default::default(),
            };
            let mut y = [0.0];
            let end = run(&mut sys, &mut (), 0.0, &mut y, 2.0, &opts);
            assert_eq!(end.reason, EndReason::Stopped);
            // One set at the start and at each accepted step's end, and one
            // more at each for the guards' rates (the default
            // `guard_rates`: a forward difference of the set along ẏ).
            assert_eq!(
                sys.guards_calls.get(),
                2 * (1 + end.work.steps),
                "{method:?}"
            );
            let calls = sys.guard_calls.get();
            assert!(calls[1] > 0, "{method:?}: {calls:?}");
            let (i, t) = sys.inner.first.unwrap();
            assert_eq!(i, 1, "{method:?}");
            assert!((t - 0.52).abs() <= 1e-13, "{method:?}: {t}");
            found.push((i, t.to_bits(), y[0].to_bits(), calls));
        }
        assert_eq!(found[0], found[1], "{method:?}");
    }
}

// ---------------------------------------------------------------------------
// Run ends
// ---------------------------------------------------------------------------

/// `y' = 1` whose right-hand side is NaN beyond `y = 1`.
struct Blowup;

impl HybridSystem<1> for Blowup {
    type Aux = ();
    type Transition = Flow;

    fn rhs(&self, _t: f64, y: &[f64; 1], dy: &mut [f64; 1]) {
        dy[0] = if y[0] > 1.0 { f64::NAN } else { 1.0 };
    }
    fn guards(&self, _t: f64, _y: &[f64; 1], out: &mut Guards) {
        out.clear();
    }
    fn reset(&mut self, _t: f64, _y: &mut [f64; 1], _index: usize) -> Flow {
        Flow::Continue
    }
}

#[test]
fn non_finite_values_end_the_run() {
    for method in [Method::Dp54, Method::Dop853, Method::Rk4] {
        let opts = EngineOptions {
            method,
            rk4_step: 0.01,
            ..EngineOptions::default()
        };
        let mut y = [0.0];
        let end: RunEnd = run(&mut Blowup, &mut (), 0.0, &mut y, 5.0, &opts);
        assert_eq!(end.reason, EndReason::NonFinite, "{method:?}");
        assert!(end.t <= 1.0 + 1e-9 && end.t > 0.9, "{method:?}: {}", end.t);
        assert!(y[0].is_finite());
    }
}

#[test]
fn work_budget_and_observer_stop() {
    let opts = EngineOptions {
        max_steps: 10,
        ..EngineOptions::default()
    };
    let mut y = [1.0, 0.0];
    let end = run(&mut Oscillator, &mut (), 0.0, &mut y, 100.0, &opts);
    assert_eq!(end.reason, EndReason::WorkBudget);
    assert_eq!(end.work.steps + end.work.rejected, 10);

    struct Clock;
    impl HybridSystem<1> for Clock {
        type Aux = ();
        type Transition = Flow;

        fn rhs(&self, _t: f64, _y: &[f64; 1], dy: &mut [f64; 1]) {
            dy[0] = 1.0;
        }
        fn guards(&self, _t: f64, _y: &[f64; 1], out: &mut Guards) {
            out.clear();
        }
        fn reset(&mut self, _t: f64, _y: &mut [f64; 1], _i: usize) -> Flow {
            Flow::Continue
        }
    }
    struct StopAt(f64);
    impl Observer<1, Clock> for StopAt {
        fn on_step(&mut self, _: &Clock, d: &Dense<1>, _: StepEnd<'_, ()>) -> Flow {
            if d.t1 >= self.0 {
                Flow::Stop
            } else {
                Flow::Continue
            }
        }
    }
    let mut y = [0.0];
    let end = run(
        &mut Clock,
        &mut StopAt(0.5),
        0.0,
        &mut y,
        1.0,
        &EngineOptions::default(),
    );
    assert_eq!(end.reason, EndReason::Stopped);
    assert!(end.t >= 0.5 && end.t < 0.52);
    assert!((y[0] - end.t).abs() < 1e-12);
}

#[test]
fn dense_output_rate_is_the_interpolant_s_derivative() {
    // Reference: central differences of `Dense::eval` inside the step, and
    // the right-hand side itself at the step's start (every interpolant here
    // is C¹ through f0).
    for method in [Method::Dp54, Method::Dop853, Method::Rk4] {
        let y0 = [1.0, 0.0];
        let mut d = Dense::default();
        step_with_dense(method, osc, 0.0, &y0, 0.5, &mut d);
        let mut r = [0.0; 2];
        d.eval_rate(0.0, &mut r);
        let mut f0 = [0.0; 2];
        osc(0.0, &y0, &mut f0);
        assert!(dist(&r, &f0) <= 1e-14, "{method:?}: {r:?} vs f0 {f0:?}");
        for t in [0.1, 0.25, 0.4] {
            let e = 1e-6;
            let (mut a, mut b) = ([0.0; 2], [0.0; 2]);
            d.eval(t + e, &mut a);
            d.eval(t - e, &mut b);
            let fd = [(a[0] - b[0]) / (2.0 * e), (a[1] - b[1]) / (2.0 * e)];
            d.eval_rate(t, &mut r);
            assert!(dist(&r, &fd) <= 1e-8, "{method:?} at {t}: {r:?} vs {fd:?}");
        }
    }
}
