//! String friction under the rigid ball on a chain on a free frame (issue 23, `--chain N --frame-mass M
//! --cart-friction F_c`): the friction acts between the first mass and the frame, and a first mass held
//! to the frame makes one body with it, the links behind a ring. Against the chain integrator with the
//! same friction between its first and last masses, momentum along the surface phase by phase, the
//! energy budget, the heavy frame against the clamped chain with string friction, and property tests
//! over random framed chains.

use proptest::prelude::*;
use proptest::test_runner::TestCaseError;

use crate::frame_chain::{assert_momentum_conserved, close, random_framed_chain};
use crate::support::chain::random_chain;
use crate::support::chain_integrator;
use crate::support::energy::assert_string_friction_works;
use crate::support::prop::config;
use crate::support::rng::Rng;
use snapback::model::contact::Cart;
use snapback::model::{Params, PhaseKind, solve};

/// A random rigid-ball bounce on a chain of 2 to 6 masses on a frame of 20 g to 20 kg, with string
/// friction from a light touch to one that holds the first mass throughout.
fn random_framed_string(rng: &mut Rng) -> Params {
    let mut p = random_framed_chain(rng, 5);
    p.cart_friction = rng.log_uniform(0.05, 200.0);
    p
}

#[test]
fn string_friction_on_a_framed_chain_agrees_with_an_independent_integration() {
    let mut rng = Rng(0xf4a3_5715_0023_0001);
    let (mut held, mut moved, mut held_grip) = (0, 0, 0);
    for case in 0..60 {
        let p = random_framed_string(&mut rng);
        let exact = solve(&p).expect("string friction on a framed chain solves");
        let reference = chain_integrator::integrate(&p, chain_integrator::step_for(&p) / 4.0);
        let o = &exact.outcome;
        let tol = 1e-9;
        let what = format!("case {case}: {p:?} ({})", exact.phase_summary());
        assert_eq!(exact.phases.len(), reference.phases, "{what}");
        let pairs = [
            ("vx2", o.vx2, reference.vx2, p.speed),
            ("omega2", o.omega2, reference.omega2, p.speed / p.radius),
            ("V_1", exact.final_state.v, reference.v2, p.speed),
            ("V_f", exact.frame_velocity(), reference.frame_v, p.speed),
            (
                "X_1 - X_f",
                exact.final_state.x,
                reference.x1,
                p.speed * p.duration,
            ),
        ];
        for (name, a, b, scale) in pairs {
            assert!(close(a, b, tol, scale), "{what}: {name} {a} vs {b}");
        }
        let e = exact.energy();
        assert!(
            close(e.final_cart, reference.chain_energy, tol, e.initial),
            "{what}: chain energy {} vs {}",
            e.final_cart,
            reference.chain_energy
        );
        held += usize::from(exact.phases.iter().any(|ph| ph.cart == Cart::Stuck));
        held_grip += usize::from(
            exact
                .phases
                .iter()
                .any(|ph| ph.cart == Cart::Stuck && ph.kind == PhaseKind::Grip),
        );

        moved += usize::from(exact.phases.iter().any(|ph| ph.cart != Cart::Stuck));
    }
    // The ball gripping the held body (its static friction carried by the ring's springs).
    assert!(
        held >= 20 && moved >= 20 && held_grip >= 3,
        "held {held}, moved {moved}, gripped while held {held_grip}"
    );
}

#[test]
fn momentum_along_the_surface_is_conserved_through_every_phase_with_string_friction() {
    let mut rng = Rng(0xf4a3_5715_0023_0002);
    for case in 0..60 {
        assert_momentum_conserved(&random_framed_string(&mut rng), &format!("case {case}"));
    }
}

#[test]
fn string_friction_on_a_framed_chain_creates_no_energy() {
    let mut rng = Rng(0xf4a3_5715_0023_0003);
    assert_string_friction_works((0..200).map(|_| random_framed_string(&mut rng)), 50);
}

#[test]
fn a_heavy_frame_approaches_the_clamped_chain_with_string_friction() {
    let mut rng = Rng(0xf4a3_5715_0023_0004);
    for case in 0..40 {
        let mut p = random_framed_string(&mut rng);
        p.frame_normal_mass = 0.0;
        p.frame_mass = 0.0;
        let wall = solve(&p).expect("a clamped chain with string friction solves");
        p.frame_mass = 1e6;
        let heavy = solve(&p).expect("a heavy frame solves");
        let what = format!(
            "case {case}: {p:?} ({} vs {})",
            wall.phase_summary(),
            heavy.phase_summary()
        );
        // The frame's recoil is of order m / M_t = 1e-7 of the speeds, and e_A differs from e_y by as much.
        let tol = 1e-5;
        let (a, b) = (&wall.outcome, &heavy.outcome);
        assert!(close(a.vx2, b.vx2, tol, p.speed), "{what}");
        assert!(close(a.omega2, b.omega2, tol, p.speed / p.radius), "{what}");
        assert!(
            close(wall.final_state.v, heavy.final_state.v, tol, p.speed),
            "{what}"
        );
        assert!(heavy.frame_velocity().abs() <= 1e-5 * p.speed, "{what}");
    }
}

proptest! {
    #![proptest_config(config(200))]

    #[test]
    fn random_framed_chains_with_string_friction_solve_within_their_budgets(seed in any::<u64>()) {
        let mut rng = Rng(seed | 1);
        let n = 2 + rng.below(14);
        let mut p = random_chain(&mut rng, n as f64);
        // Lighter and heavier frames and frictions than the integration can follow.
        p.frame_mass = rng.log_uniform(1e-3, 1e3);
        p.cart_friction = rng.log_uniform(0.01, 1000.0);
        let b = solve(&p).map_err(|e| TestCaseError::fail(format!("{e} ({p:?})")))?;
        let e = b.energy();
        prop_assert!(b.outcome.vx2.is_finite() && b.outcome.omega2.is_finite());
        prop_assert!(e.residual.abs() < 1e-9, "{e:?} ({p:?})");
        prop_assert!(e.cart_friction_loss >= 0.0 && e.friction_loss >= -1e-12 * e.initial);
        prop_assert!(e.final_ball + e.final_cart + e.frame <= e.initial * (1.0 + 1e-12));
        // Held to the frame, the first mass keeps its place on it.
        for (index, phase) in b.phases.iter().enumerate() {
            if phase.cart != Cart::Stuck {
                continue;
            }
            let first = b.sample_in(index, phase.start);
            for i in 1..=8 {
                let s = b.sample_in(index, phase.start + phase.duration() * f64::from(i) / 8.0);
                prop_assert!(s.x == first.x, "{} vs {} ({p:?})", s.x, first.x);
            }
        }
    }
}
