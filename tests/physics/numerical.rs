//! The exact solver against an independent numerical integration (RK4 with bisected events) over random
//! parameters, including bounces that grip and slide again several times.

use crate::support::integrator::integrate;
use snapback::model::{Params, PhaseKind, solve};

use crate::support::rng;
use rng::Rng;

fn random_params(rng: &mut Rng) -> Params {
    Params {
        angle_deg: rng.uniform(3.0, 90.0),
        speed: rng.uniform(2.0, 40.0),
        spin: rng.uniform(-300.0, 300.0),
        mu: rng.uniform(0.05, 0.8),
        duration: rng.uniform(2e-3, 8e-3),
        ey: rng.uniform(0.3, 1.0),
        mass: rng.uniform(0.04, 0.2),
        radius: rng.uniform(0.02, 0.05),
        alpha: rng.uniform(0.4, 0.67),
        // Light carts and stiff springs give the multi-grip bounces; heavy ones the rigid limit.
        cart_mass: if rng.unit() < 0.5 {
            rng.log_uniform(1e-5, 2e-3)
        } else {
            rng.log_uniform(2e-3, 10.0)
        },
        stiffness: if rng.unit() < 0.1 {
            0.0
        } else {
            rng.log_uniform(1e3, 1e5)
        },
        cart_friction: 0.0,
        chain: 1.0,
        ball_stiffness: 0.0,
        ball_damping: 0.0,
        ..Params::default()
    }
}

/// Step of the reference integration: small against both the contact time and the cart's period.
fn step_for(p: &Params) -> f64 {
    let fastest = (std::f64::consts::PI / p.duration).max((p.stiffness / p.cart_mass).sqrt());
    (p.duration / 20_000.0).min(0.004 / fastest)
}

#[test]
fn exact_solver_agrees_with_numerical_integration() {
    let mut rng = Rng(0x5eed_cafe_f00d_1234);
    let mut multi_grip = 0;
    let cases = 200;
    for case in 0..cases {
        let p = random_params(&mut rng);
        let exact = solve(&p).expect("valid parameters solve");
        let reference = integrate(&p, step_for(&p));
        // Relative to the value, or to the incoming scale when the value itself is near zero.
        let tol_v = 1e-7 * exact.outcome.vx2.abs().max(p.speed);
        let tol_w = 1e-7 * exact.outcome.omega2.abs().max(p.speed / p.radius);
        assert!(
            (exact.outcome.vx2 - reference.vx2).abs() <= tol_v,
            "case {case} vx2: exact {} numerical {} ({p:?}, phases {})",
            exact.outcome.vx2,
            reference.vx2,
            exact.phase_summary()
        );
        assert!(
            (exact.outcome.omega2 - reference.omega2).abs() <= tol_w,
            "case {case} omega2: exact {} numerical {} ({p:?}, phases {})",
            exact.outcome.omega2,
            reference.omega2,
            exact.phase_summary()
        );
        assert_eq!(
            exact.phases.len(),
            reference.phases,
            "case {case}: {}",
            exact.phase_summary()
        );
        let grips = exact
            .phases
            .iter()
            .filter(|ph| ph.kind == PhaseKind::Grip)
            .count();
        if grips >= 2 {
            multi_grip += 1;
        }
    }
    assert!(
        multi_grip >= 15,
        "only {multi_grip} of {cases} cases gripped twice or more"
    );
}

#[test]
fn agrees_on_the_papers_cases() {
    let base = Params::default();
    let cases = [
        base,
        Params {
            stiffness: 4e4,
            ..base
        },
        Params {
            stiffness: 4e4,
            cart_mass: 10.0,
            ..base
        },
        Params {
            cart_mass: 1e-3,
            ..base
        },
        Params {
            cart_mass: 1e-4,
            stiffness: 1500.0,
            ..base
        },
    ];
    for p in cases {
        let exact = solve(&p).unwrap();
        let reference = integrate(&p, step_for(&p));
        assert!(
            (exact.outcome.omega2 - reference.omega2).abs() < 1e-7 * exact.outcome.omega2.abs()
        );
        assert!(
            (exact.final_state.x - reference.x2).abs() < 1e-7 * 1e-3,
            "{p:?}"
        );
        assert!(
            (exact.final_state.v - reference.v2).abs() < 1e-7 * p.speed,
            "{p:?}"
        );
    }
}

#[test]
fn string_friction_agrees_with_numerical_integration() {
    // The cart sticks and slips too: a Coulomb friction F_c up to about the largest sliding friction.
    let mut rng = Rng(0xfeed_5eed_0ddb_a110);
    let mut stuck_somewhere = 0;
    let cases = 120;
    for case in 0..cases {
        let mut p = random_params(&mut rng);
        let peak_friction = p.mu
            * (1.0 + p.ey)
            * std::f64::consts::PI
            * p.mass
            * p.speed
            * p.angle_deg.to_radians().sin()
            / (2.0 * p.duration);
        p.cart_friction = rng.uniform(0.0, 1.2) * peak_friction;
        let exact = solve(&p).expect("valid parameters solve");
        let reference = integrate(&p, step_for(&p));
        let tol_v = 1e-7 * exact.outcome.vx2.abs().max(p.speed);
        let tol_w = 1e-7 * exact.outcome.omega2.abs().max(p.speed / p.radius);
        assert!(
            (exact.outcome.vx2 - reference.vx2).abs() <= tol_v
                && (exact.outcome.omega2 - reference.omega2).abs() <= tol_w,
            "case {case}: exact ({}, {}) numerical ({}, {}) for {p:?}",
            exact.outcome.vx2,
            exact.outcome.omega2,
            reference.vx2,
            reference.omega2
        );
        assert!(
            (exact.final_state.x - reference.x2).abs()
                <= 1e-7 * exact.final_state.x.abs().max(1e-6),
            "case {case}"
        );
        if exact
            .phases
            .iter()
            .any(|ph| ph.cart == snapback::model::Cart::Stuck)
        {
            stuck_somewhere += 1;
        }
    }
    assert!(
        stuck_somewhere >= 30,
        "only {stuck_somewhere} of {cases} cases stuck the cart"
    );
}
