//! The strings on a frame that recoils (issue 23, "The physics"): the free frame against an independent
//! numerical integration, the apparent restitution against its formula, the heavy frame against the
//! clamped one, momentum along the surface, the energy budget, and property tests over random frames.

use proptest::prelude::*;

use crate::support::energy::assert_nothing_created;
use crate::support::frame_integrator::integrate_frame;
use crate::support::prop::within_the_cone;
use crate::support::rng::Rng;
use snapback::model::params::spec;
use snapback::model::setup::apparent_restitution;
use snapback::model::{Bounce, FrameKind, ParamId, Params, PhaseKind, SolveError, solve};

pub(crate) fn random_frame(rng: &mut Rng) -> Params {
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
        // Light carts on stiff springs grip and slide again; heavier ones grip once.
        cart_mass: if rng.unit() < 0.5 {
            rng.log_uniform(1e-5, 2e-3)
        } else {
            rng.log_uniform(2e-3, 0.1)
        },
        stiffness: rng.log_uniform(1e3, 1e5),
        frame_mass: rng.log_uniform(0.05, 10.0),
        frame_normal_mass: if rng.unit() < 0.5 {
            0.0
        } else {
            rng.log_uniform(0.1, 10.0)
        },
        ..Params::default()
    }
}

/// Step of the reference integration: small against the contact time and the fastest swing.
pub(crate) fn step_for(p: &Params) -> f64 {
    let reduced = p.cart_mass * p.frame_mass / (p.cart_mass + p.frame_mass);
    let fastest = (std::f64::consts::PI / p.duration).max((p.stiffness / reduced).sqrt());
    (p.duration / 40_000.0).min(0.002 / fastest)
}

/// |a - b| within `rel` of the larger of |a| and `scale`.
pub(crate) fn close(a: f64, b: f64, rel: f64, scale: f64) -> bool {
    (a - b).abs() <= rel * a.abs().max(scale)
}

#[test]
fn the_free_frame_agrees_with_an_independent_integration() {
    let mut rng = Rng(0xf4a3_e5ee_d0c7_2310);
    let mut regrips = 0;
    for case in 0..60 {
        let p = random_frame(&mut rng);
        let exact = solve(&p).expect("a free frame solves");
        let reference = integrate_frame(&p, step_for(&p));
        let o = &exact.outcome;
        let speeds = p.speed;
        let tol = 1e-9;
        let summary = exact.phase_summary();
        assert!(
            close(o.vx2, reference.vx2, tol, speeds),
            "case {case} vx2 {} vs {} ({p:?}, {summary})",
            o.vx2,
            reference.vx2
        );
        assert!(
            close(o.omega2, reference.omega2, tol, speeds / p.radius),
            "case {case} omega2 {} vs {} ({p:?}, {summary})",
            o.omega2,
            reference.omega2
        );
        assert!(
            close(exact.final_state.v, reference.v2, tol, speeds),
            "case {case} V {} vs {}",
            exact.final_state.v,
            reference.v2
        );
        assert!(
            close(exact.frame_velocity(), reference.vf2, tol, speeds),
            "case {case} V_f {} vs {}",
            exact.frame_velocity(),
            reference.vf2
        );
        assert_eq!(
            exact.phases.len(),
            reference.phases,
            "case {case}: {summary}"
        );
        if exact
            .phases
            .iter()
            .filter(|ph| ph.kind == PhaseKind::Grip)
            .count()
            >= 2
        {
            regrips += 1;
        }
    }
    assert!(regrips >= 3, "only {regrips} cases gripped twice or more");
}

#[test]
fn the_apparent_restitution_follows_its_formula() {
    // The typical racquet of issue 23: M_n about 181 g, e_y = 0.85 gives e_A about 0.41.
    let p = Params {
        ey: 0.85,
        frame_mass: 0.32,
        frame_normal_mass: 0.181,
        ..Params::default()
    };
    let b = solve(&p).unwrap();
    let e_a = (0.85 * 0.181 - 0.057) / (0.181 + 0.057);
    assert_eq!(b.setup.ey_apparent, e_a);
    assert!((e_a - 0.41).abs() < 0.01, "{e_a}");
    assert_eq!(b.outcome.vy2, e_a * b.setup.vy1);
    // M_n defaults to M_t, and a normal mass alone (a clamped frame along the surface) changes only the
    // normal impulse.
    let same = solve(&Params {
        frame_normal_mass: 0.0,
        ..p
    })
    .unwrap();
    assert_eq!(
        same.setup.ey_apparent,
        apparent_restitution(0.85, 0.057, 0.32)
    );
    let normal_only = solve(&Params {
        frame_mass: 0.0,
        ..p
    })
    .unwrap();
    assert_eq!(normal_only.setup.ey_apparent, e_a);
    assert_eq!(normal_only.params.model().frame, FrameKind::Clamped);
    assert_eq!(normal_only.frame_velocity(), 0.0);
    // The normal impulse m (1 + e_A) v_y1 = 2 N0 T / pi.
    let impulse = 2.0 * b.setup.n0 * p.duration / std::f64::consts::PI;
    assert!((impulse - p.mass * (1.0 + e_a) * b.setup.vy1).abs() < 1e-12 * impulse);
}

#[test]
fn a_clamped_frame_is_the_wall_bit_for_bit() {
    let base = Params::default();
    let clamped = Params {
        frame_mass: spec(ParamId::FrameMass).parse("clamped").unwrap(),
        ..base
    };
    assert_eq!(clamped.frame_mass, 0.0);
    let (a, b) = (solve(&base).unwrap(), solve(&clamped).unwrap());
    assert_eq!(a.outcome, b.outcome);
    assert_eq!(a.energy(), b.energy());
    assert_eq!(b.energy().frame, 0.0);
}

#[test]
fn a_heavy_frame_approaches_the_clamped_one() {
    let mut rng = Rng(0x4ea5_f4a3_0000_0001);
    for _ in 0..20 {
        let p = random_frame(&mut rng);
        let heavy = Params {
            frame_mass: 1e6,
            frame_normal_mass: 0.0,
            ..p
        };
        let clamped = Params {
            frame_mass: 0.0,
            frame_normal_mass: 0.0,
            ..p
        };
        let (h, c) = (solve(&heavy).unwrap(), solve(&clamped).unwrap());
        // The frame's effect scales as m/M_t = 1e-7 or less.
        assert!(close(h.outcome.vx2, c.outcome.vx2, 1e-5, p.speed), "{p:?}");
        assert!(close(
            h.outcome.omega2,
            c.outcome.omega2,
            1e-5,
            p.speed / p.radius
        ));
        assert!(close(h.outcome.vy2, c.outcome.vy2, 1e-5, p.speed));
        assert!(h.frame_velocity().abs() < 1e-5 * p.speed);
    }
}

/// The momentum along the surface of ball, cart and frame at the start, middle and end of every phase of
/// `b` (the bounce of `p` on the single cart), against its value at first contact, to 1e-11.
pub(crate) fn assert_momentum_conserved(p: &Params, b: &Bounce) {
    let total = |vx: f64, v: f64, vf: f64| p.mass * vx + p.cart_mass * v + p.frame_mass * vf;
    let before = total(b.setup.vx1, 0.0, 0.0);
    let scale = p.mass * p.speed;
    for (index, phase) in b.phases.iter().enumerate() {
        for t in [phase.start, 0.5 * (phase.start + phase.end), phase.end] {
            let s = b.sample_in(index, t);
            let vf = phase.motion().frame_velocity(&b.setup, t);
            // A grip carries the ball's m_eff on the cart: the ball's own momentum is m v_x all the same.
            let now = total(s.vx, s.v, vf);
            assert!(
                (now - before).abs() <= 1e-11 * scale,
                "{now} vs {before} at {t} ({p:?}, {})",
                b.phase_summary()
            );
        }
    }
}

#[test]
fn momentum_along_the_surface_is_conserved() {
    let mut rng = Rng(0x30e5_7a11_0000_0002);
    for _ in 0..40 {
        let p = random_frame(&mut rng);
        assert_momentum_conserved(&p, &solve(&p).unwrap());
    }
}

#[test]
fn the_energy_budget_balances_and_nothing_is_created() {
    let mut rng = Rng(0xe4e5_9100_0000_0003);
    for _ in 0..40 {
        let p = random_frame(&mut rng);
        let b = solve(&p).unwrap();
        let e = b.energy();
        assert_nothing_created(&e, &format!("{p:?}"));
        assert!(e.frame > 0.0, "{e:?}");
    }
}

#[test]
fn what_a_free_frame_does_not_solve_is_refused_by_name() {
    for (params, flag) in [
        (
            Params {
                frame_mass: 0.3,
                cart_friction: 5.0,
                ball_stiffness: 1e5,
                stiffness: 0.0,
                chain: 3.0,
                ..Params::default()
            },
            "--stiffness 0",
        ),
        (
            Params {
                frame_mass: 0.3,
                cart_friction: 5.0,
                ball_stiffness: 1e5,
                stiffness: 0.0,
                ..Params::default()
            },
            "--stiffness 0",
        ),
        (
            Params {
                frame_mass: 0.3,
                cart_friction: 5.0,
                stiffness: 0.0,
                ..Params::default()
            },
            "--stiffness 0",
        ),
    ] {
        let err = solve(&params).unwrap_err();
        assert!(matches!(err, SolveError::FreeFrame { .. }), "{err:?}");
        assert!(err.to_string().contains(flag), "{err}");
    }
}

/// Without a spring the frame is not tied to the cart: along the surface the bounce is the clamped free
/// cart's, and the frame only lowers the normal impulse (e_A for e_y).
#[test]
fn a_frame_without_a_spring_is_the_free_cart_with_the_apparent_restitution() {
    let framed = Params {
        frame_mass: 0.188,
        stiffness: 0.0,
        ..Params::default()
    };
    let b = solve(&framed).unwrap();
    let clamped = solve(&Params {
        frame_mass: 0.0,
        ey: b.setup.ey_apparent,
        ..framed
    })
    .unwrap();
    assert!(b.setup.ey_apparent < framed.ey);
    assert_eq!(b.phase_summary(), clamped.phase_summary());
    for (x, y) in [
        (b.outcome.omega2, clamped.outcome.omega2),
        (b.outcome.vx2, clamped.outcome.vx2),
        (b.outcome.vy2, clamped.outcome.vy2),
    ] {
        assert!((x - y).abs() <= 1e-12 * y.abs().max(1.0), "{x} against {y}");
    }
    assert!(b.frame_velocity().abs() <= 1e-12, "{}", b.frame_velocity());
}

proptest! {
    #![proptest_config(crate::support::prop::config(200))]

    #[test]
    fn random_frames_solve_finite_balanced_and_held_in_grips(
        seed in any::<u64>(),
    ) {
        let mut rng = Rng(seed | 1);
        let p = random_frame(&mut rng);
        let b = solve(&p).unwrap();
        let e = b.energy();
        prop_assert!(b.outcome.vx2.is_finite() && b.outcome.omega2.is_finite());
        prop_assert!(b.frame_velocity().is_finite());
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
