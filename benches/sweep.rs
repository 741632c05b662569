//! The sweep's speed: 100 000 bounces solved on all cores and written as CSV (the target is
//! under 0.5 s end to end on two cores), and one bounce alone. `cargo bench --bench sweep`.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use snapback::analysis::{Span, sweep};
use snapback::model::{Params, solve};

const STEPS: usize = 100_000;

fn bench(c: &mut Criterion) {
    let base = Params::default();
    let angles = Span::parse("angle", "0.01", "90", false).expect("a valid span");
    let stiffness = Span::parse("stiffness", "1kN/m", "100kN/m", true).expect("a valid span");
    // One bounce of Fig. 3(c), for the comparison with benches/scipy_reference.py (same case).
    c.bench_function("one bounce, Fig. 3(c)", |b| {
        b.iter(|| solve(black_box(&base)).expect("solvable"))
    });
    let mut group = c.benchmark_group("sweep");
    group.sample_size(10);
    group.bench_function("angle 100k, solve", |b| {
        b.iter(|| sweep::sweep(black_box(&base), &angles, STEPS).expect("solvable"))
    });
    group.bench_function("angle 100k, solve and write csv", |b| {
        b.iter(|| {
            let mut out = Vec::with_capacity(16 << 20);
            sweep::write_csv(&mut out, black_box(&base), &angles, STEPS).expect("in memory");
            out
        })
    });
    group.bench_function("stiffness 100k log, solve and write csv", |b| {
        b.iter(|| {
            let mut out = Vec::with_capacity(16 << 20);
            sweep::write_csv(&mut out, black_box(&base), &stiffness, STEPS).expect("in memory");
            out
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
