//! The analysis commands end to end: formats, exit statuses and one-line errors.

use crate::support::bin;

use assert_cmd::Command;
use serde_json::Value;
use snapback::analysis::reproduce;
use snapback::model::Params;

fn snapback() -> Command {
    bin::snapback()
}

/// Runs the command; returns (status, stdout, stderr).
fn run(args: &[&str]) -> (i32, String, String) {
    let out = snapback().args(args).output().unwrap();
    (
        out.status.code().unwrap(),
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8(out.stderr).unwrap(),
    )
}

/// Asserts a usage error: status 2 and one line on stderr containing every fragment.
fn usage_error(args: &[&str], fragments: &[&str]) {
    let (code, stdout, stderr) = run(args);
    assert_eq!(code, 2, "{args:?}: {stderr}");
    assert!(stdout.is_empty(), "{args:?}");
    assert_eq!(stderr.lines().count(), 1, "{args:?}: {stderr}");
    assert!(stderr.starts_with("error: "), "{stderr}");
    for f in fragments {
        assert!(stderr.contains(f), "{args:?}: {f} not in {stderr}");
    }
}

#[test]
fn sweep_csv_has_the_contract_columns_and_every_step() {
    let (code, out, _) = run(&[
        "sweep", "--vary", "angle", "--from", "10", "--to", "90", "--steps", "9",
    ]);
    assert_eq!(code, 0);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(
        lines[0],
        "angle_deg,omega2,vx2,vy2,theta2_deg,ex,phases,slides_throughout,cart_stuck,stretch,patch_slip"
    );
    assert_eq!(lines.len(), 10);
    assert!(lines[1].starts_with("10,") && lines[9].starts_with("90,"));
    assert!(lines[1].ends_with(",slide,true,false,,"), "{}", lines[1]);
    assert!(lines[6].contains(",slide-grip-slide,false"), "{}", lines[6]);
}

#[test]
fn sweep_columns_carry_units_and_ends_take_suffixes() {
    let (code, out, _) = run(&[
        "sweep",
        "--vary",
        "cart-mass",
        "--from",
        "1g",
        "--to",
        "10g",
        "--steps",
        "3",
        "--log",
    ]);
    assert_eq!(code, 0);
    let lines: Vec<&str> = out.lines().collect();
    assert!(lines[0].starts_with("cart_mass_kg,"));
    assert!(lines[1].starts_with("0.001,"));
    assert!(lines[3].starts_with("0.01,"));
    let (_, out, _) = run(&[
        "sweep",
        "--vary",
        "stiffness",
        "--from",
        "1kN/m",
        "--to",
        "2kN/m",
        "--steps",
        "2",
    ]);
    assert!(out.starts_with("stiffness_N_m,"));
    let (_, out, _) = run(&[
        "sweep", "--vary", "mu", "--from", "0.1", "--to", "0.2", "--steps", "2",
    ]);
    assert!(out.starts_with("mu,"));
}

#[test]
fn sweep_rows_equal_single_simulate_runs() {
    let (code, out, _) = run(&[
        "sweep",
        "--vary",
        "stiffness",
        "--from",
        "5000",
        "--to",
        "40000",
        "--steps",
        "4",
        "--format",
        "json",
        "--cart-mass",
        "3g",
        "--spin",
        "-50",
    ]);
    assert_eq!(code, 0);
    let rows: Value = serde_json::from_str(&out).unwrap();
    let rows = rows.as_array().unwrap();
    assert_eq!(rows.len(), 4);
    for row in rows {
        let mut keys: Vec<&str> = row
            .as_object()
            .unwrap()
            .keys()
            .map(String::as_str)
            .collect();
        keys.sort_unstable();
        assert_eq!(
            keys,
            [
                "cart_stuck",
                "ex",
                "omega2",
                "patch_slip",
                "phases",
                "slides_throughout",
                "stiffness_N_m",
                "stretch",
                "theta2_deg",
                "vx2",
                "vy2"
            ]
        );
        let k = row["stiffness_N_m"].as_f64().unwrap().to_string();
        let (code, single, _) = run(&[
            "simulate",
            "--format",
            "json",
            "--cart-mass",
            "3g",
            "--spin",
            "-50",
            "--stiffness",
            &k,
        ]);
        assert_eq!(code, 0);
        let single: Value = serde_json::from_str(&single).unwrap();
        for key in [
            "omega2",
            "vx2",
            "vy2",
            "theta2_deg",
            "ex",
            "slides_throughout",
        ] {
            assert_eq!(row[key], single[key], "{key} at k = {k}");
        }
        assert_eq!(row["phases"], single["phase_summary"]);
    }
}

#[test]
fn sweep_rejects_bad_input_in_one_line() {
    let base = [
        "sweep", "--vary", "angle", "--from", "10", "--to", "80", "--steps", "5",
    ];
    let with = |i: usize, v: &'static str| {
        let mut args = base.to_vec();
        args[i] = v;
        args
    };
    usage_error(
        &with(2, "spinn"),
        &["--vary must be one of", "cart-mass", "got spinn"],
    );
    usage_error(
        &with(6, "95"),
        &["--to", "--angle must be in (0, 90] deg", "got 95"],
    );
    usage_error(&with(4, "10g"), &["--from", "--angle", "got 10g"]);
    usage_error(
        &with(8, "1"),
        &["--steps must be an integer in [2,", "got 1"],
    );
    usage_error(&with(8, "-3"), &["--steps", "got -3"]);
    usage_error(
        &[
            "sweep",
            "--vary",
            "stiffness",
            "--from",
            "0",
            "--to",
            "1e4",
            "--steps",
            "3",
            "--log",
        ],
        &["--log needs --from and --to above 0", "--from 0 N/m"],
    );
    usage_error(
        &[
            "sweep", "--vary", "spin", "--from", "-10", "--to", "10", "--steps", "3", "--log",
        ],
        &["--log", "--from -10 rad/s"],
    );
    usage_error(
        &[&base[..], &["--mu", "-1"]].concat(),
        &["--mu must be in [0, inf)", "got -1"],
    );
}

#[test]
fn sweep_stops_with_status_2_at_a_bounce_the_core_cannot_solve() {
    let (code, out, stderr) = run(&[
        "sweep",
        "--vary",
        "stiffness",
        "--from",
        "1",
        "--to",
        "1e15",
        "--steps",
        "3",
        "--cart-mass",
        "1mg",
    ]);
    assert_eq!(code, 2, "{stderr}");
    assert_eq!(out, "", "a failed sweep writes no partial CSV");
    assert_eq!(stderr.lines().count(), 1);
    assert!(
        stderr.contains("at --stiffness") && stderr.contains("too fast"),
        "{stderr}"
    );
}

#[test]
fn critical_angle_prints_eq7_and_the_full_model() {
    let (code, out, _) = run(&[
        "critical-angle",
        "--spin",
        "0",
        "--cart-mass",
        "10kg",
        "--stiffness",
        "4e4",
    ]);
    assert_eq!(code, 0);
    assert!(
        out.contains("Eq. (7), rigid surface") && out.contains("23.92 deg"),
        "{out}"
    );
    assert!(
        out.contains("full model") && out.contains("23.88 deg"),
        "{out}"
    );
    let (code, out, _) = run(&["critical-angle", "--format", "json"]);
    assert_eq!(code, 0);
    let doc: Value = serde_json::from_str(&out).unwrap();
    let eq7 = doc["eq7_deg"].as_f64().unwrap();
    let full = doc["full_model_deg"].as_f64().unwrap();
    assert!(
        (eq7 - 31.61).abs() < 0.01 && (full - 35.50).abs() < 0.01,
        "{doc}"
    );
    assert_eq!(doc["eq7"]["regime"], "at");
    assert_eq!(doc["params"]["stiffness"], 15000.0);
    let (code, out, _) = run(&["critical-angle", "--mu", "0", "--format", "json"]);
    assert_eq!(code, 0);
    let doc: Value = serde_json::from_str(&out).unwrap();
    assert!(doc["full_model_deg"].is_null());
    assert_eq!(doc["full_model"]["regime"], "always-slides");
    // The angle is what the command finds: giving one is refused, not ignored.
    for angle in ["45", "0"] {
        usage_error(
            &["critical-angle", "--angle", angle],
            &["--angle is what critical-angle finds"],
        );
    }
}

#[test]
fn critical_angle_reports_the_first_grip_beside_it() {
    let (code, out, _) = run(&["critical-angle", "--preset", "light-1g"]);
    assert_eq!(code, 0);
    assert!(
        out.contains("full model, this cart     32.00 deg")
            && out.contains("first grip, this cart     32.82 deg"),
        "{out}"
    );
    let (code, out, _) = run(&["critical-angle", "--chain", "8", "--format", "json"]);
    assert_eq!(code, 0);
    let doc: Value = serde_json::from_str(&out).unwrap();
    let full = doc["full_model_deg"].as_f64().unwrap();
    let grip = doc["first_grip_deg"].as_f64().unwrap();
    assert!(
        (full - 33.29).abs() < 0.01 && (grip - 33.87).abs() < 0.01,
        "{doc}"
    );
    assert_eq!(doc["full_model"]["regime"], "at");
    assert_eq!(doc["first_grip"]["deg"].as_f64(), Some(grip));
    let (code, out, _) = run(&["critical-angle", "--mu", "0", "--format", "json"]);
    assert_eq!(code, 0);
    let doc: Value = serde_json::from_str(&out).unwrap();
    assert!(doc["first_grip_deg"].is_null());
    assert_eq!(doc["first_grip"]["regime"], "always-slides");
}

#[test]
fn optimize_finds_the_stiffness_for_the_most_spin() {
    let (code, out, _) = run(&[
        "optimize",
        "--vary",
        "stiffness",
        "--from",
        "100",
        "--to",
        "1MN/m",
        "--cart-mass",
        "1g",
        "--format",
        "json",
    ]);
    assert_eq!(code, 0);
    let doc: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(doc["vary"], "stiffness");
    assert_eq!(doc["objective"], "omega2");
    assert_eq!(doc["log"], true);
    let k = doc["value"].as_f64().unwrap();
    let spin = doc["objective_value"].as_f64().unwrap();
    assert!((k - 9554.3).abs() < 1.0, "{k}");
    assert!((spin - 216.397).abs() < 1e-3, "{spin}");
    assert_eq!(doc["bounce"]["omega2"].as_f64().unwrap(), spin);
    assert_eq!(doc["bounce"]["params"]["stiffness"].as_f64().unwrap(), k);
    let (code, out, _) = run(&[
        "optimize",
        "--vary",
        "stiffness",
        "--from",
        "100",
        "--to",
        "1e6",
        "--cart-mass",
        "1g",
    ]);
    assert_eq!(code, 0);
    assert!(
        out.contains("spring stiffness k") && out.contains("9.55 kN/m"),
        "{out}"
    );
    assert!(
        out.contains("Outcome") && out.contains("216.4 rad/s"),
        "{out}"
    );
}

#[test]
fn optimize_minimizes_and_rejects_bad_objectives() {
    let (code, out, _) = run(&[
        "optimize",
        "--vary",
        "angle",
        "--from",
        "20",
        "--to",
        "80",
        "--objective",
        "theta2",
        "--minimize",
        "--format",
        "json",
    ]);
    assert_eq!(code, 0);
    let doc: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(doc["minimize"], true);
    assert_eq!(doc["objective"], "theta2");
    assert_eq!(doc["value"].as_f64().unwrap(), 20.0);
    let base = ["optimize", "--vary", "angle", "--from", "20", "--to", "80"];
    usage_error(
        &[&base[..], &["--objective", "spin"]].concat(),
        &[
            "--objective must be one of omega2, ex, vx2, theta2",
            "got spin",
        ],
    );
    usage_error(
        &[&base[..], &["--scan", "2"]].concat(),
        &["--scan must be an integer in [3,", "got 2"],
    );
    usage_error(
        &["optimize", "--vary", "nope", "--from", "1", "--to", "2"],
        &["--vary", "got nope"],
    );
}

#[test]
fn optimize_over_the_chain_tries_every_whole_number() {
    let (code, out, stderr) = run(&[
        "optimize", "--vary", "chain", "--from", "1", "--to", "16", "--format", "json",
    ]);
    assert_eq!(code, 0, "{stderr}");
    let doc: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(doc["vary"], "chain");
    assert_eq!(doc["exhaustive"], true);
    assert_eq!(doc["scan"], 16);
    assert_eq!(doc["log"], false);
    assert_eq!(doc["unit"], "");
    let n = doc["value"].as_f64().unwrap();
    let spin = doc["objective_value"].as_f64().unwrap();
    assert_eq!(doc["bounce"]["params"]["chain"].as_f64().unwrap(), n);
    // The best of solving each N on its own.
    let mut best = (0.0, f64::NEG_INFINITY);
    for each in 1..=16 {
        let (code, out, _) = run(&["simulate", "--chain", &each.to_string(), "--format", "json"]);
        assert_eq!(code, 0);
        let omega2 = serde_json::from_str::<Value>(&out).unwrap()["omega2"]
            .as_f64()
            .unwrap();
        if omega2 > best.1 {
            best = (f64::from(each), omega2);
        }
    }
    assert_eq!((n, spin), best);
    // The table says how it searched.
    let (code, out, _) = run(&[
        "optimize",
        "--vary",
        "chain",
        "--from",
        "16",
        "--to",
        "1",
        "--minimize",
    ]);
    assert_eq!(code, 0);
    assert!(
        out.starts_with(
            "The chain masses that minimises omega2 (every whole number from 16 to 1: 16 solved)\n"
        ),
        "{out}"
    );
    assert!(out.contains("chain masses N          1\n"), "{out}");
    assert!(out.contains("Outcome"), "{out}");
    // A continuous parameter is still scanned.
    let (code, out, _) = run(&[
        "optimize", "--vary", "angle", "--from", "20", "--to", "80", "--format", "json",
    ]);
    assert_eq!(code, 0);
    let doc: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(doc["exhaustive"], false);
    assert_eq!(doc["scan"], 400);
    // Ends that are not whole numbers are refused, naming the flag.
    usage_error(
        &[
            "optimize", "--vary", "chain", "--from", "1.5", "--to", "1.7",
        ],
        &["--from", "--chain must be in {1, 2, ..., 16}", "got 1.5"],
    );
    usage_error(
        &["optimize", "--vary", "chain", "--from", "1", "--to", "17"],
        &["--to", "--chain must be in {1, 2, ..., 16}", "got 17"],
    );
}

#[test]
fn sweep_over_the_chain_stays_on_whole_numbers() {
    let (code, out, _) = run(&[
        "sweep", "--vary", "chain", "--from", "1", "--to", "16", "--steps", "4",
    ]);
    assert_eq!(code, 0);
    let firsts: Vec<&str> = out
        .lines()
        .map(|line| line.split(',').next().unwrap())
        .collect();
    assert_eq!(firsts, ["chain", "1", "6", "11", "16"]);
    let (code, out, _) = run(&[
        "sweep", "--vary", "chain", "--from", "1", "--to", "16", "--steps", "5", "--log",
        "--format", "json",
    ]);
    assert_eq!(code, 0);
    let doc: Value = serde_json::from_str(&out).unwrap();
    let values: Vec<f64> = doc
        .as_array()
        .unwrap()
        .iter()
        .map(|row| row["chain"].as_f64().unwrap())
        .collect();
    assert_eq!(values, [1.0, 2.0, 4.0, 8.0, 16.0]);
    for format in ["csv", "json"] {
        usage_error(
            &[
                "sweep", "--vary", "chain", "--from", "1", "--to", "16", "--steps", "5",
                "--format", format,
            ],
            &[
                "--steps 5 puts --chain at 4.75, not a whole number",
                "use --steps 2, 4, 6 or 16",
            ],
        );
    }
}

#[test]
fn reproduce_checks_every_claim_and_fails_only_on_unexplained_differences() {
    let report = reproduce::reproduce(&Params::default()).unwrap();
    let (code, out, stderr) = run(&["reproduce", "--format", "json"]);
    assert_eq!(code, if report.complete() { 0 } else { 1 }, "{stderr}");
    let rows: Value = serde_json::from_str(&out).unwrap();
    let rows = rows.as_array().unwrap();
    let claims =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/assets/claims.md")).unwrap();
    let ids: Vec<&str> = claims
        .lines()
        .filter(|l| l.starts_with("| ") && !l.starts_with("| id "))
        .map(|l| l.split('|').nth(1).unwrap().trim())
        .collect();
    assert_eq!(ids.len(), 18);
    for id in ids {
        assert!(rows.iter().any(|r| r["id"] == id), "{id}");
    }
    for row in rows {
        for key in [
            "id", "quantity", "paper", "computed", "unit", "status", "note",
        ] {
            assert!(row.get(key).is_some(), "{key} in {row}");
        }
        let status = row["status"].as_str().unwrap();
        assert!(["reproduced", "close", "differs"].contains(&status));
        if status == "differs" {
            assert!(!row["note"].as_str().unwrap().is_empty(), "{row}");
        }
    }
    let (code, out, _) = run(&["reproduce"]);
    assert_eq!(code == 0, report.complete());
    assert!(
        out.contains("fig3c-spin") && out.contains("fig3c-return"),
        "{out}"
    );
    for row in report.unexplained() {
        assert!(
            out.contains(&format!("unexplained: {} ({})", row.id, row.quantity)),
            "{out}"
        );
    }
    assert_eq!(
        out.contains("every claim is reproduced, close"),
        report.complete()
    );
}

#[test]
fn reproduce_fails_when_differences_are_unexplained() {
    // With another friction coefficient the paper's numbers are out of reach and no reason is shown.
    let (code, out, stderr) = run(&["reproduce", "--mu", "0.3"]);
    assert_eq!(code, 1, "{stderr}");
    assert!(out.contains("unexplained: "), "{out}");
    assert!(stderr.contains("without a demonstrated reason"), "{stderr}");
    usage_error(
        &["reproduce", "--mass", "0"],
        &["--mass must be in (0, inf) kg", "got 0"],
    );
}

#[test]
fn figure_writes_svg_and_reports_bad_paths() {
    let dir = std::env::temp_dir().join(format!("snapback-cli-fig-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (which, title) in [("fig2", "ω2 (rad/s)"), ("fig3", "X (mm)")] {
        let path = dir.join(format!("{which}.svg"));
        let (code, out, stderr) = run(&["figure", which, "--out", path.to_str().unwrap()]);
        assert_eq!(code, 0);
        assert_eq!(out, "", "stdout is kept for --out -");
        assert!(stderr.contains(path.to_str().unwrap()), "{stderr}");
        let svg = std::fs::read_to_string(&path).unwrap();
        let doc = roxmltree::Document::parse(&svg).unwrap();
        assert!(
            doc.descendants()
                .any(|n| n.text().map(str::trim) == Some(title)),
            "{which}"
        );
    }
    let bad = dir.join("no-such-dir").join("f.svg");
    usage_error(
        &["figure", "fig2", "--out", bad.to_str().unwrap()],
        &["cannot write", "no-such-dir"],
    );
    usage_error(
        &["figure", "fig4", "--out", "x.svg"],
        &["FIGURE must be one of fig2, fig3", "got fig4"],
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
