//! The chain of masses and springs (`--chain N`): its limits (N = 1 is the single cart, a very heavy
//! chain is a rigid surface), its energy balance, an independent numerical integration of the 2N + 2
//! equations of motion, and properties over random chains.

use crate::support::chain_integrator;
use crate::support::prop::within_the_cone;

use proptest::prelude::*;
use snapback::model::solve::solve_chain;
use snapback::model::{Params, PhaseKind, solve};

use crate::support::rng;
use rng::Rng;

use crate::support::chain as chain_draw;
use chain_draw::{close, random_chain};

use crate::support::prop;
use prop::{config, log_range};

#[test]
fn one_mass_through_the_chain_is_the_single_cart() {
    let mut rng = Rng(0x0c4a_1ace_5eed_0001);
    let cases = 300;
    for case in 0..cases {
        let p = random_chain(&mut rng, 1.0);
        let cart = solve(&p).expect("valid parameters solve");
        let chain = solve_chain(&p).expect("the chain path solves N = 1");
        let speed = p.speed + p.radius * p.spin.abs();
        let what = format!("case {case}: {p:?} ({})", cart.phase_summary());
        assert_eq!(cart.phase_summary(), chain.phase_summary(), "{what}");
        assert_eq!(cart.phases.len(), chain.phases.len(), "{what}");
        for (a, b) in cart.phases.iter().zip(&chain.phases) {
            assert!(
                close(a.end, b.end, p.duration, 1e-12),
                "{what}: phase end {} {}",
                a.end,
                b.end
            );
        }
        let (a, b) = (&cart.outcome, &chain.outcome);
        assert!(
            close(a.omega2, b.omega2, speed / p.radius, 1e-12),
            "{what}: omega2 {} {}",
            a.omega2,
            b.omega2
        );
        assert!(
            close(a.vx2, b.vx2, speed, 1e-12),
            "{what}: vx2 {} {}",
            a.vx2,
            b.vx2
        );
        let (sa, sb) = (&cart.final_state, &chain.final_state);
        assert!(
            close(sa.v, sb.v, speed, 1e-12),
            "{what}: V {} {}",
            sa.v,
            sb.v
        );
        assert!(
            close(sa.x, sb.x, speed * p.duration, 1e-12),
            "{what}: X {} {}",
            sa.x,
            sb.x
        );
        let (ea, eb) = (cart.energy(), chain.energy());
        assert!(
            close(ea.final_cart, eb.final_cart, ea.initial, 1e-12),
            "{what}: cart energy"
        );
        assert!(
            close(ea.friction_loss, eb.friction_loss, ea.initial, 1e-12),
            "{what}: friction loss"
        );
    }
}

#[test]
fn one_mass_through_the_chain_matches_the_papers_cases() {
    let base = Params::default();
    for p in [
        base,
        Params {
            stiffness: 4e4,
            ..base
        },
        Params {
            cart_mass: 1e-3,
            ..base
        },
        Params {
            stiffness: 0.0,
            ..base
        },
        // The cart at resonance with the normal force: sqrt(k/M) = pi/T.
        Params {
            stiffness: 0.01 * (std::f64::consts::PI / 5e-3).powi(2),
            ..base
        },
    ] {
        let (cart, chain) = (solve(&p).unwrap(), solve_chain(&p).unwrap());
        assert_eq!(cart.phase_summary(), chain.phase_summary());
        assert!(
            close(cart.outcome.omega2, chain.outcome.omega2, 1.0, 1e-12),
            "{p:?}"
        );
        assert!(
            close(cart.outcome.vx2, chain.outcome.vx2, p.speed, 1e-12),
            "{p:?}"
        );
    }
}

#[test]
fn every_chain_length_balances_energy() {
    let mut rng = Rng(0xe4e4_0000_1234_abcd);
    for n in 2..=16 {
        for _ in 0..12 {
            let p = random_chain(&mut rng, n as f64);
            let b = solve(&p).expect("valid chains solve");
            let e = b.energy();
            assert!(
                e.residual.abs() < 1e-10,
                "N = {n}: residual {} for {p:?}",
                e.residual
            );
            assert!(e.final_cart >= 0.0 && e.friction_loss >= -1e-12 * e.initial);
        }
        // And the paper's case on a chain.
        let p = Params {
            chain: n as f64,
            ball_stiffness: 0.0,
            ball_damping: 0.0,
            ..Params::default()
        };
        let e = solve(&p).unwrap().energy();
        assert!(e.residual.abs() < 1e-12, "N = {n}: {}", e.residual);
        assert!(e.final_cart > 0.0, "the chain keeps some energy");
    }
}

#[test]
fn a_very_heavy_chain_is_a_rigid_surface() {
    // Once the ball grips a surface that cannot move it rolls: v_x2 - r omega2 = 0, and the friction's
    // impulse m_eff (v_x1 - r omega1) gives v_x2 = (v_x1 + alpha r omega1)/(1 + alpha).
    for n in [2.0, 5.0, 16.0] {
        for (angle, spin) in [(60.0, -100.0), (45.0, 0.0), (80.0, 50.0)] {
            let p = Params {
                chain: n,
                cart_mass: 1e12,
                angle_deg: angle,
                spin,
                ..Params::default()
            };
            let b = solve(&p).unwrap();
            assert!(
                b.phases.iter().any(|ph| ph.kind == PhaseKind::Grip),
                "{}",
                b.phase_summary()
            );
            let vx1 = b.setup.vx1;
            let rigid = (vx1 + p.alpha * p.radius * spin) / (1.0 + p.alpha);
            assert!(
                (b.outcome.vx2 - rigid).abs() < 1e-9 * p.speed,
                "N {n}: {} vs {rigid}",
                b.outcome.vx2
            );
            assert!(
                (b.outcome.vx2 - p.radius * b.outcome.omega2).abs() < 1e-9 * p.speed,
                "N {n} {angle} {spin}: {} {} {}",
                b.outcome.vx2,
                p.radius * b.outcome.omega2,
                b.phase_summary()
            );
        }
    }
}

#[test]
fn a_free_chain_moves_only_its_first_mass() {
    // k = 0: the springs are gone, the first mass alone takes the friction; the ball sees a cart of M/N.
    let p = Params {
        stiffness: 0.0,
        chain: 4.0,
        ..Params::default()
    };
    let alone = Params {
        stiffness: 0.0,
        chain: 1.0,
        ball_stiffness: 0.0,
        ball_damping: 0.0,
        cart_mass: p.cart_mass / 4.0,
        ..p
    };
    let (chain, cart) = (solve(&p).unwrap(), solve(&alone).unwrap());
    assert_eq!(chain.phase_summary(), cart.phase_summary());
    assert!(close(chain.outcome.omega2, cart.outcome.omega2, 1.0, 1e-12));
    assert!(close(chain.final_state.v, cart.final_state.v, 1.0, 1e-12));
    assert!(close(
        chain.energy().final_cart,
        cart.energy().final_cart,
        1e-9,
        1e-12
    ));
}

#[test]
fn a_chain_length_that_is_not_a_whole_number_is_refused() {
    let err = solve(&Params {
        chain: 2.5,
        ..Params::default()
    })
    .unwrap_err();
    assert_eq!(
        err.to_string(),
        "--chain must be in {1, 2, ..., 16}; got 2.5"
    );
}

#[test]
#[ignore = "slow"]
fn the_chain_agrees_with_numerical_integration() {
    let mut rng = Rng(0x5eed_c4a1_0000_0042);
    let cases = 100;
    let mut multi_grip = 0;
    let mut worst: f64 = 0.0;
    for case in 0..cases {
        let n = 2 + rng.below(7);
        let mut p = random_chain(&mut rng, n as f64);
        // Keep the fastest mode within reach of a fixed-step integration.
        p.cart_mass = p.cart_mass.max(2e-4);
        let exact = solve(&p).expect("valid chains solve");
        let reference = chain_integrator::integrate(&p, chain_integrator::step_for(&p));
        let tol_v = 1e-7 * exact.outcome.vx2.abs().max(p.speed);
        let tol_w = 1e-7 * exact.outcome.omega2.abs().max(p.speed / p.radius);
        let what = format!("case {case} N {n}: {p:?} ({})", exact.phase_summary());
        let dv = (exact.outcome.vx2 - reference.vx2).abs();
        let dw = (exact.outcome.omega2 - reference.omega2).abs();
        assert!(
            dv <= tol_v,
            "{what}: vx2 exact {} numerical {}",
            exact.outcome.vx2,
            reference.vx2
        );
        assert!(
            dw <= tol_w,
            "{what}: omega2 exact {} numerical {}",
            exact.outcome.omega2,
            reference.omega2
        );
        worst = worst.max(dv / tol_v * 1e-7).max(dw / tol_w * 1e-7);
        assert_eq!(exact.phases.len(), reference.phases, "{what}");
        let scale = exact.energy().initial;
        assert!(
            (exact.energy().final_cart - reference.chain_energy).abs() <= 1e-7 * scale,
            "{what}: chain energy {} {}",
            exact.energy().final_cart,
            reference.chain_energy
        );
        assert!(
            (exact.final_state.v - reference.v2).abs()
                <= 1e-7 * p.speed.max(exact.final_state.v.abs()),
            "{what}"
        );
        assert!(
            (exact.final_state.x - reference.x1).abs()
                <= 1e-7 * (p.speed * p.duration).max(exact.final_state.x.abs()),
            "{what}: X_1 {} {}",
            exact.final_state.x,
            reference.x1
        );
        assert!(!reference.stuck, "{what}: no string friction holds nothing");
        if exact
            .phases
            .iter()
            .filter(|ph| ph.kind == PhaseKind::Grip)
            .count()
            >= 2
        {
            multi_grip += 1;
        }
    }
    println!(
        "worst relative disagreement {worst:.2e}; {multi_grip} of {cases} cases gripped twice or more"
    );
    assert!(
        multi_grip >= 5,
        "only {multi_grip} of {cases} cases gripped twice or more"
    );
}

#[test]
fn a_chain_series_is_continuous_and_gripping_holds_zero_slip() {
    let p = Params {
        chain: 8.0,
        cart_mass: 2e-3,
        ..Params::default()
    };
    let b = solve(&p).unwrap();
    assert!(b.phases.len() >= 3, "{}", b.phase_summary());
    let series = b.series(401);
    for pair in series.windows(2) {
        if pair[0].t == pair[1].t {
            let (a, c) = (&pair[0], &pair[1]);
            assert!((a.x - c.x).abs() <= 1e-12 * (a.x.abs() + 1e-9));
            assert!((a.v - c.v).abs() <= 1e-12 * (a.v.abs() + p.speed));
            assert!((a.vx - c.vx).abs() <= 1e-12 * p.speed);
        }
    }
    for s in &series {
        if s.kind == PhaseKind::Grip {
            assert!(
                s.slip.abs() <= 1e-10 * p.speed,
                "slip {} at {}",
                s.slip,
                s.t
            );
        }
        assert!(s.friction.abs() <= p.mu * s.normal * (1.0 + 1e-9) + 1e-9 * p.mu * b.setup.n0);
    }
    assert_eq!(b.sample_at(p.duration).omega, b.outcome.omega2);
}

/// Random chains over the property tests' ranges (the cart from 0.1 g, so that even 16 masses stay
/// resolvable: sqrt(k / (M/N)) 2N T stays below the solver's limit).
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
    );
    (ball, throw, contact, chain).prop_map(|(ball, throw, contact, chain)| {
        let ((mass, radius, alpha), (angle_deg, speed, spin)) = (ball, throw);
        let ((mu, duration, ey), (cart_mass, stiffness, n)) = (contact, chain);
        Params {
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
        }
    })
}

proptest! {
    #![proptest_config(config(300))]

    #[test]
    fn every_chain_bounce_is_physical(p in chains()) {
        let b = solve(&p).expect("valid chains solve");
        let o = &b.outcome;
        for value in [o.omega2, o.vx2, o.vy2, o.speed2(), o.theta2_deg, b.final_state.x, b.final_state.v] {
            prop_assert!(value.is_finite());
        }
        let e = b.energy();
        for value in [e.initial, e.final_ball, e.final_cart, e.friction_loss, e.normal_loss] {
            prop_assert!(value.is_finite() && value >= -1e-12 * e.initial);
        }
        prop_assert!(e.residual.abs() < 1e-10, "residual {}", e.residual);
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
    }
}

#[test]
fn scenario_files_set_the_chain() {
    use snapback::scenario::Scenario;
    let s = Scenario::parse(
        "description = \"chain\"\n[params]\nchain = 4\n",
        "chain.toml",
    )
    .unwrap();
    let p = s.apply(Params::default());
    assert_eq!(p.chain, 4.0);
    assert!(solve(&p).is_ok());
    // Saved and loaded back, the chain survives.
    let again = Scenario::parse(&Scenario::from_params("c", "", &p).to_toml(), "c.toml").unwrap();
    assert_eq!(again.apply(Params::default()), p);
    let err = Scenario::parse("[params]\nchain = 2.5\n", "bad.toml").unwrap_err();
    assert!(
        err.to_string()
            .contains("chain must be in {1, 2, ..., 16}; got 2.5"),
        "{err}"
    );
    // Files written before the chain existed are single carts.
    let old = Scenario::parse("[params]\nangle = 45\n", "old.toml").unwrap();
    assert_eq!(old.apply(Params::default()).chain, 1.0);
}
