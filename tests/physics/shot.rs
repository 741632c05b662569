//! `snapback shot`: the flight against an independent integration, the reductions to `simulate`, to the
//! parabola and to the heavy cart, energy and mirror symmetry, and the command line.

use crate::support::bin;

use crate::support::flight as reference;
use crate::support::prop;
use crate::support::rng;

use assert_cmd::Command;
use nalgebra::Vector2;
use proptest::prelude::*;

use prop::config;
use rng::Rng;
use snapback::model::{Params, solve};
use snapback::shot::aero::{Air, GRAVITY, Projectile};
use snapback::shot::court::{self, COURT_MASS, NET_HEIGHT, NET_X};
use snapback::shot::flight::{Stop, fly};
use snapback::shot::frame::Surface;
use snapback::shot::racquet::Hold;
use snapback::shot::{self as shot, Shot, play, play_in};

fn preset(name: &str) -> Params {
    snapback::config::preset(name)
        .unwrap()
        .apply(Params::default())
}

/// A random stroke around the forehand preset: every shot parameter moves.
fn random_stroke(rng: &mut Rng) -> Params {
    Params {
        height: rng.uniform(0.4, 2.8),
        ball_speed: rng.uniform(0.0, 30.0),
        ball_descent_deg: rng.uniform(-10.0, 30.0),
        ball_topspin: rng.uniform(-3000.0, 3000.0) * std::f64::consts::PI / 30.0,
        racquet_speed: rng.uniform(12.0, 35.0),
        swing_path_deg: rng.uniform(-25.0, 35.0),
        face_angle_deg: rng.uniform(-15.0, 20.0),
        court_mu: rng.uniform(0.3, 0.9),
        court_ey: rng.uniform(0.6, 0.9),
        ..preset("topspin-forehand")
    }
}

fn difference(a: Option<f64>, b: Option<f64>) -> f64 {
    match (a, b) {
        (Some(a), Some(b)) => (a - b).abs(),
        (None, None) => 0.0,
        _ => f64::INFINITY,
    }
}

#[test]
fn the_flight_agrees_with_an_independent_rk4_to_a_millimetre() {
    let mut rng = Rng(0x5eed_0016);
    let mut cases: Vec<Params> = ["flat-drive", "topspin-forehand", "slice", "kick-serve"]
        .iter()
        .map(|n| preset(n))
        .collect();
    cases.extend((0..40).map(|_| random_stroke(&mut rng)));
    let (mut clearance, mut landing, mut kick, mut compared) = (0.0f64, 0.0f64, 0.0f64, [0; 3]);
    for p in &cases {
        let Ok(s) = play(p, false) else { continue };
        let l = s.strings.leaving;
        let ball = reference::Ball {
            mass: p.mass,
            radius: p.radius,
            alpha: p.alpha,
        };
        let r = reference::shot(
            &ball,
            p.height,
            l.velocity.x,
            l.velocity.y,
            l.omega_z,
            p.court_mu,
            p.court_ey,
        );
        for (k, (mine, theirs, worst)) in [
            (s.net_clearance, r.clearance, &mut clearance),
            (s.landing_x, r.landing, &mut landing),
            (s.kick_height, r.kick, &mut kick),
        ]
        .into_iter()
        .enumerate()
        {
            let d = difference(mine, theirs);
            assert!(d < 1e-3, "{p:?}: {mine:?} against {theirs:?}");
            *worst = worst.max(d);
            compared[k] += usize::from(mine.is_some());
        }
    }
    eprintln!(
        "worst differences: clearance {clearance:.2e} m, landing {landing:.2e} m, kick height {kick:.2e} m \
         (over {compared:?} values)"
    );
    assert!(compared.iter().all(|&n| n >= 10), "{compared:?}");
}

#[test]
fn a_racquet_at_rest_facing_the_ball_is_simulate_on_its_frame_at_normal_incidence() {
    for (descent, topspin) in [(10.0, 1000.0), (-5.0, -2500.0), (40.0, 0.0)] {
        let p = Params {
            racquet_speed: 0.0,
            ball_descent_deg: descent,
            face_angle_deg: -descent,
            ball_speed: 20.0,
            ball_topspin: topspin * std::f64::consts::PI / 30.0,
            ..preset("topspin-forehand")
        };
        let contact = shot::hit(&p).unwrap();
        let i = contact.incidence;
        assert!((i.theta1_deg - 90.0).abs() < 1e-9, "{i:?}");
        assert!((i.speed - 20.0).abs() < 1e-12);
        assert!((i.spin.abs() - p.ball_topspin.abs()).abs() < 1e-12);
        // The racquet in the hand is simulate's free frame of its effective masses.
        let (frame_mass, frame_normal_mass) = Hold::of(&p).unwrap().frame_masses();
        assert!(frame_mass > 0.0 && frame_normal_mass > 0.0);
        let simulated = solve(&Params {
            angle_deg: 90.0,
            speed: 20.0,
            spin: i.spin,
            frame_mass,
            frame_normal_mass,
            ..p
        })
        .unwrap()
        .outcome;
        let o = contact.bounce.outcome;
        assert!((o.omega2 - simulated.omega2).abs() < 1e-6 * simulated.omega2.abs().max(1.0));
        assert!((o.vy2 - simulated.vy2).abs() < 1e-9);
        // Back along the normal the ball came in on, at simulate's speed and spin.
        let normal = Vector2::new(descent.to_radians().cos(), descent.to_radians().sin());
        let l = contact.leaving;
        assert!((l.velocity.dot(&normal) - simulated.vy2).abs() < 1e-6);
        assert!((l.speed() - simulated.speed2()).abs() < 1e-6);
        assert!((l.omega_z.abs() - simulated.omega2.abs()).abs() < 1e-6);
    }
}

#[test]
fn an_oblique_racquet_at_rest_is_simulate_on_its_frame_at_its_incidence() {
    let p = Params {
        racquet_speed: 0.0,
        ball_descent_deg: 10.0,
        face_angle_deg: 20.0,
        ..preset("topspin-forehand")
    };
    let contact = shot::hit(&p).unwrap();
    // The ball comes in 10 deg below the horizontal onto a normal 20 deg below it: 30 deg off normal.
    assert!((contact.incidence.theta1_deg - 60.0).abs() < 1e-9);
    assert!((contact.incidence.speed - p.ball_speed).abs() < 1e-12);
    assert!((contact.incidence.spin.abs() - p.ball_topspin.abs()).abs() < 1e-12);
    let (frame_mass, frame_normal_mass) = Hold::of(&p).unwrap().frame_masses();
    let simulated = solve(&Params {
        angle_deg: contact.incidence.theta1_deg,
        speed: contact.incidence.speed,
        spin: contact.incidence.spin,
        frame_mass,
        frame_normal_mass,
        ..p
    })
    .unwrap();
    assert_eq!(contact.bounce.outcome, simulated.outcome);
}

#[test]
fn without_air_the_ball_lands_where_the_parabola_says() {
    for name in ["flat-drive", "topspin-forehand", "slice", "kick-serve"] {
        let p = preset(name);
        let s = play_in(&p, Air::VACUUM, false).unwrap();
        let (vx, vy) = (s.strings.leaving.velocity.x, s.strings.leaving.velocity.y);
        let drop = p.height - p.radius;
        let t = (vy + (vy * vy + 2.0 * GRAVITY * drop).sqrt()) / GRAVITY;
        let tn = NET_X / vx;
        let at_net = p.height + vy * tn - 0.5 * GRAVITY * tn * tn;
        assert!((s.net_clearance.unwrap() - (at_net - p.radius - NET_HEIGHT)).abs() < 1e-6);
        if let Some(x) = s.landing_x {
            assert!((x - vx * t).abs() < 1e-6, "{name}: {x} against {}", vx * t);
            assert!((s.flight_time - t).abs() < 1e-8);
        }
    }
}

#[test]
fn the_court_bounce_is_the_heavy_cart_limit() {
    let mut rng = Rng(0xc0_0016);
    for _ in 0..200 {
        let p = Params {
            court_mu: rng.uniform(0.1, 1.0),
            court_ey: rng.uniform(0.3, 1.0),
            court_duration: rng.uniform(2e-3, 6e-3),
            ..Params::default()
        };
        let floor = Surface::at_rest(Vector2::new(0.0, 1.0));
        let velocity = Vector2::new(rng.uniform(-30.0, 30.0), -rng.uniform(0.5, 20.0));
        let omega_z = rng.uniform(-600.0, 600.0);
        let i = floor.incidence(velocity, omega_z).unwrap();
        let bounce = court::bounce(&p, &i).unwrap().outcome;
        // The limit M -> infinity in closed form.
        let ball = reference::Ball {
            mass: p.mass,
            radius: p.radius,
            alpha: p.alpha,
        };
        let v1 = i.speed;
        let theta = i.theta1_deg.to_radians();
        let (vx2, vy2, omega2) = reference::rigid_bounce(
            &ball,
            p.court_mu,
            p.court_ey,
            v1 * theta.cos(),
            v1 * theta.sin(),
            i.spin,
        );
        let scale = v1.max(1.0);
        assert!(
            (bounce.vx2 - vx2).abs() < 1e-5 * scale,
            "{} {vx2}",
            bounce.vx2
        );
        assert!((bounce.vy2 - vy2).abs() < 1e-9 * scale);
        assert!((bounce.omega2 - omega2).abs() * p.radius < 1e-5 * scale);
        // And the core's own limit: a cart a thousand times heavier gives the same bounce.
        let heavier = solve(&Params {
            angle_deg: i.theta1_deg,
            speed: i.speed,
            spin: i.spin,
            mu: p.court_mu,
            ey: p.court_ey,
            duration: p.court_duration,
            cart_mass: COURT_MASS * 1e3,
            stiffness: 0.0,
            ..p
        })
        .unwrap()
        .outcome;
        assert!((bounce.vx2 - heavier.vx2).abs() < 1e-5 * scale);
    }
}

fn mirrored(p: &Params) -> Params {
    Params {
        ball_descent_deg: -p.ball_descent_deg,
        ball_topspin: -p.ball_topspin,
        swing_path_deg: -p.swing_path_deg,
        face_angle_deg: -p.face_angle_deg,
        ..*p
    }
}

fn strokes() -> impl Strategy<Value = Params> {
    (
        (0.5f64..3.0, 0.0f64..35.0, -30.0f64..40.0, -400.0f64..400.0),
        (5.0f64..40.0, -40.0f64..40.0, -30.0f64..30.0),
        (0.0f64..0.9, 0.3f64..1.0),
    )
        .prop_map(
            |((height, ball_speed, descent, topspin), (racquet, swing, face), (mu, ey))| Params {
                height,
                ball_speed,
                ball_descent_deg: descent,
                ball_topspin: topspin,
                racquet_speed: racquet,
                swing_path_deg: swing,
                face_angle_deg: face,
                court_mu: mu,
                court_ey: ey,
                ..preset("topspin-forehand")
            },
        )
}

/// Strokes anywhere in the parameters' ranges.
fn wild_strokes() -> impl Strategy<Value = Params> {
    (
        (
            0.034f64..5.0,
            0.0f64..100.0,
            -90.0f64..90.0,
            -1047.0f64..1047.0,
        ),
        (0.0f64..100.0, -89.9f64..89.9, -89.9f64..89.9),
        (0.0f64..2.0, 0.0f64..1.0, 1e-4f64..0.02),
    )
        .prop_map(
            |((height, ball_speed, descent, topspin), (racquet, swing, face), (mu, ey, t))| {
                Params {
                    height,
                    ball_speed,
                    ball_descent_deg: descent,
                    ball_topspin: topspin,
                    racquet_speed: racquet,
                    swing_path_deg: swing,
                    face_angle_deg: face,
                    court_mu: mu,
                    court_ey: ey,
                    court_duration: t,
                    ..preset("topspin-forehand")
                }
            },
        )
}

proptest! {
    #![proptest_config(config(200))]

    #[test]
    fn energy_never_grows_in_flight(
        (vx, vy, omega_z) in (-40.0f64..60.0, -20.0f64..30.0, -700.0f64..700.0),
        height in 0.1f64..3.0,
    ) {
        let ball = Projectile { mass: 0.057, radius: 0.033, omega_z, air: Air::STILL };
        let mut path = Vec::new();
        let hit = fly(&ball, [0.0, height, vx, vy], &[Stop::Down(0.0)], Some(&mut path)).unwrap();
        let [x, y, vx, vy] = hit.state;
        path.push([hit.t, x, y, vx, vy]);
        // Per unit mass: drag only takes energy away and lift does no work.
        let energy = |q: &[f64; 5]| 0.5 * (q[3] * q[3] + q[4] * q[4]) + GRAVITY * q[2];
        for pair in path.windows(2) {
            let (a, b) = (energy(&pair[0]), energy(&pair[1]));
            prop_assert!(b <= a + 1e-9 * a.abs().max(1.0), "{a} -> {b} at t = {}", pair[1][0]);
            prop_assert!(pair[1][0] > pair[0][0]);
        }
    }

    #[test]
    fn a_whole_shot_is_finite_and_its_clock_runs_on(p in wild_strokes()) {
        let Ok(s) = play(&p, true) else { return Ok(()) };
        let json = snapback::export::shot::json(&s);
        prop_assert!(!json.contains("NaN") && !json.contains("inf"), "{}", json);
        prop_assert!(s.trajectory.iter().flatten().all(|v| v.is_finite()));
        prop_assert!(s.trajectory.windows(2).all(|w| w[1][0] >= w[0][0]));
        prop_assert!(s.flight_time.is_finite() && s.flight_time > 0.0);
    }

    #[test]
    fn a_mirror_image_stroke_gives_a_mirror_image_launch(p in strokes()) {
        let (a, b) = (shot::hit(&p), shot::hit(&mirrored(&p)));
        prop_assert_eq!(a.is_ok(), b.is_ok());
        let (Ok(a), Ok(b)) = (a, b) else { return Ok(()) };
        let (ia, ib) = (a.incidence, b.incidence);
        prop_assert!((ia.theta1_deg - ib.theta1_deg).abs() < 1e-9);
        prop_assert!((ia.speed - ib.speed).abs() < 1e-9 * ia.speed);
        prop_assert!((ia.spin - ib.spin).abs() < 1e-9 * ia.spin.abs().max(1.0));
        let (la, lb) = (a.leaving, b.leaving);
        let scale = la.speed().max(1.0);
        prop_assert!((la.velocity.x - lb.velocity.x).abs() < 1e-9 * scale);
        prop_assert!((la.velocity.y + lb.velocity.y).abs() < 1e-9 * scale);
        prop_assert!((la.omega_z + lb.omega_z).abs() < 1e-9 * la.omega_z.abs().max(1.0));
    }
}

fn snapback() -> Command {
    bin::snapback()
}

fn shot_json(args: &[&str]) -> serde_json::Value {
    let out = snapback()
        .arg("shot")
        .args(args)
        .args(["--format", "json"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn the_json_has_the_issues_keys_and_numbers_only() {
    let doc = shot_json(&["--preset", "topspin-forehand", "--trajectory"]);
    for key in [
        "contact",
        "launch",
        "net_clearance_m",
        "landing_m",
        "flight_time_s",
        "in",
        "court_bounce",
        "kick_height_m",
        "trajectory",
    ] {
        assert!(doc.get(key).is_some(), "no {key} in {doc}");
    }
    for key in ["angle_deg", "speed", "spin"] {
        assert!(doc["contact"][key].is_f64());
    }
    for key in ["speed", "angle_deg", "topspin_rpm", "vx", "vy"] {
        assert!(doc["launch"][key].is_f64());
    }
    for key in ["speed", "angle_deg", "topspin_rpm", "incidence_deg"] {
        assert!(doc["court_bounce"][key].is_f64());
    }
    assert_eq!(doc["in"], true);
    let landing = doc["landing_m"].as_f64().unwrap();
    assert!((doc["landing_x_m"].as_f64().unwrap() - NET_X - landing).abs() < 1e-12);
    assert!(doc["trajectory"].as_array().unwrap().len() > 10);
    // Without --trajectory, no trajectory.
    assert!(shot_json(&[]).get("trajectory").is_none());
    // Into the net: no landing, no bounce, no kick; never NaN.
    let net = shot_json(&["--face-angle", "5"]);
    assert!(net["net_clearance_m"].as_f64().unwrap() < 0.0, "{net}");
    assert!(net["landing_m"].is_null() && net["court_bounce"].is_null());
    assert_eq!(net["in"], false);
    assert!(!serde_json::to_string(&net).unwrap().contains("NaN"));
}

#[test]
fn the_json_is_the_library_shot() {
    let doc = shot_json(&["--preset", "slice"]);
    let s: Shot = play(&preset("slice"), false).unwrap();
    assert_eq!(doc["kick_height_m"].as_f64(), s.kick_height);
    assert_eq!(doc["net_clearance_m"].as_f64(), s.net_clearance);
    assert!(doc["launch"]["topspin_rpm"].as_f64().unwrap() < 0.0);
}

#[test]
fn bad_shots_get_one_line_and_status_2() {
    for (args, wanted) in [
        (
            &["--speed", "20"][..],
            "error: --speed is what the strings see",
        ),
        (&["--spin", "0"][..], "--ball-topspin"),
        (&["--angle", "30"][..], "--racquet-speed"),
        (
            &[
                "--racquet-speed",
                "0",
                "--ball-descent",
                "-60",
                "--face-angle",
                "-80",
            ][..],
            "error: the racquet never meets the ball",
        ),
        (
            &["--ball-topspin", "20000"][..],
            "error: --ball-topspin must be in [-10000, 10000] rpm; got 20000",
        ),
        (
            &["--height", "2cm"][..],
            "error: --height must be above the ball's radius",
        ),
    ] {
        let out = snapback().arg("shot").args(args).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(wanted), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{err}");
    }
}

#[test]
fn simulate_refuses_the_shot_flags() {
    let out = snapback()
        .args(["simulate", "--racquet-speed", "20"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--racquet-speed"));
}

#[test]
fn a_bare_incoming_spin_is_rpm() {
    let a = shot_json(&["--ball-topspin", "1500"]);
    let b = shot_json(&["--ball-topspin", "25rps"]);
    assert_eq!(a["launch"], b["launch"]);
}

#[test]
fn a_sweep_of_shots_is_one_shot_per_value() {
    let out = snapback()
        .args([
            "sweep",
            "--shot",
            "--vary",
            "face-angle",
            "--from",
            "-4",
            "--to",
            "4",
            "--steps",
            "5",
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(header[0], "face_angle_deg");
    let at = |key: &str| header.iter().position(|h| *h == key).unwrap();
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 5);
    for row in &rows {
        let face: f64 = row[0].parse().unwrap();
        let p = Params {
            face_angle_deg: face,
            ..preset("topspin-forehand")
        };
        let s = play(&p, false).unwrap();
        let kick = row[at("kick_height_m")];
        assert_eq!(kick.parse::<f64>().ok(), s.kick_height, "{row:?}");
        assert_eq!(row[at("in")], s.is_in().to_string());
    }
    // A closed face sends the ball lower over the net.
    let clearance = |row: &Vec<&str>| row[at("net_clearance_m")].parse::<f64>().unwrap();
    assert!(clearance(&rows[0]) > clearance(&rows[4]));
    // Without --shot the shot's flags are refused, and so is --speed with it.
    for args in [
        &[
            "sweep",
            "--vary",
            "face-angle",
            "--from",
            "0",
            "--to",
            "1",
            "--steps",
            "2",
        ][..],
        &[
            "sweep", "--vary", "mu", "--from", "0", "--to", "1", "--steps", "2", "--height", "2",
        ][..],
        &[
            "sweep", "--shot", "--vary", "speed", "--from", "1", "--to", "2", "--steps", "2",
        ][..],
    ] {
        let out = snapback().args(args).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
    }
}

#[test]
fn the_face_angle_that_kicks_highest_lands_in() {
    let out = snapback()
        .args([
            "optimize",
            "--objective",
            "kick_height",
            "--vary",
            "face-angle",
        ])
        .args(["--from", "-10", "--to", "10", "--format", "json"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(doc["shot"]["in"], true);
    let face = doc["value"].as_f64().unwrap();
    let best = doc["objective_value"].as_f64().unwrap();
    assert_eq!(doc["shot"]["kick_height_m"].as_f64(), Some(best));
    // No face angle nearby that lands in kicks higher.
    for step in [-0.5, -0.05, 0.05, 0.5] {
        let p = Params {
            face_angle_deg: face + step,
            ..preset("topspin-forehand")
        };
        let s = play(&p, false).unwrap();
        if s.is_in() {
            assert!(
                s.kick_height.unwrap() <= best + 1e-9,
                "{step}: {:?}",
                s.kick_height
            );
        }
    }
    // A bounce objective keeps refusing the shot's flags.
    let out = snapback()
        .args([
            "optimize",
            "--vary",
            "face-angle",
            "--from",
            "0",
            "--to",
            "1",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
}
