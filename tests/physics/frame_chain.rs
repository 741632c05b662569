//! The rigid ball on a chain whose last spring is tied to a free frame (issue 23, `--chain N
//! --frame-mass M`): against an independent numerical integration with the frame as one more mass, the
//! heavy frame against the wall, momentum along the surface phase by phase, the energy budget, and
//! property tests over random framed chains.

use proptest::prelude::*;

use crate::support::chain::random_chain;
use crate::support::chain_integrator;
use crate::support::energy::assert_nothing_created;
use crate::support::phases::each_phase;
use crate::support::prop::{config, within_the_cone};
use crate::support::rng::Rng;
use snapback::model::chain::{ChainOfMasses, ChainState};
use snapback::model::contact::Contact;
use snapback::model::setup::Setup;
use snapback::model::{Params, PhaseKind, solve};

/// A random rigid-ball bounce on a chain of 2 to `sizes + 1` masses with springs, tied to a frame of 20 g
/// to 20 kg.
pub(super) fn random_framed_chain(rng: &mut Rng, sizes: usize) -> Params {
    let n = 2 + rng.below(sizes);
    let mut p = random_chain(rng, n as f64);
    p.stiffness = rng.log_uniform(1e3, 1e5);
    // Keep the fastest mode within reach of a fixed-step integration.
    p.cart_mass = p.cart_mass.max(2e-4);
    p.frame_mass = rng.log_uniform(0.02, 20.0);
    if rng.unit() < 0.5 {
        p.frame_normal_mass = rng.log_uniform(0.05, 20.0);
    }
    p
}

/// |a - b| within `rel` of the larger of |a| and `scale`.
pub(super) fn close(a: f64, b: f64, rel: f64, scale: f64) -> bool {
    (a - b).abs() <= rel * a.abs().max(scale)
}

#[test]
fn the_framed_chain_agrees_with_an_independent_integration() {
    let mut rng = Rng(0xf4a3_c4a1_2310_0001);
    let mut regrips = 0;
    for case in 0..100 {
        let p = random_framed_chain(&mut rng, 7);
        let exact = solve(&p).expect("a framed chain solves");
        let reference = chain_integrator::integrate(&p, chain_integrator::step_for(&p) / 4.0);
        let o = &exact.outcome;
        let tol = 1e-9;
        let what = format!("case {case}: {p:?} ({})", exact.phase_summary());
        assert_eq!(exact.phases.len(), reference.phases, "{what}");
        assert!(
            close(o.vx2, reference.vx2, tol, p.speed),
            "{what}: vx2 {} vs {}",
            o.vx2,
            reference.vx2
        );
        assert!(
            close(o.omega2, reference.omega2, tol, p.speed / p.radius),
            "{what}: omega2 {} vs {}",
            o.omega2,
            reference.omega2
        );
        assert!(
            close(exact.final_state.v, reference.v2, tol, p.speed),
            "{what}: V_1 {} vs {}",
            exact.final_state.v,
            reference.v2
        );
        assert!(
            close(exact.frame_velocity(), reference.frame_v, tol, p.speed),
            "{what}: V_f {} vs {}",
            exact.frame_velocity(),
            reference.frame_v
        );
        assert!(
            close(exact.final_state.x, reference.x1, tol, p.speed * p.duration),
            "{what}: X_1 - X_f {} vs {}",
            exact.final_state.x,
            reference.x1
        );
        let e = exact.energy();
        assert!(
            close(e.final_cart, reference.chain_energy, tol, e.initial),
            "{what}: chain energy {} vs {}",
            e.final_cart,
            reference.chain_energy
        );
        let grips = exact
            .phases
            .iter()
            .filter(|ph| ph.kind == PhaseKind::Grip)
            .count();
        regrips += usize::from(grips >= 2);
    }
    assert!(regrips >= 3, "only {regrips} cases gripped twice or more");
}

#[test]
fn a_heavy_frame_approaches_the_wall() {
    let mut rng = Rng(0xf4a3_c4a1_2310_0002);
    for case in 0..40 {
        let mut p = random_framed_chain(&mut rng, 7);
        p.frame_normal_mass = 0.0;
        p.frame_mass = 0.0;
        let wall = solve(&p).expect("a clamped chain solves");
        p.frame_mass = 1e6;
        let heavy = solve(&p).expect("a heavy frame solves");
        let what = format!("case {case}: {p:?} ({})", wall.phase_summary());
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

/// m v_x plus every mass's momentum along the surface, the frame's included.
fn momentum(p: &Params, setup: &Setup, s: &ChainState) -> f64 {
    let n = p.chain as usize;
    let links: f64 = s.v[..n].iter().sum::<f64>() * p.cart_mass / p.chain;
    setup.m * s.vx + links + p.frame_mass * s.v[s.frame]
}

/// Runs the framed chain of `p` phase by phase and checks its momentum along the surface (ball, masses,
/// frame) inside every phase and at its end against its value at first contact, to 1e-12.
pub(crate) fn assert_momentum_conserved(p: &Params, what: &str) {
    let setup = Setup::new(p);
    let model = ChainOfMasses::new(p, &setup).expect("a framed chain");
    let p0 = momentum(p, &setup, &model.start(&setup).0);
    let scale = setup.m * (p.speed + p.radius * p.spin.abs());
    each_phase(&model, &setup, |mode, motion, start, end| {
        // Inside the phase and at its end.
        for t in [0.5 * (start.t + end), end] {
            let s = model.state_at(&setup, motion, t, None);
            let drift = (momentum(p, &setup, &s) - p0).abs();
            assert!(
                drift <= 1e-12 * scale,
                "{what} at {t} ({mode:?}): {drift} ({p:?})"
            );
        }
    });
}

#[test]
fn momentum_along_the_surface_is_conserved_through_every_phase() {
    let mut rng = Rng(0xf4a3_c4a1_2310_0003);
    for case in 0..60 {
        assert_momentum_conserved(&random_framed_chain(&mut rng, 7), &format!("case {case}"));
    }
}

#[test]
fn the_frame_takes_its_kinetic_energy_from_the_ball_and_none_is_created() {
    let mut rng = Rng(0xf4a3_c4a1_2310_0004);
    for case in 0..200 {
        let p = random_framed_chain(&mut rng, 7);
        let b = solve(&p).expect("a framed chain solves");
        let e = b.energy();
        let what = format!("case {case}: {p:?} {e:?}");
        assert_nothing_created(&e, &what);
        if b.frame_velocity() != 0.0 {
            assert!(e.frame > 0.0, "{what}");
        }
    }
}

proptest! {
    #![proptest_config(config(200))]

    #[test]
    fn random_framed_chains_solve_finite_within_the_friction_cone(seed in any::<u64>()) {
        let mut rng = Rng(seed | 1);
        let mut p = random_framed_chain(&mut rng, 7);
        // Lighter frames and chains than the integration can follow.
        p.frame_mass = rng.log_uniform(1e-3, 1e3);
        p.cart_mass = rng.log_uniform(1e-5, 1.0);
        p.chain = (2 + rng.below(14)) as f64;
        let b = solve(&p).unwrap();
        prop_assert!(b.outcome.vx2.is_finite() && b.outcome.omega2.is_finite());
        prop_assert!(b.frame_velocity().is_finite());
        let e = b.energy();
        prop_assert!(e.residual.abs() < 1e-9, "{:?}", e);
        let n_peak = b.setup.n0;
        for s in b.series(64) {
            within_the_cone(&p, &s, n_peak)?;
            if s.kind == PhaseKind::Grip {
                prop_assert!(s.slip.abs() <= 1e-9 * p.speed, "slip {} in a grip", s.slip);
            }
        }
    }
}
