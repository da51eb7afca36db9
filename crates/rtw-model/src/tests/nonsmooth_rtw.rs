//! The ends of the Fig. 7(a) walk's branch in φ, located and named, and the
//! branch continued through them.

use crate::GuardKind;
use crate::Tip;
use crate::cycles::LimitCycle;
use crate::cycles::branches::nonsmooth::{EndKind, EndOptions, Setting, guard_name, locate_end};
use crate::cycles::{CycleOptions, StepMap, continue_segments};
use crate::{Options, Param, Params};
use hybrid_ode::continuation::Options as Cont;

/// The model, the step map's settings and the settled walk at `phi`
/// (Fig. 7(a) otherwise), with s = 0.85.
fn walk(phi: f64) -> (Params, Options, CycleOptions, LimitCycle) {
    // The model these ends were located in: strings of natural length
    // s = 0.85 (the default until it moved to 0.8875, which moves them).
    let mut options = Options::default();
    options.strings.rest_length_ratio = 0.85;
    let base = Params {
        phi,
        ..Params::fig7a()
    };
    // Near its bifurcations the walk converges slowly: settle longer.
    let cycle = CycleOptions {
        settle_steps: 300,
        ..CycleOptions::default()
    };
    let map = StepMap::new(&base, &options, &cycle);
    let lc = map.limit_cycle(&options, &cycle).expect("a walk");
    (base, options, cycle, lc)
}

/// Going down in φ, the walk's branch ends (`rtw-scan continuation`: "no
/// continuation" at φ = 0.0931) where the landing foot stops sticking at
/// once: it bounces off the ground by a vanishing height and lands again,
/// the second touchdown's speed growing from zero — a grazing of the
/// landing tip's height. The orbit goes on past it, with the same
/// nontrivial multipliers and a Jacobian that jumps.
/// The walk's map in φ.
fn in_phi<'a>(base: &'a Params, options: &'a Options, cycle: &'a CycleOptions) -> Setting<'a> {
    Setting {
        base,
        options,
        cycle,
        param: Param::Phi,
    }
}

#[test]
fn the_walks_lower_end_is_the_landing_foot_grazing_into_a_bounce() {
    let (base, options, cycle, lc) = walk(0.10);
    assert_eq!(lc.period, 1);
    let s = in_phi(&base, &options, &cycle);
    let opts = EndOptions {
        probe: 1e-3,
        reach: 0.04,
        ..EndOptions::default()
    };
    let e = locate_end(&s, &lc.orbit[0], 1, 0.10, -1.0, (0.02, 0.35), &opts).expect("an end");
    assert!(
        (0.0931..0.0932).contains(&e.old.p) && (e.old.p - e.p_new).abs() <= opts.p_tol,
        "located at {} / {}",
        e.old.p,
        e.p_new
    );
    let EndKind::Grazing(a) = e.kind else {
        panic!("named {:?}", e.kind)
    };
    assert_eq!(
        a.kind,
        GuardKind::Touchdown {
            rod: 1,
            tip: Tip::Plus
        },
        "{}",
        guard_name(a.kind)
    );
    assert!(a.value.abs() < 1e-4, "landing speed {}", a.value);
    let new = e.new.as_ref().expect("an orbit past the change");
    assert_eq!(
        new.sequence.events.len(),
        e.old.sequence.events.len() + 1,
        "{} → {}",
        e.old.sequence.describe(),
        new.sequence.describe()
    );
    // The nontrivial multipliers go on (to 1e-5): the bounce's flight is
    // a vanishing part of the step.
    let (mo, mn) = (&e.old.cycle.multipliers, &new.cycle.multipliers);
    for m in mo.iter().filter(|m| m.norm() > 1e-6) {
        let nearest = mn
            .iter()
            .map(|x| (x - m).norm())
            .fold(f64::INFINITY, f64::min);
        assert!(nearest < 1e-5, "{m} has no partner in {mn:?}");
    }
    let jump = e.jacobian_jump.expect("same section coordinates");
    assert!(jump > 0.1, "the Jacobian jumps by {jump}");
}

/// Continued down in φ from 0.095, the walk's branch crosses the grazing
/// at φ ≈ 0.09313 into a second segment: the same walk with the landing
/// foot's bounce in its mode sequence, which goes on to the range's end.
/// The segment's corrector never lands back in the first sequence.
#[test]
fn the_walks_branch_is_continued_through_the_landing_foots_grazing() {
    let (base, options, cycle, lc) = walk(0.095);
    let s = in_phi(&base, &options, &cycle);
    let cont = Cont {
        ds: 0.02,
        ds_max: 0.05,
        ds_min: 1e-6,
        p_min: 0.0925,
        p_max: 0.3,
        tol: 1e-8,
        locate_tol: 1e-6,
        p_scale: 0.1,
        ..Cont::default()
    };
    let segs = continue_segments(
        &s,
        &lc.orbit[0],
        1,
        0.095,
        -1.0,
        &cont,
        &EndOptions::default(),
        3,
    );
    assert_eq!(segs.len(), 2, "{segs:#?}");
    let end = segs[0]
        .end
        .as_ref()
        .expect("the first segment's end is named");
    assert!(matches!(end.kind, EndKind::Grazing(_)), "{:?}", end.kind);
    assert!((0.0931..0.0932).contains(&end.old.p), "{}", end.old.p);
    assert_eq!(
        segs[1].sequence.events.len(),
        segs[0].sequence.events.len() + 1,
        "the bounce: {} → {}",
        segs[0].sequence.describe(),
        segs[1].sequence.describe()
    );
    assert_eq!(segs[1].label, segs[0].label);
    let b = &segs[1].branch;
    assert_eq!(b.end, hybrid_ode::continuation::End::ParameterRange);
    assert!(b.points.iter().all(|p| p.p <= end.p_new + 1e-9));
    assert!(segs[1].end.is_none());
}

/// At the default strings (s = 0.8875), the walk continued down in φ from
/// 0.15 changes its mode sequence at φ ≈ 0.143893: rod c's sliding tip slows
/// until its speed just reaches the re-stick threshold, so a re-stick
/// (immediately followed by a slip) appears — a grazing of rod c's re-stick
/// guard. The continuation's last point lies within 1e-6 of the change, so
/// the change's own bracket gives no reference a probe step back; the end
/// must still be named by the guard's closest approach, measured against an
/// orbit a probe step back into the branch.
#[test]
fn a_branch_that_stops_next_to_its_change_still_names_the_grazing() {
    let options = Options::default();
    let p_last = 0.1438935;
    let base = Params {
        phi: p_last,
        ..Params::fig7a()
    };
    let cycle = CycleOptions {
        settle_steps: 300,
        ..CycleOptions::default()
    };
    let lc = StepMap::new(&base, &options, &cycle)
        .limit_cycle(&options, &cycle)
        .expect("a walk");
    assert_eq!(lc.period, 1);
    let s = in_phi(&base, &options, &cycle);
    let opts = EndOptions::default();
    let e = locate_end(&s, &lc.orbit[0], 1, p_last, -1.0, (0.05, 0.3), &opts).expect("an end");
    assert!(
        (0.143893..p_last).contains(&e.p_new) && (e.old.p - e.p_new).abs() <= opts.p_tol,
        "located at {} / {}",
        e.old.p,
        e.p_new
    );
    let EndKind::Grazing(a) = e.kind else {
        panic!("named {:?}", e.kind)
    };
    assert_eq!(
        a.kind,
        GuardKind::Restick { rod: 2 },
        "{}",
        guard_name(a.kind)
    );
    assert!(a.value.abs() < 1e-5, "closest approach {}", a.value);
    let new = e.new.as_ref().expect("an orbit past the change");
    assert!(
        new.sequence.events.len() == e.old.sequence.events.len() + 2,
        "a re-stick and its slip appear: {} → {}",
        e.old.sequence.describe(),
        new.sequence.describe()
    );
}
