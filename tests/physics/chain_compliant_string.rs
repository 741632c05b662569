//! The compliant ball on a chain of masses with string friction on the first mass (`--chain N
//! --ball-stiffness k_b --cart-friction F_c`): against the independent numerical reference
//! (support/chain_compliant_integrator.rs, RK4 with the first mass's Coulomb friction), which is itself
//! checked for one mass against the single cart's reference and solver; a stiff critically damped ball
//! approaching the rigid ball on the chain with the same F_c; and properties over random inputs.

use crate::support::chain_compliant_integrator;
use crate::support::compliant::incoming;
use crate::support::compliant_integrator;
use crate::support::phases::regimes;

use chain_compliant_integrator::{Reference, integrate, step_for};
use proptest::prelude::*;
use snapback::model::{Bounce, Cart, Params, PhaseKind, solve};

use crate::support::rng;
use rng::Rng;

use crate::support::compliant as compliant_params;
use compliant_params::{
    check_basics, compliant_strategy, peak_friction, random_compliant, solved_or_refused,
};

use crate::support::prop;
use prop::{check_cart_motion, config, log_range};

/// The reference's step: a 250th of a radian of the fastest oscillation (see `step_for`).
const PER_RADIAN: f64 = 0.004;

/// A random compliant ball on a chain of 2 to 16 masses with springs, the string friction from a
/// thousandth to three times mu N0.
fn random_params(rng: &mut Rng) -> Params {
    let n = 2 + rng.below(15);
    let mut p = Params {
        cart_mass: rng.log_uniform(1e-3, 1.0),
        stiffness: rng.log_uniform(1e3, 1e5),
        ball_stiffness: rng.log_uniform(1e4, 1e7),
        ..random_compliant(rng, n)
    };
    p.cart_friction = rng.log_uniform(1e-3, 3.0) * peak_friction(&p);
    p
}

/// The phases with what the first mass did, e.g. `slide/stuck grip/moving`.
fn describe(b: &Bounce) -> String {
    b.phases
        .iter()
        .map(|p| format!("{}/{}", p.kind.name(), p.cart.name()))
        .collect::<Vec<_>>()
        .join(" ")
}

/// omega2, vx2, V1 and X1 of a bounce against the reference, relative to the incoming speed (and the
/// distance covered at it).
fn differences(p: &Params, b: &Bounce, r: &Reference) -> [f64; 4] {
    let speed = incoming(p);
    [
        p.radius * (b.outcome.omega2 - r.omega2).abs() / speed,
        (b.outcome.vx2 - r.vx2).abs() / speed,
        (b.final_state.v - r.v[0]).abs() / speed,
        (b.final_state.x - r.x[0]).abs() / (speed * p.duration),
    ]
}

#[test]
fn an_independent_integration_agrees() {
    let mut rng = Rng(0x5eed_c4a1_5791_0002);
    let cases = 60;
    let mut worst = [0.0f64; 4];
    let mut worst_residual: f64 = 0.0;
    let (mut held, mut freed, mut stopped, mut held_grip) = (0, 0, 0, 0);
    for case in 0..cases {
        let p = random_params(&mut rng);
        let b = solve(&p).unwrap_or_else(|e| panic!("case {case}: {e}: {p:?}"));
        let r = integrate(&p, step_for(&p, PER_RADIAN));
        let d = differences(&p, &b, &r);
        for (w, d) in worst.iter_mut().zip(d) {
            *w = w.max(d);
        }
        assert!(
            d.iter().all(|&d| d < 1e-9),
            "case {case} (N = {}): {p:?} ({})\nsolver {:?} {:?}\nreference {r:?}\n{d:?}",
            p.chain,
            describe(&b),
            b.outcome,
            b.final_state
        );
        let e = b.energy();
        assert!(e.residual.abs() < 1e-10, "case {case}: {e:?}");
        worst_residual = worst_residual.max(e.residual.abs());
        assert_eq!(b.cart_ever_stuck(), r.held, "case {case}: {p:?}");
        let phases = &b.phases;
        held += usize::from(phases.iter().all(|ph| ph.cart == Cart::Stuck));
        let (was_freed, was_stopped) = regimes(phases);
        freed += usize::from(was_freed);
        stopped += usize::from(was_stopped);
        held_grip += usize::from(
            phases
                .iter()
                .any(|ph| (ph.kind, ph.cart) == (PhaseKind::Grip, Cart::Stuck)),
        );
    }
    println!(
        "worst relative disagreement over {cases} chains: omega2 {:.2e}, vx2 {:.2e}, V1 {:.2e}, \
         X1 {:.2e}; energy residual {worst_residual:.1e}; held throughout {held}, pushed free \
         {freed}, stopped and held again {stopped}, gripping a held first mass {held_grip}",
        worst[0], worst[1], worst[2], worst[3]
    );
    assert!(held >= 3 && freed >= 10 && stopped >= 3 && held_grip >= 3);
}

/// The reference on one mass is the single cart: its string friction rules agree with the single cart's
/// reference and solver (which the chain's length 1 is solved by).
#[test]
fn one_mass_is_the_single_cart_with_string_friction() {
    let mut rng = Rng(0x0e1e_c4a1_0000_0005);
    for case in 0..12 {
        let mut p = random_compliant(&mut rng, 1);
        p.stiffness = rng.log_uniform(1e3, 1e5);
        p.cart_friction = rng.log_uniform(1e-2, 2.0) * peak_friction(&p);
        let b = solve(&p).unwrap();
        let chain = integrate(&p, step_for(&p, PER_RADIAN));
        let cart = compliant_integrator::integrate(&p, 40_000);
        let speed = incoming(&p);
        let d = differences(&p, &b, &chain);
        assert!(d.iter().all(|&d| d < 1e-8), "case {case}: {p:?}: {d:?}");
        assert!(
            (chain.vx2 - cart.vx2).abs() < 1e-8 * speed
                && (chain.v[0] - cart.v).abs() < 1e-8 * speed,
            "case {case}: {p:?}"
        );
        assert_eq!(chain.held, cart.stuck);
        assert!(chain.energy.residual().abs() < 1e-9, "{:?}", chain.energy);
    }
}

#[test]
fn a_stiff_critically_damped_ball_approaches_the_rigid_ball_with_the_same_string_friction() {
    for (n, cart_mass, angle_deg, cart_friction) in [
        (2, 0.01, 60.0, 5.0),
        (16, 0.05, 45.0, 20.0),
        (8, 0.02, 60.0, 2.0),
    ] {
        let base = Params {
            chain: n as f64,
            cart_mass,
            angle_deg,
            cart_friction,
            ..Params::default()
        };
        let rigid = solve(&base).unwrap();
        assert!(rigid.phases.iter().any(|p| p.cart != Cart::Stuck));
        let speed = incoming(&base);
        let mut errors = vec![];
        for kb in [1e6, 1e7, 1e8, 1e9] {
            let b = solve(&Params {
                ball_stiffness: kb,
                ball_damping: 1.0,
                ..base
            })
            .unwrap();
            let (o, r) = (&b.outcome, &rigid.outcome);
            let (s, q) = (&b.final_state, &rigid.final_state);
            errors.push(
                ((o.vx2 - r.vx2).abs() + base.radius * (o.omega2 - r.omega2).abs()) / speed
                    + (s.v - q.v).abs() / speed
                    + (s.x - q.x).abs() / (speed * base.duration),
            );
        }
        let shown: Vec<String> = errors.iter().map(|e| format!("{e:.1e}")).collect();
        println!("N = {n}: error against the rigid ball at k_b = 1e6..1e9: {shown:?}");
        for pair in errors.windows(2) {
            assert!(pair[1] < pair[0], "N = {n}: {errors:?}");
        }
        assert!(errors[3] < 1e-3, "N = {n}: {errors:?}");
    }
}

fn params() -> impl Strategy<Value = Params> {
    let chain = (log_range(1e-4, 1e4), log_range(1.0, 1e5), 2usize..=16);
    (compliant_strategy(chain), log_range(1e-4, 3.0)).prop_map(|(mut p, string)| {
        p.cart_friction = string * peak_friction(&p);
        p
    })
}

proptest! {
    #![proptest_config(config(200))]

    #[test]
    fn every_compliant_chain_bounce_with_string_friction_is_physical(p in params()) {
        let Some(b) = solved_or_refused(&p)? else {
            return Ok(());
        };
        check_basics(&p, &b)?;
        check_cart_motion(&p, &b)?;
    }
}
