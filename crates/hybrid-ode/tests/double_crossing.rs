//! Crossings that go out and back within one step: a guard that dips below
//! zero and returns between two step ends is found and located like any other
//! crossing, whatever the step size; a guard that comes close without crossing
//! fires nothing.

use hybrid_ode::{
    Crossing, Dense, EndReason, EngineOptions, Flow, Guards, HybridSystem, Method, Observer,
    StepEnd, run,
};

/// `ẋ = 1` from x = 0 (so x = t) with one guard `g(x) = σ((x − 1)² − ε)`:
/// for ε > 0 it crosses zero at 1 ∓ √ε, two roots 2√ε apart; for ε < 0
/// it comes within |ε| of zero and stays on its side. The reset does nothing.
struct Parabola {
    eps: f64,
    crossing: Crossing,
    /// σ: +1 (a dip below 0) or −1 (a bump above 0).
    sign: f64,
}

impl HybridSystem<1> for Parabola {
    type Aux = ();
    type Transition = Flow;

    fn rhs(&self, _t: f64, _y: &[f64; 1], dy: &mut [f64; 1]) {
        dy[0] = 1.0;
    }

    fn guards(&self, _t: f64, y: &[f64; 1], out: &mut Guards) {
        out.clear();
        out.push(self.sign * ((y[0] - 1.0).powi(2) - self.eps), self.crossing);
    }

    fn reset(&mut self, _t: f64, _y: &mut [f64; 1], _index: usize) -> Flow {
        Flow::Continue
    }
}

/// Records the events and the longest step.
#[derive(Default)]
struct Events {
    times: Vec<f64>,
    longest_step: f64,
}

impl<const N: usize, S: HybridSystem<N>> Observer<N, S> for Events {
    fn on_step(&mut self, _s: &S, d: &Dense<N>, end: StepEnd<'_, S::Aux>) -> Flow {
        self.longest_step = self.longest_step.max(d.t1 - d.t0);
        if let StepEnd::Event { .. } = end {
            self.times.push(d.t1);
        }
        Flow::Continue
    }

    fn reads_interior(&self, _s: &S, _t0: f64, _t1: f64) -> bool {
        false
    }
}

fn opts(method: Method, h_max: f64) -> EngineOptions {
    EngineOptions {
        method,
        rtol: 1e-6,
        atol: 1e-9,
        h_max,
        ..EngineOptions::default()
    }
}

/// Runs the parabola to t = 3 and returns its events and longest step.
fn events_of(sys: &mut Parabola, method: Method, h_max: f64) -> Events {
    let mut ev = Events::default();
    let mut y = [0.0];
    let end = run(sys, &mut ev, 0.0, &mut y, 3.0, &opts(method, h_max));
    assert_eq!(end.reason, EndReason::TimeUp);
    ev
}

#[test]
fn a_dip_inside_one_step_is_found_and_located_at_any_step_size() {
    // The flow is exact at any step, so the controller grows the step to
    // h_max: with h_max ≫ 2√ε both roots lie inside one step.
    for method in [Method::Dp54, Method::Dop853, Method::Rk4] {
        for eps in [1e-2, 1e-4, 1e-8] {
            for h_max in [0.05, 0.3, 1.0, 10.0] {
                let mut sys = Parabola {
                    eps,
                    crossing: Crossing::Falling,
                    sign: 1.0,
                };
                // RK4 steps at its own fixed step, capped by h_max.
                let mut o = opts(method, h_max);
                o.rk4_step = h_max;
                let mut ev = Events::default();
                let mut y = [0.0];
                let end = run(&mut sys, &mut ev, 0.0, &mut y, 3.0, &o);
                assert_eq!(end.reason, EndReason::TimeUp);
                let root = 1.0 - eps.sqrt();
                println!(
                    "{method:?} eps {eps:e} h_max {h_max}: longest step {:.3}, events {:?}",
                    ev.longest_step, ev.times
                );
                assert_eq!(ev.times.len(), 1, "{method:?} eps {eps} h_max {h_max}");
                assert!(
                    (ev.times[0] - root).abs() <= 1e-12,
                    "{method:?} eps {eps} h_max {h_max}: event at {} not {root}",
                    ev.times[0]
                );
            }
        }
    }
}

#[test]
fn the_steps_do_span_both_roots() {
    // What makes the test above a test: the step there is far longer than
    // the dip (without an event, one step covers [0.9, 1.1] and more).
    let mut sys = Parabola {
        eps: -1e-4,
        crossing: Crossing::Falling,
        sign: 1.0,
    };
    let ev = events_of(&mut sys, Method::Dp54, 10.0);
    assert!(ev.longest_step >= 1.0, "longest step {}", ev.longest_step);
}

#[test]
fn a_bump_above_zero_fires_a_rising_or_either_guard() {
    for crossing in [Crossing::Rising, Crossing::Either] {
        let mut sys = Parabola {
            eps: 1e-4,
            crossing,
            sign: -1.0,
        };
        let ev = events_of(&mut sys, Method::Dp54, 10.0);
        // After the reset the guard sits on its crossed side, so the Either
        // guard's return through zero is a second, falling, crossing.
        let expect: &[f64] = match crossing {
            Crossing::Rising => &[0.99],
            _ => &[0.99, 1.01],
        };
        assert_eq!(ev.times.len(), expect.len(), "{crossing:?}: {:?}", ev.times);
        for (t, e) in ev.times.iter().zip(expect) {
            assert!((t - e).abs() <= 1e-12, "{crossing:?}: {t} not {e}");
        }
    }
}

#[test]
fn a_guard_that_comes_close_without_crossing_fires_nothing() {
    for method in [Method::Dp54, Method::Dop853] {
        for eps in [-1e-2, -1e-8, -1e-14] {
            for h_max in [0.05, 1.0, 10.0] {
                let mut sys = Parabola {
                    eps,
                    crossing: Crossing::Either,
                    sign: 1.0,
                };
                let ev = events_of(&mut sys, method, h_max);
                assert!(
                    ev.times.is_empty(),
                    "{method:?} eps {eps} h_max {h_max}: {:?}",
                    ev.times
                );
            }
        }
    }
}

/// The oscillator `x'' = −x` from (1, 0) with the guard `x + 1 − ε`
/// (falling): the bottom of every swing dips a hair below −1 + ε, for
/// 2√(2ε) of time; the reset does nothing. Events: one per period.
struct Swing {
    eps: f64,
}

impl HybridSystem<2> for Swing {
    type Aux = ();
    type Transition = Flow;

    fn rhs(&self, _t: f64, y: &[f64; 2], dy: &mut [f64; 2]) {
        dy[0] = y[1];
        dy[1] = -y[0];
    }

    fn guards(&self, _t: f64, y: &[f64; 2], out: &mut Guards) {
        out.clear();
        out.push(y[0] + 1.0 - self.eps, Crossing::Falling);
    }

    fn reset(&mut self, _t: f64, _y: &mut [f64; 2], _index: usize) -> Flow {
        Flow::Continue
    }
}

#[test]
fn every_swing_that_touches_is_found_at_a_loose_tolerance_without_a_cap() {
    // x = cos t dips below −1 + ε around t = (2k+1)π, for ±√(2ε): at
    // ε = 1e-3 a window of 0.09 s, while the steps at rtol 1e-4 are longer.
    let eps: f64 = 1e-3;
    for method in [Method::Dp54, Method::Dop853] {
        let mut ev = Events::default();
        let mut y = [1.0, 0.0];
        let o = EngineOptions {
            method,
            rtol: 1e-4,
            atol: 1e-7,
            h_max: f64::INFINITY,
            ..EngineOptions::default()
        };
        let t_end = 20.0 * std::f64::consts::PI;
        let end = run(&mut Swing { eps }, &mut ev, 0.0, &mut y, t_end, &o);
        assert_eq!(end.reason, EndReason::TimeUp);
        println!(
            "{method:?}: longest step {:.3}, {} events",
            ev.longest_step,
            ev.times.len()
        );
        assert!(ev.longest_step > 4.0 * (2.0 * eps).sqrt());
        assert_eq!(ev.times.len(), 10, "{method:?}: {:?}", ev.times);
        for (k, t) in ev.times.iter().enumerate() {
            let exact = (2 * k + 1) as f64 * std::f64::consts::PI - (2.0 * eps).sqrt();
            // The located root is that of the numerical solution, whose
            // phase drifts at this tolerance (1e-2 s by the 10th swing): each
            // event is still inside its own swing's window, 0.09 s wide.
            assert!(
                (t - exact).abs() < 0.5 * (2.0 * eps).sqrt(),
                "{k}: {t} vs {exact}"
            );
        }
    }
}
