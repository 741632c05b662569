//! The compliant ball with string friction on the single cart (`--ball-stiffness k_b --cart-friction
//! F_c`): against an independent numerical integration (support/compliant_integrator.rs, RK4 with the
//! cart's Coulomb friction), a stiff critically damped ball approaching the rigid ball with the same
//! F_c, a vanishing F_c approaching the model without it, the energy budget with every loss, and
//! properties over random inputs.

use crate::support::compliant_integrator;
use crate::support::phases::regimes;

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

/// A random compliant ball on the single cart with string friction from a thousandth to three times
/// mu N0.
fn random_params(rng: &mut Rng) -> Params {
    let mut p = random_compliant(rng, 1);
    p.cart_friction = rng.log_uniform(1e-3, 3.0) * peak_friction(&p);
    p
}

/// The phases with what the cart did, e.g. `slide/stuck slide/moving grip/moving`.
fn describe(b: &Bounce) -> String {
    b.phases
        .iter()
        .map(|p| format!("{}/{}", p.kind.name(), p.cart.name()))
        .collect::<Vec<_>>()
        .join(" ")
}

#[test]
fn an_independent_integration_agrees() {
    let mut rng = Rng(0x5eed_c0de_5791_0001);
    // The last 20 on heavy carts on soft springs, whose equilibrium under the string friction lies far
    // from the motion.
    let cases = 120;
    let mut worst = [0.0f64; 5];
    let mut worst_residual: f64 = 0.0;
    let (mut held, mut freed, mut stopped, mut held_grip, mut same_phases) = (0, 0, 0, 0, 0);
    for case in 0..cases {
        let mut p = random_params(&mut rng);
        if case >= 100 {
            p.cart_mass = rng.log_uniform(10.0, 1e4);
            p.stiffness = rng.log_uniform(1.0, 100.0);
            p.cart_friction = rng.log_uniform(1e-4, 0.1) * peak_friction(&p);
        }
        let b = solve(&p).unwrap_or_else(|e| panic!("case {case}: {e}: {p:?}"));
        let reference = compliant_integrator::integrate(&p, 40_000);
        let o = &b.outcome;
        let s = &b.final_state;
        let speed = p.speed + p.radius * p.spin.abs();
        let e = b.energy();
        let spring = 0.5 * p.ball_stiffness * reference.e * reference.e;
        // Relative to the largest speed, the distance covered at it, and the incoming energy.
        let differences = [
            (o.omega2 - reference.omega2).abs() * p.radius / speed,
            (o.vx2 - reference.vx2).abs() / speed,
            (s.v - reference.v).abs() / speed,
            (s.x - reference.x).abs() / (speed * p.duration),
            (e.ball_spring - spring).abs() / e.initial,
        ];
        for (w, d) in worst.iter_mut().zip(differences) {
            *w = w.max(d);
        }
        assert!(
            differences.iter().all(|&d| d < 1e-9),
            "case {case}: {p:?} ({})\nsolver {o:?} {s:?}\nreference {reference:?}\n{differences:?}",
            describe(&b)
        );
        assert!(e.residual.abs() < 1e-12, "case {case}: {e:?}");
        worst_residual = worst_residual.max(e.residual.abs());
        assert_eq!(b.cart_ever_stuck(), reference.stuck, "case {case}: {p:?}");
        same_phases += usize::from(b.phases.len() == reference.phases);
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
        "worst relative disagreement over {cases} bounces: omega2 {:.2e}, vx2 {:.2e}, V {:.2e}, X {:.2e}, \
         ball spring energy {:.2e}; energy residual {worst_residual:.1e}; held throughout {held}, pushed free {freed}, stopped and held again \
         {stopped}, gripping a held cart {held_grip}; same number of phases {same_phases}",
        worst[0], worst[1], worst[2], worst[3], worst[4]
    );
    assert!(freed >= 20 && stopped >= 5 && held >= 5 && held_grip >= 5);
    assert!(same_phases >= 110, "{same_phases}");
}

#[test]
fn a_stiff_critically_damped_ball_approaches_the_rigid_ball_with_the_same_string_friction() {
    for base in [
        Params {
            cart_friction: 20.0,
            ..Params::default()
        },
        Params {
            cart_friction: 5.0,
            cart_mass: 0.001,
            stiffness: 9554.0,
            ..Params::default()
        },
        Params {
            cart_friction: 2.0,
            angle_deg: 30.0,
            cart_mass: 0.05,
            ..Params::default()
        },
    ] {
        let rigid = solve(&base).unwrap();
        let mut errors = vec![];
        for kb in [1e6, 1e7, 1e8, 1e9] {
            let b = solve(&Params {
                ball_stiffness: kb,
                ball_damping: 1.0,
                ..base
            })
            .unwrap();
            let (o, r) = (&b.outcome, &rigid.outcome);
            let error = (o.omega2 - r.omega2).abs() * base.radius / base.speed
                + (o.vx2 - r.vx2).abs() / base.speed
                + (b.final_state.x - rigid.final_state.x).abs() / (base.speed * base.duration)
                + (b.final_state.v - rigid.final_state.v).abs() / base.speed;
            errors.push(error);
        }
        assert!(rigid.phases.iter().any(|p| p.cart != Cart::Stuck));
        for pair in errors.windows(2) {
            assert!(pair[1] < pair[0], "{base:?}: {errors:?}");
        }
        assert!(errors[3] < 1e-3, "{base:?}: {errors:?}");
    }
}

#[test]
fn a_vanishing_string_friction_approaches_the_model_without_it() {
    let mut rng = Rng(0x0fc0_0000_0003);
    for case in 0..30 {
        let p = random_compliant(&mut rng, 1);
        let free = solve(&p).unwrap();
        let mut errors = vec![];
        for fc in [1e-2, 1e-4, 1e-6] {
            let b = solve(&Params {
                cart_friction: fc * peak_friction(&p),
                ..p
            })
            .unwrap();
            let speed = p.speed + p.radius * p.spin.abs();
            errors.push(
                (b.outcome.omega2 - free.outcome.omega2).abs() * p.radius / speed
                    + (b.outcome.vx2 - free.outcome.vx2).abs() / speed,
            );
        }
        // (Rounding aside: a cart held throughout leaves nothing to approach.)
        assert!(
            errors[2] < 1e-4 && errors[2] <= errors[0] + 1e-14,
            "case {case}: {p:?}: {errors:?}"
        );
    }
}

#[test]
fn string_friction_beyond_any_push_holds_the_cart_as_a_still_surface() {
    // The cart never moves: the ball bounces off a still surface, whatever the cart's mass and spring.
    for (angle, spin) in [(20.0, 0.0), (60.0, -100.0), (80.0, 50.0)] {
        let p = Params {
            cart_friction: 1e6,
            angle_deg: angle,
            spin,
            ball_stiffness: 1e5,
            ball_damping: 0.3,
            ..Params::default()
        };
        let a = solve(&p).unwrap();
        let b = solve(&Params {
            cart_mass: 3.0,
            stiffness: 10.0,
            ..p
        })
        .unwrap();
        assert!(a.phases.iter().all(|ph| ph.cart == Cart::Stuck));
        // The same bounce, to the rounding of the event search (whose probes depend on the cart).
        let (x, y) = (&a.outcome, &b.outcome);
        let speed = x.vx2.abs() + x.vy2.abs();
        assert!(
            (x.omega2 - y.omega2).abs() * p.radius <= 1e-13 * speed
                && (x.vx2 - y.vx2).abs() <= 1e-13 * speed
                && x.vy2 == y.vy2,
            "{x:?} {y:?}"
        );
        let e = a.energy();
        assert_eq!((e.final_cart, e.cart_friction_loss), (0.0, 0.0));
        assert!(e.residual.abs() < 1e-12, "{e:?}");
    }
}

fn params() -> impl Strategy<Value = Params> {
    let cart = (
        log_range(1e-3, 1e4),
        prop_oneof![Just(0.0), log_range(1.0, 1e6)],
        Just(1usize),
    );
    (compliant_strategy(cart), log_range(1e-4, 3.0)).prop_map(|(mut p, string)| {
        p.cart_friction = string * peak_friction(&p);
        p
    })
}

proptest! {
    #![proptest_config(config(200))]

    #[test]
    fn every_compliant_bounce_with_string_friction_is_physical(p in params()) {
        let Some(b) = solved_or_refused(&p)? else {
            return Ok(());
        };
        check_basics(&p, &b)?;
        check_cart_motion(&p, &b)?;
    }
}
