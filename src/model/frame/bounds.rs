//! Checks the bounds the free frame's searches by sums (`searched_by_sums`) give against the branches
//! they bound, as `cart/bounds.rs` does the single cart's: over random valid bounces on a frame, every
//! such phase's branches are sampled densely from its start to the event its search found (or the end
//! of contact), and |f''| must stay within the curvature bound and |f''''| within the fourth-derivative
//! bound (`model::bound_samples`). A bound that is too small lets the search miss a transition.

use proptest::prelude::*;

use crate::model::bound_samples::{cases, log_uniform, rigid_ball, run, run_entering, violations};
use crate::model::params::Params;

/// Random valid bounces on a free frame of 1 g to 10 kg, the cart on a spring (the searches by sums
/// need one) and without string friction (with it the frame's searches do not use the sums).
fn params() -> impl Strategy<Value = Params> {
    let frame = (
        log_uniform(1e-5, 1e2),
        log_uniform(1.0, 1e6),
        log_uniform(1e-3, 10.0),
    );
    (rigid_ball(), frame).prop_map(|(ball, (cart_mass, stiffness, frame_mass))| Params {
        cart_mass,
        stiffness,
        frame_mass,
        chain: 1.0,
        ..ball
    })
}

#[test]
fn the_search_bounds_hold_over_random_bounces() {
    run_entering(
        params(),
        cases(400),
        &["frame slide by its sums", "frame grip by its sums"],
    );
}

#[test]
#[ignore = "slow tier: cargo test --release --lib -- --ignored"]
fn the_search_bounds_hold_over_many_random_bounces() {
    run(params(), cases(20000));
}

#[test]
fn fails_when_halved() {
    // Fig. 3(c) on a 188 g frame: halved bounds are crossed.
    let p = Params {
        frame_mass: 0.188,
        ..Params::default()
    };
    assert!(violations(&p, 1.0).is_empty());
    assert!(!violations(&p, 0.5).is_empty());
}
