//! Uncertain inputs (`--angle 50±1`, `50+-1`, `--spin -3820rpm±200`): `simulate` and `sweep` report each
//! outcome's Monte Carlo mean and spread beside the usual output; other commands refuse them.

use crate::support::bin;

use assert_cmd::Command;
use serde_json::Value;

fn snapback() -> Command {
    bin::snapback()
}

fn json(args: &[&str]) -> Value {
    let out = snapback().args(args).assert().success();
    serde_json::from_slice(&out.get_output().stdout).unwrap()
}

#[test]
fn simulate_reports_mean_and_spread_beside_the_bounce() {
    let plain = json(&[
        "simulate", "--angle", "50", "--spin", "-3820rpm", "--format", "json",
    ]);
    let args = [
        "simulate",
        "--angle",
        "50±1",
        "--spin",
        "-3820rpm±200",
        "--format",
        "json",
    ];
    let doc = json(&args);
    // The bounce at the central values is unchanged; the spread is a key beside it.
    for key in ["omega2", "vx2", "theta2_deg", "params", "phases"] {
        assert_eq!(doc[key], plain[key], "{key}");
    }
    let u = &doc["uncertainty"];
    assert_eq!(u["samples"], 1000);
    assert_eq!(u["inputs"]["angle"], 1.0);
    // A bare uncertainty is in the value's unit: 200 rpm.
    let spin = u["inputs"]["spin"].as_f64().unwrap();
    assert!((spin - 200.0 * std::f64::consts::PI / 30.0).abs() < 1e-9);
    let omega2 = &u["outcomes"]["omega2"];
    let (mean, sd) = (
        omega2["mean"].as_f64().unwrap(),
        omega2["sd"].as_f64().unwrap(),
    );
    let centre = plain["omega2"].as_f64().unwrap();
    assert!(sd > 0.0 && (mean - centre).abs() < 3.0 * sd, "{omega2}");
    // `+-` is `±`, and the seed fixes the result.
    let ascii = json(&[
        "simulate",
        "--angle",
        "50+-1",
        "--spin",
        "-3820rpm+-200",
        "--format",
        "json",
    ]);
    assert_eq!(ascii["uncertainty"], doc["uncertainty"]);
    let other = json(&[&args[..], &["--mc-seed", "2"]].concat());
    assert_ne!(
        other["uncertainty"]["outcomes"],
        doc["uncertainty"]["outcomes"]
    );
}

#[test]
fn the_table_gains_a_section_and_csv_is_refused() {
    let out = snapback()
        .args(["simulate", "--angle", "50±1", "--mc-samples", "100"])
        .assert()
        .success();
    let text = String::from_utf8_lossy(&out.get_output().stdout).to_string();
    assert!(
        text.contains("Uncertainty (Monte Carlo, 100 draws, seed 1)"),
        "{text}"
    );
    assert!(text.contains("incidence angle θ1      ± 1 deg"), "{text}");
    snapback()
        .args(["simulate", "--angle", "50±1", "--format", "csv"])
        .assert()
        .code(2);
    snapback()
        .args(["simulate", "--angle", "50±x"])
        .assert()
        .code(2)
        .stderr(predicates::str::contains(
            "--angle: the uncertainty must be a number",
        ));
    snapback()
        .args([
            "optimize",
            "--vary",
            "stiffness",
            "--from",
            "1kN/m",
            "--to",
            "2kN/m",
            "--angle",
            "50±1",
        ])
        .assert()
        .code(2)
        .stderr(predicates::str::contains(
            "taken by simulate and sweep only",
        ));
}

#[test]
fn sweep_adds_mean_and_sd_columns_after_the_usual_ones() {
    let base = [
        "sweep", "--vary", "angle", "--from", "30", "--to", "60", "--steps", "3",
    ];
    let plain = snapback().args(base).assert().success();
    let plain = String::from_utf8_lossy(&plain.get_output().stdout).to_string();
    let banded = snapback()
        .args(base)
        .args(["--spin", "-100±10", "--mc-samples", "50"])
        .assert()
        .success();
    let banded = String::from_utf8_lossy(&banded.get_output().stdout).to_string();
    for (p, b) in plain.lines().zip(banded.lines()) {
        assert!(b.starts_with(&format!("{p},")), "{p}\n{b}");
    }
    let header = banded.lines().next().unwrap();
    assert!(
        header.ends_with(",ex_mean,ex_sd,speed2_mean,speed2_sd"),
        "{header}"
    );
    let doc = json(
        &[
            &base[..],
            &[
                "--spin",
                "-100±10",
                "--mc-samples",
                "50",
                "--format",
                "json",
            ],
        ]
        .concat(),
    );
    assert_eq!(doc.as_array().unwrap().len(), 3);
    assert!(doc[1]["omega2_sd"].as_f64().unwrap() > 0.0);
}
