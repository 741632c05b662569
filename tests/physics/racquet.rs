//! The racquet in the hand (issue 23 items 2-4): its effective masses and apparent restitution against
//! their formulas, the clamped racquet as the shot was before it, and the command line.

use crate::support::bin;

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
    // landing x, kick height and net clearance (m), as that build (main with the core's frame, before
    // this branch) printed them.
    let cases = [
        (
            clamped_stroke(1.0, (20.0, 10.0, 1000.0), (20.0, 25.0, 0.0)),
            [
                35.14619560117272,
                5.577513608145125,
                3761.7460416212953,
                20.203691856811396,
                0.7065527001926383,
                0.6559485105057122,
            ],
        ),
        (
            clamped_stroke(1.0, (20.0, 10.0, 1000.0), (22.0, 8.0, -1.0)),
            [
                40.50437837951824,
                3.048744962589603,
                1877.9796588389916,
                19.06801623302998,
                0.5562782631279307,
                0.1009800306685148,
            ],
        ),
        (
            clamped_stroke(1.0, (20.0, 10.0, 1000.0), (15.0, -25.0, -12.0)),
            [
                26.413017787452794,
                2.544396650729432,
                -2947.093493772716,
                21.66411503758999,
                0.4789888454580943,
                0.5419954181192289,
            ],
        ),
        (
            clamped_stroke(2.7, (0.0, 0.0, 0.0), (38.0, 25.0, 18.0)),
            [
                42.533963782291806,
                0.5003429021990407,
                7165.693257769884,
                17.54084985263336,
                1.0970420737133721,
                0.6720814272092192,
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
