//! `snapback simulate` from the outside: each format, unit suffixes, and every class of bad input.

use crate::support::bin;

use assert_cmd::Command;
use predicates::prelude::*;
use snapback::model::{Params, solve};

fn snapback() -> Command {
    bin::snapback()
}

fn json(args: &[&str]) -> serde_json::Value {
    let out = snapback()
        .arg("simulate")
        .args(args)
        .args(["--format", "json"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("valid JSON")
}

#[test]
fn table_is_the_default() {
    let expected = format!(
        "{:.1} rad/s",
        solve(&Params::default()).unwrap().outcome.omega2
    );
    snapback()
        .arg("simulate")
        .assert()
        .success()
        .stdout(predicate::str::contains("rebound spin ω2"))
        .stdout(predicate::str::contains(expected))
        .stdout(predicate::str::contains("Phases (slide-grip-slide)"))
        .stdout(predicate::str::contains("lost to friction"));
}

/// The table shows phase times with as many decimals as it takes to tell them apart: the 10 kg cart's
/// grip breaks 23 ns before the end of contact (its last slide is real: mu N falls to zero there).
#[test]
fn a_phase_shorter_than_the_tables_rounding_still_reads_as_an_interval() {
    snapback()
        .args(["simulate", "--cart-mass", "10kg"])
        .assert()
        .success()
        .stdout(predicate::str::contains("grip   2.25792 - 4.99998 ms"))
        .stdout(predicate::str::contains("slide  4.99998 - 5.00000 ms"));
    snapback()
        .arg("simulate")
        .assert()
        .success()
        .stdout(predicate::str::contains("grip   1.3244 - 4.3917 ms"));
}

#[test]
fn json_has_the_contract_keys() {
    let v = json(&[]);
    let b = solve(&Params::default()).unwrap();
    for key in [
        "params",
        "omega2",
        "vx2",
        "vy2",
        "theta2_deg",
        "ex",
        "phases",
        "energy",
    ] {
        assert!(v.get(key).is_some(), "missing {key}");
    }
    assert_eq!(v["omega2"].as_f64().unwrap(), b.outcome.omega2);
    assert_eq!(v["vx2"].as_f64().unwrap(), b.outcome.vx2);
    assert_eq!(v["params"]["angle_deg"].as_f64().unwrap(), 60.0);
    assert_eq!(v["params"]["cart_mass"].as_f64().unwrap(), 0.01);
    let phases = v["phases"].as_array().unwrap();
    assert_eq!(phases.len(), 3);
    assert_eq!(phases[0]["kind"], "slide");
    assert_eq!(phases[1]["kind"], "grip");
    assert_eq!(phases[1]["start"].as_f64().unwrap(), b.phases[1].start);
    for key in [
        "initial",
        "final_ball",
        "final_cart",
        "friction_loss",
        "residual",
    ] {
        assert!(v["energy"][key].is_number(), "energy.{key}");
    }
    // The strings' travel, beside where they are at release; the table shows it in mm.
    let travel = snapback::analysis::timeline::travel(&b);
    assert_eq!(v["cart"]["x"].as_f64().unwrap(), b.final_state.x);
    assert_eq!(v["cart"]["peak_x"].as_f64().unwrap(), travel.peak_x);
    assert_eq!(v["cart"]["peak_v"].as_f64().unwrap(), travel.peak_v);
    snapback()
        .arg("simulate")
        .assert()
        .stdout(predicate::str::contains(
            "cart peak: |X| = 7.689 mm at 3.075 ms",
        ));
}

#[test]
fn ex_is_null_when_the_ball_arrives_rolling() {
    // v_x1 = 10 cos 60° = 5 m/s; rolling means omega1 = v_x1 / r.
    let spin = format!("{}", 10.0 * 60f64.to_radians().cos() / 0.033);
    let v = json(&["--spin", &spin]);
    assert!(v["ex"].is_null());
}

#[test]
fn csv_has_a_header_and_the_requested_samples() {
    let out = snapback()
        .args(["simulate", "--format", "csv", "--samples", "11"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some("t,N,F,X,V,vx,omega,slip,phase,cart_stuck,stretch,patch_slip")
    );
    let rows: Vec<&str> = lines.collect();
    // 11 even samples plus both sides of the two transitions.
    assert_eq!(rows.len(), 11 + 4);
    assert!(rows[0].starts_with("0,"));
    assert!(rows.last().unwrap().starts_with("0.005,"));
    assert!(rows.iter().all(|r| r.split(',').count() == 12));
    assert_eq!(
        snapback()
            .args(["simulate", "--format", "csv"])
            .output()
            .unwrap()
            .stdout
            .iter()
            .filter(|&&c| c == b'\n')
            .count(),
        1 + 501 + 4
    );
}

#[test]
fn unit_suffixes_equal_bare_si_values() {
    let with_units = json(&[
        "--cart-mass",
        "1g",
        "--stiffness",
        "2.2kN/m",
        "--duration",
        "4ms",
        "--radius",
        "3.3cm",
        "--angle",
        "0.9rad",
        "--spin",
        "-955rpm",
        "--speed",
        "36km/h",
        "--mass",
        "57 g",
    ]);
    let bare = json(&[
        "--cart-mass",
        "0.001",
        "--stiffness",
        "2200",
        "--duration",
        "0.004",
        "--radius",
        "0.033",
        "--angle",
        &format!("{}", 0.9f64.to_degrees()),
        "--spin",
        &format!("{}", -955.0 * std::f64::consts::PI / 30.0),
        "--speed",
        "10",
        "--mass",
        "0.057",
    ]);
    for key in ["omega2", "vx2", "vy2"] {
        let (a, b) = (
            with_units[key].as_f64().unwrap(),
            bare[key].as_f64().unwrap(),
        );
        assert!(
            (a - b).abs() <= 1e-12 * a.abs().max(1.0),
            "{key}: {a} vs {b}"
        );
    }
}

/// Runs `simulate` with `args`, expects exit status 2 and one line on stderr containing every `needle`.
fn rejects(args: &[&str], needles: &[&str]) {
    let out = snapback().arg("simulate").args(args).output().unwrap();
    assert_eq!(out.status.code(), Some(2), "{args:?}");
    assert!(out.stdout.is_empty());
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    for needle in needles {
        assert!(err.contains(needle), "{args:?}: {err:?} lacks {needle:?}");
    }
    assert!(!err.contains("panicked"));
}

#[test]
fn out_of_range_values_name_flag_range_and_value() {
    rejects(&["--angle", "95"], &["--angle", "(0, 90] deg", "95"]);
    rejects(&["--angle", "0"], &["--angle", "(0, 90]", "got 0"]);
    rejects(&["--mass", "0"], &["--mass", "(0, inf) kg", "got 0"]);
    rejects(&["--radius", "-3mm"], &["--radius", "(0, inf) m", "-3mm"]);
    rejects(&["--speed", "-1"], &["--speed", "(0, inf) m/s"]);
    rejects(&["--duration", "0ms"], &["--duration", "(0, inf) s", "0ms"]);
    rejects(
        &["--cart-mass", "-5g"],
        &["--cart-mass", "(0, inf) kg", "-5g"],
    );
    rejects(&["--alpha", "0"], &["--alpha", "(0, inf)"]);
    rejects(&["--mu", "-0.1"], &["--mu", "[0, inf)", "-0.1"]);
    rejects(&["--ey", "1.2"], &["--ey", "[0, 1]", "1.2"]);
    rejects(
        &["--stiffness", "-1kN/m"],
        &["--stiffness", "[0, inf) N/m", "-1kN/m"],
    );
}

#[test]
fn non_finite_and_garbage_values_are_rejected() {
    rejects(
        &["--speed", "inf"],
        &["--speed", "not a finite number", "inf"],
    );
    rejects(&["--spin", "NaN"], &["--spin", "not a finite number"]);
    rejects(&["--mass", "1e999"], &["--mass", "not a finite number"]);
    rejects(&["--mu", "lots"], &["--mu", "not a number", "lots"]);
}

#[test]
fn units_must_fit_the_flag() {
    rejects(
        &["--angle", "10g"],
        &["--angle", "unit 'g' is a mass", "an angle"],
    );
    rejects(&["--stiffness", "15kg"], &["--stiffness", "a mass"]);
    rejects(
        &["--cart-mass", "10 stone"],
        &["--cart-mass", "unknown unit 'stone'", "kg, g, mg"],
    );
    rejects(&["--mu", "0.4N"], &["--mu", "a force", "a pure number"]);
}

#[test]
fn too_fast_a_cart_is_refused_not_hung() {
    rejects(
        &[
            "--cart-mass",
            "1e-9",
            "--stiffness",
            "1e9",
            "--duration",
            "1",
        ],
        &["too fast", "stiffness"],
    );
}

#[test]
fn help_states_the_bare_units() {
    snapback()
        .args(["simulate", "--help"])
        .assert()
        .success()
        .stdout(predicate::str::contains("--cart-mass <VALUE>"))
        .stdout(predicate::str::contains("bare number in kg"))
        .stdout(predicate::str::contains("bare number in N/m"))
        .stdout(predicate::str::contains("bare number in deg"));
}
