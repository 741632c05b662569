//! One whole bounce, solved exactly: the paper's Fig. 3(c) case (slide-grip-slide), a 3-phase case
//! (Fig. 3(b)) and a 5-phase case (a 1 g cart: slide-grip-slide-grip-slide). Target: median <= 2 µs.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use snapback::model::{Params, solve};

fn bench(c: &mut Criterion) {
    let cases = [
        ("fig3c", Params::default()),
        (
            "fig3b_3_phases",
            Params {
                stiffness: 4e4,
                ..Params::default()
            },
        ),
        (
            "cart_1g_5_phases",
            Params {
                cart_mass: 1e-3,
                ..Params::default()
            },
        ),
    ];
    let mut group = c.benchmark_group("solve");
    for (name, params) in cases {
        let phases = solve(&params).expect("bench case solves").phases.len();
        assert!(phases >= 3, "{name} has {phases} phases");
        group.bench_function(name, |b| b.iter(|| solve(black_box(&params)).unwrap()));
    }
    group.finish();
    let fig3c = Params::default();
    let bounce = solve(&fig3c).unwrap();
    c.bench_function("series_501", |b| b.iter(|| black_box(&bounce).series(501)));
}

criterion_group!(benches, bench);
criterion_main!(benches);
