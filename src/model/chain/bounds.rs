//! Checks the bounds the chain's search by Taylor bounds (`search.rs`) gives it against the branches
//! they bound: over random valid chain bounces, on the wall and on a free frame, every phase searched so
//! is sampled densely from its start to the event the search found (or the end of contact), and at each
//! sample |f''| must stay within the curvature bound and |f''''| within the fourth-derivative bound. A
//! bound that is too small lets the search miss a transition silently, so each is tested where the
//! solver uses it (as `cart/bounds.rs` tests the single cart's).
//!
//! The sampling is `model::bound_samples`'s (f'' the branch's own, from the phase's sums; f'''' the
//! central difference of the f''' it carries). Halving a bound that is reached fails the test
//! (`fails_when_halved`).

use proptest::prelude::*;

use crate::model::params::Params;

use crate::model::bound_samples::{
    cases, log_uniform, rigid_ball, run, run_entering, violations, with_string_friction,
};

/// Random valid chain bounces: 2 to 12 masses, light and heavy, stiff and soft, on the wall or on a
/// free frame from a tenth of the chain's mass to a thousand times it, string friction in a third of
/// the cases, tiny and large mu, spin either way; a rigid ball.
fn params() -> impl Strategy<Value = Params> {
    let string = prop_oneof![Just(0.0), Just(0.0), 0.0f64..2.0];
    let frame = prop_oneof![Just(0.0), log_uniform(0.1, 1000.0)];
    let chain = (
        2u32..=12,
        log_uniform(1e-4, 10.0),
        log_uniform(10.0, 1e6),
        frame,
        string,
    );
    (rigid_ball(), chain).prop_map(|(ball, chain)| {
        let (links, cart_mass, stiffness, frame, string) = chain;
        let p = Params {
            cart_mass,
            stiffness,
            chain: f64::from(links),
            frame_mass: frame * cart_mass,
            ..ball
        };
        with_string_friction(p, string)
    })
}

#[test]
fn the_search_bounds_hold_over_random_chains() {
    run_entering(
        params(),
        cases(200),
        &[
            "slide on the wall",
            "slide on a frame",
            "grip on the wall",
            "grip on a frame",
        ],
    );
}

#[test]
#[ignore = "slow tier: cargo test --release --lib -- --ignored"]
fn the_search_bounds_hold_over_many_random_chains() {
    run(params(), cases(5000));
}

#[test]
fn fails_when_halved() {
    // A chain of 4 on the wall and on a 188 g frame: halved bounds are crossed. The fourth
    // derivative's bounds are reached within a factor 2 by the slide on the wall and the grip on
    // both (on the frame the slide's bound on |q_j'| leaves it more room than that).
    let mut halved = Vec::new();
    for frame_mass in [0.0, 0.188] {
        let p = Params {
            chain: 4.0,
            frame_mass,
            ..Params::default()
        };
        assert!(violations(&p, 1.0).is_empty(), "{frame_mass}");
        halved.extend(violations(&p, 0.5));
    }
    for regime in ["slide on the wall", "grip on the wall", "grip on a frame"] {
        assert!(
            halved
                .iter()
                .any(|v| v.starts_with(regime) && v.contains("|f''''|")),
            "{regime}: {halved:?}"
        );
    }
}
