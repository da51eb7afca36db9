//! Basin-of-attraction slices ([`Basin`]): the fixed
//! point is in its basin, a far point fails, a point that starts with a tip
//! in the ground is not simulated, the grid is deterministic and row-major,
//! bad settings are refused by name; and the classification rule
//! ([`follow`]) against the rimless wheel's closed-form basin.

use crate::cycles::robustness::basin::follow;
use crate::cycles::{Axis, Basin, BasinError, BasinSpec, Coord, CycleOptions, Fate, StepError};
use crate::outcome::FailureDetail;
use crate::{Label, Options, Params};
use hybrid_ode::rimless::RimlessWheel;
use hybrid_ode::{EngineOptions, Method};

/// Every point of the slice, row-major.
fn grid(b: &Basin) -> Vec<crate::cycles::BasinPoint> {
    (0..b.len()).map(|i| b.point(i)).collect()
}

fn axis(coord: Coord, from: f64, to: f64, points: usize) -> Axis {
    Axis {
        coord,
        from,
        to,
        points,
    }
}

fn spec(x: Axis, y: Axis, steps: usize) -> BasinSpec {
    BasinSpec {
        x,
        y,
        steps,
        tol: 1e-3,
    }
}

/// Fig. 7(a)'s walk, sliced over `spec`.
fn fig7a(spec: BasinSpec) -> Basin {
    Basin::new(
        &Params::fig7a(),
        &Options::default(),
        &CycleOptions::default(),
        spec,
    )
    .unwrap()
}

#[test]
fn the_fixed_point_returns_at_once_and_a_far_point_fails() {
    // ω_a offsets 0 and +40 rad/s (the walk's ω_a is −2.49 rad/s).
    let b = fig7a(spec(
        axis(Coord::Omega(0), 0.0, 40.0, 2),
        axis(Coord::Theta(1), 0.0, 0.0, 1),
        60,
    ));
    assert_eq!(b.label, Label::Walk);
    assert_eq!(b.cycle.period, 1);
    let g = grid(&b);
    assert_eq!(g[0].fate, Fate::Returns);
    assert_eq!(g[0].steps, 1);
    assert!(g[0].distance < 1e-8, "{}", g[0].distance);
    assert_eq!((g[0].label, g[0].period), (Some(Label::Walk), Some(1)));
    // A rod spun 40 rad/s the wrong way lays the star down in its first step.
    assert_eq!(
        g[1].fate,
        Fate::Fails(StepError::Failure(FailureDetail::RodDown))
    );
    assert_eq!((g[1].steps, g[1].label), (0, None));
}

#[test]
fn a_point_that_takes_every_step_gets_the_label_of_its_last_steps() {
    // +10 rad/s returns after about 38 steps; in 5 it has not.
    let b = fig7a(spec(
        axis(Coord::Omega(0), 10.0, 10.0, 1),
        axis(Coord::Theta(1), 0.0, 0.0, 1),
        5,
    ));
    let p = b.point(0);
    assert_eq!(p.fate, Fate::Survives);
    assert_eq!((p.steps, p.label), (5, Some(Label::Walk)));
    assert!(
        p.distance > 1e-3 && p.distance.is_finite(),
        "{}",
        p.distance
    );
}

#[test]
fn a_start_with_a_tip_in_the_ground_is_not_simulated() {
    // Rod b turned by −1.5 rad puts one of its tips below the slope.
    let b = fig7a(spec(
        axis(Coord::Theta(1), -1.5, -1.5, 1),
        axis(Coord::Omega(0), 0.0, 0.0, 1),
        60,
    ));
    let p = b.point(0);
    assert_eq!((p.fate, p.steps, p.label), (Fate::Infeasible, 0, None));
}

#[test]
fn the_grid_is_row_major_and_the_same_in_any_order() {
    // Cheap points: infeasible, failing and the fixed point itself.
    let b = fig7a(spec(
        axis(Coord::Omega(0), 0.0, 40.0, 2),
        axis(Coord::Theta(1), -1.5, 0.0, 2),
        60,
    ));
    assert_eq!(b.len(), 4);
    let g = grid(&b);
    let offsets: Vec<(f64, f64)> = g.iter().map(|p| (p.dx, p.dy)).collect();
    assert_eq!(
        offsets,
        [(0.0, -1.5), (40.0, -1.5), (0.0, 0.0), (40.0, 0.0)]
    );
    let backwards: Vec<_> = (0..4).rev().map(|i| b.point(i)).collect();
    for (a, z) in g.iter().zip(backwards.iter().rev()) {
        assert_eq!(a, z);
    }
    assert_eq!(g, grid(&b));
    // A range through 0 has the fixed point itself exactly (as a scan's
    // linspace axis, the ends exact too).
    let o = axis(Coord::Theta(1), -1.2, 0.8, 41).offsets();
    assert_eq!((o[0], o[24], o[40]), (-1.2, 0.0, 0.8));
    let (x0, y0) = b.centre();
    assert_eq!(x0, b.cycle.orbit[0].omega());
    assert!(y0.is_finite());
}

#[test]
fn bad_settings_are_refused_by_name_with_their_range() {
    let good = spec(
        axis(Coord::Omega(0), -1.0, 1.0, 3),
        axis(Coord::Theta(1), -0.5, 0.5, 3),
        10,
    );
    assert_eq!(good.validate(), Ok(()));
    let cases: [(BasinSpec, &str); 6] = [
        (
            BasinSpec {
                x: axis(Coord::Omega(0), 1.0, -1.0, 3),
                ..good
            },
            "x: from 1 to -1 is invalid: must be finite offsets with from <= to",
        ),
        (
            BasinSpec {
                y: axis(Coord::Theta(1), -0.5, 0.5, 0),
                ..good
            },
            "y: points 0 is invalid: must be an integer in [1, 1000]",
        ),
        (
            BasinSpec {
                y: axis(Coord::Theta(1), -0.5, f64::NAN, 3),
                ..good
            },
            "y: from -0.5 to NaN is invalid",
        ),
        (
            BasinSpec {
                y: axis(Coord::Omega(0), -0.5, 0.5, 3),
                ..good
            },
            "y: coordinate omega_a is invalid: must be a coordinate other than x's",
        ),
        (
            BasinSpec { steps: 0, ..good },
            "steps: 0 is invalid: must be an integer in [1, 100000]",
        ),
        (
            BasinSpec { tol: 0.5, ..good },
            "tol: 0.5 is invalid: must be in (0, 0.1]",
        ),
    ];
    for (s, want) in cases {
        let e = s.validate().unwrap_err();
        assert!(e.to_string().starts_with(want), "{e} (want {want})");
        // Basin::new checks before it simulates anything.
        let e2 = Basin::new(
            &Params::fig7a(),
            &Options::default(),
            &CycleOptions::default(),
            s,
        )
        .unwrap_err();
        assert!(matches!(e2, BasinError::Invalid { .. }), "{e2}");
    }
}

#[test]
fn coordinates_are_named_and_parsed_alike() {
    for c in Coord::ALL {
        assert_eq!(c.to_string().parse::<Coord>(), Ok(c));
    }
    let e = "omega".parse::<Coord>().unwrap_err();
    assert!(
        e.contains("omega_a, omega_b, omega_c, theta_a, theta_b, theta_c"),
        "{e}"
    );
}

/// McGeer's rimless wheel (α = π/8, γ = 0.08 < α, l = 1): its post-impact
/// rate `ω` rolls on from one stance to the next iff `ω² > 2 (g/l)(1 −
/// cos(α − γ))` (the hub passes the apex), and since the step map `P` is
/// increasing with its fixed point `ω*` above that threshold and `P(ω) > ω`
/// below `ω*`, every rate above the threshold converges to `ω*`: the basin
/// on the section is exactly `ω > ω_apex`. The engine's step map, followed
/// by the basin's rule, must draw that boundary.
#[test]
fn follow_draws_the_rimless_wheels_closed_form_basin() {
    let w = RimlessWheel::with_spokes(8, 1.0, 0.08, 9.81);
    let opts = EngineOptions {
        method: Method::Dop853,
        rtol: 1e-10,
        atol: 1e-12,
        h_max: 0.05,
        ..EngineOptions::default()
    };
    let apex = w.apex_rate_sq().sqrt();
    let star = w.omega_star();
    assert!(apex > 0.9 && star > apex + 0.1, "apex {apex}, ω* {star}");
    let mut rates: Vec<f64> = (0..=30).map(|k| 0.5 + 0.05 * k as f64).collect();
    rates.extend([apex - 1e-6, apex + 1e-6, apex - 1e-3, apex + 1e-3]);
    for omega in rates {
        let f = follow(
            omega,
            100,
            1e-6,
            |&o| w.step_map(o, &opts).ok_or(()),
            |&o| (o - star).abs() / star,
        );
        if omega > apex {
            assert_eq!(f.fate, Fate::Returns, "ω = {omega} (apex {apex})");
            assert!((f.last - star).abs() <= 1e-6 * star);
        } else {
            assert_eq!(f.fate, Fate::Fails(()), "ω = {omega} (apex {apex})");
            assert_eq!(f.steps, 0);
        }
    }
}

/// An error and its causes as `anyhow`'s `{:#}` prints them (and so the CLI
/// and Python's exceptions): each `source` after its error's own message.
fn chain(e: &dyn std::error::Error) -> String {
    let mut s = e.to_string();
    let mut at = e.source();
    while let Some(cause) = at {
        s.push_str(": ");
        s.push_str(&cause.to_string());
        at = cause.source();
    }
    s
}

/// A wrapped error says its cause once: an error whose message already
/// holds its cause does not also hand it on as its `source` (the chain
/// printed "the gait's limit cycle: a step failed: the run failed:
/// standing_rolls_away: a step failed: the run failed: standing_rolls_away:
/// the run failed: standing_rolls_away").
#[test]
fn a_wrapped_error_names_each_cause_once() {
    use crate::cycles::{CycleError, DiagramError};
    let step = StepError::Failure(FailureDetail::StandingRollsAway);
    let basin = BasinError::from(CycleError::from(step));
    assert_eq!(
        chain(&basin),
        "the gait's limit cycle: a step failed: the run failed: standing_rolls_away"
    );
    let newton = CycleError::from(hybrid_ode::limit::NewtonError::Singular);
    assert_eq!(
        chain(&DiagramError::from(newton)),
        "no limit cycle at the start: Newton: P − I is singular at an iterate (a multiplier at 1)"
    );
    let start = DiagramError::from(hybrid_ode::continuation::Error::NoStart);
    assert_eq!(
        chain(&start),
        "the continuation could not start: no fixed point near the starting point (Newton at \
         fixed p failed)"
    );
}
