//! Every option's documented range is one the physics survives: at both ends
//! of each range in `Options::validate`, the Fig. 7(a) point still gives a
//! physical outcome: a user who stays inside the documented ranges never gets
//! a nonsense run. A threshold or tolerance that only
//! decides how a run is integrated or judged must leave Fig. 7(a)'s walk a
//! walk; an option that changes the physics (gravity, the push, the strings'
//! natural length, friction) may change the gait but must not make the run
//! `diverged`; a work budget at its lowest may end the run `diverged`, but only
//! saying it ran out. Just outside each range, `validate` refuses.

use rtw_model::Method;
use rtw_model::outcome::FailureDetail;
use rtw_model::{Label, Options, Params, simulate};

/// What the Fig. 7(a) point must give at an end of the range.
#[derive(Clone, Copy, Debug)]
enum Expect {
    /// Fig. 7(a)'s walk, unchanged in kind.
    Walk,
    /// Any outcome but `diverged`.
    Physical,
    /// Not `diverged`, or `diverged` because it ran out of work budget.
    Budget,
}

type Set = fn(&mut Options, f64);

/// (key, lower end, upper end, just outside below, just outside above, setter, expectation).
fn ranges() -> Vec<(&'static str, f64, f64, f64, f64, Set, Expect)> {
    let max = f64::MAX;
    let tiny = f64::MIN_POSITIVE * f64::EPSILON; // the smallest positive double
    vec![
        (
            "t_max",
            tiny,
            max,
            0.0,
            f64::INFINITY,
            |o, v| o.t_max = v,
            Expect::Physical,
        ),
        (
            "rtol",
            tiny,
            0.1,
            0.0,
            0.1000001,
            |o, v| o.rtol = v,
            Expect::Walk,
        ),
        (
            "atol",
            tiny,
            0.1,
            0.0,
            0.1000001,
            |o, v| o.atol = v,
            Expect::Walk,
        ),
        (
            "rk4_step",
            tiny,
            0.1,
            0.0,
            0.1000001,
            |o, v| {
                o.method = Method::Rk4;
                o.rk4_step = v
            },
            Expect::Budget,
        ),
        (
            "h_max",
            tiny,
            f64::INFINITY,
            0.0,
            f64::NAN,
            |o, v| o.h_max = v,
            Expect::Budget,
        ),
        (
            "max_steps",
            1.0,
            u64::MAX as f64,
            0.0,
            f64::NAN,
            |o, v| o.max_steps = v as u64,
            Expect::Budget,
        ),
        (
            "g",
            0.1,
            1000.0,
            0.0999,
            1000.1,
            |o, v| o.g = v,
            Expect::Physical,
        ),
        (
            "analysis_window",
            0.1,
            1.0,
            0.0999,
            1.0001,
            |o, v| o.analysis_window = v,
            Expect::Walk,
        ),
        (
            "labels.flight",
            0.0,
            1.0 - f64::EPSILON,
            -1e-9,
            1.0,
            |o, v| o.labels.flight = v,
            Expect::Walk,
        ),
        (
            "labels.triple",
            0.0,
            1.0 - f64::EPSILON,
            -1e-9,
            1.0,
            |o, v| o.labels.triple = v,
            Expect::Walk,
        ),
        (
            "labels.flight_steps",
            0.0,
            1.0,
            -1e-9,
            1.0 + 1e-9,
            |o, v| o.labels.flight_steps = v,
            Expect::Walk,
        ),
        (
            "labels.triple_steps",
            0.0,
            1.0,
            -1e-9,
            1.0 + 1e-9,
            |o, v| o.labels.triple_steps = v,
            Expect::Walk,
        ),
        (
            "collapse_height_ratio",
            0.0,
            0.75,
            -1e-9,
            0.7501,
            |o, v| o.collapse_height_ratio = v,
            Expect::Walk,
        ),
        (
            "stall_time",
            1.0,
            max,
            0.999,
            f64::INFINITY,
            |o, v| o.stall_time = v,
            Expect::Walk,
        ),
        (
            "touchdown_offset",
            tiny,
            1e-6,
            0.0,
            1.0001e-6,
            |o, v| o.touchdown_offset = v,
            Expect::Walk,
        ),
        (
            "trace_dt",
            0.0,
            max,
            -1e-9,
            f64::INFINITY,
            |o, v| o.trace_dt = v,
            Expect::Walk,
        ),
        (
            "initial.omega",
            -50.0,
            50.0,
            -50.001,
            50.001,
            |o, v| o.initial.omega = v,
            Expect::Physical,
        ),
        (
            "strings.rest_length_ratio",
            0.0,
            1.0 - f64::EPSILON,
            -1e-9,
            1.0,
            |o, v| o.strings.rest_length_ratio = v,
            Expect::Physical,
        ),
        (
            "contact.mu",
            0.0,
            4.0 / 3.0,
            -1e-9,
            1.3334,
            |o, v| o.contact.mu = v,
            Expect::Physical,
        ),
    ]
}

#[test]
fn both_ends_of_every_option_range_give_a_physical_outcome_at_fig7a() {
    let p = Params::fig7a();
    let mut bad = Vec::new();
    for (key, lo, hi, below, above, set, expect) in ranges() {
        for (end, v) in [("lower", lo), ("upper", hi)] {
            let mut o = Options::default();
            set(&mut o, v);
            if let Err(e) = o.validate() {
                bad.push(format!("{key} = {v:e} ({end} end) is refused: {e}"));
                continue;
            }
            let out = simulate(&p, &o);
            let ok = match expect {
                Expect::Walk => out.label == Label::Walk,
                Expect::Physical => out.label != Label::Diverged,
                Expect::Budget => {
                    out.label != Label::Diverged
                        || matches!(
                            out.failure,
                            Some(FailureDetail::WorkBudget | FailureDetail::StepUnderflow)
                        )
                }
            };
            if !ok {
                bad.push(format!(
                    "{key} = {v:e} ({end} end): {} ({:?}) at t = {}, expected {expect:?}",
                    out.label, out.failure, out.t_end
                ));
            }
        }
        for v in [below, above] {
            let mut o = Options::default();
            set(&mut o, v);
            if v.is_nan() {
                continue; // max_steps has no value above u64::MAX
            }
            match o.validate() {
                Err(e) => assert_eq!(e.field, key, "{key} = {v:e}"),
                Ok(()) => bad.push(format!("{key} = {v:e} (just outside) is accepted")),
            }
        }
    }
    // ... and with infinite friction (no slip), the other end of contact.mu.
    let mut o = Options::default();
    o.contact.mu = f64::INFINITY;
    assert_ne!(simulate(&p, &o).label, Label::Diverged);
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

#[test]
fn touchdown_offset_zero_is_refused() {
    // At 0 a tip released on the ground starts its touchdown guard at exactly
    // 0, which event location does not count as a crossing: the next
    // touchdown of that tip is missed and the walk becomes a collapse.
    let o = Options {
        touchdown_offset: 0.0,
        ..Options::default()
    };
    let e = o.validate().unwrap_err();
    assert_eq!(e.field, "touchdown_offset");
    assert_eq!(e.range, "in (0, 1e-6]");
}

#[test]
fn both_ends_of_every_input_range_give_a_physical_outcome_at_fig7a() {
    use rtw_model::Param;
    use std::f64::consts::FRAC_PI_2;
    // (input, lower end, upper end, just outside below, just outside above);
    // φ's range is open, so its ends are the doubles just inside ±π/2.
    let inside = FRAC_PI_2.next_down();
    let ends = [
        (Param::Length, 1e-3, 1e3, 0.999e-3, 1.001e3),
        (Param::Rho, 1e-3, 1e3, 0.999e-3, 1.001e3),
        (Param::Alpha, 0.0, 0.49, -1e-12, 0.4901),
        (Param::Fn, 1e-2, 1e2, 0.999e-2, 1.001e2),
        (Param::Zeta, 0.0, 10.0, -1e-12, 10.001),
        (Param::Phi, -inside, inside, -FRAC_PI_2, FRAC_PI_2),
    ];
    let o = Options::default();
    let mut bad = Vec::new();
    for (param, lo, hi, below, above) in ends {
        for (end, v) in [("lower", lo), ("upper", hi)] {
            let mut p = Params::fig7a();
            p[param] = v;
            if let Err(e) = p.validate() {
                bad.push(format!(
                    "{} = {v:e} ({end} end) is refused: {e}",
                    param.name()
                ));
                continue;
            }
            let out = simulate(&p, &o);
            if out.label == Label::Diverged {
                bad.push(format!(
                    "{} = {v:e} ({end} end): diverged ({:?})",
                    param.name(),
                    out.failure
                ));
            }
        }
        for v in [below, above] {
            let mut p = Params::fig7a();
            p[param] = v;
            match p.validate() {
                Err(e) => assert_eq!(e.field, param.name(), "{} = {v:e}", param.name()),
                Ok(()) => bad.push(format!(
                    "{} = {v:e} (just outside) is accepted",
                    param.name()
                )),
            }
        }
    }
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}
