//! The crossings that a guard's values and rates at a step's ends hide,
//! found with `EngineOptions::hidden_crossings`, each on a constructed
//! system whose flow is exact (`ẋ = 1`, so `x = t` and the step grows to
//! `h_max`): a guard with a V where the right-hand side kinks, a guard still
//! crossed at another guard's event, and a guard with three roots in one
//! step. Without the option each is missed; the tests say so too, so that
//! they test something.

use hybrid_ode::{
    Crossing, Dense, EndReason, EngineOptions, Flow, Guards, HybridSystem, Method, Observer,
    StepEnd, run,
};

/// `ẋ = 1` from x = 0; the guards are `guards(x)`, all falling; the right-
/// hand side "kinks" where `x = kink` (its branch bit set below it), which is
/// what a system reports for a slack string going taut. Resets do nothing.
struct Line {
    guards: fn(f64) -> Vec<f64>,
    kink: Option<f64>,
}

impl HybridSystem<1> for Line {
    /// The state, for the kinks' sides.
    type Aux = f64;
    type Transition = Flow;

    fn rhs(&self, _t: f64, _y: &[f64; 1], dy: &mut [f64; 1]) {
        dy[0] = 1.0;
    }

    fn rhs_aux(&self, t: f64, y: &[f64; 1], dy: &mut [f64; 1], aux: &mut f64) {
        self.rhs(t, y, dy);
        *aux = y[0];
    }

    fn guards(&self, _t: f64, y: &[f64; 1], out: &mut Guards) {
        out.clear();
        for g in (self.guards)(y[0]) {
            out.push(g, Crossing::Falling);
        }
    }

    fn kink_sides(&self, _t: f64, _y: &[f64; 1], x: &f64) -> u32 {
        self.kink.map_or(0, |k| u32::from(x - k < 0.0))
    }

    fn kink(&self, _t: f64, y: &[f64; 1], index: usize) -> f64 {
        assert_eq!(index, 0);
        y[0] - self.kink.unwrap()
    }

    fn reset(&mut self, _t: f64, _y: &mut [f64; 1], _index: usize) -> Flow {
        Flow::Continue
    }
}

/// Records the events (time, guard) and the longest step.
#[derive(Default)]
struct Events {
    at: Vec<(f64, usize)>,
    longest_step: f64,
}

impl<const N: usize, S: HybridSystem<N>> Observer<N, S> for Events {
    fn on_step(&mut self, _s: &S, d: &Dense<N>, end: StepEnd<'_, S::Aux>) -> Flow {
        self.longest_step = self.longest_step.max(d.t1 - d.t0);
        if let StepEnd::Event { guard } = end {
            self.at.push((d.t1, guard));
        }
        Flow::Continue
    }

    fn reads_interior(&self, _s: &S, _t0: f64, _t1: f64) -> bool {
        false
    }
}

/// The events of `sys` to t = 3 at `h_max`, with or without the search.
fn events(sys: &mut Line, method: Method, h_max: f64, hidden: bool) -> Events {
    let opts = EngineOptions {
        method,
        rtol: 1e-6,
        atol: 1e-9,
        h_max,
        hidden_crossings: hidden,
        ..EngineOptions::default()
    };
    let mut ev = Events::default();
    let end = run(sys, &mut ev, 0.0, &mut [0.0], 3.0, &opts);
    assert_eq!(end.reason, EndReason::TimeUp);
    ev
}

/// Asserts that the events are `expect` (time to 1e-12, guard).
fn assert_events(ev: &Events, expect: &[(f64, usize)], what: &str) {
    assert_eq!(
        ev.at.len(),
        expect.len(),
        "{what}: {:?} not {expect:?}",
        ev.at
    );
    for (&(t, g), &(te, ge)) in ev.at.iter().zip(expect) {
        assert!(
            (t - te).abs() <= 1e-12 && g == ge,
            "{what}: {:?} not {expect:?}",
            ev.at
        );
    }
}

#[test]
fn a_v_shaped_dip_at_a_kink_of_the_right_hand_side_fires() {
    // g = |x − 1| − 0.01: two roots, 0.99 and 1.01, and its minimum, −0.01,
    // at the kink x = 1. From step ends far on both sides its values are
    // equal and its rates opposite, and the cubic model through them bottoms
    // out at a quarter of the step's length above zero: no dip. Split at
    // the kink, the guard is crossed there, and its root is in the first
    // piece.
    let v = |x: f64| vec![(x - 1.0).abs() - 0.01];
    for method in [Method::Dp54, Method::Dop853] {
        for h_max in [0.3, 1.0, 10.0] {
            let what = format!("{method:?} h_max {h_max}");
            let mut sys = Line {
                guards: v,
                kink: Some(1.0),
            };
            let found = events(&mut sys, method, h_max, true);
            assert_events(&found, &[(0.99, 0)], &what);
            assert!(found.longest_step >= h_max.min(1.0), "{what}: short steps");
        }
    }
}

#[test]
fn a_guard_crossed_at_another_guards_event_fires_first() {
    // Guard 0 dips below zero for 2 × 0.0083 around x = 1, far narrower than
    // a step, with a value near 1 and no slope at step ends away from it:
    // the cubic model excludes a dip. Guard 1 crosses at 1.005, inside that
    // dip, and at its event guard 0 is on its crossed side: its root,
    // 1 − 0.01 √ln 2, is the step's earliest event; guard 1 follows.
    let dip = |x: f64| vec![1.0 - 2.0 * (-((x - 1.0) / 0.01).powi(2)).exp(), 1.005 - x];
    let root = 1.0 - 0.01 * 2f64.ln().sqrt();
    for method in [Method::Dp54, Method::Dop853] {
        for h_max in [0.3, 1.0, 10.0] {
            let what = format!("{method:?} h_max {h_max}");
            let mut sys = Line {
                guards: dip,
                kink: None,
            };
            let found = events(&mut sys, method, h_max, true);
            assert_events(&found, &[(root, 0), (1.005, 1)], &what);
        }
    }
}

#[test]
fn a_guard_with_three_roots_in_a_step_fires_at_the_first() {
    // g = (0.9 − x)(x − 0.95)(x − 2) falls through zero at 0.9, rises at
    // 0.95 and falls again at 2: one bracket over a long step holds all
    // three, and the root finder, whose first secant lands in the hump
    // between the last two, may converge to 2. The first event is at 0.9.
    // (After its reset the guard starts on its crossed side, and whether it
    // fires again at 2 depends on where the next step ends: a guard that
    // starts a step crossed does not fire in it.)
    let cubic = |x: f64| vec![(0.9 - x) * (x - 0.95) * (x - 2.0)];
    for method in [Method::Dp54, Method::Dop853] {
        for h_max in [0.3, 1.0, 3.0, 10.0, 100.0] {
            let what = format!("{method:?} h_max {h_max}");
            let mut sys = Line {
                guards: cubic,
                kink: None,
            };
            let found = events(&mut sys, method, h_max, true);
            let first = found.at.first().copied();
            assert!(
                first.is_some_and(|(t, g)| (t - 0.9).abs() <= 1e-12 && g == 0),
                "{what}: {:?}",
                found.at
            );
        }
    }
}
