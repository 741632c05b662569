//! Checks the bounds the single cart gives its event search against the branches they bound: over random
//! valid bounces, every phase's branches are sampled densely from the phase's start to the event the
//! search found (or the end of contact), and at each sample |f''| must stay within the curvature bound and
//! |f''''| within the fourth-derivative bound. A bound that is too small lets the search miss a
//! transition silently, so each is tested where the solver uses it.
//!
//! The sampling is `model::bound_samples`'s (f'' the branch's own, from the closed form; f'''' the
//! central difference of the f''' it carries); halving a bound that is reached fails the test
//! (`fails_when_halved`). At first contact the slide carries the rate from inside the contact (F' = mu N0
//! w at t = 0, tested below), as the Taylor polynomials from an interval's ends need.

use proptest::prelude::*;

use crate::model::params::Params;
use crate::model::setup::Setup;

use crate::model::bound_samples::{
    cases, checked, log_uniform, rigid_ball, run, run_entering, violations, with_string_friction,
};

/// Random valid single-cart bounces, as the property tests draw them (tests/physics/properties.rs):
/// light and heavy carts, no spring, string friction in half the cases, tiny and large mu, spin either
/// way; no chain, no compliant ball.
fn params() -> impl Strategy<Value = Params> {
    let string = prop_oneof![Just(0.0), 0.0f64..2.0];
    let cart = (
        log_uniform(1e-5, 1e6),
        prop_oneof![Just(0.0), log_uniform(1.0, 1e6)],
        string,
    );
    (rigid_ball(), cart).prop_map(|(ball, (cart_mass, stiffness, string))| {
        let p = Params {
            cart_mass,
            stiffness,
            chain: 1.0,
            ..ball
        };
        with_string_friction(p, string)
    })
}

#[test]
fn the_search_bounds_hold_over_random_bounces() {
    run_entering(
        params(),
        cases(400),
        &[
            "slide, string friction",
            "slide by its sums",
            "slide on a still cart",
            "grip, string friction",
            "grip by its sums",
        ],
    );
}

#[test]
#[ignore = "slow tier: cargo test --release --lib -- --ignored"]
fn the_search_bounds_hold_over_many_random_bounces() {
    run(params(), cases(20000));
}

#[test]
fn the_friction_rate_at_first_contact_is_the_one_inside_contact() {
    use super::super::contact::Cart;
    use super::slide::Slide;
    let setup = Setup::new(&Params::default());
    let slide = Slide::new(
        &setup,
        setup.initial(Params::default().spin),
        1.0,
        Cart::Moving(1),
    );
    let (_, (friction, rate)) = slide.sample(&setup, 0.0);
    assert_eq!(friction, 0.0);
    assert_eq!(rate, setup.peak_friction() * setup.w);
}

#[test]
fn fails_when_halved() {
    // The default bounce's slide at the paper's figure: halved bounds are crossed.
    let p = Params::default();
    assert!(violations(&p, 1.0).is_empty());
    assert!(!violations(&p, 0.5).is_empty());
}

/// A last slide of 83 ns, on a cart string friction holds still, found by the slow tier: with the
/// difference step of the longer phases (h = 104 ns) the samples near T differenced across the end of
/// contact (f''' is 0 beyond it), a violation of the sampling's own making.
#[test]
fn a_phase_shorter_than_the_difference_step_is_sampled_inside_itself() {
    let p = Params {
        angle_deg: 0.5,
        speed: 0.5,
        spin: 0.0,
        mu: 1.0439194801091243,
        duration: 0.010388565645786187,
        ey: 0.0,
        mass: 0.005,
        radius: 0.005,
        alpha: 0.2,
        cart_mass: 0.931112582197682,
        stiffness: 290.3526456688556,
        cart_friction: 0.0024935718319515038,
        ..Params::default()
    };
    checked();
    let found = violations(&p, 1.0);
    assert!(found.is_empty(), "{}", found.join("; "));
    assert_eq!(checked().get("slide on a still cart"), Some(&2));
}
