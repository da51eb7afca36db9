//! `Options::stop_when_settled`: a run that stops once its touchdown return
//! map has converged measures the same gait as the full-length run.
use rtw_model::{Label, Options, Params, simulate};

/// The literal model (docs/model.md §9) with rest-length ratio `s`.
fn options(s: f64, stop: bool) -> Options {
    let mut o = Options {
        stop_when_settled: stop,
        ..Options::literal()
    };
    o.strings.rest_length_ratio = s;
    o
}

#[test]
fn a_settled_walk_stops_early_with_the_full_runs_statistics() {
    // Fig. 7(a) with prestressed strings walks with period 1 (docs/model.md §9).
    let full = simulate(&Params::fig7a(), &options(0.85, false));
    let early = simulate(&Params::fig7a(), &options(0.85, true));
    assert_eq!((full.label, full.period), (Label::Walk, 1));
    assert_eq!((early.label, early.period), (full.label, full.period));
    assert!(
        early.t_end < 0.75 * full.t_end,
        "stopped at {}",
        early.t_end
    );
    assert!(early.work.rhs_evals < full.work.rhs_evals);
    // Fractions of a periodic gait over whole periods equal those over the
    // last 10 s up to the part period at the window's ends (< 1 step / 10 s).
    let (a, b) = (early.fractions, full.fractions);
    for (x, y) in [(a.slsp, b.slsp), (a.dlsp, b.dlsp), (a.nlsp, b.nlsp)] {
        assert!((x - y).abs() < 0.01, "{a:?} vs {b:?}");
    }
    // The full run counts whole touchdowns in 10 s: f_w within 1 per 10 s.
    assert!(
        (early.f_w - full.f_w).abs() <= 0.1 + 1e-9,
        "{} vs {}",
        early.f_w,
        full.f_w
    );
    assert!((early.speed - full.speed).abs() < 0.01 * full.speed);
    assert!((early.mu_required - full.mu_required).abs() < 0.01 * full.mu_required);
}

#[test]
fn a_chaotic_gait_runs_to_the_end_unchanged() {
    // With zero-rest-length strings the Fig. 7(a) point skips chaotically:
    // its return map never converges, so the run is the full-length one.
    let full = simulate(&Params::fig7a(), &options(0.0, false));
    let early = simulate(&Params::fig7a(), &options(0.0, true));
    assert_eq!(full.label, Label::Skip);
    assert_eq!(full.period, 0);
    assert_eq!(early.t_end, full.t_end);
    assert_eq!(early.label, full.label);
    assert_eq!(early.fractions, full.fractions);
    assert_eq!(early.f_w, full.f_w);
}

#[test]
fn a_tip_chattering_in_place_is_not_a_settled_gait() {
    // Found in the Saltelli scan (results/sensitivity/saltelli, sample 43023):
    // a tip bounced in place with repeating returns, the run stopped as a
    // settled period-1 walk without a single new foot in its window, and
    // reported f_w = 43 517 Hz. A settled window must hold a step.
    let p = Params::new(
        0.8,
        4.810884497478921,
        0.047129818635375735,
        1.6387042173891897,
        0.052269083362228255,
        0.07463919233430306,
    )
    .unwrap();
    let o = simulate(&p, &Options::default());
    if o.period > 0 {
        assert!(o.f_w_newfoot > 0.0, "{o:?}");
    }
    // Touchdowns per second of a rolling star: a handful per step, never kHz.
    assert!(o.f_w < 100.0, "f_w = {} ({:?})", o.f_w, o.label);
}
