//! String friction under a compliant ball on a chain on a free frame (issue 23, `--chain N
//! --ball-stiffness k_b --frame-mass M_t --cart-friction F_c`): the friction acts between the first
//! mass and the frame, and a first mass held to the frame makes one body with it, the links behind a
//! ring, which the ball's spring grips or slides on. Against the independent integration of
//! support/chain_compliant_integrator.rs (RK4 with that friction between the first and the last mass),
//! momentum along the surface phase by phase, the energy budget, the heavy frame against the clamped
//! chain with the same string friction, the longest chain on a frame (its 16 links and the frame, 17
//! masses), and property tests.

use proptest::prelude::*;

use super::frame_compliant::disagreements;
use crate::support::chain_compliant_integrator::{integrate, step_for};
use crate::support::chain_integrator;
use crate::support::compliant::{incoming, peak_friction, random_compliant, solved_or_refused};
use crate::support::energy::assert_string_friction_works;
use crate::support::phases::each_phase;
use crate::support::phases::regimes;
use crate::support::prop::{config, within_the_cone};
use crate::support::rng::Rng;
use snapback::model::chain::ChainState;
use snapback::model::compliant::CompliantBall;
use snapback::model::contact::{Ball, Contact};
use snapback::model::setup::Setup;
use snapback::model::{Bounce, Cart, Params, PhaseKind, solve};

/// The reference's step: a 250th of a radian of the fastest oscillation (see `step_for`).
const PER_RADIAN: f64 = 0.004;

/// A random compliant ball on a chain of `links` masses with springs, tied to a frame of 20 g to
/// 20 kg, the string friction from a thousandth to three times mu N0.
fn random_params(rng: &mut Rng, links: usize) -> Params {
    let mut p = random_compliant(rng, links);
    p.stiffness = rng.log_uniform(1e3, 1e5);
    p.ball_damping = rng.uniform(0.05, 1.5);
    p.frame_mass = rng.log_uniform(0.02, 20.0);
    if rng.unit() < 0.5 {
        p.frame_normal_mass = rng.log_uniform(0.05, 20.0);
    }
    p.cart_friction = rng.log_uniform(1e-3, 3.0) * peak_friction(&p);
    p
}

/// Solves `p` and checks it against the reference to 1e-9: the same phases, the same holding, and
/// every quantity of [`disagreements`]. The largest disagreement.
fn check_against_reference(p: &Params, what: &str) -> (Bounce, f64) {
    let b = solve(p).unwrap_or_else(|e| panic!("{what}: {e}\n{p:?}"));
    let r = integrate(p, step_for(p, PER_RADIAN));
    let what = format!("{what}: {p:?} ({})\n{r:?}", b.phase_summary());
    assert_eq!(b.phases.len(), r.phases, "{what}");
    assert_eq!(b.cart_ever_stuck(), r.held, "{what}");
    let mut worst: f64 = 0.0;
    for (name, d) in disagreements(p, &b, &r) {
        assert!(d < 1e-9, "{name} off by {d:.2e}: {what}");
        worst = worst.max(d);
    }
    (b, worst)
}

#[test]
fn string_friction_under_a_compliant_ball_on_a_framed_chain_agrees_with_an_integration() {
    let mut rng = Rng(0xf4a3_c5a1_5715_0001);
    let (mut held_grip, mut held_slide, mut freed, mut stopped) = (0, 0, 0, 0);
    let mut worst: f64 = 0.0;
    for case in 0..50 {
        let links = 2 + rng.below(5);
        let p = random_params(&mut rng, links);
        let (b, d) = check_against_reference(&p, &format!("case {case}"));
        worst = worst.max(d);
        let phases = &b.phases;
        let held = |kind| {
            phases
                .iter()
                .any(|ph| (ph.kind, ph.cart) == (kind, Cart::Stuck))
        };
        held_grip += usize::from(held(PhaseKind::Grip));
        held_slide += usize::from(held(PhaseKind::Slide));
        let (was_freed, was_stopped) = regimes(phases);
        freed += usize::from(was_freed);
        stopped += usize::from(was_stopped);
    }
    eprintln!(
        "worst disagreement {worst:.2e}; gripping a held first mass {held_grip}, sliding on one \
         {held_slide}, pushed free {freed}, stopped and held {stopped}"
    );
    assert!(
        held_grip >= 5 && held_slide >= 5 && freed >= 5 && stopped >= 3,
        "held grips {held_grip}, held slides {held_slide}, freed {freed}, stopped {stopped}"
    );
}

/// m v_x plus every mass's momentum along the surface, the frame's included.
fn momentum(p: &Params, setup: &Setup, s: &ChainState) -> f64 {
    let n = p.chain as usize;
    let links: f64 = s.v[..n].iter().sum::<f64>() * p.cart_mass / p.chain;
    setup.m * s.vx + links + p.frame_mass * s.v[s.frame]
}

#[test]
fn momentum_along_the_surface_is_conserved_through_every_phase() {
    let mut rng = Rng(0xf4a3_c5a1_5715_0002);
    let mut held_grips = 0;
    for case in 0..60 {
        let links = 2 + rng.below(7);
        let p = random_params(&mut rng, links);
        let (model, setup) = CompliantBall::new(&p, true).expect("a framed chain");
        let p0 = momentum(&p, &setup, model.start(&setup).0.full());
        let scale = setup.m * (p.speed + p.radius * p.spin.abs());
        each_phase(&model, &setup, |mode, motion, start, end| {
            held_grips += usize::from(mode.1 == Cart::Stuck && mode.0 == Ball::Grip);
            // Inside the phase and at its end.
            for t in [0.5 * (CompliantBall::time(start) + end), end] {
                let s = model.state_at(&setup, motion, t, None);
                let drift = (momentum(&p, &setup, s.full()) - p0).abs();
                assert!(
                    drift <= 1e-11 * scale,
                    "case {case} at {t} ({mode:?}): {drift} ({p:?})"
                );
            }
        });
    }
    assert!(held_grips >= 5, "only {held_grips} held grips");
}

#[test]
fn string_friction_under_a_compliant_ball_on_a_framed_chain_creates_no_energy() {
    let mut rng = Rng(0xf4a3_c5a1_5715_0003);
    let bounces = (0..150).map(|_| {
        let links = 2 + rng.below(7);
        random_params(&mut rng, links)
    });
    assert_string_friction_works(bounces, 40);
}

#[test]
fn a_heavy_frame_approaches_the_clamped_chain_with_the_same_string_friction() {
    let mut rng = Rng(0xf4a3_c5a1_5715_0004);
    for case in 0..40 {
        let links = 2 + rng.below(7);
        let mut p = random_params(&mut rng, links);
        p.frame_normal_mass = 0.0;
        p.frame_mass = 0.0;
        let wall = solve(&p).expect("a clamped chain with string friction solves");
        p.frame_mass = 1e6;
        let heavy = solve(&p).expect("a heavy frame solves");
        let what = format!(
            "case {case}: {p:?} ({} against {})",
            wall.phase_summary(),
            heavy.phase_summary()
        );
        // The frame's recoil is of order m / M_t = 1e-7 of the speeds, and e_A differs from e_y by as
        // much.
        let speed = incoming(&p);
        let tol = 1e-5;
        let (a, b) = (&wall.outcome, &heavy.outcome);
        assert!((a.vx2 - b.vx2).abs() <= tol * speed, "{what}");
        assert!(
            p.radius * (a.omega2 - b.omega2).abs() <= tol * speed,
            "{what}"
        );
        assert!(
            (wall.final_state.v - heavy.final_state.v).abs() <= tol * speed,
            "{what}"
        );
        assert!(heavy.frame_velocity().abs() <= 1e-5 * p.speed, "{what}");
    }
}

#[test]
fn the_longest_chain_on_a_frame_agrees_with_the_integrations() {
    // The rigid ball, with and without string friction, against the chain's integration.
    for cart_friction in [0.0, 5.0] {
        let p = Params {
            chain: 16.0,
            frame_mass: 0.3,
            cart_friction,
            ..Params::default()
        };
        let exact = solve(&p).expect("a chain of 16 on a frame solves");
        let reference = chain_integrator::integrate(&p, chain_integrator::step_for(&p) / 8.0);
        let what = format!("{p:?} ({})", exact.phase_summary());
        assert_eq!(exact.phases.len(), reference.phases, "{what}");
        let pairs = [
            (exact.outcome.vx2, reference.vx2, p.speed),
            (exact.outcome.omega2, reference.omega2, p.speed / p.radius),
            (exact.final_state.v, reference.v2, p.speed),
            (exact.frame_velocity(), reference.frame_v, p.speed),
        ];
        for (a, b, scale) in pairs {
            assert!((a - b).abs() <= 1e-9 * scale, "{what}: {a} vs {b}");
        }
    }
    // The compliant ball, with and without string friction.
    for cart_friction in [0.0, 30.0] {
        let p = Params {
            chain: 16.0,
            frame_mass: 0.188,
            ball_stiffness: 1e5,
            ball_damping: 0.3,
            cart_friction,
            ..Params::default()
        };
        check_against_reference(&p, "chain of 16");
    }
}

proptest! {
    #![proptest_config(config(100))]

    #[test]
    fn random_framed_chains_with_string_friction_under_a_compliant_ball_solve_within_the_cone(
        seed in any::<u64>(),
    ) {
        let mut rng = Rng(seed | 1);
        let links = 2 + rng.below(15);
        let mut p = random_params(&mut rng, links);
        // Lighter frames and balls than the integration can follow.
        p.frame_mass = rng.log_uniform(1e-3, 1e3);
        p.ball_damping = if rng.unit() < 0.2 { 0.0 } else { rng.uniform(0.05, 1.5) };
        let Some(b) = solved_or_refused(&p)? else {
            return Ok(());
        };
        prop_assert!(b.outcome.vx2.is_finite() && b.outcome.omega2.is_finite());
        prop_assert!(b.frame_velocity().is_finite());
        let e = b.energy();
        prop_assert!(e.residual.abs() < 1e-9, "{:?}", e);
        let n_peak = b.setup.n0;
        for s in b.series(64) {
            within_the_cone(&p, &s, n_peak)?;
        }
    }
}
