//! Criterion benches of the model's hot path (filled in with the dynamics).
use criterion::{Criterion, criterion_group, criterion_main};

fn params(c: &mut Criterion) {
    let p = rtw_model::Params::fig7a();
    c.bench_function("physical_from_params", |b| {
        b.iter(|| rtw_model::Physical::new(&p, rtw_model::Normalization::Supplementary, 9.81))
    });
}

criterion_group!(benches, params);
criterion_main!(benches);
