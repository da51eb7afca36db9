//! Criterion benches of the model's hot path: one right-hand side, one guard
//! evaluation, one integrator step (with its dense output) per method, and
//! whole 20 s runs at the Fig. 7(a) point per tolerance and method.
//! `cargo bench -p rtw-model`.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use hybrid_ode::kernels::step_with_dense;
use hybrid_ode::{Dense, Guards, HybridSystem, Method};
use rtw_model::plant::initial::initial_state;
use rtw_model::plant::rtw::Rtw;
use rtw_model::plant::slots::N;
use rtw_model::{Options, Params, Physical, simulate};
use std::hint::black_box;

fn hot_path(c: &mut Criterion) {
    let o = Options::default();
    let phys = Physical::new(&Params::fig7a(), o.normalization, o.g);
    let mut rtw = Rtw::new(&phys, &o);
    let (y, _) = initial_state(&mut rtw, &o, &mut Default::default()).expect("standing start");
    let mut dy = [0.0; N];
    c.bench_function("rhs", |b| {
        b.iter(|| rtw.dynamics(black_box(&y), &mut dy));
    });
    let mut g = Guards::default();
    c.bench_function("guards", |b| {
        b.iter(|| rtw.guards(0.0, black_box(&y), &mut g));
    });
    // One step of each method from the standing start, with the method's
    // full dense output (what a step with an event costs).
    let mut dense = Dense::<N>::default();
    for (method, name) in [
        (Method::Rk4, "step/rk4"),
        (Method::Dp54, "step/dp54"),
        (Method::Dop853, "step/dop853"),
    ] {
        c.bench_function(name, |b| {
            b.iter(|| {
                step_with_dense(
                    method,
                    |_, y, dy| {
                        rtw.dynamics(y, dy);
                    },
                    0.0,
                    black_box(&y),
                    1e-3,
                    &mut dense,
                )
            });
        });
    }
}

fn runs(c: &mut Criterion) {
    let mut group = c.benchmark_group("run_20s_fig7a");
    group.sample_size(20);
    for (method, name) in [(Method::Dp54, "dp54"), (Method::Dop853, "dop853")] {
        for rtol in [1e-6, 1e-8, 1e-10] {
            for s in [0.0, 0.85] {
                let mut o = Options {
                    method,
                    rtol,
                    atol: rtol * 1e-2,
                    ..Options::default()
                };
                o.strings.rest_length_ratio = s;
                let id = BenchmarkId::new(format!("{name}/s={s}"), format!("rtol={rtol:e}"));
                group.bench_with_input(id, &o, |b, o| {
                    b.iter(|| simulate(black_box(&Params::fig7a()), o));
                });
            }
        }
    }
    group.finish();
}

criterion_group!(benches, hot_path, runs);
criterion_main!(benches);
