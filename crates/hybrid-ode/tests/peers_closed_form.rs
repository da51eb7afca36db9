//! The peer benchmark's rtw side (`examples/peers`) against the closed forms
//! it is scored on, at the accuracy the benchmark's page reports: the
//! bouncing ball's impact times, the rimless wheel's touchdown times and
//! post-impact rates, and the impact oscillator's first impact near grazing.

#[path = "../examples/peers/closed_form.rs"]
mod closed_form;

use closed_form::{
    Ball, IMPACTS, Impacts, Oscillator, ball_reference, gauss_legendre, wheel, wheel_reference,
};
use hybrid_ode::{EngineOptions, Method, run};

fn opts(method: Method, tol: f64) -> EngineOptions {
    EngineOptions {
        method,
        rtol: tol,
        atol: tol,
        h_max: 0.0,
        ..EngineOptions::default()
    }
}

#[test]
fn the_references_are_the_closed_forms() {
    // Dropped from 1 m: t_1 = sqrt(2/9.81) s, v_1 = sqrt(2·9.81) m/s, and
    // after 10 impacts the ball leaves at 0.8^10 v_1.
    let mut t = [0.0; IMPACTS];
    let y = ball_reference(1.0, &mut t);
    assert!((t[0] - 0.451_523_640_985_730_9).abs() < 1e-15);
    let v1 = (2.0f64 * 9.81).sqrt();
    assert!((t[1] - t[0] - 2.0 * 0.8 * v1 / 9.81).abs() < 1e-15);
    assert!((y[1] - 0.8f64.powi(10) * v1).abs() < 1e-15);
    // The wheel (12 spokes, l = 1, γ = 0.08) from ω0 = 1.2 rad/s: its first
    // stance lasts 0.449 147 724 382 225 s (SciPy's adaptive quad and
    // NumPy's 64-node Gauss–Legendre agree to 1e-16), and ten steps of
    // McGeer's map take the rate to 1.542 346 047 877 235 rad/s.
    let w = wheel();
    let y = wheel_reference(&w, 1.2, &mut t);
    assert!((t[0] - 0.449_147_724_382_224_8).abs() < 1e-15, "{}", t[0]);
    assert!((y[1] - 1.542_346_047_877_234_8).abs() < 1e-14, "{}", y[1]);
    assert_eq!(y[0], w.gamma - w.alpha);
    // The quadrature integrates polynomials of degree 79 exactly.
    let (x, wt) = gauss_legendre::<40>();
    let moment: f64 = x.iter().zip(&wt).map(|(x, w)| w * x.powi(78)).sum();
    assert!((moment - 2.0 / 79.0).abs() < 1e-15);
}

#[test]
fn ball_impacts_match_the_closed_form_at_every_tolerance() {
    // The flow is a parabola, which both methods integrate exactly: what
    // is left is event location (to 1e-13 s) and its propagation over ten
    // bounces.
    for method in [Method::Dop853, Method::Dp54] {
        for tol in [1e-6, 1e-9, 1e-12] {
            for h0 in [1.0, 1.37, 1.995] {
                let mut obs = Impacts::default();
                let mut y = [h0, 0.0];
                run(&mut Ball, &mut obs, 0.0, &mut y, 100.0, &opts(method, tol));
                assert_eq!(obs.count, IMPACTS, "{method:?} {tol} {h0}");
                let mut want = [0.0; IMPACTS];
                let y_ref = ball_reference(h0, &mut want);
                for (got, want) in obs.times.iter().zip(&want) {
                    assert!((got - want).abs() < 1e-10, "{method:?} {tol} {h0}");
                }
                assert!((y[1] - y_ref[1]).abs() < 1e-10);
                assert!(y[0] >= 0.0 && y[0] < 1e-12);
            }
        }
    }
}

#[test]
fn wheel_steps_match_the_closed_form_to_a_hundred_tolerances() {
    // Tolerances are per step; over ten stances the touchdown times and the
    // final rate drift by a few tens of tol at most (results/bench/peers.md).
    let w = wheel();
    for method in [Method::Dop853, Method::Dp54] {
        for tol in [1e-6, 1e-9, 1e-12] {
            for omega0 in [1.2, 1.56, 1.996] {
                let mut obs = Impacts::default();
                let mut y = w.initial_state(omega0);
                run(&mut { w }, &mut obs, 0.0, &mut y, 100.0, &opts(method, tol));
                assert_eq!(obs.count, IMPACTS);
                let mut want = [0.0; IMPACTS];
                let y_ref = wheel_reference(&w, omega0, &mut want);
                for (got, want) in obs.times.iter().zip(&want) {
                    assert!((got - want).abs() < 100.0 * tol, "{method:?} {tol}");
                }
                assert!((y[1] - y_ref[1]).abs() < 100.0 * tol, "{method:?} {tol}");
                assert!((y[0] - y_ref[0]).abs() < 1e-12);
            }
        }
    }
}

#[test]
fn oscillator_first_impact_is_found_and_matches_the_closed_form() {
    // Just past grazing the orbit is beyond the stop for a sliver of a
    // step (0.035 s of a 7.85 s period at ε = 1e-4): found only by the
    // engine's dip search. The impact time's error is the state error over
    // the small impact speed, hence the loose bound.
    let (t, y) = Oscillator::past_grazing(0.0).reference();
    // At grazing: Ωt − θ = 2π, the orbit's maximum, and the speed is 0.
    let theta = (2.0f64 * 0.05 * 0.8).atan2(1.0 - 0.64);
    assert!((t - (theta + 2.0 * std::f64::consts::PI) / 0.8).abs() < 1e-12);
    assert_eq!(y, [1.0, 0.0]);
    for method in [Method::Dop853, Method::Dp54] {
        for tol in [1e-6, 1e-9, 1e-12] {
            for eps in [1e-4, 1e-2, 0.1] {
                let osc = Oscillator::past_grazing(eps);
                let (t0, mut y) = osc.start();
                let mut obs = Impacts::stopping_after(1);
                run(
                    &mut { osc },
                    &mut obs,
                    t0,
                    &mut y,
                    100.0,
                    &opts(method, tol),
                );
                assert_eq!(obs.count, 1, "{method:?} {tol} {eps}");
                let (t_ref, y_ref) = osc.reference();
                let err = (obs.times[0] - t_ref).abs();
                assert!(err < 1e4 * tol, "{method:?} {tol} {eps}: {err}");
                assert!(
                    (y[1] - y_ref[1]).abs() < 1e4 * tol,
                    "{method:?} {tol} {eps}"
                );
            }
        }
    }
}
