//! `snapback fit`: recovery of known parameters from synthetic data, the coverage of its 95% intervals,
//! and its command line (formats, errors).

use crate::support::bin;

use assert_cmd::Command;
use rand::SeedableRng;
use rand::rngs::StdRng;
use rand_distr::{Distribution, Normal};
use snapback::analysis::fit::data::{Dataset, Measurement, Quantity, Row};
use snapback::analysis::fit::{self, Fit, Options, free};
use snapback::model::{ParamId, Params, solve};

/// The truth the synthetic data are made from: Fig. 3(c) with a 5 g cart on 12 kN/m and mu = 0.35.
fn truth() -> Params {
    Params {
        cart_mass: 0.005,
        stiffness: 12_000.0,
        mu: 0.35,
        ..Params::default()
    }
}

/// Standard deviation of the synthetic noise on omega2, rad/s.
const SIGMA: f64 = 3.0;

/// omega2 at angles 20..80 deg by 10 and spins 0 and -100 rad/s, from `truth()` plus normal noise of
/// SIGMA drawn from `seed`; each row carries SIGMA when `with_sigma`.
fn synthetic(seed: u64, with_sigma: bool) -> Dataset {
    let mut rng = StdRng::seed_from_u64(seed);
    let noise = Normal::new(0.0, SIGMA).unwrap();
    let mut rows = Vec::new();
    for spin in [0.0, -100.0] {
        for angle in (2..=8).map(|a| f64::from(a) * 10.0) {
            let conditions = vec![(ParamId::Angle, angle), (ParamId::Spin, spin)];
            let row = Row {
                line: rows.len() + 2,
                group: None,
                conditions,
                measured: Vec::new(),
            };
            let omega2 = solve(&row.params(&truth())).unwrap().outcome.omega2;
            rows.push(Row {
                measured: vec![Measurement {
                    quantity: Quantity::Omega2,
                    value: omega2 + noise.sample(&mut rng),
                    sigma: with_sigma.then_some(SIGMA),
                }],
                ..row
            });
        }
    }
    Dataset {
        origin: format!("synthetic-{seed}"),
        rows,
        conditions: vec![ParamId::Angle, ParamId::Spin],
        absolute_sigma: with_sigma,
        groups: Vec::new(),
    }
}

fn fit_three(data: &Dataset) -> Fit {
    let free = free::parse_list("cart-mass,stiffness,mu", &data.conditions).unwrap();
    // The fit starts from the defaults (10 g, 15 kN/m, 0.4), not from the truth.
    fit::fit(&Params::default(), &free, data, &Options::default()).unwrap()
}

/// How many of the fitted parameters' 95% intervals hold the truth.
fn covered(fit: &Fit) -> Vec<bool> {
    fit.free
        .iter()
        .map(|f| {
            let (lo, hi) = f.ci95.expect("every parameter is determined");
            (lo..=hi).contains(&truth().get(f.id))
        })
        .collect()
}

#[test]
fn a_fit_recovers_known_parameters_within_their_intervals() {
    for with_sigma in [true, false] {
        let fit = fit_three(&synthetic(1, with_sigma));
        assert!(fit.converged, "{fit:?}");
        assert_eq!(fit.dof, 11);
        assert!(covered(&fit).iter().all(|&c| c), "{:?}", fit.free);
        for f in &fit.free {
            let se = f.stderr.unwrap();
            // The data determine each to better than a quarter: a real recovery, not a wide interval.
            assert!(se < 0.25 * f.value, "{f:?}");
        }
        // Noise of SIGMA: the residuals scatter by about SIGMA.
        let spread = if with_sigma { fit.rms * SIGMA } else { fit.rms };
        assert!((0.5 * SIGMA..2.0 * SIGMA).contains(&spread), "{}", fit.rms);
    }
}

/// Over 200 seeded data sets the 95% intervals of each of the three parameters hold the truth 90 to 98%
/// of the time.
#[test]
#[ignore = "slow"]
fn intervals_cover_the_truth_about_95_percent_of_the_time() {
    const SETS: u64 = 200;
    let mut hits = [0usize; 3];
    for seed in 0..SETS {
        let fit = fit_three(&synthetic(1000 + seed, true));
        for (hit, c) in hits.iter_mut().zip(covered(&fit)) {
            *hit += usize::from(c);
        }
    }
    eprintln!("coverage of {SETS} data sets (cart_mass, stiffness, mu): {hits:?}");
    for hit in hits {
        let rate = hit as f64 / SETS as f64;
        assert!((0.90..=0.98).contains(&rate), "{hits:?}");
    }
}

fn snapback() -> Command {
    bin::snapback()
}

const DATA: &str = "# synthetic\nangle,spin,omega2,sigma_omega2\n20,0,135.6,3\n30,0,195.7,3\n40,0,223.5,3\n\
    50,0,214.4,3\n60,0,174.8,3\n70,0,122.5,3\n80,0,60.5,3\n20,-100rad/s,27.5,3\n30,-100,91.3,3\n\
    40,-100,151.9,3\n50,-100,172.6,3\n60,-100,178.7,3\n70,-100,135.2,3\n80,-955rpm,78.1,3\n";

#[test]
fn json_has_the_promised_keys() {
    let out = snapback()
        .args(["fit", "--data", "-", "--free", "cart-mass,stiffness,mu"])
        .args(["--format", "json"])
        .write_stdin(DATA)
        .assert()
        .success();
    let doc: serde_json::Value = serde_json::from_slice(&out.get_output().stdout).unwrap();
    for key in ["cart_mass", "stiffness", "mu"] {
        let p = &doc["free"][key];
        let (lo, hi) = (
            p["ci95"][0].as_f64().unwrap(),
            p["ci95"][1].as_f64().unwrap(),
        );
        let value = p["value"].as_f64().unwrap();
        assert!(
            lo < value && value < hi && p["stderr"].as_f64().unwrap() > 0.0,
            "{p}"
        );
    }
    assert_eq!(doc["dof"], 11);
    assert_eq!(doc["converged"], true);
    assert!(doc["chi2"].as_f64().unwrap() > 0.0 && doc["rms"].as_f64().unwrap() > 0.0);
    assert_eq!(doc["correlation"].as_array().unwrap().len(), 3);
    assert_eq!(doc["correlation"][1][1], 1.0);
    let rows = doc["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 14);
    let first = &rows[0];
    let (m, y, r) = (
        first["measured"]["omega2"].as_f64().unwrap(),
        first["model"]["omega2"].as_f64().unwrap(),
        first["residual"]["omega2"].as_f64().unwrap(),
    );
    assert_eq!(m, 135.6);
    assert!((y - m - r).abs() < 1e-12);
}

#[test]
fn bad_data_name_file_line_and_column_and_exit_2() {
    let dir = std::env::temp_dir().join(format!("snapback-fit-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("bad.csv");
    for (text, message) in [
        (
            "angle,omega9\n40,1\n",
            "bad.csv:1:2: unknown column 'omega9'",
        ),
        (
            "angle,omega2\n40,1\n50\n",
            "bad.csv:3:2: missing value for omega2",
        ),
        ("angle,omega2\n40,1\n4o,2\n", "bad.csv:3:1: angle: "),
        (
            "angle,omega2\n40,1.2.3\n",
            "bad.csv:2:2: '1.2.3' is not a number",
        ),
    ] {
        std::fs::write(&path, text).unwrap();
        let out = snapback()
            .args(["fit", "--free", "mu", "--data"])
            .arg(&path)
            .assert()
            .code(2);
        let stderr = String::from_utf8_lossy(&out.get_output().stderr).to_string();
        assert!(
            stderr.starts_with("error: ") && stderr.contains(message),
            "{stderr}"
        );
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn too_few_rows_are_refused() {
    snapback()
        .args(["fit", "--data", "-", "--free", "cart-mass,stiffness,mu"])
        .write_stdin("angle,omega2\n40,100\n50,120\n")
        .assert()
        .code(2)
        .stderr(predicates::str::contains(
            "2 measurements cannot determine 3 free parameters",
        ));
}

#[test]
fn a_parameter_the_data_cannot_determine_is_named_not_nan() {
    // A rigid ball ignores its damping: nothing in the data depends on it.
    let out = snapback()
        .args(["fit", "--data", "-", "--free", "mu,ball-damping"])
        .write_stdin(DATA)
        .assert()
        .success();
    let text = String::from_utf8_lossy(&out.get_output().stdout).to_string();
    assert!(
        text.contains("the data cannot determine ball-damping"),
        "{text}"
    );
    assert!(!text.to_lowercase().contains("nan"), "{text}");
    let out = snapback()
        .args([
            "fit",
            "--data",
            "-",
            "--free",
            "mu,ball-damping",
            "--format",
            "json",
        ])
        .write_stdin(DATA)
        .assert()
        .success();
    let doc: serde_json::Value = serde_json::from_slice(&out.get_output().stdout).unwrap();
    assert_eq!(doc["undetermined"], serde_json::json!(["ball_damping"]));
    assert!(doc["free"]["ball_damping"]["stderr"].is_null());
    assert!(doc["free"]["mu"]["stderr"].as_f64().unwrap() > 0.0);
    assert_eq!(doc["converged"], false);
}
