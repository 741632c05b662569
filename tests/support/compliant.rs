//! Random compliant-ball bounces, shared by the compliant ball's tests on the cart and on a chain.

use proptest::prelude::*;
use proptest::test_runner::TestCaseError;
use snapback::model::{Bounce, Params, PhaseKind, SolveError, solve};

use super::prop::log_range;
use super::rng::Rng;

/// The tangential speed scale |v_x1| + r |omega1| (at least a hundredth of the speed).
pub fn incoming(p: &Params) -> f64 {
    let vx1 = p.speed * (90.0 - p.angle_deg).to_radians().sin();
    (vx1.abs() + p.radius * p.spin.abs()).max(0.01 * p.speed)
}

/// Random bounces with a moderately stiff ball (its contact mode at most about 35 radians per contact
/// times a few) on `chain` masses; 10 % of the carts are free (k = 0).
pub fn random_compliant(rng: &mut Rng, chain: usize) -> Params {
    Params {
        angle_deg: rng.uniform(5.0, 90.0),
        speed: rng.uniform(2.0, 30.0),
        spin: rng.uniform(-300.0, 300.0),
        mu: rng.uniform(0.1, 0.8),
        duration: rng.uniform(2e-3, 8e-3),
        ey: rng.uniform(0.3, 1.0),
        mass: rng.uniform(0.04, 0.2),
        radius: rng.uniform(0.02, 0.05),
        alpha: rng.uniform(0.4, 0.67),
        cart_mass: rng.log_uniform(3e-3, 1.0),
        stiffness: if rng.unit() < 0.1 {
            0.0
        } else {
            rng.log_uniform(1e3, 1e5)
        },
        cart_friction: 0.0,
        chain: chain as f64,
        ball_stiffness: rng.log_uniform(1e4, 1e6),
        ball_damping: if rng.unit() < 0.2 {
            0.0
        } else {
            rng.uniform(0.05, 1.5)
        },
        ..Params::default()
    }
}

/// Random valid compliant balls over the property tests' ranges, with the cart's (mass, stiffness, number
/// of masses) drawn from `cart`.
pub fn compliant_strategy(
    cart: impl Strategy<Value = (f64, f64, usize)>,
) -> impl Strategy<Value = Params> {
    let ball = (0.01f64..0.5, 0.01f64..0.1, 0.3f64..0.8);
    let throw = (
        prop_oneof![1.0f64..=90.0, Just(90.0)],
        0.5f64..50.0,
        -500.0f64..500.0,
    );
    let contact = (0.0f64..1.2, 1e-3f64..20e-3, 0.0f64..=1.0);
    let compliance = (
        log_range(1e3, 1e8),
        prop_oneof![Just(0.0), Just(1.0), 0.0f64..3.0, log_range(1e-12, 1e-2)],
    );
    (ball, throw, contact, cart, compliance).prop_map(
        |(
            (mass, radius, alpha),
            (angle_deg, speed, spin),
            (mu, duration, ey),
            (cart_mass, stiffness, n),
            (kb, zeta),
        )| Params {
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
            ball_stiffness: kb,
            ball_damping: zeta,
            ..Params::default()
        },
    )
}

/// The bounce of `p`, or `None` for a refusal a compliant ball may meet: an undamped (or nearly) stiff
/// ball that chatters past the phase cap or the work budget, or a motion too fast to resolve (checked to
/// be beyond the limit). Any other refusal fails the test.
pub fn solved_or_refused(p: &Params) -> Result<Option<Bounce>, TestCaseError> {
    match solve(p) {
        Ok(b) => Ok(Some(b)),
        Err(SolveError::TooManyPhases { .. } | SolveError::Stalled { .. })
            if p.ball_damping < 0.1 =>
        {
            Ok(None)
        }
        Err(SolveError::BallTooFast { radians, .. } | SolveError::TooFast { radians }) => {
            prop_assert!(radians > snapback::model::error::MAX_RADIANS);
            Ok(None)
        }
        Err(e) => panic!("{e}"),
    }
}

/// What every compliant bounce on the cart must show: a finite outcome, no negative energy term, the
/// energy balanced, phases tiling [0, T], |F| <= mu N along the contact, and no patch slip while it grips.
#[allow(dead_code)] // the chain's tests run checks of their own
pub fn check_basics(p: &Params, b: &Bounce) -> Result<(), TestCaseError> {
    let o = &b.outcome;
    for value in [
        o.omega2,
        o.vx2,
        o.vy2,
        o.speed2(),
        o.theta2_deg,
        b.final_state.x,
        b.final_state.v,
    ] {
        prop_assert!(value.is_finite());
    }
    let e = b.energy();
    for value in [
        e.final_ball,
        e.final_cart,
        e.ball_spring,
        e.dashpot_loss,
        e.cart_friction_loss,
    ] {
        prop_assert!(value.is_finite() && value >= -1e-12 * e.initial);
    }
    prop_assert!(e.friction_loss >= -1e-9 * e.initial, "{e:?}");
    prop_assert!(e.residual.abs() < 1e-10, "residual {e:?}");
    prop_assert_eq!(b.phases[0].start, 0.0);
    prop_assert_eq!(b.phases.last().unwrap().end, p.duration);
    for pair in b.phases.windows(2) {
        prop_assert_eq!(pair[0].end, pair[1].start);
    }
    let n_peak = b.setup.n0;
    for s in &b.series(200) {
        prop_assert!(
            s.friction.abs() <= p.mu * s.normal + 1e-8 * p.mu * n_peak + 1e-12,
            "|F| = {} > mu N = {} at t = {}",
            s.friction.abs(),
            p.mu * s.normal,
            s.t
        );
        if s.kind == PhaseKind::Grip {
            prop_assert!(
                s.patch_slip == 0.0,
                "patch slip {} in a grip at {}",
                s.patch_slip,
                s.t
            );
        }
    }
    Ok(())
}

/// mu N0, the largest sliding friction of a bounce: the scale the string friction is drawn on.
#[allow(dead_code)] // only the string-friction tests draw it
pub fn peak_friction(p: &Params) -> f64 {
    p.mu * (1.0 + p.ey) * std::f64::consts::PI * p.mass * p.speed * p.angle_deg.to_radians().sin()
        / (2.0 * p.duration)
}
