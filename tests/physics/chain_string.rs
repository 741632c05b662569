//! String friction on a chain's first mass (`--chain N --cart-friction F_c`): against an independent
//! numerical integration of the 2N + 2 equations of motion with Coulomb friction on the first mass, the
//! chain of one against the single cart's own model, a first mass held throughout against a still
//! surface, and properties over random chains.

use crate::support::chain_integrator;
use crate::support::phases::regimes;
use crate::support::prop::within_the_cone;

use proptest::prelude::*;
use snapback::model::solve::solve_chain;
use snapback::model::{Cart, Params, PhaseKind, solve};

use crate::support::rng;
use rng::Rng;

use crate::support::chain as chain_draw;
use chain_draw::{close, random_chain};

use crate::support::prop;
use prop::{check_cart_motion, config, log_range};

/// mu N0, the largest sliding friction of a bounce.
fn peak_friction(p: &Params) -> f64 {
    p.mu * (1.0 + p.ey) * std::f64::consts::PI * p.mass * p.speed * p.angle_deg.to_radians().sin()
        / (2.0 * p.duration)
}

/// A random bounce on `chain` masses with string friction F_c from a thousandth to three times mu N0.
fn random_params(rng: &mut Rng, chain: f64) -> Params {
    let mut p = random_chain(rng, chain);
    p.cart_friction = rng.log_uniform(1e-3, 3.0) * peak_friction(&p);
    p
}

#[test]
#[ignore = "slow"]
fn string_friction_on_a_chain_agrees_with_numerical_integration() {
    let mut rng = Rng(0x5791_c4a1_f00d_0012);
    let cases = 100;
    let (mut held, mut freed, mut stopped, mut rolled_free) = (0, 0, 0, 0);
    let mut worst: f64 = 0.0;
    for case in 0..cases {
        let n = 2 + rng.below(15);
        let mut p = random_params(&mut rng, n as f64);
        // Keep the fastest mode within reach of a fixed-step integration.
        p.cart_mass = p.cart_mass.max(2e-4 * n as f64 / 8.0);
        let exact = solve(&p).expect("chains with string friction solve");
        let reference = chain_integrator::integrate(&p, chain_integrator::step_for(&p));
        let what = format!("case {case} N {n}: {p:?} ({})", describe(&exact));
        let speed = p.speed + p.radius * p.spin.abs();
        let dv = (exact.outcome.vx2 - reference.vx2).abs() / exact.outcome.vx2.abs().max(p.speed);
        let dw = (exact.outcome.omega2 - reference.omega2).abs()
            / exact.outcome.omega2.abs().max(speed / p.radius);
        assert!(
            dv <= 1e-7,
            "{what}: vx2 exact {} numerical {}",
            exact.outcome.vx2,
            reference.vx2
        );
        assert!(
            dw <= 1e-7,
            "{what}: omega2 exact {} numerical {}",
            exact.outcome.omega2,
            reference.omega2
        );
        worst = worst.max(dv).max(dw);
        assert_eq!(exact.phases.len(), reference.phases, "{what}");
        assert_eq!(exact.cart_ever_stuck(), reference.stuck, "{what}");
        let e = exact.energy();
        assert!(
            (e.final_cart - reference.chain_energy).abs() <= 1e-7 * e.initial,
            "{what}: chain energy {} {}",
            e.final_cart,
            reference.chain_energy
        );
        assert!(
            close(exact.final_state.v, reference.v2, p.speed, 1e-7),
            "{what}: V_1 {} {}",
            exact.final_state.v,
            reference.v2
        );
        assert!(
            close(
                exact.final_state.x,
                reference.x1,
                p.speed * p.duration,
                1e-7
            ),
            "{what}: X_1 {} {}",
            exact.final_state.x,
            reference.x1
        );
        let phases = &exact.phases;
        held += usize::from(phases.iter().any(|ph| ph.cart == Cart::Stuck));
        let (was_freed, was_stopped) = regimes(phases);
        freed += usize::from(was_freed);
        stopped += usize::from(was_stopped);
        // Pushed free under a rolling ball by the masses behind it (only a chain does that).
        rolled_free += usize::from(phases.windows(2).any(|w| {
            (w[0].kind, w[0].cart) == (PhaseKind::Grip, Cart::Stuck) && w[1].cart != Cart::Stuck
        }));
    }
    println!(
        "worst relative disagreement {worst:.2e} over {cases} chains; the first mass held in {held}, \
         pushed free in {freed} ({rolled_free} under a rolling ball), stopped and held again in {stopped}"
    );
    assert!(
        freed >= 20 && stopped >= 5 && rolled_free >= 1,
        "freed {freed} ({rolled_free} rolling), stopped {stopped}"
    );
}

/// The phases with what the first mass did, e.g. `slide/stuck slide/moving grip/moving`.
fn describe(b: &snapback::model::Bounce) -> String {
    b.phases
        .iter()
        .map(|p| format!("{}/{}", p.kind.name(), p.cart.name()))
        .collect::<Vec<_>>()
        .join(" ")
}

#[test]
fn one_mass_with_string_friction_through_the_chain_is_the_single_cart() {
    let mut rng = Rng(0x0c4a_1ace_5eed_0012);
    let cases = 300;
    for case in 0..cases {
        let p = random_params(&mut rng, 1.0);
        let cart = solve(&p).expect("valid parameters solve");
        let chain = solve_chain(&p).expect("the chain path solves N = 1");
        let speed = p.speed + p.radius * p.spin.abs();
        let what = format!("case {case}: {p:?} ({})", describe(&cart));
        assert_eq!(describe(&cart), describe(&chain), "{what}");
        for (a, b) in cart.phases.iter().zip(&chain.phases) {
            assert!(close(a.end, b.end, p.duration, 1e-10), "{what}: phase end");
        }
        let (a, b) = (&cart.outcome, &chain.outcome);
        assert!(
            close(a.omega2, b.omega2, speed / p.radius, 1e-10),
            "{what}: omega2 {} {}",
            a.omega2,
            b.omega2
        );
        assert!(close(a.vx2, b.vx2, speed, 1e-10), "{what}: vx2");
        let (sa, sb) = (&cart.final_state, &chain.final_state);
        assert!(close(sa.v, sb.v, speed, 1e-10), "{what}: V");
        assert!(close(sa.x, sb.x, speed * p.duration, 1e-10), "{what}: X");
        let (ea, eb) = (cart.energy(), chain.energy());
        for (x, y) in [
            (ea.final_cart, eb.final_cart),
            (ea.friction_loss, eb.friction_loss),
            (ea.cart_friction_loss, eb.cart_friction_loss),
        ] {
            assert!(
                close(x, y, ea.initial, 1e-10),
                "{what}: energy {ea:?} {eb:?}"
            );
        }
    }
}

#[test]
fn a_first_mass_held_throughout_is_a_still_surface() {
    // String friction beyond any push: the first mass never moves, the chain behind it stays at rest,
    // and the ball bounces as off the single cart held the same way.
    for n in [2.0, 5.0, 16.0] {
        for (angle, spin) in [(20.0, 0.0), (60.0, -100.0), (80.0, 50.0)] {
            let p = Params {
                chain: n,
                cart_friction: 1e6,
                angle_deg: angle,
                spin,
                ..Params::default()
            };
            let (chain, cart) = (
                solve(&p).unwrap(),
                solve(&Params { chain: 1.0, ..p }).unwrap(),
            );
            assert!(chain.phases.iter().all(|ph| ph.cart == Cart::Stuck));
            assert_eq!(chain.phase_summary(), cart.phase_summary());
            let (a, b) = (&chain.outcome, &cart.outcome);
            assert!(
                close(a.omega2, b.omega2, p.speed / p.radius, 1e-13),
                "{a:?} {b:?}"
            );
            assert!(close(a.vx2, b.vx2, p.speed, 1e-13), "{a:?} {b:?}");
            let e = chain.energy();
            assert_eq!((e.final_cart, e.cart_friction_loss), (0.0, 0.0));
        }
    }
}

/// Random chains with string friction over the property tests' ranges (the cart from 0.1 g, so that
/// even 16 masses stay resolvable), F_c from none to about twice mu N0.
fn chains() -> impl Strategy<Value = Params> {
    let ball = (0.005f64..0.5, 0.005f64..0.12, 0.2f64..1.0);
    let throw = (
        prop_oneof![0.5f64..=90.0, Just(90.0)],
        0.5f64..50.0,
        -500.0f64..500.0,
    );
    let contact = (0.0f64..1.2, 0.5e-3f64..20e-3, 0.0f64..=1.0);
    let chain = (
        log_range(1e-4, 1e6),
        prop_oneof![Just(0.0), log_range(1.0, 1e5)],
        2usize..=16,
        log_range(1e-4, 2.0),
    );
    (ball, throw, contact, chain).prop_map(|(ball, throw, contact, chain)| {
        let ((mass, radius, alpha), (angle_deg, speed, spin)) = (ball, throw);
        let ((mu, duration, ey), (cart_mass, stiffness, n, string)) = (contact, chain);
        let mut p = Params {
            angle_deg,
            speed,
            spin,
            mu,
            duration,
            ey,
            mass,
            radius,
            alpha,
            cart_mass,
            stiffness,
            cart_friction: 0.0,
            chain: n as f64,
            ball_stiffness: 0.0,
            ball_damping: 0.0,
            ..Params::default()
        };
        p.cart_friction = string * peak_friction(&p);
        p
    })
}

proptest! {
    #![proptest_config(config(300))]

    #[test]
    fn every_chain_bounce_with_string_friction_is_physical(p in chains()) {
        let b = solve(&p).expect("valid chains solve");
        let o = &b.outcome;
        for value in [o.omega2, o.vx2, o.vy2, o.speed2(), o.theta2_deg, b.final_state.x, b.final_state.v] {
            prop_assert!(value.is_finite());
        }
        let e = b.energy();
        for value in [e.initial, e.final_ball, e.final_cart, e.friction_loss, e.normal_loss, e.cart_friction_loss] {
            prop_assert!(value.is_finite() && value >= -1e-12 * e.initial);
        }
        prop_assert!(e.residual.abs() < 1e-9, "residual {}", e.residual);
        prop_assert_eq!(b.phases[0].start, 0.0);
        prop_assert_eq!(b.phases.last().unwrap().end, p.duration);
        for pair in b.phases.windows(2) {
            prop_assert_eq!(pair[0].end, pair[1].start);
        }
        let speed_scale = p.speed + p.radius * p.spin.abs();
        for s in &b.series(300) {
            within_the_cone(&p, s, b.setup.n0)?;
            if s.kind == PhaseKind::Grip {
                prop_assert!(s.slip.abs() <= 1e-9 * speed_scale, "slip {} in grip at {}", s.slip, s.t);
            }
        }
        check_cart_motion(&p, &b)?;
    }
}
