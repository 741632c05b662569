//! The model against the paper (Cross 2010): its closed-form limits, Eqs. (7) and (8), the rolling ratio
//! of Fig. 3(a), and the phase timelines of Fig. 3.

use snapback::model::{Params, PhaseKind, solve};

fn heavy() -> Params {
    Params {
        cart_mass: 1e6,
        ..Params::default()
    }
}

/// Eq. (8): omega2 = omega1 + 2 mu v1 sin(theta1) / (alpha r) when the ball slides throughout.
fn eq8(p: &Params) -> f64 {
    p.spin + 2.0 * p.mu * p.speed * p.angle_deg.to_radians().sin() / (p.alpha * p.radius)
}

/// Eq. (7): tan(theta1) = (1 - r omega1 / v_x1) / (2 mu (1 + 1/alpha)), solved for theta1 by bisection
/// (v_x1 = v1 cos theta1 depends on theta1 too).
fn eq7(p: &Params) -> f64 {
    let f = |deg: f64| {
        let th = deg.to_radians();
        th.tan()
            - (1.0 - p.radius * p.spin / (p.speed * th.cos()))
                / (2.0 * p.mu * (1.0 + 1.0 / p.alpha))
    };
    let (mut lo, mut hi) = (1e-6, 89.999);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if f(mid) < 0.0 { lo = mid } else { hi = mid }
    }
    0.5 * (lo + hi)
}

/// The largest angle at which the model's ball slides for the whole contact, by bisection.
fn critical_angle(p: &Params) -> f64 {
    let slides = |deg: f64| {
        solve(&Params {
            angle_deg: deg,
            ..*p
        })
        .unwrap()
        .slides_throughout()
    };
    let (mut lo, mut hi) = (0.5, 89.0);
    assert!(slides(lo) && !slides(hi));
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if slides(mid) { lo = mid } else { hi = mid }
    }
    lo
}

#[test]
fn eq8_coefficient_is_440_8() {
    let p = Params::default();
    let coefficient = 2.0 * p.mu * p.speed / (p.alpha * p.radius);
    assert!((coefficient - 440.8).abs() < 0.05, "{coefficient}");
}

#[test]
fn pure_sliding_follows_eq8_on_a_heavy_cart() {
    for spin in [0.0, -100.0, 50.0] {
        for angle in [2.0, 10.0, 20.0] {
            let p = Params {
                angle_deg: angle,
                spin,
                ..heavy()
            };
            let b = solve(&p).unwrap();
            assert!(
                b.slides_throughout(),
                "{angle} {spin}: {}",
                b.phase_summary()
            );
            assert!(
                (b.outcome.omega2 - eq8(&p)).abs() < 1e-6,
                "{} vs {}",
                b.outcome.omega2,
                eq8(&p)
            );
        }
    }
    // The paper's example: omega1 = 0 at 23.9 degrees gives 178.6 rad/s.
    let p = Params {
        angle_deg: 23.9,
        spin: 0.0,
        ..heavy()
    };
    assert!((solve(&p).unwrap().outcome.omega2 - 178.6).abs() < 0.05);
}

#[test]
fn pure_sliding_does_not_depend_on_the_cart() {
    // At glancing angles the ball slides throughout and the cart cannot change omega2 (Sec. III).
    for (mass, k) in [(10.0, 4e4), (0.01, 4e4), (0.01, 1.5e4)] {
        let p = Params {
            angle_deg: 10.0,
            spin: 0.0,
            cart_mass: mass,
            stiffness: k,
            ..Params::default()
        };
        let b = solve(&p).unwrap();
        assert!(b.slides_throughout());
        assert!((b.outcome.omega2 - eq8(&p)).abs() < 1e-9);
    }
}

#[test]
fn heavy_cart_critical_angle_is_eq7() {
    for spin in [0.0, -100.0] {
        let p = Params { spin, ..heavy() };
        let model = critical_angle(&p);
        let formula = eq7(&p);
        assert!(
            (model - formula).abs() < 0.01,
            "spin {spin}: model {model} vs Eq. (7) {formula}"
        );
    }
    // omega1 = 0: Eq. (7) is the paper's 23.9 degrees.
    assert!(
        (eq7(&Params {
            spin: 0.0,
            ..heavy()
        }) - 23.9)
            .abs()
            < 0.05
    );
}

#[test]
fn soft_spring_slides_to_a_higher_angle() {
    // Sec. III: with omega1 = 0 the soft spring keeps the ball sliding beyond 23.9 degrees (paper: 26.6).
    let soft = critical_angle(&Params {
        spin: 0.0,
        cart_mass: 0.01,
        stiffness: 1.5e4,
        ..Params::default()
    });
    let rigid = eq7(&Params {
        spin: 0.0,
        ..heavy()
    });
    assert!(soft > rigid + 1.0, "soft {soft} rigid {rigid}");
}

#[test]
fn heavy_cart_ends_rolling_with_conserved_angular_momentum() {
    // Angular momentum about the contact point is conserved on a rigid surface; once the ball grips it
    // rolls: v_x2 = r omega2 = (v_x1 + alpha r omega1) / (1 + alpha).
    let p = heavy();
    let b = solve(&p).unwrap();
    let vx1 = p.speed * p.angle_deg.to_radians().cos();
    let rolling = (vx1 + p.alpha * p.radius * p.spin) / (1.0 + p.alpha);
    assert!(
        (b.outcome.vx2 - rolling).abs() < 1e-6,
        "{} vs {rolling}",
        b.outcome.vx2
    );
    assert!((b.outcome.roll_ratio.unwrap() - 1.0).abs() < 1e-6);
    assert!(b.outcome.ex.unwrap().abs() < 1e-6);
}

#[test]
fn normal_incidence_on_a_heavy_cart_gives_no_spin() {
    let b = solve(&Params {
        angle_deg: 90.0,
        spin: 0.0,
        ..heavy()
    })
    .unwrap();
    assert_eq!(b.outcome.omega2, 0.0);
    assert_eq!(b.outcome.vx2, 0.0);
    assert_eq!(b.outcome.theta2_deg, 90.0);
}

#[test]
fn fig3a_heavy_cart() {
    // 10 kg cart, k = 4e4 N/m: slides for 2.25 ms, then grips; bounces with r omega2 / v_x2 = 0.992.
    let p = Params {
        cart_mass: 10.0,
        stiffness: 4e4,
        ..Params::default()
    };
    let b = solve(&p).unwrap();
    assert_eq!(b.phases[0].kind, PhaseKind::Slide);
    assert_eq!(b.phases[1].kind, PhaseKind::Grip);
    let grip = b.phases[1].start * 1e3;
    assert!((grip - 2.25).abs() < 0.01, "grip at {grip} ms");
    let ratio = b.outcome.roll_ratio.unwrap();
    assert!((ratio - 0.992).abs() < 0.0005, "{ratio}");
    // The grip lasts to the end of the contact (up to a last slide shorter than a microsecond).
    assert!(b.phases[1].end > p.duration - 1e-6);
}

#[test]
fn fig3b_light_cart() {
    // 10 g cart, k = 4e4 N/m: grips at about 1.7 ms, the cart peaks at 4.4 mm near 2.3 ms, slides again near the end.
    let b = solve(&Params {
        stiffness: 4e4,
        ..Params::default()
    })
    .unwrap();
    assert_eq!(b.phase_summary(), "slide-grip-slide");
    assert!((b.phases[1].start * 1e3 - 1.7).abs() < 0.05);
    let series = b.series(5001);
    let peak = series.iter().max_by(|a, b| a.x.total_cmp(&b.x)).unwrap();
    assert!((peak.x * 1e3 - 4.4).abs() < 0.1, "{}", peak.x);
    assert!((peak.t * 1e3 - 2.3).abs() < 0.05, "{}", peak.t);
    // At the grip the friction force drops (paper: from 109 N to 90 N).
    let at_grip: Vec<_> = series.iter().filter(|s| s.t == b.phases[1].start).collect();
    assert_eq!(at_grip.len(), 2);
    assert!(at_grip[0].friction > at_grip[1].friction);
}

#[test]
fn fig3c_soft_spring() {
    // 10 g cart, k = 1.5e4 N/m: grips at 1.32-1.34 ms, X peaks at 7.7 mm at 3.1 ms, omega2 near 162.8.
    let b = solve(&Params::default()).unwrap();
    assert_eq!(b.phase_summary(), "slide-grip-slide");
    let grip = b.phases[1].start * 1e3;
    assert!((1.32..1.34).contains(&grip), "{grip}");
    let series = b.series(5001);
    let peak = series.iter().max_by(|a, b| a.x.total_cmp(&b.x)).unwrap();
    assert!((peak.x * 1e3 - 7.7).abs() < 0.05);
    assert!((peak.t * 1e3 - 3.1).abs() < 0.05);
    let fastest = series.iter().max_by(|a, b| a.v.total_cmp(&b.v)).unwrap();
    assert!(
        (fastest.t - b.phases[1].start).abs() < 1e-9,
        "cart fastest at the grip"
    );
    // The exact model gives 160.8 rad/s, 1.2 % below the paper's printed 162.8.
    assert!(
        (b.outcome.omega2 - 162.8).abs() / 162.8 < 0.015,
        "{}",
        b.outcome.omega2
    );
}

#[test]
fn light_carts_add_spin() {
    // Sec. III: lighter carts give more spin than the 10 g cart (the paper's 216 and 223 rad/s are at
    // the spring stiffness that maximises spin).
    let best = |mass: f64| {
        (0..200)
            .map(|i| 300.0 * 1.04f64.powi(i))
            .filter_map(|k| {
                solve(&Params {
                    cart_mass: mass,
                    stiffness: k,
                    ..Params::default()
                })
                .ok()
            })
            .map(|b| b.outcome.omega2)
            .fold(f64::MIN, f64::max)
    };
    let (ten, one, tenth) = (best(0.01), best(1e-3), best(1e-4));
    assert!(ten < one && one < tenth, "{ten} {one} {tenth}");
}

#[test]
fn phases_tile_the_contact() {
    for p in [
        Params::default(),
        Params {
            cart_mass: 1e-5,
            stiffness: 4e4,
            ..Params::default()
        },
    ] {
        let b = solve(&p).unwrap();
        assert_eq!(b.phases.first().unwrap().start, 0.0);
        assert_eq!(b.phases.last().unwrap().end, p.duration);
        for pair in b.phases.windows(2) {
            assert_eq!(pair[0].end, pair[1].start);
            assert_ne!(pair[0].kind, pair[1].kind, "{}", b.phase_summary());
        }
    }
}
