//! `hybrid::run` performs no heap allocation: a counting global allocator
//! (counting per thread) sees no allocation during runs of the rimless wheel
//! with every method.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

use rtw_model::hybrid::{EndReason, EngineOptions, run};
use rtw_model::integrate::Method;
use rtw_model::rimless::RimlessWheel;

struct Counting;

thread_local! {
    static ALLOCS: Cell<u64> = const { Cell::new(0) };
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCS.with(|c| c.set(c.get() + 1));
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCS.with(|c| c.set(c.get() + 1));
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn allocs() -> u64 {
    ALLOCS.with(|c| c.get())
}

#[test]
fn run_does_not_allocate() {
    for method in [Method::Dp54, Method::Dop853, Method::Rk4 { h: 1e-3 }] {
        let mut w = RimlessWheel::with_spokes(8, 1.0, 0.08, 9.81);
        w.stop_after = 50;
        let opts = EngineOptions {
            method,
            ..EngineOptions::default()
        };
        let mut y = w.initial_state(1.3 * w.omega_star());
        let before = allocs();
        let end = run(&mut w, 0.0, &mut y, 1e3, &opts);
        let after = allocs();
        assert_eq!(end.reason, EndReason::Stopped);
        assert_eq!(w.impacts, 50);
        assert_eq!(
            after,
            before,
            "{method:?}: {} allocations in run",
            after - before
        );
    }
}

#[test]
fn simulate_does_not_allocate() {
    // A whole RTW run (initial state, engine, guards, resets, statistics)
    // lives in fixed-size arrays: zero heap allocations, whatever t_max.
    use rtw_model::options::{InitialShape, MethodChoice};
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
        (0.0, InitialShape::RigidStar, MethodChoice::Dop853),
        (0.85, InitialShape::Static, MethodChoice::Dp54),
        (0.85, InitialShape::RigidStar, MethodChoice::Rk4),
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
