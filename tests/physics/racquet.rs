//! The racquet in the hand (issue 23 items 2-4): its effective masses and apparent restitution against
//! their formulas, the clamped racquet as the shot was before it, and the command line.

use crate::support::bin;
use crate::support::flight as reference;
use crate::support::frame_integrator::integrate_frame;
use crate::support::rng::Rng;

use snapback::config;
use snapback::model::Params;
use snapback::shot::racquet::{Hold, Racquet};
use snapback::shot::{self, play};

const RPM: f64 = std::f64::consts::PI / 30.0;

/// A stroke as the four shot presets were written before the racquet was held (e_y = 0.45 standing in
/// for a hand-held racquet), struck by a clamped racquet.
fn clamped_stroke(height: f64, ball: (f64, f64, f64), swing: (f64, f64, f64)) -> Params {
    Params {
        ey: 0.45,
        height,
        ball_speed: ball.0,
        ball_descent_deg: ball.1,
        ball_topspin: ball.2 * RPM,
        racquet_speed: swing.0,
        swing_path_deg: swing.1,
        face_angle_deg: swing.2,
        racquet_mass: 0.0,
        ..Params::default()
    }
}

#[test]
fn a_clamped_racquet_plays_the_shots_of_before_bit_for_bit() {
    // `snapback shot --preset NAME` before the racquet was held: launch vx, vy (m/s), topspin (rpm),
    // landing x, kick height and net clearance (m), as that build printed them (updated when the event
    // search began to predict crossings by Newton: they moved by at most 3e-15 relative; and when the
    // single cart's crossings were refined by the cubic Taylor model: at most 1.1e-14 relative, the net
    // clearance's 1.1e-15 m; and when the single cart's slide watched its slip through sums of sines:
    // at most 6.6e-15 relative, the net clearance's 6.7e-16 m; and when the grip's margins were
    // summed likewise: at most 2.6e-15 relative, the net clearance's 1.8e-15 m; and when the single
    // cart's searches by sums began refining from the crossing predicted from both ends: one shot of
    // four moved, at most 2.1e-15 relative; and when the cubic model's step became its series in
    // Newton's step: two shots moved, at most 3.6e-15 relative, the net clearance's 9e-16 m; and when
    // that series was kept to steps near the root: one of them went back, the other moved by at most
    // 2.5e-15 relative).
    let cases = [
        (
            clamped_stroke(1.0, (20.0, 10.0, 1000.0), (20.0, 25.0, 0.0)),
            [
                35.14619560117272,
                5.577513608145125,
                3761.7460416212953,
                20.203691856811396,
                0.7065527001926373,
                0.6559485105057122,
            ],
        ),
        (
            clamped_stroke(1.0, (20.0, 10.0, 1000.0), (22.0, 8.0, -1.0)),
            [
                40.50437837951824,
                3.0487449625895953,
                1877.9796588389875,
                19.06801623302998,
                0.5562782631279309,
                0.10098003066851502,
            ],
        ),
        (
            clamped_stroke(1.0, (20.0, 10.0, 1000.0), (15.0, -25.0, -12.0)),
            [
                26.413017787452794,
                2.5443966507294338,
                -2947.0934937727143,
                21.66411503759,
                0.4789888454580939,
                0.5419954181192289,
            ],
        ),
        (
            clamped_stroke(2.7, (0.0, 0.0, 0.0), (38.0, 25.0, 18.0)),
            [
                42.533963782291806,
                0.5003429021990407,
                7165.693257769882,
                17.540849852633354,
                1.0970420737133728,
                0.6720814272092167,
            ],
        ),
    ];
    for (p, before) in cases {
        let s = play(&p, false).unwrap();
        assert_eq!(s.racquet, Hold::Clamped);
        let l = s.strings.leaving;
        let now = [
            l.velocity.x,
            l.velocity.y,
            l.topspin() * (30.0 / std::f64::consts::PI),
            s.landing_x.unwrap(),
            s.kick_height.unwrap(),
            s.net_clearance.unwrap(),
        ];
        assert_eq!(now, before, "{p:?}");
    }
}

fn snapback_shot(args: &[&str]) -> std::process::Output {
    bin::snapback().arg("shot").args(args).output().unwrap()
}

fn shot_json(args: &[&str]) -> serde_json::Value {
    let out = snapback_shot(&[args, &["--format", "json"][..]].concat());
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn the_json_gives_the_racquet_in_si() {
    let typical_flags = [
        "--racquet-mass",
        "320g",
        "--balance",
        "33cm",
        "--swing-weight",
        "320",
        "--twist-weight",
        "14",
        "--impact",
        "52cm",
    ];
    let doc = shot_json(&typical_flags);
    let r = &doc["racquet"];
    let typical = Racquet {
        mass: 0.320,
        balance: 0.33,
        swing_weight: 320e-4,
        twist_weight: 14e-4,
        impact: 0.52,
    };
    assert_eq!(r["clamped"], false);
    assert_eq!(
        r["effective_mass_normal"].as_f64(),
        Some(typical.effective_mass_normal())
    );
    assert_eq!(
        r["effective_mass_tangential"].as_f64(),
        Some(typical.effective_mass_tangential())
    );
    let m = Params::default().mass;
    let ey = shot::base().ey;
    let normal = typical.effective_mass_normal();
    let e_a = r["ey_apparent"].as_f64().unwrap();
    assert!(
        (e_a - (ey * normal - m) / (normal + m)).abs() < 1e-15,
        "{r}"
    );
    let (dn, dt) = (
        r["recoil_normal"].as_f64().unwrap(),
        r["recoil_tangential"].as_f64().unwrap(),
    );
    assert!(dn > 0.0);
    assert_eq!(r["recoil_speed"].as_f64(), Some(dn.hypot(dt)));
    // Clamped: no effective mass (infinite), e_y itself, no recoil.
    let doc = shot_json(&["--racquet-mass", "clamped"]);
    let r = &doc["racquet"];
    assert_eq!(r["clamped"], true);
    assert!(r["effective_mass_normal"].is_null() && r["effective_mass_tangential"].is_null());
    assert_eq!(r["ey_apparent"].as_f64(), Some(shot::base().ey));
    assert_eq!(r["recoil_speed"].as_f64(), Some(0.0));
}

#[test]
fn a_racquet_that_cannot_be_is_refused_by_its_flags() {
    let out = snapback_shot(&["--swing-weight", "100", "--racquet-mass", "350g"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(err.lines().count(), 1, "{err}");
    for part in [
        "--swing-weight 100 kg cm^2",
        "--racquet-mass 350 g",
        "--balance 33 cm",
        "I_cm = SW - M_r (balance - 10 cm)^2",
        "must be above 0",
    ] {
        assert!(err.contains(part), "{part:?} in {err}");
    }
    for (args, wanted) in [
        (
            &["--impact", "80cm"][..],
            "--impact must be in (0, 0.7366] m; got 80cm",
        ),
        (
            &["--racquet-mass", "-1"][..],
            "--racquet-mass must be in [0, inf) kg; got -1",
        ),
        (
            &["--twist-weight", "5 kg"][..],
            "--twist-weight: unit 'kg' is a mass",
        ),
    ] {
        let out = snapback_shot(args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(wanted), "{wanted:?} in {err}");
    }
    // The bounce's commands do not take the racquet.
    let out = bin::snapback()
        .args([
            "sweep", "--vary", "impact", "--from", "40cm", "--to", "60cm", "--steps", "3",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("add --shot"));
}

#[test]
fn the_swing_weight_takes_the_units_specifications_use() {
    let bare = shot_json(&["--swing-weight", "330"]);
    let suffixed = shot_json(&["--swing-weight", "0.033 kg m^2"]);
    assert_eq!(
        bare["racquet"]["effective_mass_normal"],
        suffixed["racquet"]["effective_mass_normal"]
    );
}

fn preset(name: &str) -> Params {
    config::preset(name).unwrap().apply(Params::default())
}

#[test]
fn each_shot_preset_lands_where_its_description_says() {
    let play_preset = |name| play(&preset(name), false).unwrap();
    let (forehand, flat, slice, serve) = (
        play_preset("topspin-forehand"),
        play_preset("flat-drive"),
        play_preset("slice"),
        play_preset("kick-serve"),
    );
    for s in [&forehand, &flat, &slice, &serve] {
        assert!(s.is_in(), "{s:?}");
        // A real racquet, in the hand, on the ball's own restitution.
        assert!(matches!(s.racquet, Hold::Hand(_)));
        assert_eq!(s.strings.bounce.params.ey, 0.85);
    }
    let speed = |s: &snapback::shot::Shot| s.strings.leaving.speed();
    let topspin = |s: &snapback::shot::Shot| s.strings.leaving.topspin();
    // The forehand: topspin, with room over the net.
    assert!(topspin(&forehand) > 2500.0 * RPM);
    assert!(forehand.net_clearance.unwrap() > 0.3);
    // The flat drive: the fastest groundstroke, low over the net, with the least topspin.
    assert!(speed(&flat) > speed(&forehand) && speed(&flat) > speed(&slice));
    assert!(flat.net_clearance.unwrap() < 0.3);
    assert!(topspin(&flat) > 0.0 && topspin(&flat) < topspin(&forehand));
    // The slice: backspin.
    assert!(topspin(&slice) < 0.0);
    // The kick serve: inside the service box (6.40 m beyond the net), kicking highest.
    let landing = serve.landing_x.unwrap() - snapback::shot::court::NET_X;
    assert!(landing > 0.0 && landing < 6.40, "{landing}");
    for other in [&forehand, &flat, &slice] {
        assert!(serve.kick_height.unwrap() > other.kick_height.unwrap());
    }
}

#[test]
fn a_hand_held_racquet_recoils_and_returns_less_than_a_clamped_one() {
    for name in ["topspin-forehand", "flat-drive", "slice", "kick-serve"] {
        let held = preset(name);
        let clamped = Params {
            racquet_mass: 0.0,
            ..held
        };
        let (h, c) = (play(&held, false).unwrap(), play(&clamped, false).unwrap());
        // The same stroke meets the ball the same way...
        assert_eq!(h.strings.incidence, c.strings.incidence);
        // ...and sends it off slower: the racquet takes some of the energy away in its recoil.
        let (hb, cb) = (&h.strings.bounce, &c.strings.bounce);
        assert!(
            h.strings.leaving.speed() < c.strings.leaving.speed(),
            "{name}"
        );
        // Normal to the strings the ball leaves with e_A (the core's e_y on a clamped frame).
        let e_a = h.racquet.ey_apparent(held.ey, held.mass);
        assert!((hb.outcome.vy2 - e_a * hb.setup.vy1).abs() < 1e-12 * hb.setup.vy1);
        assert_eq!(cb.outcome.vy2, held.ey * cb.setup.vy1);
        assert!(e_a < 0.5 * held.ey, "{name}: e_A {e_a}");
        // Along the strings the frame is carried off the way the ball pushed it.
        let recoil = h.racquet.recoil(hb);
        assert!(recoil.normal > 0.0 && recoil.tangential > 0.0, "{recoil:?}");
        assert!(hb.frame_velocity() > 0.0);
        assert_eq!(cb.frame_velocity(), 0.0);
        assert_eq!(c.racquet.recoil(cb).speed(), 0.0);
    }
}

#[test]
fn a_racquet_of_a_thousand_tonnes_approaches_the_clamped_one() {
    for name in ["topspin-forehand", "flat-drive", "slice", "kick-serve"] {
        let clamped = Params {
            racquet_mass: 0.0,
            ..preset(name)
        };
        // 1e6 kg with its moments of inertia scaled alike (I_cm stays above 0).
        let heavy = Params {
            racquet_mass: 1e6,
            swing_weight: 1e6 * 0.1,
            twist_weight: 1e6 * 0.005,
            ..clamped
        };
        let (h, c) = (play(&heavy, false).unwrap(), play(&clamped, false).unwrap());
        let (lh, lc) = (h.strings.leaving, c.strings.leaving);
        let dv = (lh.velocity - lc.velocity).norm();
        assert!(dv < 1e-5 * lc.speed(), "{name}: {dv}");
        assert!(
            (lh.omega_z - lc.omega_z).abs() < 1e-5 * lc.omega_z.abs(),
            "{name}"
        );
        assert!(
            (h.landing_x.unwrap() - c.landing_x.unwrap()).abs() < 1e-4,
            "{name}"
        );
        assert!(h.racquet.recoil(&h.strings.bounce).speed() < 1e-5);
    }
}

/// The launch of `p` by independent means: the change to the strings' frame written out here, the
/// racquet's effective masses from the formulas, the bounce by the RK4 integration of the ball
/// on a free frame. Velocity and spin about z in the court frame.
fn independent_launch(p: &Params) -> ([f64; 2], f64) {
    let (sin_s, cos_s) = p.swing_path_deg.to_radians().sin_cos();
    let (sin_f, cos_f) = p.face_angle_deg.to_radians().sin_cos();
    let (sin_d, cos_d) = p.ball_descent_deg.to_radians().sin_cos();
    let strings = [p.racquet_speed * cos_s, p.racquet_speed * sin_s];
    let relative = [
        -p.ball_speed * cos_d - strings[0],
        -p.ball_speed * sin_d - strings[1],
    ];
    let normal = [cos_f, -sin_f];
    let towards = -(relative[0] * normal[0] + relative[1] * normal[1]);
    let across = [normal[1], -normal[0]];
    let a = relative[0] * across[0] + relative[1] * across[1];
    let tangent = if a >= 0.0 {
        across
    } else {
        [-across[0], -across[1]]
    };
    let vx1 = a.abs();
    let sense = normal[0] * tangent[1] - normal[1] * tangent[0];
    // The racquet: I_cm = SW - M (balance - 0.1)^2, b = impact - balance.
    let (mr, i_cm) = (
        p.racquet_mass,
        p.swing_weight - p.racquet_mass * (p.balance - 0.1).powi(2),
    );
    let b2 = (p.impact - p.balance).powi(2);
    let mn = 1.0 / (1.0 / mr + b2 / i_cm);
    let mt = 1.0 / (1.0 / mr + b2 / (i_cm + p.twist_weight));
    let e_a = (p.ey * mn - p.mass) / (mn + p.mass);
    let on_strings = Params {
        angle_deg: towards.atan2(vx1).to_degrees(),
        speed: towards.hypot(vx1),
        spin: sense * p.ball_topspin,
        frame_mass: mt,
        frame_normal_mass: mn,
        ..*p
    };
    let step = (p.duration / 40_000.0)
        .min(0.002 * (p.cart_mass * mt / (p.cart_mass + mt) / p.stiffness).sqrt());
    let bounce = integrate_frame(&on_strings, step);
    let vy2 = e_a * towards;
    (
        [
            tangent[0] * bounce.vx2 + normal[0] * vy2 + strings[0],
            tangent[1] * bounce.vx2 + normal[1] * vy2 + strings[1],
        ],
        sense * bounce.omega2,
    )
}

#[test]
fn a_hand_held_shot_agrees_with_an_independent_solution_end_to_end() {
    let mut rng = Rng(0x004a_cce7_2023);
    let mut cases: Vec<Params> = ["topspin-forehand", "flat-drive", "slice", "kick-serve"]
        .iter()
        .map(|n| preset(n))
        .collect();
    cases.extend((0..16).map(|_| Params {
        height: rng.uniform(0.6, 2.7),
        ball_speed: rng.uniform(0.0, 30.0),
        ball_descent_deg: rng.uniform(-10.0, 30.0),
        ball_topspin: rng.uniform(-3000.0, 3000.0) * RPM,
        racquet_speed: rng.uniform(15.0, 38.0),
        swing_path_deg: rng.uniform(-25.0, 30.0),
        face_angle_deg: rng.uniform(-15.0, 20.0),
        racquet_mass: rng.uniform(0.25, 0.40),
        balance: rng.uniform(0.30, 0.36),
        swing_weight: rng.uniform(280e-4, 360e-4),
        twist_weight: rng.uniform(12e-4, 18e-4),
        impact: rng.uniform(0.40, 0.64),
        ..preset("topspin-forehand")
    }));
    let (mut launch, mut court, mut compared) = (0.0f64, 0.0f64, 0);
    for p in &cases {
        let Ok(s) = play(p, false) else { continue };
        let (v, omega_z) = independent_launch(p);
        let l = s.strings.leaving;
        let dv = (l.velocity.x - v[0]).hypot(l.velocity.y - v[1]);
        let dw = (l.omega_z - omega_z).abs();
        assert!(
            dv < 1e-6 && dw < 1e-6 * omega_z.abs().max(1.0),
            "{p:?}: {dv} m/s, {dw} rad/s"
        );
        launch = launch.max(dv);
        let ball = reference::Ball {
            mass: p.mass,
            radius: p.radius,
            alpha: p.alpha,
        };
        let r = reference::shot(&ball, p.height, v[0], v[1], omega_z, p.court_mu, p.court_ey);
        for (mine, theirs) in [
            (s.net_clearance, r.clearance),
            (s.landing_x, r.landing),
            (s.kick_height, r.kick),
        ] {
            let d = match (mine, theirs) {
                (Some(a), Some(b)) => (a - b).abs(),
                (None, None) => 0.0,
                _ => f64::INFINITY,
            };
            assert!(d < 1e-3, "{p:?}: {mine:?} against {theirs:?}");
            court = court.max(d);
        }
        compared += 1;
    }
    eprintln!("worst: launch {launch:.1e} m/s, court {court:.1e} m over {compared} shots");
    assert!(compared >= 15, "{compared}");
}

#[test]
fn a_shot_the_hand_held_racquet_cannot_solve_names_the_racquet_flag() {
    let refused = [
        "--preset",
        "topspin-forehand",
        "--stiffness",
        "0",
        "--ball-stiffness",
        "100kN/m",
        "--cart-friction",
        "10",
    ];
    let out = snapback_shot(&refused);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("hand-held racquet"), "{err}");
    assert!(err.contains("--racquet-mass clamped"), "{err}");
    assert!(!err.contains("--frame-mass"), "{err}");
    // The advice works: the same shot on a clamped racquet is played.
    shot_json(&[&refused[..], &["--racquet-mass", "clamped"][..]].concat());
}
