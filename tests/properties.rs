//! Property tests over random valid parameters: the solver never panics, its results are finite, energy
//! balances, friction never exceeds mu N, the slip is zero while the ball grips, and the state is
//! continuous across every transition.

use proptest::prelude::*;
use snapback::model::{Params, PhaseKind, solve};

fn log_range(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (lo.ln()..=hi.ln()).prop_map(f64::exp)
}

fn params() -> impl Strategy<Value = Params> {
    let ball = (0.005f64..0.5, 0.005f64..0.12, 0.2f64..1.0);
    let throw = (
        prop_oneof![0.5f64..=90.0, Just(90.0)],
        0.5f64..50.0,
        -500.0f64..500.0,
    );
    let contact = (0.0f64..1.2, 0.5e-3f64..20e-3, 0.0f64..=1.0);
    let cart = (
        log_range(1e-5, 1e6),
        prop_oneof![Just(0.0), log_range(1.0, 1e6)],
    );
    (ball, throw, contact, cart).prop_map(
        |(
            (mass, radius, alpha),
            (angle_deg, speed, spin),
            (mu, duration, ey),
            (cart_mass, stiffness),
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
        },
    )
}

/// 400 cases by default; `PROPTEST_CASES=100000` searches deeper.
fn config() -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(400);
    ProptestConfig::with_cases(cases)
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn every_valid_bounce_is_physical(p in params()) {
        let b = solve(&p).expect("valid parameters solve");
        let o = &b.outcome;
        for value in [o.omega2, o.vx2, o.vy2, o.speed2, o.theta2_deg, b.final_state.x, b.final_state.v] {
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
            // |F| <= mu N, up to rounding.
            prop_assert!(
                s.friction.abs() <= p.mu * s.normal + 1e-9 * p.mu * n_peak + 1e-12,
                "|F| = {} > mu N = {} at t = {}", s.friction.abs(), p.mu * s.normal, s.t
            );
            if s.kind == PhaseKind::Grip {
                prop_assert!(s.slip.abs() <= 1e-9 * speed_scale, "slip {} in grip at {}", s.slip, s.t);
            }
        }
        // Both sides of each transition: the state is continuous (only F may jump).
        for pair in series.windows(2) {
            if pair[0].t == pair[1].t {
                let (a, c) = (&pair[0], &pair[1]);
                prop_assert!((a.x - c.x).abs() <= 1e-12 * (a.x.abs() + 1e-9));
                prop_assert!((a.v - c.v).abs() <= 1e-12 * (a.v.abs() + speed_scale));
                prop_assert!((a.vx - c.vx).abs() <= 1e-12 * speed_scale);
                prop_assert!((a.omega - c.omega).abs() <= 1e-12 * speed_scale / p.radius);
                prop_assert!(a.phase + 1 == c.phase);
            }
        }
    }

    #[test]
    fn transitions_are_located_to_a_picosecond(p in params()) {
        // At a slide's end the slip is zero; at a grip's end |F_s| = mu N. The time error of a
        // transition is the event function's value there over its rate.
        let b = solve(&p).unwrap();
        let speed_scale = p.speed + p.radius * p.spin.abs();
        for (index, before) in b.phases.iter().enumerate().take(b.phases.len() - 1) {
            let t = before.end;
            let left = b.sample_in(index, t);
            // Where the rate itself vanishes (a grazing transition) time is not the right measure, so
            // the value may also sit at the rounding floor of its terms.
            let (error, rate, floor) = match before.kind {
                PhaseKind::Slide => {
                    // d(slip)/dt from the equations of motion, Eqs. (1)-(3).
                    let f = before.slip_sign as f64 * p.mu * left.normal;
                    let m_eff = p.mass * p.alpha / (1.0 + p.alpha);
                    let rate = -f / m_eff - (f - p.stiffness * left.x) / p.cart_mass;
                    (left.slip.abs(), rate.abs(), 1e-11 * (speed_scale + left.v.abs()))
                }
                PhaseKind::Grip => {
                    let gain = b.setup.grip_gain;
                    let n0w = b.setup.n0 * b.setup.w;
                    let margin = (gain * left.x).abs() - p.mu * left.normal;
                    let rate = gain * left.v * left.x.signum() - p.mu * n0w * (b.setup.w * t).cos();
                    (margin.abs(), rate.abs(), 1e-11 * p.mu * b.setup.n0)
                }
            };
            prop_assert!(error <= 1e-12 * rate + floor, "{:?} ending at {t}: value {error} rate {rate}", before.kind);
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
