//! Property tests over random valid parameters: the solver never panics, its results are finite, energy
//! balances, friction never exceeds mu N, the slip is zero while the ball grips, and the state is
//! continuous across every transition.

use proptest::prelude::*;
use snapback::model::{Cart, Params, PhaseKind, solve};

use crate::support::prop;
use crate::support::prop::within_the_cone;
use prop::{check_cart_motion, config, log_range};

fn params() -> impl Strategy<Value = Params> {
    let ball = (0.005f64..0.5, 0.005f64..0.12, 0.2f64..1.0);
    let throw = (
        prop_oneof![0.5f64..=90.0, Just(90.0)],
        0.5f64..50.0,
        -500.0f64..500.0,
    );
    let contact = (0.0f64..1.2, 0.5e-3f64..20e-3, 0.0f64..=1.0);
    // String friction: none in half the cases, else up to about twice the largest sliding friction.
    let string = prop_oneof![Just(0.0), 0.0f64..2.0];
    let cart = (
        log_range(1e-5, 1e6),
        prop_oneof![Just(0.0), log_range(1.0, 1e6)],
        string,
    );
    (ball, throw, contact, cart).prop_map(|(ball, throw, contact, cart)| {
        let ((mass, radius, alpha), (angle_deg, speed, spin)) = (ball, throw);
        let ((mu, duration, ey), (cart_mass, stiffness, string)) = (contact, cart);
        let peak_friction =
            mu * (1.0 + ey) * std::f64::consts::PI * mass * speed * angle_deg.to_radians().sin()
                / (2.0 * duration);
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
            cart_friction: string * peak_friction,
            chain: 1.0,
            ball_stiffness: 0.0,
            ball_damping: 0.0,
            ..Params::default()
        }
    })
}

proptest! {
    #![proptest_config(config(400))]

    #[test]
    fn every_valid_bounce_is_physical(p in params()) {
        let b = solve(&p).expect("valid parameters solve");
        let o = &b.outcome;
        for value in [o.omega2, o.vx2, o.vy2, o.speed2(), o.theta2_deg, b.final_state.x, b.final_state.v] {
            prop_assert!(value.is_finite());
        }
        prop_assert!(o.ex.is_none_or(f64::is_finite));
        let e = &b.energy();
        for value in [e.initial, e.final_ball, e.final_cart, e.friction_loss, e.normal_loss] {
            prop_assert!(value.is_finite() && value >= -1e-12 * e.initial);
        }
        prop_assert!(e.residual.abs() < 1e-10, "residual {}", e.residual);

        // The phases tile [0, T].
        prop_assert_eq!(b.phases[0].start, 0.0);
        prop_assert_eq!(b.phases.last().unwrap().end, p.duration);
        for pair in b.phases.windows(2) {
            prop_assert_eq!(pair[0].end, pair[1].start);
        }

        let n_peak = b.setup.n0;
        let speed_scale = p.speed + p.radius * p.spin.abs();
        let series = b.series(300);
        for s in &series {
            within_the_cone(&p, s, n_peak)?;
            if s.kind == PhaseKind::Grip {
                prop_assert!(s.slip.abs() <= 1e-9 * speed_scale, "slip {} in grip at {}", s.slip, s.t);
            }
        }
        check_cart_motion(&p, &b)?;
        // Both sides of each transition: the state is continuous (only F may jump), to rounding of the
        // closed forms' terms. A transition's state is the search's last probe's, whose angles may be
        // turned from the probe before it (an ulp from fresh ones), and early in a slide the cart's
        // x = A (sin w tau - (w/Omega) sin Omega tau) cancels: x is held to 1e-12 of the cart's largest
        // excursion in the bounce, not of itself.
        let x_scale = series.iter().map(|s| s.x.abs()).fold(1e-9, f64::max);
        for pair in series.windows(2) {
            if pair[0].t == pair[1].t {
                let (a, c) = (&pair[0], &pair[1]);
                prop_assert!((a.x - c.x).abs() <= 1e-12 * (a.x.abs() + x_scale));
                prop_assert!((a.v - c.v).abs() <= 1e-12 * (a.v.abs() + speed_scale));
                prop_assert!((a.vx - c.vx).abs() <= 1e-12 * speed_scale);
                prop_assert!((a.omega - c.omega).abs() <= 1e-12 * speed_scale / p.radius);
                prop_assert!(a.phase + 1 == c.phase);
            }
        }
    }

    #[test]
    fn transitions_are_located_to_a_picosecond(p in params()) {
        // Each phase ends on one of its events: a slide when the slip is zero, a grip when |F_s| = mu N,
        // a moving cart when it stops, a stuck cart when the push on it reaches F_c. The time error of
        // the event is its function's value there over its rate; where the rate vanishes (a grazing
        // transition) the value may instead sit at the rounding floor of its terms.
        let b = solve(&p).unwrap();
        let speed_scale = p.speed + p.radius * p.spin.abs();
        let m_eff = p.mass * p.alpha / (1.0 + p.alpha);
        let (n0, w) = (b.setup.n0, b.setup.w);
        for (index, phase) in b.phases.iter().enumerate().take(b.phases.len() - 1) {
            let t = phase.end;
            let s = b.sample_in(index, t);
            let string = match phase.cart {
                Cart::Moving(dir) => f64::from(dir) * p.cart_friction,
                Cart::Stuck => 0.0,
            };
            let cart_accel = match (phase.kind, phase.cart) {
                (_, Cart::Stuck) => 0.0,
                (PhaseKind::Slide, _) => (s.friction - p.stiffness * s.x - string) / p.cart_mass,
                (PhaseKind::Grip, _) => -(p.stiffness * s.x + string) / (p.cart_mass + m_eff),
            };
            let friction_rate = match phase.kind {
                PhaseKind::Slide => f64::from(phase.slip_sign) * p.mu * n0 * w * (w * t).cos(),
                PhaseKind::Grip => b.setup.grip_gain * s.v,
            };
            let force_floor = 1e-11 * (p.mu * n0 + p.stiffness * s.x.abs() + p.cart_friction);
            let speed_floor = 1e-11 * (speed_scale + s.v.abs());
            // (value, rate, floor) of each event that can end this phase.
            let mut events = vec![];
            match phase.kind {
                PhaseKind::Slide => events.push((s.slip, -s.friction / m_eff - cart_accel, speed_floor)),
                PhaseKind::Grip => {
                    let limit_rate = p.mu * n0 * w * (w * t).cos();
                    let sign = s.friction.signum();
                    events.push((s.friction.abs() - p.mu * s.normal, sign * friction_rate - limit_rate, force_floor));
                }
            }
            match phase.cart {
                Cart::Moving(_) if p.cart_friction > 0.0 => events.push((s.v, cart_accel, speed_floor)),
                Cart::Moving(_) => {}
                Cart::Stuck => {
                    let push = s.friction - p.stiffness * s.x;
                    events.push((push.abs() - p.cart_friction, push.signum() * friction_rate, force_floor));
                }
            }
            let located = events
                .iter()
                .any(|&(value, rate, floor)| value.abs() <= 1e-12 * rate.abs() + floor);
            prop_assert!(located, "{:?}/{:?} ending at {t}: events {events:?}", phase.kind, phase.cart);
        }
    }

    #[test]
    fn a_rolling_ball_stays_rolling(p in params()) {
        // Arriving with zero slip, the ball grips at once; the cart never moves and nothing changes.
        let vx1 = p.speed * (90.0 - p.angle_deg).to_radians().sin();
        let p = Params { spin: vx1 / p.radius, ..p };
        let b = solve(&p).unwrap();
        prop_assert_eq!(b.phase_summary(), "grip");
        prop_assert!(b.outcome.ex.is_none());
        prop_assert!((b.outcome.omega2 - p.spin).abs() <= 1e-12 * p.spin.abs().max(1.0));
        prop_assert_eq!(b.final_state.x, 0.0);
    }
}
