//! One whole shot (issue 16): the bounce on the strings in the racquet's frame, the flight with drag and
//! Magnus lift to the net and the court, the bounce on the court and the second flight to the opponent's
//! baseline, for each shot preset. Target: median < 50 µs.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use snapback::model::Params;
use snapback::shot::play;

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("shot");
    for name in ["topspin-forehand", "flat-drive", "slice", "kick-serve"] {
        let params = snapback::config::preset(name)
            .expect("shot preset")
            .apply(Params::default());
        let shot = play(&params, false).expect("the preset plays");
        assert!(shot.kick_height.is_some(), "{name} bounces and kicks");
        group.bench_function(name, |b| {
            b.iter(|| play(black_box(&params), false).unwrap())
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
