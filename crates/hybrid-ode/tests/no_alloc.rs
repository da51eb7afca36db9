//! `run` performs no heap allocation: a counting global allocator (counting
//! per thread) sees no allocation during runs of the rimless wheel with
//! every method, nor during a variational run.

use hybrid_ode::counting::{CountingAlloc, allocations};
use hybrid_ode::rimless::{RimlessWheel, Walk};
use hybrid_ode::{EndReason, EngineOptions, Method, Variational, run};

#[global_allocator]
static GLOBAL: CountingAlloc = CountingAlloc;

#[test]
fn run_does_not_allocate() {
    for method in [Method::Dp54, Method::Dop853, Method::Rk4] {
        let mut w = RimlessWheel::with_spokes(8, 1.0, 0.08, 9.81);
        let mut walk = Walk::stopping_after(50);
        let opts = EngineOptions {
            method,
            ..EngineOptions::default()
        };
        let mut y = w.initial_state(1.3 * w.omega_star());
        let before = allocations();
        let end = run(&mut w, &mut walk, 0.0, &mut y, 1e3, &opts);
        let after = allocations();
        assert_eq!(end.reason, EndReason::Stopped);
        assert_eq!(walk.impacts, 50);
        assert_eq!(
            after,
            before,
            "{method:?}: {} allocations in run",
            after - before
        );
    }
}

#[test]
fn a_variational_run_does_not_allocate() {
    let w = RimlessWheel::with_spokes(8, 1.0, 0.08, 9.81);
    let mut var = Variational::new(w, Walk::stopping_after(5), [1.0, 3.0]);
    let mut z: [f64; 6] =
        Variational::<RimlessWheel, Walk, 2>::initial(&w.initial_state(1.3 * w.omega_star()));
    let before = allocations();
    let end = var.run(0.0, &mut z, 1e3, &EngineOptions::default());
    let after = allocations();
    assert_eq!(end.reason, EndReason::Stopped);
    assert_eq!(var.observer.impacts, 5);
    assert_eq!(after, before, "{} allocations", after - before);
}
