//! `snapback fit` of 3 free parameters (cart mass, stiffness, mu) to 40 rows: omega2 at 20 angles from
//! 10 to 86 deg and spins 0 and -100 rad/s, made from a 5 g cart on 12 kN/m with mu = 0.35 plus a
//! seeded noise of 3 rad/s, fitted from the defaults (10 g, 15 kN/m, 0.4), with the global search alone
//! and with the profile intervals too (target: median < 2 s); and the grouped fit of the shipped string
//! table, one string-on-string friction per material (target: < 20 s).

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use rand::SeedableRng;
use rand::rngs::StdRng;
use rand_distr::{Distribution, Normal};
use snapback::analysis::fit::data::{self, Dataset, Measurement, Quantity, Row};
use snapback::analysis::fit::{self, Options, free};
use snapback::model::{ParamId, Params, solve};

fn data() -> Dataset {
    let truth = Params {
        cart_mass: 0.005,
        stiffness: 12_000.0,
        mu: 0.35,
        ..Params::default()
    };
    let mut rng = StdRng::seed_from_u64(40);
    let noise = Normal::new(0.0, 3.0).unwrap();
    let mut rows = Vec::new();
    for spin in [0.0, -100.0] {
        for i in 0..20 {
            let mut row = Row {
                line: rows.len() + 2,
                group: None,
                conditions: vec![
                    (ParamId::Angle, 10.0 + 4.0 * f64::from(i)),
                    (ParamId::Spin, spin),
                ],
                measured: Vec::new(),
            };
            let omega2 = solve(&row.params(&truth)).unwrap().outcome.omega2;
            row.measured.push(Measurement {
                quantity: Quantity::Omega2,
                value: omega2 + noise.sample(&mut rng),
                sigma: Some(3.0),
            });
            rows.push(row);
        }
    }
    Dataset {
        origin: "bench".into(),
        rows,
        conditions: vec![ParamId::Angle, ParamId::Spin],
        absolute_sigma: true,
        groups: Vec::new(),
    }
}

fn bench(c: &mut Criterion) {
    let data = data();
    let free = free::parse_list("cart-mass,stiffness,mu", &data.conditions).unwrap();
    let base = Params::default();
    let options = Options::default();
    assert!(fit::fit(&base, &free, &data, &options).unwrap().converged);
    let mut group = c.benchmark_group("fit");
    group.sample_size(10);
    group.bench_function("three_free_40_rows", |b| {
        b.iter(|| fit::fit(black_box(&base), &free, &data, &options).unwrap())
    });
    let search_only = Options {
        profile: false,
        ..options
    };
    group.bench_function("three_free_40_rows_search_only", |b| {
        b.iter(|| fit::fit(black_box(&base), &free, &data, &search_only).unwrap())
    });
    let layout = data::Layout {
        group: Some("material".into()),
        ignore: [
            "company",
            "string",
            "gauge",
            "tension_lb",
            "angle_article_deg",
        ]
        .map(String::from)
        .to_vec(),
    };
    let table = include_str!("../assets/data/twu-string-movement-and-spin.csv");
    let strings = data::parse_with(table, "twu", &layout).unwrap();
    let grouped = free::parse_lists("", "cart-friction", &strings.conditions, 3).unwrap();
    let polyester = snapback::config::preset("polyester-strings")
        .unwrap()
        .apply(Params::default());
    group.bench_function("strings_grouped_by_material", |b| {
        b.iter(|| fit::fit(black_box(&polyester), &grouped, &strings, &options).unwrap())
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
