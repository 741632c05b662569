//! One whole bounce, solved exactly: the paper's Fig. 3(c) case (slide-grip-slide), a 3-phase case
//! (Fig. 3(b)) and a 5-phase case (a 1 g cart: slide-grip-slide-grip-slide). Target: median <= 2 µs.
//! And the Fig. 3(c) case on a chain of 8 masses (`chain_8`, 5 phases), and with a compliant ball
//! (`compliant_ball`, k_b = 1 MN/m, zeta 0.5, slide-grip-slide), and both together
//! (`chain_8_compliant_ball`, 5 phases).

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
    // A chain of 8 masses sharing the 10 g cart (slide-grip-slide-grip-slide), solved in its modes.
    let chain8 = Params {
        chain: 8.0,
        ..Params::default()
    };
    let phases = solve(&chain8).expect("chain case solves").phases.len();
    assert!(phases >= 3, "chain_8 has {phases} phases");
    group.bench_function("chain_8", |b| b.iter(|| solve(black_box(&chain8)).unwrap()));
    // The Fig. 3(c) case with a compliant ball.
    let ball = Params {
        ball_stiffness: 1e6,
        ball_damping: 0.5,
        ..Params::default()
    };
    let phases = solve(&ball).expect("compliant case solves").phases.len();
    assert!(phases >= 3, "compliant_ball has {phases} phases");
    group.bench_function("compliant_ball", |b| {
        b.iter(|| solve(black_box(&ball)).unwrap())
    });
    // Both: a chain of 8 masses touched by the compliant ball, one damped modal system in each grip
    // (issue 6's benchmark case, target 50 µs).
    let chain8_ball = Params { chain: 8.0, ..ball };
    let phases = solve(&chain8_ball)
        .expect("chain + ball case solves")
        .phases
        .len();
    assert!(phases >= 3, "chain_8_compliant_ball has {phases} phases");
    group.bench_function("chain_8_compliant_ball", |b| {
        b.iter(|| solve(black_box(&chain8_ball)).unwrap())
    });
    group.finish();
    let fig3c = Params::default();
    let bounce = solve(&fig3c).unwrap();
    c.bench_function("series_501", |b| b.iter(|| black_box(&bounce).series(501)));
}

criterion_group!(benches, bench);
criterion_main!(benches);
