//! A whole RTW run performs no heap allocation: hybrid-ode's counting global
//! allocator (per thread) sees none during `simulate`.

use hybrid_ode::counting::{CountingAlloc, allocations as allocs};

#[global_allocator]
static GLOBAL: CountingAlloc = CountingAlloc;

#[test]
fn simulate_does_not_allocate() {
    // A whole RTW run (initial state, engine, guards, resets, statistics)
    // lives in fixed-size arrays: zero heap allocations, whatever t_max.
    use rtw_model::options::{InitialShape, Method};
    use rtw_model::{Options, Params, simulate};
    // The adopted default (finite friction: sliding phases, slack strings,
    // static start) as well as the literal variant.
    let o = Options {
        t_max: 6.0,
        ..Options::default()
    };
    let before = allocs();
    let out = simulate(&Params::fig7a(), &o);
    let after = allocs();
    assert!(out.touchdowns > 5 && out.slide_time > 0.0, "{out:?}");
    assert_eq!(
        after,
        before,
        "default options: {} allocations",
        after - before
    );
    for (s, shape, method) in [
        (0.0, InitialShape::RigidStar, Method::Dop853),
        (0.85, InitialShape::Static, Method::Dp54),
        (0.85, InitialShape::RigidStar, Method::Rk4),
    ] {
        let mut o = Options {
            method,
            t_max: 6.0,
            ..Options::literal()
        };
        o.strings.rest_length_ratio = s;
        o.initial.shape = shape;
        let before = allocs();
        let out = simulate(&Params::fig7a(), &o);
        let after = allocs();
        assert!(out.touchdowns > 5, "{out:?}");
        assert_eq!(
            after,
            before,
            "s = {s}, {shape:?}, {method:?}: {} allocations",
            after - before
        );
    }
}
